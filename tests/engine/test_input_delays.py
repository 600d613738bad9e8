"""Delays on input arcs (`arc P -> T : e @+ k`, CPN Tools' preempting time stamps, docs/semantics.md, Time):
T may remove the tokens of P up to k time units before their timestamps. Each test runs the compiled
engine and the reference interpreter; the native search is compared with the Python search (the C
generated from the inscriptions, and the engine's groups)."""

import pytest

import cpn
from cpn.statespace import ExploreOptions, Explorer, nativetimed
from cpn.statespace.store import packed_unavailable
from tests.engine._explore import counts, graph, same_exploration
from tests.engine.randomnets import random_timed_net
from tests.engine.test_differential import _compare

ENGINES = [False, True]  # compiled, reference
NATIVE = packed_unavailable()

# CPN Tools' help ("Arc inscriptions", preempting time stamps): tokens stamped 8; t2 with `@+5` on its
# input arc is enabled at 3, t1 without it not until 8
HELP = """colset TU = unit timed;
place P : TU = 1`() @+ 8;
place Q : TU;
trans t1;
trans t2;
arc P -> t1 : ();
arc t1 -> Q : ();
arc P -> t2 : () @+ 5;
arc t2 -> Q : ();
"""


def _engine(text, reference, **kw):
    return cpn.loads(text, "m.cpnet").engine(reference=reference, **kw)


def _steps(e, s):
    return [(e.format_binding_element(be), e.clock(t), e.marking(t)) for be, t in e.successors(s)]


@pytest.mark.parametrize("reference", ENGINES)
def test_the_helps_example_t2_occurs_at_3_and_t1_would_wait_until_8(reference):
    e = _engine(HELP, reference)
    assert _steps(e, e.initial_state()) == [("Top't2 1: {}", 3, [{}, {((), 3): 1}])]
    e = _engine(HELP.replace("() @+ 5;", "();"), reference)  # without the delay both wait until 8
    assert [(b, c) for b, c, _m in _steps(e, e.initial_state())] == [("Top't1 1: {}", 8), ("Top't2 1: {}", 8)]


@pytest.mark.parametrize("reference", ENGINES)
def test_the_tokens_with_the_largest_available_stamps_are_removed(reference):
    """Stamps 1, 4, 6 and 9 at clock 0, two tokens removed by `2`x @+ 5`: available are those stamped up to
    0 + 5 (1 and 4); the ready time is 4 - 5 = -1, so the occurrence is at 0; left are the stamps 6 and 9."""
    text = """colset C = int with 0..1; colset TC = int with 0..1 timed; var x : C;
    place P : TC = 1`0 @+ 1 ++ 1`0 @+ 4 ++ 1`0 @+ 6 ++ 1`0 @+ 9; place Q : TC;
    trans T; arc P -> T : 2`x @+ 5; arc T -> Q : x;"""
    e = _engine(text, reference)
    assert _steps(e, e.initial_state()) == [("Top'T 1: {x=0}", 0, [{(0, 6): 1, (0, 9): 1}, {(0, 0): 1}])]
    # with one token of each stamp removed by `x @+ 5` at 0: the 4, not the 1
    e = _engine(text.replace("2`x @+ 5", "x @+ 5"), reference)
    assert _steps(e, e.initial_state())[0][2][0] == {(0, 1): 1, (0, 6): 1, (0, 9): 1}


@pytest.mark.parametrize("reference", ENGINES)
def test_a_transition_is_examined_when_its_tokens_become_ready_early(reference):
    """A guard that holds only at 3: the token stamped 8 is ready at 8 - 5 = 3, when T is examined and
    occurs; without the delay T is examined at 0 and 8 only, and never occurs."""
    text = """colset TU = unit timed; colset I = int; place P : TU = 1`() @+ 8; place Log : I;
    trans T [intTime() = 3]; arc P -> T : () @+ 5; arc T -> Log : intTime();"""
    e = _engine(text, reference)
    assert _steps(e, e.initial_state()) == [("Top'T 1: {}", 3, [{}, {3: 1}])]
    assert counts(_engine(text.replace("() @+ 5", "()"), reference)) == (1, 0, 1)


# T1 takes P's token 2 early and puts it back 5 later (so every 3 time units), T2 every 4. Under time
# condensation (clock 0, stamps relative), with P@p Q@q a state: A = P@0 Q@0; at 0 T1 gives B = P@5 Q@0,
# T2 gives C = P@0 Q@4, and both lead to D = P@5 Q@4; then T1 at 3 gives E = P@5 Q@1, T2 at 1 gives
# F = P@4 Q@4, T1 at 2 gives G = P@5 Q@2, T2 at 2 gives H = P@3 Q@4, T1 at 1 gives I = P@5 Q@3; in I both
# are ready at 3: T1 gives B again, T2 gives J = P@2 Q@4, and T1 at 0 gives D. 10 states, 12 arcs.
# Without the delay (T1 every 5 time units): 11 states and 13 arcs.
CYCLE = """colset TU = unit timed;
place P : TU = 1`();
place Q : TU = 1`();
trans T1;
trans T2;
arc P -> T1 : () @+ 2;
arc T1 -> P : () @+ 5;
arc Q -> T2 : ();
arc T2 -> Q : () @+ 4;
"""


