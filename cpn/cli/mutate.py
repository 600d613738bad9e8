"""`cpn-verify mutate SCENARIO|DIR...`: how strong is the gate? Mutation testing of the models the scenarios
check (`cpn.gate.mutation`), with the score, what each property catches and every surviving mutant.

Exit statuses: 0 done (and the score is at least --fail-under); 1 the score is below --fail-under, or the
original model violates a property; 2 the time budget left mutants unrun, or the original's search was
stopped by a limit; 64 bad usage; 65 bad model or scenario file; 73 an output cannot be written.
"""

from __future__ import annotations

import argparse
import json
import sys

from cpn.cli._common import (
    ExitStatus,
    UsageError,
    add_output_option,
    add_quiet_option,
    add_set_option,
    prepare_outputs,
    sets_of,
    write_output,
)
from cpn.cli._scenarios import load_scenarios, scenario_paths

DESCRIPTION = """Generate mutants of the model each scenario checks (a guard negated, weakened or
strengthened, a comparison off by one, an arc removed, a constant or a delay changed, a token dropped
or duplicated, the branches of an 'if' exchanged, a priority changed; docs/mutation.md), run every
scenario that checks the model on each mutant, and report the mutation score (killed / (killed +
survived)), which property caught each mutant with its trace length, and every surviving mutant as a
diff of the model text with its position: behaviour no property constrains. Mutants that do not load,
that leave the labelled state space unchanged (equivalent) or whose search a limit stopped
(undecided) are counted apart."""

EPILOG = """exit statuses:
  0   done, and the score is at least --fail-under
  1   the score is below --fail-under, or the original model already violates a property
  2   the time budget (--max-seconds) left mutants unrun, or a limit stopped the original's search
  64  bad usage
  65  bad model or scenario file
  70  internal error (a bug in cpn-verify: please report it)
  73  an output file cannot be created (checked before any work starts)
"""


