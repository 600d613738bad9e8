"""Comparing check reports with those of an earlier run (`--baseline DIR`): what changed.

The headline is a property that held and now does not. Imports the standard library only.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass


@dataclass(frozen=True)
class Change:
    run: str
    what: str  # 'broke' 'fixed' 'verdict' 'new' 'removed' 'states' 'arcs' 'dead_markings' 'bound'
    text: str

    @property
    def is_regression(self) -> bool:
        return self.what == "broke"


def load_reports(folder: str) -> dict[str, dict]:
    """The JSON check reports of a folder, by run name (other JSON files are ignored). A run name that
    two reports of the folder share pairs with neither: its entry is an `Ambiguous` list of their files."""
    out: dict = {}
    if not os.path.isdir(folder):
        return out
    for name in sorted(os.listdir(folder)):
        if not name.endswith(".json"):
            continue
        try:
            with open(os.path.join(folder, name), encoding="utf-8") as fh:
                doc = json.load(fh)
        except (OSError, ValueError):
            continue
        if isinstance(doc, dict) and str(doc.get("schema", "")).startswith("cpn-verify/check-report/"):
            run = doc["run"]
            if run in out:
                before = out[run]
                out[run] = Ambiguous([*before, name] if isinstance(before, Ambiguous) else [before["_file"], name])
            else:
                out[run] = {**doc, "_file": name}
    return out


class Ambiguous(list):
    """The report files of a baseline folder that hold the same run name: none of them is compared."""


def compare(old: dict[str, dict], new: list[dict]) -> list[Change]:
    """Changes from `old` (by run name) to the runs `new`, regressions first, then in run order."""
    changes: list[Change] = []
    for doc in new:
        run = doc["run"]
        before = old.get(run)
        if before is None:
            changes.append(Change(run, "new", f"{run}: new scenario run (no baseline report)"))
            continue
        if isinstance(before, Ambiguous):
            changes.append(Change(run, "new", f"{run}: not compared: the baseline holds {len(before)} reports of "
                                  f"a run of this name ({', '.join(before)})"))
            continue
        oldp = {p["name"]: p for p in before.get("properties", [])}
        newp = {p["name"]: p for p in doc["properties"]}
        for name, p in newp.items():
            q = oldp.get(name)
            if q is None:
                changes.append(Change(run, "new", f"{run}: new property '{name}' is {p['verdict']}"))
            elif q["verdict"] != p["verdict"]:
                # judged as the gate judges (a mutant's expected violation counts as holding)
                was, now = q.get("gate", q["verdict"]), p.get("gate", p["verdict"])
                kind = ("broke" if was == "holds" and now != "holds" else
                        "fixed" if now == "holds" and was != "holds" else "verdict")
                changes.append(Change(run, kind, f"{run}: '{name}' {q['verdict']} -> {p['verdict']}"
                                      + (f": {p['message']}" if p["verdict"] != "holds" else "")))
        for name in oldp.keys() - newp.keys():
            changes.append(Change(run, "removed", f"{run}: property '{name}' was removed"))
        so, sn = before.get("statespace", {}), doc["statespace"]
        for key in ("states", "arcs"):
            if so.get(key) != sn.get(key):
                changes.append(Change(run, key, f"{run}: {key} {so.get(key)} -> {sn.get(key)}"))
        do, dn = before.get("dead_markings", {}).get("count"), doc["dead_markings"]["count"]
        if do != dn:
            changes.append(Change(run, "dead_markings", f"{run}: dead markings {do} -> {dn}"))
        bo, bn = before.get("bounds", {}), doc.get("bounds", {})
        for place in sorted(set(bo) | set(bn)):
            if bo.get(place) != bn.get(place):
                a, b = bo.get(place), bn.get(place)
                fa = f"[{a['lower']}, {a['upper']}]" if a else "none"
                fb = f"[{b['lower']}, {b['upper']}]" if b else "none"
                changes.append(Change(run, "bound", f"{run}: bounds of {place} {fa} -> {fb}"))
    order = {"broke": 0}
    return sorted(changes, key=lambda c: order.get(c.what, 1))
