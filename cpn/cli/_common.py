"""What every subcommand shares: the exit statuses, the common options (`--set`, limits, outputs,
`--quiet`), checking output paths before any work, and turning errors into exit statuses in one place.

Imports `cpn.errors`, `cpn.statespace.options` and the standard library.
"""

from __future__ import annotations

import argparse
import enum
import os
import sys
from dataclasses import dataclass

from cpn._util.resources import ResourceMissing

STDOUT = "-"


class ExitStatus(enum.IntEnum):
    """The exit statuses of `cpn-verify` (sysexits numbers where they exist)."""

    OK = 0  # done; every property holds on a complete state space; lint: no error
    VIOLATED = 1  # a property is violated (`cpn-verify check`)
    UNKNOWN = 2  # a limit stopped the search before anything was violated
    USAGE = 64  # EX_USAGE: bad options, a missing input file
    DATAERR = 65  # EX_DATAERR: a bad model or scenario file, an error while evaluating the model
    SOFTWARE = 70  # EX_SOFTWARE: a bug in cpn-verify
    CANTCREAT = 73  # EX_CANTCREAT: an output file cannot be written
    INTERRUPTED = 130  # 128 + SIGINT: interrupted outside a search (a search reports a partial result)

    @staticmethod
    def worst(statuses) -> ExitStatus:
        """The most serious of several statuses (for one command over several files)."""
        return max((ExitStatus(s) for s in statuses), key=_SEVERITY.index, default=ExitStatus.OK)


# from least to most serious: a definite violation outranks an unknown result, a file that could not
# be read or written outranks a bad model, and a bug outranks everything
_SEVERITY = [ExitStatus.OK, ExitStatus.UNKNOWN, ExitStatus.VIOLATED, ExitStatus.DATAERR, ExitStatus.USAGE,
             ExitStatus.CANTCREAT, ExitStatus.INTERRUPTED, ExitStatus.SOFTWARE]

EPILOG = """exit statuses:
  0   done: every property holds on a complete state space (lint: no error)
  1   a property is violated (only 'cpn-verify check' verifies properties)
  2   unknown: a limit stopped the search first (a partial report is printed), or branching
      options restricted the state space
  64  bad usage, or a model file that does not exist
  65  bad model or scenario file, or an error while evaluating the model
  70  internal error (a bug in cpn-verify: please report it)
  73  an output file cannot be created (checked before any work starts)
  130 interrupted (Ctrl-C during a search instead ends it with a partial report and status 2)

outputs: every option that names an output file takes '-' for standard output; at most one output may
go to standard output, and it then replaces the text report. A reader that stops early
('cpn-verify check | head') never changes the exit status: the command finishes its work.
"""


class UsageError(Exception):
    """Bad options: exit 64."""

    status = ExitStatus.USAGE


class CannotCreate(Exception):
    """An output file cannot be written: exit 73."""

    status = ExitStatus.CANTCREAT


# ---------------------------------------------------------------------- options

QUIET_HELP = ("print only results, warnings and errors: no progress line, no notes, no confirmations "
              "('ok', 'wrote FILE')")


def add_quiet_option(p: argparse.ArgumentParser) -> None:
    p.add_argument("-q", "--quiet", action="store_true", help=QUIET_HELP)


def add_set_option(p: argparse.ArgumentParser) -> None:
    p.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                   help="override a 'val' constant of the model (may be repeated)")


def add_output_option(p: argparse.ArgumentParser, flag: str, what: str, *names: str) -> None:
    p.add_argument(*names, flag, metavar="FILE", help=f"write {what} to FILE ('-': standard output)")


