"""The net is the engine's only input; one arc-kind vocabulary; the engine protocol."""

import ast
import pathlib

import pytest

import cpn
from cpn.expr import nodes as E
from cpn.expr.evaluate import Evaluator
from cpn.values.builtins import FUNCTIONS, MLError, binop
from tests.engine._explore import graph

ROOT = pathlib.Path(__file__).resolve().parents[2]

# functions (one argument, curried, recursive), let, case, fn, a function-valued constant, records,
# unions and an index: what the compiled engine compiles and what it leaves to the evaluator
MODEL = """
colset N = int with 0..3;
colset PH = index ph with 1..2;
colset R = record a : N * b : N;
colset U = union Tok : N + Stop;
var n : N; var p : PH; var r : R;
val limit = 2;
val twice = fn x => 2 * x;
fun inc x = if x < limit then x + 1 else 0;
fun add a b = (a + b) mod 4;
fun kind (Tok k) = k | kind Stop = 0;
fun sum [] = 0 | sum (x :: xs) = x + sum xs;
place A : N = 1`0;
place B : R = 1`{a = 0, b = 1};
place C : U = 1`(Tok 1);
place D : PH = 1`ph(1);
trans t [n < 3];
arc A -> t : n;
arc t -> A : let val m = inc n in case m of 0 => 1 | k => k end;
trans s;
arc B -> s : r;
arc s -> B : {a = add (#a r) 1, b = (fn y => y) (#b r)};
trans u;
arc C -> u : Tok n;
arc u -> C : Tok (twice (kind (Tok n)) mod 4);
trans v [sum [n, 1] <= 3];
arc D -> v : p;
arc A <-> v : n;
arc v -> D : ph(if p = ph(1) then 2 else 1);
"""


def test_the_engine_reads_nothing_of_the_front_end():
    model = cpn.loads(MODEL)
    expected = graph(model.engine(), 500)
    net = model.net
    net.checked = None  # the checked model stays with the front end; an engine needs only the Net
    assert graph(cpn.engine.compile_net(net), 500) == expected
    assert graph(cpn.engine.compile_net(net, reference=True), 500) == expected
    assert len(expected) > 10


def test_net_fields_are_the_closed_expression_form():
    net = cpn.loads(MODEL).net
    exprs = [a.expr for t in net.transitions for a in t.arcs] + [g for t in net.transitions for g in t.guards]
    assert all(isinstance(x, E.Expr) for x in exprs)
    assert net.variables["n"].kind == "var" and net.variables["n"].data == "N"
    assert [d.name for d in net.globals.decls if isinstance(d, E.FunDecl)] == ["inc", "add", "kind", "sum"]
    vals = {d.pat.name: d for d in net.globals.decls if isinstance(d, E.ValDecl)}
    assert sorted(vals) == ["limit", "twice"]
    # limit's value is kept; twice is a function, evaluated again from its declaration
    assert net.globals.constants == {vals["limit"].pat.ref.uid: 2}


def test_evaluator_of_the_net_runs_global_declarations():
    net = cpn.loads(MODEL).net
    ev = Evaluator(net.colsets, net.globals)
    inc = next(d for d in net.globals.decls if isinstance(d, E.FunDecl) and d.name == "inc")
    assert ev.globals[inc.ref.uid](1) == 2 and ev.globals[inc.ref.uid](2) == 0


def test_builtins_live_below_the_engine():
    assert FUNCTIONS["List.nth"](((1, 2, 3), 1)) == 2
    assert binop("div", 7, 2) == 3
    with pytest.raises(MLError):
        binop("mod", 1, 0)


def _imports(pkg: str) -> set[str]:
    out = set()
    for path in (ROOT / "cpn" / pkg).rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom) and node.module:
                out.add(node.module)
            elif isinstance(node, ast.Import):
                out.update(a.name for a in node.names)
    return out


def test_engine_imports_neither_the_language_nor_the_front_end():
    assert not {m for m in _imports("engine") if m.startswith("cpn.lang")}


def test_one_arc_kind_from_the_checker_to_the_engine():
    from cpn.arcs import ArcKind

    m = cpn.loads("colset U = unit; place A : U = 1`(); place B : U; place C : U; place D : U;\n"
                  "trans t; arc A -> t; arc t -> B; arc C <-> t; inhibitor D -> t; reset B -> t;")
    kinds = [a.kind for a in m.net.transitions[0].arcs]
    assert all(type(k) is ArcKind for k in kinds)
    assert sorted(kinds) == sorted(ArcKind)
    assert [k for k in ArcKind if k.consumes] == [ArcKind.IN, ArcKind.BOTH]
    assert [k for k in ArcKind if k.produces] == [ArcKind.OUT, ArcKind.BOTH]
    assert [k for k in ArcKind if not k.reads] == [ArcKind.OUT]
    assert ArcKind.INHIBITOR.blocks and ArcKind.RESET.empties and ArcKind.IN == "in"


def _protocol_members():
    from cpn.engine import Engine

    return {n for n in vars(Engine) if not n.startswith("_")} | set(Engine.__annotations__)


@pytest.mark.parametrize("reference", [False, True])
def test_both_engines_have_the_whole_protocol(reference):
    engine = cpn.loads(MODEL).engine(reference=reference)
    missing = {n for n in _protocol_members() if not hasattr(engine, n)}
    assert not missing


def test_the_toy_engine_of_the_tests_has_the_whole_protocol():
    from tests.statespace._toy import dining_philosophers

    assert not {n for n in _protocol_members() if not hasattr(dining_philosophers(2), n)}


def test_bounds_print_cpn_ml_with_either_engine():
    from cpn.checks import boundedness
    from cpn.statespace import Explorer

    texts = []
    for reference in (False, True):
        x = Explorer(cpn.loads(MODEL).engine(reference=reference)).run()
        texts.append([(b.upper_text, b.lower_text) for b in boundedness(x).places])
    assert texts[0] == texts[1]
    assert ("1`ph(1)++1`ph(2)", "empty") in texts[1]


@pytest.mark.parametrize("reference", [False, True])
def test_a_token_outside_its_colour_set_is_e0402(reference):
    from cpn.errors import EvaluationError
    from cpn.statespace import Explorer

    m = cpn.loads("colset N = int with 0..2; var x : N; place P : N = 1`2; trans t;\n"
                  "arc P -> t : x; arc t -> P : x + 1;")
    with pytest.raises(EvaluationError) as info:
        Explorer(m.engine(reference=reference)).run()
    assert info.value.diagnostic().code == "E0402"
    assert "error[E0402]" in info.value.render()


def test_an_evaluation_failure_stays_e0401():
    from cpn.errors import EvaluationError
    from cpn.statespace import Explorer

    m = cpn.loads("colset N = int with 0..2; var x : N; place P : N = 1`0; trans t;\n"
                  "arc P -> t : x; arc t -> P : 1 div x;")
    with pytest.raises(EvaluationError) as info:
        Explorer(m.engine()).run()
    assert info.value.diagnostic().code == "E0401"
