"""JUnit XML of scenario runs: one test suite per run, one test case per property.

The layout is the one CI systems read (Jenkins' junit-10 schema, also read by GitLab, GitHub
actions and Azure): `testsuites > testsuite(name, tests, failures, errors, skipped, time) >
testcase(name, classname, time) > failure | error | skipped`. A violated property is a failure whose
text is the counterexample, an unknown one is skipped with the reason, a property whose text raised an
ML exception is an error. Imports `cpn.report.verdicts` and the standard library only.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

from cpn.report.verdicts import property_warnings, render_steps


def _gate(p: dict) -> str:
    return p.get("gate", p["verdict"])


def render_junit(docs: list[dict], timings: bool = True) -> str:
    root = ET.Element("testsuites", name="cpn-verify check")
    totals = {"tests": 0, "failures": 0, "errors": 0, "skipped": 0}
    total_time = 0.0
    for doc in docs:
        props = doc["properties"]
        counts = {"tests": len(props),
                  "failures": sum(_gate(p) == "violated" for p in props),
                  "errors": sum(_gate(p) == "error" for p in props),
                  "skipped": sum(_gate(p) == "unknown" for p in props)}
        secs = doc["statespace"].get("seconds", 0.0) + doc["statespace"].get("check_seconds", 0.0)
        total_time += secs
        suite = ET.SubElement(root, "testsuite", name=doc["run"], **{k: str(v) for k, v in counts.items()},
                              time=f"{secs:.3f}" if timings else "0")
        ET.SubElement(ET.SubElement(suite, "properties"), "property", name="states",
                      value=str(doc["statespace"]["states"]))
        for p in props:
            case = ET.SubElement(suite, "testcase", name=p["name"], classname=doc["run"],
                                 file=doc["file"], line=str(p["line"]),
                                 time=f"{p.get('seconds', 0.0):.3f}" if timings else "0")
            if _gate(p) == "violated" and p["verdict"] == "holds":
                ET.SubElement(case, "failure", type=p["kind"],
                              message="expected to be violated, but holds: the bug this scenario stands for is "
                              "no longer caught")
            elif _gate(p) == "violated":
                el = ET.SubElement(case, "failure", message=p["message"], type=p["kind"])
                el.text = "\n".join(render_steps(p.get("trace", {}), indent="")) if "trace" in p else p["message"]
            elif p["verdict"] == "error":
                ET.SubElement(case, "error", message=p["message"], type="evaluation")
            elif p["verdict"] == "unknown":
                ET.SubElement(case, "skipped", message=f"unknown: {p['message']}")
            if p.get("warnings"):  # it holds, but vacuously or by structure alone: JUnit has no warning element
                ET.SubElement(case, "system-out").text = "\n".join(f"warning[{code}]: {w}"
                                                                   for code, w in property_warnings(p))
        for k in totals:
            totals[k] += counts[k]
    for k, v in totals.items():
        root.set(k, str(v))
    root.set("time", f"{total_time:.3f}" if timings else "0")
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n"
