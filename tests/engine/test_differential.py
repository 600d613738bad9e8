"""The compiled engine against the reference interpreter: same enabled binding elements, same successors
(timestamps included), on every model of the repository and on random nets; and the native search
(`--backend c`) against the Python search with tuples: the same graph."""

import functools
import glob
import os

import pytest

import cpn
from cpn.engine.clock import TimeCondensationRefused
from cpn.statespace import ExploreOptions, Explorer, nativetimed
from cpn.statespace.store import packed_unavailable
from tests.engine._explore import graph, same_exploration
from tests.engine.randomnets import random_net, random_timed_net

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(__file__)))
# the repository's models, and the small models of the tests (local declarations, exceptions, lists as
# multisets, long chains, records, recursion, a model that reads the clock) but the one that stops with an
# uncaught exception on purpose
MODELS = sorted(glob.glob(os.path.join(ROOT, "models", "**", "*.cpnet"), recursive=True)
                + [p for p in glob.glob(os.path.join(ROOT, "tests", "models", "*.cpnet"))
                   if not p.endswith("uncaught.cpnet")])
SMALL = {"dp.cpnet": {"N": 4}, "ms.cpnet": {"N": 2}}


def _compare(model, condensation=False, limit=150):
    """The canonical graphs of both engines (every marking with timestamps and clock, and per marking the
    binding elements with their successors) agree: completely if the state space has fewer than `limit`
    states, else on every state both engines expanded among their first `limit`."""
    a = graph(model.engine(time_condensation=condensation), limit)
    b = graph(model.engine(time_condensation=condensation, reference=True), limit)
    if len(a) < limit and len(b) < limit:
        assert a.keys() == b.keys()
    common = a.keys() & b.keys()
    assert common, "the engines do not even agree on the initial state"
    for k in common:
        assert a[k] == b[k], k


def test_each_folder_of_models_holds_models():
    """The folders globbed above exist and hold models (a glob of a moved or misspelt folder finds nothing, and
    the comparison would silently leave those models out)."""
    for folder in (os.path.join(ROOT, "models"), os.path.join(ROOT, "tests", "models")):
        assert any(p.startswith(folder + os.sep) for p in MODELS), f"no model of {folder} is compared"


@pytest.mark.parametrize("path", MODELS + [os.path.join(ROOT, "bench", "nets", n) for n in SMALL],
                         ids=os.path.basename)
def test_repository_models(path):
    model = cpn.load(path, set=SMALL.get(os.path.basename(path)))
    # time condensation only where it is sound: on a model that does not read the clock
    _compare(model, condensation=model.net.is_timed and not model.engine().reads_clock)
    if model.net.is_timed:
        _compare(model, condensation=False, limit=60)


@functools.lru_cache(maxsize=None)
def _random_model(seed: int):
    """Random net `seed`, loaded once for test_random_nets and test_random_nets_native_search (a model is
    only read: each engine is compiled from its net anew)."""
    return cpn.loads(random_net(seed), f"random{seed}.cpnet")


@pytest.fixture(scope="module", autouse=True)
def _forget_random_models():
    yield
    _random_model.cache_clear()


@pytest.mark.parametrize("chunk", range(10))
def test_random_nets(chunk):
    """1,000 random nets in ten chunks of 100."""
    for seed in range(chunk * 100, chunk * 100 + 100):
        text = random_net(seed)
        model = _random_model(seed)
        try:
            _compare(model, condensation=model.net.is_timed and seed % 2 == 0, limit=25)
        except AssertionError:
            raise AssertionError(f"engines differ on random net {seed}:\n{text}") from None


@pytest.mark.parametrize("chunk", range(3))
def test_random_timed_nets(chunk):
    """300 random timed nets in three chunks of 100, about half of them reading the clock: without time
    condensation; with it where it is sound (the net does not read the clock), else both engines refuse it."""
    for seed in range(chunk * 100, chunk * 100 + 100):
        text = random_timed_net(seed)
        model = cpn.loads(text, f"timed{seed}.cpnet")
        try:
            _compare(model, condensation=False, limit=30)
            if model.engine().reads_clock:
                for reference in (False, True):
                    with pytest.raises(TimeCondensationRefused):
                        model.engine(time_condensation=True, reference=reference)
            else:
                _compare(model, condensation=True, limit=30)
        except AssertionError:
            raise AssertionError(f"engines differ on random timed net {seed}:\n{text}") from None


NATIVE = packed_unavailable()


def _same_search(model, limit):
    cond = model.net.is_timed
    c = Explorer(model.engine(time_condensation=cond), ExploreOptions(max_states=limit, backend="c")).run()
    py = Explorer(model.engine(time_condensation=cond),
                  ExploreOptions(max_states=limit, backend="python", packed_states=False)).run()
    assert py.backend == "python" and py.graph.store.kind == "tuples"
    # timed nets and priorities too (cpn.statespace.nativetimed); a net reading the clock stays in Python
    assert c.backend == ("python" if model.engine().reads_clock else "c"), c.notes
    same_exploration(c, py)


@pytest.mark.skipif(NATIVE is not None, reason=f"no native code: {NATIVE}")
@pytest.mark.parametrize("chunk", range(5))
def test_random_nets_native_search(chunk, monkeypatch):
    """The native search on the 1,000 random nets, in five chunks of 200 (timed ones included), its
    transitions answered by the engine (C generated from the inscriptions: tests/engine/test_generated_c.py,
    which compiles fewer nets: a compilation takes a second or two)."""
    monkeypatch.setenv("CPN_NO_GENERATED", "1")
    monkeypatch.setattr(nativetimed, "HAND_OVER_RATE", 1e9)  # timed nets: the C search to the end
    for seed in range(chunk * 200, chunk * 200 + 200):
        text = random_net(seed)
        model = _random_model(seed)
        try:
            _same_search(model, limit=150)
        except AssertionError:
            raise AssertionError(f"native and Python searches differ on random net {seed}:\n{text}") from None


FAMILY = """
val N = 3;
colset INT = int;
colset TINT = int timed;
colset K = int with 1..N;
var x, c : INT;
place go : TINT = 1`1 ++ 1`2 @+ 1;
place done : INT;
module Stage(me : K) {
  port io Tok : TINT;
  port out Out : INT;
  place Count : INT = 1`0;
  trans pass [x = me orelse x = me + N, c < 2] @+ me;
  arc Tok -> pass : x;
  arc Count -> pass : c;
  arc pass -> Count : c + 1;
  arc pass -> Tok : (if x < N then 1`(x + 1) else empty) @+ c;
  arc pass -> Out : if x >= N then 1`x else empty;
}
instance Stage[i : 1..N] = Stage(me = i) { Tok = go, Out = done };
"""


@pytest.mark.parametrize("n", ["1", "3"])
def test_instance_family(n):
    """A family of module instances (`instance Stage[i : 1..N] = ...`, the bound set from outside)."""
    model = cpn.loads(FAMILY, "family.cpnet", set={"N": n})
    assert len([t for t in model.net.transitions if t.page == "Stage"]) == int(n)
    _compare(model, condensation=True)
    _compare(model, condensation=False)
