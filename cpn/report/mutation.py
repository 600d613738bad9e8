"""Reports of a mutation run (`cpn.gate.mutation.MutationReport`): a JSON document first, then text,
Markdown and an HTML page rendered from it.

Imports `cpn.gate.mutation` and the standard library only.
"""

from __future__ import annotations

import html

from cpn.gate.mutants import OPERATORS
from cpn.gate.mutation import EQUIVALENT, KILLED, NOT_LOADABLE, OUTCOMES, SURVIVED, UNDECIDED

RUNTIME_ERROR = "(the model fails while it is explored)"


def mutation_document(report, timings: bool = True) -> dict:
    """The JSON document of a mutation run (keys documented in docs/mutation.md)."""
    models = [_model_document(m, timings) for m in report.models]
    doc = {
        "seed": report.seed,
        "max_mutants": report.max_mutants,
        "max_seconds": report.max_seconds,
        "score": _rounded(report.score),
        "counts": {o: report.count(o) for o in OUTCOMES},
        "not_run": report.not_run,
        "models": models,
    }
    if timings:
        doc["workers"] = report.workers
        doc["seconds"] = round(report.seconds, 3)
    return doc


def _rounded(score: float | None) -> float | None:
    return None if score is None else round(score, 1)


def _model_document(m, timings: bool) -> dict:
    doc = {
        "model": m.model,
        "scenarios": m.scenarios,
        "runs": m.runs,
        "problem": m.problem,
        "generated": m.generated,
        "selected": m.selected,
        "not_run": m.not_run,
        "score": _rounded(m.score),
        "counts": {o: m.count(o) for o in OUTCOMES},
        "original": [{k: v for k, v in r.items() if timings or k != "seconds"} for r in m.original],
        "properties": _property_table(m),
        "mutants": [_mutant_document(o, m.source, timings) for o in m.outcomes],
    }
    if timings:
        doc["seconds"] = round(m.seconds, 3)
        doc["seconds_per_mutant"] = round(sum(o.seconds for o in m.outcomes) / len(m.outcomes), 3) if m.outcomes else None
    return doc


def _mutant_document(o, source: str, timings: bool) -> dict:
    m = o.mutant
    doc = {
        "id": m.ident,
        "operator": m.operator,
        "description": m.description,
        "position": str(m.span),
        "line": m.span.line,
        "col": m.span.col,
        "outcome": o.outcome,
        "killers": [{"scenario": k.scenario, "run": k.run, "property": k.prop, "verdict": k.verdict,
                     "steps": k.steps} for k in o.killers],
        "reason": o.reason or None,
        "diff": m.diff(source),
    }
    if timings:
        doc["seconds"] = round(o.seconds, 3)
    return doc


def _property_table(m) -> list[dict]:
    """Per property (scenario, name): how many mutants it caught, and how many only it caught; every
    property of the scenarios is listed, those that caught nothing too."""
    rows: dict[tuple, dict] = {}
    for path in m.scenarios:
        for name in m.property_names.get(path, ()):
            rows.setdefault((path, name), {"scenario": path, "property": name, "caught": 0, "only": 0})
    for o in m.outcomes:
        if o.outcome != KILLED:
            continue
        keys = {(k.scenario, k.prop) for k in o.killers} or {("", RUNTIME_ERROR)}
        for key in sorted(keys):
            row = rows.setdefault(key, {"scenario": key[0], "property": key[1], "caught": 0, "only": 0})
            row["caught"] += 1
            if len(keys) == 1:
                row["only"] += 1
    return list(rows.values())


# ---------------------------------------------------------------------------------------------- text


def _score_text(score: float | None) -> str:
    return "no mutant decided" if score is None else f"{score:.1f}%"


def _counts_text(counts: dict, not_run: int) -> str:
    decided = counts[KILLED] + counts[SURVIVED]
    parts = [f"{counts[KILLED]} killed of {decided} decided", f"{counts[SURVIVED]} survived",
             f"{counts[EQUIVALENT]} equivalent", f"{counts[NOT_LOADABLE]} not loadable",
             f"{counts[UNDECIDED]} undecided"]
    if not_run:
        parts.append(f"{not_run} not run (time budget)")
    return ", ".join(parts)


