"""The native search of timed nets and of nets with priorities (`cpn.statespace.nativetimed`,
`_timed.c`, `cpn.engine.timedgroups`). The graph must be the Python search's own (the same states under
the same ids, arcs in the same order, the same binding elements, BFS parents and levels, the same stop and
time-growth evidence), with and without time condensation; each test asserts that the C search ran."""

import glob
import os
import random

import pytest

import cpn
from cpn.statespace import ExploreOptions, Explorer, chooser, native, nativetimed
from cpn.statespace.store import packed_unavailable
from tests._checkrun import check_reports, record_backends
from tests._shared import needs_shared
from tests.engine._explore import same_exploration
from tests.engine.randomnets import random_net, random_timed_net

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(__file__)))
NATIVE = packed_unavailable()
needs_native = pytest.mark.skipif(NATIVE is not None, reason=f"native code unavailable: {NATIVE}")
TIMED_MODELS = [p for p in sorted(glob.glob(os.path.join(ROOT, "models", "**", "*.cpnet"), recursive=True)
                                  + glob.glob(os.path.join(ROOT, "tests", "statespace", "models", "*.cpnet")))
                if "timed" in open(p).read()]
LEFT_NOTE = "the Python engine computes "




def _both(model, condensation: bool, limit: int = 3000, **options):
    """The C search and the Python search of `model`: the same graph; the C search ran to the end."""
    c = Explorer(model.engine(time_condensation=condensation),
                 ExploreOptions(backend="c", max_states=limit, **options)).run()
    py = Explorer(model.engine(time_condensation=condensation),
                  ExploreOptions(backend="python", max_states=limit, packed_states=False, **options)).run()
    assert c.backend == "c" and py.backend == "python", c.notes
    assert not any("handed over" in n for n in c.notes), c.notes
    same_exploration(c, py)
    assert c.untimed_states == py.untimed_states and c.time_growth == py.time_growth
    return c


@needs_native
@pytest.mark.parametrize("path", TIMED_MODELS, ids=os.path.basename)
@pytest.mark.parametrize("condensation", [False, True], ids=["timed", "condensed"])
def test_the_repository_timed_models_run_in_c(path, condensation, fills):
    model = cpn.load(path)
    assert model.net.is_timed
    c = _both(model, condensation)
    assert all(n.startswith(LEFT_NOTE) for n in c.notes), c.notes
    if c.notes:  # some transitions' bindings come from the engine
        assert 0 < fills[0] <= c.graph.expanded
    else:  # the net's generated C computes everything: the search never returns to the engine
        assert fills[0] == 0


SAMPLES = ["TimedProtocol.cpn", "TimedResourceAlloc.cpn", "priorities.cpn"]


@needs_shared
@needs_native
@pytest.mark.parametrize("name", SAMPLES)
def test_cpn_tools_timed_samples_run_in_c(name, fills):
    """CPN Tools' timed samples (priorities.cpn: timed, with priorities), both ways, up to 3,000 states."""
    from tests._shared import SHARED

    path = os.path.join(SHARED, "cpntools-samples", name)
    model = cpn.load(path)
    for condensation in (False, True):
        c = _both(model, condensation)
        assert c.n_states >= 50 and (fills[0] > 0 or not c.notes)  # (wholly in C: never the engine)


@needs_native
def test_the_time_growth_watch_stops_the_c_search_where_it_stops_python(fills):
    model = cpn.load(os.path.join(ROOT, "models", "examples", "stop_and_wait.cpnet"))
    c = _both(model, False, limit=10**6)
    assert c.stop_reason.value == "time_grows" and c.time_growth is not None
    # the states C found without the engine: their values were all cached
    assert fills[0] < c.graph.expanded


@needs_native
def test_random_timed_nets_run_in_c(fills):
    """Every random timed net that does not read the clock, with and without time condensation: priorities,
    delays on transitions and arcs, inhibitor and reset arcs on timed places."""
    ran = 0
    for seed in range(120):
        text = random_timed_net(seed)
        model = cpn.loads(text, f"timed{seed}.cpnet")
        if model.engine().reads_clock:
            continue
        for condensation in (False, True):
            try:
                _both(model, condensation, limit=200)
            except AssertionError:
                raise AssertionError(f"C and Python differ on random timed net {seed} (condensation "
                                     f"{condensation}):\n{text}") from None
            ran += 1
    assert ran >= 100


