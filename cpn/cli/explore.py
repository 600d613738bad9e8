"""`cpn-verify explore MODEL`: build the state space and print the standard report.

Exit statuses: 0 the state space is complete; 2 partial (a limit stopped the search); 64 bad usage;
65 bad model; 73 an output file cannot be written (checked before the search starts). The report goes
to stdout; progress (on a terminal only) and errors go to stderr.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time

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
    parse_sets,
    sets_of,
    write_output,
)
from cpn.cli._search_args import ProgressLine, explore_options, explore_outputs
from cpn.report.words import noun

__all__ = ["add_parser", "explore_engine", "load_engine", "parse_sets", "run"]

DESCRIPTION = """Build the full state space (occurrence graph) of MODEL breadth-first and print
CPN Tools' standard state space report: statistics, integer and multi-set bounds, home markings,
dead markings (each, up to a cap, with its marking and a shortest trace), dead and live transition
instances, and fairness. A search stopped by a limit is reported as Partial with its unexpanded nodes,
which are never counted as dead markings. Properties are verified (exit 1 when one is violated) by
'cpn-verify check'."""


def add_parser(subparsers) -> argparse.ArgumentParser:
    p = subparsers.add_parser("explore", help="build the state space and print the standard report",
                              description=DESCRIPTION)
    p.add_argument("model", metavar="MODEL", help="model file (.cpnet, .pnml or .cpn)")
    add_set_option(p)
    add_limit_options(p)
    _add_search_options(p)
    add_parallel_options(p)
    _add_report_options(p)
    return p


def _add_search_options(p) -> None:
    """The options that choose which state space is built, and how."""
    p.add_argument("--time-condensation", action="store_true",
                   help="identify states that differ only by a uniform time shift (CPN Tools' CreationTime)")
    p.add_argument("--reduction", choices=["stubborn", "symmetry"], default=None,
                   help="explore a reduced graph: 'stubborn' follows only a stubborn set of transition instances "
                   "in each state (partial-order reduction; untimed nets without priorities); it preserves the "
                   "dead markings only, so the report gives them and says which sections are not preserved; "
                   "'symmetry' stores one marking per orbit of the model's declared symmetry (see --symmetry)")
    p.add_argument("--symmetry", metavar="CS[,CS...]", default=None,
                   help="symmetry reduction over these enumeration or index colour sets: NAME for all "
                   "permutations of its values, NAME:rotations for rotations (cyclic colour sets); 'auto' "
                   "takes every one the net does not tell apart (e.g. a PNML symmetric net's enumerations). "
                   "Refused, with the inscription at fault, when the net tells the values apart. The report "
                   "gives the quotient graph's counts, the full counts from the orbit sizes, and says which "
                   "sections are not preserved")
    p.add_argument("--no-time-growth-check", action="store_true",
                   help="do not stop a timed search whose markings modulo time no longer change")
    p.add_argument("--branch-transitions", metavar="NAMES", default=None,
                   help="branching option: explore only the binding elements of these transitions "
                        "(comma-separated; a name as in the report, Top'Send 1, or a transition's name, "
                        "for all its instances): a restricted state space")
    p.add_argument("--max-successors", type=int, metavar="N", default=None,
                   help="branching option: explore at most N successors of each state (the first in the "
                        "engine's fixed order): a restricted state space")
    p.add_argument("--until-time", type=int, metavar="B", default=None,
                   help="expand no state whose model time (clock) exceeds B: the timed state space up to "
                        "time B, reported as partial when some state lies beyond B")
    p.add_argument("--sweep-line", action="store_true",
                   help="explore in the order of a progress measure (default: the global clock of a timed net, "
                   "without time condensation) and delete the states behind it from memory: exact counts, "
                   "dead markings and bounds, but no graph (no SCCs, home, liveness, fairness or traces)")
    p.add_argument("--progress", metavar="EXPR", default=None,
                   help="the sweep-line's progress measure: an integer expression over the marking, as in a "
                   "scenario's properties (implies --sweep-line); an arc that decreases it is handled "
                   "and reported, and the counts are then upper bounds")
    p.add_argument("--backend", choices=("auto", "python", "c"), default="auto",
                   help="the search: 'c' runs its loop, caches and graph in native code and the transitions "
                   "in C generated from the net (built with the system C compiler, cached), 'python' in "
                   "Python; 'auto' (the default) is 'c' where it can run, generating the C once the search "
                   "is large, and says why not elsewhere (with --verbose); the state space is the same")


def _add_report_options(p) -> None:
    """The output files and what the text report shows."""
    add_output_option(p, "--json", "the result as JSON")
    add_output_option(p, "--dot", "the state space and SCC graph as DOT (small nets)")
    add_output_option(p, "--graphml", "the state space and SCC graph as GraphML (small nets)")
    p.add_argument("--max-export-states", type=int, metavar="N", default=None,
                   help="draw --dot and --graphml, and put the graph in --json, for a state space of up to N "
                   "states (default: 10,000; 0: no limit); above it they are skipped with a warning")
    add_output_option(p, "--html", "the report as one self-contained HTML page (the net, the state space, "
                      "a chart of the trace to each dead marking)")
    add_output_option(p, "--msc", "the trace to the first dead marking as a message sequence chart (SVG)")
    add_quiet_option(p)
    p.add_argument("-v", "--verbose", action="store_true",
                   help="also print which search ran and why, where that changes no result and asks nothing "
                   "of you (the Python search of a timed net, transitions whose bindings come from Python)")
    p.add_argument("--trace-to-dead", action="store_true",
                   help="show the marking changes of each step of the traces to the dead markings")
    p.add_argument("--max-listed", type=int, metavar="N", default=None,
                   help="cut every long listing of the text report (multi-set bounds, trace steps, "
                   "transition instances) at N entries and say how many were left out, and list N dead "
                   "markings with a trace (default: 20 colours, 100 steps, 100 names, 10 dead markings; "
                   "0: no cap); the JSON keeps every colour, step and name")


def load_engine(path: str, sets: dict[str, str], time_condensation: bool):
    """The model's engine; raises ModelError (bad model) or ConfigurationError (no such file)."""
    from cpn.cli._common import load_model

    return load_model(path, sets, state_space=True).engine(time_condensation=time_condensation)


