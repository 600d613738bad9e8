"""Property texts are compiled by the engine's `predicate_compiler` capability (`cpn.engine.propertycode`),
which the property language reaches through the engine's protocol; an engine without it is checked with
the tree-walking evaluator, with the same values."""

import pathlib

import pytest

import cpn
from cpn.checks.columns import TransitionIndex
from cpn.diagnostics import Span
from cpn.engine.protocol import has
from cpn.lang import types as T
from cpn.properties.predicates import PropertyLanguage
from cpn.statespace import ExploreOptions, Explorer

ROOT = pathlib.Path(__file__).resolve().parents[2]
TEXTS = [
    "forall Station'Idle (fn m => size m <= 1) andalso size (sum Station'Idle) + size (sum Station'Busy) = 3",
    "size (Office'Requests 1) = 0 andalso Office'Log 1 = ID.all()",
    "exists Station'Busy (fn m => size m = 1)",
    "cf (2, Office'Replies 1) = 1 orelse cf (2, Office'Log 1) = 1",
    "let val n = size (sum Station'Busy) in n * n < 9 end",
]


class WithoutCompiler:
    """The engine, less its predicate compiler."""

    def __init__(self, engine):
        self._engine = engine

    def __getattr__(self, name):
        if name == "predicate_compiler":
            raise AttributeError(name)
        return getattr(self._engine, name)


def _values(engine, states, text):
    lang = PropertyLanguage(engine.net, engine, TransitionIndex(engine))
    compiled = lang.compile(text, None, Span("<test>", 1, 1), T.BOOL, "the test's text")
    return [compiled.fn(i, s) for i, s in enumerate(states)]


@pytest.mark.parametrize("reference", [False, True], ids=["compiled", "reference"])
def test_the_engines_compiler_and_the_evaluator_agree(reference):
    engine = cpn.load(ROOT / "models/examples/stations.cpnet").engine(reference=reference)
    assert has(engine, "predicate_compiler") and not has(WithoutCompiler(engine), "predicate_compiler")
    states = list(Explorer(engine, ExploreOptions()).run().graph.states)
    assert len(states) > 10
    varying = 0
    for text in TEXTS:
        got = _values(engine, states, text)
        assert got == _values(WithoutCompiler(engine), states, text), text
        varying += len(set(got)) > 1
    assert varying >= 3  # texts that tell states apart, not constants


def test_the_property_language_imports_no_code_generator():
    source = (ROOT / "cpn/properties/predicates.py").read_text(encoding="utf-8")
    assert "cpn.engine.codegen" not in source and "cpn.engine.runtime" not in source


def test_a_function_with_two_wildcards_in_its_tuple_pattern_compiles():
    # 'fn (_, _, l) => ...' became a Python lambda with the parameter '_' twice, a SyntaxError at compile time
    model = cpn.loads("colset I = int; colset T = product I * I * I; var a, b, c : I;\n"
                      "place P : T = 1`(1,2,3); trans t [c < 4];\narc P -> t : (a,b,c); arc t -> P : (a,b,c+1);")
    engine = model.engine()
    states = list(Explorer(engine, ExploreOptions()).run().graph.states)
    text = "List.all (fn (_, _, l) => l < 4) (ms_to_list (Top'P 1))"
    got = _values(engine, states, text)
    assert got == [True, False] and got == _values(WithoutCompiler(engine), states, text)


@pytest.fixture
def parses(monkeypatch) -> list:
    """The parses of property texts made while the test runs (none kept from before)."""
    from cpn.properties import predicates

    monkeypatch.setattr(predicates, "_PARSES", type(predicates._PARSES)())
    made: list = []
    real = predicates.parse
    monkeypatch.setattr(predicates, "parse", lambda *a, **k: made.append(a) or real(*a, **k))
    return made


def test_a_text_is_parsed_once_and_each_check_types_its_own_copy(parses):
    engine = cpn.load(ROOT / "models/examples/stations.cpnet").engine()
    states = list(Explorer(engine, ExploreOptions()).run().graph.states)
    first = _values(engine, states, TEXTS[0])
    lang = PropertyLanguage(engine.net, engine, TransitionIndex(engine))
    a = lang.check(TEXTS[0], None, Span("<test>", 1, 1), T.BOOL, "the test's text")
    b = lang.check(TEXTS[0], None, Span("<test>", 1, 1), T.BOOL, "the test's text")
    assert a is not b and _values(engine, states, TEXTS[0]) == first
    assert len(parses) == 1
    # a text with a syntax error is not kept: each check reports it
    for _ in range(2):
        with pytest.raises(cpn.ModelError):
            lang.check("size (", None, Span("<test>", 1, 1), T.BOOL, "the test's text")
    assert len(parses) == 3


