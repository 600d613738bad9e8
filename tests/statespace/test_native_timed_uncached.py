"""The native timed search's results computed anew (`_timed.c`): a group whose ready lists or effects
are rarely reused (more than half of its first `native.UNCACHED_AFTER` look-ups missed) has them computed
by the net's generated C for each state instead of cached. The graph must stay the Python search's own
(the same states under the same ids, the same arcs and binding elements, the same markings modulo time);
here the judging is made after a few look-ups so that small nets reach it."""

import os

import pytest

import cpn
from cpn.statespace import ExploreOptions, Explorer, native, nativetimed
from cpn.statespace.store import packed_unavailable
from tests.engine._explore import same_exploration
from tests.engine.randomnets import random_timed_net

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(__file__)))
NATIVE = packed_unavailable()
needs_native = pytest.mark.skipif(NATIVE is not None, reason=f"native code unavailable: {NATIVE}")


@pytest.fixture
def uncached(monkeypatch):
    """Judge the caches after 8 look-ups; the list gets, per native timed search that ended, how many of
    its caches computed their results anew."""
    monkeypatch.setattr(native, "UNCACHED_AFTER", 8)
    monkeypatch.setattr(nativetimed, "HAND_OVER_RATE", 1e9)
    got: list[int] = []
    run = nativetimed.TimedNativeSearch._run

    def counted(self, *args):
        stop = run(self, *args)
        if stop is not None:
            got.append(self.uncached())
        return stop
    monkeypatch.setattr(nativetimed.TimedNativeSearch, "_run", counted)
    return got


def _same(model, condensation: bool, limit: int):
    c = Explorer(model.engine(time_condensation=condensation),
                 ExploreOptions(backend="c", max_states=limit)).run()
    py = Explorer(model.engine(time_condensation=condensation),
                  ExploreOptions(backend="python", max_states=limit, packed_states=False)).run()
    assert c.backend == "c" and py.backend == "python", c.notes
    same_exploration(c, py)
    assert [tuple(s) for s in c.graph.states] == [tuple(s) for s in py.graph.states]
    assert [[list(d.items()) for d in c.engine.marking(s)] for s in c.graph.states] == \
        [[list(d.items()) for d in py.engine.marking(s)] for s in py.graph.states]
    assert c.untimed_states == py.untimed_states and c.time_growth == py.time_growth
    return c


@needs_native
def test_random_timed_nets_with_results_computed_anew(uncached):
    ran = 0
    for seed in range(2, 66, 8):
        text = random_timed_net(seed).replace("intTime()", "0")
        model = cpn.loads(text, f"timed{seed}.cpnet")
        code, why = model.engine().timed_groups().native_code()
        if why is not None or code.left:
            continue
        for condensation in (False, True):
            try:
                _same(model, condensation, limit=400)
            except AssertionError:
                raise AssertionError(f"C and Python differ on random timed net {seed} (condensation "
                                     f"{condensation}):\n{text}") from None
            ran += 1
    assert ran >= 8
    assert sum(n > 0 for n in uncached) >= 2, uncached  # the searches did compute results anew


@needs_native
def test_the_polled_timed_family_has_its_untimed_twins_graph(uncached):
    """bench/nets/ms_polled_timed.cpnet: its clock advances (a request waits for the bus, a response for
    its delay), the group of Reply meets new registers in nearly every state and computes its effects
    anew; the graph is the Python search's, with the states and arcs of the untimed twin."""
    timed = cpn.load(os.path.join(ROOT, "bench", "nets", "ms_polled_timed.cpnet"), set={"N": "3"})
    c = _same(timed, True, limit=10_000)
    assert c.complete and uncached[-1] > 0
    twin = cpn.load(os.path.join(ROOT, "bench", "nets", "ms_polled.cpnet"), set={"N": "3"})
    u = Explorer(twin.engine(), ExploreOptions(backend="c")).run()
    assert (c.n_states, c.n_arcs) == (u.n_states, u.n_arcs) == (513, 648)


MIXED = """
colset N = int with 0..3 timed;
colset L = list N;
var x, y : N;
place P : N = 1`0 ++ (1`1@+1) ++ (1`2@+3);
place Q : N;
place R : N = 1`3;
trans inc [x < 3] @+ 1;
arc P -> inc : x;
arc inc -> P : (x + 1) @+ 2;
arc inc -> Q : x;
trans back [Int.toString x <> "9"];
arc Q -> back : x;
arc back -> P : x @+ 1;
trans swap [x <> y];
arc R -> swap : y;
arc P -> swap : x;
arc swap -> R : x @+ 2;
arc swap -> P : y;
"""


@needs_native
@pytest.mark.parametrize("condensation", [False, True], ids=["timed", "condensed"])
def test_results_computed_anew_beside_a_transition_left_to_python(condensation, uncached):
    """`back` makes a string: the engine computes its bindings, the others' results are computed anew in C
    once judged, and the tables both keep stay in step."""
    model = cpn.loads(MIXED, "mixed.cpnet")
    code, _ = model.engine().timed_groups().native_code()
    assert sorted(code.left) == [1]
    _same(model, condensation, limit=3000)
