"""The C generated from a timed net's inscriptions, or from those of a net with priorities
(`cpn.engine.ccodegen.TimedTransitionC`), under the native timed search (`cpn.statespace.nativetimed`):
the graph must be the Python search's own (the same states under the same ids, arcs in the same order,
the same binding elements and dead markings), and where every transition is in C the search never
returns to the engine."""

import os
import random

import pytest

import cpn
from cpn.statespace import ExploreOptions, Explorer, nativetimed
from cpn.statespace.store import packed_unavailable
from tests._shared import count_calls
from tests.engine._explore import same_exploration
from tests.engine.randomnets import random_net, random_timed_net
from tests.statespace._native import same_error

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(__file__)))
NATIVE = packed_unavailable()
needs_native = pytest.mark.skipif(NATIVE is not None, reason=f"native code unavailable: {NATIVE}")




def _both(model, condensation: bool, limit: int):
    c = Explorer(model.engine(time_condensation=condensation),
                 ExploreOptions(backend="c", max_states=limit)).run()
    py = Explorer(model.engine(time_condensation=condensation),
                  ExploreOptions(backend="python", max_states=limit, packed_states=False)).run()
    assert c.backend == "c" and py.backend == "python", c.notes
    same_exploration(c, py)  # (the same offsets: the same dead markings)
    # the same ids of the places' markings, each kept with its tokens in the same order
    assert [tuple(s) for s in c.graph.states] == [tuple(s) for s in py.graph.states]
    assert [[list(d.items()) for d in c.engine.marking(s)] for s in c.graph.states] == \
        [[list(d.items()) for d in py.engine.marking(s)] for s in py.graph.states]
    assert c.untimed_states == py.untimed_states and c.time_growth == py.time_growth
    return c


def _without_clock(text: str) -> str:
    """A random timed net whose reads of the clock are the constant 0 (the native timed search examines
    transitions that do not read it)."""
    return text.replace("intTime()", "0")


def _with_priorities(text: str, seed: int) -> str:
    rng = random.Random(seed)
    out = []
    for line in text.splitlines():
        if line.startswith("trans ") and "priority" not in line and rng.random() < 0.7:
            line = line.rstrip(";") + f" priority {rng.choice([500, 1000, 2000])};"
        out.append(line)
    return "\n".join(out) + "\n"


@needs_native
def test_random_timed_nets_run_wholly_in_generated_c(fills):
    """Random timed nets (timed int, unit and product colour sets, delays on transitions and output arcs,
    initial timestamps, inhibitor, reset and double arcs on timed places, priorities), with and without
    time condensation: each a compilation of its C, so 24 of them."""
    ran = 0
    for seed in range(0, 96, 4):
        text = _without_clock(random_timed_net(seed))
        if seed % 8 == 4:
            text = _with_priorities(text, seed)
        model = cpn.loads(text, f"timed{seed}.cpnet")
        code, why = model.engine().timed_groups().native_code()
        assert why is None and code.left == {}, (why, code and code.left)
        for condensation in (False, True):
            fills[0] = 0
            try:
                c = _both(model, condensation, limit=300)
            except AssertionError:
                raise AssertionError(f"C and Python differ on random timed net {seed} (condensation "
                                     f"{condensation}):\n{text}") from None
            assert fills[0] == 0 and c.notes == [], (seed, c.notes)
            ran += 1
    assert ran == 48


@needs_native
def test_random_nets_with_priorities_run_wholly_in_generated_c(fills):
    ran = 0
    for seed in range(1, 200, 13):
        text = _with_priorities(random_net(seed), seed)
        model = cpn.loads(text, f"random{seed}.cpnet")
        if model.net.is_timed or all(t.priority is None for t in model.net.transitions):
            continue
        code, why = model.engine().timed_groups().native_code()
        if why is not None or code.left:
            continue
        fills[0] = 0
        try:
            c = _both(model, False, limit=300)
        except AssertionError:
            raise AssertionError(f"C and Python differ on random net {seed}:\n{text}") from None
        assert fills[0] == 0 and c.notes == []
        ran += 1
    assert ran >= 8