def test_scenario_files_with_the_same_text_share_its_parse_and_keep_their_own_positions(parses):
    from cpn.properties import predicates

    engine = cpn.load(ROOT / "models/examples/stations.cpnet").engine()
    lang = PropertyLanguage(engine.net, engine, TransitionIndex(engine))
    # the file name is also a string of the text: only the spans' file changes
    text = f'{TEXTS[0]} andalso "a.toml" <> ""'
    exprs = {f: lang.check(text, None, Span(f, 1, 1), T.BOOL, "the test's text") for f in ("a.toml", "b.toml")}
    assert len(parses) == 1
    for f, expr in exprs.items():
        spans = {n.span.file for n in predicates.walk(expr) if getattr(n, "span", None) is not None}
        strings = [n.value for n in predicates.walk(expr) if isinstance(getattr(n, "value", None), str)]
        assert spans == {f} and "a.toml" in strings


# The values and functions a `let` declares are compiled (Python lambdas applied at once); a function that
# calls itself leaves its `let` to the evaluator
LETS = [
    ("let val n = size (sum Station'Busy) in n * n < 9 end", True),
    ("let val (a, b) = (size (sum Station'Busy), size (sum Station'Idle)) in a < b end", True),
    ("let val (_, n) = (0, size (Office'Replies 1)) in n < 2 end", True),
    ("let fun idle m = size m = 1 in forall Station'Idle idle end", True),
    ("let fun served (i : ID) = cf (i, Office'Log 1) = 1 in List.all served [1, 2] orelse served 3 end", True),
    ("let val k = 2 fun over (x, y : int) = x + y > k in over (size (Office'Log 1), size (Office'Replies 1)) end",
     True),
    ("let val n = 1 val n = n + size (Office'Log 1) in n > 1 end", True),
    ("List.all (fn (x, y : int) => x <= y) [(size (Office'Log 1), 2)]", True),
    ("let fun count n = if n = 0 then 0 else 1 + count (n - 1) in count (size (Office'Log 1)) < 3 end", False),
    ("let fun one 1 = true | one _ = false in one (size (Office'Log 1)) end", False),  # two clauses
]


@pytest.mark.parametrize(("text", "compiled"), LETS, ids=range(len(LETS)))
def test_let_declarations_are_compiled_with_the_evaluators_values(text, compiled, monkeypatch):
    from cpn.expr.evaluate import Evaluator

    engine = cpn.load(ROOT / "models/examples/stations.cpnet").engine()
    states = list(Explorer(engine, ExploreOptions()).run().graph.states)
    expected = _values(WithoutCompiler(engine), states, text)
    calls = []
    real = Evaluator.eval
    monkeypatch.setattr(Evaluator, "eval", lambda self, *a: calls.append(a) or real(self, *a))
    assert _values(engine, states, text) == expected
    assert (not calls) is compiled, calls[:1]
    assert len(set(expected)) > 1  # a text that tells states apart


def test_enabled_reads_the_finished_graph_as_it_reads_the_engine():
    # on the finished graph, `enabled` tests a state's arcs (marked once per arc); elsewhere, the engine's
    # successors: the same values, and those of the transitions' own enabling
    engine = cpn.load(ROOT / "models/examples/stations.cpnet").engine()
    g = Explorer(engine, ExploreOptions()).run().graph
    lang = PropertyLanguage(engine.net, engine, TransitionIndex(engine))
    text = "enabled \"Station'Take\" andalso not (enabled \"Office'Archive\")"
    compiled = lang.compile(text, None, Span("<test>", 1, 1), T.BOOL, "the test's text")
    states = list(g.states)
    lang.ctx.graph = g
    by_graph = [compiled.fn(i, s) for i, s in enumerate(states)]
    lang.ctx.graph = None
    by_engine = [compiled.fn(i, s) for i, s in enumerate(states)]

    def fires(s, name):
        return any(engine.transitions[engine.binding_element(be).transition].name.startswith(name + " ")
                   for be, _ in engine.successors(s))

    expected = [fires(s, "Station'Take") and not fires(s, "Office'Archive") for s in states]
    assert by_graph == expected and by_engine == expected and True in expected and False in expected
