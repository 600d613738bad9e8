"""`kind = "ltl"` in scenario files: on random nets, the LTL formulas that have a CTL equivalent agree
with the CTL checker, and every counterexample is a lasso that replays through the engine."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cpn.checks.verdict import Status
from cpn.errors import ModelError
from cpn.gate.run import run_scenario
from cpn.gate.scenario import loads_scenario
from tests.checks.test_traces import _replays
from tests.engine.randomnets import random_net

# (LTL, CTL) pairs that mean the same on every graph; p and q are atoms over the random net's places
PAIRS = [
    ("G p", "AG p"),
    ("F p", "AF p"),
    ("G (F p)", "AG (AF p)"),
    ("U (p, q)", "AU (p, q)"),
    ("G (not p orelse F q)", "AG (not p orelse AF q)"),
]
P = "size (Top'p0 1) <= {k}"
Q = "size (Top'p1 1) >= 1"

def _sub(f: str, k: int) -> str:
    """The formula with its atoms p and q written out (the names p0, p1 are left alone)."""
    atoms = {"p": f"({P.format(k=k)})", "q": f"({Q})"}
    return "".join(atoms.get(ch, ch) if (i == 0 or not f[i - 1].isalnum()) and (i + 1 == len(f) or not f[i + 1].isalnum())
                   else ch for i, ch in enumerate(f))

def _run(tmp_path, seed, body):
    model = tmp_path / f"r{seed}.cpnet"
    model.write_text(random_net(seed), encoding="utf-8")
    s = loads_scenario(f'model = "{model.name}"\n' + body, str(tmp_path / "r.toml"))
    return run_scenario(s, s.runs[0], {"max_states": 3000})

@settings(max_examples=40, deadline=None)
@given(st.integers(0, 10**6), st.integers(0, 2))
def test_ltl_agrees_with_ctl_where_they_mean_the_same(tmp_path_factory, seed, k):
    tmp = tmp_path_factory.mktemp("l")
    r = _run(tmp, seed, "\n".join(
        f'[[property]]\nname = "{kind}{i}"\nkind = "{kind}"\nformula = "{_sub(f, k)}"\n'
        for i, pair in enumerate(PAIRS) for kind, f in zip(("ltl", "ctl"), pair)))
    by = {p.spec.name: p.verdict for p in r.results}
    if not r.exploration.complete:
        # the search on the fly may decide within the limit what the partial graph cannot
        assert all(v.status is Status.UNKNOWN or "on the fly" in v.message
                   for n, v in by.items() if n.startswith("ltl"))
        return
    g = r.exploration.graph
    for i in range(len(PAIRS)):
        ltl, ctl = by[f"ltl{i}"], by[f"ctl{i}"]
        assert ltl.status is ctl.status, (PAIRS[i], ltl.message, ctl.message)
        if ltl.status is Status.VIOLATED and ltl.evidence is not None:
            ev = ltl.evidence
            assert ev.path[0] == 0 and _replays(r.engine, g, ev)
            if ev.cycle:
                assert ev.cycle[-1] == ev.path[-1]  # a lasso: the cycle returns to the end of the path
            else:
                assert not g.out_arcs(ev.path[-1])  # else the path ends in a dead marking

def test_an_ltl_lasso_through_the_check_command(tmp_path):
    (tmp_path / "m.cpnet").write_text(
        "colset U = unit; place A : U = 1`(); place B : U;"
        " trans go; trans back; arc A -> go; arc go -> B; arc B -> back; arc back -> A;", encoding="utf-8")
    s = loads_scenario('model = "m.cpnet"\n[[property]]\nname = "stays"\nkind = "ltl"\n'
                       'formula = "F (G (size (Top\'A 1) = 1))"\n'
                       '[[property]]\nname = "returns"\nkind = "ltl"\n'
                       'formula = "ALWAYS (EVENTUALLY (size (Top\'A 1) = 1))"\n', str(tmp_path / "s.toml"))
    r = run_scenario(s, s.runs[0], {})
    by = {p.spec.name: p.verdict for p in r.results}
    assert by["returns"].status is Status.HOLDS
    v = by["stays"]
    assert v.status is Status.VIOLATED and "cycles through" in v.message
    assert v.evidence.cycle and v.evidence.cycle[-1] == v.evidence.path[-1]

def test_a_temporal_operator_inside_a_function_is_refused_at_its_place(tmp_path):
    (tmp_path / "m.cpnet").write_text("colset U = unit; place A : U = 1`(); trans t; arc A -> t;", encoding="utf-8")
    with pytest.raises(ModelError) as err:
        s = loads_scenario('model = "m.cpnet"\n[[property]]\nname = "x"\nkind = "ltl"\n'
                           'formula = "let val b = G true in b end"\n', str(tmp_path / "s.toml"))
        run_scenario(s, s.runs[0], {})
    d = err.value.diagnostics[0]
    assert d.code == "E0702" and d.span.line == 5


SPIN = ("colset U = unit; place A : U = 1`(); place B : U;"
        " trans spin; trans go; arc A -> spin; arc spin -> A; arc A -> go; arc go -> B;")


def test_weak_fairness_keeps_only_the_paths_that_do_not_ignore_a_transition_forever(tmp_path):
    (tmp_path / "m.cpnet").write_text(SPIN, encoding="utf-8")
    body = ('model = "m.cpnet"\n[[property]]\nname = "plain"\nkind = "ltl"\nformula = "F (size (Top\'B 1) = 1)"\n'
            '[[property]]\nname = "fair"\nkind = "ltl"\nformula = "F (size (Top\'B 1) = 1)"\n'
            'weak_fairness = ["Top\'go"]\n')
    s = loads_scenario(body, str(tmp_path / "s.toml"))
    by = {p.spec.name: p.verdict for p in run_scenario(s, s.runs[0], {}).results}
    assert by["plain"].status is Status.VIOLATED  # spin forever
    assert by["fair"].status is Status.HOLDS


def test_a_weak_fairness_name_not_in_the_net_is_an_error_with_a_suggestion(tmp_path):
    (tmp_path / "m.cpnet").write_text(SPIN, encoding="utf-8")
    body = ('model = "m.cpnet"\n[[property]]\nname = "fair"\nkind = "ltl"\nformula = "F (size (Top\'B 1) = 1)"\n'
            'weak_fairness = ["Top\'goo"]\n')
    with pytest.raises(ModelError) as err:
        s = loads_scenario(body, str(tmp_path / "s.toml"))
        run_scenario(s, s.runs[0], {})
    d = err.value.diagnostics[0]
    assert d.code == "E0703" and "Top'go" in (d.hint or "") and d.span.line == 6
