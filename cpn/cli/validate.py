"""`cpn-verify validate DIR`: explore every instance of an external validation corpus and compare.

DIR holds `expected.json` (shared/validation/README.md): per instance a model file, its format and the
published figures. Each model goes through `cpn.load`, is explored completely, and every published
figure (states, arcs, token maxima, dead markings, the Model Checking Contest global properties) is
compared, one row per instance: match, mismatch, error (the model could not be loaded or explored),
partial (cut short by --max-states: nothing compared) or skipped.

Where an instance has `formulas/oracle.json` (the Model Checking Contest's published verdicts of its
property files), every formula of the seven examinations is also answered (`cpn-verify mcc`) and compared:
agree, disagree, or unknown (a limit stopped it), per instance, per examination and in total.
"""

from __future__ import annotations

import argparse
import fnmatch
import importlib.util
import json
import os
import sys
import time
from dataclasses import dataclass, field

from cpn.checks.mcc import PROPERTIES
from cpn.cli._common import (
    ExitStatus,
    UsageError,
    add_output_option,
    add_quiet_option,
    prepare_outputs,
    write_output,
)

FIGURES = ("states", "arcs", "arcs_distinct_marking_pairs", "max_tokens_per_marking", "max_tokens_in_place",
           "dead_markings", "deadlock_reachable")
MAX_STATES_DEFAULT = 3_000_000
FORMULA_SECONDS_DEFAULT = 300.0
FORMULA_STATES_DEFAULT = 500_000

# validate's own exit statuses: it verifies no property, so the commands' common list (where 1 is "a
# property is violated") does not describe it
EPILOG = """exit statuses:
  0   every instance compared matches all its published figures and formula verdicts (skipped
      instances aside)
  1   the corpus does not validate: a published figure or formula verdict differs ('mismatch',
      'disagree'), or an instance's model could not be loaded or explored ('error')
  2   nothing differs, but some state space was cut short by --max-states ('partial': not compared),
      or a formula was not answered within its limits ('unknown')
  64  bad usage: DIR has no readable expected.json, or no instance matches --only
  70  internal error (a bug in cpn-verify: please report it)
  73  the --json file cannot be created (checked before any work starts)
  130 interrupted

outputs: --json takes '-' for standard output; the table then goes to standard error.
"""


