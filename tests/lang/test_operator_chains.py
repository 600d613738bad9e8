"""Long chains of every operator: 600 and 5,000 terms of one operator in an initial marking, a `val`, a
guard, an arc inscription and a function body, from `.cpnet` and from `.cpn`, in both engines.

Each chain's value is worked out by hand (the formula beside it), not by running the tool.
"""

import pytest

import cpn
from cpn.errors import EvaluationError, ModelError
from tests._models import cpn_document, figures

# family: (colour set as .cpnet text, as CPN XML, operator, terms of an n-term chain, the value by hand,
# that value as CPN ML text)
FAMILIES = {
    "+": ("int", "<int/>", "+", lambda n: [str(i) for i in range(1, n + 1)],
          lambda n: n * (n + 1) // 2),
    "-": ("int", "<int/>", "-", lambda n: ["1000000"] + [str(i) for i in range(1, n)],
          lambda n: 1000000 - (n - 1) * n // 2),
    "*": ("int", "<int/>", "*", lambda n: ["2"] * 20 + ["1"] * (n - 20), lambda n: 2 ** 20),
    "div": ("int", "<int/>", "div", lambda n: [str(2 ** 40)] + ["2"] * 20 + ["1"] * (n - 21), lambda n: 2 ** 20),
    "mod": ("int", "<int/>", "mod", lambda n: ["1000003"] + ["1000000"] * (n - 2) + ["2"], lambda n: 1),
    "^": ("string", "<string/>", "^", lambda n: ['"a"' if i % 2 == 0 else '"b"' for i in range(n)],
          lambda n: "ab" * (n // 2)),
    "andalso": ("bool", "<bool/>", "andalso", lambda n: ["true"] * (n - 1) + ["(1 < 2)"], lambda n: True),
    "orelse": ("bool", "<bool/>", "orelse", lambda n: ["false"] * (n - 1) + ["(2 < 3)"], lambda n: True),
    "^^": ("list C", "<list><id>C</id></list>", "^^", lambda n: [f"[{i}]" for i in range(n)],
           lambda n: list(range(n))),
    "@": ("list C", "<list><id>C</id></list>", "@", lambda n: [f"[{i}]" for i in range(n)],
          lambda n: list(range(n))),
    "::": ("list C", "<list><id>C</id></list>", "::", lambda n: [str(i) for i in range(n - 1)] + ["[n1]"],
           lambda n: list(range(n))),
}


def ml(v) -> str:
    """CPN ML text (and CPN Tools' printed form) of a hand-computed value."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return f"~{-v}" if v < 0 else str(v)
    if isinstance(v, str):
        return f'"{v}"'
    return "[" + ",".join(ml(x) for x in v) + "]"


def parts(family: str, n: int):
    """The declarations, places, transition and arcs of a model whose transition T fires once and puts
    the chain's value on Out three times: from a `val`, from a function, from the arc itself. Its guard
    compares the chain with the value; place Init holds the chain as its initial marking."""
    cs, _xml, op, terms, value = FAMILIES[family]
    ts = terms(n)
    chain = f" {op} ".join(ts)
    fchain = f" {op} ".join(["z"] + ts[1:]) if family != "::" else f" {op} ".join(ts[:-1] + ["z"])
    arg = ts[0] if family != "::" else "[n1]"
    v = value(n)
    guard = chain if cs == "bool" else f"({chain}) = {ml(v)}"
    mls = [f"val n1 = {n - 1};", f"val v = {chain};", f"fun f z = {fchain};"]
    places = [("Init", "R", f"1`({chain})"), ("Go", "U", "1`()"), ("Out", "R", "")]
    arcs = [("Go", "T", "u"), ("T", "Out", f"1`v ++ 1`(f {arg}) ++ 1`({chain})")]
    return mls, places, ("T", guard), arcs, v


def cpnet_text(family: str, n: int) -> str:
    cs = FAMILIES[family][0]
    mls, places, (t, guard), arcs, _ = parts(family, n)
    lines = ["colset C = int;", f"colset R = {cs};", "colset U = unit;", "var u : U;"]
    lines += mls
    lines += [f"place {p} : {c}" + (f" = {init}" if init else "") + ";" for p, c, init in places]
    lines.append(f"trans {t} [{guard}];")
    lines += [f"arc {a} -> {b} : {x};" for a, b, x in arcs]
    return "\n".join(lines) + "\n"


def cpn_text(family: str, n: int) -> str:
    xml = FAMILIES[family][1]
    mls, places, (t, guard), arcs, _ = parts(family, n)
    return cpn_document([("C", "<int/>"), ("R", xml), ("U", "<unit/>")], [("u", "U")], mls, places,
                        [(t, f"[{guard}]")], arcs)


def load(family: str, n: int, lang: str, tmp_path):
    if lang == "cpnet":
        return cpn.loads(cpnet_text(family, n), f"{family}.cpnet")
    path = tmp_path / "chain.cpn"
    path.write_text(cpn_text(family, n), encoding="iso-8859-1")
    return cpn.load(path)


# Every family at 600 terms (E0206 before) in both languages, and at 5,000 in `.cpnet` (long tests: `--slow`);
# a `.cpn` file's text goes through the same walkers, so two families at 5,000 show that its import keeps
# chains flat too, in the suite.
CASES = ([(family, 600, lang) for family in FAMILIES for lang in ("cpnet", "cpn")]
         + [pytest.param(family, 5000, "cpnet", marks=pytest.mark.slow) for family in FAMILIES]
         + [("+", 5000, "cpn"), ("::", 5000, "cpn")])


@pytest.mark.parametrize(("family", "n", "lang"), CASES)
def test_a_long_chain_loads_checks_and_runs_in_both_engines(family, n, lang, tmp_path):
    model = load(family, n, lang, tmp_path)
    v = ml(FAMILIES[family][4](n))
    seen = []
    for reference in (False, True):
        e = model.engine(reference=reference)
        s0 = e.initial_state()
        names = [p.name for p in e.places]
        assert e.format_marking(s0, names.index("Top'Init 1")) == f"1`{v}"
        succ = e.successors(s0)
        assert len(succ) == 1  # the guard holds
        [(_, s1)] = succ
        assert e.format_marking(s1, names.index("Top'Out 1")) == f"3`{v}"
        assert e.successors(s1) == []
        seen.append([e.format_marking(s1, p) for p in range(len(names))])
    assert seen[0] == seen[1]


@pytest.mark.parametrize("reference", [False, True])
def test_a_mixed_chain_of_plus_and_minus_in_a_function(reference):
    # 1 - 2 + 3 - 4 + ... - 600: each pair (2k-1) - 2k is -1, 300 pairs: -300
    chain = "".join(f" {'+' if i % 2 else '-'} {i}" for i in range(2, 601))
    src = f"colset C = int; var x : C;\nfun f y = y{chain};\nplace P : C = 1`1; place Q : C;\n" \
          "trans T; arc P -> T : x; arc T -> Q : f x;\n"
    e = cpn.loads(src, "m.cpnet").engine(reference=reference)
    [(_, s1)] = e.successors(e.initial_state())
    assert e.format_marking(s1, 1) == "1`~300"


@pytest.mark.parametrize("reference", [False, True])
@pytest.mark.parametrize("n", [600, 5000])
def test_a_long_andalso_chain_still_stops_at_the_first_false(reference, n):
    # `x div 0` after the false operand is never evaluated: no division by zero, the guard is false
    terms = ["x > 0"] * (n // 2) + ["x > 5"] + ["x div 0 = 1"] + ["true"] * (n - n // 2 - 2)
    src = "colset C = int; var x : C;\nfun g x = " + " andalso ".join(terms) + ";\n" \
          "place P : C = 1`1; place Q : C;\ntrans T [not (g x) orelse " + " orelse ".join(["false"] * n) + "];\n" \
          "arc P -> T : x; arc T -> Q : x;\n"
    e = cpn.loads(src, "m.cpnet").engine(reference=reference)
    assert len(e.successors(e.initial_state())) == 1


@pytest.mark.parametrize("reference", [False, True])
def test_a_division_by_zero_inside_a_long_chain_is_a_positioned_run_time_error(reference):
    # 1000 div 10 div ... div (x - 1) div ...: x = 1 divides by zero after 300 operands
    terms = ["1000000"] + ["1"] * 300 + ["(x - 1)"] + ["1"] * 299
    src = "colset C = int; var x : C;\nplace P : C = 1`1; place Q : C;\ntrans T;\narc P -> T : x;\n" \
          "arc T -> Q : " + " div ".join(terms) + ";\n"
    e = cpn.loads(src, "m.cpnet").engine(reference=reference)
    with pytest.raises(EvaluationError) as info:
        e.successors(e.initial_state())
    assert "division by zero" in str(info.value) and "x=1" in str(info.value)
    assert info.value.span.line == 5


def test_a_long_multiset_sum_on_an_output_arc_compiles():
    # 5,000 terms 1`i on an output arc: the compiled code adds them in chunks
    n = 5000
    src = "colset C = int; colset U = unit; var u : U;\nplace Go : U = 1`(); place Q : C;\ntrans T;\n" \
          "arc Go -> T : u;\narc T -> Q : " + " ++ ".join(f"1`{i}" for i in range(n)) + ";\n"
    for reference in (False, True):
        e = cpn.loads(src, "m.cpnet").engine(reference=reference)
        [(_, s1)] = e.successors(e.initial_state())
        assert e.token_counts(s1) == (0, n)


def test_two_thousand_nested_parentheses_are_refused_at_their_position():
    # real nesting (each '+' inside the parentheses of the one before) is not a chain
    text = "colset C = int;\nval x = " + "(1 + " * 2000 + "1" + ")" * 2000 + ";\n"
    with pytest.raises(ModelError) as info:
        cpn.loads(text, "deep.cpnet")
    d = info.value.diagnostics[0]
    assert d.code == "E0206" and d.span.line == 2 and d.span.col > 1
    assert d.hint and "let" in d.hint
    assert "Traceback" not in info.value.render()


def test_parentheses_around_a_chain_are_not_nesting():
    # ((((1 + 2) + 3) + 4) ...): the parentheses group the chain as it groups itself
    n = 2000
    text = "colset C = int;\nval x = " + "(" * (n - 1) + "1" + "".join(f" + {i})" for i in range(2, n + 1)) + ";\n" \
           "place P : C = 1`x;\n"
    e = cpn.loads(text, "m.cpnet").engine()
    assert e.format_marking(e.initial_state(), 0) == f"1`{n * (n + 1) // 2}"


@pytest.mark.parametrize("name", ["chains.cpnet", "chains.cpn"])
@pytest.mark.parametrize("reference", [False, True])
def test_the_chains_model_has_its_hand_checked_figures(name, reference):
    # every operator with 600 terms (the model's header works the figures out)
    assert figures(name, reference=reference) == (6, 5, 1)
