"""A `case` over constants in an arc inscription (CPN Tools' resource allocation samples: ``case x of p =>
2`e | q => 1`e``) runs in the generated C as conditional terms: on output arcs and, where every term
keeps a condition (so that it binds no variable and the binding order is the engine's), on input arcs.
The native search's graph must be the Python search's own; a `case` C cannot split stays with the engine,
transition by transition."""

import pytest

import cpn
from cpn.statespace import ExploreOptions, Explorer
from cpn.statespace.store import packed_unavailable
from tests.engine._explore import same_exploration
from tests.statespace._native import both_searches, net_code, same_error, wholly_in_c

NATIVE = packed_unavailable()
pytestmark = pytest.mark.skipif(NATIVE is not None, reason=f"native code unavailable: {NATIVE}")

# every rule a constant of U: no catch-all needed; the input case reads a variable another arc binds
HEAD = """colset U = with p | q | r; colset E = with e; colset I = int with 0..3; colset P = product U * I;
var x : U; var i : I;
place A : P = 1`(p, 0) ++ 1`(q, 1) ++ 1`(r, 2);
place S : E = 3`e;
place B : P;
"""
NETS = {
    "enumeration": HEAD + """trans t1; arc A -> t1 : (x, i); arc S -> t1 : case x of p => 2`e | q => 1`e | r => empty;
arc t1 -> B : (x, i);
trans t2 [i < 3]; arc B -> t2 : (x, i);
arc t2 -> S : case x of p => 2`e | q => 1`e | r => empty;
arc t2 -> A : case x of q => 1`(x, i + 1) | _ => 1`(x, i);
""",
    "integers": HEAD + """trans t1; arc A -> t1 : (x, i); arc S -> t1 : case i of 0 => 1`e | 1 => 2`e | _ => empty;
arc t1 -> B : (x, i);
trans t2; arc B -> t2 : (x, i); arc t2 -> S : case i of 0 => 1`e | 1 => 2`e | _ => empty;
arc t2 -> A : case x of p => 1`(x, (i + 1) mod 4) | q => 1`(x, i) | r => 1`(q, i);
""",
    "timed": HEAD.replace("colset E = with e;", "colset E = with e timed;").replace(
        "colset P = product U * I;", "colset P = product U * I timed;") + """trans t1;
arc A -> t1 : (x, i); arc S -> t1 : case x of p => 2`e | q => 1`e | r => empty;
arc t1 -> B : (x, i) @+ 2;
trans t2 [i < 3]; arc B -> t2 : (x, i);
arc t2 -> S : case x of p => 2`e @+ 1 | q => 1`e | r => empty;
arc t2 -> A : case x of q => 1`(x, i + 1) | _ => 1`(x, i) @+ 3;
""",
}


@pytest.mark.parametrize("name", sorted(NETS))
def test_a_case_over_constants_runs_in_c_with_the_python_searchs_graph(name):
    model = cpn.loads(NETS[name], f"{name}.cpnet")
    wholly_in_c(model)
    condensed = name == "timed"  # (its clock grows without end: condensed, its state space is finite)
    c = both_searches(model.engine(time_condensation=condensed), model.engine(time_condensation=condensed))
    assert c.complete and c.notes == [] and c.n_states > 5


def _left(arc):
    """A net whose transition t1 has input inscription `arc`, and its C, which leaves t1 to the engine."""
    text = HEAD.replace("3`e;", "3`e;\nvar j : I;") + f"trans t1; arc A -> t1 : (x, i); {arc}\narc t1 -> B : (x, i);"
    model = cpn.loads(text, "left.cpnet")
    code, why = net_code(model)
    assert why is None and [model.engine().transitions[t].name for t in code.left] == ["Top't1 1"]
    return model


def test_a_case_without_a_rule_for_every_value_stays_with_the_engine_and_fails_as_there():
    model = _left("arc S -> t1 : case x of p => 2`e | q => 1`e;")  # no rule for r
    assert "no rule of the case-expression matches" in same_error(model)


def test_a_case_whose_rules_bind_variables_stays_with_the_engine():
    model = _left("arc S -> t1 : case (x, i) of (p, j) => j`e | _ => empty;")
    auto = Explorer(model.engine(), ExploreOptions(backend="auto")).run()
    py = Explorer(model.engine(), ExploreOptions(backend="python", packed_states=False)).run()
    same_exploration(auto, py)
    assert auto.complete and auto.n_states > 3
