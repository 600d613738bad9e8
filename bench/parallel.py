"""The partitioned search (`--workers N`, `--ray`) beside the one-process search, on DP(N) and MS(N).

Usage:
  python bench/parallel.py [--nets dp,ms] [--sizes "dp=12;ms=7"] [--modes one,python,w1,w2] [--repeat 3]
                           [--simulate 1,2,4,16,64] [--bandwidth-mbs 117] [--latency-ms 0.2] [--json FILE]

Measured (`--modes`): every run in a fresh subprocess, the modes alternating so that they share the
machine's load. `one` is the default one-process search (the native back end where it runs), `c` the
one-process native search with the net's C from the start (`--backend c`), `python` the one-process
Python search, `wN` what `--workers N` runs (N threads of one process where the net is wholly in C,
`cpn.statespace.threads`, else N processes), `tN` the threads alone (the run fails if they do not apply),
`pN` N worker processes (`threads=False`), `rayN` the partitioned search on N Ray actors of a local Ray
instance (its start is not counted). The net's C is built (or found in the cache) before the clock starts.
Per mode: the median wall seconds of the search (`Explorer.run`, graph assembly included), the median CPU
seconds (this process's, all its threads, plus the worker processes'), its phases for the partitioned
search, and for processes the bytes the workers sent each other per state and per arc sent. The load
average of the machine is printed before and after: on a shared machine the ratios are what they are.

Simulated (`--simulate P,...`): the partitioned search with P workers run in this one process, worker
after worker within each step (`PartitionWorker`, the same code as the processes run), the CPU seconds of
every worker in every step measured. The estimated wall time on P machines is the sum over the steps of
the slowest worker's CPU seconds (the level-synchronous barrier) plus, per step, the latency and the
largest number of bytes one worker sends or receives divided by the bandwidth; the assembly in the
coordinator is added as measured, with the time the workers' parts take to reach it over one link of
that bandwidth. That is an estimate of a cluster of P idle single-core machines on a
network of the given bandwidth and latency (defaults: 1 Gbit/s Ethernet's 117 MB/s, 0.2 ms), not a
measurement of one.
"""

from __future__ import annotations

import argparse
import json
import os
import pickle
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
DEFAULT_SIZES = {"dp": [12], "ms": [7]}


def child(net: str, n: int, mode: str) -> dict:
    """One measurement in this (fresh) process."""
    sys.path.insert(0, ROOT)
    import cpn
    from cpn.statespace import ExploreOptions, Explorer

    model = cpn.load(os.path.join(HERE, "nets", f"{net}.cpnet"), set={"N": str(n)})
    engine = model.engine()
    opts: dict = {}
    if mode != "python":  # the net's C built (or loaded from the cache) before the clock starts
        from cpn.statespace import native

        code, _notes = native.generated(engine, ExploreOptions(backend="c"))
        if code is not None:
            native.library(code)
    if mode == "python":
        opts["backend"] = "python"
    elif mode == "c":
        opts["backend"] = "c"
    elif mode[0] in "wtp" and mode[1:].isdigit():
        opts["workers"] = int(mode[1:])
        opts["threads"] = mode[0] != "p"
    elif mode.startswith("ray"):
        import ray

        ray.init(num_cpus=os.cpu_count(), include_dashboard=False, log_to_driver=False, configure_logging=False)
        opts.update(workers=int(mode[3:]), ray="local")
    t0, c0 = time.perf_counter(), time.process_time()
    x = Explorer(engine, ExploreOptions(**opts)).run()
    seconds, cpu = time.perf_counter() - t0, time.process_time() - c0
    if mode[0] == "t" and x.backend != "threads":
        raise SystemExit(f"the threads did not run: {x.notes}")
    if x.partition and "worker_cpu_seconds" in x.partition:
        cpu += sum(x.partition["worker_cpu_seconds"])
    out = {"net": net, "n": n, "mode": mode, "backend": x.backend, "states": x.n_states, "arcs": x.n_arcs,
           "complete": x.complete, "seconds": seconds, "cpu": cpu, "dead": len(x.graph.dead_states())}
    if x.partition:
        out["partition"] = x.partition
    return out


def _run_child(net: str, n: int, mode: str) -> dict:
    cmd = [sys.executable, os.path.abspath(__file__), "--child", net, str(n), mode]
    res = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT, check=False)
    if res.returncode != 0:
        raise SystemExit(f"{net}({n}) {mode} failed:\n{res.stderr}")
    return json.loads(res.stdout.strip().splitlines()[-1])


