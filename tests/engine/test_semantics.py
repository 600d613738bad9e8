"""Hand-checked small nets: the clock, delays, enabling by timestamp, removal, inhibitor and reset arcs,
priorities, free variables, guard bindings, CS.ran(), and the flattening of modules, ports and fusion."""

import os

import pytest

import cpn
from cpn.errors import EvaluationError

HEAD = """colset C = int with 0..3;
colset TC = int with 0..3 timed;
colset U = unit;
colset TU = unit timed;
var x, y : C;
"""


def load(body, **kw):
    return cpn.loads(HEAD + body, "t.cpnet", **kw)


def step(engine, s):
    return [(engine.format_binding_element(be), t) for be, t in engine.successors(s)]


def place(engine, s, name):
    p = engine.net.place(name)
    return engine.marking(s)[p.index]


@pytest.mark.parametrize("reference", [False, True])
def test_clock_advances_to_the_earliest_enabling_time(reference):
    e = load("place P : TC = 1`1 @+ 5; place Q : TC;\ntrans t;\narc P -> t : x;\narc t -> Q : x @+ 2;"
             ).engine(reference=reference)
    s0 = e.initial_state()
    assert e.clock(s0) == 0
    [(be, s1)] = step(e, s0)
    assert be == "Top't 1: {x=1}"
    assert e.clock(s1) == 5
    assert place(e, s1, "Top'Q 1") == {(1, 7): 1}


@pytest.mark.parametrize("reference", [False, True])
def test_transition_and_arc_delays_add_up(reference):
    e = load("place P : TC = 1`1; place Q : TC;\ntrans t @+ 3;\narc P -> t : x;\narc t -> Q : x @+ 2;"
             ).engine(reference=reference)
    [(_, s1)] = step(e, e.initial_state())
    assert place(e, s1, "Top'Q 1") == {(1, 5): 1}
    assert e.clock(s1) == 0


@pytest.mark.parametrize("reference", [False, True])
def test_only_bindings_ready_now_are_enabled(reference):
    e = load("place P : TC = 1`1 ++ (1`2 @+ 10);\ntrans t;\narc P -> t : x;").engine(reference=reference)
    assert [b for b, _ in step(e, e.initial_state())] == ["Top't 1: {x=1}"]


@pytest.mark.parametrize("reference", [False, True])
def test_earliest_binding_wins_when_nothing_is_ready(reference):
    e = load("place P : TC = (1`2 @+ 7) ++ (1`1 @+ 4);\ntrans t;\narc P -> t : x;").engine(reference=reference)
    [(b, s1)] = step(e, e.initial_state())
    assert b == "Top't 1: {x=1}" and e.clock(s1) == 4


@pytest.mark.parametrize("reference", [False, True])
def test_removal_takes_the_latest_ready_token(reference):
    e = load("place P : TC = 1`1 ++ (1`1 @+ 3); place Z : TU = 1`() @+ 3;\ntrans t;\narc P -> t : x;\n"
             "arc Z -> t : ();").engine(reference=reference)
    [(_, s1)] = step(e, e.initial_state())
    assert e.clock(s1) == 3
    assert place(e, s1, "Top'P 1") == {(1, 0): 1}


@pytest.mark.parametrize("reference", [False, True])
def test_double_arc_on_a_timed_place_renews_the_timestamp(reference):
    e = load("place P : TC = 1`2;\ntrans t @+ 4;\narc P <-> t : x;").engine(reference=reference)
    [(_, s1)] = step(e, e.initial_state())
    assert place(e, s1, "Top'P 1") == {(2, 4): 1}


@pytest.mark.parametrize("reference", [False, True])
def test_time_condensation_shifts_to_zero(reference):
    m = load("place P : TC = (1`1 @+ 5) ++ (1`2 @+ 8);\ntrans t;\narc P -> t : x;\narc t -> P : x @+ 1;")
    e = m.engine(time_condensation=True, reference=reference)
    [(_, s1)] = step(e, e.initial_state())
    assert e.clock(s1) == 0
    assert place(e, s1, "Top'P 1") == {(1, 1): 1, (2, 3): 1}


@pytest.mark.parametrize("reference", [False, True])
def test_inhibitor_arcs(reference):
    e = load("place P : C = 1`1; place Q : C = 1`2;\ntrans empty_q; trans no_two; trans no_one;\n"
             "inhibitor Q -> empty_q;\ninhibitor Q -> no_two : 2;\ninhibitor Q -> no_one : 1;\n"
             "arc P -> empty_q : x; arc P -> no_two : x; arc P -> no_one : x;").engine(reference=reference)
    assert [b for b, _ in step(e, e.initial_state())] == ["Top'no_one 1: {x=1}"]


