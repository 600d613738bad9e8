"""The native search of timed nets against the Python search, and against the native search of the untimed
twin: two timed MS(N) families.

Usage:
  python bench/timed.py [--nets polled,ms] [--sizes 8,10] [--python-sizes 8] [--repeat 3]
                        [--python-repeat 1] [--searches c-timed,c-untimed,python] [--json FILE]

The nets (bench/nets/), explored with time condensation, so that their state spaces are finite:
- `polled`: ms_polled_timed.cpnet, MS(N) whose registers change only when the master writes them, with a
  timed bus (a request arrives one time unit after it is sent) and timed responses (two units after the
  reply); its clock advances in every cycle. Its untimed twin ms_polled.cpnet has the same states and
  arcs, so the two native searches do the same work but for time. N = 9 has 1,082,565 states.
- `ms`: ms_timed.cpnet, the same timing on bench/nets/ms.cpnet, whose untimed Update is always enabled: its
  clock never advances (3^N (2N + 1) states, the first request never delivered); the twin is ms.cpnet.
  N = 10 has 1,240,029 states.
For each net and N, in this process, a fresh engine per run, the searches alternating in each round:
- `c-timed`: `--backend c` on the timed net (the native timed search, every transition in the net's
  generated C);
- `c-untimed`: `--backend c` on the untimed twin with the same N;
- `python`: `--backend python` on the timed net, only at --python-sizes and in the first --python-repeat
  rounds (it takes minutes at a million states);
each the median of its runs' seconds (wall clock, and the CPU time of this process: on a machine shared
with other jobs the CPU time is the steadier measure), and the states per second they give. The load
average (`os.getloadavg`) is printed before and after each N. The nets' libraries are built by a first,
short run of each (the compilation is not measured). A search that does not complete is reported with its
stop reason. `--searches` runs only some of the three (to profile one: `perf record -g python
bench/timed.py --nets polled --sizes 9 --repeat 1 --searches c-timed`).
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
NETS = {  # name: (timed net, untimed twin)
    "polled": (os.path.join(HERE, "nets", "ms_polled_timed.cpnet"), os.path.join(HERE, "nets", "ms_polled.cpnet")),
    "ms": (os.path.join(HERE, "nets", "ms_timed.cpnet"), os.path.join(HERE, "nets", "ms.cpnet")),
}
SEARCHES = ("c-timed", "c-untimed", "python")


def engine(model):
    return model.engine(time_condensation=True) if model.net.is_timed else model.engine()


def run(model, backend: str) -> tuple[float, float, object]:
    e = engine(model)
    start, cpu = time.perf_counter(), time.process_time()
    x = Explorer(e, ExploreOptions(backend=backend)).run()
    return time.perf_counter() - start, time.process_time() - cpu, x


def load() -> str:
    return "/".join(f"{v:.1f}" for v in os.getloadavg())


def measure(net: str, n: int, repeat: int, python_repeat: int, searches=SEARCHES) -> dict:
    timed, untimed = (cpn.load(path, set={"N": str(n)}) for path in NETS[net])
    plan = {"c-timed": (timed, "c"), "c-untimed": (untimed, "c"), "python": (timed, "python")}
    for model in (timed, untimed):  # the libraries built once, outside the measure
        Explorer(engine(model), ExploreOptions(backend="c", max_states=10)).run()
    row: dict = {"net": net, "N": n, "load_before": load()}
    runs: dict[str, list[tuple[float, float]]] = {name: [] for name in SEARCHES}
    found: dict[str, object] = {}
    for r in range(repeat):
        for name in searches:
            if name == "python" and r >= python_repeat:
                continue
            model, backend = plan[name]
            seconds, cpu, x = run(model, backend)
            runs[name].append((seconds, cpu))
            found[name] = x
    row["load_after"] = load()
    for name in SEARCHES:
        if not runs[name]:
            continue
        x = found[name]
        wall = statistics.median(s for s, _ in runs[name])
        cpu = statistics.median(c for _, c in runs[name])
        row[name] = {"states": x.n_states, "arcs": x.n_arcs, "complete": x.complete, "backend": x.backend,
                     "stop": x.stop_reason.value, "runs": len(runs[name]), "seconds": round(wall, 3),
                     "cpu_seconds": round(cpu, 3), "states_per_second": round(x.n_states / wall) if wall else None,
                     "states_per_cpu_second": round(x.n_states / cpu) if cpu else None}
    return row


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--nets", default="polled,ms", help=f"the families (default polled,ms; known: {', '.join(NETS)})")
    ap.add_argument("--sizes", default="8,10", help="the values of N (default 8,10)")
    ap.add_argument("--python-sizes", help="the values of N at which the Python search runs too (default: all)")
    ap.add_argument("--repeat", type=int, default=3, help="rounds per N (default 3)")
    ap.add_argument("--python-repeat", type=int, help="rounds with the Python search (default: all)")
    ap.add_argument("--searches", default=",".join(SEARCHES), help="the searches run (default: all three)")
    ap.add_argument("--json", help="also write the rows to this file")
    args = ap.parse_args(argv)
    sizes = [int(v) for v in args.sizes.split(",")]
    py_sizes = sizes if args.python_sizes is None else [int(v) for v in args.python_sizes.split(",") if v]
    searches = args.searches.split(",")
    for name in searches:
        if name not in SEARCHES:
            ap.error(f"unknown search {name!r} (known: {', '.join(SEARCHES)})")
    rows = []
    print(f"{'net':>6} {'N':>3} {'search':>10} {'states':>10} {'arcs':>11} {'runs':>4} {'seconds':>8} {'cpu s':>8} "
          f"{'states/s':>10} {'st/cpu s':>10}  backend")
    for net in args.nets.split(","):
        if net not in NETS:
            ap.error(f"unknown net {net!r} (known: {', '.join(NETS)})")
        for n in sizes:
            py_repeat = (args.repeat if args.python_repeat is None else args.python_repeat) if n in py_sizes else 0
            row = measure(net, n, args.repeat, py_repeat, searches)
            rows.append(row)
            for name in SEARCHES:
                r = row.get(name)
                if r is None:
                    continue
                stop = "" if r["complete"] else f"  (stopped: {r['stop']})"
                print(f"{net:>6} {n:>3} {name:>10} {r['states']:>10,} {r['arcs']:>11,} {r['runs']:>4} "
                      f"{r['seconds']:>8.3f} {r['cpu_seconds']:>8.3f} {r['states_per_second']:>10,} "
                      f"{r['states_per_cpu_second']:>10,}  {r['backend']}{stop}")
            ct, cu, py = row.get("c-timed"), row.get("c-untimed"), row.get("python")
            parts = []
            if ct and py and ct["seconds"] and ct["cpu_seconds"]:
                parts.append(f"c-timed / python: {py['seconds'] / ct['seconds']:.1f}x "
                             f"(CPU {py['cpu_seconds'] / ct['cpu_seconds']:.1f}x)")
            if ct and cu and cu["states_per_second"] and cu["states_per_cpu_second"]:
                parts.append(f"c-timed / c-untimed states/s: {ct['states_per_second'] / cu['states_per_second']:.2f} "
                             f"(per CPU second {ct['states_per_cpu_second'] / cu['states_per_cpu_second']:.2f})")
            parts.append(f"load {row['load_before']} -> {row['load_after']}")
            print(f"{net:>6} {n:>3} {'':>10} {'; '.join(parts)}")
            sys.stdout.flush()
    if args.json:
        with open(args.json, "w", encoding="utf-8") as f:
            json.dump(rows, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
