"""The MODBUS gate (`cpn-verify check specs/modbus`) as a user runs it, against the Python search of an
earlier commit, alternating in one run.

Usage:
  python bench/gate.py [--base REV] [--repeat 3] [--modes base,python,auto] [--specs specs/modbus]
                       [--json FILE]

Modes, each a fresh `python -m cpn check SPECS --no-timings -q --reports DIR` in a subprocess:
  base    the Python search (`CPN_NO_GENERATED=1`) of commit --base (default 8b3402d, the last commit before
          the native timed search ran the gate), in a detached worktree of it made for the run;
  python  this tree's Python search (`CPN_NO_GENERATED=1`), with its default processes;
  auto    this tree's default (native where it runs, a process per core).
The modes alternate within each repetition (base, python, auto; then again), so that they share the
machine's load; a shared machine's speed drifts by a tenth and more within minutes, and only runs made
side by side compare. Every run's report files must be byte-identical to the committed ones
(`reports/modbus` for `specs/modbus`), else the bench stops. Printed per mode: the median wall and CPU
seconds (the process and its children) and the peak resident size of the largest process; then the ratio
of the medians against `base`, and the ratio within each repetition (its smallest and largest). The load
average is printed before and after. Nothing here is a test: the figures are what this machine gave.
"""

from __future__ import annotations

import argparse
import filecmp
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

#: the commit whose Python search the goal is measured against: the last before the native timed search
#: ran the gate's scenarios
BASE = "8b3402d"


def _same_tree(a: str, b: str) -> bool:
    """Whether folders a and b hold the same files with the same bytes."""
    cmp = filecmp.dircmp(a, b)
    if cmp.left_only or cmp.right_only or cmp.funny_files:
        return False
    _match, mismatch, errors = filecmp.cmpfiles(a, b, cmp.common_files, shallow=False)
    return not mismatch and not errors and all(_same_tree(os.path.join(a, d), os.path.join(b, d))
                                               for d in cmp.common_dirs)


def run_once(tree: str, specs: str, python_search: bool, expected: str | None) -> dict:
    """One gate run in a subprocess from `tree`: wall and CPU seconds, peak resident MiB (the largest of the
    process and its children), and whether its reports are the committed ones."""
    env = dict(os.environ)
    if python_search:
        env["CPN_NO_GENERATED"] = "1"
    out = tempfile.mkdtemp(prefix="cpn-gate-")
    try:
        with tempfile.TemporaryFile("w+") as err:
            t0 = time.perf_counter()
            p = subprocess.Popen([sys.executable, "-m", "cpn", "check", specs, "--no-timings", "-q", "--reports",
                                  out], cwd=tree, env=env, stdout=subprocess.DEVNULL, stderr=err, text=True)
            _pid, status, usage = os.wait4(p.pid, 0)  # this run's usage: the process and the children it waited for
            wall = time.perf_counter() - t0
            p.returncode = os.waitstatus_to_exitcode(status)
            if p.returncode != 0:
                err.seek(0)
                raise SystemExit(f"the gate failed in {tree} (exit status {p.returncode}):\n{err.read()[-2000:]}")
        same = None if expected is None else _same_tree(out, expected)
        if same is False:
            raise SystemExit(f"the reports of {tree} differ from {expected}")
        return {"wall_s": wall, "cpu_s": usage.ru_utime + usage.ru_stime, "peak_mib": usage.ru_maxrss / 1024,
                "reports_identical": same}
    finally:
        shutil.rmtree(out, ignore_errors=True)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--base", default=BASE, help=f"the commit of mode 'base' (default {BASE})")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--modes", default="base,python,auto")
    ap.add_argument("--specs", default="specs/modbus")
    ap.add_argument("--json", help="write the figures to FILE")
    a = ap.parse_args(argv)
    modes = [m.strip() for m in a.modes.split(",") if m.strip()]
    unknown = sorted(set(modes) - {"base", "python", "auto"})
    if unknown:
        ap.error(f"unknown mode(s) {', '.join(unknown)}: give base, python, auto")
    expected = os.path.join(ROOT, "reports", "modbus") if os.path.normpath(a.specs) == os.path.join("specs", "modbus") \
        else None
    worktree = None
    if "base" in modes:
        worktree = tempfile.mkdtemp(prefix="cpn-gate-base-")
        os.rmdir(worktree)
        subprocess.run(["git", "worktree", "add", "--detach", worktree, a.base], cwd=ROOT, check=True,
                       capture_output=True)
    trees = {"base": worktree, "python": ROOT, "auto": ROOT}
    runs: dict[str, list[dict]] = {m: [] for m in modes}
    try:
        print(f"load average before: {os.getloadavg()[0]:.2f}; {len(modes)} modes x {a.repeat}", flush=True)
        for i in range(a.repeat):
            for m in modes:
                r = run_once(trees[m], a.specs, m in ("base", "python"), expected)
                runs[m].append(r)
                print(f"  {i + 1} {m:6} {r['wall_s']:7.1f} s wall {r['cpu_s']:7.1f} s CPU "
                      f"{r['peak_mib']:6.0f} MiB", flush=True)
        print(f"load average after: {os.getloadavg()[0]:.2f}")
    finally:
        if worktree is not None:
            subprocess.run(["git", "worktree", "remove", "--force", worktree], cwd=ROOT, capture_output=True)
    summary = {}
    for m in modes:
        summary[m] = {k: statistics.median(r[k] for r in runs[m]) for k in ("wall_s", "cpu_s", "peak_mib")}
        print(f"{m:6} median {summary[m]['wall_s']:7.1f} s wall {summary[m]['cpu_s']:7.1f} s CPU "
              f"{summary[m]['peak_mib']:6.0f} MiB")
    if "base" in modes:
        for m in modes:
            if m == "base":
                continue
            pairs = [b["wall_s"] / r["wall_s"] for b, r in zip(runs["base"], runs[m])]
            summary[m]["speedup"] = summary["base"]["wall_s"] / summary[m]["wall_s"]
            summary[m]["speedup_per_repetition"] = pairs
            print(f"{m:6} {summary[m]['speedup']:.2f} times base (medians); per repetition "
                  f"{min(pairs):.2f} to {max(pairs):.2f}")
    if a.json:
        with open(a.json, "w", encoding="utf-8") as fh:
            json.dump({"base": a.base, "specs": a.specs, "runs": runs, "summary": summary}, fh, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