def run(args) -> int:
    sets = sets_of(args)
    check_limits(args)
    check_parallel(args)
    if args.max_listed is not None and args.max_listed < 0:
        raise UsageError(f"--max-listed must not be negative, got {args.max_listed}")
    if getattr(args, "max_export_states", None) is not None and args.max_export_states < 0:
        raise UsageError(f"--max-export-states must not be negative, got {args.max_export_states}")
    if getattr(args, "max_successors", None) is not None and args.max_successors <= 0:
        raise UsageError(f"--max-successors must be positive, got {args.max_successors}")
    if getattr(args, "until_time", None) is not None and args.until_time < 0:
        raise UsageError(f"--until-time must not be negative, got {args.until_time}")
    if getattr(args, "symmetry", None) is not None:
        if getattr(args, "reduction", None) == "stubborn":
            raise UsageError("--symmetry and --reduction stubborn cannot be combined; choose one reduction")
        args.reduction = "symmetry"
    if getattr(args, "reduction", None) and (args.dot or args.graphml):
        how = "stubborn sets" if args.reduction == "stubborn" else "symmetry (one node per orbit)"
        raise UsageError("--dot and --graphml draw the state space and its SCC graph, which a graph reduced by "
                         f"{how} does not preserve; drop --reduction/--symmetry to draw the full graph")
    explore_outputs(args)  # before the model is even loaded: a long run must never be lost to a bad path
    if not os.path.exists(args.model):
        raise UsageError(f"no such model file: '{args.model}'")
    if getattr(args, "sweep_line", False) or getattr(args, "progress", None):
        from cpn.cli._sweep import run_sweep

        return run_sweep(args, sets)
    if getattr(args, "reduction", None) == "symmetry":
        from cpn.cli._common import load_model

        model = load_model(args.model, sets, state_space=True)
        args.symmetric_colour_sets = model.symmetry(getattr(args, "symmetry", None))
        engine = model.engine(time_condensation=args.time_condensation)
    else:
        engine = load_engine(args.model, sets, args.time_condensation)
    return explore_engine(engine, args, sets)


