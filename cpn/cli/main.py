"""The `cpn-verify` command line: argument parsing, subcommands and exit statuses.

The only module that reads argv and calls sys.exit. Each subcommand lives in its own module
`cpn.cli.<name>` with `add_parser(subparsers)` and `run(args) -> int`; what they share (options, output
checks, the exit statuses and the mapping of errors to them) is in `cpn.cli._common`.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys

from cpn._util.resources import ResourceMissing
from cpn.cli._common import EPILOG, ExitStatus, exit_status_of, render_error

SUBCOMMANDS = ["lint", "simulate", "explore", "check", "mutate", "convert", "validate", "mcc"]


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="cpn-verify",
        description="Verify protocol designs with timed, hierarchical Coloured Petri Nets.",
        epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    from cpn import __version__

    parser.add_argument("--version", action="version", version=f"cpn-verify {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name in SUBCOMMANDS:
        try:
            module = importlib.import_module(f"cpn.cli.{name}")
        except ModuleNotFoundError as exc:
            if exc.name == f"cpn.cli.{name}":
                continue
            raise
        p = module.add_parser(sub)
        if p.epilog is None:
            p.epilog = EPILOG
            p.formatter_class = argparse.RawDescriptionHelpFormatter
        p.set_defaults(_run=module.run, _parser=p)
    return parser


class _ReaderGone:
    """A text stream that goes on silently once the program reading it has gone.

    `cpn-verify check DIR | head -n 3` closes the pipe early; writing to it raises BrokenPipeError.
    The command must still finish its work and exit with its verdict's status (a violation is never
    turned into success), so from then on the stream's output is thrown away: its file descriptor is
    pointed at the null device, which also lets the interpreter flush it at exit without an error.
    """

    def __init__(self, stream):
        self._stream = stream
        self.gone = False

    def write(self, text: str) -> int:
        if not self.gone:
            try:
                return self._stream.write(text)
            except BrokenPipeError:
                self._lost()
        return len(text)

    def flush(self) -> None:
        if not self.gone:
            try:
                self._stream.flush()
            except BrokenPipeError:
                self._lost()

    def _lost(self) -> None:
        self.gone = True
        try:
            null = os.open(os.devnull, os.O_WRONLY)
            try:
                os.dup2(null, self._stream.fileno())
            finally:
                os.close(null)
        except (OSError, ValueError, AttributeError):  # no descriptor (a stream in memory): nothing to flush
            pass

    def __getattr__(self, name):
        return getattr(self._stream, name)


def main(argv: list[str] | None = None) -> int:
    """Run the command line; returns the exit status. Standard output and error are guarded: a reader
    that goes away early never changes the status (`_ReaderGone`)."""
    saved = sys.stdout, sys.stderr
    if sys.stdout is not None:
        sys.stdout = _ReaderGone(sys.stdout)
    if sys.stderr is not None:
        sys.stderr = _ReaderGone(sys.stderr)
    try:
        return _main(argv)
    finally:
        for guard in (sys.stdout, sys.stderr):
            if isinstance(guard, _ReaderGone):
                guard.flush()
        sys.stdout, sys.stderr = saved


def _main(argv: list[str] | None) -> int:
    parser = build_parser()
    try:
        args, extra = parser.parse_known_args(argv)
        if extra:
            # an unknown flag after a subcommand: that subcommand's usage, not the top level's
            (getattr(args, "_parser", None) or parser).error(f"unrecognized arguments: {' '.join(extra)}")
    except SystemExit as exc:  # argparse exits 2 on bad usage; our contract says 64
        code = exc.code if isinstance(exc.code, int) else ExitStatus.USAGE
        return int(ExitStatus.USAGE if code == 2 else code)
    if not getattr(args, "_run", None):
        parser.print_help(sys.stderr)
        return int(ExitStatus.USAGE)
    try:
        return int(args._run(args))
    except (Exception, KeyboardInterrupt) as exc:  # noqa: BLE001 - the last line of defence
        status = exit_status_of(exc)
        if status is ExitStatus.SOFTWARE and not isinstance(exc, ResourceMissing):
            import traceback

            traceback.print_exc()
        print(render_error(exc), file=sys.stderr)
        return int(status)


#: the garbage collector's thresholds for the command line (Python's are 700, 10, 10): a search allocates
#: millions of objects that live as long as its graph, and with the default thresholds the collector walked
#: them again and again (docs/performance.md, "The garbage collector")
GC_THRESHOLDS = (20_000, 20, 10)


def entry() -> None:
    import gc

    gc.set_threshold(*GC_THRESHOLDS)
    sys.exit(main())
