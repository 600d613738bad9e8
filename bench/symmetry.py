"""Symmetry reduction benchmark: states, arcs and seconds of the full graph and of the quotient graph.

Usage:
  python bench/symmetry.py [--nets dp,ms,contest] [--sizes dp=5,8,10;ms=4,5,6] [--repeat 1] [--json FILE]

DP(N) and MS(N) are bench/nets/dp_sym.cpnet and ms_sym.cpnet: the nets of bench/statespace.py (the same
state spaces, checked here) with their symmetry declared (rotations of the philosophers, permutations of
the slaves). The contest nets are the symmetric nets of ../shared/validation whose enumerations
`--symmetry auto` accepts. Per net: the full graph (the native search where it can run, and the Python
search), the quotient graph (the Python search), the full counts computed from the orbit sizes (which
must equal the full graph's: the run fails otherwise), the dead markings (full, orbits) and the
properties compared (integer bounds, dead and live transition instances, fairness). Seconds are
generation only, medians over --repeat runs, in this process, one run at a time.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SHARED = os.environ.get("CPN_SHARED_DIR") or os.path.join(ROOT, "..", "shared")
DEFAULT_SIZES = {"dp": [5, 8, 10], "ms": [4, 5, 6]}
CONTEST = ["Philosophers-COL-000005", "Philosophers-COL-000010", "SharedMemory-COL-000005",
           "DatabaseWithMutex-COL-02", "Referendum-COL-0010", "CSRepetitions-COL-02",
           "DrinkVendingMachine-COL-02", "BART-COL-002"]


def measure(model, scalars, repeat: int) -> dict:
    from cpn.report import build_report
    from cpn.statespace import ExploreOptions, Explorer

    def run(opts):
        times, x = [], None
        for _ in range(repeat):
            engine = model.engine()
            t0 = time.perf_counter()
            x = Explorer(engine, opts).run()
            times.append(time.perf_counter() - t0)
        return x, statistics.median(times)

    full, t_full = run(ExploreOptions())
    _, t_full_py = run(ExploreOptions(backend="python"))
    quot, t_quot = run(ExploreOptions(reduction="symmetry", symmetry=tuple(scalars)))
    st = quot.reduction_stats
    if (st["full_states"], st["full_arcs"]) != (full.n_states, full.n_arcs):
        raise SystemExit(f"full counts differ: {st['full_states']}, {st['full_arcs']} from the orbits against "
                         f"{full.n_states}, {full.n_arcs}")
    rf, rq = build_report(full, trace_to_dead=False), build_report(quot, trace_to_dead=False)
    same = {"bounds": [(b.upper, b.lower) for b in rf.bounds.places] == [(b.upper, b.lower) for b in rq.bounds.places],
            "dead_markings": rf.dead.count == rq.full_dead_count,
            "dead_transitions": rf.dead_transitions == rq.dead_transitions,
            "live_transitions": rf.live_transitions == rq.live_transitions,
            "fairness": rf.fairness == rq.fairness}
    if not all(same.values()):
        raise SystemExit(f"the quotient disagrees with the full graph: {same}")
    return {"symmetry": st["symmetry"], "group": st["group_order"], "states": full.n_states, "arcs": full.n_arcs,
            "orbits": quot.n_states, "orbit_arcs": quot.n_arcs, "dead": rf.dead.count, "dead_orbits": rq.dead.count,
            "full_s": t_full, "full_backend": full.backend, "full_python_s": t_full_py, "quotient_s": t_quot,
            "properties_equal": sorted(same)}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--nets", default="dp,ms,contest")
    ap.add_argument("--sizes", default=None, help="dp=5,8,10;ms=4,5,6")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--json", default=None)
    args = ap.parse_args(argv)
    sys.path.insert(0, ROOT)
    import cpn

    sizes = dict(DEFAULT_SIZES)
    for part in (args.sizes or "").split(";"):
        if "=" in part:
            k, v = part.split("=", 1)
            sizes[k.strip()] = [int(x) for x in v.split(",")]
    rows = []
    nets = args.nets.split(",")
    for net in ("dp", "ms"):
        if net not in nets:
            continue
        for n in sizes[net]:
            model = cpn.load(os.path.join(HERE, "nets", f"{net}_sym.cpnet"), set={"N": str(n)})
            rows.append({"net": f"{net.upper()}({n})", **measure(model, model.symmetry(), args.repeat)})
            _print(rows[-1])
    if "contest" in nets:
        for name in CONTEST:
            path = os.path.join(SHARED, "validation", name, "model.pnml")
            if not os.path.exists(path):
                continue
            model = cpn.load(path)
            rows.append({"net": name, **measure(model, model.symmetry("auto"), args.repeat)})
            _print(rows[-1])
    if args.json:
        with open(args.json, "w", encoding="utf-8") as fh:
            json.dump(rows, fh, indent=1)
    return 0


def _print(r: dict) -> None:
    print(f"| {r['net']} | {', '.join(r['symmetry'])} | {r['group']:,} | {r['states']:,} | {r['orbits']:,} | "
          f"{r['states'] / r['orbits']:.1f} | {r['dead']} / {r['dead_orbits']} | {r['full_s']:.2f} ({r['full_backend']}) | "
          f"{r['full_python_s']:.2f} | {r['quotient_s']:.2f} |", flush=True)


if __name__ == "__main__":
    raise SystemExit(main())
