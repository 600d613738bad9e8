"""The model time at which a binding element is bound (CPN Tools advances
the clock first), the time-growth watch and time condensation on a model that reads the clock, and the
transition instance named by a run-time error."""

import json
import os

import pytest

import cpn
from cpn.cli.main import main
from cpn.engine.clock import TimeCondensationRefused
from cpn.errors import EvaluationError
from cpn.statespace import ExploreOptions, Explorer
from tests.engine._explore import counts, graph

ENGINES = [False, True]  # compiled, reference

GUARD_FALSE_WHEN_READY = """colset TU = unit timed; colset I = int; place P : TU = 1`() @+ 25; place Log : I;
trans T [intTime() < 20]; arc P -> T : (); arc T -> Log : intTime();
"""

GUARD_TIME_LT_30 = """colset TU = unit timed;
place A : TU = 1`();
trans T [time() < 30];
arc A -> T : ();
arc T -> A : () @+ 1;
"""


def _engine(text, reference, **kw):
    return cpn.loads(text, "m.cpnet").engine(reference=reference, **kw)


def _log(engine, s, name="Top'Log 1"):
    return engine.marking(s)[engine.net.place(name).index]


@pytest.mark.parametrize("reference", ENGINES)
def test_guard_is_evaluated_at_the_time_the_tokens_are_ready(reference):
    """The token is ready at 25, when the guard is false: T never occurs (was 1`0 compiled, 1`25 reference)."""
    e = _engine(GUARD_FALSE_WHEN_READY, reference)
    s0 = e.initial_state()
    assert e.successors(s0) == []
    assert counts(e) == (1, 0, 1)
    assert _log(e, s0) == {}


@pytest.mark.parametrize("reference", ENGINES)
def test_time_lt_30_has_31_states(reference):
    """The last occurrence is at time 29; at 30 the guard is false (CPN Tools: 31 states, was 32)."""
    e = _engine(GUARD_TIME_LT_30, reference)
    assert counts(e) == (31, 30, 1)


def test_time_growth_watch_does_not_stop_a_model_that_reads_the_clock():
    """The same net is finite: explored completely, not stopped after 9 states as 'time grows'."""
    x = Explorer(_engine(GUARD_TIME_LT_30, False), ExploreOptions(detect_time_growth=True)).run()
    assert x.complete and (x.n_states, x.n_arcs) == (31, 30)


def test_partial_search_of_a_clock_reading_model_says_why_it_was_not_stopped(tmp_path, capsys):
    path = tmp_path / "loop.cpnet"
    path.write_text("colset TU = unit timed;\nplace A : TU = 1`();\ntrans T [intTime() >= 0];\n"
                    "arc A -> T : ();\narc T -> A : () @+ 1;\n")
    out = tmp_path / "o.json"
    assert main(["explore", str(path), "--max-states", "40", "--quiet", "--json", str(out)]) == 2
    d = json.loads(out.read_text())
    assert d["statespace"]["reads_clock"] is True
    assert d["statespace"]["stop_reason"] == "max_states"
    assert any("time-growth watch does not apply" in n and "loop.cpnet:3:10" in n for n in d["notes"])


@pytest.mark.parametrize("reference", ENGINES)
def test_a_function_that_reads_the_clock(reference):
    """A guard and an output inscription that read the clock through functions: examined at 7, the
    token's timestamp (the compiled engine failed with a NameError, the reference never fired)."""
    e = _engine("colset TU = unit timed; colset I = int;\nfun late(u) = intTime() > 5;\nfun now(u) = intTime();\n"
                "place P : TU = 1`() @+ 7; place Log : I;\n"
                "trans T [late()]; arc P -> T : (); arc T -> Log : now();\n", reference)
    [(_, s1)] = e.successors(e.initial_state())
    assert e.clock(s1) == 7 and _log(e, s1) == {7: 1}


