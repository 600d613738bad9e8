"""State-space benchmark: DP(N) and MS(N) of shared/bench/BENCHMARKS.md, optionally beside cpncheck.

Usage:
  python bench/statespace.py [--nets dp,ms] [--sizes dp=5,8,10;ms=4,6,8 | 4,6,8] [--repeat 3]
                             [--backends c,python,packed] [--cpncheck] [--json FILE]

Every measurement runs in a fresh subprocess, so peak memory (ru_maxrss) is that run's alone. Per size
it prints states, arcs, generation seconds, whole-report seconds (generation plus the analysis of the
standard report), states per second, peak memory after generation and after the report, and bytes per
state (peak RSS growth during generation divided by the states), generation CPU seconds (`gen cpu`, less
sensitive to a shared machine's load than wall seconds) and, for `c`, the seconds to generate and
compile the net's C (`build s`, before the clock starts; a few milliseconds once it is in the cache).
Medians over --repeat runs.
--backends picks the searches to compare: `c` (the native search, `--backend c`), `python` (the Python
search, `--backend python`: the engine's tuples in a dict below a million states) and `packed` (the Python
search with the packed state store from the first state). With several, their runs alternate, so that they share the machine's load,
and each gets its own row.

With --cpncheck, the same nets as CPN Tools .cpn files (shared/bench/make_cpn_nets.py) are run with
cpncheck from the virtual environment CPNCHECK_VENV (default ../cpncheck-venv; `pip install cpncheck` there): shared/bench/cpncheck_run.py for
generation, `cpncheck check NET.cpn` for the full report, and the ratios are printed (against the last
back end of --backends; `--cpncheck-repeat K` runs cpncheck K times a size instead of --repeat).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SHARED_BENCH = os.path.join(os.environ.get("CPN_SHARED_DIR") or os.path.join(ROOT, "..", "shared"), "bench")
CPNCHECK_VENV = os.environ.get("CPNCHECK_VENV", os.path.join(ROOT, "..", "cpncheck-venv"))
DEFAULT_SIZES = {"dp": [5, 8, 10, 12, 14], "ms": [4, 5, 6, 7, 8]}


# ------------------------------------------------------------------------------------------ child

def child(net: str, n: int, backend: str = "c") -> dict:
    """One measurement, in this (fresh) process: load, generate, report."""
    sys.path.insert(0, ROOT)
    import cpn
    from cpn.report import build_report
    from cpn.statespace import ExploreOptions, Explorer
    from cpn.statespace._memory import current_rss_mb, peak_rss_mb

    t_start = time.perf_counter()
    model = cpn.load(os.path.join(HERE, "nets", f"{net}.cpnet"), set={"N": str(n)})
    engine = model.engine(time_condensation=False)
    load_s = time.perf_counter() - t_start
    build_s = 0.0
    if backend == "c":  # the net's C is built (or found in the cache) before the clock starts
        from cpn.statespace import native

        t_build = time.perf_counter()
        native.library()
        code, _why = engine.native_code()
        if code is not None:
            native.library(code)
        build_s = time.perf_counter() - t_build
    rss0 = current_rss_mb()
    cpu0 = time.process_time()
    x = Explorer(engine, ExploreOptions(pack_from=0 if backend == "packed" else 1_000_000,
                                        backend="c" if backend == "c" else "python")).run()
    cpu_gen = time.process_time() - cpu0
    rss_gen = current_rss_mb()
    peak_gen = peak_rss_mb()
    report = build_report(x, model=f"{net}({n})")
    cpu_all = time.process_time() - cpu0
    peak_all = peak_rss_mb()
    dead = report.dead.count
    return {
        "net": net, "n": n, # the search asked for, and the one that finished it where that differs ("c>python": handed over)
        "backend": backend if x.backend == ("c" if backend == "c" else "python") else f"{backend}>{x.backend}", "states": x.n_states, "arcs": x.n_arcs, "dead": dead, "complete": x.complete,
        "load_s": load_s, "build_s": build_s, "gen_s": x.seconds, "report_s": report.seconds, "analysis_s": report.analysis_seconds,
        "peak_gen_mb": peak_gen, "peak_report_mb": peak_all, "rss_before_mb": rss0,
        "gen_cpu_s": cpu_gen, "report_cpu_s": cpu_all,
        "bytes_per_state": max(0.0, rss_gen - rss0) * 1048576 / max(1, x.n_states),
        "wall_s": time.perf_counter() - t_start,
    }


def run_measured(cmd: list[str], env=None) -> tuple[str, float, float]:
    """Run cmd and reap it with os.wait4, which gives that child's own peak RSS."""
    t0 = time.perf_counter()
    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        p = subprocess.Popen(cmd, stdout=out, stderr=err, text=True, env=env)
        _pid, status, usage = os.wait4(p.pid, 0)
        p.returncode = os.waitstatus_to_exitcode(status)
        wall = time.perf_counter() - t0
        out.seek(0)
        err.seek(0)
        text, etext = out.read(), err.read()
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({p.returncode}):\n{etext[-2000:]}")
    return text, wall, usage.ru_maxrss / 1024


