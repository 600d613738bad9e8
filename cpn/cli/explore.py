"""`cpn-verify explore MODEL`: build the state space and print the standard report.

Exit statuses: 0 the state space is complete; 2 partial (a limit stopped the search); 64 bad usage;
65 bad model. The report goes to stdout; progress (on a terminal only) and errors go to stderr.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time

EXIT_COMPLETE = 0
EXIT_PARTIAL = 2
EXIT_USAGE = 64
EXIT_DATAERR = 65

DESCRIPTION = """Build the full state space (occurrence graph) of MODEL breadth-first and print
CPN Tools' standard state space report: statistics, integer and multi-set bounds, home markings,
dead markings (with the shortest trace to the first one), dead and live transition instances, and
fairness. A search stopped by a limit is reported as Partial with its unexpanded nodes, which are
never counted as dead markings."""


def add_parser(subparsers) -> argparse.ArgumentParser:
    p = subparsers.add_parser("explore", help="build the state space and print the standard report",
                              description=DESCRIPTION)
    p.add_argument("model", metavar="MODEL", help="model file (.cpnet, .pnml or .cpn)")
    p.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                   help="override a 'val' constant of the model (may be repeated)")
    p.add_argument("--max-states", type=int, metavar="N", help="stop after N states")
    p.add_argument("--max-arcs", type=int, metavar="N", help="stop after N arcs")
    p.add_argument("--max-seconds", type=float, metavar="S", help="stop after S seconds of generation")
    p.add_argument("--max-memory", type=float, metavar="MB", help="stop when the process uses MB MiB")
    p.add_argument("--time-condensation", action="store_true",
                   help="identify states that differ only by a uniform time shift (CPN Tools' CreationTime)")
    p.add_argument("--no-time-growth-check", action="store_true",
                   help="do not stop a timed search whose markings modulo time no longer change")
    p.add_argument("--json", metavar="FILE", help="write the result as JSON to FILE ('-': stdout, no text)")
    p.add_argument("--dot", metavar="FILE", help="write the state space and SCC graph as DOT (small nets)")
    p.add_argument("--graphml", metavar="FILE", help="write the state space and SCC graph as GraphML")
    p.add_argument("--quiet", action="store_true", help="no progress line")
    p.add_argument("--trace-to-dead", action="store_true",
                   help="show the marking changes of each step of the trace to the first dead marking")
    return p


def parse_sets(items: list[str]) -> dict[str, str]:
    out = {}
    for item in items:
        name, eq, value = item.partition("=")
        if not eq or not name.strip():
            raise ValueError(f"--set expects NAME=VALUE, got '{item}'")
        out[name.strip()] = value.strip()
    return out


def load_engine(path: str, sets: dict[str, str], time_condensation: bool):
    """The model's engine; raises ModelError (bad model) or OSError (unreadable file)."""
    import cpn

    model = cpn.load(path, set=sets)
    return model.engine(time_condensation=time_condensation)


def run(args) -> int:
    from cpn.errors import ConfigurationError, ModelError

    try:
        sets = parse_sets(args.set)
        for name in ("max_states", "max_arcs", "max_seconds", "max_memory"):
            v = getattr(args, name)
            if v is not None and v <= 0:
                raise ValueError(f"--{name.replace('_', '-')} must be positive, got {v:g}")
    except ValueError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    if not os.path.exists(args.model):
        print(f"error: no such model file: '{args.model}'", file=sys.stderr)
        return EXIT_USAGE
    try:
        engine = load_engine(args.model, sets, args.time_condensation)
    except ModelError as err:
        print(err.render(), file=sys.stderr)
        return EXIT_DATAERR
    except ConfigurationError as err:
        print(err.render(), file=sys.stderr)
        return EXIT_USAGE
    except OSError as exc:
        print(f"error: cannot read '{args.model}': {exc}", file=sys.stderr)
        return EXIT_USAGE
    return explore_engine(engine, args, sets)


