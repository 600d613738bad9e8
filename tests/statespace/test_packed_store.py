"""The packed state store (states as fixed-width records in native memory, found through an
open-addressing hash table) and the native search (its loop, caches and arcs in C) give the very graph
the Python search with tuples gives: the same states under the same ids, the same arcs in the same order,
the same binding elements, BFS parents and levels."""

import glob
import os

import pytest

import cpn
from cpn.statespace import ExploreOptions, Explorer
from cpn.statespace.store import PackedStore, TupleStore, new_store, packed_unavailable
from tests.engine.randomnets import random_net

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(__file__)))
MODELS = sorted(glob.glob(os.path.join(ROOT, "models", "**", "*.cpnet"), recursive=True))
SMALL = {"dp.cpnet": {"N": 5}, "ms.cpnet": {"N": 3}}
NATIVE = packed_unavailable()
needs_native = pytest.mark.skipif(NATIVE is not None, reason=f"packed store unavailable: {NATIVE}")


def _explore(model, limit, **options):
    engine = model.engine(time_condensation=model.net.is_timed)
    return Explorer(engine, ExploreOptions(max_states=limit, **options)).run()


def _same_graph(model, limit=3000):
    b = _explore(model, limit, packed_states=False)
    assert b.graph.store.kind == "tuples" and b.backend == "python"
    ga = _same_as(_explore(model, limit, backend="python", pack_from=0), b)
    assert ga.store.kind == "packed"
    # packed part-way through the search (after the first 512 expansions)
    late = _explore(model, limit, backend="python", pack_from=600)
    _same_as(late, b)
    assert late.graph.store.kind == ("packed" if late.graph.expanded > 512 and len(late.graph.store) >= 600
                                     else "tuples")
    c = _explore(model, limit, backend="c")
    # timed nets too (cpn.statespace.nativetimed), which may hand over where most states need the engine
    assert c.backend == "c" or any("the native search handed over" in n for n in c.notes), c.notes
    _same_as(c, b)
    return ga