def ours(net: str, n: int, backend: str = "c") -> dict:
    out, wall, peak = run_measured([sys.executable, os.path.abspath(__file__), "--child", net, str(n), backend])
    d = json.loads(out.strip().splitlines()[-1])
    d["process_wall_s"] = wall
    d["process_peak_mb"] = peak
    return d


def cpncheck(cpn_dir: str, net: str, n: int) -> dict:
    path = os.path.join(cpn_dir, f"{net}_{n}.cpn")
    py = os.path.join(CPNCHECK_VENV, "bin", "python")
    out, wall, peak = run_measured([py, os.path.join(SHARED_BENCH, "cpncheck_run.py"), path])
    fields = dict(re.findall(r"(\w+)=(\S+)", out))
    gen = {"states": int(fields["states"]), "arcs": int(fields["arcs"]), "gen_s": float(fields["explore_s"]),
           "gen_wall_s": wall, "peak_gen_mb": peak}
    _out, wall2, peak2 = run_measured([os.path.join(CPNCHECK_VENV, "bin", "cpncheck"), "check", path])
    gen.update({"report_wall_s": wall2, "peak_report_mb": peak2})
    return gen


# ------------------------------------------------------------------------------------------ main

def parse_sizes(text: str | None, nets: list[str]) -> dict[str, list[int]]:
    if not text:
        return {k: DEFAULT_SIZES[k] for k in nets}
    if "=" not in text:
        sizes = [int(s) for s in text.split(",") if s]
        return {k: sizes for k in nets}
    out = {}
    for part in text.split(";"):
        k, _, v = part.partition("=")
        out[k.strip()] = [int(s) for s in v.split(",") if s]
    return {k: out.get(k, DEFAULT_SIZES[k]) for k in nets}


