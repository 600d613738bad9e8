"""`cpn-verify simulate` draws the values of `bernoulli`, `discrete`, `CS.ran()` and `@+[a,b]` with their
distributions, where explore tries every value (docs/semantics.md, "Random draws")."""

import json
import re

import cpn
from cpn.cli.main import main

HEAD = """colset U = unit; colset B = int with 0..1; colset D = int with 0..7; colset S = with s1 | s2 | s3;
var y : B;
place A : U = 1`();
place R : B; place Q : D; place N : U; place T : S;
"""


def _run(tmp_path, capsys, text: str, steps: int = 2000, seed: int = 11) -> dict:
    path = tmp_path / "m.cpnet"
    path.write_text(HEAD + text)
    assert main(["simulate", str(path), "--steps", str(steps), "--seed", str(seed), "--json", "-"]) == 0
    return json.loads(capsys.readouterr().out)


def _counts(marking: str) -> dict:
    """'187`0++1813`1' -> {'0': 187, '1': 1813}"""
    return {v: int(n) for n, v in re.findall(r"(\d+)`([^+]+)", marking)}


def test_bernoulli_is_1_with_probability_p(tmp_path, capsys):
    # drawn 50/50 (one binding element per value, every one equally likely), about 1,000 of 2,000 would be 1
    run = _run(tmp_path, capsys, "trans t; arc A -> t; arc t -> A; arc t -> R : bernoulli(0.9);")
    ones = _counts(run["final_marking"]["Top'R 1"]).get("1", 0)
    assert 0.85 * 2000 <= ones <= 0.95 * 2000


def test_bernoulli_in_a_function_and_in_a_guard_that_binds_outputs(tmp_path, capsys):
    text = """fun lost () = bernoulli(0.2);
trans t [y = bernoulli(0.1)]; arc A -> t; arc t -> A; arc t -> R : y; arc t -> Q : if y = 1 then 1`3 else 1`0;
trans u; arc A -> u; arc u -> A; arc u -> N : if lost () = 1 then 1`() else empty;
"""
    run = _run(tmp_path, capsys, text)
    r = _counts(run["final_marking"]["Top'R 1"])
    q = _counts(run["final_marking"]["Top'Q 1"])
    fired_t = r.get("0", 0) + r.get("1", 0)
    assert 0.45 * 2000 <= fired_t <= 0.55 * 2000  # two transitions, each about half of the steps
    assert 0.05 * fired_t <= r.get("1", 0) <= 0.15 * fired_t
    assert (q.get("3", 0), q.get("0", 0)) == (r.get("1", 0), r.get("0", 0))  # one draw, read by both arcs
    lost = _counts(run["final_marking"].get("Top'N 1", "0`()")).get("()", 0)
    assert 0.15 * (2000 - fired_t) <= lost <= 0.25 * (2000 - fired_t)


def test_a_transition_that_draws_is_no_likelier_than_one_that_does_not(tmp_path, capsys):
    # one binding element per value would give t eight binding elements against u's three: t in 8 steps of 11
    text = """trans t; arc A -> t; arc t -> A; arc t -> Q : discrete(0, 7);
trans u; arc A -> u; arc u -> A; arc u -> T : S.ran();
"""
    run = _run(tmp_path, capsys, text)
    q = _counts(run["final_marking"]["Top'Q 1"])
    s = _counts(run["final_marking"]["Top'T 1"])
    fired_t = sum(q.values())
    assert 0.45 * 2000 <= fired_t <= 0.55 * 2000
    assert all(0.09 * fired_t <= q.get(str(v), 0) <= 0.16 * fired_t for v in range(8))
    assert all(0.28 * (2000 - fired_t) <= s.get(c, 0) <= 0.39 * (2000 - fired_t) for c in ("s1", "s2", "s3"))


def test_the_same_seed_gives_the_same_run(tmp_path, capsys):
    text = "trans t; arc A -> t; arc t -> A; arc t -> R : bernoulli(0.3);"
    a = _run(tmp_path, capsys, text, steps=200, seed=5)
    b = _run(tmp_path, capsys, text, steps=200, seed=5)
    c = _run(tmp_path, capsys, text, steps=200, seed=6)
    assert a["steps"] == b["steps"] and a["steps"] != c["steps"]


def test_explore_still_tries_every_value():
    m = cpn.loads(HEAD + "trans t; arc A -> t; arc t -> R : bernoulli(0.9);", "m.cpnet")
    e = m.engine()
    assert sorted(e.format_binding_element(be) for be, _ in e.successors(e.initial_state())) == [
        "Top't 1: {bernoulli(0,1)#1=0}", "Top't 1: {bernoulli(0,1)#1=1}"]
