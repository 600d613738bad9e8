"""The engine's optional capabilities (`cpn.engine.protocol.Capabilities`): declared, offered by the compiled
engine, and used by the upper layers through their public names."""

import pytest

import cpn
from cpn.engine.protocol import Capabilities

MODEL = """
colset N = int with 0..3;
var n : N;
place A : N = 1`0 ++ 1`1;
trans t [n < 3];
arc A -> t : n;
arc t -> A : n + 1;
"""


def _members():
    return {n for n in vars(Capabilities) if not n.startswith("_")} | set(Capabilities.__annotations__)


def test_the_compiled_engine_offers_every_capability():
    engine = cpn.loads(MODEL).engine()
    assert not {n for n in _members() if not hasattr(engine, n)}


def test_the_reference_interpreter_offers_what_the_reports_use():
    engine = cpn.loads(MODEL).engine(reference=True)
    assert engine.reference and engine.net is not None and engine.time_condensation is False
    t = engine.transitions[0]
    env = engine.binding_env(t, {"n": 2})
    assert engine.arc_tokens(t.arcs[1].expr, env, t) == [(3, 1, 0)]


def test_forgetting_the_memo_changes_no_successor():
    engine = cpn.loads(MODEL).engine()
    s0 = engine.initial_state()
    before = engine.successors(s0)
    assert any(info.memo for info in engine._plan)
    engine.forget_memo()
    assert not any(info.memo for info in engine._plan) and not engine._fire_memo
    assert engine.successors(s0) == before


@pytest.mark.parametrize("name", ["_plan", "_fire_memo"])
def test_the_sweep_line_no_longer_reads_the_engines_private_tables(name):
    import inspect

    from cpn.statespace import sweep

    assert name not in inspect.getsource(sweep)
