"""The `cpn-verify` command line: argument parsing, subcommands and exit statuses.

The only module that reads argv, writes to stdout/stderr for the user, or calls sys.exit.
Each subcommand lives in its own module `cpn.cli.<name>` with `add_parser(subparsers)` and
`run(args) -> int`.
"""

from __future__ import annotations

import argparse
import importlib
import sys

EXIT_OK = 0
EXIT_VIOLATED = 1
EXIT_UNKNOWN = 2
EXIT_USAGE = 64
EXIT_DATAERR = 65
EXIT_SOFTWARE = 70

EPILOG = """exit statuses:
  0   every property holds on a complete state space (lint: no errors)
  1   a property is violated
  2   unknown: a limit stopped the search first
  64  bad usage
  65  bad model or scenario file
  70  internal error (a bug in cpn-verify: please report it)
"""

SUBCOMMANDS = ["lint", "simulate", "explore", "convert", "validate"]


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
        p.set_defaults(_run=module.run)
    return parser


class _UsageError(Exception):
    pass


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # argparse exits 2 on bad usage; our contract says 64
        code = exc.code if isinstance(exc.code, int) else EXIT_USAGE
        return EXIT_USAGE if code == 2 else code
    if not getattr(args, "_run", None):
        parser.print_help(sys.stderr)
        return EXIT_USAGE
    try:
        return int(args._run(args))
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return EXIT_OK
    except Exception as exc:  # noqa: BLE001 - the last line of defence: no traceback for users
        from cpn.errors import CpnError

        if isinstance(exc, CpnError):
            print(exc.render(), file=sys.stderr)
            return exc.exit_status
        import traceback

        traceback.print_exc()
        print(
            "error: internal error in cpn-verify (this is a bug, please report it with the model)",
            file=sys.stderr,
        )
        return EXIT_SOFTWARE


def entry() -> None:
    sys.exit(main())