def _with_priorities(text: str, seed: int) -> str:
    """The random net with priorities on some of its transitions (500, 1000 or 2000)."""
    rng = random.Random(seed)
    lines = []
    for line in text.splitlines():
        if line.startswith("trans ") and rng.random() < 0.7:
            line = line.rstrip(";") + f" priority {rng.choice([500, 1000, 2000])};"
        lines.append(line)
    return "\n".join(lines) + "\n"


@needs_native
def test_random_nets_with_priorities_run_in_c(fills, monkeypatch):
    """The search with its caches filled by the engine (without the nets' C: a compilation each;
    tests/statespace/test_native_timed_c.py runs their C)."""
    monkeypatch.setenv("CPN_NO_GENERATED", "1")
    ran = 0
    for seed in range(200):
        text = _with_priorities(random_net(seed), seed)
        model = cpn.loads(text, f"random{seed}.cpnet")
        if model.net.is_timed or all(t.priority is None for t in model.net.transitions):
            continue
        try:
            _both(model, False, limit=200)
        except AssertionError:
            raise AssertionError(f"C and Python differ on random net {seed}:\n{text}") from None
        ran += 1
    assert ran >= 100


PRIORITIES = """
colset N = int with 0..3;
var x : N;
place P : N = 1`0 ++ 1`1 ++ 1`2;
place Q : N;
trans low priority 2000;
trans high [x <> 1] priority 500;
trans normal;
arc P -> low : x;
arc low -> Q : x;
arc P -> high : x;
arc high -> Q : x;
arc Q -> normal : x;
arc normal -> P : (x + 1) mod 4;
"""


@needs_native
def test_priorities_select_in_c(fills):
    """`high` (500) goes first wherever it is enabled; `low` (2000) only where nothing else is."""
    model = cpn.loads(PRIORITIES, "priorities.cpnet")
    assert model.engine().successor_groups() is None
    c = _both(model, False)
    assert c.notes == [] and fills[0] == 0  # the net's generated C computes every transition's bindings
    names = {c.engine.format_binding_element(be).split(":")[0] for be in c.graph.bes}
    assert names == {"Top'high 1", "Top'normal 1", "Top'low 1"}
    for i in range(c.graph.expanded):
        fired = {c.engine.format_binding_element(be).split(":")[0] for be, _d in c.graph.out_arcs(i)}
        assert not ({"Top'high 1"} < fired)  # nothing of a larger priority beside `high`


@needs_native
def test_a_model_time_past_32_bits_hands_over_to_python():
    model = cpn.loads("colset T = unit timed; place P : T = 1`(); trans t @+ 3000000000; arc P -> t; arc t -> P;",
                      "far.cpnet")
    c = Explorer(model.engine(), ExploreOptions(backend="c", max_states=4)).run()
    py = Explorer(model.engine(), ExploreOptions(backend="python", max_states=4, packed_states=False)).run()
    same_exploration(c, py)
    assert c.backend == "python"
    assert any("handed over to the Python search after 2 states: the model time 6000000000 does not fit" in n
               for n in c.notes), c.notes


def test_the_engine_expands_a_state_as_its_successor_function_does():
    """`TimedGroups.expand(s).succ` is `successors(s)` on the states of random timed nets."""
    for seed in range(0, 60):
        model = cpn.loads(random_timed_net(seed), f"timed{seed}.cpnet")
        for condensation in (False, True):
            engine = model.engine(time_condensation=condensation)
            if engine.reads_clock:
                assert engine.timed_groups() is None
                break
            twin = model.engine(time_condensation=condensation)
            tg = twin.timed_groups()
            states = [engine.initial_state()]
            assert twin.initial_state() == states[0]
            i = 0
            while i < min(len(states), 40):
                succ = engine.successors(states[i])
                assert tg.expand(states[i], successors=True).succ == succ, seed
                states.extend(t for _be, t in succ if t not in states)
                i += 1


@needs_native
def test_the_clock_widens_the_records_of_the_c_search(fills):
    """The clock outgrows 1 and then 2 bytes: the store's records widen during the search, and the
    time-growth watch reads the states at their new width."""
    model = cpn.loads("colset T = unit timed; place P : T = 1`(); trans t @+ 10000; arc P -> t; arc t -> P;",
                      "slow.cpnet")
    c = _both(model, False, limit=100)
    assert c.stop_reason.value == "time_grows" and c.graph.store.widths[-1] == 4
    assert max(c.engine.clock(s) for s in c.graph.states) > 65535