@pytest.mark.parametrize("reference", ENGINES)
def test_time_condensation_with_an_input_delay(reference):
    assert counts(_engine(CYCLE, reference, time_condensation=True)) == (10, 12, 0)
    assert counts(_engine(CYCLE.replace("() @+ 2", "()"), reference, time_condensation=True)) == (11, 13, 0)


def test_a_delay_from_a_val_follows_set():
    text = HELP.replace("@+ 5", "@+ D").replace("colset TU", "val D = 5; colset TU")
    for d, when in ((5, 3), (2, 6), (0, 8)):
        e = cpn.loads(text, "m.cpnet", set={"D": d}).engine()
        assert [c for _b, c, _m in _steps(e, e.initial_state())][-1] == when


def test_a_delay_in_a_module_takes_the_instances_parameter():
    text = """colset TU = unit timed; colset I = int;
    module M(k : I) { place P : TU = 1`() @+ 8; place Q : TU; trans t; arc P -> t : () @+ k; arc t -> Q : (); }
    instance A = M(k = 1); instance B = M(k = 6);"""
    model = cpn.loads(text, "m.cpnet")
    assert [a.preemption for t in model.net.transitions for a in t.arcs] == [1, 0, 6, 0]
    e = model.engine()
    assert [(b, c) for b, c, _m in _steps(e, e.initial_state())] == [("M't 2: {}", 2)]


def test_compiled_and_reference_agree_on_the_examples():
    for text in (HELP, CYCLE):
        model = cpn.loads(text, "m.cpnet")
        _compare(model)
        _compare(model, condensation=True)
    assert graph(cpn.loads(CYCLE, "m.cpnet").engine(time_condensation=True))


@pytest.mark.parametrize("chunk", range(2))
def test_random_timed_nets_with_input_delays(chunk):
    """200 random timed nets whose input arcs from timed places have delays about half the time (a number
    or a `val`), about half of them reading the clock: compiled engine against reference interpreter,
    with time condensation where it is sound."""
    with_delay = 0
    for seed in range(chunk * 100, chunk * 100 + 100):
        text = random_timed_net(seed, preempt=True)
        model = cpn.loads(text, f"early{seed}.cpnet")
        with_delay += any(a.preemption for t in model.net.transitions for a in t.arcs)
        try:
            _compare(model, condensation=False, limit=30)
            if not model.engine().reads_clock:
                _compare(model, condensation=True, limit=30)
        except AssertionError:
            raise AssertionError(f"engines differ on random timed net {seed} with input delays:\n{text}") from None
    assert with_delay >= 30


@pytest.mark.skipif(NATIVE is not None, reason=f"no native code: {NATIVE}")
@pytest.mark.parametrize("generated", [True, False], ids=["generated-c", "engine-groups"])
def test_the_native_search_gives_the_python_graph(generated, monkeypatch):
    """The C search against the Python search on the examples and on random timed nets with input delays
    that do not read the clock: with the transitions in generated C (every one of them: none is left to
    the engine), and with the engine's groups."""
    if not generated:
        monkeypatch.setenv("CPN_NO_GENERATED", "1")
    monkeypatch.setattr(nativetimed, "HAND_OVER_RATE", 1e9)  # the C search to the end
    models = [cpn.loads(HELP, "help.cpnet"), cpn.loads(CYCLE, "cycle.cpnet")]
    for seed in range(400):
        if len(models) >= (8 if generated else 30):
            break
        model = cpn.loads(random_timed_net(seed, preempt=True), f"early{seed}.cpnet")
        if not model.engine().reads_clock and any(a.preemption for t in model.net.transitions for a in t.arcs):
            models.append(model)
    for model in models:
        for cond in (False, True):
            c = Explorer(model.engine(time_condensation=cond), ExploreOptions(backend="c", max_states=300)).run()
            py = Explorer(model.engine(time_condensation=cond),
                          ExploreOptions(backend="python", max_states=300, packed_states=False)).run()
            assert c.backend == "c"
            same_exploration(c, py)
            if generated:
                code, why = model.engine(time_condensation=cond).timed_groups().native_code()
                assert why is None and code.left == {}, (model.net.source_file, why, code and code.left)
    cycle = Explorer(models[1].engine(time_condensation=True), ExploreOptions(backend="c")).run()
    assert (len(cycle.graph.states), cycle.complete) == (10, True)
