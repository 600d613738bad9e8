"""Cost of `cpn-verify check` against `explore`: every property of a scenario run, versus generation alone.

Usage:
  python bench/check.py [SCENARIO ...] [--set NAME=VALUE ...] [--repeat 3]

For each run of each scenario (default: specs/examples/ms.toml with N=5 and specs/examples/dp.toml with
N=10) it measures, in one process, the median over --repeat of: what `cpn-verify explore` does (load the
model, generate, build the standard report), generation alone, and the whole check (load, compile the
properties, generate with the on-the-fly checks, decide every property). It prints check / explore (the
target is at most 2) and check / generation.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)

DEFAULT = [("specs/examples/ms.toml", {"N": 5}), ("specs/examples/dp.toml", {"N": 10})]


def measure(path: str, values: dict, repeat: int) -> dict:
    from cpn.gate.run import run_scenario
    from cpn.gate.scenario import Run, load_scenario
    from cpn.model import load
    from cpn.report import build_report
    from cpn.statespace import ExploreOptions, Explorer

    scenario = load_scenario(path)
    base = scenario.runs[0]
    run = Run(f"{scenario.name}[{','.join(f'{k}={v}' for k, v in values.items())}]", dict(values),
              {**base.values, **values})
    tc = bool(scenario.explore.get("time_condensation", False))
    gen, full, decide, explore = [], [], [], []
    states = 0
    for _ in range(repeat):
        t0 = time.perf_counter()
        engine = load(scenario.model, set=run.values).engine(time_condensation=tc)
        t1 = time.perf_counter()
        x = Explorer(engine, ExploreOptions(time_condensation=tc)).run()
        gen.append(time.perf_counter() - t1)
        build_report(x, model=scenario.model, options={})
        explore.append(time.perf_counter() - t0)
        states = x.n_states
        t0 = time.perf_counter()
        r = run_scenario(scenario, run)
        full.append(time.perf_counter() - t0)
        decide.append(r.check_seconds)
        assert r.exploration.n_states == states
    g, f, e = statistics.median(gen), statistics.median(full), statistics.median(explore)
    return {"run": run.name, "states": states, "generation_s": g, "explore_s": e, "check_s": f,
            "decide_s": statistics.median(decide), "ratio": f / e, "ratio_gen": f / g,
            "properties": len(scenario.properties)}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenarios", nargs="*")
    ap.add_argument("--set", action="append", default=[], metavar="NAME=VALUE")
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args(argv)
    values = {k: int(v) if v.lstrip("-").isdigit() else v for k, _, v in (s.partition("=") for s in a.set)}
    jobs = [(p, values) for p in a.scenarios] if a.scenarios else DEFAULT
    print(f"{'run':<14} {'props':>5} {'states':>9} {'explore s':>10} {'generate s':>10} {'check s':>9} "
          f"{'decide s':>9} {'check/explore':>13} {'check/generate':>14}")
    for path, vals in jobs:
        m = measure(os.path.join(ROOT, path) if not os.path.isabs(path) else path, vals, a.repeat)
        print(f"{m['run']:<14} {m['properties']:>5} {m['states']:>9,} {m['explore_s']:>10.2f} "
              f"{m['generation_s']:>10.2f} {m['check_s']:>9.2f} {m['decide_s']:>9.2f} {m['ratio']:>13.2f} "
              f"{m['ratio_gen']:>14.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
