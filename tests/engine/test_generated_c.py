"""C generated from the net's inscriptions (`cpn.engine.ccodegen`) computes the
transitions' bindings and effects for the native search. The Python engine stays the reference: the graph
must be the one the Python search finds (the same states under the same ids, arcs in the same order, the
same binding elements), whether a transition runs in C, is left to the Python engine (with a note saying
why), or the C code hands one computation back at run time."""

import glob
import os

import pytest

import cpn
from cpn.engine import ccodegen
from cpn.errors import EvaluationError
from cpn.statespace import ExploreOptions, Explorer, native, nativetimed
from cpn.statespace.store import packed_unavailable
from tests._shared import count_calls, needs_shared
from tests.engine._explore import same_exploration
from tests.engine.randomnets import random_net

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(__file__)))
MODELS = sorted(glob.glob(os.path.join(ROOT, "models", "**", "*.cpnet"), recursive=True))
SMALL = {"dp.cpnet": {"N": 5}, "ms.cpnet": {"N": 3}}
NATIVE = packed_unavailable()
needs_native = pytest.mark.skipif(NATIVE is not None, reason=f"native code unavailable: {NATIVE}")


@pytest.fixture
def returns(monkeypatch):
    """How many times the native search went back to the Python engine (the generated C missing)."""
    return count_calls(monkeypatch, native.NativeSearch, "_fill")


def _both(model, limit=3000):
    c = Explorer(model.engine(), ExploreOptions(backend="c", max_states=limit)).run()
    py = Explorer(model.engine(), ExploreOptions(backend="python", max_states=limit, packed_states=False)).run()
    same_exploration(c, py)
    assert [c.engine.format_binding_element(b) for b in set(c.graph.bes)] == \
        [py.engine.format_binding_element(b) for b in set(c.graph.bes)]
    return c


@needs_native
@pytest.mark.parametrize("path", MODELS + [os.path.join(ROOT, "bench", "nets", n) for n in SMALL],
                         ids=os.path.basename)
def test_generated_c_gives_the_python_graph_on_the_repository_models(path, returns, monkeypatch):
    monkeypatch.setattr(nativetimed, "HAND_OVER_RATE", 1e9)  # the timed ones: the C search to the end
    model = cpn.load(path, set=SMALL.get(os.path.basename(path)))
    c = _both(model)
    code, why = model.engine().native_code()
    assert c.backend == "c"
    if model.net.is_timed:  # the native timed search, with the C of the net's timed transitions
        assert code is None and why == "the net is timed"
        tcode, twhy = model.engine().timed_groups().native_code()
        if tcode is not None and not tcode.left:
            assert c.notes == []
        else:
            assert c.notes and all("the Python engine computes" in n for n in c.notes), c.notes
        return
    if code is not None and not code.left:
        assert returns[0] == 0, "a net wholly in C went back to the Python engine"
        assert c.notes == []
    else:
        assert any("the Python engine computes" in n for n in c.notes)


@needs_native
def test_the_benchmark_nets_run_wholly_in_c(returns):
    for name, n in (("dp.cpnet", 7), ("ms.cpnet", 4)):
        model = cpn.load(os.path.join(ROOT, "bench", "nets", name), set={"N": n})
        code, why = model.engine().native_code()
        assert why is None and code.left == {} and len(code.native) == len(model.net.transitions)
        c = _both(model, limit=10**6)
        assert c.backend == "c" and c.complete and c.notes == []
    assert returns[0] == 0


@needs_native
def test_generated_c_gives_the_python_graph_on_random_nets(returns):
    wholly = 0
    for seed in list(range(3, 1000, 23))[:24]:  # 24 nets (each compilation takes a second or two)
        text = random_net(seed)
        model = cpn.loads(text, f"random{seed}.cpnet")
        before = returns[0]
        try:
            _both(model, limit=300)
        except AssertionError:
            raise AssertionError(f"C and Python differ on random net {seed}:\n{text}") from None
        code, _ = model.engine().native_code()
        if code is not None and not code.left:
            assert returns[0] == before, f"random net {seed} went back to the Python engine:\n{text}"
            wholly += 1
    assert wholly >= 16  # the untimed ones are wholly in C