def add_limit_options(p: argparse.ArgumentParser, default_seconds: float | None = None) -> None:
    """--max-states, --max-arcs, --max-seconds, --max-memory. With `default_seconds` (`check`), a search
    whose scenario sets no time limit stops after that many seconds, and `--max-seconds 0` means none."""
    from cpn.statespace.options import DEFAULT_MEMORY_SHARE, default_max_memory_mb

    default = default_max_memory_mb()
    p.add_argument("--max-states", type=int, metavar="N", help="stop after N states")
    p.add_argument("--max-arcs", type=int, metavar="N", help="stop after N arcs")
    if default_seconds is None:
        p.add_argument("--max-seconds", type=float, metavar="S", help="stop after S seconds of generation")
    else:
        p.add_argument("--max-seconds", type=float, metavar="S",
                       help=f"stop each search after S seconds of generation (default {default_seconds:g}, for "
                       "the runs whose scenario sets no max_seconds, so that an unbounded model ends with a "
                       "partial report; 0: no time limit)")
        p.set_defaults(max_seconds_default=default_seconds)
    p.add_argument("--max-memory", type=float, metavar="MB",
                   help="stop when the process uses MB MiB of resident memory (default "
                   f"{_mib(default)}: {DEFAULT_MEMORY_SHARE * 100:.0f}%% of the memory of this machine or of its "
                   "container limit, so that an unbounded model ends with a partial report; 0: no limit)")


def add_parallel_options(p: argparse.ArgumentParser) -> None:
    """--workers N and --ray [ADDRESS]: the partitioned search (cpn.statespace.parallel, .distributed)."""
    p.add_argument("--workers", type=int, metavar="N", default=None,
                   help="search with N threads of this process where every transition is in generated C "
                   "(else N processes), each owning a part of the states (untimed nets; the same state space "
                   "and report as one process; timed nets, reductions and branching options are searched "
                   "in one process, with a note)")
    p.add_argument("--ray", nargs="?", const="local", default=None, metavar="ADDRESS",
                   help="run the workers of the partitioned search on a Ray cluster: ADDRESS of its head "
                   "(host:port), 'auto' for the cluster started on this machine with 'ray start --head', "
                   "nothing for a local Ray instance started for this command (needs: pip install "
                   "'cpn-verify[ray]'); --workers defaults to the cluster's CPUs")


def check_parallel(args) -> None:
    """--workers must be positive; --ray needs Ray installed (a UsageError with the install hint)."""
    workers = getattr(args, "workers", None)
    if workers is not None and workers < 1:
        raise UsageError(f"--workers must be at least 1, got {workers}")
    if getattr(args, "ray", None) is not None:
        from cpn.statespace.distributed import ray_unavailable

        why = ray_unavailable()
        if why is not None:
            raise UsageError(f"--ray: {why}\nhint: pip install 'cpn-verify[ray]' (or run without --ray: "
                             "--workers N uses the processes of this machine)")


def _mib(mb: float | None) -> str:
    return "none" if mb is None else f"{mb:,.0f}"


def check_limits(args) -> None:
    """Limits must be positive. Without --max-memory the default applies (`args.max_memory_is_default`
    says so); `--max-memory 0` means no memory limit, and so does `--max-seconds 0` where the command has
    a default time limit (`add_limit_options(default_seconds=...)`)."""
    from cpn.statespace.options import default_max_memory_mb

    may_be_zero = {"max_memory"} | ({"max_seconds"} if getattr(args, "max_seconds_default", None) else set())
    for name in ("max_states", "max_arcs", "max_seconds", "max_memory"):
        v = getattr(args, name, None)
        if v is None or (name in may_be_zero and v == 0):
            continue
        if v <= 0:
            raise UsageError(f"--{name.replace('_', '-')} must be positive, got {v:g}")
    if hasattr(args, "max_memory"):
        args.max_memory_is_default = args.max_memory is None
        if args.max_memory is None:
            args.max_memory = default_max_memory_mb()
        elif args.max_memory == 0:
            args.max_memory = None


def parse_sets(items: list[str]) -> dict[str, str]:
    """`--set NAME=VALUE` items as a dict; raises ValueError for an item without '='."""
    out = {}
    for item in items:
        name, eq, value = item.partition("=")
        if not eq or not name.strip():
            raise ValueError(f"--set expects NAME=VALUE, got '{item}'")
        out[name.strip()] = value.strip()
    return out


def sets_of(args) -> dict[str, str]:
    try:
        return parse_sets(getattr(args, "set", []) or [])
    except ValueError as exc:
        raise UsageError(str(exc)) from None


# ---------------------------------------------------------------------- outputs


@dataclass(frozen=True)
class Output:
    option: str  # '--json', '-o', ...
    path: str  # a file name, or '-' for standard output

    @property
    def to_stdout(self) -> bool:
        return self.path == STDOUT


