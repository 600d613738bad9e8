"""`cpn-verify simulate` on the 42-slave Modbus-A chain reproduces the paper's checkpoints,
and reports/modbus_a_42_simulation.txt is what bench/modbus_a_simulation.py writes today."""

import importlib.util
import os

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
_spec = importlib.util.spec_from_file_location("modbus_a_simulation", os.path.join(ROOT, "bench", "modbus_a_simulation.py"))
sim = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(sim)


def test_42_slaves_reproduce_the_papers_checkpoints():
    _, trace = sim.simulate(42, 0)
    assert trace["ended"] == "dead"
    rows = sim.iterations(trace["steps"])
    after = {i: c for i, _, c in rows}
    assert {i: after[i] for i in (9, 18, 30, 44)} == {9: 8, 18: 17, 30: 29, 44: 42}
    assert max(after) == 44  # the 44th message is the unanswered one: the master stops


def test_committed_report_is_current():
    with open(os.path.join(ROOT, "reports", "modbus_a_42_simulation.txt"), encoding="utf-8") as fh:
        committed = fh.read()
    text = sim.report(42, 0)
    assert committed == text
    assert "checkpoints (9 -> 8, 18 -> 17, 30 -> 29, 44 -> 42, 44 iterations in all): reproduced" in text


def test_smaller_chain_takes_n_plus_two_iterations():
    _, trace = sim.simulate(5, 1)
    rows = sim.iterations(trace["steps"])
    assert [c for _, _, c in rows] == [0, 1, 2, 3, 4, 5, 5]