MIXED = """
colset N = int with 0..3 timed;
colset L = list N;
var x, y : N;
place P : N = 1`0 ++ (1`1@+1) ++ (1`2@+3);
place Q : N;
place R : N = 1`3;
trans inc [x < 3] @+ 1 priority 1000;
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
def test_a_transition_left_to_python_beside_transitions_in_c(condensation, fills):
    """`back` makes a string: the engine computes its bindings (a note says why), the others run in C, and
    the tables both keep stay in step (the ids agree)."""
    model = cpn.loads(MIXED, "mixed.cpnet")
    code, _ = model.engine().timed_groups().native_code()
    assert sorted(code.left) == [1] and len(code.native) == 2
    c = _both(model, condensation, limit=3000)
    [note] = c.notes
    assert note.startswith("the Python engine computes the bindings of transition 'Top'back 1'")
    assert 0 < fills[0] < c.graph.expanded


@needs_native
def test_an_error_in_c_is_the_python_engines_report():
    """A division by zero in a delay computed in C: the engine evaluates it again and reports it, as the
    Python search does."""
    text = ("colset N = int with 0..3 timed; var x : N; place P : N = 1`2;"
            " trans t [x > 0]; arc P -> t : x; arc t -> P : (x - 1) @+ (6 div (x - 1));")
    error = same_error(cpn.loads(text, "div.cpnet"), max_states=100)
    assert "the inscription of arc" in error and "x=1" in error, error


@needs_native
def test_auto_searches_a_net_wholly_in_c_natively_building_its_c_on_the_way(fills, monkeypatch):
    """`auto` on a timed net whose transitions are all in C: the native timed search, the engine filling
    its caches up to `GENERATE_AFTER` states, the net's C from there on; the Python search's graph."""
    from cpn.statespace import explore

    monkeypatch.setattr(explore, "CHECK_EVERY", 64)  # (else the search looks at its limits at 512 states only)
    monkeypatch.setattr(nativetimed, "GENERATE_AFTER", 200)
    monkeypatch.setattr(nativetimed, "GENERATE_PER_LINE", 0)  # (else 4 per line of its C: past the 729 states)
    built: list[int] = []  # the search's head where it went on with the net's C
    upgrade = nativetimed.TimedNativeSearch._timed_library
    monkeypatch.setattr(nativetimed.TimedNativeSearch, "_timed_library",
                        lambda self: built.append(self.head) or upgrade(self))
    model = cpn.load(os.path.join(ROOT, "bench", "nets", "ms_timed.cpnet"), set={"N": "4"})
    auto = Explorer(model.engine(time_condensation=True), ExploreOptions()).run()
    py = Explorer(model.engine(time_condensation=True), ExploreOptions(backend="python", packed_states=False)).run()
    assert auto.backend == "c" and auto.backend_notes == [] and auto.notes == []
    same_exploration(auto, py)
    assert auto.untimed_states == py.untimed_states  # the watch's count across the C being built
    assert auto.complete and auto.n_states == 729
    assert len(built) == 1 and 200 <= built[0] < 729
    assert 0 < fills[0] < 400  # the engine expanded states before the C was built, none after


@needs_native
def test_auto_goes_on_in_c_at_once_where_a_run_before_built_the_nets_c(fills, monkeypatch, tmp_path):
    """Past `LOOK_FOR_BUILT_AFTER` states `auto` looks in the compile cache: where a run before built this
    net's C (with the same constants), the search goes on in C from there; else it makes and builds nothing
    then, and the engine goes on filling the caches up to `GENERATE_AFTER`. The Python search's graph
    every time."""
    from cpn.statespace import explore
    from cpn.statespace.native import library_built

    monkeypatch.setenv("CPN_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(explore, "CHECK_EVERY", 64)  # the search looks at its limits every 64 states
    monkeypatch.setattr(nativetimed, "LOOK_FOR_BUILT_AFTER", 100)
    monkeypatch.setattr(nativetimed, "GENERATE_PER_LINE", 0)
    attached: list[int] = []  # the search's head where it went on with the net's C
    upgrade = nativetimed.TimedNativeSearch._timed_library
    monkeypatch.setattr(nativetimed.TimedNativeSearch, "_timed_library",
                        lambda self: attached.append(self.head) or upgrade(self))
    made = count_calls(monkeypatch, nativetimed.TimedNativeSearch, "_make_code")

    def search(n: str, generate_after: int):
        monkeypatch.setattr(nativetimed, "GENERATE_AFTER", generate_after)
        model = cpn.load(os.path.join(ROOT, "bench", "nets", "ms_timed.cpnet"), set={"N": n})
        x = Explorer(model.engine(time_condensation=True), ExploreOptions()).run()
        same_exploration(x, Explorer(model.engine(time_condensation=True),
                                     ExploreOptions(backend="python", packed_states=False)).run())
        assert x.backend == "c" and x.notes == [] and x.complete
        return model

    search("4", 10**9)  # an empty cache: nothing made at the look, nothing built
    assert attached == [] and made[0] == 0
    model = search("4", 300)  # the C built past 300 states
    assert len(attached) == 1 and 300 <= attached[0] < 729
    assert library_built(model.engine(time_condensation=True).timed_groups().native_code()[0], timed=True)
    attached.clear()
    before = fills[0]
    search("4", 10**9)  # the same net and constants: in C from the look on
    assert len(attached) == 1 and 100 <= attached[0] < 300 and fills[0] > before
    attached.clear()
    search("3", 10**9)  # other constants: another net, whose C no run built
    assert attached == []

UNBOUNDED = """
colset N = int with 0..3 timed;
colset I = real;
var x : N;
var i : I;
place P : N = 1`0 ++ (1`1@+1);
place C : I = 1`0.0;
trans inc [x < 3] @+ 1;
arc P -> inc : x;
arc inc -> P : (x + 1) @+ 1;
trans count [i < 4.0];
arc P -> count : x;
arc C -> count : i;
arc count -> C : i + 1.0;
arc count -> P : 0 @+ 2;
"""


@needs_native
@pytest.mark.parametrize("condensation", [False, True], ids=["timed", "condensed"])
def test_a_place_c_cannot_hold_leaves_only_its_transitions_to_python(condensation, fills):
    """Place C's colour set (reals) has no C representation: `count`, which reads it, is the
    engine's, `inc` runs in C; the markings of C are the engine's alone."""
    model = cpn.loads(UNBOUNDED, "unbounded.cpnet")
    code, _ = model.engine().timed_groups().native_code()
    assert code.native == [0] and code.layouts[1] is None
    c = _both(model, condensation, limit=3000)
    assert c.notes == ["the Python engine computes the bindings of transition 'Top'count 1': colour set I (real) has "
                       "no C layout"]
    assert 0 < fills[0] <= c.graph.expanded  # (count reads P, whose timed marking rarely recurs)


def test_a_net_without_a_transition_in_c_has_one_reason():
    model = cpn.loads("colset L = real timed; var l : L; place P : L = 1`0.0;"
                      " trans t [l < 3.0]; arc P -> t : l; arc t -> P : (l + 1.0) @+ 1;", "reals.cpnet")
    code, why = model.engine().timed_groups().native_code()
    assert code is None and why == "place 'Top'P 1': colour set L (real) has no C layout"


