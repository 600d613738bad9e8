"""`cpn-verify lint MODEL...`: check models and print every diagnostic; exit 0 (clean) or 65."""

from __future__ import annotations

import argparse
import sys

from cpn.cli.explore import parse_sets


def add_parser(subparsers) -> argparse.ArgumentParser:
    p = subparsers.add_parser("lint", help="check a model and report every error",
                              description="Parse, resolve and type-check MODEL and flatten its modules; print "
                              "every error with its position, the source line and a hint.")
    p.add_argument("models", nargs="+", metavar="MODEL", help="model files (.cpnet, .pnml, .cpn)")
    p.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                   help="override a 'val' constant of the model (may be repeated)")
    p.add_argument("--quiet", action="store_true", help="print nothing for clean models")
    return p


def run(args) -> int:
    import cpn
    from cpn.diagnostics import render
    from cpn.errors import ConfigurationError, ModelError

    try:
        sets = parse_sets(args.set)
    except ValueError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 64
    status = 0
    for path in args.models:
        try:
            model = cpn.load(path, set=sets)
        except ModelError as err:
            print(err.render(), file=sys.stderr)
            status = 65
            continue
        except ConfigurationError as err:
            print(err.render(), file=sys.stderr)
            return 64
        for w in model.warnings:
            print(render(w, model.source), file=sys.stderr)
        if not args.quiet:
            net = model.net
            print(f"{path}: ok ({len(net.places)} place instances, {len(net.transitions)} transition instances"
                  f"{', timed' if net.is_timed else ''})")
    return status