def _killers_text(mut: dict) -> str:
    if not mut["killers"]:
        return mut["reason"] or RUNTIME_ERROR
    out = []
    for k in mut["killers"]:
        steps = "" if k["steps"] is None else f", {k['steps']} step{'s' if k['steps'] != 1 else ''}"
        how = "" if k["verdict"] == "violated" else f", {k['verdict']}"
        out.append(f"'{k['property']}' ({k['run']}{how}{steps})")
    if mut["reason"]:  # a run-time error of the mutant in another run (--all-runs)
        out.append(mut["reason"])
    return "; ".join(out)


def render_text(doc: dict, verbose: bool = False) -> str:
    """The text report: per model, the score, what each property caught, and every surviving mutant as a
    diff with its position."""
    out = []
    for m in doc["models"]:
        runs = f"{m['runs']} run{'s' if m['runs'] != 1 else ''}"
        scen = f"{len(m['scenarios'])} scenario{'s' if len(m['scenarios']) != 1 else ''}"
        out.append(f"model {m['model']} ({scen}, {runs})")
        if m["problem"]:
            out.append(f"  not mutated: {m['problem']}")
            out.append("")
            continue
        sample = (f"{m['selected']} of {m['generated']} mutants (seed {doc['seed']})"
                  if m["selected"] < m["generated"] else f"{m['generated']} mutants")
        out.append(f"  {sample}: score {_score_text(m['score'])}")
        out.append(f"  {_counts_text(m['counts'], m['not_run'])}")
        if "seconds" in m and m["mutants"]:
            out.append(f"  {m['seconds']:.1f} s, {m['seconds_per_mutant']:.2f} s per mutant")
        if m["properties"]:
            out.append("  mutants caught by each property (only: caught by no other):")
            width = max(len(str(p["caught"])) for p in m["properties"])
            for p in m["properties"]:
                where = f" [{p['scenario']}]" if len(m["scenarios"]) > 1 and p["scenario"] else ""
                name = p["property"] if p["property"] == RUNTIME_ERROR else f"'{p['property']}'"
                out.append(f"    {p['caught']:>{width}} (only {p['only']})  {name}{where}")
        for outcome, title in ((SURVIVED, "surviving mutants (no property catches them)"),
                               (UNDECIDED, "undecided mutants"), (NOT_LOADABLE, "mutants that do not load"),
                               (EQUIVALENT, "equivalent mutants (the same labelled state space)"),
                               (KILLED, "killed mutants")):
            muts = [x for x in m["mutants"] if x["outcome"] == outcome]
            if not muts or (outcome == KILLED and not verbose):
                continue
            out.append("")
            out.append(f"  {title}:")
            for x in muts:
                out.append(f"  {x['position']}: {x['id']} {x['operator']}: {x['description']}")
                if outcome == SURVIVED:
                    out.extend("    " + line for line in x["diff"].rstrip("\n").splitlines())
                elif outcome == KILLED:
                    out.append(f"    caught by {_killers_text(x)}")
                elif x["reason"]:
                    out.append(f"    {x['reason']}")
        out.append("")
    total = doc["counts"]
    if len(doc["models"]) > 1:
        out.append(f"all models: score {_score_text(doc['score'])} ({_counts_text(total, doc['not_run'])})")
    return "\n".join(out).rstrip("\n") + "\n"


# ---------------------------------------------------------------------------------------------- Markdown


def _md(text: str) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def render_markdown(doc: dict) -> str:
    out = ["# Mutation testing", ""]
    out.append(f"Score {_score_text(doc['score'])}: {_counts_text(doc['counts'], doc['not_run'])} "
               f"(seed {doc['seed']}).")
    out.append("")
    for m in doc["models"]:
        out += [f"## {_md(m['model'])}", ""]
        out.append("Scenarios: " + ", ".join(f"`{s}`" for s in m["scenarios"]) + ".")
        out.append("")
        if m["problem"]:
            out += [f"Not mutated: {_md(m['problem'])}.", ""]
            continue
        out.append(f"{m['selected']} of {m['generated']} mutants; score {_score_text(m['score'])}: "
                   f"{_counts_text(m['counts'], m['not_run'])}."
                   + (f" {m['seconds']:.1f} s, {m['seconds_per_mutant']:.2f} s per mutant." if "seconds" in m
                      and m["mutants"] else ""))
        out.append("")
        if m["properties"]:
            out += ["| property | mutants caught | caught by no other |", "|---|---:|---:|"]
            for p in m["properties"]:
                out.append(f"| {_md(p['property'])} | {p['caught']} | {p['only']} |")
            out.append("")
        survivors = [x for x in m["mutants"] if x["outcome"] == SURVIVED]
        if survivors:
            out += ["### Surviving mutants", ""]
            for x in survivors:
                out += [f"**{x['id']}** `{x['position']}` {x['operator']}: {_md(x['description'])}", "",
                        "```diff", x["diff"].rstrip("\n"), "```", ""]
        others = [x for x in m["mutants"] if x["outcome"] != SURVIVED]
        if others:
            out += ["### Other mutants", "", "| mutant | position | operator | outcome | caught by / reason |",
                    "|---|---|---|---|---|"]
            for x in others:
                why = _killers_text(x) if x["outcome"] == KILLED else (x["reason"] or "")
                out.append(f"| {x['id']} | `{x['position']}` | {x['operator']} | {x['outcome']} | {_md(why)} |")
            out.append("")
    out += ["### Operators", ""]
    out += [f"- `{k}`: {v}" for k, v in OPERATORS.items()]
    return "\n".join(out) + "\n"