def measure(nets: dict, modes: list[str], repeat: int) -> list[dict]:
    rows = []
    for net, sizes in nets.items():
        for n in sizes:
            runs: dict[str, list[dict]] = {m: [] for m in modes}
            for _ in range(repeat):
                for m in modes:
                    runs[m].append(_run_child(net, n, m))
            base = statistics.median(r["seconds"] for r in runs[modes[0]])
            one_worker = statistics.median(r["seconds"] for r in runs["w1"]) if "w1" in runs else None
            for m in modes:
                rs = runs[m]
                first = rs[0]
                for r in rs:
                    assert (r["states"], r["arcs"], r["dead"]) == (first["states"], first["arcs"], first["dead"])
                med = statistics.median(r["seconds"] for r in rs)
                row = {"net": f"{net.upper()}({n})", "mode": m, "backend": first["backend"], "states": first["states"],
                       "arcs": first["arcs"], "seconds": med, "cpu": statistics.median(r["cpu"] for r in rs),
                       "runs": [round(r["seconds"], 3) for r in rs], f"vs_{modes[0]}": base / med,
                       "vs_w1": (one_worker / med) if one_worker else None}
                parts = [r["partition"] for r in rs if "partition" in r]
                if parts and "threads" in parts[0]:
                    p = parts[len(parts) // 2]
                    row["phases"] = p["seconds"]
                    row["computed"] = p["computed"]  # per thread: results computed by the net's C
                    row["uncached"] = p["uncached"]  # per thread: caches whose results are computed anew
                    row["barrier_seconds"] = p["barrier_seconds"]
                    row["cpu_seconds"] = p["cpu_seconds"]  # per thread: expanding, storing what was sent
                elif parts:
                    p = parts[len(parts) // 2]
                    row["phases"] = p["seconds"]
                    row["worker_cpu"] = statistics.median(sum(q["worker_cpu_seconds"]) for q in parts)
                    row["bytes_per_state"] = p["bytes_sent"] / first["states"]
                    row["bytes_per_arc_sent"] = p["bytes_sent"] / p["successors_sent"] if p["successors_sent"] else 0
                    row["arcs_sent_share"] = p["successors_sent"] / first["arcs"]
                rows.append(row)
    return rows


def simulate(net: str, n: int, counts: list[int], bandwidth_mbs: float, latency_ms: float) -> list[dict]:
    """The partitioned search with P in-process workers, timed per worker and step (see the module)."""
    sys.path.insert(0, ROOT)
    import gc

    import cpn
    from cpn.engine.transfer import transfer_for
    from cpn.statespace import ExploreOptions
    from cpn.statespace.parallel import STEP_STATES, PartitionWorker, StopReason, _Coordinator, net_blob

    model = cpn.load(os.path.join(HERE, "nets", f"{net}.cpnet"), set={"N": str(n)})
    rows = []
    for p in counts:
        engine = model.engine()
        tr = transfer_for(engine)
        blob = net_blob(engine.net)
        workers = [PartitionWorker(blob, False, w, p) for w in range(p)]
        s0 = engine.initial_state()
        workers[tr.stable_hash(s0) % p].seed(tr.export_state(s0))
        inboxes = [[None] * p for _ in range(p)]
        advance = False
        wall = cpu_total = net_total = 0.0
        steps = 0
        bytes_total = 0
        gc.disable()
        while True:
            statuses, outboxes, cpus = [], [], []
            for w in workers:
                t = time.process_time()
                st, out = w.step(STEP_STATES, advance, inboxes[w.me])
                cpus.append(time.process_time() - t)
                statuses.append(st)
                outboxes.append(out)
            steps += 1
            sent = [sum(len(b) for b in row if b) for row in outboxes]
            received = [sum(len(outboxes[w][d]) for w in range(p) if outboxes[w][d]) for d in range(p)]
            bytes_total += sum(sent)
            step_net = (latency_ms / 1000 if p > 1 else 0.0) + max(sent + received) / (bandwidth_mbs * 1e6)
            wall += max(cpus) + step_net
            net_total += step_net
            cpu_total += sum(cpus)
            inboxes = [[outboxes[w][d] for w in range(p)] for d in range(p)]
            left = sum(s[3] for s in statuses)
            in_flight = any(b for row in outboxes for b in row)
            if left == 0 and not in_flight and sum(s[4] for s in statuses) == 0:
                break
            advance = left == 0
        gc.enable()
        parts = [pickle.loads(w.collect()) for w in workers]
        t = time.process_time()
        c = _Coordinator(engine, tr, ExploreOptions(), None, type("T", (), {"n": p, "name": "simulated"})(), 0.0)
        g, _ = c._assemble(parts, StopReason.COMPLETE)
        assemble = time.process_time() - t
        collect_bytes = sum(len(pickle.dumps(q)) for q in parts)
        rows.append({"net": f"{net.upper()}({n})", "workers": p, "states": g.n_states, "arcs": g.n_arcs,
                     "steps": steps, "cpu_total": cpu_total, "search_estimate": wall, "network": net_total,
                     # the parts reach the coordinator through its one link
                     "assemble": assemble + (collect_bytes / (bandwidth_mbs * 1e6) if p > 1 else 0.0),
                     "collect_bytes": collect_bytes,
                     "bytes_per_state": bytes_total / g.n_states,
                     "max_worker_states": max(len(q["states"]) for q in parts)})
        del workers, parts, g
    base = rows[0]["search_estimate"]
    for r in rows:
        r["search_speedup"] = base / r["search_estimate"]
        r["with_assembly_speedup"] = (base + rows[0]["assemble"]) / (r["search_estimate"] + r["assemble"])
    return rows


def _sizes(text: str | None, nets: list[str]) -> dict:
    if not text:
        return {k: DEFAULT_SIZES[k] for k in nets}
    out = {}
    for part in text.split(";"):
        k, _, v = part.partition("=")
        out[k.strip()] = [int(x) for x in v.split(",")]
    return {k: out[k] for k in nets if k in out}


def _load() -> str:
    try:
        return " ".join(f"{x:.2f}" for x in os.getloadavg())
    except OSError:
        return "unknown"


def main(argv=None) -> int:
    if argv is None and len(sys.argv) > 1 and sys.argv[1] == "--child":
        print(json.dumps(child(sys.argv[2], int(sys.argv[3]), sys.argv[4])))
        return 0
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--nets", default="dp,ms")
    ap.add_argument("--sizes", default=None)
    ap.add_argument("--modes", default="one,python,w1,w2")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--simulate", default=None, metavar="P,...")
    ap.add_argument("--bandwidth-mbs", type=float, default=117.0)
    ap.add_argument("--latency-ms", type=float, default=0.2)
    ap.add_argument("--json", default=None)
    args = ap.parse_args(argv)
    nets = _sizes(args.sizes, args.nets.split(","))
    result: dict = {"cpus": os.cpu_count(), "load_before": _load()}
    if args.simulate:
        counts = [int(x) for x in args.simulate.split(",")]
        sim = []
        for net, sizes in nets.items():
            for n in sizes:
                sim += simulate(net, n, counts, args.bandwidth_mbs, args.latency_ms)
        result["simulated"] = sim
        print(f"simulated ({args.bandwidth_mbs:g} MB/s, {args.latency_ms:g} ms per step; CPU seconds of this "
              f"machine, load {result['load_before']})")
        print("| net | P | steps | CPU s (all workers) | est. search s | network s | collect + assembly s | speed-up "
              "(search) | speed-up (with assembly) | bytes/state | largest part |")
        print("|---|---|---|---|---|---|---|---|---|---|---|")
        for r in sim:
            print(f"| {r['net']} | {r['workers']} | {r['steps']} | {r['cpu_total']:.2f} | {r['search_estimate']:.2f} | "
                  f"{r['network']:.3f} | {r['assemble']:.2f} | {r['search_speedup']:.2f} | "
                  f"{r['with_assembly_speedup']:.2f} | {r['bytes_per_state']:.1f} | "
                  f"{r['max_worker_states'] / r['states']:.1%} |")
    else:
        modes = args.modes.split(",")
        rows = measure(nets, modes, args.repeat)
        result["rows"] = rows
        result["load_after"] = _load()
        print(f"{os.cpu_count()} CPUs; load average before {result['load_before']}, after {result['load_after']}; "
              f"medians of {args.repeat}")
        print(f"| net | mode | ran as | states | arcs | seconds | CPU s | vs {modes[0]} | vs w1 | phases "
              "(search/collect/assemble) | workers' CPU s | bytes/state | bytes/arc sent | arcs sent |")
        print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        for r in rows:
            ph = r.get("phases")
            phases = "/".join(f"{ph[k]:.2f}" if k in ph else "-" for k in ("search", "collect", "assemble")) if ph else ""
            vs_w1 = f"{r['vs_w1']:.2f}" if r["vs_w1"] else ""
            extra = (f"{r['worker_cpu']:.2f} | {r['bytes_per_state']:.1f} | {r['bytes_per_arc_sent']:.1f} | "
                     f"{r['arcs_sent_share']:.0%}") if "worker_cpu" in r else " | | | "
            print(f"| {r['net']} | {r['mode']} | {r['backend']} | {r['states']:,} | {r['arcs']:,} | {r['seconds']:.2f} | "
                  f"{r['cpu']:.2f} | {r[f'vs_{modes[0]}']:.2f} | {vs_w1} | {phases} | {extra} |")
    if args.json:
        with open(args.json, "w", encoding="utf-8") as fh:
            json.dump(result, fh, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
