"""MODBUS: the cost of `cpn-verify check` on the thesis's scenarios, and state spaces beyond 8 slaves.

Usage:
  python bench/modbus.py [--repeat 3]            # the thesis's scenarios A.1-D.4 (17 files) and all of specs/modbus
  python bench/modbus.py --scaling [--budget 600]
  python bench/modbus.py --table [--budget 600]   # the side-by-side table of reports/README.md
  python bench/modbus.py --sweep [--budget 600] [--ns 4,6,...] [--ks 1,4,...] [--full-max-memory 4096]
                                                  # the sweep-line against the full search (scenario B)
  python bench/modbus.py --sweep-thesis           # the same on the thesis's scenarios A.1-D.4 and the fault variants
  python bench/modbus.py --sweep-memo 16          # the sweep-line with the engine's memo tables emptied, then kept
  python bench/modbus.py --symmetry [--budget 300] [--sym-ns 4,8,...] [--sym-ks 1,4,...]
                                                  # broadcasts to NS slaves: the full model against the
                                                  # quotient of bench/nets/modbus_bcast_sym.cpnet
  python bench/modbus.py --native [--repeat 3]    # timed nets: the native search against the Python search
  python bench/modbus.py --native-check [--repeat 3]  # `check specs/modbus` with and without it

The first form times, as a user would, `python -m cpn check FILES --no-reports -q` (a fresh process: start-up,
loading and compiling the model, exploring, deciding every property) over --repeat runs and prints the
medians: once for the 17 files A_1.toml ... D_4.toml, once for the whole of specs/modbus/ (with the fault
variants, Modbus-A N = 1..8 and the mutants). The issue's target is ten minutes on this 2-core machine.

The --table form prints, per thesis scenario, the thesis's figures (MODBUS.md 3.5) next to ours: the gate's
state space (time condensation, as the scenario file says) and the timed state space without condensation
(what CPN Tools computes), explored with `python -m cpn explore models/modbus/modbus.cpnet --set ...` and
the scenario's values.

The --write-specs form writes the thesis's scenario files of specs/modbus (A_1.toml ... D_4.toml) and the
extra configurations, every file with the full property set of its family; the --mutants form runs the
bug catalogue (MUTANTS: each bug a value of the model's MUTANT switch, or of a parameter) against every
thesis scenario and prints the table of reports/README.md (--write-mutants: and writes
specs/modbus/mutants/, each mutant on the first thesis scenario whose complete search catches it).

The second form measures growing numbers of slaves, each run bounded by --budget seconds of generation
(a run stopped by it ends the series):
- scenario B (slave k at address k, fc [1,2,3,4] for k >= 4) with NS slaves, the frames {1..NS} x {1}
  (every slave once, as B.6) and {0..NS} x {1} (the same and one broadcast), PO 1, explored with time
  condensation: `python -m cpn explore models/modbus/modbus.cpnet --time-condensation --set 'CONFIG="B"'
  --set NS=n --set 'ADRS=[1,...,n]' --set 'FCS=[1]' --set PO=1` (states, arcs, seconds of generation);
  the model has 16 slave instances, so NS stops at 16;
- Modbus-A with N slaves, generation alone (`explore`), N up to 245 (IDs up to MAX_ID = 247 with 98 and 99
  skipped);
- Modbus-A with N slaves: every property of specs/modbus/modbus_a.toml (MA1-MA8) checked by the gate for
  N beyond the file's 1..8 (MAXN raised with N); N stops at 96: from N = 98 on the ID counter skips the
  reserved IDs 98 and 99 (MODBUS.md 4.5 E4), so the k-th slave no longer gets ID k and MA2 is violated
  by design.

The --native form explores timed nets (the scenarios B_1-B_6 and D_1-D_4 of specs/modbus, each as its file
says and then without time condensation; scenario B with NS 10 and 12 slaves and a broadcast, condensed;
models/examples/stop_and_wait.cpnet with and without condensation; CPN Tools' samples TimedProtocol.cpn and
TimedResourceAlloc.cpn of ../shared/cpntools-samples both ways; every search bounded at 20,000 states) with
`--backend python`, `--backend c`
(which hands over to the Python search where nearly every state needs the engine) and `--backend c`
without that hand-over (`c-only`), in this process, the three alternating, a fresh engine per run:
medians of --repeat runs of the generation's seconds (the net's library already built), states per
second, and for c-only the share of states the engine expanded for the C search.
The --native-check form runs `cpn-verify check specs/modbus --no-reports` in this process, --repeat times
each way, alternating: with the native search of timed nets (the default), and with timed nets left to
the Python search (`CompiledEngine.timed_groups` returning None; everything else unchanged), and prints
the medians of the wall seconds.
"""

from __future__ import annotations

import argparse
import glob
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)

THESIS = sorted(f for f in glob.glob(os.path.join(ROOT, "specs", "modbus", "[A-D]_[0-9].toml")))


def timed_check(paths: list[str], repeat: int) -> tuple[float, list[float]]:
    runs = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        r = subprocess.run([sys.executable, "-m", "cpn", "check", *paths, "--no-reports", "-q"], cwd=ROOT,
                           capture_output=True, text=True)
        runs.append(time.perf_counter() - t0)
        if r.returncode != 0:
            sys.exit(f"check failed ({r.returncode}):\n{r.stdout}{r.stderr}")
    return statistics.median(runs), runs


def scaling_b(budget: float) -> None:
    from cpn.model import load
    from cpn.statespace import ExploreOptions, Explorer

    print("scenario B, PO 1, FCS [1], --time-condensation (seconds: generation)")
    print(f"{'NS':>3} {'states':>9} {'arcs':>10} {'s':>8}   {'+ broadcast: states':>19} {'arcs':>10} {'s':>8}")
    for ns in range(4, 17, 2):
        row = []
        for adrs in (list(range(1, ns + 1)), [0] + list(range(1, ns + 1))):
            values = {"CONFIG": '"B"', "NS": str(ns), "ADRS": str(adrs).replace(" ", ""), "FCS": "[1]", "PO": "1"}
            engine = load(os.path.join(ROOT, "models", "modbus", "modbus.cpnet"), set=values).engine(
                time_condensation=True)
            t0 = time.perf_counter()
            x = Explorer(engine, ExploreOptions(time_condensation=True, max_seconds=budget)).run()
            secs = time.perf_counter() - t0
            row.append((x.n_states, x.n_arcs, secs, x.complete))
        print(f"{ns:>3} {row[0][0]:>9,} {row[0][1]:>10,} {row[0][2]:>8.2f}   {row[1][0]:>19,} {row[1][1]:>10,} "
              f"{row[1][2]:>8.2f}", flush=True)
        if not (row[0][3] and row[1][3]):
            print("    (stopped by the budget)")
            return


def scaling_modbus_a_explore(budget: float) -> None:
    from cpn.model import load
    from cpn.statespace import ExploreOptions, Explorer

    print("Modbus-A, generation alone: python -m cpn explore models/modbus/modbus_a.cpnet --time-condensation "
          "--set N=n --set MAXN=max(64,n)")
    print(f"{'N':>4} {'states':>9} {'arcs':>10} {'dead':>5} {'s':>8}")
    for n in (8, 16, 32, 42, 64, 96, 128, 192, 245):
        engine = load(os.path.join(ROOT, "models", "modbus", "modbus_a.cpnet"),
                      set={"N": str(n), "MAXN": str(max(64, n))}).engine(time_condensation=True)
        t0 = time.perf_counter()
        x = Explorer(engine, ExploreOptions(time_condensation=True, max_seconds=budget)).run()
        secs = time.perf_counter() - t0
        print(f"{n:>4} {x.n_states:>9,} {x.n_arcs:>10,} {len(x.graph.dead_states()) if x.complete else '-':>5} "
              f"{secs:>8.2f}", flush=True)
        if not x.complete:
            print("    (stopped by the budget)")
            return


def scaling_modbus_a(budget: float) -> None:
    from cpn.checks.verdict import Status
    from cpn.gate.run import run_scenario
    from cpn.gate.scenario import Run, load_scenario

    scenario = load_scenario(os.path.join(ROOT, "specs", "modbus", "modbus_a.toml"))
    base = scenario.runs[0]
    print("Modbus-A: every property of specs/modbus/modbus_a.toml (seconds: generation + deciding)")
    print(f"{'N':>4} {'states':>9} {'arcs':>10} {'s':>8}  verdict")
    for n in (8, 16, 24, 32, 42, 48, 64, 80, 96):
        values = {**base.values, "N": n, "MAXN": max(64, n)}
        run = Run(f"Modbus-A[N={n}]", {"N": n}, values)
        t0 = time.perf_counter()
        r = run_scenario(scenario, run, {"max_seconds": budget})
        secs = time.perf_counter() - t0
        x = r.exploration
        verdicts = {p.verdict.status for p in r.results}
        print(f"{n:>4} {x.n_states:>9,} {x.n_arcs:>10,} {secs:>8.2f}  {r.status.value}"
              f" ({sum(1 for p in r.results if p.verdict.status is Status.HOLDS)} of {len(r.results)} hold)",
              flush=True)
        if not x.complete or Status.UNKNOWN in verdicts:
            print("    (stopped by the budget)")
            return


