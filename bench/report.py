"""Report-versus-search benchmark: the standard report's cost beside the search's, per model.

Usage:
  python bench/report.py [MODEL_OR_NAME ...] [--repeat 3] [--json FILE] [--figures DIR]

Without models it runs every instance of the validation corpus (`../shared/validation/expected.json`);
a name is an instance of that corpus, anything else a model path. Every measurement runs in a fresh
subprocess: load, `Explorer.run()` (the search), then `build_report` (the report: SCCs, bounds,
dead, live, home, fairness, trace). Per model it prints states, arcs, the medians of the search
seconds and the report seconds, their ratio (report / search; the goal is at most 1), and the median
seconds of each part of the report when the report gives them (`Report.part_seconds`).

`--figures DIR` writes each model's JSON result (`to_json`) without its timing keys, to compare two
versions of the code figure by figure (`diff -r`).
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


def child(path: str, figures: str | None) -> dict:
    """One measurement, in this (fresh) process."""
    sys.path.insert(0, ROOT)
    import cpn
    from cpn.report import build_report, to_json
    from cpn.statespace import Explorer

    engine = cpn.load(path).engine(time_condensation=False)
    x = Explorer(engine).run()
    t0 = time.perf_counter()
    report = build_report(x, model=os.path.basename(os.path.dirname(path)) or path)
    report_s = time.perf_counter() - t0
    if figures:
        data = _without_timing(to_json(report))
        name = os.path.basename(os.path.dirname(path)) if path.endswith("model.pnml") else os.path.basename(path)
        with open(os.path.join(figures, name + ".json"), "w", encoding="utf-8") as fh:
            json.dump(data, fh, indent=1, sort_keys=True)
    return {"states": x.n_states, "arcs": x.n_arcs, "search_s": x.seconds, "report_s": report_s,
            "parts": dict(getattr(report, "part_seconds", {}) or {})}


def _without_timing(data):
    if isinstance(data, dict):
        return {k: _without_timing(v) for k, v in data.items() if k not in TIMING_KEYS}
    if isinstance(data, list):
        return [_without_timing(v) for v in data]
    return data


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
    ap.add_argument("--child", metavar="MODEL", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.child:
        print(json.dumps(child(args.child, args.figures)))
        return 0
    if args.figures:
        os.makedirs(args.figures, exist_ok=True)
    models = [resolve(m) for m in args.models] or corpus_models()
    rows = []
    print(f"{'model':38} {'states':>10} {'arcs':>11} {'search s':>9} {'report s':>9} {'ratio':>6}  parts (s)")
    for path in models:
        runs = []
        for k in range(args.repeat):
            cmd = [sys.executable, os.path.abspath(__file__), "--child", path]
            if args.figures and k == 0:
                cmd += ["--figures", args.figures]
            out = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
            if out.returncode != 0:
                print(f"{path}: failed\n{out.stderr[-2000:]}", file=sys.stderr)
                break
            runs.append(json.loads(out.stdout.strip().splitlines()[-1]))
        if not runs:
            continue
        name = os.path.basename(os.path.dirname(path)) if path.endswith("model.pnml") else os.path.basename(path)
        search = statistics.median(r["search_s"] for r in runs)
        report = statistics.median(r["report_s"] for r in runs)
        parts = {p: statistics.median(r["parts"].get(p, 0.0) for r in runs) for p in runs[0]["parts"]}
        row = {"model": name, "states": runs[0]["states"], "arcs": runs[0]["arcs"], "search_s": search,
               "report_s": report, "ratio": report / search if search else None, "parts": parts, "runs": runs}
        rows.append(row)
        shown = " ".join(f"{p} {s:.2f}" for p, s in parts.items() if s >= 0.005)
        ratio = f"{report / search:6.2f}" if search else "     -"
        print(f"{name[:38]:38} {row['states']:>10,} {row['arcs']:>11,} {search:9.2f} {report:9.2f} {ratio}  {shown}",
              flush=True)
    if args.json:
        with open(args.json, "w", encoding="utf-8") as fh:
            json.dump(rows, fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