def add_parser(subparsers) -> argparse.ArgumentParser:
    p = subparsers.add_parser("mutate", help="mutation testing: how strong are the properties of the scenarios?",
                              description=DESCRIPTION, epilog=EPILOG,
                              formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("paths", nargs="+", metavar="SCENARIO|DIR", help="scenario files or folders of them")
    p.add_argument("--seed", type=int, default=0, metavar="N",
                   help="the seed that draws the sample of --max-mutants (default 0): the same seed, the same mutants")
    p.add_argument("--max-mutants", type=int, metavar="N", help="run at most N mutants of each model, drawn with --seed")
    p.add_argument("--max-seconds", type=float, metavar="S",
                   help="start no mutant after S seconds (those left are reported as not run, status 2)")
    p.add_argument("--max-states", type=int, metavar="N",
                   help="stop each mutant's search after N states (default: 10 times the original's states "
                   "plus 1,000); a mutant stopped before any property fails is undecided")
    p.add_argument("--workers", type=int, default=1, metavar="N", help="run N mutants at a time, in N processes")
    p.add_argument("--all-runs", action="store_true",
                   help="run a killed mutant through every run of its gate too (slower), so that every property "
                   "that catches it is counted, not only those of the first run that does")
    p.add_argument("--fail-under", type=float, metavar="PERCENT",
                   help="exit with status 1 if the mutation score is below PERCENT")
    add_output_option(p, "--json", "the JSON report")
    add_output_option(p, "--markdown", "the Markdown report")
    add_output_option(p, "--html", "the report as an HTML page")
    add_set_option(p)
    p.add_argument("--no-timings", action="store_true", help="leave run times out of the output and reports")
    p.add_argument("-v", "--verbose", action="store_true", help="list the killed mutants too, with what caught them")
    add_quiet_option(p)
    return p


def run(args) -> int:
    from cpn.errors import ConfigurationError, EvaluationError, ModelError
    from cpn.gate.mutation import mutate
    from cpn.report.mutation import mutation_document

    _check_options(args)
    sets = sets_of(args)
    outputs = prepare_outputs(("--json", args.json), ("--markdown", args.markdown), ("--html", args.html))
    scenarios, bad = load_scenarios(scenario_paths(args.paths), sets, unique=False)
    progress = _Progress() if (not args.quiet and sys.stderr.isatty()) else None
    try:
        report = mutate(scenarios, seed=args.seed, max_mutants=args.max_mutants, max_seconds=args.max_seconds,
                        workers=args.workers, mutant_max_states=args.max_states, all_runs=args.all_runs,
                        overrides=_original_limits(sets), on_outcome=progress)
    except (ModelError, EvaluationError) as err:
        print(err.render(), file=sys.stderr)
        return ExitStatus.DATAERR
    except ConfigurationError as err:
        print(err.render(), file=sys.stderr)
        return ExitStatus.USAGE if getattr(err, "code", None) == "E0305" else ExitStatus.DATAERR
    finally:
        if progress is not None:
            progress.close()
    _write_documents(mutation_document(report, timings=not args.no_timings), outputs, args)
    return _status(report, bad, args.fail_under)


def _write_documents(doc: dict, outputs: list, args) -> None:
    """The text on standard output (unless an output file takes it), then the --json, --markdown and
    --html files."""
    from cpn.report.mutation import render_html, render_markdown, render_text

    renders = {"--json": lambda: json.dumps(doc, indent=2, ensure_ascii=False) + "\n",
               "--markdown": lambda: render_markdown(doc), "--html": lambda: render_html(doc)}
    if not any(o.to_stdout for o in outputs):
        sys.stdout.write(render_text(doc, verbose=args.verbose))
    for o in outputs:
        write_output(o, renders[o.option]())
        if not o.to_stdout and not args.quiet:
            print(f"wrote {o.path}", file=sys.stderr)


def _status(report, bad: int, fail_under: float | None) -> int:
    """The exit status: refused files, the original models' problems, mutants not run, --fail-under."""
    found = [ExitStatus.DATAERR if bad else ExitStatus.OK]
    for m in report.models:
        if m.problem is not None:
            print(f"{m.model}: {m.problem}", file=sys.stderr)
            found.append({"violated": ExitStatus.VIOLATED, "unknown": ExitStatus.UNKNOWN}.get(m.problem_status,
                                                                                              ExitStatus.DATAERR))
    if report.not_run:
        found.append(ExitStatus.UNKNOWN)
    if fail_under is not None:
        score = report.score
        if score is None:
            print("no mutant was decided (killed or survived): there is no score to compare with --fail-under",
                  file=sys.stderr)
            found.append(ExitStatus.UNKNOWN)
        elif score < fail_under:
            print(f"the mutation score {score:.1f}% is below --fail-under {fail_under:g}%", file=sys.stderr)
            found.append(ExitStatus.VIOLATED)
    return ExitStatus.worst(found)


def _original_limits(sets: dict) -> dict:
    """The original model's runs are limited as `cpn-verify check` limits them where the scenario sets no
    limit (a time limit, and the memory default), so that an unbounded model ends."""
    from cpn.cli.check import DEFAULT_MAX_SECONDS
    from cpn.statespace.options import default_max_memory_mb

    return {"set": sets or None, "default_max_seconds": DEFAULT_MAX_SECONDS,
            "default_max_memory_mb": default_max_memory_mb()}


def _check_options(args) -> None:
    if args.workers < 1:
        raise UsageError(f"--workers must be at least 1, got {args.workers}")
    for name in ("max_mutants", "max_seconds", "max_states"):
        v = getattr(args, name)
        if v is not None and v <= 0:
            raise UsageError(f"--{name.replace('_', '-')} must be positive, got {v:g}")
    if args.fail_under is not None and not 0 <= args.fail_under <= 100:
        raise UsageError(f"--fail-under is a percentage between 0 and 100, got {args.fail_under:g}")


class _Progress:
    """One line on the terminal: how many mutants of the model are decided, and the last outcome."""

    def __init__(self):
        self.shown = False

    def __call__(self, model, outcome) -> None:
        done = len(model.outcomes)
        line = f"{model.model}: mutant {done}/{model.selected} ({outcome.mutant.ident} {outcome.outcome})"
        sys.stderr.write("\r" + line[:119].ljust(119))
        sys.stderr.flush()
        self.shown = True

    def close(self) -> None:
        if self.shown:
            sys.stderr.write("\r" + " " * 119 + "\r")
            sys.stderr.flush()
