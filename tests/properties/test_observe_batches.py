"""The native search shows a check's monitor the states it stored a batch at a time
(`_Monitor.observe_many`, `Compiled.first`): each property must find the same first marking, and fail at
the same marking, as when it is shown the states one by one."""

import pathlib

import pytest

import cpn
from cpn.checks.columns import TransitionIndex
from cpn.diagnostics import Span
from cpn.gate.run import _Monitor
from cpn.lang import types as T
from cpn.properties.kinds import Invariant, Reachable
from cpn.properties.predicates import PredicateError, PropertyLanguage
from cpn.properties.spec import PropertySpec
from cpn.statespace import ExploreOptions, Explorer

ROOT = pathlib.Path(__file__).resolve().parents[2]
TEXTS = [
    "size (sum Station'Busy) <= 1",
    "size (Office'Requests 1) = 0 andalso Office'Log 1 = ID.all()",
    "cf (2, Office'Replies 1) = 1 orelse cf (2, Office'Log 1) = 1",
    "size (sum Station'Busy) + size (Office'Replies 1) < 3",
    "true",
    "false",
    # fails (division by zero) wherever no station is busy
    "10 div size (sum Station'Busy) > 4",
]
CHUNKS = [1, 7, 512]


@pytest.fixture(scope="module")
def net():
    engine = cpn.load(ROOT / "models/examples/stations.cpnet").engine()
    states = list(Explorer(engine, ExploreOptions()).run().graph.states)
    assert len(states) > 20
    return engine, states


def _compiled(engine, text):
    lang = PropertyLanguage(engine.net, engine, TransitionIndex(engine))
    return lang.compile(text, None, Span("<test>", 1, 1), T.BOOL, "the test's text")


def _one_by_one(engine, states, text, wanted):
    """(the first position with the value `wanted`, the position of the first failure before it)."""
    fn = _compiled(engine, text).fn
    for i, s in enumerate(states):
        try:
            v = fn(i, s)
        except PredicateError as exc:
            return None, exc.state_id
        if bool(v) is wanted:
            return i, None
    return None, None


def _in_batches(engine, states, text, wanted, size):
    c = _compiled(engine, text)
    assert c.first is not None  # the compiled engine's texts are memoised: the batch path is taken
    for start in range(0, len(states), size):
        try:
            i = c.first_where(start, states[start:start + size], wanted)
        except PredicateError as exc:
            return None, exc.state_id
        if i is not None:
            return start + i, None
    return None, None


@pytest.mark.parametrize("wanted", [True, False])
@pytest.mark.parametrize("text", TEXTS)
def test_a_batch_finds_the_first_marking_and_the_first_failure(net, text, wanted):
    engine, states = net
    expected = _one_by_one(engine, states, text, wanted)
    for size in CHUNKS:
        assert _in_batches(engine, states, text, wanted, size) == expected, (text, wanted, size)


def test_the_texts_tell_markings_apart_and_one_fails(net):
    engine, states = net
    firsts = {text: _one_by_one(engine, states, text, False) for text in TEXTS}
    assert any(found not in (None, 0) for found, _ in firsts.values())  # a violation past the first marking
    assert firsts["10 div size (sum Station'Busy) > 4"][1] == 0  # no station is busy at first


def _checks(engine):
    spec = PropertySpec(1, "p", "invariant", {}, Span("<test>", 1, 1))
    return [Invariant(spec, _compiled(engine, t)) for t in TEXTS] + \
        [Reachable(spec, _compiled(engine, t)) for t in TEXTS]


def _outcome(checks):
    return [(c.found, None if c.error is None else c.error.state_id) for c in checks]


@pytest.mark.parametrize("size", CHUNKS)
def test_the_monitor_sees_a_batch_as_the_states_one_by_one(net, size):
    engine, states = net
    one = _checks(engine)
    monitor = _Monitor(one, None, False, False)
    for s in states:
        monitor(s)
    batched = _checks(engine)
    monitor = _Monitor(batched, None, False, False)
    for start in range(0, len(states), size):
        monitor.observe_many(states[start:start + size])
    assert monitor.sid == len(states)
    assert _outcome(batched) == _outcome(one)
    assert any(c.error is not None for c in one) and any(c.found not in (None, 0) for c in one)
