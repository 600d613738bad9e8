"""SARIF 2.1.0 of scenario runs: each violated (or undecided) property is a result located at the
property's line in its scenario file, so code hosts annotate the spec file in a pull request.

Imports `cpn.report.verdicts` and the standard library only.
"""

from __future__ import annotations

import os

from cpn.report.verdicts import render_steps

SARIF_SCHEMA = "https://json.schemastore.org/sarif-2.1.0.json"
LEVELS = {"violated": "error", "error": "error", "unknown": "warning"}
VACUITY_RULE = "cpn/vacuity"  # a property that holds vacuously or by structure alone: a warning


def render_sarif(docs: list[dict], version: str, base: str | None = None) -> dict:
    """The SARIF log (a dict to dump as JSON). URIs are relative to `base` (default: the working folder)."""
    base = base or os.getcwd()
    kinds = sorted({p["kind"] for d in docs for p in d["properties"]})
    rules = [{"id": f"cpn/{k}", "name": k.replace("_", " "),
              "shortDescription": {"text": f"a '{k}' property of a scenario (docs/specs.md)"}} for k in kinds]
    if any(p.get("warnings") for d in docs for p in d["properties"]):
        rules.append({"id": VACUITY_RULE, "name": "vacuity", "shortDescription": {
            "text": "a property that holds vacuously, or by the net's structure alone (docs/mutation.md, 'Vacuity')"}})
    results = []
    for d in docs:
        uri = os.path.relpath(d["file"], base).replace(os.sep, "/")
        for p in d["properties"]:
            gate = p.get("gate", p["verdict"])
            level = LEVELS.get(gate)
            for w in p.get("warnings", ()) if level is None else ():
                results.append({
                    "ruleId": VACUITY_RULE, "ruleIndex": len(rules) - 1, "level": "warning",
                    "message": {"text": f"{d['run']}: property '{p['name']}' {w}"},
                    "locations": [{"physicalLocation": {
                        "artifactLocation": {"uri": uri},
                        "region": {"startLine": max(1, p["line"]), "startColumn": max(1, p["column"])}}}],
                    "properties": {"scenario": d["run"], "verdict": p["verdict"]},
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
