"""SARIF 2.1.0 of scenario runs: each violated (or undecided) property is a result located at the
property's line in its scenario file, so code hosts annotate the spec file in a pull request.

Imports `cpn.report.verdicts` and the standard library only.
"""

from __future__ import annotations

import os

from cpn.report.verdicts import property_warnings, render_steps

SARIF_SCHEMA = "https://json.schemastore.org/sarif-2.1.0.json"
LEVELS = {"violated": "error", "error": "error", "unknown": "warning"}
# a property that holds vacuously, or by the net's structure alone: a warning, one rule per diagnostic code
WARNING_RULES = {
    "W0702": ("holds vacuously", "a property that holds vacuously: an implication whose premise is never true, a "
              "dead-marking predicate with no dead marking, a CTL sub-formula that constrains nothing "
              "(docs/mutation.md, 'Vacuity')"),
    "W0703": ("follows from the net's structure", "a property that follows from the net's structure: a place "
              "invariant or bound of the incidence matrix that no guard, token value or order of occurrences "
              "can break (docs/mutation.md, 'Vacuity')"),
}


def render_sarif(docs: list[dict], version: str, base: str | None = None) -> dict:
    """The SARIF log (a dict to dump as JSON). URIs are relative to `base` (default: the working folder)."""
    base = base or os.getcwd()
    kinds = sorted({p["kind"] for d in docs for p in d["properties"]})
    rules = [{"id": f"cpn/{k}", "name": k.replace("_", " "),
              "shortDescription": {"text": f"a '{k}' property of a scenario (docs/specs.md)"}} for k in kinds]
    warned = sorted({code for d in docs for p in d["properties"] for code, _ in property_warnings(p)})
    first_warning = len(rules)
    for code in warned:
        name, text = WARNING_RULES.get(code, ("warning", "a warning about a property"))
        rules.append({"id": f"cpn/{code}", "name": name, "shortDescription": {"text": text}})
    results = []
    for d in docs:
        uri = os.path.relpath(d["file"], base).replace(os.sep, "/")
        for p in d["properties"]:
            gate = p.get("gate", p["verdict"])
            level = LEVELS.get(gate)
            for code, w in property_warnings(p) if level is None else ():
                results.append({
                    "ruleId": f"cpn/{code}", "ruleIndex": first_warning + warned.index(code), "level": "warning",
                    "message": {"text": f"warning[{code}]: {d['run']}: property '{p['name']}' {w}"},
                    "locations": [{"physicalLocation": {
                        "artifactLocation": {"uri": uri},
                        "region": {"startLine": max(1, p["line"]), "startColumn": max(1, p["column"])}}}],
                    "properties": {"scenario": d["run"], "verdict": p["verdict"], "code": code},
                })
            if level is None:
                continue
            text = f"{d['run']}: property '{p['name']}' is {p['verdict']}: {p['message']}"
            if p.get("expect", "holds") != "holds":
                text = (f"{d['run']}: property '{p['name']}' is {p['verdict']}, expected {p['expect']}"
                        + (f": {p['message']}" if p["message"] else ""))
            if "trace" in p and p["verdict"] == "violated":
                text += "\n" + "\n".join(render_steps(p["trace"], indent="  "))
            results.append({
                "ruleId": f"cpn/{p['kind']}",
                "ruleIndex": kinds.index(p["kind"]),
                "level": level,
                "message": {"text": text},
                "locations": [{"physicalLocation": {
                    "artifactLocation": {"uri": uri},
                    "region": {"startLine": max(1, p["line"]), "startColumn": max(1, p["column"])}}}],
                "properties": {"scenario": d["run"], "verdict": p["verdict"]},
            })
    return {
        "$schema": SARIF_SCHEMA,
        "version": "2.1.0",
        "runs": [{
            "tool": {"driver": {"name": "cpn-verify", "version": version, "rules": rules}},
            "results": results,
        }],
    }
