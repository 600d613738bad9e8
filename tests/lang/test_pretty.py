"""parse(pretty(ast)) == ast: on every model of the repository, on random nets and on expressions."""

import glob
import os

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cpn.diagnostics import Span
from cpn.lang import ast as A
from cpn.lang.parser import parse
from cpn.lang.pretty import pretty
from tests.engine.randomnets import random_net

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(__file__)))
MODELS = sorted(glob.glob(os.path.join(ROOT, "**", "*.cpnet"), recursive=True))


def shape(x):
    """The syntax tree without positions and annotations, as a flat list in preorder (iterative, and flat so
    that comparing two shapes does not recurse: a model may hold a chain of thousands of operators)."""
    out = []
    stack = [x]
    while stack:
        y = stack.pop()
        if isinstance(y, (A.Expr, A.Pat, A.Decl, A.TypeExpr, A.ColsetBody, A.Clause)):
            keys = sorted(k for k in y.__dataclass_fields__
                          if k not in ("span", "ty", "ref", "op_ty", "index", "ty_labels", "ran_var")
                          and not k.endswith("_span"))
            out.append((type(y).__name__, tuple(keys)))
            stack.extend(getattr(y, k) for k in reversed(keys))
        elif isinstance(y, Span):
            out.append(None)
        elif isinstance(y, (list, tuple)):
            items = [i for i in y if not isinstance(i, Span)]
            out.append(("items", len(items)))
            stack.extend(reversed(items))
        else:
            out.append(y)
    return out


def roundtrip(text, filename="a.cpnet"):
    m1 = parse(text, filename)  # a model's own path: the files it uses are found beside it
    out = pretty(m1)
    m2 = parse(out, "b.cpnet")
    assert shape(m1.decls) == shape(m2.decls), out
    assert pretty(m2) == out


@pytest.mark.parametrize("path", MODELS, ids=lambda p: os.path.relpath(p, ROOT))
def test_repository_models_round_trip(path):
    with open(path, encoding="utf-8") as fh:
        roundtrip(fh.read(), path)


def test_random_nets_round_trip():
    for seed in range(200):
        roundtrip(random_net(seed))


atoms = st.sampled_from(["x", "1", "~2", '"a"', "true", "()", "[]", "empty", "C.all()", "#1 t"])


def exprs(depth=3):
    if depth == 0:
        return atoms
    sub = exprs(depth - 1)
    return st.one_of(
        atoms,
        st.builds(lambda a, o, b: f"({a} {o} {b})", sub, st.sampled_from(
            ["+", "-", "*", "div", "mod", "^", "::", "^^", "=", "<>", "<", ">=", "andalso", "orelse", "++",
             "--", "`", "@+"]), sub),
        st.builds(lambda a, b, c: f"(if {a} then {b} else {c})", sub, sub, sub),
        st.builds(lambda a, b: f"f ({a}, {b})", sub, sub),
        st.builds(lambda a: f"let val y = {a} in y end", sub),
        st.builds(lambda a, b: f"(case {a} of 0 => {b} | _ => {b})", sub, sub),
    )


@settings(max_examples=200, deadline=None)
@given(exprs())
def test_expressions_round_trip(e):
    roundtrip(f"val v = {e};")
