"""`cpn-verify check [SCENARIO|DIR]...`: prove the properties of scenario files, the CI gate.

Parses the arguments, runs each scenario (`cpn.checks.gate`), prints the summary and the counterexamples,
writes the reports. Exit statuses (DESIGN.md 4): 0 every property holds on a complete state space; 1 a
property is violated; 2 unknown (a limit stopped a search first); 64 bad usage; 65 bad model or scenario
file (or a property text that fails in some marking); 70 internal error.
"""

from __future__ import annotations

import argparse
import json
import os
import sys

from cpn.cli._common import (
    ExitStatus,
    UsageError,
    add_limit_options,
    add_output_option,
    add_parallel_options,
    add_quiet_option,
    check_limits,
    check_parallel,
    prepare_outputs,
    write_output,
)
from cpn.cli.explore import _ProgressLine

DEFAULT_DIR = "specs"

DESCRIPTION = """Explore the state space of each scenario (a TOML file naming a model, the values of its
constants, exploration limits and the properties the protocol must have; docs/specs.md) and give each
property a verdict: holds, violated (with the shortest counterexample), or unknown (a limit stopped the
search). With no argument, every *.toml under specs/ is checked. Reports (text, JSON, Markdown) are
written per scenario run under --reports."""




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
    add_limit_options(p)  # override the limits of every scenario ([explore] in the file)
    add_parallel_options(p)
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
    from cpn import __version__
    from cpn.checks.gate import run_scenario
    from cpn.checks.scenario import load_scenario, scenario_files
    from cpn.errors import ConfigurationError, EvaluationError, ModelError
    from cpn.report.verdicts import report_name, run_report

    check_limits(args)
    check_parallel(args)
    outputs = {o.option: o for o in prepare_outputs(("--junit", args.junit), ("--sarif", args.sarif))}
    paths = args.paths or [DEFAULT_DIR]
    for p in paths:
        if not os.path.exists(p):
            hint = "" if args.paths else " (name scenario files or folders, or run from the folder that holds specs/)"
            raise UsageError(f"no such scenario file or folder: '{p}'{hint}")
    files = scenario_files(paths)
    if not files:
        raise UsageError(f"no scenario (*.toml) in {', '.join(paths)}")
    overrides = {"max_states": args.max_states, "max_arcs": args.max_arcs, "max_seconds": args.max_seconds,
                 # the default memory limit applies only where a scenario sets none
                 "default_max_memory_mb" if args.max_memory_is_default else "max_memory_mb": args.max_memory,
                 "stop_at_first_violation": True if args.stop_at_first_violation else None,
                 "workers": args.workers, "ray": args.ray,
                 "sweep_line": True if args.sweep_line or args.progress else None, "progress": args.progress}
    if args.html:
        _prepare_html_folder(args.html)  # before any run: a long check must never be lost to a bad path
    pages: list = []
    stdout_taken = any(o.to_stdout for o in outputs.values())
    docs: list[dict] = []
    bad_files = 0
    timings = not args.no_timings
    for path in files:
        try:
            scenario = load_scenario(path)
        except ModelError as err:
            print(err.render(), file=sys.stderr)
            bad_files += 1
            continue
        for r in scenario.runs:
            display = _ProgressLine() if (not args.quiet and sys.stderr.isatty()) else None
            try:
                result = run_scenario(scenario, r, overrides, progress=display)
            except (ModelError, EvaluationError) as err:
                if len(scenario.runs) > 1:
                    print(f"in run {r.name}:", file=sys.stderr)
                print(err.render(), file=sys.stderr)
                bad_files += 1
                continue
            except ConfigurationError as err:
                print(f"{path}: {err.render()}", file=sys.stderr)
                bad_files += 1
                continue
            finally:
                if display is not None:
                    display.close()
            doc = run_report(result, timings=timings)
            docs.append(doc)
            if not args.quiet and not stdout_taken:
                _print_run(doc, args.trace_format)
            if not args.no_reports:
                _write_reports(args.reports, report_name(r.name), doc)
            if args.html and result.exploration.graph is not None:  # a sweep-line run has no graph to draw
                pages.append(_write_html_page(args.html, result, report_name(r.name)))
    if not stdout_taken:
        _print_summary(docs, timings)
    if "--junit" in outputs:
        from cpn.report.junit import render_junit

        write_output(outputs["--junit"], render_junit(docs, timings))
    if "--sarif" in outputs:
        from cpn.report.sarif import render_sarif

        write_output(outputs["--sarif"], json.dumps(render_sarif(docs, __version__), indent=2, ensure_ascii=False)
                     + "\n")
    if args.html:
        from cpn.report.html import write_index

        write_index(args.html, pages)
    if args.baseline and not stdout_taken:
        _print_baseline(args.baseline, docs)
    statuses = {d["verdict"] for d in docs}
    if bad_files or "error" in statuses:
        return ExitStatus.DATAERR
    if "violated" in statuses:
        return ExitStatus.VIOLATED
    if "unknown" in statuses:
        return ExitStatus.UNKNOWN
    return ExitStatus.OK