LEFT = """
colset N = int with 0..3;
var x : N;
fun add a b = (a + b) mod 4;
place P : N = 1`0 ++ 1`1;
place Q : N = 1`2;
trans grow [x < 3];
trans shift;
arc P -> grow : x;
arc grow -> P : x + 1;
arc Q -> shift : x;
arc shift -> Q : add x 1;
"""


@needs_native
def test_a_transition_outside_the_subset_is_left_to_python_with_a_note(returns):
    model = cpn.loads(LEFT, "left.cpnet")
    code, why = model.engine().native_code()
    assert why is None and code.native == [0] and list(code.left) == [1]
    c = _both(model)
    assert c.backend == "c" and returns[0] > 0
    assert c.notes == [f"the Python engine computes the bindings of transition '{model.net.transitions[1].name}': "
                       f"{code.left[1]}"]


@needs_native
def test_a_place_outside_the_subset_leaves_the_whole_net_to_python():
    model = cpn.loads("colset S = real; var s : S; place P : S = 1`0.0; trans t; arc P -> t : s;"
                      " arc t -> P : s + 1.0;", "reals.cpnet")
    c = Explorer(model.engine(), ExploreOptions(backend="c", max_states=5)).run()
    assert c.backend == "c"
    [note] = c.notes
    assert note.startswith("the Python engine computes every transition's bindings: place ")
    assert "real" in note


DEEP = """
colset N = int with 0..3;
var x : N;
fun depth n = if n = 0 then 0 else 1 + depth (n - 1);
place P : N = 1`0;
trans t [depth (100 * (x mod 2)) >= 0];
arc P -> t : x;
arc t -> P : (x + 1) mod 4;
"""


@needs_native
def test_what_c_cannot_evaluate_at_run_time_is_computed_by_python(returns):
    # the recursion goes deeper than the C code's bound: the Python engine computes those bindings
    model = cpn.loads(DEEP, "deep.cpnet")
    code, _ = model.engine().native_code()
    assert code.left == {}
    c = _both(model)
    assert c.n_states == 4 and returns[0] > 0


DIV = """
colset N = int with 0..3;
var x : N;
place P : N = 1`3;
trans t [10 div (x - 1) > 0];
arc P -> t : x;
arc t -> P : x - 1;
"""


@needs_native
def test_an_evaluation_error_in_generated_c_is_the_python_engines_error():
    errors = {}
    for backend in ("c", "python"):
        model = cpn.loads(DIV, "div.cpnet")
        with pytest.raises(EvaluationError) as info:
            Explorer(model.engine(), ExploreOptions(backend=backend)).run()
        errors[backend] = (str(info.value), info.value.trace)
    assert errors["c"] == errors["python"]
    assert "division by zero" in errors["c"][0]


def test_the_generated_code_follows_the_binding_plan():
    """Colour ids are positions in CS.all() (products in mixed radix), checked against the values."""
    model = cpn.loads("colset A = int with 2..4; colset B = bool; colset R = record x : A * y : B;"
                      " colset P = product A * R; var p : P; place Q : P; trans t; arc Q -> t : p;", "r.cpnet")
    lay = ccodegen.layout(model.net.colsets["P"])
    assert lay.size == 3 * 3 * 2 and lay.leaves == [(2, 3), (2, 3), (0, 2)]
    assert [lay.index[v] for v in lay.values] == list(range(lay.size))
    with pytest.raises(ccodegen.NotNative):
        ccodegen.layout(model.net.colsets["P"].__class__("S", [cpn.loads("colset S = string;", "s.cpnet")
                                                                 .net.colsets["S"]]))


@needs_native
def test_auto_builds_the_c_part_way_and_goes_on_with_the_same_graph(monkeypatch):
    """`--backend auto` starts with the engine answering the native search, and compiles the net's C once
    the search is large enough (or the engine is needed more than once a state): the states found so far
    are copied over, and the graph is the one the Python search finds."""
    upgrades = []
    upgrade = native.NativeSearch._upgrade

    def counted(self):
        upgrades.append(self.head)
        return upgrade(self)
    monkeypatch.setattr(native.NativeSearch, "_upgrade", counted)
    monkeypatch.setattr(native, "GENERATE_AFTER", 1500)
    monkeypatch.setattr(native, "GENERATE_PER_LINE", 0)
    for name, n, at in (("ms.cpnet", 5, 1536), ("dp.cpnet", 8, 512)):
        model = cpn.load(os.path.join(ROOT, "bench", "nets", name), set={"N": n})
        auto = Explorer(model.engine(), ExploreOptions(backend="auto")).run()
        py = Explorer(model.engine(), ExploreOptions(backend="python", packed_states=False)).run()
        same_exploration(auto, py)
        assert auto.backend == "c" and auto.notes == [] and upgrades[-1] == at
    # a search that ends before it is large enough never builds the C
    model = cpn.load(os.path.join(ROOT, "bench", "nets", "ms.cpnet"), set={"N": 3})
    Explorer(model.engine(), ExploreOptions(backend="auto")).run()
    assert len(upgrades) == 2