# scenario -> (thesis nodes, thesis dead markings, thesis time as printed)
THESIS_FIGURES = {
    "A.1": ("13 905", 7, "0:16"), "A.2": ("68 101", 24, "6:45"), "A.3": ("29 245", 6, "4:47"),
    "A.4": ("150 957", 50, "13:14"), "B.1": ("183 607", 11, "0:19"), "B.2": ("170 399", 22, "0:44"),
    "B.3": ("190 167", 24, "0:52"), "B.4": ("33 893", 3, "1:53"), "B.5": ("295 195", 2, "24:31"),
    "B.6": ("68 960", 2, "0:15"), "C.1": ("68 014", 24, "7:13"), "C.2": ("77 819", 24, "7:56"),
    "C.3": ("143 440", 15, "1:02:53"), "D.1": ("86 546", 24, "0:8 (h:m)"), "D.2": ("148 520", 28, "0:28 (h:m)"),
    "D.3": ("389 690", 68, "3:52 (h:m)"), "D.4": ("726 624", 31, "47:20 (h:m)"),
}


def _explore(values: dict, condensed: bool, budget: float) -> str:
    from cpn.model import load
    from cpn.statespace import ExploreOptions, Explorer

    engine = load(os.path.join(ROOT, "models", "modbus", "modbus.cpnet"), set=values).engine(
        time_condensation=condensed)
    t0 = time.perf_counter()
    x = Explorer(engine, ExploreOptions(time_condensation=condensed, max_seconds=budget)).run()
    secs = time.perf_counter() - t0
    if not x.complete:
        return f"> {x.n_states:,} (stopped after {secs:.0f} s) | | | |"
    dead = [x.graph.states[i] for i in x.graph.dead_states()]
    untimed = len({engine.untimed(s) for s in dead})
    return f"{x.n_states:,} | {x.n_arcs:,} | {len(dead)} ({untimed}) | {secs:.2f} |"