def test_refusal_names_the_function_that_reads_the_clock():
    src = "colset TU = unit timed;\nfun late(u) = intTime() > 5;\nplace P : TU = 1`();\ntrans T [late()];\n" \
          "arc P -> T : ();\narc T -> P : () @+ 1;\n"
    with pytest.raises(TimeCondensationRefused) as info:
        _engine(src, False, time_condensation=True)
    assert (info.value.read.span.line, info.value.read.span.col) == (4, 10)
    assert "note: 'late' reads it at m.cpnet:2:15" in info.value.render()


def test_the_engines_of_one_net_find_its_clock_reads_once(monkeypatch):
    """Every engine of a net (the search's, those printing its traces) asks where it reads the clock: the
    net's transitions are walked once, and each engine gets a dict of its own."""
    from cpn.engine import clock

    walked = []
    real = clock._clock_reads
    monkeypatch.setattr(clock, "_clock_reads", lambda net: walked.append(net) or real(net))
    src = "colset TU = unit timed;\nfun late(u) = intTime() > 5;\nplace P : TU = 1`();\ntrans T [late()];\n" \
          "arc P -> T : ();\narc T -> P : () @+ 1;\ntrans U; arc P -> U : (); arc U -> P : () @+ 2;\n"
    m = cpn.loads(src, filename="m.cpnet")
    a, b = m.engine(), m.engine(reference=True)
    assert len(walked) == 1 and a.clock_reads == b.clock_reads and list(a.clock_reads) == [0]
    assert a.clock_reads[0].via == "'late' reads it at m.cpnet:2:15"
    a.clock_reads.clear()
    assert list(m.engine().clock_reads) == [0] and len(walked) == 1
    assert list(cpn.loads(src, filename="m.cpnet").engine().clock_reads) == [0] and len(walked) == 2


@pytest.mark.parametrize("reference", ENGINES)
def test_guard_false_at_the_clock_true_at_a_later_own_timestamp(reference):
    """At 0 the binding x=1 is ready but its guard is false; T is examined again at 5, the timestamp of
    its other token, where both bindings are enabled."""
    e = _engine("colset TC = int with 0..3 timed; var x : TC;\nplace P : TC = 1`1 ++ 1`2 @+ 5;\n"
                "trans T [intTime() >= 5];\narc P -> T : x;\n", reference)
    succ = e.successors(e.initial_state())
    assert sorted(e.binding_element(be).binding["x"] for be, _ in succ) == [1, 2]
    assert {e.clock(s) for _, s in succ} == {5}


@pytest.mark.parametrize("reference", ENGINES)
def test_guard_true_only_at_a_time_that_is_no_timestamp_of_its_tokens(reference):
    """The clock moves only to timestamps of tokens: T (guard true only at 7) and U (token ready at 5,
    guard false there) never occur, and the clock does not move."""
    e = _engine("colset TU = unit timed;\nplace P : TU = 1`(); place Q : TU = 1`() @+ 5;\n"
                "trans T [intTime() = 7]; trans U [intTime() > 100];\narc P -> T : (); arc Q -> U : ();\n",
                reference)
    assert e.successors(e.initial_state()) == []


@pytest.mark.parametrize("reference", ENGINES)
def test_transition_examined_at_the_clock_of_a_later_state(reference):
    """T's guard is false at 0; U occurs at 5 (its token's time); in that state (clock 5) T is enabled."""
    e = _engine("colset TU = unit timed;\nplace P : TU = 1`(); place Q : TU = 1`() @+ 5;\n"
                "trans T [intTime() >= 5]; trans U;\narc P -> T : (); arc Q -> U : ();\n", reference)
    [(b, s1)] = e.successors(e.initial_state())
    assert e.format_binding_element(b) == "Top'U 1: {}" and e.clock(s1) == 5
    [(b, s2)] = e.successors(s1)
    assert e.format_binding_element(b) == "Top'T 1: {}" and e.clock(s2) == 5


