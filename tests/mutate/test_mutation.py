"""Mutation testing of a gate: which mutants of tests/mutate/counter.cpnet each scenario catches, the score,
mutants counted apart (not loadable, equivalent), the budget, and the command line's exit statuses."""

import json
import pathlib

import pytest

from cpn.cli.main import main
from cpn.gate.mutation import EQUIVALENT, KILLED, NOT_LOADABLE, SURVIVED, mutate
from cpn.gate.scenario import load_scenario

HERE = pathlib.Path(__file__).parent
WEAK = str(HERE / "weak.toml")
STRONG = str(HERE / "strong.toml")


@pytest.fixture(scope="module")
def weak():
    return mutate([load_scenario(WEAK)]).models[0]


@pytest.fixture(scope="module")
def strong():
    return mutate([load_scenario(STRONG)]).models[0]


def outcome_of(model, operator, line_text):
    """The outcome of the one mutant of `operator` whose mutated line reads `line_text`."""
    got = [o for o in model.outcomes if o.mutant.operator == operator
           and line_text in o.mutant.apply(model.source).splitlines()]
    assert len(got) == 1, (operator, line_text, got)
    return got[0]


def test_the_weak_gate_lets_the_off_by_one_guard_through(weak):
    off_by_one = outcome_of(weak, "comparison-changed", "trans inc [n <= Max];")
    assert off_by_one.outcome == SURVIVED and not off_by_one.killers
    # a count dropped from the initial marking is what 'one count' does catch, at once
    dropped = outcome_of(weak, "token-dropped", "place Count : N;")
    assert dropped.outcome == KILLED
    assert [(k.prop, k.steps) for k in dropped.killers] == [("one count", 0)]
    assert weak.count(KILLED) + weak.count(SURVIVED) + weak.count(EQUIVALENT) + weak.count(NOT_LOADABLE) \
        == len(weak.outcomes) == weak.generated


def test_the_strong_gate_catches_it_with_a_shortest_trace(strong, weak):
    off_by_one = outcome_of(strong, "comparison-changed", "trans inc [n <= Max];")
    assert off_by_one.outcome == KILLED
    # 0 -> 1 -> 2 -> 3 -> 4: the fourth step passes Max
    assert [(k.prop, k.verdict, k.steps) for k in off_by_one.killers] == [
        ("the count never passes Max", "violated", 4), ("it stops at Max", "violated", 4)]
    assert strong.score > weak.score
    assert strong.score == pytest.approx(100 * strong.count(KILLED) / (strong.count(KILLED) + strong.count(SURVIVED)))
    # a token put back on Token each time instead of tested: no property of either gate reads Token
    one_way = outcome_of(strong, "arc-one-way", "arc inc -> Token : ();")
    assert one_way.outcome == SURVIVED


def test_a_run_time_error_of_the_mutant_kills_it(strong):
    minus = outcome_of(strong, "arithmetic-changed", "arc inc -> Count : n - 1;")
    assert minus.outcome == KILLED and not minus.killers
    assert "E0402" in minus.reason and "outside its colour set" in minus.reason


def test_mutants_counted_apart(strong):
    # ~1 is outside N = int with 0..5: the mutant does not load
    assert outcome_of(strong, "constant-changed", "place Count : N = 1`~1;").outcome == NOT_LOADABLE
    # inc is the only transition: a priority changes nothing; Token is only tested: the arc changes nothing
    assert outcome_of(strong, "priority-changed", "trans inc [n < Max] priority 100;").outcome == EQUIVALENT
    removed = [o for o in strong.outcomes if o.mutant.operator == "arc-removed" and "Token" in o.mutant.description]
    assert [o.outcome for o in removed] == [EQUIVALENT]
    assert strong.count(EQUIVALENT) == 2 and strong.count(NOT_LOADABLE) == 1


def test_the_same_mutants_for_the_same_seed():
    def drawn(seed):
        return [o.mutant.number for o in mutate([load_scenario(WEAK)], seed=seed, max_mutants=4).models[0].outcomes]

    first = drawn(11)
    assert len(first) == 4 and drawn(11) == first


def test_the_original_must_pass_its_gate(tmp_path, capsys):
    (tmp_path / "counter.cpnet").write_text((HERE / "counter.cpnet").read_text(encoding="utf-8"), encoding="utf-8")
    bad = tmp_path / "bad.toml"
    bad.write_text('model = "counter.cpnet"\n[[property]]\nname = "never 2"\nkind = "invariant"\n'
                   'expr = "Counter\'Count 1 <> (1`2)"\n', encoding="utf-8")
    assert main(["mutate", str(bad)]) == 1
    err = capsys.readouterr().err
    assert "the original model does not pass the gate" in err and "'never 2' is violated" in err


def cli(args, capsys):
    code = main(["mutate", "--no-timings", *args])
    out, err = capsys.readouterr()
    return code, out, err


