"""Issue 11 item 5: every mutant of specs/modbus/mutants/ is caught by `check`, by the property its bug must
break (and by no other property of its file), with a shortest counterexample."""

import os
from collections import deque

import pytest

from cpn.checks.gate import run_scenario
from cpn.checks.scenario import load_scenario
from cpn.checks.verdict import Status

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MUTANTS = os.path.join(ROOT, "specs", "modbus", "mutants")

# file -> the MODBUS.md properties its bug breaks (issue 11 item 5 and MODBUS.md 4.5)
BROKEN = {
    "slave_answers_broadcast": {"S-P4"},
    "slave_answers_broadcast_alone": {"S-P4"},
    "master_sends_early": {"S-P2"},
    "superslave_sends_after_tw": {"SS-P3"},
    "superslave_unicast_reply": {"SS-P2"},
    "t3_shorter_than_tw_tbc": {"SS-P5", "S-P9"},
    "slow_slave_collides": {"S-P9"},
    "overlapping_addresses": {"M-P4", "S-P3"},
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
}


def _distances(g):
    dist = [-1] * g.n_states
    dist[0] = 0
    queue = deque([0])
    while queue:
        u = queue.popleft()
        for _, v in g.out_arcs(u):
            if dist[v] < 0:
                dist[v] = dist[u] + 1
                queue.append(v)
    return dist


def test_every_mutant_file_is_listed():
    files = {f[:-5] for f in os.listdir(MUTANTS) if f.endswith(".toml")}
    assert files == set(BROKEN)


@pytest.mark.parametrize("name", sorted(BROKEN))
def test_mutant_is_caught_by_the_property_it_breaks(name):
    scenario = load_scenario(os.path.join(MUTANTS, name + ".toml"))
    (run,) = scenario.runs
    result = run_scenario(scenario, run)
    assert result.exploration.complete
    violated = [r for r in result.results if r.verdict.status is Status.VIOLATED]
    assert {r.spec.name.split(" ")[0].rstrip(":") for r in violated} == BROKEN[name]
    # every violation is one the file expects (the gate passes), and nothing else fails
    assert all(r.spec.expect == "violated" for r in violated)
    assert result.status is Status.HOLDS
    dist = None
    for r in violated:
        if r.spec.kind == "reachable":  # a witness that does not exist: no trace to show
            continue
        ev = r.verdict.evidence
        assert ev is not None and ev.path[0] == 0, r.spec.name
        dist = dist or _distances(result.exploration.graph)
        assert len(ev.path) - 1 == dist[ev.path[-1]], r.spec.name  # shortest to the bad marking


def test_a_reply_to_a_broadcast_is_caught_as_soon_as_it_is_sent():
    # S-P4 flags the slave's reply itself, not only the collision two replies make
    scenario = load_scenario(os.path.join(MUTANTS, "slave_answers_broadcast_alone.toml"))
    result = run_scenario(scenario, scenario.runs[0])
    (r,) = [r for r in result.results if r.spec.name.startswith("S-P4")]
    assert r.verdict.status is Status.VIOLATED
    ev = r.verdict.evidence
    last = result.engine.binding_element(ev.arcs[-1]).transition
    assert result.engine.transitions[last].name == "Slave'EndBroadcast 1"
    assert len(ev.path) - 1 == 6


def test_modbus_a_properties_evaluate_on_long_chains():
    # MA2/MA4 were recursive CPN ML functions over the chain: past about 80 slaves the evaluation failed
    # ('maximum recursion depth exceeded'); they are now List.all over List.tabulate
    scenario = load_scenario(os.path.join(ROOT, "specs", "modbus", "modbus_a.toml"))
    base = scenario.runs[0]
    run = type(base)("Modbus-A[N=100]", {"N": 100}, {**base.values, "N": 100, "MAXN": 100})
    result = run_scenario(scenario, run, {"max_states": 300})
    assert all(r.verdict.status is not Status.ERROR for r in result.results)
    assert {r.verdict.status for r in result.results} == {Status.UNKNOWN}  # a partial search holds nothing