@pytest.mark.parametrize("reference", ENGINES)
def test_input_inscription_and_delay_read_the_new_time(reference):
    """The input inscription `intTime()` selects the token whose value is the time the binding occurs at
    (5, when the token is ready), and the transition delay reads that time too."""
    e = _engine("colset T = int timed; var n : T;\nplace P : T = (1`5 ++ 1`0) @+ 5; place Q : T;\n"
                "trans t @+ intTime();\narc P -> t : intTime();\narc t -> Q : intTime();\n", reference)
    [(_, s1)] = e.successors(e.initial_state())
    assert e.clock(s1) == 5
    assert _log(e, s1, "Top'P 1") == {(0, 5): 1}
    assert _log(e, s1, "Top'Q 1") == {(5, 10): 1}


@pytest.mark.parametrize("reference", ENGINES)
def test_time_condensation_is_refused_on_a_model_that_reads_the_clock(reference):
    with pytest.raises(TimeCondensationRefused) as info:
        _engine(GUARD_TIME_LT_30, reference, time_condensation=True)
    err = info.value
    assert (err.read.span.line, err.read.span.col) == (3, 10)
    assert err.read.transition == "Top'T 1"
    text = err.render()
    assert text.startswith("m.cpnet:3:10: error[E0601]: time condensation cannot be used")
    assert "trans T [time() < 30];" in text and "^^^^^^" in text and "hint:" in text


def test_time_condensation_refusal_on_the_command_line(tmp_path, capsys):
    path = tmp_path / "lt30.cpnet"
    path.write_text(GUARD_TIME_LT_30)
    assert main(["explore", str(path), "--time-condensation", "--quiet"]) == 64
    err = capsys.readouterr().err
    assert f"{path}:3:10: error[E0601]" in err and "Traceback" not in err
    # the same model without condensation is finite and complete
    assert main(["explore", str(path), "--quiet"]) == 0


def test_time_condensation_still_applies_to_a_model_that_does_not_read_the_clock():
    root = os.path.dirname(os.path.dirname(os.path.dirname(__file__)))
    m = cpn.load(os.path.join(root, "tests", "statespace", "models", "ticker.cpnet"))
    assert not m.engine(time_condensation=True).reads_clock
    assert Explorer(m.engine(time_condensation=True)).run().complete


TWO_INSTANCES = """colset C = int with 0..3; var x : C;
module M(k : C) { port in In : C; place Out : C; trans T [10 div (x - k) > 0]; arc In -> T : x; arc T -> Out : x; }
place A : C = 1`1;
instance M1 = M(k = 0) { In = A };
instance M2 = M(k = 1) { In = A };
"""


@pytest.mark.parametrize("reference", ENGINES)
def test_run_time_error_names_the_transition_instance(reference):
    """The division by zero happens in the second instance; the error names `M'T 2`, the
    guard's position and the binding."""
    e = _engine(TWO_INSTANCES, reference)
    with pytest.raises(EvaluationError) as info:
        e.successors(e.initial_state())
    err = info.value
    assert "transition 'M'T 2'" in err.message and "division by zero" in err.message
    assert err.element == "M'T 2"
    assert (err.span.line, err.span.col) == (2, 59)
    assert err.binding == {"x": "1"}
    assert "x=1" in err.message


def test_run_time_error_on_the_command_line_names_the_instance(tmp_path, capsys):
    path = tmp_path / "two.cpnet"
    path.write_text(TWO_INSTANCES)
    assert main(["explore", str(path), "--quiet"]) == 65
    err = capsys.readouterr().err
    assert f"{path}:2:59: error[E0401]: the guard of transition 'M'T 2' failed for binding <x=1>" in err


@pytest.mark.parametrize("reference", ENGINES)
def test_both_engines_agree_on_the_examples(reference):
    """Canonical graphs of the examples above are the same in both engines."""
    for text in (GUARD_FALSE_WHEN_READY, GUARD_TIME_LT_30):
        assert graph(_engine(text, reference)) == graph(_engine(text, not reference))
