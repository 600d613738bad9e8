"""The native timed search on the MODBUS models (`models/modbus/`) with the constants of the gate's scenario
files: the graph must be the Python search's own (tests/statespace/test_native_timed.py says what is
compared), and where every transition is in the net's generated C the engine expands no state. In a file
of its own so that the suite's workers share the compilations (each scenario's C is built anew)."""

import glob
import os
import tomllib

import pytest

import cpn
from cpn.engine import ccodegen
from cpn.statespace import ExploreOptions, Explorer
from tests.engine._explore import same_exploration
from tests.statespace.test_native_timed import ROOT, _both, needs_native

ALL_SCENARIOS = sorted(os.path.basename(p)[:-5] for p in glob.glob(os.path.join(ROOT, "specs", "modbus", "*.toml")))
#: the suite runs these (each compiles its own C: one serial-line scenario, a long test (`--slow`; the serial-line
#: model's C is compared in the suite by the broadcast test below), Modbus-A, Modbus/TCP); `CPN_ALL_SCENARIOS=1`
#: runs every scenario file of the gate
SCENARIOS = ALL_SCENARIOS if os.environ.get("CPN_ALL_SCENARIOS") else \
    [pytest.param("B_5", marks=pytest.mark.slow), "modbus_a", "tcp_mixed"]


@needs_native
@pytest.mark.parametrize("name", SCENARIOS)
def test_the_modbus_scenarios_run_in_c(name, fills):
    """Scenario files of the MODBUS gate (their model's constants fixed), both ways, with and without time
    condensation. The serial-line and Modbus-A models are wholly in the generated C, so the engine expands
    no state; in Modbus/TCP the client's Close (`list_to_ms` of a list) is the engine's."""
    path = os.path.join(ROOT, "specs", "modbus", f"{name}.toml")
    with open(path, "rb") as f:
        spec = tomllib.load(f)
    model = cpn.load(os.path.join(os.path.dirname(path), spec["model"]), set=spec.get("set"))
    code, _ = model.engine().timed_groups().native_code()
    tcp = name.startswith("tcp")
    left = sorted({model.engine().transitions[t].name.split("'")[1].split(" ")[0] for t in code.left})
    assert left == (["Close"] if tcp else []), left
    for condensation in (True, False):
        c = _both(model, condensation, limit=2000)
        assert c.n_states > 50, c.n_states
        if not tcp:
            assert fills[0] == 0 and not c.notes, (fills, c.notes)
        else:
            assert fills[0] > 0 and all("Close" in n for n in c.notes), c.notes


@needs_native
def test_modbus_scenario_b_with_a_broadcast_in_c(fills):
    """Scenario B with 8 slaves and a broadcast: every frame reaches the 8 slaves, one reception round each."""
    values = {"CONFIG": '"B"', "NS": "8", "ADRS": "[0,1,2,3,4,5,6,7,8]", "FCS": "[1]", "PO": "1"}
    model = cpn.load(os.path.join(ROOT, "models", "modbus", "modbus.cpnet"), set=values)
    c = _both(model, True)
    assert (c.n_states, c.n_arcs, c.complete) == (883, 1042, True)


def test_auto_searches_modbus_natively_without_making_its_c_for_a_small_search():
    """MODBUS is wholly in C: `auto` searches it natively, the engine filling the caches (faster than the
    Python search on the gate's scenarios, docs/performance.md); its C (about 51,000 lines) would be made
    only past 205,000 states, so a small search never makes it. The Python search's graph."""
    spec = tomllib.load(open(os.path.join(ROOT, "specs", "modbus", "B_5.toml"), "rb"))
    model = cpn.load(os.path.join(ROOT, "specs", "modbus", spec["model"]), set=spec.get("set"))
    auto = Explorer(model.engine(time_condensation=True), ExploreOptions(max_states=300)).run()
    py = Explorer(model.engine(time_condensation=True),
                  ExploreOptions(backend="python", max_states=300, packed_states=False)).run()
    assert auto.backend == "c" and auto.notes == []
    same_exploration(auto, py)
    assert getattr(auto.engine, "_timed_native_code", None) is None  # (decided without the whole net's C)


@pytest.mark.parametrize("name", ["B_5", "tcp_mixed", "modbus_a"])
def test_one_instance_of_each_transition_says_what_the_whole_c_leaves(name):
    """`auto` decides on the C of one instance of each transition of a module (`probe`): it leaves to the
    engine the transitions the whole net's C leaves (by their module transition)."""
    spec = tomllib.load(open(os.path.join(ROOT, "specs", "modbus", f"{name}.toml"), "rb"))
    model = cpn.load(os.path.join(ROOT, "specs", "modbus", spec["model"]), set=spec.get("set"))
    engine = model.engine(time_condensation=True)
    probe = ccodegen.timed_native_code(engine, probe=True)
    whole = ccodegen.timed_native_code(engine)
    assert len(probe.native) + len(probe.left) < len(engine.transitions) or name == "modbus_a"

    def kinds(left):
        return {(engine.transitions[t].page, engine.transitions[t].transition) for t in left}
    assert kinds(probe.left) == kinds(whole.left)
    assert set(probe.left.values()) == set(whole.left.values())
