"""`cpn-verify lint MODEL...`: check every model and print every diagnostic.

Every file is checked, even after one that is missing or bad; the exit status is the worst of them:
0 every model is clean (warnings allowed), 65 some model has errors, 64 some file does not exist (or a
bad option), 73 the --json file cannot be written.
"""

from __future__ import annotations

import argparse
import json
import sys

from cpn.cli._common import (
    ExitStatus,
    add_output_option,
    add_quiet_option,
    add_set_option,
    exit_status_of,
    model_warnings,
    prepare_outputs,
    render_error,
    sets_of,
    write_output,
)
from cpn.report.words import noun


def add_parser(subparsers) -> argparse.ArgumentParser:
    p = subparsers.add_parser("lint", help="check models and report every error",
                              description="Parse, resolve and type-check each MODEL and flatten its modules; "
                              "print every error and warning with its position, the source line and a hint. "
                              "Every file is checked; the exit status is the worst one.")
    p.add_argument("models", nargs="+", metavar="MODEL", help="model files (.cpnet, .pnml, .cpn)")
    add_set_option(p)
    add_output_option(p, "--json", "one entry per model (status, counts, diagnostics)")
    add_quiet_option(p)
    return p


def _diagnostic_json(d) -> dict:
    s = d.span
    return {"code": d.code, "severity": d.severity.value, "message": d.message,
            "file": s.file if s else None, "line": s.line if s else None, "col": s.col if s else None,
            "hint": d.hint, "notes": list(d.notes)}


def lint_file(path: str, sets: dict[str, str]) -> tuple[dict, str]:
    """(the JSON entry, the text for stderr) of one model file."""
    import cpn
    from cpn.diagnostics import render
    from cpn.errors import ModelError

    entry: dict = {"path": path, "status": "ok", "exit_status": 0, "diagnostics": []}
    try:
        model = cpn.load(path, set=sets)
    except ModelError as err:
        entry.update(status="error", exit_status=int(ExitStatus.DATAERR),
                     diagnostics=[_diagnostic_json(d) for d in err.diagnostics])
        return entry, err.render()
    except Exception as exc:  # noqa: BLE001 - one unreadable file must not stop the others
        status = exit_status_of(exc)
        if status is ExitStatus.SOFTWARE:
            raise
        entry.update(status="unreadable", exit_status=int(status), message=str(exc))
        return entry, render_error(exc)
    warnings = model_warnings(model)
    net = model.net
    # a model that draws random values (or has real delays, references, side effects) is valid and simulated;
    # explore and check refuse it (W0105, W0106 say where)
    entry.update(places=len(net.places), transitions=len(net.transitions), timed=bool(net.is_timed),
                 simulation_only=bool(getattr(net.checked, "random_draws", ())
                                      or getattr(net.checked, "simulation_only", ())),
                 diagnostics=[_diagnostic_json(w) for w in warnings])
    return entry, "\n".join(render(w, model.text_of(w.span)) for w in warnings)


def run(args) -> int:
    sets = sets_of(args)
    outputs = {o.option: o for o in prepare_outputs(("--json", args.json))}
    json_to_stdout = "--json" in outputs and outputs["--json"].to_stdout
    entries = []
    for path in args.models:
        entry, messages = lint_file(path, sets)
        entries.append(entry)
        if messages:
            print(messages, file=sys.stderr)
        if entry["status"] == "ok" and not args.quiet and not json_to_stdout:
            np, nt = entry["places"], entry["transitions"]
            print(f"{path}: ok ({np} {noun(np, 'place instance')}, {nt} {noun(nt, 'transition instance')}"
                  f"{', timed' if entry['timed'] else ''}"
                  f"{'; simulate only: explore and check cannot analyse it' if entry['simulation_only'] else ''})")
    status = ExitStatus.worst(e["exit_status"] for e in entries)
    if "--json" in outputs:
        write_output(outputs["--json"], json.dumps({"exit_status": int(status), "models": entries}, indent=2,
                                                   ensure_ascii=False) + "\n")
    return status
