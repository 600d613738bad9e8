"""A `live_transitions` counterexample is the shortest trace to a marking from which the transition can
never occur (docs/specs.md), not a trace to the first terminal SCC that lacks it."""

from pathlib import Path

from cpn.gate.run import run_scenario
from cpn.gate.scenario import load_scenario
from tests._graphs import bfs_distances
from tests.checks._nets import scenario

ROOT = Path(__file__).resolve().parents[2]


def _verdict(path: str):
    s = load_scenario(path)
    r = run_scenario(s, s.runs[0])
    (result,) = r.results
    return r, result.verdict


def _stations(tmp_path, transition: str) -> str:
    path = tmp_path / "s.toml"
    path.write_text(f'model = "{ROOT / "models/examples/stations.cpnet"}"\n'
                    f'[[property]]\nkind = "live_transitions"\ntransitions = ["{transition}"]\n', encoding="utf-8")
    return str(path)


def _never_occurs_after(r, state: int, transition: str) -> bool:
    """No arc of `transition` is reachable from `state` (a search of the graph, independent of the check)."""
    g, engine = r.exploration.graph, r.engine
    seen, todo = {state}, [state]
    while todo:
        u = todo.pop()
        for be, v in g.out_arcs(u):
            if engine.format_binding_element(be).split(":")[0].strip() == transition:
                return False
            if v not in seen:
                seen.add(v)
                todo.append(v)
    return True


def test_stations_take_1_gets_the_one_step_trace(tmp_path):
    r, v = _verdict(_stations(tmp_path, "Station'Take 1"))
    assert v.status.value == "violated"
    ev = v.evidence
    assert len(ev.path) - 1 == 1  # Station 1 takes its request: it can never take another
    assert _never_occurs_after(r, ev.target, "Station'Take 1")
    assert not _never_occurs_after(r, 0, "Station'Take 1")


def test_the_trace_is_the_shortest_to_such_a_marking(tmp_path):
    r, v = _verdict(_stations(tmp_path, "Station'Take 1"))
    g = r.exploration.graph
    targets = [s for s in range(g.n_states) if _never_occurs_after(r, s, "Station'Take 1")]
    dist = bfs_distances(g)
    assert len(v.evidence.path) - 1 == min(dist[s] for s in targets)


def test_a_transition_dead_from_the_start_gets_an_empty_trace(tmp_path):
    net = """net D;
colset U = unit;
place A : U = 1`();
place B : U;
place C : U;
trans Go;
arc A -> Go;
arc Go -> C;
trans Spin;
arc C -> Spin;
arc Spin -> C;
trans Never;
arc B -> Never;
arc Never -> A;
"""  # states {A} -Go-> {C} -Spin-> {C}: the only terminal SCC is {C}, one step away; Never is dead from the start
    path = scenario(tmp_path, net, '[[property]]\nkind = "live_transitions"\ntransitions = ["D\'Never 1"]\n')
    _r, v = _verdict(path)
    assert v.status.value == "violated" and v.evidence.path == (0,)