# ---------------------------------------------------------------------------------------------- HTML

_STYLE = """body{font-family:system-ui,sans-serif;margin:2em;max-width:72em;color:#222}
table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ccc;padding:.2em .6em;text-align:left}
td.n{text-align:right}pre{background:#f6f6f6;padding:.5em;overflow-x:auto}
.add{color:#060}.del{color:#a00}.survived{background:#fee}.killed{background:#efe}
"""


def _diff_html(diff: str) -> str:
    lines = []
    for line in diff.rstrip("\n").splitlines():
        cls = "add" if line.startswith("+") and not line.startswith("+++") else (
            "del" if line.startswith("-") and not line.startswith("---") else "")
        text = html.escape(line)
        lines.append(f'<span class="{cls}">{text}</span>' if cls else text)
    return "<pre>" + "\n".join(lines) + "</pre>"


def render_html(doc: dict) -> str:
    e = html.escape
    out = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8"><title>Mutation testing</title>',
           f"<style>{_STYLE}</style></head><body>", "<h1>Mutation testing</h1>",
           f"<p>Score {e(_score_text(doc['score']))}: {e(_counts_text(doc['counts'], doc['not_run']))} "
           f"(seed {doc['seed']}).</p>"]
    for m in doc["models"]:
        out.append(f"<h2>{e(m['model'])}</h2>")
        out.append("<p>Scenarios: " + ", ".join(f"<code>{e(s)}</code>" for s in m["scenarios"]) + "</p>")
        if m["problem"]:
            out.append(f"<p>Not mutated: {e(m['problem'])}</p>")
            continue
        out.append(f"<p>{m['selected']} of {m['generated']} mutants; score {e(_score_text(m['score']))}: "
                   f"{e(_counts_text(m['counts'], m['not_run']))}.</p>")
        if m["properties"]:
            out.append("<table><tr><th>property</th><th>mutants caught</th><th>caught by no other</th></tr>")
            for p in m["properties"]:
                out.append(f"<tr><td>{e(p['property'])}</td><td class=n>{p['caught']}</td>"
                           f"<td class=n>{p['only']}</td></tr>")
            out.append("</table>")
        survivors = [x for x in m["mutants"] if x["outcome"] == SURVIVED]
        if survivors:
            out.append("<h3>Surviving mutants</h3>")
            for x in survivors:
                out.append(f"<p><b>{e(x['id'])}</b> <code>{e(x['position'])}</code> {e(x['operator'])}: "
                           f"{e(x['description'])}</p>")
                out.append(_diff_html(x["diff"]))
        others = [x for x in m["mutants"] if x["outcome"] != SURVIVED]
        if others:
            out.append("<h3>Other mutants</h3><table><tr><th>mutant</th><th>position</th><th>operator</th>"
                       "<th>outcome</th><th>caught by / reason</th></tr>")
            for x in others:
                why = _killers_text(x) if x["outcome"] == KILLED else (x["reason"] or "")
                cls = ' class="killed"' if x["outcome"] == KILLED else ""
                out.append(f"<tr{cls}><td>{e(x['id'])}</td><td><code>{e(x['position'])}</code></td>"
                           f"<td>{e(x['operator'])}</td><td>{e(x['outcome'])}</td><td>{e(why)}</td></tr>")
            out.append("</table>")
    out.append("</body></html>")
    return "\n".join(out) + "\n"
