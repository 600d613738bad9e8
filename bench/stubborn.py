"""Cross-check and measure stubborn sets against the full state space on every model of a directory.

    python bench/stubborn.py [../shared/validation models bench/nets ...] [--max-states N] [--max-seconds S]
                             [--set NAME=VALUE ...]

For each model (`.cpnet`, `.pnml`, `.cpn`, found recursively): the full graph, the reduced graph for
deadlocks and the reduced graph with the visibility condition on one place, each bounded by the limits.
When the full graph is complete, the set of dead markings (canonical markings) of both reduced graphs must
equal the full graph's and the markings of the visible place reached must be the same; a row says
`same` or `DIFFERENT`. States and seconds of each graph are printed side by side.
"""

from __future__ import annotations

import argparse
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

import cpn  # noqa: E402
from cpn.statespace import ExploreOptions, Explorer  # noqa: E402
from tests.statespace._reduction import dead_set, projections  # noqa: E402


def models(paths):
    for root in paths:
        if os.path.isfile(root):
            yield root
            continue
        for d, _dirs, files in sorted(os.walk(root)):
            for f in sorted(files):
                if f.endswith((".cpnet", ".pnml", ".cpn")):
                    yield os.path.join(d, f)


def run(engine, **opts):
    t = time.perf_counter()
    x = Explorer(engine, ExploreOptions(**opts)).run()
    return x, time.perf_counter() - t


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("paths", nargs="*", default=["../shared/validation", "models", "bench/nets"])
    ap.add_argument("--max-states", type=int, default=200_000)
    ap.add_argument("--max-seconds", type=float, default=120.0)
    ap.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                    help="a value of the models' `val` constants (bench/nets: N)")
    args = ap.parse_args(argv)
    bad = 0
    print(f"{'model':58} {'full':>9} {'s':>6} {'deadlk':>9} {'s':>6} {'visible':>9} {'s':>6}  result")
    for path in models(args.paths):
        name = os.path.relpath(path) + "".join(f" {kv}" for kv in args.set)
        try:
            values = dict(kv.split("=", 1) for kv in args.set)
            engine = cpn.load(path, set=values or None).engine()
        except Exception as err:  # noqa: BLE001 - a model the loader refuses is listed, not fatal
            print(f"{name:58} not loaded: {str(err).splitlines()[0][:60]}")
            continue
        limits = {"max_states": args.max_states, "max_seconds": args.max_seconds}
        full, tf = run(engine, **limits)
        red, tr = run(engine, reduction="stubborn", **limits)
        visible = frozenset({0}) if engine.places else frozenset()
        vis, tv = run(engine, reduction="stubborn", visible_places=visible, **limits)
        if not (full.complete and red.complete and vis.complete):
            result = "partial (not compared)"
        elif dead_set(red) == dead_set(full) == dead_set(vis) and \
                projections(vis, sorted(visible)) == projections(full, sorted(visible)):
            result = "same" + ("" if red.reduction else " (not reduced: " + red.notes[0].split(": ", 1)[1].split(";")[0] + ")")
        else:
            result = "DIFFERENT"
            bad += 1
        print(f"{name[-58:]:58} {full.n_states:>9,} {tf:>6.2f} {red.n_states:>9,} {tr:>6.2f} {vis.n_states:>9,} "
              f"{tv:>6.2f}  {result}", flush=True)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