@pytest.mark.parametrize("reference", [False, True])
def test_reset_arc_empties_the_place(reference):
    e = load("place P : C = 2`1 ++ 1`3; place S : U = 1`();\ntrans clear;\narc S -> clear;\nreset P -> clear;\n"
             "arc clear -> P : 0;").engine(reference=reference)
    [(_, s1)] = step(e, e.initial_state())
    assert place(e, s1, "Top'P 1") == {0: 1}


@pytest.mark.parametrize("reference", [False, True])
def test_priority_filters_enabled_binding_elements(reference):
    e = load("place P : U = 1`();\ntrans hi priority 100; trans lo;\narc P -> hi; arc P -> lo;"
             ).engine(reference=reference)
    assert [b for b, _ in step(e, e.initial_state())] == ["Top'hi 1: {}"]


@pytest.mark.parametrize("reference", [False, True])
def test_free_variable_of_a_small_colour_set_takes_every_value(reference):
    e = load("place P : U = 1`(); place Q : C;\ntrans t;\narc P -> t;\narc t -> Q : y;").engine(reference=reference)
    assert sorted(b for b, _ in step(e, e.initial_state())) == [f"Top't 1: {{y={i}}}" for i in range(4)]


@pytest.mark.parametrize("reference", [False, True])
def test_guard_binds_a_variable(reference):
    e = load("place P : C = 1`1 ++ 1`2; place Q : C;\ntrans t [y = x + 1];\narc P -> t : x;\narc t -> Q : y;"
             ).engine(reference=reference)
    got = sorted(b for b, _ in step(e, e.initial_state()))
    assert got == ["Top't 1: {x=1, y=2}", "Top't 1: {x=2, y=3}"]


@pytest.mark.parametrize("reference", [False, True])
def test_guard_bound_value_outside_the_colour_set_is_no_binding(reference):
    e = load("place P : C = 1`3; place Q : C;\ntrans t [y = x + 1];\narc P -> t : x;\narc t -> Q : y;"
             ).engine(reference=reference)
    assert step(e, e.initial_state()) == []


@pytest.mark.parametrize("reference", [False, True])
def test_ran_is_a_choice_of_every_value(reference):
    e = load("place P : U = 1`(); place Q : C;\ntrans t;\narc P -> t;\narc t -> Q : C.ran();"
             ).engine(reference=reference)
    succ = step(e, e.initial_state())
    assert sorted(next(iter(place(e, s, "Top'Q 1"))) for _, s in succ) == [0, 1, 2, 3]


def test_coefficients_count_tokens():
    e = load("place P : C = 3`1;\ntrans t;\narc P -> t : 2`x;").engine()
    [(b, s1)] = step(e, e.initial_state())
    assert place(e, s1, "Top'P 1") == {1: 1}
    assert step(e, s1) == []


def test_evaluation_error_names_the_element_and_binding():
    m = load("place P : C = 1`0;\ntrans t [10 div x > 1];\narc P -> t : x;")
    with pytest.raises(EvaluationError) as info:
        e = m.engine()
        e.successors(e.initial_state())
    err = info.value
    assert (err.span.line, err.span.col) == (7, 10)
    assert err.binding == {"x": "0"}
    assert "division by zero" in err.message
    assert "t.cpnet:7:10" in err.render()


def test_token_outside_its_colour_set_is_an_error():
    m = load("place P : C = 1`3;\ntrans t;\narc P -> t : x;\narc t -> P : x + 1;")
    e = m.engine()
    with pytest.raises(EvaluationError) as info:
        e.successors(e.initial_state())
    assert "outside its colour set C" in info.value.message


def test_flattening_names_ports_and_fusion():
    root = os.path.dirname(os.path.dirname(os.path.dirname(__file__)))
    net = cpn.load(os.path.join(root, "models", "examples", "stations.cpnet")).net
    names = [p.name for p in net.places]
    assert names == ["Office'Requests 1", "Office'Replies 1", "Office'Log 1",
                     "Station'Idle 1", "Station'Busy 1",
                     "Station'Idle 2", "Station'Busy 2",
                     "Station'Idle 3", "Station'Busy 3"]
    assert net.place("Office'Requests 1").aliases == ["Station'Inbox 1", "Station'Inbox 2", "Station'Inbox 3"]
    assert net.place("Office'Log 1").aliases == ["Station'Served 1", "Station'Served 2", "Station'Served 3"]
    assert [t.name for t in net.transitions] == [
        "Office'Archive 1", "Station'Take 1", "Station'Done 1", "Station'Take 2", "Station'Done 2",
        "Station'Take 3", "Station'Done 3"]
    # each instance's parameter: Station 2 takes only request 2
    take2 = net.transition("Station'Take 2")
    assert list(take2.params.values()) == [2]