def _branching_options(engine, options, names: str | None, max_successors: int | None):
    """The options with the branching options of the command line (a UsageError for an unknown name)."""
    import dataclasses

    if names is None and max_successors is None:
        return options
    pred = text = None
    if names is not None:
        wanted = [n.strip() for n in names.split(",") if n.strip()]
        if not wanted:
            raise UsageError("--branch-transitions needs at least one transition name")
        chosen = set()
        for name in wanted:
            found = {i for i, t in enumerate(engine.transitions)
                     if t.name == name or t.name.rsplit(" ", 1)[0].split("'", 1)[-1] == name}
            if not found:
                raise UsageError(f"--branch-transitions: the model has no transition '{name}' (its transitions: "
                                 + ", ".join(t.name for t in engine.transitions) + ")")
            chosen |= found
        names_text = ", ".join(engine.transitions[i].name for i in sorted(chosen))
        text = f"only the binding elements of {names_text}"

        def pred(be, chosen=frozenset(chosen)):
            return engine.binding_element(be).transition in chosen
    return dataclasses.replace(options, branching_predicate=pred, branching_text=text,
                               max_successors=max_successors)


def explore_engine(engine, args, sets: dict[str, str] | None = None) -> int:
    """Explore, report and export for an already built engine (the part of `run` after loading)."""
    from cpn.report import build_report, render_text, to_json

    outputs = {o.option: o for o in explore_outputs(args)}
    quiet = bool(getattr(args, "quiet", False))
    options = _branching_options(engine, explore_options(args), getattr(args, "branch_transitions", None),
                                 getattr(args, "max_successors", None))
    if options.until_time is not None and not getattr(engine, "is_timed", False) and not quiet:
        print("note: the model is untimed (its clock is always 0): --until-time has no effect", file=sys.stderr)
    live = not quiet and sys.stderr.isatty()
    x = _search(engine, options, live)
    printed = set()
    if not quiet or options.backend == "c":
        for note in x.notes + (x.backend_notes if getattr(args, "verbose", False) else []):
            print(f"note: {note}", file=sys.stderr)
            printed.add(note)
    # --max-listed N: every text cap and the number of dead markings listed become N (0: no cap)
    max_listed = getattr(args, "max_listed", None)
    caps = {} if max_listed is None else {"max_listed": max_listed if max_listed > 0 else None}
    report_line = _ReportLine() if live else None
    try:
        report = build_report(x, model=os.path.abspath(args.model), options=_report_options(args, sets),
                              progress=report_line, **({} if max_listed is None else {"dead_listed": caps["max_listed"]}))
    finally:
        if report_line:
            report_line.close()
    if not any(o.to_stdout for o in outputs.values()):
        sys.stdout.write(render_text(report, marking_changes=bool(getattr(args, "trace_to_dead", False)), **caps))
    if "--json" in outputs:
        doc = to_json(report, graph=True, max_export_states=getattr(args, "max_export_states", None))
        if doc["graph"]["skipped"]:
            print(f"warning: --json: the graph is left out: {doc['graph']['note']}", file=sys.stderr)
        write_output(outputs["--json"], json.dumps(doc, indent=2, ensure_ascii=False) + "\n")
    _write_graphs(report, outputs, getattr(args, "max_export_states", None))
    _write_pictures(report, outputs, quiet)
    return _result_status(x, report, printed, bool(getattr(args, "max_memory_is_default", False)))


def _search(engine, options, live: bool):
    """The exploration, with a live progress line on stderr when `live`."""
    from cpn.errors import EvaluationError
    from cpn.statespace import Explorer

    display = ProgressLine() if live else None
    try:
        x = Explorer(engine, options, progress=display).run()
    except EvaluationError:
        if display:
            display.close()
        raise
    if display:
        display.close()
    return x


