"""The native search of timed nets against the Python search, and against the native search of the untimed
twin: the timed MS(N) family.

Usage:
  python bench/timed.py [--sizes 4,6,8,10] [--repeat 3] [--json FILE]

The net is bench/nets/ms_timed.cpnet: bench/nets/ms.cpnet (a MODBUS-like master with N slaves) with a timed
bus (a request arrives one time unit after it is sent) and timed responses (two units after the reply),
explored with time condensation, so that its state space is finite; at N = 10 it has more than a million
states. For each N, in this process, a fresh engine per run, the three searches alternating:
- `python`: `--backend python` on the timed net;
- `c-timed`: `--backend c` on the timed net (the native timed search, every transition in the net's
  generated C);
- `c-untimed`: `--backend c` on the untimed twin bench/nets/ms.cpnet with the same N;
each the median of --repeat runs of the generation's seconds, and the states per second it gives. The
nets' libraries are built by a first, untimed run of each (the compilation is not measured). A search that
does not complete is reported with its stop reason.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

import cpn  # noqa: E402
from cpn.statespace import ExploreOptions, Explorer  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
TIMED = os.path.join(HERE, "nets", "ms_timed.cpnet")
UNTIMED = os.path.join(HERE, "nets", "ms.cpnet")
SEARCHES = (("python", TIMED, "python"), ("c-timed", TIMED, "c"), ("c-untimed", UNTIMED, "c"))


def run(model, backend: str, condensation: bool) -> tuple[float, object]:
    engine = model.engine(time_condensation=condensation) if model.net.is_timed else model.engine()
    start = time.perf_counter()
    x = Explorer(engine, ExploreOptions(backend=backend)).run()
    return time.perf_counter() - start, x


def measure(n: int, repeat: int) -> dict:
    models = {path: cpn.load(path, set={"N": str(n)}) for path in (TIMED, UNTIMED)}
    for _name, path, backend in SEARCHES:  # the libraries built once, outside the measure
        if backend == "c":
            Explorer(models[path].engine(**({"time_condensation": True} if path == TIMED else {})),
                     ExploreOptions(backend="c", max_states=10)).run()
    times: dict[str, list[float]] = {name: [] for name, _, _ in SEARCHES}
    found: dict[str, object] = {}
    for _ in range(repeat):
        for name, path, backend in SEARCHES:
            seconds, x = run(models[path], backend, True)
            times[name].append(seconds)
            found[name] = x
    row = {"N": n}
    for name, _, _ in SEARCHES:
        x = found[name]
        median = statistics.median(times[name])
        row[name] = {"states": x.n_states, "arcs": x.n_arcs, "complete": x.complete, "backend": x.backend,
                     "stop": x.stop_reason.value, "seconds": round(median, 3),
                     "states_per_second": round(x.n_states / median) if median else None}
    return row


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sizes", default="4,6,8,10", help="the values of N (default 4,6,8,10)")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--json", help="also write the rows to this file")
    args = ap.parse_args(argv)
    rows = []
    print(f"{'N':>3} {'search':>10} {'states':>10} {'arcs':>11} {'seconds':>8} {'states/s':>10}  backend")
    for n in (int(v) for v in args.sizes.split(",")):
        row = measure(n, args.repeat)
        rows.append(row)
        for name, _, _ in SEARCHES:
            r = row[name]
            stop = "" if r["complete"] else f"  (stopped: {r['stop']})"
            print(f"{n:>3} {name:>10} {r['states']:>10,} {r['arcs']:>11,} {r['seconds']:>8.3f} "
                  f"{r['states_per_second']:>10,}  {r['backend']}{stop}")
        py, ct = row["python"], row["c-timed"]
        if py["seconds"] and ct["seconds"]:
            print(f"{n:>3} {'':>10} c-timed / python: {py['seconds'] / ct['seconds']:.1f}x; c-timed / c-untimed "
                  f"states/s: {ct['states_per_second'] / row['c-untimed']['states_per_second']:.2f}")
        sys.stdout.flush()
    if args.json:
        with open(args.json, "w", encoding="utf-8") as f:
            json.dump(rows, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