def _options(args):
    from cpn.statespace import ExploreOptions

    return ExploreOptions(max_states=args.max_states, max_arcs=args.max_arcs, max_seconds=args.max_seconds,
                          max_memory_mb=args.max_memory, time_condensation=args.time_condensation,
                          detect_time_growth=not args.no_time_growth_check)


def explore_engine(engine, args, sets: dict[str, str] | None = None) -> int:
    """Explore, report and export for an already built engine (the part of `run` after loading)."""
    from cpn.errors import EvaluationError
    from cpn.report import build_report, render_text, to_json
    from cpn.report.graphs import MAX_EXPORT_STATES, TooLargeToExport, write_dot, write_graphml
    from cpn.statespace import Explorer

    options = _options(args)
    display = _ProgressLine() if (not args.quiet and sys.stderr.isatty()) else None
    try:
        x = Explorer(engine, options, progress=display).run()
    except EvaluationError as err:
        if display:
            display.close()
        print(err.render(), file=sys.stderr)
        return EXIT_DATAERR
    if display:
        display.close()
    opts = {"set": sets or {}, "max_states": args.max_states, "max_arcs": args.max_arcs,
            "max_seconds": args.max_seconds, "max_memory_mb": args.max_memory,
            "time_condensation": bool(args.time_condensation)}
    report = build_report(x, model=os.path.abspath(args.model), options=opts)
    json_to_stdout = args.json == "-"
    if not json_to_stdout:
        text = render_text(report)
        if not args.trace_to_dead:
            text = _without_marking_changes(text)
        sys.stdout.write(text)
    if args.json:
        data = json.dumps(to_json(report), indent=2, ensure_ascii=False)
        if json_to_stdout:
            sys.stdout.write(data + "\n")
        else:
            with open(args.json, "w", encoding="utf-8") as fh:
                fh.write(data + "\n")
    for path, writer, kind in ((args.dot, write_dot, "DOT"), (args.graphml, write_graphml, "GraphML")):
        if not path:
            continue
        try:
            writer(report, path)
        except TooLargeToExport:
            print(f"note: {kind} export skipped: the state space has {x.n_states:,} states and exports are "
                  f"limited to {MAX_EXPORT_STATES:,} (a drawing that large is unreadable); use --json "
                  "for the figures or a --max-states limit for a partial drawing", file=sys.stderr)
    if not x.complete:
        print(f"partial state space: stopped because {x.stop_reason.describe(x.options)}; "
              f"{x.unexpanded:,} states were not expanded", file=sys.stderr)
        for note in report.notes:
            print(f"note: {note}", file=sys.stderr)
        return EXIT_PARTIAL
    return EXIT_COMPLETE


def _without_marking_changes(text: str) -> str:
    """Drop the per-step marking changes of the dead-marking trace (kept with --trace-to-dead)."""
    out = []
    in_trace = False
    for line in text.split("\n"):
        if line.startswith("  Shortest trace to dead marking"):
            in_trace = True
        elif in_trace and not line.startswith("     "):
            in_trace = False
        if in_trace and line.startswith("          "):
            continue
        out.append(line)
    return "\n".join(out)


class _ProgressLine:
    """A rich live line on stderr (states, arcs, queue, states/s, memory), shown after one second."""

    def __init__(self):
        self._live = None
        self._t0 = time.perf_counter()

    def __call__(self, p) -> None:
        if self._live is None:
            if p.seconds < 1.0:
                return
            from rich.console import Console
            from rich.live import Live

            self._live = Live("", console=Console(stderr=True), transient=True, auto_refresh=False)
            self._live.start()
        self._live.update(
            f"[bold]exploring[/]  states {p.states:,}  arcs {p.arcs:,}  queue {p.queue:,}  "
            f"{p.states_per_second:,.0f} states/s  {p.memory_mb:,.0f} MiB  {p.seconds:,.1f} s", refresh=True)

    def close(self) -> None:
        if self._live is not None:
            self._live.stop()
            self._live = None