def _corpus():
    import json

    from tests._shared import SHARED

    try:
        with open(os.path.join(SHARED, "validation", "expected.json"), encoding="utf-8") as fh:
            instances = json.load(fh)["instances"]
    except OSError:
        return []
    limit = int(os.environ.get("CPN_NATIVE_CORPUS_STATES", "5000"))
    # small instances with few transitions: each one's C is compiled (a second or two)
    return [i for i in instances if i["states"] <= limit
            and (limit > 5000 or (i.get("transitions") or 0) <= 60)]


CORPUS = _corpus()


@needs_shared
@needs_native
@pytest.mark.parametrize("inst", CORPUS, ids=[i["name"] for i in CORPUS])
def test_generated_c_gives_the_python_graph_on_the_validation_corpus(inst):
    """`CPN_NATIVE_CORPUS_STATES=100000` compares every instance of up to 100,000 states."""
    from tests._shared import SHARED

    model = cpn.load(os.path.join(SHARED, "validation", inst["file"]))
    c = _both(model, limit=10**6)
    code, _why = model.engine().native_code()
    if c.backend == "python":  # transitions left to the engine, whose results rarely recur: handed over
        assert code is None or code.left
        assert any("handed over to the Python search" in n for n in c.notes)
    assert c.n_states == inst["states"]


# 3 * 2e9 * 2e9 * 4 = 4.8e19 does not fit 64 bits: wrapped around it would be negative and `t` dead in C.
OVERFLOW = """
colset N = int with 0..3;
var x : N;
place P : N = 1`3;
trans t [x * 2000000000 * 2000000000 * 4 > 0 andalso ~(x * 2000000000 * 2000000000 * 4) < 0
         andalso (x - 4000000000000000000 - 4000000000000000000 - 4000000000000000000) < 0];
arc P -> t : x;
arc t -> P : x - 1;
"""


@needs_native
def test_integer_overflow_in_generated_c_is_computed_by_python(returns):
    model = cpn.loads(OVERFLOW, "overflow.cpnet")
    code, _ = model.engine().native_code()
    assert code.left == {}, "the guard should be generated in C"
    c = _both(model)
    # x = 3, 2, 1 each satisfy the guard (the products exceed 2^63, the difference goes below -2^63)
    assert c.n_states == 4 and c.n_arcs == 3 and returns[0] > 0


@needs_native
def test_results_computed_anew_instead_of_cached_give_the_same_graph(monkeypatch, returns):
    """With the C of the net, a cache whose first lookups mostly miss stops storing results: they are
    computed for each state again. Judged after one lookup here, so that every cache of these nets
    turns so at once; the graphs are still the Python engine's."""
    searches = []
    flush = native.NativeSearch.flush

    def spy(self):
        searches.append(self)
        return flush(self)

    monkeypatch.setattr(native.NativeSearch, "flush", spy)
    monkeypatch.setattr(native, "UNCACHED_AFTER", 1)
    nets = [cpn.load(os.path.join(ROOT, "bench", "nets", "dp.cpnet"), set={"N": 7}),
            cpn.load(os.path.join(ROOT, "bench", "nets", "ms.cpnet"), set={"N": 4})]
    nets += [cpn.loads(random_net(seed), f"random{seed}.cpnet") for seed in range(3, 1000, 23)[:12]]
    turned = 0
    for model in nets:
        if model.net.is_timed:
            continue
        del searches[:]
        c = _both(model, limit=10**6 if model.net.name in ("DP", "MS") else 300)
        assert c.backend == "c"
        turned += searches[-1].uncached() > 0
    assert turned >= 8
    monkeypatch.setattr(native, "UNCACHED_AFTER", 0)  # every result cached: nothing turns
    del searches[:]
    _both(nets[0], limit=10**6)
    assert searches[-1].uncached() == 0
