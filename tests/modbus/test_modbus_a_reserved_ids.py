"""Modbus-A past the reserved IDs: with 100 slaves the ID counter passes RESET_ID = 98 and CONFIG_ID = 99,
which no slave may get and the master never polls (a frame for ID 98 is a reset); MA2 and MA7 follow the
allocation sequence 1, 2, ..., 97, 100, 101, ... (specs/modbus/modbus_a_100.toml). The mutant whose counter
hands out the reserved IDs gives slaves 98 and 99 those IDs; the gate catches it on a chain of 6 with the
reserved IDs 4 and 5 (specs/modbus/mutants/ma_reserved_ids.toml, tests/modbus/test_modbus_mutants.py)."""

import os

import pytest

import cpn
from cpn.checks.verdict import Status
from cpn.gate.run import run_scenario
from cpn.gate.scenario import load_scenario

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MODEL = os.path.join(ROOT, "models", "modbus", "modbus_a.cpnet")


def _final(n: int, mutant: str = "none"):
    """The dead marking's slaves (position -> (mode, ID)) and poll log of a chain of n slaves."""
    model = cpn.load(MODEL, set={"N": str(n), "MUTANT": f'"{mutant}"'})
    engine = model.engine(time_condensation=True)
    state = engine.initial_state()
    while True:  # the allocation is one path but for the order of timers: follow the first successor
        succ = list(engine.successors(state))
        if not succ:
            break
        state = succ[0][1]
    marking = dict(zip([p.name for p in model.net.places], engine.marking(state)))
    slaves = {p: (md, i) for ((p, md, i), _n) in marking["Chain'Slaves 1"].items()}
    (log,) = marking["Master'PollLog 1"]
    return slaves, [k for k, _ in log]


@pytest.mark.parametrize("n", [99, 100])
def test_the_counter_skips_the_reserved_ids(n):
    slaves, polled = _final(n)
    model = cpn.load(MODEL, set={"N": str(n)})
    default = model.net.colsets["MODE"].values()[0]
    ids = list(range(1, 98)) + list(range(100, n + 3))
    assert [slaves[p] for p in range(1, n + 1)] == [(default, i) for i in ids[:n]]
    assert 98 not in polled and 99 not in polled
    assert sorted(k for k in polled if k) == ids[:n]


def test_the_mutant_hands_out_the_reserved_ids():
    slaves, polled = _final(100, "reserved-ids")
    assert slaves[98][1] == 98 and slaves[99][1] == 99 and 98 in polled


@pytest.mark.slow  # 13 s; CI's installation check runs the scenario too, in the README's main command
def test_the_100_slave_scenario_holds_and_exercises_the_reserved_ids():
    scenario = load_scenario(os.path.join(ROOT, "specs", "modbus", "modbus_a_100.toml"))
    (run,) = scenario.runs
    assert str(run.values["N"]) == "100"
    result = run_scenario(scenario, run)
    assert result.exploration.complete
    assert {r.spec.name.split(":")[0]: r.verdict.status for r in result.results}["MA2"] is Status.HOLDS
    assert all(r.verdict.status is Status.HOLDS for r in result.results)