def table(budget: float) -> None:
    from cpn.gate.run import run_scenario
    from cpn.gate.scenario import load_scenario

    print("| scenario | thesis nodes | thesis DM | thesis time | check: states | arcs | DM | s "
          "| timed: states | arcs | DM (mod. time) | s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for path in THESIS:
        scenario = load_scenario(path)
        run = scenario.runs[0]
        t0 = time.perf_counter()
        r = run_scenario(scenario, run)
        secs = time.perf_counter() - t0
        x = r.exploration
        nodes, dm, tt = THESIS_FIGURES[scenario.name]
        cells = [scenario.name, nodes, str(dm), tt, f"{x.n_states:,}", f"{x.n_arcs:,}",
                 str(len(x.graph.dead_states())), f"{secs:.2f}"]
        values = {k: str(v) for k, v in run.values.items()}
        print("| " + " | ".join(cells) + " | " + _explore(values, False, budget), flush=True)


# the sweep-line's progress measure for scenario B: the frames the master has done (Master'Done only
# grows: no occurrence decreases it)
SWEEP_MEASURE = "size (Master'Done 1)"


def _explore_process(values: dict, budget: float, sweep: bool, max_memory: float = 0) -> dict:
    """`python -m cpn explore models/modbus/modbus.cpnet --time-condensation ... --json -` in a fresh
    process (so that its peak memory is its own): the JSON statistics, with the wall-clock seconds."""
    cmd = [sys.executable, "-m", "cpn", "explore", os.path.join("models", "modbus", "modbus.cpnet"),
           "--time-condensation", "-q", "--json", "-", "--max-seconds", str(budget)]
    for k, v in values.items():
        cmd += ["--set", f"{k}={v}"]
    if sweep:
        cmd += ["--progress", SWEEP_MEASURE]
    if max_memory:
        cmd += ["--max-memory", str(max_memory)]
    t0 = time.perf_counter()
    r = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if r.returncode not in (0, 2):
        sys.exit(f"explore failed ({r.returncode}):\n{r.stderr}")
    import json

    d = json.loads(r.stdout)
    st = d["statespace"]
    st["dead"] = d["dead_markings"]["count"]
    st["wall"] = wall
    return st


def _series(title: str, header: str, items, row) -> None:
    """A table: its title, its header, then `row(item)` for each item (it prints its row and says whether
    its runs completed); the first run stopped by the budget ends the table."""
    print(title)
    print(header)
    for item in items:
        if not row(item):
            print("    (stopped by the budget)")
            break


def _sweep_row(label, values: dict, budget: float, full_memory: float) -> bool:
    full = _explore_process(values, budget, False, full_memory)
    sweep = _explore_process(values, budget, True)
    same = (full["states"], full["arcs"], full["dead"]) == (sweep["states"], sweep["arcs"], sweep["dead"])
    if full["complete"] and sweep["complete"] and not same:
        sys.exit(f"the sweep-line differs from the full search at {label}: {full} {sweep}")
    cells = [label, f"{sweep['states']:,}", f"{sweep['arcs']:,}", str(sweep["dead"]),
             f"{full['peak_memory_mb']:.0f}" if full["complete"] else f"stopped ({full['stop_reason']}) after "
             f"{full['states']:,} states", f"{full['seconds']:.2f}",
             f"{sweep['peak_states']:,}", f"{sweep['peak_memory_mb']:.0f}", f"{sweep['seconds']:.2f}",
             "yes" if sweep["exact"] else "no"]
    print("| " + " | ".join(cells) + " |", flush=True)
    return sweep["complete"]


def sweep_scaling(budget: float, ns_list: list[int], ks: list[int], full_memory: float) -> None:
    """Scenario B with broadcasts, full search against the sweep-line (each in a fresh process; the full
    search bounded by `full_memory` MiB on this shared machine). The sweep-line's measure is SWEEP_MEASURE."""
    header = ("| {} | states | arcs | DM | full: peak MiB | s | sweep-line: peak states held | peak MiB | s "
              "| exact |\n|---|---|---|---|---|---|---|---|---|---|")

    def b_row(ns, adrs, label):
        values = {"CONFIG": '"B"', "NS": str(ns), "ADRS": str(adrs).replace(" ", ""), "FCS": "[1]", "PO": "1"}
        return _sweep_row(label, values, budget, full_memory)

    _series(f"scenario B with one broadcast, PO 1, FCS [1], --time-condensation; sweep-line: --progress "
            f"\"{SWEEP_MEASURE}\"", header.format("NS"), ns_list,
            lambda ns: b_row(ns, [0] + list(range(1, ns + 1)), str(ns)))
    print()
    _series("scenario B, NS 10, the frames {1..10} x {1} and k broadcasts (ADRS = [0,1,...,10,0,...,0])",
            header.format("k"), ks, lambda k: b_row(10, [0] + list(range(1, 11)) + [0] * (k - 1), str(k)))


SYM_MODEL = os.path.join(HERE, "nets", "modbus_bcast_sym.cpnet")


def symmetric_model(ns: int) -> str:
    """bench/nets/modbus_bcast_sym.cpnet for NS slaves: one Slave instance per value of SIX."""
    import re

    with open(SYM_MODEL, encoding="utf-8") as f:
        s = f.read()
    s = re.sub(r"val NS = \d+;", f"val NS = {ns};", s)
    s = re.sub(r"instance Slave\d+ = .*\n", "", s)
    return s + "".join(f"instance Slave{k} = Slave(me = sl({k})) {{ B2S = b2s }};\n" for k in range(1, ns + 1))


def _explore_json(path: str, values: dict, budget: float, extra: list, max_memory: float) -> dict:
    """`python -m cpn explore PATH --time-condensation -q --json - ...` in a fresh process: the statistics."""
    import json

    cmd = [sys.executable, "-m", "cpn", "explore", path, "--time-condensation", "-q", "--json", "-",
           "--max-seconds", str(budget), "--max-memory", str(max_memory)] + extra
    for k, v in values.items():
        cmd += ["--set", f"{k}={v}"]
    r = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if r.returncode not in (0, 2):
        sys.exit(f"explore failed ({r.returncode}):\n{r.stderr}")
    d = json.loads(r.stdout)
    st = d["statespace"]
    st["dead"] = d["dead_markings"]["count"]
    st["full_dead"] = d["dead_markings"].get("full_count")
    return st


def _check_symmetric(path: str, values: dict, budget: float, max_memory: float, tmp: str) -> str:
    """`python -m cpn check` of bench/nets/modbus_bcast_sym.toml on the model at `path` with `values`: the
    verdicts on the quotient and the seconds of the whole run."""
    import json
    import shutil

    with open(SYM_MODEL.replace(".cpnet", ".toml"), encoding="utf-8") as f:
        spec = f.read()
    spec = spec.replace('model = "modbus_bcast_sym.cpnet"', f'model = "{os.path.basename(path)}"')
    head, _, rest = spec.partition("[set]\n")
    _, _, rest = rest.partition("\n\n")
    sets = "".join(f"{k} = {json.dumps(v)}\n" for k, v in values.items())
    spec_path = os.path.join(tmp, "check.toml")
    with open(spec_path, "w", encoding="utf-8") as f:
        f.write(f"{head}[set]\n{sets}\n{rest}")
    reports = os.path.join(tmp, "reports")
    shutil.rmtree(reports, ignore_errors=True)
    t0 = time.perf_counter()
    r = subprocess.run([sys.executable, "-m", "cpn", "check", spec_path, "--reports", reports, "--no-timings", "-q",
                        "--max-seconds", str(budget), "--max-memory", str(max_memory)],
                       cwd=ROOT, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    runs = [os.path.join(reports, n) for n in os.listdir(reports) if n.endswith(".json")] if os.path.isdir(reports) else []
    if not runs:
        sys.exit(f"check failed ({r.returncode}):\n{r.stderr}")
    with open(runs[0], encoding="utf-8") as f:
        run = json.load(f)
    counts: dict = {}
    for p in run["properties"]:
        counts[p["verdict"]] = counts.get(p["verdict"], 0) + 1
    return ", ".join(f"{n} {v}" for v, n in sorted(counts.items())) + f" ({wall:.1f} s)"


def symmetry_scaling(budget: float, ns_list: list[int], ks: list[int], max_memory: float) -> None:
    """Broadcasts to NS slaves: the quotient of bench/nets/modbus_bcast_sym.cpnet (the slaves as module
    instances permuted by symmetry), and the verdicts of bench/nets/modbus_bcast_sym.toml checked on the
    quotient. The variant was a copy of models/modbus/modbus.cpnet's broadcasts; modbus.cpnet now explores
    the slaves' receptions in slave order, which a permutation of the slaves does not preserve, so its
    column is left empty (no longer the same state space)."""
    import tempfile

    tmp = tempfile.mkdtemp(prefix="modbus-sym-")

    def row(ns, values, full_model: bool, label):
        path = os.path.join(tmp, f"modbus_bcast_sym_{ns}.cpnet")
        with open(path, "w", encoding="utf-8") as f:
            f.write(symmetric_model(ns))
        full = None  # no modbus.cpnet column any more (see the docstring); full_model is kept for the series
        q = _explore_json(path, values, budget, ["--reduction", "symmetry"], max_memory)
        verdicts = _check_symmetric(path, values, budget, max_memory, tmp) if q["complete"] else None
        if full is not None and full["complete"] and q["complete"]:
            same = (q["full_states"], q["full_arcs"], q["full_dead"]) == (full["states"], full["arcs"], full["dead"])
            if not same:
                sys.exit(f"the quotient's orbit sums differ from modbus.cpnet at {label}: {q} {full}")
        cells = [label]
        if full is None:
            cells += ["", "", "", ""]
        elif full["complete"]:
            cells += [f"{full['states']:,}", f"{full['arcs']:,}", f"{full['seconds']:.2f}",
                      f"{full['peak_memory_mb']:.0f}"]
        else:
            cells += [f"stopped ({full['stop_reason']})", "", f"{full['seconds']:.2f}", f"{full['peak_memory_mb']:.0f}"]
        if q["complete"]:
            cells += [f"{q['states']:,}", f"{q['arcs']:,}", f"{q['full_states']:,}", f"{q['full_arcs']:,}",
                      f"{q['seconds']:.2f}", f"{q['peak_memory_mb']:.0f}"]
        else:
            cells += [f"stopped ({q['stop_reason']}) after {q['states']:,}", "", "", "", f"{q['seconds']:.2f}",
                      f"{q['peak_memory_mb']:.0f}"]
        cells.append("" if verdicts is None else verdicts)
        print("| " + " | ".join(cells) + " |", flush=True)
        return q["complete"]

    header = ("| {} | modbus.cpnet: states | arcs | s | peak MiB | quotient: orbits | arcs | full states (orbit sums) "
              "| full arcs | s | peak MiB | check on the quotient |\n|---|---|---|---|---|---|---|---|---|---|---|---|")
    _series("one broadcast (ADRS [0], FCS [1], PO 1; every slave drops the code), --time-condensation",
            header.format("NS"), ns_list, lambda ns: row(ns, {"ADRS": "[0]", "FCS": "[1]", "PO": "1"}, True, str(ns)))
    print()
    _series("the same with BCAST_ANY = true: every slave processes the broadcast (1 or 50 ms); no modbus.cpnet "
            "column (its scenario-B slaves 2 and 3 drop the code)", header.format("NS"), ns_list,
            lambda ns: row(ns, {"ADRS": "[0]", "FCS": "[1]", "PO": "1", "BCAST_ANY": "true"}, False, str(ns)))
    print()
    _series("NS 16, k broadcasts (ADRS [0,...,0])", header.format("k"), ks,
            lambda k: row(16, {"ADRS": str([0] * k).replace(" ", ""), "FCS": "[1]", "PO": "1"}, k == 1, str(k)))


THESIS_MEASURE = "size (Master'Done 1)"


def sweep_thesis() -> None:
    """Per thesis scenario (and the fault variants): the full search and the sweep-line, condensed with
    the measure THESIS_MEASURE and timed (no condensation) with the clock; in this process, generation only."""
    from cpn.checks.columns import TransitionIndex
    from cpn.gate.scenario import load_scenario
    from cpn.gate.sweep import progress_measure
    from cpn.model import load
    from cpn.properties.predicates import PropertyLanguage
    from cpn.statespace import ExploreOptions, Explorer
    from cpn.statespace.sweep import SweepLine

    paths = THESIS + [os.path.join(ROOT, "specs", "modbus", f) for f in ("A_2_faults.toml", "D_4_faults.toml")]
    print(f"condensed: --time-condensation --progress \"{THESIS_MEASURE}\"; timed: --sweep-line (the clock)")
    print("| scenario | condensed: states | arcs | DM | peak held | regress arcs | timed: states | arcs | DM "
          "| peak held |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for path in paths:
        scenario = load_scenario(path)
        model = load(scenario.model, set=scenario.runs[0].values)
        cells = [scenario.name]
        for condensed in (True, False):
            engine = model.engine(time_condensation=condensed)
            opts = ExploreOptions(time_condensation=condensed)
            x = Explorer(engine, opts).run()
            measure = text = None
            if condensed:
                text = THESIS_MEASURE
                measure = progress_measure(PropertyLanguage(model.net, engine, TransitionIndex(engine)), text)
            y = SweepLine(engine, opts, measure, text).run()
            full = (x.n_states, x.n_arcs, len(x.graph.dead_states()))
            if not (x.complete and y.complete and y.exact and full == (y.states, y.arcs, len(y.dead))):
                sys.exit(f"{scenario.name}: the sweep-line differs from the full search: {full} {y}")
            cells += [f"{y.states:,}", f"{y.arcs:,}", str(len(y.dead)), f"{y.peak_states:,}"]
            if condensed:
                cells.append(str(y.regress_arcs))
        print("| " + " | ".join(cells) + " |", flush=True)


def sweep_memo(k: int, forget: bool) -> None:
    """One sweep-line run of scenario B (NS 10, k broadcasts) in this process, with the engine's memo
    tables emptied behind the sweep-line (the default) or kept: entries left, peak memory, seconds."""
    from cpn.checks.columns import TransitionIndex
    from cpn.gate.sweep import progress_measure
    from cpn.model import load
    from cpn.properties.predicates import PropertyLanguage
    from cpn.statespace import ExploreOptions
    from cpn.statespace import sweep as sweep_module
    from cpn.statespace._memory import peak_rss_mb

    if not forget:
        sweep_module.FORGET_EVERY = 1 << 62
    values = {"CONFIG": '"B"', "NS": "10", "ADRS": str([0] + list(range(1, 11)) + [0] * (k - 1)).replace(" ", ""),
              "FCS": "[1]", "PO": "1"}
    model = load(os.path.join(ROOT, "models", "modbus", "modbus.cpnet"), set=values)
    engine = model.engine(time_condensation=True)
    measure = progress_measure(PropertyLanguage(model.net, engine, TransitionIndex(engine)), SWEEP_MEASURE)
    t0 = time.perf_counter()
    x = sweep_module.SweepLine(engine, ExploreOptions(time_condensation=True), measure, SWEEP_MEASURE).run()
    secs = time.perf_counter() - t0
    entries = sum(len(i.memo) for i in engine._plan)
    print(f"k={k} memo tables {'emptied' if forget else 'kept'}: {x.states:,} states, peak {x.peak_states:,} held, "
          f"{entries:,} memo entries left, peak {peak_rss_mb():.0f} MiB, {secs:.2f} s")


def _native_nets() -> list[tuple[str, list[tuple[str, dict | None, bool]]]]:
    """(label, [(model path, constants, time condensation), ...]) of the --native rows."""
    import tomllib

    def scenarios(names, condensed):
        out = []
        for name in names:
            path = os.path.join(ROOT, "specs", "modbus", f"{name}.toml")
            with open(path, "rb") as f:
                spec = tomllib.load(f)
            tc = spec.get("explore", {}).get("time_condensation", False) if condensed else False
            out.append((os.path.join(os.path.dirname(path), spec["model"]), spec.get("set"), tc))
        return out
    modbus = os.path.join(ROOT, "models", "modbus", "modbus.cpnet")
    stop = os.path.join(ROOT, "models", "examples", "stop_and_wait.cpnet")
    bs, ds = [f"B_{i}" for i in range(1, 7)], [f"D_{i}" for i in range(1, 5)]
    rows = [("B_1-B_6 (as the files say)", scenarios(bs, True)), ("B_1-B_6 timed", scenarios(bs, False)),
            ("D_1-D_4 (as the files say)", scenarios(ds, True)), ("D_1-D_4 timed", scenarios(ds, False))]
    for ns in (10, 12):
        values = {"CONFIG": '"B"', "NS": str(ns), "ADRS": str([0] + list(range(1, ns + 1))).replace(" ", ""),
                  "FCS": "[1]", "PO": "1"}
        rows.append((f"B NS {ns} + broadcast, condensed", [(modbus, values, True)]))
    rows += [("stop_and_wait condensed", [(stop, None, True)]), ("stop_and_wait timed", [(stop, None, False)])]
    samples = os.path.join(os.environ.get("CPN_SHARED_DIR") or os.path.join(ROOT, "..", "shared"), "cpntools-samples")
    for name in ("TimedProtocol", "TimedResourceAlloc"):
        path = os.path.join(samples, f"{name}.cpn")
        if os.path.exists(path):
            rows += [(f"{name} condensed, 20,000 states", [(path, None, True)]),
                     (f"{name} timed, 20,000 states", [(path, None, False)])]
    return rows


def native_timed(repeat: int) -> None:
    """The --native table (see the module's docstring)."""
    from cpn import load
    from cpn.statespace import ExploreOptions, Explorer, nativetimed

    fills = [0]
    fill = nativetimed.TimedNativeSearch._fill

    def counted(self):
        fills[0] += 1
        return fill(self)
    nativetimed.TimedNativeSearch._fill = counted
    rate = nativetimed.HAND_OVER_RATE
    try:
        load_avg = os.getloadavg()
    except OSError:
        load_avg = (float("nan"),) * 3
    print(f"load average at start: {load_avg[0]:.1f} {load_avg[1]:.1f} {load_avg[2]:.1f}; {os.cpu_count()} CPUs")
    print(f"{'net':34} {'backend':>8} {'states':>8} {'arcs':>8} {'gen s':>7} {'states/s':>9} {'engine':>7}  ran")
    for label, runs in _native_nets():
        models = [(load(path, set=values), tc) for path, values, tc in runs]
        for backend in ("python", "c", "c-only"):  # built (or found in the cache) before the clock starts
            if backend != "python":
                nativetimed.HAND_OVER_RATE = 1e9
                for model, tc in models:
                    Explorer(model.engine(time_condensation=tc), ExploreOptions(backend="c", max_states=2)).run()
        times: dict[str, list[float]] = {"python": [], "c": [], "c-only": []}
        facts: dict[str, tuple] = {}
        for _ in range(repeat):
            for backend in ("python", "c", "c-only"):
                nativetimed.HAND_OVER_RATE = 1e9 if backend == "c-only" else rate
                fills[0] = 0
                seconds = states = arcs = expanded = 0
                ran = set()
                for model, tc in models:
                    x = Explorer(model.engine(time_condensation=tc),
                                 ExploreOptions(backend="python" if backend == "python" else "c",
                                                max_states=20_000)).run()
                    seconds += x.seconds
                    states, arcs, expanded = states + x.n_states, arcs + x.n_arcs, expanded + x.graph.expanded
                    ran.add(x.backend)
                times[backend].append(seconds)
                facts[backend] = (states, arcs, fills[0] / expanded if backend == "c-only" else None,
                                  ",".join(sorted(ran)))
        nativetimed.HAND_OVER_RATE = rate
        for backend in ("python", "c", "c-only"):
            states, arcs, share, ran = facts[backend]
            med = statistics.median(times[backend])
            engine = f"{share:.0%}" if share is not None else ""
            print(f"{label:34} {backend:>8} {states:>8,} {arcs:>8,} {med:>7.2f} {states / med:>9,.0f} {engine:>7}  {ran}")
    nativetimed.TimedNativeSearch._fill = fill


def native_check(repeat: int) -> None:
    """The --native-check figures (see the module's docstring)."""
    import contextlib
    import io

    from cpn.cli.main import main as cli
    from cpn.engine.compiled import CompiledEngine

    timed_groups = CompiledEngine.timed_groups
    print(f"load average at start: {os.getloadavg()[0]:.1f}; {os.cpu_count()} CPUs")
    seconds: dict[str, list[float]] = {"c": [], "python": []}
    try:
        for _ in range(repeat):
            for how in seconds:
                CompiledEngine.timed_groups = timed_groups if how == "c" else (lambda _self: None)
                t = time.perf_counter()
                with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
                    cli(["check", os.path.join(ROOT, "specs", "modbus"), "--no-reports"])
                seconds[how].append(time.perf_counter() - t)
    finally:
        CompiledEngine.timed_groups = timed_groups
    for how, runs in seconds.items():
        label = "native timed search" if how == "c" else "timed nets in Python"
        print(f"check specs/modbus, {label}: median {statistics.median(runs):.1f} s "
              f"(runs {', '.join(f'{r:.1f}' for r in runs)})")
    print(f"load average at end: {os.getloadavg()[0]:.1f}")


# ---------------------------------------------------------------- the scenario files (specs/modbus/)
# `python bench/modbus.py --write-specs` writes the thesis's scenario files A_1.toml ... D_4.toml, the extra
# configurations and, with --mutants, runs the bug catalogue against them and writes specs/modbus/mutants/.
# The expected outcome of each frame is computed here from the serial-line and application specifications
# (MODBUS.md 1.4, 2.4), independently of the model's own functions, so that a bug in the model's slave
# logic is not also a bug in the oracle.

MODEL_REL = "../../models/modbus/modbus.cpnet"
R15, R69 = list(range(1, 6)), list(range(6, 10))
CFG_A = [dict(adrs=[3], fcs=[1, 2, 3, 4], regs=R15, ss=False), dict(adrs=[5], fcs=[2, 3, 4, 7], regs=R69, ss=False)]
CFG_D = [dict(adrs=[3], fcs=[1, 2, 3, 4, 12, 65, 66], regs=R15, ss=True),
         dict(adrs=[5], fcs=[2, 3, 4, 7, 12], regs=R69, ss=False)]


def _cfg_b(ns: int) -> list[dict]:
    out = []
    for k in range(1, ns + 1):
        fcs, regs = {1: ([1, 2, 3, 4], R15), 2: ([2, 3, 4, 7], R69), 3: ([2, 3, 20, 21], R69)}.get(k, ([1, 2, 3, 4], R15))
        out.append(dict(adrs=[k], fcs=fcs, regs=regs, ss=False))
    return out


def _slaves(sets: dict) -> list[dict]:
    config = sets["CONFIG"].strip('"')
    if config == "B":
        return _cfg_b(int(sets["NS"]))
    if config == "C":
        return [CFG_A[0], dict(CFG_A[1], adrs=_ints(sets["S2ADRS"]))]
    if config == "D":
        return CFG_D
    return CFG_A


def _ints(text: str) -> list[int]:
    return [int(x) for x in text.strip("[]").split(",") if x.strip()]


BCAST_OK = [5, 6, 15, 16]
WREGS = list(range(1, 10))  # the model's WREGS: the registers and coils the write codes of WFCS write


def _bwrite(code: int) -> dict:
    """The values that make one scenario of a family send a broadcast write first, which every slave
    processes: every slave implements the write codes (WFCS, on WREGS; the thesis's slaves have none)."""
    return dict(WFCS=str(BCAST_OK).replace(" ", ""), PRE=f"[(0, {code}, 1, 1)]")


# (name, file, values); LATE: the slave that may be late (the owner of the first unicast address that
# supports the frames' first code, so that its processing, not an exception, is what is late); CRC 1 (all):
# the line may corrupt one frame, anywhere
SCENARIOS = [
    ("A.1", "A_1", dict(CONFIG='"A"', ADRS="[3,5]", FCS="[4,5,7]", PO="2")),
    ("A.2", "A_2", dict(CONFIG='"A"', ADRS="[0,3,5,6]", FCS="[1,7,20]", PO="2", **_bwrite(6))),
    ("A.3", "A_3", dict(CONFIG='"A"', ADRS="[0,3,5,6]", FCS="[1,7,20]", PO="0")),
    ("A.4", "A_4", dict(CONFIG='"A"', ADRS="[0,3,5,6]", FCS="[1,7,20]", PO="5")),
    ("B.1", "B_1", dict(CONFIG='"B"', NS="3", ADRS="[3,5,6]", FCS="[1,7,20]", PO="5", LATE="[3]")),
    ("B.2", "B_2", dict(CONFIG='"B"', NS="3", ADRS="[0,3,5,6]", FCS="[1,7,20]", PO="2", LATE="[3]", **_bwrite(16))),
    ("B.3", "B_3", dict(CONFIG='"B"', NS="3", ADRS="[0,3,5,6]", FCS="[1,7,20]", PO="2", LATE="[3]",
                        BCAST_ANY="true")),
    ("B.4", "B_4", dict(CONFIG='"B"', NS="5", ADRS="[0,3,5,6,7]", FCS="[1]", PO="1", LATE="[5]")),
    ("B.5", "B_5", dict(CONFIG='"B"', NS="6", ADRS="[0,2,3,4]", FCS="[1]", PO="0", LATE="[4]")),
    ("B.6", "B_6", dict(CONFIG='"B"', NS="8", ADRS="[1,2,3,4,5,6,7,8]", FCS="[1]", PO="1", LATE="[1]")),
    ("C.1", "C_1", dict(CONFIG='"C"', S2ADRS="[5]", ADRS="[0,3,5,6]", FCS="[1,7,20]", PO="2", **_bwrite(5))),
    ("C.2", "C_2", dict(CONFIG='"C"', S2ADRS="[5,6]", ADRS="[0,3,5,6]", FCS="[1,7,20]", PO="2")),
    ("C.3", "C_3", dict(CONFIG='"C"', S2ADRS="[5,6,7]", ADRS="[0,3,5,6,7,8]", FCS="[1,7,20]", PO="1")),
    ("D.1", "D_1", dict(CONFIG='"D"', ADRS="[0,3,5,6]", FCS="[1,7,20]", PO="2")),
    ("D.2", "D_2", dict(CONFIG='"D"', ADRS="[3,5]", FCS="[1,7,20,65]", PO="2")),
    ("D.3", "D_3", dict(CONFIG='"D"', ADRS="[0,3,5]", FCS="[1,7,20,65]", PO="2", **_bwrite(15))),
    ("D.4", "D_4", dict(CONFIG='"D"', ADRS="[0,3,5,6]", FCS="[1,7,20,65]", PO="1")),
]
# configurations beyond the thesis's rows (not thesis scenarios: the bug catalogue does not count them)
EXTRAS = [
    ("A.1-exceptions", "A_1_exceptions",
     dict(CONFIG='"A"', ADRS="[3,5]", FCS="[4,5,7]", PO="2", FAIL_FCS="[4]",
          EXTRA="[(3, 3, 99, 1), (3, 3, 1, 200), (5, 1, 1, 1), (5, 4, 6, 1)]"),
     "exceptions 01, 02, 03 and 04, and a frame with two faults (code 1 and register 1 at Slave2: 01 first)"),
    ("A.2-with-faults", "A_2_faults", dict(CONFIG='"A"', ADRS="[0,3,5,6]", FCS="[1,7,20]", PO="2", LOSS="1"),
     "a line that also loses one frame"),
    ("D.4-with-faults", "D_4_faults", dict(CONFIG='"D"', ADRS="[0,3,5,6]", FCS="[1,7,20,65]", PO="1", LOSS="1"),
     "a line that also loses one frame"),
]
DEFAULTS = dict(LATE="[1]", CRC="1")


def _explicit(text: str) -> list[tuple]:
    """The frames of an ML list of (address, code, register, quantity), as EXTRA and PRE write them."""
    return [tuple(int(x) for x in part.strip("( ").split(","))
            for part in filter(None, (p.strip(" ,") for p in text.strip()[1:-1].split(")")))]


def _frames(sets: dict) -> list[tuple]:
    slaves = _slaves(sets)
    out = _explicit(sets.get("PRE", "[]"))
    for a in _ints(sets["ADRS"]):
        for c in _ints(sets["FCS"]):
            owners = [s for s in slaves if a in s["adrs"]]
            out.append((a, c, 1 if a == 0 or not owners else owners[0]["regs"][0], 1))
    return out + _explicit(sets.get("EXTRA", "[]"))


def _expected(sets: dict, frame: tuple) -> int:
    """The outcome the specifications require for a frame: -1 no reply (broadcast, absent address, a
    super-request with an error), -2 the SuperSlave's broadcast, else the exception code (0: a normal reply).
    Order of the checks: SL Appendix A and the per-function diagrams of AP (code, quantity, address, execution)."""
    a, c, r, q = frame
    owners = [s for s in _slaves(sets) if a in s["adrs"]]
    if a == 0 or not owners:
        return -1
    s = owners[0]
    e = _request_error(sets, s, frame)
    if s["ss"] and c == 65:
        return -1 if e else -2  # a super-request with an error: no reply (rule 4)
    if e == 0 and c in _ints(sets.get("FAIL_FCS", "[]")):
        return 4
    return e


def _request_error(sets: dict, slave: dict, frame: tuple) -> int:
    """The exception a request raises at a slave before execution (0: none): function code (01), quantity
    (03), register address and range (02), in that order (SL Appendix A, AP's per-function diagrams)."""
    _, c, r, q = frame
    writes = _ints(sets.get("WFCS", "[]"))
    regs = WREGS if c in writes else slave["regs"]
    if c not in slave["fcs"] and c not in writes:
        return 1
    if c in (1, 2, 3, 4, 15, 16) and not 1 <= q <= {1: 2000, 2: 2000, 3: 125, 4: 125, 15: 1968, 16: 123}[c]:
        return 3
    if c in (1, 2, 3, 4, 5, 6, 15, 16, 22, 23) and not (
            r in regs and r + (q - 1 if c in (1, 2, 3, 4, 15, 16) else 0) in regs):
        return 2
    return 0


def _broadcast_writes(sets: dict) -> list[int]:
    """The ids of the master's broadcasts that every slave processes (a code allowed in broadcasts, no
    error at any slave)."""
    slaves = _slaves(sets)
    return [i + 1 for i, f in enumerate(_frames(sets)) if f[0] == 0 and f[1] in BCAST_OK
            and all(_request_error(sets, s, f) == 0 for s in slaves)]


def _q(text: str) -> str:
    return "'''" + text + "'''"


def _properties(name: str, sets: dict) -> list[dict]:
    config = sets["CONFIG"].strip('"')
    slaves = _slaves(sets)
    ns = len(slaves)
    frames = _frames(sets)
    expect = [(f[0], f[1], _expected(sets, f)) for f in frames]
    ml = lambda e: f"~{-e}" if e < 0 else str(e)  # noqa: E731
    expect_ml = "[" + ", ".join(f"({a}, {c}, {ml(e)})" for a, c, e in expect) + "]"
    answered = [i + 1 for i, (_, _, e) in enumerate(expect) if e != -1]
    absent = sorted({a for a, _, e in expect if a != 0 and not any(a in s["adrs"] for s in slaves)})
    props = []

    def add(pname, kind, **fields):
        if STRUCTURAL in pname:
            fields.setdefault("description", STRUCTURAL_WHY)
        props.append(dict(name=pname, kind=kind, **fields))

    add(f"S-P1 (claim 1) {STRUCTURAL}: the master is in one state of Fig. 7", "bound",
        place="Master'State 1", upper_equals=1, lower_equals=1)
    per = " andalso\n".join(
        f"size (Slave'Idle {k}) + size (Slave'Processing {k}) + size (Slave'FormatNormal {k}) + "
        f"size (Slave'FormatError {k}) + size (Slave'WaitEvent {k}) = 1" for k in range(1, ns + 1))
    add(f"S-P1 (claim 1) {STRUCTURAL}: every slave is in one state of Fig. 8", "invariant", expr=per)
    add("S-P2 (claim 2): no new request before the reply, the time-out or the turnaround", "invariant",
        expr="let val d = size (Master'Done 1) in ms_to_col (Master'NextId 1) - 1 <= d + 1 andalso\n"
             "List.all (fn (f : FRAME) => #id f <= d + 1) (ms_to_list (Modbus'm2b 1)) end")
    add("S-P3 (claim 3, S2): a slave acts only on a frame with a good CRC, for one of its addresses or a broadcast",
        "invariant",
        expr="let fun mine (k, f : FRAME) = #ok f andalso (#adr f = 0 orelse mem (#adrs (cfgOf k)) (#adr f))\n"
             "in List.all mine (ms_to_list (sum Slave'Processing)) andalso List.all mine (ms_to_list (sum Slave'FormatNormal))\n"
             "andalso List.all mine (ms_to_list (sum Slave'FormatError)) andalso List.all mine (ms_to_list (sum Slave'WaitEvent)) end")
    add("S-P3 (claim 3): every frame reaches every slave, one reception round at a time (b2s)", "bound",
        place="Modbus'b2s 1", at_most=1)
    add("S-P4: no reply to a broadcast", "invariant",
        expr="let fun ok (f : FRAME) = #src f = 0 orelse #1 (requestOf f) <> 0\n"
             "in List.all ok (ms_to_list (Modbus's2b 1)) andalso List.all ok (ms_to_list (Modbus'b2m 1)) end")
    add("S-P4: a slave processes a broadcast of the master only for a code allowed in broadcasts", "invariant",
        expr="List.all (fn (k, f : FRAME) => #adr f <> 0 orelse #src f <> 0 orelse BCAST_ANY orelse mem BCAST_OK (#fc f))\n"
             "(ms_to_list (sum Slave'Processing))")
    add("S-P5: the master delivers only a good reply that answers its request, with the expected code or exception",
        "invariant",
        expr=f"let val EXPECT = {expect_ml}\n"
             "    (* per frame id: (address, code, outcome); outcome ~1: no reply, ~2: the SuperSlave's broadcast *)\n"
             "    fun ok d = case d of\n"
             "        Answer (i, p) => let val (a, c, e) = List.nth (EXPECT, i - 1) in #ok p andalso\n"
             "          (if e = ~2 then #adr p = 0 andalso #fc p = c\n"
             "           else e >= 0 andalso #adr p = a andalso #exc p = e andalso #fc p = (if e = 0 then c else c + 128)) end\n"
             "      | NoAnswer i => #1 (List.nth (EXPECT, i - 1)) <> 0\n"
             "      | Sent i => #1 (List.nth (EXPECT, i - 1)) = 0\n"
             "in List.all ok (ms_to_list (Master'Done 1)) end")
    add("S-P5: a reply carries the requested address (the slave's own, or the MultiSlave's requested one)",
        "invariant",
        expr="let fun ok (f : FRAME) = #src f = 0 orelse #adr f = 0 orelse #adr f = #1 (requestOf f)\n"
             "in List.all ok (ms_to_list (Modbus's2b 1)) andalso List.all ok (ms_to_list (Modbus'b2m 1)) end")
    add("S-P5: when every slave is prompt, every frame to an existing slave is answered as expected", "reachable",
        expr=f"let val done = ms_to_list (Master'Done 1)\n"
             "    fun answered i = List.exists (fn d => case d of Answer (j, _) => j = i | _ => false) done\n"
             f"in size (Master'Done 1) = NFRAMES andalso List.all answered {answered} end")
    add("S-P6: a frame is sent at most 1 + PO times", "invariant",
        expr="sendsOf (ms_to_col (Master'State 1)) <= PO + 1")
    if absent:
        add(f"S-P6: a frame for the absent address {absent[0]} is sent 1 + PO times, then an error", "reachable",
            expr=f"case ms_to_col (Master'State 1) of ProcError at => #adr (#f at) = {absent[0]} andalso "
                 "#sends at = PO + 1 | _ => false")
    add("S-P7 (claim 4): every dead marking has every frame done once, everything idle and every channel empty",
        "dead_markings",
        expr="Master'Queue 1 = (1`[]) andalso Master'State 1 = (1`Idle) andalso size (Master'Done 1) = NFRAMES andalso\n"
             "List.all (fn i => List.exists (fn d => outId d = i) (ms_to_list (Master'Done 1))) (range (1, NFRAMES)) andalso\n"
             "size (Modbus'm2b 1) + size (Modbus'b2m 1) + size (Modbus's2b 1) + size (Modbus'b2s 1) +\n"
             "size (Master'Timer 1) = 0 andalso forall Slave'Idle (fn m => size m = 1)")
    add("S-P8 (claim 4): no infinite loop (the state space has no cycle)", "no_livelock")
    add(f"S-P9 {STRUCTURAL}: one frame on the line (a node transmits only on a silent line)",
        "bound", expr="size (Modbus'm2b 1) + size (Modbus's2b 1)", at_most=1)
    add("S-P10: the turnaround delay protects a broadcast: no frame reaches a slave still processing one",
        "invariant",
        expr="let val busy = List.map #1 (List.filter (fn (k, g : FRAME) => #adr g = 0) (ms_to_list (sum Slave'Processing)))\n"
             "in List.all (fn (ks, f : FRAME) => #src f <> 0 orelse not (List.exists (fn k => mem busy k) ks))\n"
             "(ms_to_list (Modbus'b2s 1)) end")
    writes = _broadcast_writes(sets)
    if writes:
        add(f"S-P4 (where a broadcast write is sent): every slave processes the broadcast write {writes[0]}",
            "reachable",
            expr=f"List.length (List.filter (fn (k, g : FRAME) => #src g = 0 andalso #id g = {writes[0]})\n"
                 "(ms_to_list (sum Slave'Processing))) = NSLAVES")
    for fact, expr in _dead_facts(sets):
        add(f"{DEAD} {fact}", "invariant", expr=expr)
    if config == "C":
        add("M-P4: the address sets of the nodes are disjoint", "invariant",
            expr="List.all (fn k => List.all (fn l => k = l orelse\n"
                 "List.all (fn a => not (mem (#adrs (cfgOf l)) a)) (#adrs (cfgOf k))) (range (1, NSLAVES))) (range (1, NSLAVES))")
    if config == "D":
        add("SS-P1: a super-request is only ever sent unicast", "invariant",
            expr="case ms_to_col (Master'State 1) of WaitSuper at => #adr (#f at) <> 0 | _ => true")
        add("SS-P2: the SuperSlave answers a super-request only by broadcast, never unicast", "invariant",
            expr="let fun ok (f : FRAME) = let val (a, c, _, _) = requestOf f in\n"
                 "not (#src f = 1 andalso a <> 0 andalso c = SUPER_FC andalso #adr f <> 0) end\n"
                 "in List.all ok (ms_to_list (Modbus's2b 1)) andalso List.all ok (ms_to_list (Modbus'b2m 1)) end")
        add("SS-P3: the SuperSlave's broadcast starts no later than its receipt of the super-request + the tw "
            "the request carries", "invariant",
            expr="(* (id, late) per broadcast started: late iff receipt + tw had passed (a stopwatch set from the\n"
                 "   request's tw at its receipt: under time condensation no property reads the clock) *)\n"
                 "List.all (fn (i, late) => not late) (ms_to_list (sum Slave'SuperStarts))")
        add("SS-P4: while the SuperSlave's broadcast is on the line, the master is waiting for it (t3 = tw + tBC + t2)",
            "invariant",
            expr="List.all (fn (f : FRAME) => #src f = 0 orelse #adr f <> 0 orelse\n"
                 "(case ms_to_col (Master'State 1) of WaitSuper at => #id (#f at) = #id f | _ => false))\n"
                 "(ms_to_list (Modbus's2b 1))")
        add("SS-P5: the master does not transmit while the SuperSlave waits for its event", "invariant",
            expr="size (Modbus'm2b 1) = 0 orelse size (Slave'WaitEvent 1) = 0")
        add("SS-P6: no slave other than the SuperSlave sends a broadcast", "invariant",
            expr="let fun ok (f : FRAME) = #src f = 0 orelse #src f = 1 orelse #adr f <> 0\n"
                 "in List.all ok (ms_to_list (Modbus's2b 1)) andalso List.all ok (ms_to_list (Modbus'b2m 1)) end")
    return props


# the label of a property that holds by the net's structure (a place invariant, the silence token): it
# cannot catch a bug in a guard, a token value or an order of occurrences, so it does not count as
# verification (reports/README.md; the bug catalogue leaves it out)
STRUCTURAL = "[structural]"
STRUCTURAL_WHY = ("holds by the net's structure (a place invariant or the line's silence token): no guard, token "
                  "value or order of occurrences can break it, so it is not counted as verification")
# the label of a protocol fact: a path the configuration excludes never occurs
DEAD = "dead (a protocol fact of the configuration):"


def _dead_facts(sets: dict) -> list[tuple[str, str]]:
    """The protocol paths the scenario's configuration excludes, derived from its frames and slaves (not
    from a state space): (what, a state predicate that the paths' transitions are never enabled)."""
    frames, slaves = _frames(sets), _slaves(sets)
    never = lambda ts: " andalso ".join(f'not (enabled "{t}")' for t in ts)  # noqa: E731
    supers = [f for f in frames if f[1] == 65 and f[0] != 0 and any(s["ss"] and f[0] in s["adrs"] for s in slaves)]
    out = []
    if not any(f[0] == 0 for f in frames):
        out.append(("no broadcast in the frames: the master never sends one (M2) nor waits its turnaround (M3)",
                    never(["Master'SendBroadcast", "Master'TurnaroundExpired"])))
    if not _broadcast_writes(sets) and sets.get("BCAST_ANY", "false") != "true" and not supers:
        out.append(("the frames' broadcasts are read codes, dropped unprocessed, and no SuperSlave broadcasts: "
                    "no slave processes a broadcast (S6)", never(["Slave'AcceptBroadcast", "Slave'EndBroadcast"])))
    if not supers:
        out.append(("no super-request to a SuperSlave: the master never waits t3, no SuperSlave opens a window",
                    never(["Master'SendSuper", "Slave'AcceptSuper", "Slave'SendSuperBroadcast"])))
    if not _ints(sets.get("FAIL_FCS", "[]")):
        out.append(("no execution fails: no exception 04 (S7)", never(["Slave'ProcessingError"])))
    if sets.get("LOSS", "0") == "0":
        out.append(("the line loses no frame", never(["Bus'LoseMaster", "Bus'LoseSlave"])))
    return out


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    return _q(v) if "\n" in v or "'" in v or '"' in v else f'"{v}"'


def spec_text(name: str, sets: dict, description: str, model: str = MODEL_REL, mutant: str | None = None,
              expect_violated=(), props=None) -> str:
    sets = {**DEFAULTS, **sets}
    if mutant:
        sets["MUTANT"] = f'"{mutant}"'
    how = "--mutants --write-mutants" if mutant or "mutant" in name else "--write-specs"
    lines = [f"# {name}: written by `python bench/modbus.py {how}` (do not edit by hand).",
             "# Choices where the seed is silent (MODBUS.md 3.6) are in models/modbus/modbus.cpnet; here:",
             "# frames every pair address x code in list order (register: the first of the owner, quantity 1);",
             "# RESP_TO 1000, TURNAROUND 200, TPROC {1, 50} ms and TLATE 1010 ms (beyond the time-out) for the",
             f"# slave(s) LATE = {sets['LATE']}; the line may corrupt CRC = {sets['CRC']} frame(s); 11-bit characters at 9600 baud;",
             "# broadcasts take TPROC_BC {1, 50} ms; the SuperSlave's work {50, tw, tw + 10, tw + t2 + 10} ms, tw = 210 ms",
             "# carried in the super-request" + (f"; first the broadcast write PRE = {sets['PRE']}, which every slave"
                                                 f" processes (WFCS = {sets['WFCS']})." if "PRE" in sets else "."),
             f'name = "{name}"', f'model = "{model}"', f'description = "{description}"', "", "[set]"]
    for k, v in sets.items():
        lines.append(f"{k} = {_toml_value(v)}")
    lines += ["", "[explore]", "time_condensation = true", "max_seconds = 600", ""]
    for p in props if props is not None else _properties(name, sets):
        lines.append("[[property]]")
        for key in ("name", "description", "kind", "place", "expr", "upper_equals", "lower_equals", "at_most"):
            if key in p:
                lines.append(f"{key} = {_toml_value(p[key])}")
        if p["name"] in expect_violated:
            lines.append('expect = "violated"  # the bug of this mutant must break it')
        lines.append("")
    return "\n".join(lines)


def write_specs() -> None:
    folder = os.path.join(ROOT, "specs", "modbus")
    for name, stem, sets in SCENARIOS:
        figs = THESIS_FIGURES[name]
        first = f"the broadcast write {sets['PRE'][1:-1]}, then " if "PRE" in sets else ""
        desc = (f"Thesis scenario {name} (MODBUS.md 3.5): frames {first}{sets['ADRS']} x {sets['FCS']} in list order, "
                f"PO {sets['PO']}. Thesis: {figs[0]} nodes, {figs[1]} dead markings, {figs[2]}.")
        with open(os.path.join(folder, stem + ".toml"), "w", encoding="utf-8") as fh:
            fh.write(spec_text(name, sets, desc))
    for name, stem, sets, what in EXTRAS:
        with open(os.path.join(folder, stem + ".toml"), "w", encoding="utf-8") as fh:
            fh.write(spec_text(name, sets, f"{name}: {what}."))


# ---------------------------------------------------------------- the bug catalogue (specs/modbus/mutants/)
# (switch, the bug as a firmware engineer would write it, where the rule comes from); each is a value of the
# model's MUTANT, a switch of the real model, run against the full, unchanged property set of the thesis's
# scenarios by `python bench/modbus.py --mutants`
MUTANTS = [
    ("no-address-filter", "a slave answers frames for any address (its own address check removed)", "SL 2.4.2 S2"),
    ("slave-ignores-crc", "a slave acts on a frame with a CRC error", "SL 2.4.2 S2, 2.6"),
    ("master-any-reply", "the master accepts a reply from any slave as the expected one", "SL 2.4.1 M4/M5"),
    ("master-adr-only", "the master checks the reply's address but not its function code",
     "SL 2.4.1 M5, AP 4.1"),
    ("master-ignores-crc", "the master accepts a corrupted reply", "SL 2.4.1 M8"),
    ("master-no-exception", "the master does not take an exception reply as the answer", "SL 2.4.1, AP 7"),
    ("early-send", "the master sends the next request without waiting for the reply or the time-out",
     "SL 2.4.1 (claim 2)"),
    ("retry-off-by-one", "the master retries PO + 1 times (<= instead of <)", "SL 2.4.1 retries"),
    ("no-retry", "the master never retries", "SL 2.4.1 retries"),
    ("timeout-from-send", "the response time-out is started without the slave's processing time (0 ms)",
     "SL 2.4.1 response time-out"),
    ("short-turnaround", "1 ms turnaround delay after a broadcast", "SL 2.4.1 turnaround"),
    ("bcast-reply", "a slave answers a broadcast it has processed (with its own address in the reply)", "SL 2.1"),
    ("bcast-exception", "a slave sends an exception reply to a broadcast with an error", "SL 2.1, App. A"),
    ("bcast-any-code", "a slave processes a broadcast of a read code", "SL 2.1, App. A"),
    ("busy-slave-queues", "a busy slave queues the frames that arrive while it processes", "SL 2.4.2 Fig. 8"),
    ("exc-order", "exception checks in the wrong order (register before function code)", "SL App. A, AP 6"),
    ("reply-own-address", "a MultiSlave replies with its first address, not the requested one",
     "mMODBUS rule 4"),
    ("super-as-unicast", "the master sends a super-request as an ordinary unicast and waits for a reply",
     "mMODBUS master rules 2-3"),
    ("unicast-super", "the SuperSlave answers a super-request by unicast", "mMODBUS SuperSlave rule 4"),
    ("late-super", "the SuperSlave ignores the end of its window tw and sends when its work is done",
     "mMODBUS SuperSlave rule 2b"),
    ("super-window-long", "the SuperSlave's window is 30 ms longer than tw", "mMODBUS SuperSlave rule 2a"),
    ("super-no-t2", "the master ignores t2 after the SuperSlave's broadcast", "mMODBUS t3 = tw + tBC + t2"),
    ("exc-no-0x80", "a slave's exception reply carries the plain function code (the 0x80 bit missing)", "AP 7"),
    ("bcast-as-unicast", "the master treats a broadcast as a unicast (waits for a reply, retries)", "SL 2.4.1 M2"),
    ("timer-not-stopped", "the response timer is not stopped when the reply arrives", "SL 2.4.1 M5"),
    ("multislave-first-only", "a MultiSlave accepts only its first address", "mMODBUS rule 2a"),
    ("bcast-super", "the master sends a super-request (0, 65) to the broadcast address", "mMODBUS master rule 2"),
    ("slave-silent-on-error", "a slave does not answer a request with an error (no exception reply)",
     "SL 2.4.2 S4, AP 7"),
    ("t3-short", "t3 = tw + tBC - 1, shorter than tw + tBC + t2", "mMODBUS eq. (1)"),
    ("overlapping-addresses", "the MultiSlave's address set overlaps Slave1's ([3, 5])", "mMODBUS implicit rule"),
]
# a bug that is a value of the model's parameters rather than a switch
PARAM_MUTANTS = {"t3-short": {"T3": "TW + TBC - 1"}, "overlapping-addresses": {"S2ADRS": "[3,5]"}}
MUTANT_BUDGET = 5  # seconds of search per mutant and scenario; a mutant whose state space is larger is
# judged on the part searched (a violation found there is real, the cell marked '*'; '?' where nothing
# was found in time)


def _short(name: str) -> str:
    return name.split(" ")[0].rstrip(":")


def _mutant_values(mutant: str) -> dict:
    return PARAM_MUTANTS.get(mutant, {"MUTANT": f'"{mutant}"'})


def write_mutant_on(mutant: str, stem: str) -> None:
    """Write specs/modbus/mutants/MUTANT.toml on the scenario file STEM (a complete search, no budget): for a
    mutant whose table searches stop at the budget, or one that only an extra configuration catches."""
    from cpn.checks.verdict import Status
    from cpn.gate.run import run_scenario
    from cpn.gate.scenario import load_scenario

    (name, sets) = [(n, v) for n, st, v, *_ in SCENARIOS + EXTRAS if st == stem][0]
    bug = [b for m, b, _ in MUTANTS if m == mutant][0]
    folder = os.path.join(ROOT, "specs", "modbus")
    scenario = load_scenario(os.path.join(folder, stem + ".toml"))
    base = scenario.runs[0]
    result = run_scenario(scenario, type(base)(base.name, base.params, {**base.values, **_mutant_values(mutant)}))
    assert result.exploration.complete, mutant
    broken = {r.spec.name for r in result.results if r.verdict.status is Status.VIOLATED}
    assert any(STRUCTURAL not in b for b in broken), mutant
    print(mutant, stem, sorted(_short(b) for b in broken), f"{result.exploration.n_states:,} states")
    text = spec_text(f"{name} mutant {mutant}", {**sets, **PARAM_MUTANTS.get(mutant, {})},
                     f"Bug: {bug}. Scenario {name}, its full property set; the bug breaks the properties "
                     "marked expect = violated.", model="../" + MODEL_REL,
                     mutant=None if mutant in PARAM_MUTANTS else mutant, expect_violated=broken,
                     props=_properties(name, {**DEFAULTS, **sets}))
    with open(os.path.join(folder, "mutants", mutant + ".toml"), "w", encoding="utf-8") as fh:
        fh.write(text)


def run_mutants(write: bool, only: list[str] | None = None, columns: list[str] | None = None) -> None:
    """Every mutant against every thesis scenario (the full property set of the scenario file, in this
    process): the properties violated and the shortest trace; with write, a file per caught mutant in
    specs/modbus/mutants/ (the first thesis scenario that catches it, its properties unchanged)."""
    from cpn.checks.verdict import Status
    from cpn.gate.run import run_scenario
    from cpn.gate.scenario import load_scenario

    folder = os.path.join(ROOT, "specs", "modbus")
    print("| mutant | bug | " + " | ".join(n for n, _, _ in SCENARIOS) + " |")
    print("|---|---|" + "---|" * len(SCENARIOS))
    for mutant, bug, _ in MUTANTS:
        if only and mutant not in only:
            continue
        cells, first = [], None
        for name, stem, sets in SCENARIOS:
            if columns and name not in columns:
                continue
            scenario = load_scenario(os.path.join(folder, stem + ".toml"))
            base = scenario.runs[0]
            run = type(base)(base.name, base.params, {**base.values, **_mutant_values(mutant)})
            result = run_scenario(scenario, run, {"max_seconds": MUTANT_BUDGET})
            every = [r for r in result.results if r.verdict.status is Status.VIOLATED]
            # a property that holds by the net's structure does not count as catching a bug
            violated = [r for r in every if STRUCTURAL not in r.spec.name]
            if not violated:
                cells.append("-" if result.exploration.complete else "?")
                continue
            best = []
            for r in violated:
                ev = r.verdict.evidence
                steps = len(ev.path) - 1 if ev is not None and getattr(ev, "path", None) else None
                best.append((steps if steps is not None else 10 ** 9, _short(r.spec.name), r.spec.name))
            best.sort()
            names = sorted({b[1] for b in best})
            steps = best[0][0]
            complete = result.exploration.complete
            cells.append(", ".join(names) + (f" ({steps})" if steps < 10 ** 9 else "") + ("" if complete else " *"))
            if first is None and complete:  # the gate needs a complete search: every verdict decided
                first = (name, stem, sets, {r.spec.name for r in every})
        print(f"| {mutant} | {bug} | " + " | ".join(cells) + " |", flush=True)
        if write and first is not None:
            name, stem, sets, broken = first
            text = spec_text(f"{name} mutant {mutant}", {**sets, **PARAM_MUTANTS.get(mutant, {})},
                             f"Bug: {bug}. Thesis scenario {name}, its full property set; the bug breaks the "
                             "properties marked expect = violated.", model="../" + MODEL_REL,
                             mutant=None if mutant in PARAM_MUTANTS else mutant, expect_violated=broken,
                             props=_properties(name, {**DEFAULTS, **sets}))
            with open(os.path.join(folder, "mutants", mutant + ".toml"), "w", encoding="utf-8") as fh:
                fh.write(text)


# the protocol paths of SL Figs. 7 and 8 (MODBUS.md 1.3, 1.4) and the model's transitions that take them
PATHS = [
    ("M1", ["Master'SendUnicast", "Master'SendSuper"]), ("M2", ["Master'SendBroadcast"]),
    ("M3", ["Master'TurnaroundExpired", "Master'T2Expired"]), ("M4", ["Master'ReplyUnexpected", "Master'SuperUnexpected"]),
    ("M5", ["Master'ReplyExpected", "Master'SuperAnswer", "Master'SuperException"]),
    ("M6", ["Master'ResponseTimeout", "Master'SuperTimeout"]), ("M7", ["Master'EndReply"]),
    ("M8", ["Master'FrameError"]), ("M9", ["Master'Retry", "Master'GiveUp"]),
    ("S2", ["Slave'Discard"]), ("S3", ["Slave'AcceptUnicast", "Slave'AcceptBroadcast", "Slave'AcceptSuper"]),
    ("S4", ["Slave'RejectUnicast", "Slave'RejectBroadcast", "Slave'RejectSuper"]), ("S5", ["Slave'EndUnicast"]),
    ("S6", ["Slave'EndBroadcast"]), ("S7", ["Slave'ProcessingError"]), ("S8", ["Slave'SendNormal"]),
    ("S9", ["Slave'SendError"]), ("busy", ["Slave'Lost"]),
]


def coverage() -> None:
    """Which paths of SL Figs. 7 and 8 each thesis scenario exercises (a transition that occurs in its state
    space); S1, a reception, is every S2-S4 and the busy slave's loss."""
    from cpn.gate.run import run_scenario
    from cpn.gate.scenario import load_scenario

    print("| scenario | " + " | ".join(p for p, _ in PATHS) + " |")
    print("|---|" + "---|" * len(PATHS))
    for name, stem, _ in SCENARIOS + [(n, s, v) for n, s, v, _ in EXTRAS]:
        scenario = load_scenario(os.path.join(ROOT, "specs", "modbus", stem + ".toml"))
        r = run_scenario(scenario, scenario.runs[0])
        g, engine = r.exploration.graph, r.engine
        fired = {engine.transitions[engine.binding_element(be).transition].name.rsplit(" ", 1)[0] for be in g.bes}
        print(f"| {name} | " + " | ".join("x" if fired & set(ts) else "-" for _, ts in PATHS) + " |", flush=True)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--scaling", action="store_true")
    ap.add_argument("--table", action="store_true")
    ap.add_argument("--sweep", action="store_true", help="the sweep-line against the full search (scenario B)")
    ap.add_argument("--sweep-thesis", action="store_true",
                    help="the sweep-line against the full search on the thesis scenarios and the fault variants")
    ap.add_argument("--sweep-memo", metavar="K", type=int, default=None,
                    help="one sweep-line run (NS 10, K broadcasts) with the engine's memo tables emptied, then kept")
    ap.add_argument("--memo-child", choices=("emptied", "kept"), default=None, help=argparse.SUPPRESS)
    ap.add_argument("--ns", default="4,6,8,10,12,14,16", help="--sweep: the numbers of slaves (default 4,6,...,16)")
    # the initial FRAMES (recursive CPN ML functions) loads with 1,034 frames too (k = 1024, measured)
    ap.add_argument("--ks", default="1,4,16,64,128",
                    help="--sweep: the numbers of broadcasts at NS 10 (default 1,4,16,64,128)")
    ap.add_argument("--full-max-memory", type=float, default=4096,
                    help="--sweep: the full search's --max-memory in MiB (default 4096, on a shared machine)")
    ap.add_argument("--symmetry", action="store_true",
                    help="broadcasts to NS slaves: modbus.cpnet against the symmetry-reduced module-instance variant")
    ap.add_argument("--sym-ns", default="4,8,12,16,24,32,48,64,96,128",
                    help="--symmetry: the numbers of slaves (modbus.cpnet up to its 16 instances)")
    ap.add_argument("--sym-ks", default="1,4,16,64", help="--symmetry: the numbers of broadcasts at NS 16")
    ap.add_argument("--budget", type=float, default=600.0, help="seconds of generation per run (default 600)")
    ap.add_argument("--native", action="store_true", help="timed nets: the native search against the Python search")
    ap.add_argument("--native-check", action="store_true",
                    help="check specs/modbus with and without the native search of timed nets")
    ap.add_argument("--write-specs", action="store_true",
                    help="write the thesis's scenario files and the extra configurations of specs/modbus")
    ap.add_argument("--mutants", action="store_true",
                    help="every mutant of the bug catalogue against every thesis scenario (the table of reports/README.md)")
    ap.add_argument("--write-mutants", action="store_true", help="with --mutants: write specs/modbus/mutants/")
    ap.add_argument("--only", default="", help="with --mutants: these mutants only (comma-separated)")
    ap.add_argument("--columns", default="", help="with --mutants: these thesis scenarios only (comma-separated)")
    ap.add_argument("--coverage", action="store_true",
                    help="the paths of SL Figs. 7 and 8 each thesis scenario exercises (reports/README.md)")
    ap.add_argument("--write-mutant", nargs=2, metavar=("MUTANT", "STEM"),
                    help="write one mutant file on the scenario file STEM, after a complete search")
    a = ap.parse_args(argv)
    if a.write_mutant:
        write_mutant_on(*a.write_mutant)
        return 0
    if a.coverage:
        coverage()
        return 0
    if a.mutants:
        run_mutants(a.write_mutants, [m for m in a.only.split(",") if m] if a.only else None,
                    [c for c in a.columns.split(",") if c] if a.columns else None)
        return 0
    if a.write_specs:
        write_specs()
        return 0
    if a.native_check:
        native_check(a.repeat)
        return 0
    if a.native:
        native_timed(a.repeat)
        return 0
    if a.table:
        table(a.budget)
        return 0
    if a.sweep_thesis:
        sweep_thesis()
        return 0
    if a.sweep_memo is not None:
        if a.memo_child is not None:
            sweep_memo(a.sweep_memo, a.memo_child == "emptied")
            return 0
        for how in ("emptied", "kept"):  # each in a fresh process: its peak memory is its own
            subprocess.run([sys.executable, __file__, "--sweep-memo", str(a.sweep_memo), "--memo-child", how],
                           check=True)
        return 0
    if a.symmetry:
        symmetry_scaling(a.budget, [int(n) for n in a.sym_ns.split(",") if n],
                         [int(k) for k in a.sym_ks.split(",") if k], a.full_max_memory)
        return 0
    if a.sweep:
        sweep_scaling(a.budget, [int(n) for n in a.ns.split(",") if n], [int(k) for k in a.ks.split(",") if k],
                      a.full_max_memory)
        return 0
    if a.scaling:
        scaling_b(a.budget)
        print()
        scaling_modbus_a_explore(a.budget)
        print()
        scaling_modbus_a(a.budget)
        return 0
    try:
        load = os.getloadavg()[0]
    except OSError:
        load = float("nan")
    print(f"load average at start: {load:.1f}; {os.cpu_count()} CPUs")
    med, runs = timed_check(THESIS, a.repeat)
    print(f"check of the {len(THESIS)} thesis scenarios A.1-D.4: median {med:.1f} s "
          f"(runs: {', '.join(f'{s:.1f}' for s in runs)})")
    med, runs = timed_check(["specs/modbus"], a.repeat)
    print(f"check of all of specs/modbus: median {med:.1f} s (runs: {', '.join(f'{s:.1f}' for s in runs)})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
