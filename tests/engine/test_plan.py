"""The binding plan (cpn.engine.plan) on its own: the order in which variables are bound and guards tested."""

import pytest

import cpn
from cpn.engine import plan

HEAD = "colset N = int with 0..3; colset B = bool; var x, y, z : N; var b : B;\n"


def _plan(body):
    t = cpn.loads(HEAD + body).net.transitions[0]
    read = []
    for a in t.arcs:
        if a.kind.reads and a.place not in read:
            read.append(a.place)
    return plan.binding_plan(plan.input_terms(t, read), t.guards, t.variables, t.free)


def _kinds(steps):
    return [type(s).__name__ + (f"({s.var})" if isinstance(s, plan.Enumerate) else "") for s in steps]


def test_a_guard_is_tested_as_soon_as_its_variables_are_bound():
    steps = _plan("place P : N; place Q : N; trans t [x < 2 andalso y > x];\narc P -> t : x; arc Q -> t : y;")
    assert _kinds(steps) == ["Loop", "Test", "Loop", "Test"]
    assert [s.new for s in steps if isinstance(s, plan.Loop)] == [{"x"}, {"y"}]


def test_tokens_before_guard_binders_before_free_variables():
    steps = _plan("place P : N; trans t [y = x + 1, b];\narc P -> t : x;")
    assert _kinds(steps) == ["Loop", "Bind", "Enumerate(b)", "Test"]
    bind = steps[1]
    assert bind.new == {"y"} and bind.guard == 0


def test_a_closed_guard_comes_first():
    assert _kinds(_plan("place P : N; trans t [1 < 2];\narc P -> t : x;")) == ["Test", "Loop"]


def test_a_pattern_binds_all_its_variables_in_one_loop():
    steps = _plan("colset P2 = product N * N; place P : P2; trans t;\narc P -> t : (x, y);")
    assert _kinds(steps) == ["Loop"] and steps[0].new == {"x", "y"}


def test_terms_of_a_sum_and_conditional_terms():
    t = cpn.loads(HEAD + "place P : N; trans t;\narc P -> t : 1`x ++ (if x > 0 then 1`0 else empty);").net.transitions[0]
    ts = plan.terms(t.arcs[0].expr)
    assert [bool(x.cond) for x in ts] == [False, True]


def test_unbindable_variables_are_reported():
    with pytest.raises(plan.Unbindable, match="z"):
        plan.binding_plan([], [], ["z"], [])
