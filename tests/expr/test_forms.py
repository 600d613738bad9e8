"""Expression forms that declare their rules in one module (cpn/expr/form.py, cpn/expr/forms/): the parser,
the type checker, the evaluator, the binding analysis, the printer and the Python compiler look them up."""

import inspect
import pathlib
import re
from dataclasses import dataclass
from typing import Any

import pytest
from lark import Tree

import cpn
import cpn.lang.parser
from cpn.engine import codegen
from cpn.expr import binding, forms, pretty
from cpn.expr import nodes as N
from cpn.expr.evaluate import Evaluator
from cpn.lang.transform import ToAst

CPN = pathlib.Path(cpn.__file__).resolve().parent
GRAMMAR = (CPN / "lang" / "grammar.lark").read_text()


def _files_naming(pattern: str) -> list[str]:
    rx = re.compile(pattern)
    return sorted(str(p.relative_to(CPN)) for p in CPN.rglob("*.py") if rx.search(p.read_text()))


@pytest.mark.parametrize("node", ["Raise", "Handle"])
def test_a_registered_form_is_named_by_its_module_alone(node):
    # handle took 9 files (its node class, the transformer, the type rule, the evaluator, the binding
    # analysis, the printer, the compiler, the language's import list, the grammar): now its module, its line
    # in cpn/expr/forms/__init__.py and its grammar rule
    # the class, a method named after it (`_e_Raise`), an attribute (`A.Raise`), a call or an import
    assert _files_naming(rf"class {node}\b|[._]{node}\b|\b{node}[(,]") == ["expr/forms/exceptions.py"]
    assert re.search(rf"-> {forms.FORMS[getattr(forms.exceptions, node)].rule}\b", GRAMMAR)


@pytest.mark.parametrize("form", list(forms.FORMS.values()), ids=lambda f: f.node.__name__)
def test_every_registered_form_has_its_rules(form):
    cls = type(form)
    for rule in ("infer", "evaluate", "show", "children"):
        assert getattr(cls, rule) is not getattr(forms.Form, rule) or rule == "children", rule
    if form.rule is not None:
        assert re.search(rf"-> {form.rule}\b", GRAMMAR), form.rule


@dataclass(slots=True, eq=False)
class Twice(N.Expr):
    expr: N.Expr
    ty: Any = None


class TwiceForm(forms.Form):
    """A form no module of the package names: `twice e` is `(e, e)`."""

    node = Twice
    rule = "twice_test_only"
    compiled = True

    def children(self, e):
        return [e.expr]

    def evaluate(self, ev, e, env):
        v = ev.eval(e.expr, env)
        return (v, v)

    def compile(self, ec, e):
        return f"(({ec.expr(e.expr)},) * 2)" if self.compiled else None

    def show(self, e, pp):
        return f"(twice {pp.atom(e.expr)})"


@pytest.fixture
def twice():
    forms.register(TwiceForm)
    try:
        yield forms.FORMS[Twice]
    finally:
        del forms.FORMS[Twice], forms.BY_RULE["twice_test_only"]


def _x():
    return N.Name(None, "x", ref=N.Ref("x", "var", uid=7, data="N"))


def test_a_new_form_is_parsed_evaluated_analysed_and_printed_through_its_module(twice):
    e = ToAst("t.cpnet").transform(Tree("twice_test_only", [_x()]))
    assert type(e) is Twice and e.expr.name == "x"
    assert Evaluator({}).eval(e, {7: 3}) == (3, 3)
    assert binding.all_vars(N.TupleE(None, [e])) == {"x"}
    assert pretty.expr(N.TupleE(None, [e, N.Const(None, 1, "int")])) == "((twice x), 1)"


@pytest.mark.parametrize("compiled", [True, False])
def test_a_new_form_is_compiled_or_left_to_the_evaluator(twice, compiled):
    twice.compiled = compiled
    ec = codegen.ExprCompiler(codegen.Namespace(), Evaluator({}), {"x": "v0"}, {}, {"x": 7})
    code = ec.expr(N.TupleE(None, [Twice(None, _x())]))
    if compiled:
        assert code == "(((v0,) * 2), )"
    else:
        assert re.fullmatch(r"\(EVAL\(_X\d+, \{\*\*_P\d+, 7: v0\}\), \)", code)


def test_two_forms_of_one_node_are_refused(twice):
    with pytest.raises(ValueError, match="two forms of Twice"):
        forms.register(TwiceForm)


def test_handle_and_raise_round_trip_through_the_printer():
    m = cpn.loads("colset C = int with 0..5; exception Big of int; var x : C; place P : C = 1`0; trans T;"
                  " arc P -> T : x; arc T -> P : (if x > 3 then raise Big x else x + 1) handle Big n => n - 4;")
    text = pretty.expr(m.net.transitions[0].arcs[1].expr)
    assert "handle" in text and "raise" in text
    assert pretty.expr(cpn.lang.parser.parse(f"val it = {text};", "t.cpnet").decls[0].expr) == text
    e = m.engine()
    assert e.format_marking(e.successors(e.initial_state())[0][1], 0) == "1`1"


@pytest.mark.parametrize("form", list(forms.FORMS.values()), ids=lambda f: f.node.__name__)
def test_a_registered_form_has_no_rule_left_in_the_walkers(form):
    from cpn.lang.typecheck import Checker

    name = form.node.__name__
    assert not hasattr(Evaluator, f"_e_{name}")
    assert not hasattr(codegen.ExprCompiler, f"_c_{name}")
    assert not hasattr(Checker, f"_i_{name}")
    assert form.rule is None or not hasattr(ToAst, form.rule)
    for walker in (pretty.expr, binding.children):
        # no branch of its own (pattern positions, which the binding analysis reads, are another matter)
        assert not re.search(rf"isinstance\(e, [^)]*\bN\.{name}\b", inspect.getsource(walker)), walker