def _same_as(a, b):
    ga, gb = a.graph, b.graph
    assert a.stop_reason is b.stop_reason and a.levels == b.levels
    assert a.predicate_state == b.predicate_state
    assert len(ga.states) == len(gb.states)
    # the engines are distinct objects: compare what the states mean, in id order
    assert [a.engine.marking(s) for s in ga.states] == [b.engine.marking(s) for s in gb.states]
    assert [a.engine.clock(s) for s in ga.states] == [b.engine.clock(s) for s in gb.states]
    assert list(ga.offsets) == list(gb.offsets)
    assert list(ga.dst) == list(gb.dst)
    assert list(ga.bes) == list(gb.bes)
    assert list(ga.parent) == list(gb.parent) and list(ga.parent_be) == list(gb.parent_be)
    for i in (0, len(ga.states) // 2, len(ga.states) - 1):
        assert ga.state_id(ga.states[i]) == i
    return ga


@needs_native
# MODBUS's serial-line model is the longest (15 s on a 2-core machine): a long test (`--slow`); its graph is
# compared in the suite by the other tests of the packed store on the timed models
@pytest.mark.parametrize("path", [pytest.param(m, marks=pytest.mark.slow) if m.endswith(os.sep + "modbus.cpnet")
                                  else m for m in MODELS]
                         + [os.path.join(ROOT, "bench", "nets", n) for n in SMALL],
                         ids=os.path.basename)
def test_packed_store_gives_the_same_graph_on_the_repository_models(path):
    g = _same_graph(cpn.load(path, set=SMALL.get(os.path.basename(path))))
    assert g.store.kind == "packed"


@needs_native
def test_packed_store_gives_the_same_graph_on_random_nets(monkeypatch):
    monkeypatch.setenv("CPN_NO_GENERATED", "1")  # the generated C: tests/engine/test_generated_c.py
    for seed in range(0, 1000, 7):
        text = random_net(seed)
        try:
            _same_graph(cpn.loads(text, f"random{seed}.cpnet"), limit=300)
        except AssertionError:
            raise AssertionError(f"stores differ on random net {seed}:\n{text}") from None


@needs_native
def test_fields_widen_as_their_values_grow():
    st = new_store((0, 0, 0))
    assert isinstance(st, PackedStore) and st.widths == [1, 1, 1]
    states = [(i % 7, i, i * i) for i in range(1, 70_000, 97)] + [(1, 2, 1 << 40)]
    dst = []
    fresh = st.add_successors([(0, s) for s in states], dst)
    assert fresh == list(range(len(states))) and dst == list(range(1, len(states) + 1))
    assert st.widths == [1, 4, 8]
    assert list(st.states) == [(0, 0, 0)] + states
    assert [st.find(s) for s in states] == dst
    assert st.find((9, 9, 9)) is None
    # already-known states, some twice in one batch, keep their ids; a new one gets the next id
    again = []
    assert st.add_successors([(0, states[3]), (0, (5, 5, 5)), (0, (5, 5, 5)), (0, (0, 0, 0))], again) == [1]
    assert again == [4, len(states) + 1, len(states) + 1, 0]


@needs_native
def test_a_state_that_cannot_be_packed_turns_the_store_into_tuples():
    st = new_store((1, 2))
    st.add_successors([(0, (3, 4))], [])
    assert st.add_successors([(0, (5, -1)), (0, (3, 4)), (0, (1.5, 2))], dst := []) == [0, 2]
    assert dst == [2, 1, 3]
    assert st.kind == "tuples" and st.nbytes() is None
    assert list(st.states) == [(1, 2), (3, 4), (5, -1), (1.5, 2)]
    assert st.find((3, 4)) == 1


def test_states_other_than_int_tuples_use_the_tuple_store():
    assert isinstance(new_store(("a", 1)), TupleStore)
    assert isinstance(new_store(()), TupleStore)
    assert isinstance(new_store((1, 2), packed=False), TupleStore)


def test_without_native_code_the_search_uses_tuples(monkeypatch, tmp_path):
    import cpn.statespace.store as store_module
    from cpn._util import cbuild

    monkeypatch.setenv("CPN_NO_NATIVE", "1")
    monkeypatch.setattr(cbuild, "_loaded", {})
    assert "CPN_NO_NATIVE" in store_module.packed_unavailable()
    model = cpn.load(os.path.join(ROOT, "bench", "nets", "dp.cpnet"), set={"N": 4})
    x = Explorer(model.engine()).run()
    assert x.graph.store.kind == "tuples"
    assert (x.n_states, x.n_arcs) == (Explorer(model.engine(), ExploreOptions(packed_states=False)).run().n_states,
                                      Explorer(model.engine(), ExploreOptions(packed_states=False)).run().n_arcs)


def _without_times(d):
    if isinstance(d, dict):
        return {k: _without_times(v) for k, v in d.items() if "second" not in k and "memory" not in k}
    if isinstance(d, list):
        return [_without_times(v) for v in d]
    return d


@needs_native
def test_cli_backends_give_the_same_report(capsys):
    import json

    from cpn.cli.main import main

    model = os.path.join(ROOT, "bench", "nets", "ms.cpnet")
    reports = {}
    for backend in ("python", "c"):
        assert main(["explore", model, "--set", "N=3", "--backend", backend, "--json", "-"]) == 0
        out = capsys.readouterr()
        assert out.err == ""
        reports[backend] = _without_times(json.loads(out.out))
    assert reports["c"] == reports["python"]
    assert reports["c"]["statespace"]["states"] == 837


def test_cli_says_why_the_python_back_end_searches(capsys):
    from cpn.cli.main import main

    model = os.path.join(ROOT, "tests", "models", "reads_clock.cpnet")
    assert main(["explore", model, "--backend", "c", "--max-states", "50", "-q"]) in (0, 2)
    err = capsys.readouterr().err
    assert ("note: the Python back end searched this net: the guard of transition 'Top'late 1' reads the model clock, "
            "and the native search examines transitions at the clock and the occurrence time only") in err
    assert main(["explore", model, "--backend", "python", "--max-states", "50", "-q"]) in (0, 2)
    assert "note:" not in capsys.readouterr().err.replace("partial state space", "")


@needs_native
def test_native_search_hands_over_where_results_rarely_recur(monkeypatch):
    """DP's transitions see new markings of their input places in nearly every state: without C code of
    its inscriptions, the native search hands over to the Python search at its first look (512 states), and
    the graph is still the same; with it, the native search goes on to the end."""
    from tests.engine._explore import same_exploration

    model = cpn.load(os.path.join(ROOT, "bench", "nets", "dp.cpnet"), set={"N": 8})
    generated = Explorer(model.engine(), ExploreOptions(backend="c")).run()
    assert generated.backend == "c" and generated.notes == []
    monkeypatch.setenv("CPN_NO_GENERATED", "1")
    c = Explorer(model.engine(), ExploreOptions(backend="c")).run()
    py = Explorer(model.engine(), ExploreOptions(backend="python", packed_states=False)).run()
    assert c.backend == "python" and c.graph.store.kind == "packed"
    assert any("handed over to the Python search after 512 states" in n for n in c.notes)
    same_exploration(c, py)
    same_exploration(generated, py)
    ms = cpn.load(os.path.join(ROOT, "bench", "nets", "ms.cpnet"), set={"N": 4})
    x = Explorer(ms.engine(), ExploreOptions(backend="c")).run()
    assert x.backend == "c" and x.notes == []


COUNTER = """net Counter;
colset C = int with 0..70000;
colset S = int with 0..2;
var x : C;
var y : S;
place P : C = 1`0;
place Q : S = 1`0;
trans Inc [x < 70000];
arc P -> Inc : x;
arc Inc -> P : x + 1;
arc Q <-> Inc : y;
"""


@needs_native
def test_native_search_widens_its_records_as_place_ids_grow():
    """The native search keeps a field in the fewest bytes its ids so far need: P's 70,001 markings take it
    from one byte to two and to four during the search, Q's one stays in one byte; the graph is the Python one."""
    from tests.engine._explore import same_exploration

    model = cpn.loads(COUNTER, "counter.cpnet")
    c = Explorer(model.engine(), ExploreOptions(backend="c")).run()
    py = Explorer(model.engine(), ExploreOptions(backend="python", packed_states=False)).run()
    assert c.backend == "c" and c.n_states == py.n_states == 70_001
    assert c.graph.store.widths == [4, 1]
    same_exploration(c, py)
    assert c.graph.state_id(c.graph.states[-1]) == c.n_states - 1


@needs_native
def test_a_slice_of_packed_states_decodes_as_its_states():
    st = new_store((0, 0))
    st.add_successors([(0, (i % 300, i)) for i in range(1, 1000)], [])
    states = st.states
    one_by_one = [states[j] for j in range(len(states))]
    assert one_by_one[:3] == [(0, 0), (1, 1), (2, 2)] and one_by_one[-1] == (999 % 300, 999)
    for sl in (slice(5, 17), slice(990, 2000), slice(10, 5), slice(None, None, 7), slice(-3, None), slice(0, 0)):
        assert states[sl] == one_by_one[sl]