STATES = """
colset ST = union Idle + Busy + Done timed;
colset N = int with 0..2;
colset SN = product ST * N timed;
var s : ST;
var n : N;
fun next Idle = Busy | next Busy = Done | next Done = Idle;
place P : SN = 1`(Idle, 0) ++ (1`(Busy, 1)@+1);
place Q : ST = 1`Done;
trans go [s <> Done] @+ 1;
arc P -> go : (s, n);
arc go -> P : (next s, (n + 1) mod 3);
trans fin;
arc P -> fin : (Done, n);
arc Q -> fin : s;
arc fin -> P : (if s = Done then Idle else Busy, n) @+ 2;
arc fin -> Q : Idle;
trans back [s = Idle];
arc Q -> back : s;
arc back -> Q : Done @+ 1;
"""


@needs_native
@pytest.mark.parametrize("condensation", [False, True], ids=["timed", "condensed"])
def test_a_union_without_data_is_an_enumeration_in_c(condensation, fills):
    """A union whose constructors carry no data: its values are their positions in C, in tokens, products,
    patterns of a function's clauses, guards, conditionals and constants."""
    model = cpn.loads(STATES, "states.cpnet")
    code, why = model.engine().timed_groups().native_code()
    assert why is None and code.left == {}
    c = _both(model, condensation, limit=500)
    assert c.notes == [] and fills[0] == 0 and c.n_states > 50
    untimed = cpn.loads(STATES.replace(" timed;", ";").replace("@+1", "").replace(" @+ 1", "")
                        .replace(" @+ 2", ""), "states_untimed.cpnet")
    code, why = untimed.engine().native_code()
    assert why is None and code.left == {}
    same_exploration(Explorer(untimed.engine(), ExploreOptions(backend="c")).run(),
                     Explorer(untimed.engine(), ExploreOptions(backend="python", packed_states=False)).run())


@pytest.mark.parametrize("path", ["bench/nets/ms_timed.cpnet", "bench/nets/dp.cpnet"])
def test_the_same_net_loaded_again_in_a_process_gives_the_same_c(path):
    """The net's C names nothing by the process's symbol numbers (which grow with every load): loaded again,
    the same net is the same C, one library in the compile cache (the C of a model's functions included)."""
    from cpn.engine.protocol import capability

    sources = []
    for _ in range(2):
        e = cpn.load(os.path.join(ROOT, path)).engine()
        code = e.timed_groups().native_code()[0] if e.is_timed else capability(e, "native_code")()[0]
        sources.append(code.source)
    assert sources[0] == sources[1] and "static int64_t uf" in sources[0]  # (a function of the model in C)
