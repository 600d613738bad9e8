"""`cpn-verify simulate MODEL`: fire random (seeded) binding elements and print the trace."""

from __future__ import annotations

import argparse
import random
import sys

from cpn.cli.explore import parse_sets


def add_parser(subparsers) -> argparse.ArgumentParser:
    p = subparsers.add_parser("simulate", help="fire random enabled binding elements and print the trace",
                              description="Starting from the initial marking, repeatedly choose one enabled "
                              "binding element at random (reproducibly, with --seed) and fire it; print step, "
                              "model time, transition instance and binding.")
    p.add_argument("model", metavar="MODEL", help="model file (.cpnet, .pnml or .cpn)")
    p.add_argument("--steps", type=int, default=20, metavar="N", help="at most N steps (default 20)")
    p.add_argument("--seed", type=int, default=0, metavar="S", help="random seed (default 0)")
    p.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                   help="override a 'val' constant of the model (may be repeated)")
    p.add_argument("--show-marking", action="store_true", help="print the final marking")
    return p


def run(args) -> int:
    import cpn
    from cpn.errors import ConfigurationError, EvaluationError, ModelError

    if args.steps < 0:
        print("error: --steps must not be negative", file=sys.stderr)
        return 64
    try:
        sets = parse_sets(args.set)
        model = cpn.load(args.model, set=sets)
    except ValueError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 64
    except ModelError as err:
        print(err.render(), file=sys.stderr)
        return 65
    except ConfigurationError as err:
        print(err.render(), file=sys.stderr)
        return 64
    engine = model.engine()
    rng = random.Random(args.seed)
    s = engine.initial_state()
    trace = []
    width = len(str(args.steps))
    print(f"{'step':>{max(width, 4)}}  {'time':>6}  binding element")
    step = 0
    try:
        while step < args.steps:
            succ = engine.successors(s)
            if not succ:
                print(f"dead marking after {step} steps: no binding element is enabled")
                break
            be, s = succ[rng.randrange(len(succ))]
            step += 1
            trace.append(engine.format_binding_element(be))
            print(f"{step:>{max(width, 4)}}  {engine.clock(s):>6}  {trace[-1]}")
        else:
            print(f"stopped after {step} steps (--steps {args.steps})")
    except EvaluationError as err:
        err.trace = trace
        print(err.render(), file=sys.stderr)
        return 65
    if args.show_marking:
        print()
        for p in engine.places:
            text = engine.format_marking(s, p.index)
            if text != "empty":
                print(f"{p.name}: {text}")
    return 0
