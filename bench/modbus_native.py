"""The MODBUS serial-line model, wholly in the generated C, searched natively against the Python search.

Usage:
  python bench/modbus_native.py [--faults 6,12] [--python-faults 6,12] [--json FILE]

The net: models/modbus/modbus.cpnet, scenario B (three slaves, addresses [3,5,6], codes [1,7,20], five
retries, every slave possibly late) with K corrupted frames and K lost frames allowed (`CRC` = `LOSS` =
K), explored with time condensation: the faults multiply the interleavings (K = 6: 177,177 states,
K = 12: 810,097, K = 14: 1,001,635). For each K, in this process, a fresh engine per search: `--backend c` (the net's C built
first by a short search and timed apart: its compilation, about 51,000 lines at -O2, is done once per
constant set and cached) and `--backend python` (only at --python-faults); wall and CPU seconds, states,
arcs, and whether both searches found the same numbers of states and arcs.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

import cpn  # noqa: E402
from cpn.statespace import ExploreOptions, Explorer  # noqa: E402

MODEL = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "models", "modbus", "modbus.cpnet")


def values(k: int) -> dict:
    return {"CONFIG": '"B"', "NS": "3", "ADRS": "[3,5,6]", "FCS": "[1,7,20]", "PO": "5", "LATE": "[1,2,3]",
            "CRC": str(k), "LOSS": str(k)}


def search(model, backend: str) -> dict:
    start, cpu = time.perf_counter(), time.process_time()
    x = Explorer(model.engine(time_condensation=True), ExploreOptions(backend=backend)).run()
    return {"backend": x.backend.value, "states": x.n_states, "arcs": x.n_arcs, "complete": x.complete,
            "wall": round(time.perf_counter() - start, 2), "cpu": round(time.process_time() - cpu, 2)}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--faults", default="6,12", help="the values of K (default 6,12)")
    ap.add_argument("--python-faults", default="6,12", help="those the Python search runs too (default 6,12)")
    ap.add_argument("--json", help="also write the rows to this file")
    args = ap.parse_args(argv)
    rows = []
    py = {int(k) for k in args.python_faults.split(",") if k}
    for k in (int(k) for k in args.faults.split(",")):
        model = cpn.load(MODEL, set=values(k))
        start = time.perf_counter()
        Explorer(model.engine(time_condensation=True), ExploreOptions(backend="c", max_states=10)).run()
        row = {"K": k, "build_seconds": round(time.perf_counter() - start, 1), "load": os.getloadavg()[0],
               "c": search(model, "c")}
        if k in py:
            row["python"] = search(model, "python")
            row["same"] = (row["c"]["states"], row["c"]["arcs"]) == (row["python"]["states"], row["python"]["arcs"])
            row["speedup_wall"] = round(row["python"]["wall"] / row["c"]["wall"], 1)
        print(json.dumps(row), flush=True)
        rows.append(row)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