@needs_native
def test_the_c_search_hands_over_where_nearly_every_state_needs_the_engine(monkeypatch):
    """MODBUS scenario B without the net's generated C: the slaves' transitions read the bus place, whose
    marking is new in nearly every state; past 64 states the search goes on in Python, with the same graph.
    (With it, enough of them are C's that the search stays native, with the same graph.)"""
    monkeypatch.setenv("CPN_NO_GENERATED", "1")
    values = {"CONFIG": '"B"', "NS": "8", "ADRS": "[0,1,2,3,4,5,6,7,8]", "FCS": "[1]", "PO": "1"}
    model = cpn.load(os.path.join(ROOT, "models", "modbus", "modbus.cpnet"), set=values)
    c = Explorer(model.engine(time_condensation=True), ExploreOptions(backend="c")).run()
    py = Explorer(model.engine(time_condensation=True), ExploreOptions(backend="python", packed_states=False)).run()
    same_exploration(c, py)
    assert c.backend == "python"
    [note] = [n for n in c.notes if "handed over" in n]
    assert note.startswith("the native search handed over to the Python search after 6")
    assert "times on average (transitions' results rarely recur)" in note


EARLY = """name = "early"
model = "MODEL"

[set]
CONFIG = '"B"'
NS = "6"
ADRS = "[0,2,3,4]"
FCS = "[1]"
PO = "0"

[explore]
time_condensation = true

[[property]]
name = "never two copies of a frame on b2s (false early on: a broadcast)"
kind = "invariant"
expr = "size (Modbus'b2s 1) <= 1"
"""


@needs_native
@pytest.mark.parametrize("name,to_the_end", [("A_1", True), ("D_4_faults", True), ("early", False)])
def test_modbus_scenario_checks_search_natively_with_the_python_verdicts(name, to_the_end, tmp_path, capsys,
                                                                          monkeypatch):
    """`cpn-verify check` on a MODBUS scenario file (timed, condensed): the native timed search runs under
    the check's monitor (to the end, or handing over to the Python search, which shows the monitor the
    states from there on), and the reports are those of the Python search."""
    monkeypatch.setattr(native, "TIMED_AUTO", True)  # a check runs with `auto`
    if to_the_end:
        monkeypatch.setattr(nativetimed, "HAND_OVER_RATE", 1e9)
    spec = os.path.join(ROOT, "specs", "modbus", f"{name}.toml")
    if name == "early":  # B.5's net hands over after 64 states; the monitor must see the states before
        spec = str(tmp_path / "early.toml")
        with open(spec, "w", encoding="utf-8") as f:
            f.write(EARLY.replace("MODEL", os.path.join(ROOT, "models", "modbus", "modbus.cpnet").replace("\\", "/")))
    backends = record_backends(monkeypatch)
    code_c, docs_c = check_reports(tmp_path, "c", capsys, spec)
    assert backends and backends == [None] * len(backends)
    monkeypatch.setattr(chooser, "why_not_native", lambda *_: "the Python search, for comparison")
    code_py, docs_py = check_reports(tmp_path, "py", capsys, spec)
    assert code_c == code_py and docs_c == docs_py and docs_c
    if name != "early":  # the scenario holds: the gate's verdict (the gate test leaves these two to this test)
        assert code_c == 0


def test_auto_leaves_timed_nets_to_the_python_search_with_a_note():
    """The native search of a timed net whose bindings come from the engine is slower than the Python one:
    `auto` keeps the Python search and says why; `--backend c` asks for the native one. A net wholly in
    the generated C: `auto` searches it natively (tests/statespace/test_native_timed_c.py)."""
    model = cpn.loads("colset N = int with 0..3 timed; colset L = real; var x : N; var l : L;"
                      " place P : N = 1`0; place Q : L = 1`0.0; trans t [x < 3] @+ 1; arc P -> t : x;"
                      " arc t -> P : (x + 1) @+ 1; trans u [l < 2.0]; arc Q -> u : l; arc u -> Q : l + 1.0;",
                      "halfway.cpnet")
    auto = Explorer(model.engine(time_condensation=True), ExploreOptions(max_states=200)).run()
    assert auto.backend == "python"
    # a note that asks nothing of the user: with the search's other notes, not in the report's
    assert any("searched natively by `auto` only where the net's generated C computes every transition" in n
               for n in auto.backend_notes), auto.backend_notes
    assert not any("searched natively" in n for n in auto.notes), auto.notes
    c = Explorer(model.engine(time_condensation=True), ExploreOptions(backend="c", max_states=200)).run()
    assert c.backend == "c"