def prepare_outputs(*pairs: tuple[str, str | None]) -> list[Output]:
    """Check every output (option, path) before any work: at most one '-', every file writable.

    Raises UsageError (two outputs to standard output) or CannotCreate (a file that cannot be written:
    its folder is missing, it is a folder, or the system refuses to create it).
    """
    outputs = [Output(opt, path) for opt, path in pairs if path]
    to_stdout = [o.option for o in outputs if o.to_stdout]
    if len(to_stdout) > 1:
        raise UsageError(f"only one output can go to standard output, but {' and '.join(to_stdout)} both "
                         "name '-'")
    for o in outputs:
        if not o.to_stdout:
            check_writable(o.path, o.option)
    return outputs


def check_writable(path: str, option: str) -> None:
    """Raise CannotCreate unless `path` can be opened for writing; a file it creates is removed again."""
    if os.path.isdir(path):
        raise CannotCreate(f"cannot write {option} {path}: it is a folder; name a file inside it")
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise CannotCreate(f"cannot write {option} {path}: the folder {folder} does not exist")
    existed = os.path.exists(path)
    try:
        with open(path, "a", encoding="utf-8"):
            pass
    except OSError as exc:
        raise CannotCreate(f"cannot write {option} {path}: {exc.strerror or exc}") from None
    if not existed:
        try:
            os.remove(path)
        except OSError:
            pass


def write_output(output: Output, text: str) -> None:
    """Write `text` to the output (standard output for '-'); raises CannotCreate."""
    if output.to_stdout:
        sys.stdout.write(text)
        sys.stdout.flush()
        return
    try:
        with open(output.path, "w", encoding="utf-8") as fh:
            fh.write(text)
    except OSError as exc:
        raise CannotCreate(f"cannot write {output.option} {output.path}: {exc.strerror or exc}") from None


# ---------------------------------------------------------------------- errors to exit statuses


def exit_status_of(exc: BaseException) -> ExitStatus:
    """The exit status for an exception that ends a subcommand (the one mapping of the command line)."""
    from cpn.errors import CpnError

    if isinstance(exc, (UsageError, CannotCreate)):
        return exc.status
    if isinstance(exc, CpnError):
        return ExitStatus(exc.exit_status)
    if isinstance(exc, KeyboardInterrupt):
        return ExitStatus.INTERRUPTED
    # a BrokenPipeError of standard output never gets here (cpn.cli.main guards both streams): any other
    # is an error like every other one, never a success
    return ExitStatus.SOFTWARE


def render_error(exc: BaseException) -> str:
    """What the user reads for an exception that ends a subcommand (never a traceback but for bugs)."""
    from cpn.errors import CpnError

    if isinstance(exc, (UsageError, CannotCreate)):
        return f"error: {exc}"
    if isinstance(exc, CpnError):
        return exc.render()
    if isinstance(exc, KeyboardInterrupt):
        return "interrupted"
    if isinstance(exc, ResourceMissing):  # an incomplete installation (status 70): no bug to trace
        return f"error: {exc}"
    return "error: internal error in cpn-verify (this is a bug, please report it with the model)"



# ---------------------------------------------------------------------- models


def model_warnings(model) -> list:
    """The model's warnings, plus one for a model without any place or transition (an empty file, or
    one holding only comments or declarations, is almost always the wrong file)."""
    from cpn.diagnostics import Diagnostic, Severity, Span

    warnings = list(model.warnings)
    net = model.net
    if not net.places and not net.transitions:
        warnings.insert(0, Diagnostic(
            "W0103", "the model declares no place and no transition" + (
                "; the file is empty" if not model.source.strip() else ""),
            Span(model.path, 1, 1), hint="Check that this is the intended file; a net needs at least one place.",
            severity=Severity.WARNING))
    return warnings


def load_model(path: str, sets: dict[str, str], *, show_warnings: bool = True, state_space: bool = False):
    """`cpn.load` for the command line: its warnings go to stderr (never silenced by --quiet). With
    `state_space` (explore), the warnings that a random draw or another construct is for simulation only
    (W0105, W0106) are left out: building the engine refuses each with an error at the same place (E0206)."""
    import cpn
    from cpn.diagnostics import render

    model = cpn.load(path, set=sets)
    if show_warnings:
        for w in model_warnings(model):
            if not (state_space and w.code in ("W0105", "W0106")):
                print(render(w, model.text_of(w.span)), file=sys.stderr)
    return model
