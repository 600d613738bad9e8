"""The engines that print traces are built once per net and kind, and a trace reads the same either way."""

import cpn
from cpn.report import verdicts
from cpn.report.verdicts import printing_engine

TIMED = """colset T = int with 0..40 timed; var x : T;
place P : T = 1`0; place Q : T;
trans t; arc P -> t : x; arc t -> Q : x + 1 @+ 3; arc t -> P : x @+ 5;"""


def test_one_engine_per_net_and_kind():
    net = cpn.loads(TIMED, "t.cpnet").net
    plain = printing_engine(net)
    assert printing_engine(net) is plain
    ref = printing_engine(net, reference=True)
    assert ref is not plain and printing_engine(net, reference=True) is ref
    other = cpn.loads(TIMED.replace("@+ 5", "@+ 6"), "t.cpnet").net
    assert printing_engine(other) is not plain


def test_only_the_last_nets_are_kept(monkeypatch):
    monkeypatch.setattr(verdicts, "PRINTING_NETS", 2)
    nets = [cpn.loads(TIMED.replace("@+ 5", f"@+ {k}"), "t.cpnet").net for k in range(1, 5)]
    first = printing_engine(nets[0])
    for n in nets[1:]:
        printing_engine(n)
    held = {id(v[0]) for v in verdicts._PRINTING_ENGINES.values()}
    assert len(held) == 2 and id(nets[0]) not in held
    assert printing_engine(nets[0]) is not first  # built again once dropped


def test_a_trace_prints_the_same_from_a_kept_engine():
    model = cpn.loads(TIMED, "t.cpnet")
    engine = model.engine(time_condensation=True)
    s0 = engine.initial_state()
    bes = []
    state = s0
    for _ in range(3):
        be, state = next(iter(engine.successors(state)))
        bes.append(be)
    first = verdicts._replay_absolute(engine, bes)
    again = verdicts._replay_absolute(engine, bes)
    assert first is not None and again is not None
    assert first[0] is again[0]
    assert first[2] == again[2] == [engine.format_binding_element(b) for b in bes]
    assert [first[0].clock(s) for s in first[1]] == [0, 0, 5, 10]


def test_a_condensed_trace_replays_on_its_engines_twin_as_on_a_net_compiled_again():
    # the twin shares the compiled transitions and the memo tables; a fresh uncondensed engine is the oracle
    model = cpn.loads(TIMED, "t.cpnet")
    engine = model.engine(time_condensation=True)
    twin = engine.uncondensed()
    assert twin is not engine and twin.store is engine.store and not twin.time_condensation
    assert twin._be is engine._be  # binding elements numbered alike: a replay matches them by number
    assert engine.time_condensation and model.engine().uncondensed().time_condensation is False
    state, bes = engine.initial_state(), []
    for _ in range(4):
        be, state = next(iter(engine.successors(state)))
        bes.append(be)
    plain, states, texts = verdicts._replay_absolute(engine, bes)
    assert plain.store is engine.store  # nothing compiled again
    fresh = model.engine()
    s, want = fresh.initial_state(), [fresh.initial_state()]
    for text in texts:
        s = next(t for b, t in fresh.successors(s) if fresh.format_binding_element(b) == text)
        want.append(s)
    assert [plain.clock(x) for x in states] == [fresh.clock(x) for x in want] == [0, 0, 5, 10, 15]
    assert [[plain.format_marking(x, p) for p in range(len(plain.places))] for x in states] == \
           [[fresh.format_marking(x, p) for p in range(len(fresh.places))] for x in want]