def add_parser(subparsers) -> argparse.ArgumentParser:
    p = subparsers.add_parser(
        "validate", help="explore an external validation corpus and compare with its published figures",
        description=__doc__.split("\n\n")[1], epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("directory", metavar="DIR", help="folder with expected.json and the model files")
    p.add_argument("--max-states", type=int, default=MAX_STATES_DEFAULT, metavar="N",
                   help=f"stop exploring an instance after N states (default {MAX_STATES_DEFAULT:,})")
    p.add_argument("--only", action="append", metavar="NAME",
                   help="validate only instances whose name matches NAME (a glob; may be repeated)")
    p.add_argument("--skip-larger-than", type=int, metavar="N",
                   help="skip instances whose published state count exceeds N")
    p.add_argument("--no-formulas", action="store_true",
                   help="compare the published figures only, not the contest's formula verdicts")
    p.add_argument("--formula-seconds", type=float, default=FORMULA_SECONDS_DEFAULT, metavar="S",
                   help="the time to answer all the formulas of one instance (default "
                   f"{FORMULA_SECONDS_DEFAULT:g}); those left are 'unknown'")
    p.add_argument("--formula-max-states", type=int, default=FORMULA_STATES_DEFAULT, metavar="N",
                   help=f"give up a formula whose search through the engine passes N markings (default "
                   f"{FORMULA_STATES_DEFAULT:,}; the whole state space, for CTL and UpperBounds, is bounded by --max-states)")
    add_output_option(p, "--json", "the results as JSON")
    add_quiet_option(p)
    return p


# ---------------------------------------------------------------------- exploration

@dataclass
class Figures:
    """What one complete (or cut short) exploration found, in expected.json's vocabulary."""

    states: int = 0
    arcs: int = 0
    max_tokens_per_marking: int = 0
    max_tokens_in_place: int = 0  # all tokens of one place
    max_of_one_colour_in_place: int = 0  # the largest multiplicity of one colour in one place
    dead_markings: int = 0
    arcs_distinct_marking_pairs: int = 0  # distinct (M, M') pairs joined by at least one arc
    scc_nodes: int = 0
    scc_arcs: int = 0  # state-space arcs between two SCCs (CPN Tools' count)
    complete: bool = True
    stop_message: str = ""
    properties: dict[str, bool] = field(default_factory=dict)

    @property
    def deadlock_reachable(self) -> bool:
        return self.dead_markings > 0


def explore_figures(engine, max_states: int = MAX_STATES_DEFAULT) -> Figures:
    """Explore with the state-space explorer and compute the figures expected.json publishes (the global
    properties are the Model Checking Contest's, `cpn.checks.mcc`)."""
    from cpn.checks.bounds import boundedness
    from cpn.checks.liveness import dead_markings, scc_summary
    from cpn.checks.mcc import distinct_marking_pairs, global_properties
    from cpn.checks.verdict import Status
    from cpn.statespace import ExploreOptions, Explorer
    from cpn.statespace.options import default_max_memory_mb

    x = Explorer(engine, ExploreOptions(max_states=max_states, max_memory_mb=default_max_memory_mb())).run()
    b = boundedness(x)
    fig = Figures(states=x.n_states, arcs=x.n_arcs, max_tokens_per_marking=b.max_tokens_per_marking,
                  max_tokens_in_place=b.max_tokens_in_place,
                  max_of_one_colour_in_place=b.max_of_one_colour_in_place,
                  dead_markings=dead_markings(x).count, complete=x.complete,
                  stop_message=x.stop_reason.describe(x.options))
    if not x.complete:
        return fig
    fig.arcs_distinct_marking_pairs = distinct_marking_pairs(x)
    scc = scc_summary(x)
    fig.scc_nodes, fig.scc_arcs = scc.nodes, scc.arcs
    fig.properties = {name: v.status is Status.HOLDS for name, v in global_properties(x, b, scc).items()}
    return fig


# ---------------------------------------------------------------------- comparison

@dataclass
class Result:
    name: str
    format: str
    status: str  # "match", "mismatch", "partial", "skipped", "error"
    seconds: float = 0.0
    expected: dict = field(default_factory=dict)
    found: dict = field(default_factory=dict)
    differences: list[str] = field(default_factory=list)
    reason: str = ""
    formulas: list[dict] = field(default_factory=list)  # one per formula: id, examination, expected, found, ...
    formula_seconds: float = 0.0
    exam_seconds: dict = field(default_factory=dict)  # examination -> seconds to answer its formulas

    def ratios(self) -> dict[str, float]:
        """Per examination: the time to answer its formulas over the time to explore the state space once
        (`seconds`, which includes loading the model)."""
        return {e: t / self.seconds for e, t in self.exam_seconds.items()} if self.seconds else {}

    def formula_counts(self) -> dict[str, int]:
        return {k: sum(f["result"] == k for f in self.formulas) for k in ("agree", "disagree", "unknown")}


def found_figures(fig: Figures, fmt: str) -> dict:
    """The figures in expected.json's keys; for coloured PNML, max_tokens_in_place is the contest's."""
    in_place = fig.max_of_one_colour_in_place if fmt == "pnml-col" else fig.max_tokens_in_place
    out = {"states": fig.states, "arcs": fig.arcs, "max_tokens_per_marking": fig.max_tokens_per_marking,
           "max_tokens_in_place": in_place, "dead_markings": fig.dead_markings,
           "deadlock_reachable": fig.deadlock_reachable}
    if fig.complete:
        out["arcs_distinct_marking_pairs"] = fig.arcs_distinct_marking_pairs
        out["scc_graph"] = {"nodes": fig.scc_nodes, "arcs": fig.scc_arcs}
        out["mcc_global_properties"] = dict(fig.properties)
    return out


def compare(expected: dict, found: dict) -> list[str]:
    """One line per published figure that differs from what was found."""
    diffs = []
    for key in FIGURES:
        if expected.get(key) is not None and key in found and expected[key] != found[key]:
            diffs.append(f"{key}: expected {expected[key]}, found {found[key]}")
    scc, got_scc = expected.get("scc_graph") or {}, found.get("scc_graph") or {}
    for key in ("nodes", "arcs"):
        if key in scc and key in got_scc and scc[key] != got_scc[key]:
            diffs.append(f"scc_graph {key}: expected {scc[key]}, found {got_scc[key]}")
    props = expected.get("mcc_global_properties") or {}
    got = found.get("mcc_global_properties") or {}
    for key in PROPERTIES:
        if key in props and key in got and props[key] != got[key]:
            diffs.append(f"{key}: expected {props[key]}, found {got[key]}")
    return diffs


def _importer_available(path: str) -> bool:
    """A `.cpnet` file, or a format that `cpn.io` registers."""
    from cpn.io import importer_for

    importer = importer_for(path)
    return importer is None or importlib.util.find_spec(importer.module) is not None


def validate_instance(directory: str, inst: dict, max_states: int) -> Result:
    import cpn

    res = Result(inst["name"], inst.get("format", "?"), "error", expected=inst)
    path = os.path.join(directory, inst["file"])
    t0 = time.perf_counter()
    try:
        model = cpn.load(path)
        engine = model.engine()
        fig = explore_figures(engine, max_states)
    except Exception as exc:  # noqa: BLE001 - one broken instance must not stop the table
        render = getattr(exc, "render", None)
        res.reason = render() if callable(render) else f"{type(exc).__name__}: {exc}"
        res.seconds = time.perf_counter() - t0
        return res
    res.seconds = time.perf_counter() - t0
    res.found = found_figures(fig, res.format)
    if not fig.complete:
        # figures of part of a state space say nothing about the whole (a maximum may come later)
        res.status = "partial"
        res.reason = f"stopped because {fig.stop_message}; nothing compared"
        return res
    res.differences = compare(inst, res.found)
    res.status = "mismatch" if res.differences else "match"
    return res


def validate_formulas(directory: str, res: Result, inst: dict, seconds: float, max_states: int,
                      graph_max_states: int | None = None) -> None:
    """Answer every formula of the instance's property files and compare with `formulas/oracle.json`."""
    from cpn.cli.mcc import ContestModel, answer_file
    from cpn.properties.contest import EXAMINATIONS

    folder = os.path.join(directory, os.path.dirname(inst["file"]), "formulas")
    try:
        with open(os.path.join(folder, "oracle.json"), encoding="utf-8") as fh:
            oracle = json.load(fh)["verdicts"]
    except (OSError, ValueError, KeyError):
        return
    t0 = time.perf_counter()
    model = ContestModel.load(os.path.join(directory, inst["file"]), max_states=max_states,
                              graph_max_states=graph_max_states, deadline=time.monotonic() + seconds)
    for exam in EXAMINATIONS:
        if exam not in oracle:
            continue
        model.forget()  # each examination from scratch: its time against the exploration's is the ratio
        t1 = time.perf_counter()
        answers = answer_file(model, os.path.join(folder, f"{exam}.xml"))
        res.exam_seconds[exam] = time.perf_counter() - t1
        for a in answers:
            expected = oracle[exam].get(a.id)
            found = a.value if not isinstance(a.value, bool) else ("TRUE" if a.value else "FALSE")
            result = "unknown" if a.value is None else "agree" if found == expected else "disagree"
            res.formulas.append({"id": a.id, "examination": exam, "expected": expected, "found": found,
                                 "result": result, "states": a.states, "seconds": round(a.seconds, 4),
                                 **({"reason": a.reason} if a.reason else {})})
    res.formula_seconds = time.perf_counter() - t0


def select(instances: list[dict], only: list[str] | None, skip_larger_than: int | None) -> list[tuple[dict, str]]:
    """(instance, reason to skip or '') for every instance chosen by --only."""
    out = []
    for inst in instances:
        if only and not any(fnmatch.fnmatchcase(inst["name"], pat) or inst["name"] == pat for pat in only):
            continue
        reason = ""
        if skip_larger_than is not None and inst.get("states", 0) > skip_larger_than:
            reason = f"{inst['states']:,} states > --skip-larger-than {skip_larger_than:,}"
        elif not _importer_available(inst.get("file", "")):
            reason = f"no importer for format '{inst.get('format')}' yet"
        out.append((inst, reason))
    return out


# ---------------------------------------------------------------------- output

_COLS = [("instance", 36, "<"), ("states", 10, ">"), ("arcs", 10, ">"), ("tok/mark", 8, ">"),
         ("tok/place", 9, ">"), ("dead", 6, ">"), ("props", 5, ">"), ("result", 8, "<"), ("seconds", 8, ">")]


def _row(values: list[str]) -> str:
    return "  ".join(f"{v:{align}{width}}" for v, (_n, width, align) in zip(values, _COLS)).rstrip()


def format_row(r: Result) -> str:
    f = r.found
    if not f:
        return _row([r.name, "-", "-", "-", "-", "-", "-", r.status, f"{r.seconds:.2f}" if r.seconds else "-"])
    props = r.expected.get("mcc_global_properties") or {}
    got = f.get("mcc_global_properties") or {}
    checked = [k for k in PROPERTIES if k in props and k in got]
    ok = sum(props[k] == got[k] for k in checked)
    dead = f"{f['dead_markings']}"
    return _row([r.name, f"{f['states']:,}", f"{f['arcs']:,}", str(f["max_tokens_per_marking"]),
                 str(f["max_tokens_in_place"]), dead, f"{ok}/{len(checked)}" if checked else "-",
                 r.status, f"{r.seconds:.2f}"])


def run(args) -> int:
    directory = args.directory
    outputs = {o.option: o for o in prepare_outputs(("--json", args.json))}
    text = not ("--json" in outputs and outputs["--json"].to_stdout)
    out = sys.stdout if text else sys.stderr
    chosen = select(_read_instances(directory), args.only, args.skip_larger_than)
    if not chosen:
        raise UsageError("no instance matches --only")
    print(_row([n for n, _w, _a in _COLS]), file=out)
    results = []
    for inst, skip in chosen:
        r = _validate(directory, inst, skip, args)
        results.append(r)
        _print_result(r, out, args.quiet)
    counts = {s: sum(r.status == s for r in results) for s in ("match", "mismatch", "error", "partial", "skipped")}
    total = sum(r.seconds for r in results)
    print(f"\n{counts['match']} match, {counts['mismatch']} mismatch, {counts['error']} error, "
          f"{counts['partial']} partial, {counts['skipped']} skipped; {total:.1f} s", file=out)
    formulas = formula_totals(results)
    if formulas:
        print(format_formula_totals(formulas, args.formula_seconds), file=out)
        print(format_ratios(results), file=out)
    if "--json" in outputs:
        write_output(outputs["--json"], json.dumps({"directory": directory, "max_states": args.max_states,
                                                    "formula_seconds": args.formula_seconds,
                                                    "formula_max_states": args.formula_max_states,
                                                    "formula_totals": formulas,
                                                    "results": [_result_json(r) for r in results]}, indent=2)
                     + "\n")
    if counts["mismatch"] or counts["error"] or formulas.get("total", {}).get("disagree"):
        return ExitStatus.VIOLATED
    if counts["partial"] or formulas.get("total", {}).get("unknown"):
        return ExitStatus.UNKNOWN
    return ExitStatus.OK


def _read_instances(directory: str) -> list[dict]:
    """The instances of DIR/expected.json; a usage error when it cannot be read."""
    spec = os.path.join(directory, "expected.json")
    try:
        with open(spec, encoding="utf-8") as fh:
            corpus = json.load(fh)
    except (OSError, ValueError) as exc:
        raise UsageError(f"cannot read {spec}: {exc}") from None
    return corpus["instances"] if isinstance(corpus, dict) else corpus


def _validate(directory: str, inst: dict, skip: str | None, args) -> Result:
    """One instance's row: skipped, or its figures compared (and its formulas, unless --no-formulas)."""
    if skip:
        return Result(inst["name"], inst.get("format", "?"), "skipped", expected=inst, reason=skip)
    r = validate_instance(directory, inst, args.max_states)
    if not args.no_formulas and r.status in ("match", "mismatch"):
        validate_formulas(directory, r, inst, args.formula_seconds, args.formula_max_states, args.max_states)
    return r


def _print_result(r: Result, out, quiet: bool) -> None:
    """An instance's row, its differences, its formulas' counts and disagreements, and why it failed."""
    print(format_row(r), file=out, flush=True)
    for d in r.differences:
        print(f"    {d}", file=out)
    if r.formulas:
        n = r.formula_counts()
        print(f"    formulas: {n['agree']} agree, {n['disagree']} disagree, {n['unknown']} unknown "
              f"({r.formula_seconds:.1f} s)", file=out)
        for f in r.formulas:
            if f["result"] != "agree":
                print(f"    {f['result']}: {f['id']}: published {f['expected']}, found {f['found']}"
                      + (f" ({f['reason']})" if f.get("reason") else ""), file=out)
    if r.reason and r.status != "match" and not (quiet and r.status in ("skipped", "partial")):
        for line in r.reason.splitlines()[:12]:
            print(f"    {line}", file=out)


def _result_json(r: Result) -> dict:
    """An instance's entry in the --json file."""
    return {"name": r.name, "format": r.format, "status": r.status, "seconds": round(r.seconds, 3),
            "found": r.found, "differences": r.differences, "reason": r.reason,
            **({"formulas": r.formulas, "formula_seconds": round(r.formula_seconds, 3),
                "examination_seconds": {e: round(t, 3) for e, t in r.exam_seconds.items()},
                "examination_ratio": {e: round(x, 2) for e, x in r.ratios().items()}}
               if r.formulas else {})}


def formula_totals(results: list[Result]) -> dict[str, dict[str, int]]:
    """agree / disagree / unknown per examination and in total ('total'), over every instance."""
    out: dict[str, dict[str, int]] = {}
    for r in results:
        for f in r.formulas:
            for key in (f["examination"], "total"):
                row = out.setdefault(key, {"agree": 0, "disagree": 0, "unknown": 0})
                row[f["result"]] += 1
    if "total" in out:
        out["total"] = out.pop("total")  # last
    return out


def format_ratios(results: list[Result]) -> str:
    """Per examination, the median and largest ratio of the time to answer its 16 formulas (from nothing)
    to the time to explore the whole state space once, over the instances."""
    per: dict[str, list[tuple[float, str]]] = {}
    for r in results:
        for e, x in r.ratios().items():
            per.setdefault(e, []).append((x, r.name))
    lines = ["\ntime to answer an examination / time to explore the state space once:",
             f"  {'examination':<24}  {'median':>7}  {'largest':>8}  instance"]
    for e, xs in per.items():
        xs.sort()
        lines.append(f"  {e:<24}  {xs[len(xs) // 2][0]:>7.2f}  {xs[-1][0]:>8.2f}  {xs[-1][1]}")
    return "\n".join(lines)


def format_formula_totals(totals: dict[str, dict[str, int]], seconds: float) -> str:
    lines = [f"\nformula verdicts against the published ones (at most {seconds:g} s per instance):",
             f"  {'examination':<24}  {'agree':>6}  {'disagree':>8}  {'unknown':>7}"]
    for exam, n in totals.items():
        lines.append(f"  {exam:<24}  {n['agree']:>6}  {n['disagree']:>8}  {n['unknown']:>7}")
    return "\n".join(lines)