def _report_options(args, sets: dict[str, str] | None) -> dict:
    """The options of the command line that shaped the state space, as the report records them."""
    return {"set": sets or {}, "max_states": args.max_states, "max_arcs": args.max_arcs,
            "max_seconds": args.max_seconds, "max_memory_mb": args.max_memory,
            "max_memory_is_default": bool(getattr(args, "max_memory_is_default", False)),
            "time_condensation": bool(args.time_condensation),
            "until_time": getattr(args, "until_time", None),
            "branch_transitions": getattr(args, "branch_transitions", None),
            "max_successors": getattr(args, "max_successors", None),
            "reduction": getattr(args, "reduction", None),
            "symmetry": [str(s) for s in getattr(args, "symmetric_colour_sets", ()) or ()] or None}


def _write_graphs(report, outputs: dict, limit: int | None) -> None:
    """--dot and --graphml, each skipped with a warning when the state space is above the drawing limit."""
    from cpn.report.graphs import MAX_EXPORT_STATES, TooLargeToExport, render_dot, render_graphml

    n_states = report.exploration.n_states
    for option, render, kind in (("--dot", render_dot, "DOT"), ("--graphml", render_graphml, "GraphML")):
        if option not in outputs:
            continue
        try:
            text = render(report, limit)
        except TooLargeToExport:
            # a warning, so printed even with --quiet: the file asked for is not written
            shown = MAX_EXPORT_STATES if limit is None else limit
            print(f"warning: {option}: {kind} export skipped: the state space has {n_states:,} states, above "
                  f"the limit of {shown:,} for drawings; raise it with --max-export-states {n_states} (0: no "
                  "limit), or draw a partial state space with --max-states", file=sys.stderr)
            continue
        write_output(outputs[option], text)


def _result_status(x, report, printed: set, memory_default: bool) -> int:
    """OK for a complete state space; UNKNOWN, with a warning, for a partial or restricted one."""
    if not x.complete:
        # a warning about the result, so printed even with --quiet
        reason = x.stop_reason.describe(x.options)
        if x.stop_reason.value == "max_memory" and memory_default:
            reason += " (the default limit: raise it with --max-memory MB, or --max-memory 0 for none)"
        print(f"partial state space: stopped because {reason}; {x.unexpanded:,} "
              f"{noun(x.unexpanded, 'state was', 'states were')} not expanded", file=sys.stderr)
        for note in report.notes:
            if note not in printed:  # each note once: the search's were printed above
                print(f"note: {note}", file=sys.stderr)
        return ExitStatus.UNKNOWN
    if x.restricted:
        # a warning about the result, so printed even with --quiet
        print(f"restricted state space (branching options: {x.options.restriction()}): its figures are not "
              "those of the whole state space", file=sys.stderr)
        return ExitStatus.UNKNOWN
    return ExitStatus.OK


def _write_pictures(report, outputs: dict, quiet: bool) -> None:
    """--html (the report as a page) and --msc (the trace to the first dead marking as a chart)."""
    if "--html" in outputs:
        from cpn.report.html import render_html

        write_output(outputs["--html"], render_html(report))
    if "--msc" in outputs:
        from cpn.report.html import dead_marking_traces

        traces = dead_marking_traces(report, limit=1)
        if traces:
            write_output(outputs["--msc"], traces[0].svg(standalone=True) + "\n")
        elif not quiet:
            print("note: --msc: no chart written: there is no dead marking to trace", file=sys.stderr)


class _ReportLine:
    """A rich live line on stderr while the report is built (its part, fairness's transition instances),
    shown after one second, like the search's line."""

    def __init__(self):
        self._live = None
        self._t0 = time.perf_counter()
        self._shown = 0.0

    def __call__(self, part: str, done: int, total: int) -> None:
        seconds = time.perf_counter() - self._t0
        if seconds - self._shown < 0.2:
            return  # at most five updates a second: fairness reports every transition instance
        self._shown = seconds
        if self._live is None:
            if seconds < 1.0:
                return
            from rich.console import Console
            from rich.live import Live

            self._live = Live("", console=Console(stderr=True), transient=True, auto_refresh=False)
            self._live.start()
        step = f"  {done:,}/{total:,}" if total > 1 else ""
        self._live.update(f"[bold]report[/]  {part.replace('_', ' ')}{step}  {seconds:,.1f} s", refresh=True)

    def close(self) -> None:
        if self._live is not None:
            self._live.stop()
            self._live = None
