"""`cpn-verify check [SCENARIO|DIR]...`: prove the properties of scenario files, the CI gate.

Parses the arguments, runs each scenario (`cpn.gate.run`), prints the summary and the counterexamples,
writes the reports. Exit statuses (DESIGN.md 4): 0 every property holds on a complete state space; 1 a
property is violated; 2 unknown (a limit stopped a search first); 64 bad usage; 65 bad model or scenario
file (or a property text that fails in some marking); 70 internal error.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from concurrent.futures.process import BrokenProcessPool
from typing import NamedTuple

from cpn.cli._common import (
    ExitStatus,
    UsageError,
    add_limit_options,
    add_output_option,
    add_parallel_options,
    add_quiet_option,
    add_set_option,
    check_limits,
    check_parallel,
    prepare_outputs,
    sets_of,
    write_output,
)
from cpn.cli._scenarios import load_scenarios, scenario_paths
from cpn.cli._search_args import ProgressLine

DEFAULT_DIR = "specs"
# seconds of generation per run where neither the scenario (max_seconds) nor --max-seconds sets a limit: an
# unbounded model ends with a partial report (status 2) instead of filling the machine's memory
DEFAULT_MAX_SECONDS = 600.0

DESCRIPTION = f"""Explore the state space of each scenario (a TOML file naming a model, the values of its
constants, exploration limits and the properties the protocol must have; docs/specs.md) and give each
property a verdict: holds, violated (with the shortest counterexample), or unknown (a limit stopped the
search). With no argument, every *.toml under specs/ is checked. Reports (text, JSON, Markdown) are
written per scenario run under --reports. A run whose scenario sets no max_seconds stops after
{DEFAULT_MAX_SECONDS:g} seconds of search (--max-seconds changes it for every run)."""




def add_parser(subparsers) -> argparse.ArgumentParser:
    p = subparsers.add_parser("check", help="prove the properties of scenario files (the CI gate)",
                              description=DESCRIPTION)
    p.add_argument("paths", nargs="*", metavar="SCENARIO|DIR", help=f"scenario files or folders (default: {DEFAULT_DIR}/)")
    p.add_argument("--reports", metavar="DIR", default="reports",
                   help="folder for the per-run reports (default: reports)")
    p.add_argument("--no-reports", action="store_true", help="write no per-run report files")
    add_output_option(p, "--junit", "JUnit XML (one test case per property)")
    add_output_option(p, "--sarif", "SARIF 2.1.0 (violations located in the spec files)")
    p.add_argument("--html", metavar="DIR",
                   help="write one HTML page per scenario run (the net, the state space, every counterexample "
                   "as a chart) and an index page, DIR/index.html")
    p.add_argument("--baseline", metavar="DIR",
                   help="compare with the JSON reports of an earlier run in DIR and print what changed")
    p.add_argument("--trace-format", choices=("text", "json"), default="text",
                   help="how counterexamples are printed (default: text)")
    add_set_option(p)  # over [set] and the parameter table of every scenario; the run's name shows it
    add_limit_options(p, default_seconds=DEFAULT_MAX_SECONDS)  # override every scenario's [explore] limits
    add_parallel_options(p)
    p.add_argument("-j", "--jobs", type=int, metavar="N", default=None,
                   help="check N scenario runs at once, each in a process of its own (default: one per "
                   "processor of this machine, 1 with --workers or --ray); the output and the reports are "
                   "those of one process, and each run keeps its limits (--max-memory is each process's)")
    p.add_argument("--stop-at-first-violation", action="store_true",
                   help="stop each search at the first violated invariant or dead marking (fail fast)")
    p.add_argument("--sweep-line", action="store_true",
                   help="explore every run with the sweep-line method (as sweep_line = true in [explore]; "
                   "docs/specs.md): less memory, no graph, so properties that need one are unknown")
    p.add_argument("--progress", metavar="EXPR", default=None,
                   help="the sweep-line's progress measure, an integer expression over the marking "
                   "(as progress = \"...\" in [explore]); default: the scenario's, else the global clock")
    p.add_argument("--no-timings", action="store_true",
                   help="leave run times out of the output and reports (byte-identical reruns)")
    add_quiet_option(p)
    return p


def run(args) -> int:
    from cpn.model import caching

    with caching():  # a model is parsed once, and checked once per set of constant values (cpn.model.LoadCache)
        return _run(args)


def _run(args) -> int:
    from cpn.report.verdicts import report_name

    check_limits(args)
    check_parallel(args)
    sets = sets_of(args)
    outputs = {o.option: o for o in prepare_outputs(("--junit", args.junit), ("--sarif", args.sarif))}
    files = scenario_paths(args.paths or [DEFAULT_DIR], "" if args.paths else
                           " (name scenario files or folders, or run from the folder that holds specs/)")
    _prepare_folders(args)
    pages: list = []
    stdout_taken = any(o.to_stdout for o in outputs.values())
    docs: list[dict] = []
    timings = not args.no_timings
    scenarios, bad_files = load_scenarios(files, sets)
    for scenario in scenarios:
        if not scenario.properties:
            from cpn.diagnostics import render

            print(render(_no_property(scenario), scenario.source), file=sys.stderr)
    tasks = [(scenario, r) for scenario in scenarios for r in scenario.runs]
    jobs = _jobs(args, tasks)
    settings = _Settings(_overrides(args, sets), args.quiet, timings, args.html)
    usage_errors = 0
    done = 0
    interrupted = lost = False
    try:
        for (_, r), (doc, page, failure) in zip(tasks, _outcomes(tasks, settings, jobs)):
            done += 1
            if doc is None:
                usage_errors += failure == "usage"
                bad_files += failure == "bad"
                continue
            docs.append(doc)
            if not stdout_taken:  # --quiet keeps results: where a property fails, and its trace
                _print_run(doc, args.trace_format)
            if not args.no_reports:
                _write_reports(args.reports, report_name(r.name), doc)
            if page is not None:
                pages.append(page)
    except KeyboardInterrupt:  # between searches, or with --jobs (a search itself ends with a partial report)
        interrupted = True
        print(f"interrupted: {len(tasks) - done} of {len(tasks)} runs not checked", file=sys.stderr)
    except BrokenProcessPool:  # --jobs: a process ended without a result, and the pool with it
        lost = True
        print("error: a process checking the runs ended without a result (stopped by the system, out of memory, "
              f"or a crash); {len(tasks) - done} of {len(tasks)} runs not checked, from '{tasks[done][1].name}' on\n"
              "hint: check them with --jobs 1 to see which run stops its process", file=sys.stderr)
    if not stdout_taken:
        _print_summary(docs, timings)
    _write_outputs(outputs, docs, timings)
    if args.html:
        from cpn.report.html import write_index

        write_index(args.html, pages)
    if args.baseline and not stdout_taken:
        _print_baseline(args.baseline, docs)
    statuses = {d["verdict"] for d in docs}
    found = [ExitStatus.USAGE if usage_errors else ExitStatus.OK,
             ExitStatus.DATAERR if bad_files or "error" in statuses else ExitStatus.OK,
             ExitStatus.VIOLATED if "violated" in statuses else ExitStatus.OK,
             ExitStatus.UNKNOWN if "unknown" in statuses else ExitStatus.OK]
    if lost:
        return ExitStatus.SOFTWARE
    return ExitStatus.INTERRUPTED if interrupted else ExitStatus.worst(found)


class _Settings(NamedTuple):
    """What every run of one `check` shares."""

    overrides: dict
    quiet: bool
    timings: bool
    html: str | None


def _jobs(args, tasks: list) -> int:
    """How many runs are checked at once (--jobs; cpn.cli._jobs): one at a time where a search of its own
    spreads over the processors (--workers, --ray, or `workers`/`ray` in a scenario's [explore])."""
    from cpn.cli._jobs import default_jobs

    if args.jobs is not None and args.jobs < 1:
        raise UsageError(f"--jobs must be at least 1, got {args.jobs}")
    partitioned = sorted({s.path for s, _ in tasks if s.explore.get("workers") or s.explore.get("ray")})
    why = ("--workers or --ray spread each search over the processors" if args.workers or args.ray
           else f"{partitioned[0]} searches with workers of its own ([explore] workers or ray)" if partitioned
           else None)
    if why is not None:
        if args.jobs is not None and args.jobs > 1 and not args.quiet:
            print(f"note: the runs are checked one at a time: {why}", file=sys.stderr)
        return 1
    return min(args.jobs, max(len(tasks), 1)) if args.jobs is not None else default_jobs(len(tasks))


def _outcomes(tasks: list, settings: _Settings, jobs: int):
    """(report document, HTML index entry, failure) of each run, in order: in this process, or in `jobs`."""
    from cpn.cli._jobs import ordered_map

    items = [(scenario, r, settings) for scenario, r in tasks]
    return map(_check_run, items) if jobs <= 1 else ordered_map(_check_run, items, jobs)


def _check_run(item) -> tuple:
    """Run one scenario run: (its report document, its HTML page's index entry or None, None), or
    (None, None, "bad" or "usage") with the error printed."""
    from cpn.report.verdicts import report_name, run_report

    scenario, r, settings = item
    result, failure = _run_one(scenario, r, settings.overrides, settings.quiet)
    if result is None:
        return None, None, failure
    doc = run_report(result, timings=settings.timings)
    page = None
    if settings.html and result.exploration.graph is not None:  # a sweep-line run has no graph to draw
        page = _write_html_page(settings.html, result, report_name(r.name), settings.timings)
    return doc, page, None



def _prepare_folders(args) -> None:
    """Check --baseline, and make the --reports and --html folders, before any run: a long check must
    never be lost to a bad path."""
    if args.baseline is not None and not os.path.isdir(args.baseline):
        what = "it is a file, not a folder" if os.path.exists(args.baseline) else "no such folder"
        raise UsageError(f"--baseline {args.baseline}: {what}\nhint: name the --reports folder of an "
                         "earlier run of 'cpn-verify check' (its JSON reports are compared with this run's)")
    if not args.no_reports:
        _prepare_folder(args.reports, "--reports",
                        "" if args.reports != "reports" else " (the default, reports/ in the working directory; "
                        "give --reports DIR, or --no-reports)")
    if args.html:
        _prepare_folder(args.html, "--html")


def _overrides(args, sets: dict) -> dict:
    """What the command line sets for every run, over the scenarios' own settings."""
    return {"max_states": args.max_states, "max_arcs": args.max_arcs, "max_seconds": args.max_seconds,
            # the default limits apply only where a scenario sets none
            "default_max_memory_mb" if args.max_memory_is_default else "max_memory_mb": args.max_memory,
            "default_max_seconds": args.max_seconds_default if args.max_seconds is None else None,
            "stop_at_first_violation": True if args.stop_at_first_violation else None,
            "workers": args.workers, "ray": args.ray,
            "sweep_line": True if args.sweep_line or args.progress else None, "progress": args.progress,
            "set": sets or None}



def _run_one(scenario, r, overrides: dict, quiet: bool):
    """Run `r` of `scenario`: (its result, None), or (None, "bad" or "usage") with the error printed."""
    from cpn.engine.clock import TimeCondensationRefused
    from cpn.errors import ConfigurationError, EvaluationError, ModelError
    from cpn.gate.run import run_scenario

    display = ProgressLine() if (not quiet and sys.stderr.isatty()) else None
    try:
        return run_scenario(scenario, r, overrides, progress=display), None
    except (ModelError, EvaluationError) as err:
        if len(scenario.runs) > 1:
            print(f"in run {r.name}:", file=sys.stderr)
        print(err.render(), file=sys.stderr)
        return None, "bad"
    except ConfigurationError as err:
        print(f"{scenario.path}: {err.render()}", file=sys.stderr)
        # a value of --set that the model refuses, or time condensation asked of a model that reads
        # the clock: usage refusals (64), as `explore` reports them
        if getattr(err, "code", None) == "E0305" or isinstance(err, TimeCondensationRefused):
            return None, "usage"
        return None, "bad"
    finally:
        if display is not None:
            display.close()


def _write_outputs(outputs: dict, docs: list[dict], timings: bool) -> None:
    """The JUnit and SARIF files of the whole check, where asked."""
    from cpn import __version__

    if "--junit" in outputs:
        from cpn.report.junit import render_junit

        write_output(outputs["--junit"], render_junit(docs, timings))
    if "--sarif" in outputs:
        from cpn.report.sarif import render_sarif

        write_output(outputs["--sarif"], json.dumps(render_sarif(docs, __version__), indent=2, ensure_ascii=False)
                     + "\n")






def _no_property(scenario):
    """The warning for a scenario that states no property: its runs would pass the gate having checked nothing."""
    from cpn.diagnostics import Diagnostic, Severity, Span

    return Diagnostic("W0701", "the scenario states no property: its runs check nothing, and the gate counts "
                      "them as holding", Span(scenario.path, 1, 1),
                      hint="Add the properties the protocol must have as [[property]] tables (docs/specs.md); "
                      "to look at a state space alone, run 'cpn-verify explore MODEL'.", severity=Severity.WARNING)


def _print_run(doc: dict, trace_format: str) -> None:
    from cpn.report.verdicts import label, property_warnings, render_steps

    for p in doc["properties"]:
        where = f"{os.path.relpath(doc['file'])}:{p['line']}:{p['column']}"
        for code, w in property_warnings(p):
            print(f"{where}: warning[{code}]: {doc['run']}: '{p['name']}' ({p['kind']}) {w}", file=sys.stderr)
        if p.get("gate", p["verdict"]) == "holds":
            continue
        print(f"{where}: {label(p)}: {doc['run']}: '{p['name']}' ({p['kind']}): {p['message']}")
        if "trace" in p:
            if trace_format == "json":
                print(json.dumps({"run": doc["run"], "property": p["name"], **p["trace"]}, ensure_ascii=False))
            else:
                print("\n".join(render_steps(p["trace"], indent="    ")))
        print()


def _print_summary(docs: list[dict], timings: bool) -> None:
    """One line per run (its time limit says "default" where its scenario sets none), then each property
    that does not hold, the runs that checked nothing, and the runs the default time limit stopped."""
    from cpn.report.verdicts import label

    if not docs:
        return
    rows = []
    for d in docs:
        st = d["statespace"]
        counts: dict[str, int] = {}
        for p in d["properties"]:
            counts[label(p)] = counts.get(label(p), 0) + 1
        tally = ", ".join(f"{n} {v}" for v, n in sorted(counts.items(), key=lambda kv: (_ORDER[kv[0].split()[0]],
                                                                                        kv[0])))
        space = f"{st['states']:,}" + ("" if st["complete"] else " (partial)")
        secs = f"{st.get('seconds', 0) + st.get('check_seconds', 0):.2f}" if timings else "-"
        rows.append((d["run"], space, secs, _time_limit(d), d["verdict"], tally or "no property"))
    head = ("scenario", "states", "seconds", "time limit", "verdict", "properties")
    left = (0, 3, 4, 5)
    widths = [max(len(r[i]) for r in rows + [head]) for i in range(len(head))]

    def row(cells) -> str:
        return "  ".join(f"{c:<{widths[i]}}" if i in left else f"{c:>{widths[i]}}" for i, c in enumerate(cells))

    print(row(head).rstrip())
    for r in rows:
        print(row(r).rstrip())
    for d in docs:
        bad = [p for p in d["properties"] if p.get("gate", p["verdict"]) != "holds"]
        for p in bad:
            print(f"  {label(p):<9} {d['run']}: {p['name']}")
    empty = [d["run"] for d in docs if not d["properties"]]
    if empty:
        print(f"  {len(empty)} run{'s' if len(empty) > 1 else ''} checked no property, the scenario states none: "
              + ", ".join(empty))
    for d in docs:
        o = d.get("options", {})
        if d["statespace"]["stop_reason"] == "max_seconds" and o.get("max_seconds_is_default"):
            print(f"  {d['run']}: stopped by the default time limit of {o['max_seconds']:g} s a run; set max_seconds "
                  "in the scenario's [explore], or give --max-seconds S (0: no limit)")


def _time_limit(doc: dict) -> str:
    """The run's limit on seconds of search: '600 s (default)' where the scenario sets none."""
    o = doc.get("options", {})
    if o.get("max_seconds") is None:
        return "none"
    return f"{o['max_seconds']:g} s" + (" (default)" if o.get("max_seconds_is_default") else "")


_ORDER = {"error": 0, "violated": 1, "unknown": 2, "holds": 3}


def _print_baseline(folder: str, docs: list[dict]) -> None:
    from cpn.report.baseline import compare, load_reports

    old = load_reports(folder)
    if not old:
        print(f"\nbaseline: no check reports in '{folder}'")
        return
    changes = compare(old, docs)
    broke = sum(c.is_regression for c in changes)
    head = f"{broke} propert{'y' if broke == 1 else 'ies'} broke; " if broke else ""
    print(f"\n{head}changes since the baseline in '{folder}':")
    if not changes:
        print("  none")
    for c in changes:
        print(f"  {'REGRESSION ' if c.is_regression else ''}{c.text}")


def _prepare_folder(folder: str, option: str, default: str = "") -> None:
    """Create the output folder and write a file in it, before any work: CannotCreate (exit 73) if it
    cannot be (a file in the way, no permission, a read-only file system)."""
    import tempfile

    from cpn.cli._common import CannotCreate

    if os.path.exists(folder) and not os.path.isdir(folder):
        raise CannotCreate(f"cannot write {option} {folder}: it is a file, not a folder{default}")
    try:
        os.makedirs(folder, exist_ok=True)
        fd, probe = tempfile.mkstemp(prefix=".cpn-verify-", dir=folder)
        os.close(fd)
        os.remove(probe)
    except OSError as exc:
        raise CannotCreate(f"cannot write {option} {folder}: {exc.strerror or exc}{default}") from None


def _write_html_page(folder: str, result, stem: str, timings: bool = True):
    """The page of one run (its report, its verdicts and their traces); returns its index entry."""
    from cpn.properties.vacuity import warning_code
    from cpn.report import build_report
    from cpn.report.html import Verdict, write_run_page

    x = result.exploration
    report = build_report(x, model=result.scenario.model,
                          options={"set": dict(result.run.values),
                                   "time_condensation": bool(result.options.get("time_condensation"))})
    report.timings = timings
    verdicts = []
    for r in result.results:
        v = r.verdict
        expect = "" if r.spec.expect == "holds" else f" (expected: {r.spec.expect})"
        verdicts.append(Verdict(r.spec.name, v.status, v.message + expect, v.evidence,
                                places=tuple(result.engine.places[p].name for p in r.reads),
                                warnings=tuple((warning_code(w), w) for w in r.warnings)))
    return write_run_page(folder, stem, result.run.name, report, verdicts, status=result.status.value)


def _write_reports(folder: str, stem: str, doc: dict) -> None:
    from cpn.report.verdicts import render_markdown, render_text

    _write(os.path.join(folder, f"{stem}.json"), json.dumps(doc, indent=2, ensure_ascii=False) + "\n")
    _write(os.path.join(folder, f"{stem}.txt"), render_text(doc))
    _write(os.path.join(folder, f"{stem}.md"), render_markdown(doc))


def _write(path: str, text: str) -> None:
    from cpn.cli._common import CannotCreate

    try:
        folder = os.path.dirname(path)
        if folder:
            os.makedirs(folder, exist_ok=True)
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(text)
    except OSError as exc:  # the folder was checked before the run; this is a full disk, or a folder in the way
        raise CannotCreate(f"cannot write the report {path}: {exc.strerror or exc}") from None
