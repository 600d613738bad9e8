"""The sweep-line method from the command line (`explore --sweep-line`, `--progress`)
and in scenarios (`sweep_line = true`, `progress = "..."`): the same counts, dead markings, bounds and
verdicts as the full search, the properties that need the graph unknown with the reason."""

import json
import os

import cpn
from cpn.cli.main import main
from cpn.gate.run import run_scenario
from cpn.gate.scenario import load_scenario
from cpn.statespace import ExploreOptions, Explorer
from tests.engine.randomnets import random_timed_net

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TIMER = os.path.join(ROOT, "models", "examples", "timer_cancel.cpnet")
MODBUS = os.path.join(ROOT, "models", "modbus", "modbus.cpnet")
B8 = ["--set", 'CONFIG="B"', "--set", "NS=8", "--set", "ADRS=[0,1,2,3,4,5,6,7,8]", "--set", "FCS=[1]", "--set", "PO=1"]


def test_explore_sweep_line_json_equals_the_full_search(tmp_path):
    assert main(["explore", TIMER, "-q", "--json", str(tmp_path / "full.json")]) == 0
    assert main(["explore", TIMER, "-q", "--sweep-line", "--json", str(tmp_path / "sweep.json")]) == 0
    full = json.loads((tmp_path / "full.json").read_text(encoding="utf-8"))
    sweep = json.loads((tmp_path / "sweep.json").read_text(encoding="utf-8"))
    st = sweep["statespace"]
    assert (st["states"], st["arcs"], st["complete"]) == (full["statespace"]["states"], full["statespace"]["arcs"], True)
    assert st["method"] == "sweep-line" and st["exact"] and st["progress_measure"] == "the global clock"
    assert 0 < st["peak_states"] < st["states"]
    assert sweep["bounds"] == full["bounds"] and sweep["multiset_bounds"] == full["multiset_bounds"]
    assert sweep["dead_markings"]["count"] == full["dead_markings"]["count"] == 3
    assert sweep["scc"] is None and sweep["home_markings"] is None and "scc" in sweep["not_available"]


def test_explore_sweep_line_text_report(capsys):
    assert main(["explore", TIMER, "--sweep-line"]) == 0
    out = capsys.readouterr().out
    assert "State Space (sweep-line)" in out and "Nodes:  12" in out and "Peak nodes held in memory: 5" in out
    assert "Dead Markings: 3" in out and "no trace" in out and "Home Markings: not available" in out


def test_explore_progress_measure_under_time_condensation(tmp_path, capsys):
    # the MODBUS scenarios are condensed: the clock is no measure there, the number of frames the master
    # has done is one (it never decreases), and the counts are those of the full condensed search
    assert main(["explore", MODBUS, *B8, "--time-condensation", "-q", "--json", str(tmp_path / "f.json")]) == 0
    assert main(["explore", MODBUS, *B8, "--time-condensation", "-q", "--progress",
                 "size (Master'Done 1)", "--json", str(tmp_path / "s.json")]) == 0
    full = json.loads((tmp_path / "f.json").read_text(encoding="utf-8"))["statespace"]
    sweep = json.loads((tmp_path / "s.json").read_text(encoding="utf-8"))["statespace"]
    assert (sweep["states"], sweep["arcs"], sweep["regress_arcs"]) == (full["states"], full["arcs"], 0) == (883, 1042, 0)
    assert sweep["peak_states"] < sweep["states"]


def test_explore_sweep_line_refusals(tmp_path, capsys):
    assert main(["explore", MODBUS, *B8, "--time-condensation", "--sweep-line"]) == 64
    assert "cannot use the clock under time condensation" in capsys.readouterr().err
    model = tmp_path / "u.cpnet"
    model.write_text("colset U = unit; place A : U = 1`(); trans t; arc A -> t;", encoding="utf-8")
    assert main(["explore", str(model), "--sweep-line"]) == 64
    assert "untimed" in capsys.readouterr().err
    assert main(["explore", TIMER, "--sweep-line", "--dot", str(tmp_path / "g.dot")]) == 64
    assert "--dot cannot be combined with --sweep-line" in capsys.readouterr().err
    assert main(["explore", TIMER, "--sweep-line", "--workers", "2"]) == 64
    assert "--workers cannot be combined with --sweep-line" in capsys.readouterr().err
    assert main(["explore", TIMER, "--progress", "size (TimerCancel'Sendz 1)"]) == 65
    err = capsys.readouterr().err
    assert "--progress:1:7: error[E0703]: no place 'TimerCancel'Sendz'" in err and "^" in err
    assert "Did you mean the place 'TimerCancel'Sends'?" in err


SCENARIO = """model = "{model}"
[set]
CONFIG = '"A"'
ADRS = "[3,5]"
FCS = "[4,5,7]"
PO = "2"

[explore]
time_condensation = true
{extra}

[[property]]
name = "one master state"
kind = "bound"
place = "Master'State 1"
upper = 1
lower = 1

[[property]]
name = "one frame on the line"
kind = "invariant"
expr = "size (Modbus'm2b 1) + size (Modbus's2b 1) <= 1"

[[property]]
name = "a frame on the line"
kind = "reachable"
expr = "size (Modbus'm2b 1) + size (Modbus's2b 1) = 1"

[[property]]
name = "one dead marking"
kind = "dead_markings"
count = 1
count_modulo_time = 1

[[property]]
name = "the master is busy (wrong on purpose)"
kind = "invariant"
expr = "size (Master'NextId 1) = 0"

[[property]]
name = "no cycle"
kind = "no_livelock"

[[property]]
name = "home"
kind = "home"
"""


