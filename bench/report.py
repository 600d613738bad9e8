"""Report-versus-search benchmark: the standard report's cost beside the search's, per model.

Usage:
  python bench/report.py [MODEL_OR_NAME ...] [--repeat 3] [--json FILE] [--figures DIR] [--baseline ROOT]
                         [--markdown FILE] [--profile N]

Without models it runs every instance of the validation corpus (`../shared/validation/expected.json`);
a name is an instance of that corpus, anything else a model path. Every measurement runs in a fresh
subprocess: load, `Explorer.run()` (the search), then `build_report` (the report: SCCs, bounds,
dead, live, home, fairness, trace). Per model it prints states, arcs, the medians of the search
seconds and the report seconds, their ratio (report / search; the goal is at most 1), and the median
seconds of each part of the report when the report gives them (`Report.part_seconds`). It also
measures the CPU seconds of both (`time.process_time`, the one process's own time): on a shared machine
wall seconds include the time other processes held the cores, CPU seconds do not, so the CPU ratio is
the steadier figure.

`--markdown FILE` writes the table as Markdown (docs/performance.md takes it as it is). `--profile N`
runs the report of each model once more under cProfile (in its child process, after the measured runs)
and prints the N entries with the most cumulative time.

`--figures DIR` writes each model's JSON result (`to_json`) without its timing keys, to compare two
versions of the code figure by figure (`diff -r`).

`--baseline ROOT` measures a second checkout of the project side by side, in the same run: for each
model the runs alternate between ROOT's code and this one (same machine, same minutes), and the table
gets the baseline's report seconds and ratio. ROOT needs only its `cpn` package: this script is run from
here with ROOT first on the import path. With `--figures`, the baseline's figures go to DIR/baseline.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
VALIDATION = os.path.join(os.environ.get("CPN_SHARED_DIR") or os.path.join(ROOT, "..", "shared"), "validation")
TIMING_KEYS = ("seconds", "report_seconds", "report_part_seconds", "peak_memory_mb", "model")


def child(path: str, figures: str | None, root: str = ROOT, profile: int = 0) -> dict:
    """One measurement, in this (fresh) process, of the code under `root`."""
    sys.path.insert(0, root)
    import cpn
    from cpn.report import build_report, to_json
    from cpn.statespace import Explorer

    engine = cpn.load(path).engine(time_condensation=False)
    c0 = time.process_time()
    x = Explorer(engine).run()
    c1 = time.process_time()
    t0 = time.perf_counter()
    report = build_report(x, model=os.path.basename(os.path.dirname(path)) or path)
    report_s = time.perf_counter() - t0
    report_cpu = time.process_time() - c1
    if profile:
        import cProfile
        import pstats

        prof = cProfile.Profile()
        prof.runcall(build_report, x)
        pstats.Stats(prof, stream=sys.stderr).sort_stats("cumulative").print_stats(profile)
    if figures:
        data = _without_timing(to_json(report))
        name = os.path.basename(os.path.dirname(path)) if path.endswith("model.pnml") else os.path.basename(path)
        with open(os.path.join(figures, name + ".json"), "w", encoding="utf-8") as fh:
            json.dump(data, fh, indent=1, sort_keys=True)
    return {"states": x.n_states, "arcs": x.n_arcs, "search_s": x.seconds, "report_s": report_s,
            "search_cpu": c1 - c0, "report_cpu": report_cpu,
            "parts": dict(getattr(report, "part_seconds", {}) or {})}


def _without_timing(data):
    if isinstance(data, dict):
        return {k: _without_timing(v) for k, v in data.items() if k not in TIMING_KEYS}
    if isinstance(data, list):
        return [_without_timing(v) for v in data]
    return data


def _name(path: str) -> str:
    return os.path.basename(os.path.dirname(path)) if path.endswith("model.pnml") else os.path.basename(path)


def corpus_models() -> list[str]:
    with open(os.path.join(VALIDATION, "expected.json"), encoding="utf-8") as fh:
        instances = json.load(fh)["instances"]
    return [os.path.join(VALIDATION, i["file"]) for i in instances]


def resolve(model: str) -> str:
    if os.path.exists(model):
        return model
    with open(os.path.join(VALIDATION, "expected.json"), encoding="utf-8") as fh:
        for i in json.load(fh)["instances"]:
            if i["name"] == model:
                return os.path.join(VALIDATION, i["file"])
    raise SystemExit(f"error: no model or corpus instance named '{model}'")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("models", nargs="*")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--json", metavar="FILE", help="write every run's measurements as JSON")
    ap.add_argument("--figures", metavar="DIR", help="write each model's figures (JSON without timings)")
    ap.add_argument("--baseline", metavar="ROOT", help="a second checkout, measured side by side")
    ap.add_argument("--markdown", metavar="FILE", help="write the table as Markdown")
    ap.add_argument("--profile", type=int, default=0, metavar="N",
                    help="print the N most expensive calls of each report (cProfile, cumulative)")
    ap.add_argument("--child", metavar="MODEL", help=argparse.SUPPRESS)
    ap.add_argument("--root", default=ROOT, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.child:
        print(json.dumps(child(args.child, args.figures, args.root, args.profile)))
        return 0
    sides = [("new", ROOT, args.figures)]
    if args.baseline:
        base_figures = os.path.join(args.figures, "baseline") if args.figures else None
        sides.insert(0, ("base", os.path.abspath(args.baseline), base_figures))
    for _side, _root, figures in sides:
        if figures:
            os.makedirs(figures, exist_ok=True)
    models = [resolve(m) for m in args.models] or corpus_models()
    rows = []
    head = (f"{'model':38} {'states':>10} {'arcs':>11} {'search s':>9} {'report s':>9} {'ratio':>6}"
            f" {'cpu ratio':>9}")
    if args.baseline:
        head += f" {'base search':>11} {'base report':>11} {'base ratio':>10}"
    print(head + "  parts (s)")
    for path in models:
        runs: dict[str, list] = {side: [] for side, _r, _f in sides}
        for k in range(args.repeat):
            for side, root, figures in sides:
                cmd = [sys.executable, os.path.abspath(__file__), "--child", path, "--root", root]
                if figures and k == 0:
                    cmd += ["--figures", figures]
                if args.profile and k == args.repeat - 1:
                    cmd += ["--profile", str(args.profile)]
                out = subprocess.run(cmd, capture_output=True, text=True, cwd=root)
                if args.profile and k == args.repeat - 1:
                    print(f"--- profile of the report of {_name(path)} ({side})\n{out.stderr}")
                if out.returncode != 0:
                    print(f"{path} ({side}): failed\n{out.stderr[-2000:]}", file=sys.stderr)
                    continue
                runs[side].append(json.loads(out.stdout.strip().splitlines()[-1]))
        if not runs["new"]:
            continue
        name = _name(path)
        row = {"model": name, "states": runs["new"][0]["states"], "arcs": runs["new"][0]["arcs"]}
        for side, rs in runs.items():
            if not rs:
                continue
            search = statistics.median(r["search_s"] for r in rs)
            report = statistics.median(r["report_s"] for r in rs)
            parts = {p: statistics.median(r["parts"].get(p, 0.0) for r in rs) for p in rs[0]["parts"]}
            search_cpu = statistics.median(r.get("search_cpu", 0.0) for r in rs)
            report_cpu = statistics.median(r.get("report_cpu", 0.0) for r in rs)
            row[side] = {"search_s": search, "report_s": report, "ratio": report / search if search else None,
                         "search_cpu": search_cpu, "report_cpu": report_cpu,
                         "cpu_ratio": report_cpu / search_cpu if search_cpu else None,
                         "parts": parts, "runs": rs}
        rows.append(row)
        new = row["new"]
        ratio = f"{new['ratio']:6.2f}" if new["ratio"] is not None else "     -"
        cpu_ratio = f"{new['cpu_ratio']:9.2f}" if new["cpu_ratio"] is not None else "        -"
        line = (f"{name[:38]:38} {row['states']:>10,} {row['arcs']:>11,} {new['search_s']:9.2f}"
                f" {new['report_s']:9.2f} {ratio} {cpu_ratio}")
        if "base" in row:
            base = row["base"]
            bratio = f"{base['ratio']:10.2f}" if base["ratio"] is not None else "         -"
            line += f" {base['search_s']:11.2f} {base['report_s']:11.2f} {bratio}"
        shown = " ".join(f"{p} {s:.2f}" for p, s in new["parts"].items() if s >= 0.005)
        print(f"{line}  {shown}", flush=True)
    if args.json:
        with open(args.json, "w", encoding="utf-8") as fh:
            json.dump(rows, fh, indent=1)
    if args.markdown:
        with open(args.markdown, "w", encoding="utf-8") as fh:
            fh.write(markdown(rows))
    return 0


def markdown(rows: list[dict]) -> str:
    """The table of a run as Markdown: per model, wall and CPU seconds of search and report, their
    ratios, the baseline's when there is one, and the largest parts of the report."""
    base = any("base" in r for r in rows)
    head = ["instance", "states", "arcs", "search s", "report s", "report / search", "search CPU s",
            "report CPU s", "CPU report / search"]
    if base:
        head += ["before: report s", "before: report / search", "before: CPU report / search"]
    head.append("largest parts (s)")

    def num(v, fmt="{:.2f}"):
        return "-" if v is None else fmt.format(v)

    lines = ["| " + " | ".join(head) + " |", "|---|" + "---:|" * (len(head) - 2) + "---|"]
    for r in rows:
        new = r["new"]
        cells = [r["model"], f"{r['states']:,}", f"{r['arcs']:,}", num(new["search_s"]), num(new["report_s"]),
                 num(new["ratio"]), num(new["search_cpu"]), num(new["report_cpu"]), num(new["cpu_ratio"])]
        if base:
            b = r.get("base", {})
            cells += [num(b.get("report_s")), num(b.get("ratio")), num(b.get("cpu_ratio"))]
        parts = sorted(new["parts"].items(), key=lambda kv: -kv[1])[:2]
        cells.append(", ".join(f"{p} {s:.2f}" for p, s in parts if s >= 0.005) or "-")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    sys.exit(main())