def _print_run(doc: dict, trace_format: str) -> None:
    from cpn.report.verdicts import label, render_steps

    for p in doc["properties"]:
        if p.get("gate", p["verdict"]) == "holds":
            continue
        where = f"{os.path.relpath(doc['file'])}:{p['line']}:{p['column']}"
        print(f"{where}: {label(p)}: {doc['run']}: '{p['name']}' ({p['kind']}): {p['message']}")
        if "trace" in p:
            if trace_format == "json":
                print(json.dumps({"run": doc["run"], "property": p["name"], **p["trace"]}, ensure_ascii=False))
            else:
                print("\n".join(render_steps(p["trace"], indent="    ")))
        print()


def _print_summary(docs: list[dict], timings: bool) -> None:
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
        rows.append((d["run"], space, secs, d["verdict"], tally))
    head = ("scenario", "states", "seconds", "verdict", "properties")
    widths = [max(len(r[i]) for r in rows + [head]) for i in range(5)]
    line = "  ".join(f"{h:<{widths[i]}}" if i in (0, 3, 4) else f"{h:>{widths[i]}}" for i, h in enumerate(head))
    print(line.rstrip())
    for r in rows:
        print("  ".join(f"{c:<{widths[i]}}" if i in (0, 3, 4) else f"{c:>{widths[i]}}" for i, c in enumerate(r)).rstrip())
    for d in docs:
        bad = [p for p in d["properties"] if p.get("gate", p["verdict"]) != "holds"]
        for p in bad:
            print(f"  {label(p):<9} {d['run']}: {p['name']}")


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


def _prepare_html_folder(folder: str) -> None:
    from cpn.cli._common import CannotCreate

    try:
        os.makedirs(folder, exist_ok=True)
    except OSError as exc:
        raise CannotCreate(f"cannot write --html {folder}: {exc.strerror or exc}") from None


def _write_html_page(folder: str, result, stem: str):
    """The page of one run (its report, its verdicts and their traces); returns its index entry."""
    from cpn.report import build_report
    from cpn.report.html import Verdict, write_run_page

    x = result.exploration
    report = build_report(x, model=result.scenario.model,
                          options={"set": dict(result.run.values),
                                   "time_condensation": bool(result.options.get("time_condensation"))})
    verdicts = []
    for r in result.results:
        v = r.verdict
        expect = "" if r.spec.expect == "holds" else f" (expected: {r.spec.expect})"
        verdicts.append(Verdict(r.spec.name, v.status, v.message + expect, v.evidence))
    return write_run_page(folder, stem, result.run.name, report, verdicts, status=result.status.value)


def _write_reports(folder: str, stem: str, doc: dict) -> None:
    from cpn.report.verdicts import render_markdown, render_text

    os.makedirs(folder, exist_ok=True)
    _write(os.path.join(folder, f"{stem}.json"), json.dumps(doc, indent=2, ensure_ascii=False) + "\n")
    _write(os.path.join(folder, f"{stem}.txt"), render_text(doc))
    _write(os.path.join(folder, f"{stem}.md"), render_markdown(doc))


def _write(path: str, text: str) -> None:
    folder = os.path.dirname(path)
    if folder:
        os.makedirs(folder, exist_ok=True)
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(text)