def median(rows: list[dict], key: str) -> float:
    return statistics.median(r[key] for r in rows)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--nets", default="dp,ms")
    ap.add_argument("--sizes")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--backends", default="c,python", help="searches to compare: c,python,packed")
    ap.add_argument("--cpncheck", action="store_true")
    ap.add_argument("--cpncheck-repeat", type=int, metavar="K",
                    help="cpncheck's runs per size (default: --repeat; MS(8) takes it minutes a run)")
    ap.add_argument("--json", metavar="FILE")
    ap.add_argument("--child", nargs=3, metavar=("NET", "N", "BACKEND"), help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.child:
        print(json.dumps(child(args.child[0], int(args.child[1]), args.child[2])))
        return 0
    nets = [s.strip() for s in args.nets.split(",") if s.strip()]
    backends = [s.strip() for s in args.backends.split(",") if s.strip()]
    sizes = parse_sizes(args.sizes, nets)
    cpn_dir = None
    if args.cpncheck and not os.path.exists(os.path.join(CPNCHECK_VENV, "bin", "cpncheck")):
        print(f"error: cpncheck is not installed in {CPNCHECK_VENV}; run:\n"
              f"  python3 -m venv {CPNCHECK_VENV} && {CPNCHECK_VENV}/bin/pip install cpncheck\n"
              "(or set CPNCHECK_VENV to another virtual environment that has it)", file=sys.stderr)
        return 64
    if args.cpncheck:
        cpn_dir = tempfile.mkdtemp(prefix="cpn-bench-")
        subprocess.run([sys.executable, os.path.join(SHARED_BENCH, "make_cpn_nets.py"), cpn_dir], check=True)
    results = []
    head = (f"{'net':<6}{'backend':>10}{'states':>10}{'arcs':>11}{'gen s':>8}{'report s':>9}{'states/s':>10}"
            f"{'peak MiB':>9}{'rep MiB':>8}{'B/state':>8}{'wall s':>8}{'gen cpu':>8}{'build s':>8}")
    if args.cpncheck:
        head += f" | {'cpncheck gen s':>14}{'report s':>9}{'peak MiB':>9}{'x gen':>7}{'x rep':>7}{'mem':>6}"
    print(head)
    for net in nets:
        for n in sizes[net]:
            by_backend: dict[str, list[dict]] = {st: [] for st in backends}
            for _ in range(args.repeat):
                for st in backends:
                    by_backend[st].append(ours(net, n, st))
            if len({(r[0]["states"], r[0]["arcs"]) for r in by_backend.values()}) > 1:
                print(f"{net}({n}): COUNTS DIFFER between the back ends", flush=True)
            for st in backends:
                runs = by_backend[st]
                row = {"net": net, "n": n, "backend": runs[0]["backend"], "states": runs[0]["states"],
                       "arcs": runs[0]["arcs"], "gen_s": median(runs, "gen_s"), "report_s": median(runs, "report_s"),
                       "process_wall_s": median(runs, "process_wall_s"),
                       "peak_gen_mb": median(runs, "peak_gen_mb"), "peak_report_mb": median(runs, "peak_report_mb"),
                       "bytes_per_state": median(runs, "bytes_per_state"), "gen_cpu_s": median(runs, "gen_cpu_s"),
                       "build_s": median(runs, "build_s"), "runs": runs}
                row["states_per_s"] = row["states"] / row["gen_s"] if row["gen_s"] else 0.0
                line = (f"{net}({n})".ljust(6) + f"{row['backend']:>10}{row['states']:>10,}{row['arcs']:>11,}"
                        f"{row['gen_s']:>8.2f}{row['report_s']:>9.2f}{row['states_per_s']:>10,.0f}"
                        f"{row['peak_gen_mb']:>9.0f}{row['peak_report_mb']:>8.0f}{row['bytes_per_state']:>8.0f}"
                        f"{row['process_wall_s']:>8.2f}{row['gen_cpu_s']:>8.2f}{row['build_s']:>8.2f}")
                if st != backends[-1]:
                    print(line, flush=True)
                    results.append(row)
            if args.cpncheck:
                cruns = [cpncheck(cpn_dir, net, n) for _ in range(args.cpncheck_repeat or args.repeat)]
                c = {"gen_s": median(cruns, "gen_s"), "report_wall_s": median(cruns, "report_wall_s"),
                     "peak_report_mb": median(cruns, "peak_report_mb"), "peak_gen_mb": median(cruns, "peak_gen_mb"),
                     "states": cruns[0]["states"], "arcs": cruns[0]["arcs"], "runs": cruns}
                row["cpncheck"] = c
                row["ratio_gen"] = c["gen_s"] / row["gen_s"]
                row["ratio_report"] = c["report_wall_s"] / row["process_wall_s"]
                row["ratio_memory"] = c["peak_report_mb"] / row["peak_report_mb"]
                agree = "" if (c["states"], c["arcs"]) == (row["states"], row["arcs"]) else " COUNTS DIFFER"
                line += (f" | {c['gen_s']:>14.2f}{c['report_wall_s']:>9.2f}{c['peak_report_mb']:>9.0f}"
                         f"{row['ratio_gen']:>7.1f}{row['ratio_report']:>7.1f}{row['ratio_memory']:>6.1f}{agree}")
            print(line, flush=True)
            results.append(row)
    if args.cpncheck:
        print("x gen: cpncheck generation s / ours; x rep: cpncheck check wall s / our whole process wall s "
              "(load, compile, generation, report); mem: cpncheck check peak / our peak")
    if args.json:
        with open(args.json, "w") as fh:
            json.dump({"python": sys.version, "results": results}, fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
