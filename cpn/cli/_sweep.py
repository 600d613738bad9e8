"""`cpn-verify explore MODEL --sweep-line [--progress EXPR]`: the sweep-line search and its report.

Exit statuses as `explore`: 0 complete, 2 partial; 64 an option the sweep-line method cannot honour or no
progress measure; 65 a bad model or a bad measure text.
"""

from __future__ import annotations

import json
import os
import sys

from cpn.cli._common import ExitStatus, UsageError, write_output
from cpn.cli._search_args import ProgressLine, explore_options, explore_outputs
from cpn.report.words import noun

# options of `explore` that need the whole graph, restrict it or partition it, and so do not combine with
# the sweep-line
_REFUSED = (("reduction", "--reduction"), ("until_time", "--until-time"), ("branch_transitions", "--branch-transitions"),
            ("max_successors", "--max-successors"), ("dot", "--dot"), ("graphml", "--graphml"), ("html", "--html"),
            ("msc", "--msc"), ("workers", "--workers"), ("ray", "--ray"))


def run_sweep(args, sets: dict) -> int:
    from cpn.checks.columns import TransitionIndex
    from cpn.cli._common import load_model
    from cpn.errors import ConfigurationError
    from cpn.gate.sweep import progress_measure
    from cpn.properties.predicates import PropertyLanguage
    from cpn.report.sweep import render_sweep_text, sweep_to_json
    from cpn.statespace.sweep import SweepLine

    for attr, option in _REFUSED:
        if getattr(args, attr, None):
            raise UsageError(f"{option} cannot be combined with --sweep-line: the sweep-line method explores every "
                             "successor in one process and keeps no graph; drop one of the two")
    outputs = {o.option: o for o in explore_outputs(args)}
    quiet = bool(getattr(args, "quiet", False))
    model = load_model(args.model, sets, state_space=True)
    engine = model.engine(time_condensation=args.time_condensation)
    measure = None
    if args.progress:
        lang = PropertyLanguage(model.net, engine, TransitionIndex(engine))
        measure = progress_measure(lang, args.progress)
    display = ProgressLine() if (not quiet and sys.stderr.isatty()) else None
    try:
        try:
            x = SweepLine(engine, explore_options(args), measure, args.progress, progress=display).run()
        except ConfigurationError as err:
            raise UsageError(err.render().removeprefix("error: ")) from None
    finally:
        if display:
            display.close()
    path = os.path.abspath(args.model)
    max_listed = getattr(args, "max_listed", None)
    if not any(o.to_stdout for o in outputs.values()):
        cap = 10 if max_listed is None else (max_listed or None)
        sys.stdout.write(render_sweep_text(x, path, cap))
    if "--json" in outputs:
        opts = {"set": sets or {}, "max_states": args.max_states, "max_arcs": args.max_arcs,
                "max_seconds": args.max_seconds, "max_memory_mb": args.max_memory,
                "time_condensation": bool(args.time_condensation), "sweep_line": True, "progress": args.progress}
        write_output(outputs["--json"], json.dumps(sweep_to_json(x, path, opts), indent=2, ensure_ascii=False) + "\n")
    if not quiet:
        for note in x.notes:
            print(f"note: {note}", file=sys.stderr)
    if not x.complete:
        print(f"partial state space: stopped because {x.stop_reason.describe(x.options)}; {x.unexpanded:,} "
              f"{noun(x.unexpanded, 'state was', 'states were')} not expanded", file=sys.stderr)
        return ExitStatus.UNKNOWN
    return ExitStatus.OK
