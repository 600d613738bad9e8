"""The one expression tree (cpn/expr/): the language parses into its nodes, the net holds them, one printer,
one binding analysis and one evaluator read them for every layer."""

import importlib

import pytest

import cpn
from cpn.expr import nodes as N
from cpn.expr import pretty
from cpn.lang import ast as A
from cpn.lang.parser import parse

# a let with a function of two clauses, a flexible record pattern, a case: forms an inscription may hold
MODEL = """
colset N = int with 0..3;
colset R = record a : N * b : N;
var r : R; var n : N;
place P : R = 1`{a = 1, b = 2};
place Q : N;
trans t;
arc P -> t : r;
arc t -> Q : let fun f 0 = 1 | f k = k in case r of {a = x, ...} => f x end;
"""


def test_the_language_and_the_net_share_the_node_classes():
    assert A.Name is N.Name and A.PRecord is N.PRecord and A.ValDecl is N.ValDecl
    net = cpn.loads(MODEL).net
    out = net.transitions[0].arcs[1].expr
    assert isinstance(out, N.ToMs) and isinstance(out.expr, N.Let) and isinstance(out.expr.body, N.Case)
    assert isinstance(out.expr.body.rules[0][0], N.PRecord)


@pytest.mark.parametrize("gone", ["cpn.net.expr", "cpn.net.pretty"])
def test_the_duplicate_modules_are_gone(gone):
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module(gone)


def test_a_flexible_record_pattern_of_an_inscription_prints_as_cpn_ml():
    # the net's printer wrote "{a = x ...}", which no CPN ML parser reads
    out = cpn.loads(MODEL).net.transitions[0].arcs[1].expr
    text = pretty.expr(out)
    assert "{a = x, ...}" in text
    assert "fun f (0) = 1 | f (k) = k;" in text


def test_the_printed_inscription_parses_back_to_the_same_text():
    out = cpn.loads(MODEL).net.transitions[0].arcs[1].expr
    text = pretty.expr(out)
    decl = parse(f"val it = {text};", "t.cpnet").decls[0]
    assert pretty.expr(decl.expr) == text


@pytest.mark.parametrize("gone", ["cpn.net.binding", "cpn.lang.binding"])
def test_the_duplicate_binding_analyses_are_gone(gone):
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module(gone)


def test_one_binding_analysis_reads_the_typed_tree_and_the_net():
    from cpn.expr import binding

    text = ("colset N = int with 0..3; colset NN = product N * N; var x, y : N; place P : NN;"
            " trans t [y = x + 1]; arc P -> t : (x, 2);")
    typed = parse(text, "t.cpnet").decls
    arc = next(d for d in typed if isinstance(d, A.ArcDecl))
    # before typing no name is resolved: nothing is a variable yet
    assert binding.pattern_vars(arc.expr) == set()
    t = cpn.loads(text).net.transitions[0]
    assert binding.pattern_vars(t.arcs[0].expr) == {"x"}
    assert binding.guard_binder(binding.guard_conjuncts(t.guards)[0], {"x"})[0].name == "y"


@pytest.mark.parametrize("gone", ["cpn.engine.evaluate", "cpn.lang.evaluate"])
def test_the_duplicate_evaluators_are_gone(gone):
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module(gone)


# one expression, computed by the checker for a constant and by the engines for an output arc
EXPR = ("let fun f 0 = 1 | f k = if k < 0 then raise Neg k else k * f (k - 1) "
        "in (f 3, R.set_b {a = 1, b = 2} 3, (f (~1)) handle Neg k => k) end")


@pytest.mark.parametrize("reference", [False, True])
def test_the_checker_and_the_engines_evaluate_alike(reference):
    from cpn.expr.evaluate import Evaluator
    from cpn.lang.typecheck import check

    text = (f"colset N = int; colset R = record a : N * b : N; colset T = product N * R * N; exception Neg of N;"
            f" val C = {EXPR};"
            f" place P : T; place U : N = 1`0; trans t; arc U -> t : 0; arc t -> P : {EXPR};")
    checked = check(parse(text, "t.cpnet"))
    assert type(checked.evaluator) is Evaluator
    m = cpn.loads(text)
    (c,) = [d for d in m.net.globals.decls if isinstance(d, N.ValDecl) and d.pat.name == "C"]
    assert m.net.globals.constants[c.pat.ref.uid] == (6, (1, 3), -1)
    e = m.engine(reference=reference)
    ((_, s1),) = e.successors(e.initial_state())
    assert list(e.marking(s1)[0]) == [(6, (1, 3), -1)]


def test_lowering_closes_an_expression_form_it_does_not_name():
    # a new form needs no line in cpn/net/translate.py: every node is closed by one rule
    from dataclasses import dataclass
    from typing import Any

    from cpn.lang.symbols import Symbol
    from cpn.net.translate import Translator

    @dataclass(slots=True, eq=False)
    class Twice(N.Expr):
        expr: N.Expr
        ty: Any = None

    sym = Symbol("x", "var", data="N")
    typed = Twice(None, N.Annot(None, N.Name(None, "x", ty="int", ref=sym), N.TName(None, "N")), ty="int")
    closed = Translator().expr(typed)
    assert type(closed) is Twice and closed.ty is None
    assert isinstance(closed.expr, N.Name) and isinstance(closed.expr.ref, N.Ref)  # the annotation dropped
    assert (closed.expr.ref.name, closed.expr.ref.kind, closed.expr.ref.uid) == ("x", "var", sym.uid)
