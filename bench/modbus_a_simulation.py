"""Modbus-A at 42 slaves by simulation: the paper's checkpoints (MODBUS.md 4.3), from `cpn-verify simulate`.

Usage:
  python bench/modbus_a_simulation.py [--n 42] [--seed 0] [--out reports/modbus_a_42_simulation.txt]

Runs `python -m cpn simulate models/modbus/modbus_a.cpnet --set N=42 --steps 100000 --seed 0 --json -`
until the dead marking, then reads the trace: an iteration is one message of the master's allocation
(the reset, then each configuration message); after iteration i (when the master sends message i + 1, or
stops), the number of configured slaves is the number of `Chain'TakeId` occurrences so far. The paper
reports 8, 17, 29 and 42 configured slaves after the 9th, 18th, 30th and 44th iteration. The report is
printed and, with --out, written (the same bytes for the same arguments).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODEL = "models/modbus/modbus_a.cpnet"
PAPER = {9: 8, 18: 17, 30: 29, 44: 42}  # iteration -> slaves configured (42-slave run)


def simulate(n: int, seed: int) -> tuple[list[str], dict]:
    cmd = [sys.executable, "-m", "cpn", "simulate", MODEL, "--set", f"N={n}", "--steps", "100000",
           "--seed", str(seed), "-q", "--json", "-"]
    out = subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True).stdout
    return cmd, json.loads(out)


def iterations(steps: list[dict]) -> list[tuple[int, int, int]]:
    """(iteration, model time at its end, slaves configured after it), one per message of the master."""
    rows, sent, configured = [], 0, 0
    for s in steps:
        be = s["binding_element"]
        if be.startswith(("Master'SendReset ", "Master'SendConfig ", "Master'Stop ")):
            if sent:
                rows.append((sent, s["time"], configured))
            if be.startswith("Master'Stop "):
                break
            sent += 1
        elif be.startswith("Chain'TakeId "):
            configured += 1
    return rows


def report(n: int, seed: int) -> str:
    cmd, sim = simulate(n, seed)
    rows = iterations(sim["steps"])
    slaves = sim["final_marking"]["Chain'Slaves 1"]
    ids = [(int(p), mode, int(i)) for p, mode, i in re.findall(r"\((\d+),(\w+),(\d+)\)", slaves)]
    lines = [f"Modbus-A, {n} slaves, by simulation (MODBUS.md 4.3)",
             "command: python " + " ".join(["-m", "cpn"] + cmd[3:]),
             f"ended: {sim['ended']} marking after {len(sim['steps'])} steps, model time {sim['time']} ms",
             "", "iteration  message            time  configured"]
    for i, t, c in rows:
        msg = "reset" if i == 1 else f"configuration {i - 1}"
        mark = f"   paper: {PAPER[i]}" if n == 42 and i in PAPER else ""
        lines.append(f"{i:>9}  {msg:<17} {t:>5}  {c:>10}{mark}")
    lines.append("")
    unique = sorted(i for _, _, i in ids) == list(range(1, n + 1))
    by_position = all(mode == "Default" and p == i for p, mode, i in ids) and len(ids) == n
    lines.append(f"final: {len(ids)} slaves, IDs unique: {'yes' if unique else 'no'}, "
                 f"ID = position, default mode: {'yes' if by_position else 'no'}")
    if n == 42:
        got = {i: c for i, _, c in rows if i in PAPER}
        same = got == PAPER and max(i for i, _, _ in rows) == 44
        lines.append("paper's checkpoints (9 -> 8, 18 -> 17, 30 -> 29, 44 -> 42, 44 iterations in all): "
                     + ("reproduced" if same else f"NOT reproduced: {got}"))
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=42)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--out")
    args = ap.parse_args(argv)
    text = report(args.n, args.seed)
    sys.stdout.write(text)
    if args.out:
        with open(args.out, "w", encoding="utf-8") as fh:
            fh.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