def test_module_parameters_give_different_behaviour_per_instance():
    src = """colset C = int with 0..3; var x : C;
module M(k : C) { port in In : C; port out Out : C; trans t [x = k]; arc In -> t : x; arc t -> Out : x; }
place A : C = C.all(); place B : C;
instance M1 = M(k = 1) { In = A, Out = B };
instance M2 = M(k = 3) { In = A, Out = B };
"""
    e = cpn.loads(src, "m.cpnet").engine()
    assert sorted(b for b, _ in step(e, e.initial_state())) == ["M't 1: {x=1}", "M't 2: {x=3}"]


def test_nested_modules_number_instances_depth_first():
    src = """colset U = unit;
module Leaf() { place L : U = 1`(); }
module Mid() { place X : U; instance A = Leaf(); instance B = Leaf(); }
instance M1 = Mid(); instance M2 = Mid();
"""
    net = cpn.loads(src, "m.cpnet").net
    assert [p.name for p in net.places] == ["Mid'X 1", "Leaf'L 1", "Leaf'L 2", "Mid'X 2", "Leaf'L 3", "Leaf'L 4"]


@pytest.mark.parametrize("reference", [False, True])
def test_api_enabled_and_fire(reference):
    e = load("place P : C = 1`1 ++ 1`2; place Q : C;\ntrans t;\narc P -> t : x;\narc t -> Q : x;"
             ).engine(reference=reference)
    s0 = e.initial_state()
    assert sorted(b.binding["x"] for b in e.enabled(s0)) == [1, 2]
    s1 = e.fire(s0, "Top't 1: {x=2}")
    assert place(e, s1, "Top'Q 1") == {2: 1}
    with pytest.raises(ValueError):
        e.fire(s1, "Top't 1: {x=2}")


@pytest.mark.parametrize("reference", [False, True])
def test_transition_without_input_arcs_is_always_enabled(reference):
    e = load("colset S = int with 0..2; place Q : S;\ntrans gen;\narc gen -> Q : 1;").engine(reference=reference)
    s = e.initial_state()
    for n in (1, 2):
        [(b, s)] = step(e, s)
        assert b == "Top'gen 1: {}"
        assert place(e, s, "Top'Q 1") == {1: n}


@pytest.mark.parametrize("reference", [False, True])
def test_double_arc_puts_back_only_its_own_inscription(reference):
    e = load("place P : C = 1`1 ++ 1`2;\ntrans t [x < y];\narc P <-> t : x;\narc P <-> t : y;"
             ).engine(reference=reference)
    [(_, s1)] = step(e, e.initial_state())
    assert place(e, s1, "Top'P 1") == {1: 1, 2: 1}
    e = load("place P : C = 3`1;\ntrans t;\narc P <-> t : x;\narc P -> t : x;").engine(reference=reference)
    s = e.initial_state()
    counts = []
    while True:
        succ = step(e, s)
        if not succ:
            break
        s = succ[0][1]
        counts.append(place(e, s, "Top'P 1").get(1, 0))
    assert counts == [2, 1]


@pytest.mark.parametrize("reference", [False, True])
def test_int_time_is_the_firing_time(reference):
    e = load("colset T = int timed; colset I = int; var n : T;\nplace P : T = 1`1 @+ 4; place Q : I;\n"
             "trans t @+ intTime();\narc P -> t : n;\narc t -> Q : intTime();\narc t -> P : n;"
             ).engine(reference=reference)
    [(_, s1)] = step(e, e.initial_state())
    assert e.clock(s1) == 4
    assert place(e, s1, "Top'Q 1") == {4: 1}
    assert place(e, s1, "Top'P 1") == {(1, 8): 1}


@pytest.mark.parametrize("reference", [False, True])
def test_transition_without_arcs_is_a_self_loop(reference):
    e = load("place P : C = 1`0;\ntrans u;").engine(reference=reference)
    s0 = e.initial_state()
    [(b, s1)] = step(e, s0)
    assert b == "Top'u 1: {}" and s1 == s0


@pytest.mark.parametrize("reference", [False, True])
def test_variable_only_in_a_conditional_input_is_free(reference):
    e = load("colset B = bool; var b : B;\nplace P : C = 1`2 ++ 1`1; place F : B = 1`false; place Q : C;\n"
             "trans t;\narc F -> t : b;\narc P -> t : if b then 1`x else empty;\n"
             "arc t -> Q : if b then 1`x else empty;").engine(reference=reference)
    assert sorted(b for b, _ in step(e, e.initial_state())) == [f"Top't 1: {{b=false, x={i}}}" for i in range(4)]