def _runs(tmp_path, extra):
    path = tmp_path / "s.toml"
    path.write_text(SCENARIO.format(model=MODBUS, extra=extra), encoding="utf-8")
    scenario = load_scenario(str(path))
    return run_scenario(scenario, scenario.runs[0])


def test_scenario_sweep_line_decides_what_it_can(tmp_path):
    full = _runs(tmp_path, "")
    sweep = _runs(tmp_path, "sweep_line = true\nprogress = \"size (Master'Done 1)\"")
    x = sweep.exploration
    assert (x.states, x.arcs, x.exact, len(x.dead)) == (full.exploration.n_states, full.exploration.n_arcs, True, 1)
    got = [r.verdict.status.value for r in sweep.results]
    assert got == [r.verdict.status.value for r in full.results][:5] + ["unknown", "unknown"]
    assert got[:5] == ["holds", "holds", "holds", "holds", "violated"]
    assert "no trace" in sweep.results[4].verdict.message and sweep.results[4].verdict.evidence is None
    assert "not available under the sweep-line method" in sweep.results[5].verdict.message


def test_check_cli_sweep_line_report(tmp_path, capsys):
    path = tmp_path / "s.toml"
    path.write_text(SCENARIO.format(model=MODBUS, extra=""), encoding="utf-8")
    status = main(["check", str(path), "--sweep-line", "--progress", "size (Master'Done 1)",
                   "--reports", str(tmp_path / "r"), "--no-timings"])
    assert status == 1  # the property that is wrong on purpose
    doc = json.loads((tmp_path / "r" / "s.json").read_text(encoding="utf-8"))
    assert doc["statespace"]["method"] == "sweep-line" and doc["statespace"]["exact"]
    assert doc["dead_markings"]["count"] == 1 and doc["bounds"]["Master'State 1"] == {"upper": 1, "lower": 1}
    assert "sweep-line, exact counts" in (tmp_path / "r" / "s.txt").read_text(encoding="utf-8")


def test_scenario_sweep_line_options_are_checked(tmp_path, capsys):
    path = tmp_path / "s.toml"
    path.write_text(SCENARIO.format(model=MODBUS, extra="progress = \"1\""), encoding="utf-8")
    assert main(["check", str(path), "--no-reports"]) == 65
    assert "error[E0702]: 'progress' is the sweep-line method's progress measure" in capsys.readouterr().err
    path.write_text(SCENARIO.format(model=MODBUS, extra="sweep_line = true\nreduction = \"stubborn\""),
                    encoding="utf-8")
    assert main(["check", str(path), "--no-reports"]) == 65
    assert "'sweep_line' cannot be combined with 'reduction'" in capsys.readouterr().err
    path.write_text(SCENARIO.format(model=MODBUS, extra="sweep_line = true\nprogress = \"Master'State 1\""),
                    encoding="utf-8")
    assert main(["check", str(path), "--no-reports"]) == 65
    assert "s.toml:11:13: error[" in capsys.readouterr().err  # the measure's type error, in the file


RANDOM = """model = "n.cpnet"
[explore]
{extra}
max_states = 3000

[[property]]
kind = "invariant"
expr = "size (Top'p0 1) <= 1"

[[property]]
kind = "invariant"
expr = "size (Top'p1 1) + size (Top'p0 1) <= 2"

[[property]]
kind = "reachable"
expr = "size (Top'p1 1) = 0"

[[property]]
kind = "deadlock_free"

[[property]]
kind = "bound"
place = "Top'p0 1"
upper = 1
lower = 0
"""


def test_random_timed_nets_verdicts_equal_the_full_search(tmp_path):
    compared = 0
    for seed in range(40):
        text = random_timed_net(seed)
        # the finite ones have at most 256 states (seeds 0..59): past 500 the state space has no end
        if not Explorer(cpn.loads(text).engine(), ExploreOptions(max_states=500, backend="python")).run().complete:
            continue
        (tmp_path / "n.cpnet").write_text(text, encoding="utf-8")
        verdicts = []
        for extra in ("", "sweep_line = true"):
            (tmp_path / "s.toml").write_text(RANDOM.format(extra=extra), encoding="utf-8")
            scenario = load_scenario(str(tmp_path / "s.toml"))
            r = run_scenario(scenario, scenario.runs[0])
            verdicts.append([p.verdict.status.value for p in r.results])
        assert verdicts[0] == verdicts[1], f"random timed net {seed}:\n{text}"
        compared += 1
    assert compared >= 12


def test_check_html_skips_the_page_of_a_sweep_line_run(tmp_path, capsys):
    path = tmp_path / "s.toml"
    path.write_text(SCENARIO.format(model=MODBUS, extra=""), encoding="utf-8")
    status = main(["check", str(path), "--sweep-line", "--progress", "size (Master'Done 1)",
                   "--no-reports", "--html", str(tmp_path / "h")])
    assert status == 1 and (tmp_path / "h").is_dir()