def test_fail_under_sets_the_exit_status(capsys, weak):
    code, out, err = cli([WEAK, "--fail-under", "90"], capsys)
    assert code == 1 and f"score {weak.score:.1f}% is below --fail-under 90%" in err
    assert "surviving mutants" in out and "+trans inc [n <= Max];" in out
    code, _, _ = cli([WEAK, "--fail-under", f"{weak.score:.1f}"], capsys)
    assert code == 0
    code, _, err = cli([WEAK, "--fail-under", "150"], capsys)
    assert code == 64 and "--fail-under" in err


def test_reports_and_an_unwritable_output(tmp_path, capsys):
    js, md, page = tmp_path / "m.json", tmp_path / "m.md", tmp_path / "m.html"
    code, _, _ = cli([STRONG, "--json", str(js), "--markdown", str(md), "--html", str(page), "-q"], capsys)
    assert code == 0
    doc = json.loads(js.read_text(encoding="utf-8"))
    model = doc["models"][0]
    assert model["counts"]["killed"] + model["counts"]["survived"] > 0
    assert doc["score"] == model["score"]
    m = next(m for m in model["mutants"] if m["operator"] == "comparison-changed")
    assert m["position"].endswith("counter.cpnet:14:14") and m["killers"][0]["steps"] == 4
    props = {p["property"]: p for p in model["properties"]}
    assert props["the count never passes Max"]["caught"] >= 1
    survivor = next(m for m in model["mutants"] if m["outcome"] == "survived")
    assert survivor["diff"] in md.read_text(encoding="utf-8")
    assert survivor["id"] in page.read_text(encoding="utf-8")
    code, _, err = cli([STRONG, "--json", str(tmp_path / "no" / "m.json")], capsys)
    assert code == 73 and "does not exist" in err


def test_a_time_budget_leaves_mutants_unrun(capsys):
    code, out, _ = cli([WEAK, "--max-seconds", "0.001"], capsys)
    assert code == 2 and "not run (time budget)" in out


def test_workers_give_the_same_outcomes():
    def outcomes(workers):
        got = mutate([load_scenario(STRONG)], workers=workers, max_mutants=8, seed=3).models[0].outcomes
        return [(o.mutant.number, o.outcome, [(k.prop, k.steps) for k in o.killers]) for o in got]

    serial = outcomes(1)
    assert len(serial) == 8 and outcomes(2) == serial


def test_a_model_that_does_not_load_is_reported_and_the_others_run(tmp_path, capsys):
    (tmp_path / "bad.cpnet").write_text("colset U = unit; place A : U = 1`(); trans t; arc A -> t : 1;\n",
                                        encoding="utf-8")
    bad = tmp_path / "bad.toml"
    bad.write_text('model = "bad.cpnet"\n[[property]]\nname = "d"\nkind = "deadlock_free"\n', encoding="utf-8")
    code, out, err = cli([str(bad), WEAK], capsys)
    assert code == 65
    assert "the original model cannot be checked" in err and "bad.cpnet:1:" in err
    assert "tests/mutate/counter.cpnet (1 scenario, 1 run)" in out and "27 mutants" in out


def test_all_runs_credits_every_property_that_catches_a_mutant():
    both = [load_scenario(WEAK), load_scenario(STRONG)]  # one gate: both check counter.cpnet

    def killers(model):
        dropped = outcome_of(model, "token-dropped", "place Count : N;")
        return [(pathlib.Path(k.scenario).name, k.prop) for k in dropped.killers]

    first = mutate(both).models[0]
    assert first.scenarios == [WEAK, STRONG] and first.runs == 2
    assert killers(first) == [("weak.toml", "one count")]  # the first run that catches it
    every = mutate(both, all_runs=True).models[0]
    assert killers(every) == [("weak.toml", "one count"), ("strong.toml", "one count"),
                              ("strong.toml", "the count never passes Max"), ("strong.toml", "it stops at Max")]
    assert [o.outcome for o in every.outcomes] == [o.outcome for o in first.outcomes]
    # the off-by-one guard passes the weak scenario and is caught by the strong one
    assert [k.prop for k in outcome_of(first, "comparison-changed", "trans inc [n <= Max];").killers] == [
        "the count never passes Max", "it stops at Max"]


def test_the_digest_compares_labelled_graphs():
    import cpn
    from cpn.gate.mutation import graph_digest
    from cpn.statespace import ExploreOptions, Explorer

    def digest(text):
        x = Explorer(cpn.loads(text).engine(), ExploreOptions()).run()
        return (x.graph.n_states, x.graph.n_arcs), graph_digest(x)

    ring = "colset N = int with 0..3; var n : N; place P : N = 1`{}; trans t; arc P -> t : n; arc t -> P : {};"
    a = digest(ring.format(0, "(n + 1) mod 4"))
    assert a == digest(ring.format(0, "(n + 1) mod 4"))
    # the same markings and arcs from another initial marking, and the same counts the other way round
    b, c = digest(ring.format(1, "(n + 1) mod 4")), digest(ring.format(0, "(n + 3) mod 4"))
    assert a[0] == b[0] == c[0] and len({a[1], b[1], c[1]}) == 3
