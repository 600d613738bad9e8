"""Every mutant of specs/modbus/mutants/ is caught by `check`, by the
properties its file marks (and by no other property of its file), with a shortest counterexample. The
MODBUS mutants are the bug catalogue of bench/modbus.py (MUTANTS), each run against the full, unchanged
property set of a thesis scenario; the Modbus-A ones are the fault variants of MODBUS.md 4.5."""

import importlib.util
import os
import tomllib

import pytest

from cpn.checks.verdict import Status
from cpn.gate.run import run_scenario
from cpn.gate.scenario import load_scenario
from tests._graphs import bfs_distances

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MUTANTS = os.path.join(ROOT, "specs", "modbus", "mutants")
_spec = importlib.util.spec_from_file_location("bench_modbus", os.path.join(ROOT, "bench", "modbus.py"))
bench = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(bench)

# Modbus-A file -> the MODBUS.md properties its fault breaks (MODBUS.md 4.5)
BROKEN_MA = {
    "ma_forward_config": {"MA3"},
    "ma_E1_reset_race": {"MA2", "MA3"},
    "ma_E2_config_lost": {"MA2"},
    "ma_E2_config_lost_next": {"MA2"},
    "ma_E3_ack_lost_stop": {"MA2"},
    "ma_E3_ack_lost_same": {"MA3"},
    "ma_E3_ack_lost_next": {"MA5", "MA7"},
    "ma_E4_max_id": {"MA2"},
    "ma_E5_no_reset": {"MA2", "MA3"},
    "ma_E6_hung": {"MA2"},
    "ma_E6_mute": {"MA2"},
    "ma_reserved_ids": {"MA2", "MA6", "MA7"},
}
# catalogue bugs without a file (findings, reports/README.md): none; super-window-long (caught by SS-P3, a
# timing property) and bcast-reply (caught where every slave processes a broadcast write) have theirs
NOT_CAUGHT: set[str] = set()
CAUGHT_ON_PARTIAL_SEARCHES_ONLY: set[str] = set()
CATALOGUE = [m for m, _, _ in bench.MUTANTS]
# the MODBUS/TCP mutants (tcp_*.toml) are bench/modbus_tcp.py's, checked by tests/modbus/test_modbus_tcp.py
FILES = sorted(f[:-5] for f in os.listdir(MUTANTS) if f.endswith(".toml") and not f.startswith("tcp_"))


def test_every_mutant_file_is_listed():
    assert set(FILES) == set(BROKEN_MA) | (set(CATALOGUE) - NOT_CAUGHT - CAUGHT_ON_PARTIAL_SEARCHES_ONLY)
    assert len(CATALOGUE) >= 30


def _violated(name):
    scenario = load_scenario(os.path.join(MUTANTS, name + ".toml"))
    (run,) = scenario.runs
    result = run_scenario(scenario, run)
    assert result.exploration.complete
    return result, [r for r in result.results if r.verdict.status is Status.VIOLATED]


@pytest.mark.parametrize("name", sorted(set(FILES) - set(BROKEN_MA)))
def test_catalogue_mutant_runs_a_thesis_scenario_with_its_full_property_set(name):
    with open(os.path.join(MUTANTS, name + ".toml"), "rb") as fh:
        mutant = tomllib.load(fh)
    thesis_name = mutant["name"].split(" mutant ")[0]
    # a thesis scenario, or (exc-order, whose bug needs a frame with two faults) an extra configuration
    (stem,) = [stem for n, stem, *_ in bench.SCENARIOS + bench.EXTRAS if n == thesis_name]
    with open(os.path.join(ROOT, "specs", "modbus", stem + ".toml"), "rb") as fh:
        thesis = tomllib.load(fh)
    strip = [{k: v for k, v in p.items() if k != "expect"} for p in mutant["property"]]
    assert strip == thesis["property"]  # the thesis's properties, unchanged
    values = {k: v for k, v in mutant["set"].items() if k != "MUTANT"}
    changed = {k for k in set(values) | set(thesis["set"]) if values.get(k) != thesis["set"].get(k)}
    assert changed <= set(bench.PARAM_MUTANTS.get(name, {}))
    assert mutant["set"].get("MUTANT", f'"{name}"') == f'"{name}"'


@pytest.mark.parametrize("name", FILES)
def test_mutant_is_caught_by_the_property_it_breaks(name):
    result, violated = _violated(name)
    if name in BROKEN_MA:
        assert {r.spec.name.split(" ")[0].rstrip(":") for r in violated} == BROKEN_MA[name]
    assert violated
    # every violation is one the file expects (the gate passes), and nothing else fails
    assert all(r.spec.expect == "violated" for r in violated)
    assert result.status is Status.HOLDS
    dist = None
    for r in violated:
        if r.spec.kind == "reachable":  # a witness that does not exist: no trace to show
            continue
        ev = r.verdict.evidence
        assert ev is not None and ev.path[0] == 0, r.spec.name
        if r.spec.kind in ("invariant", "bound"):  # decided on the fly: the shortest trace to a bad marking
            dist = dist or bfs_distances(result.exploration.graph)
            assert len(ev.path) - 1 == dist[ev.path[-1]], r.spec.name


def test_modbus_a_properties_evaluate_on_long_chains():
    # MA2/MA4 were recursive CPN ML functions over the chain: past about 80 slaves the evaluation failed
    # ('maximum recursion depth exceeded'); they are now List.all over List.tabulate
    scenario = load_scenario(os.path.join(ROOT, "specs", "modbus", "modbus_a.toml"))
    base = scenario.runs[0]
    run = type(base)("Modbus-A[N=100]", {"N": 100}, {**base.values, "N": 100, "MAXN": 100})
    result = run_scenario(scenario, run, {"max_states": 300})
    assert all(r.verdict.status is not Status.ERROR for r in result.results)
    assert {r.verdict.status for r in result.results} == {Status.UNKNOWN}  # a partial search holds nothing
