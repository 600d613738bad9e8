"""The LTL to Büchi translation against a direct reading of LTL on lasso words (u v v v ...)."""

from __future__ import annotations

import random

import pytest

from cpn.checks.buchi import accepts, nnf, translate

OPS1 = ("not", "X", "F", "G")
OPS2 = ("and", "or", "U", "R")


def random_formula(rng: random.Random, depth: int, n_aps: int) -> tuple:
    if depth == 0 or rng.random() < 0.25:
        r = rng.random()
        return ("true",) if r < 0.05 else ("false",) if r < 0.1 else ("ap", rng.randrange(n_aps))
    if rng.random() < 0.45:
        return (rng.choice(OPS1), random_formula(rng, depth - 1, n_aps))
    return (rng.choice(OPS2), random_formula(rng, depth - 1, n_aps), random_formula(rng, depth - 1, n_aps))


def holds_on_lasso(f: tuple, prefix: list, cycle: list) -> bool:
    """LTL on the word prefix cycle^omega, by the definitions: positions 0..n-1, the successor of n-1
    being len(prefix); U and R as least and greatest fixed points over the positions."""
    word = list(prefix) + list(cycle)
    n, loop = len(word), len(prefix)
    nxt = [k + 1 if k + 1 < n else loop for k in range(n)]

    def ev(g) -> list[bool]:
        op = g[0]
        if op == "true":
            return [True] * n
        if op == "false":
            return [False] * n
        if op == "ap":
            return [g[1] in letter for letter in word]
        if op == "not":
            return [not v for v in ev(g[1])]
        if op in ("and", "or"):
            a, b = ev(g[1]), ev(g[2])
            return [x and y for x, y in zip(a, b)] if op == "and" else [x or y for x, y in zip(a, b)]
        if op == "X":
            a = ev(g[1])
            return [a[nxt[k]] for k in range(n)]
        if op == "F":
            return ev(("U", ("true",), g[1]))
        if op == "G":
            return ev(("R", ("false",), g[1]))
        a, b = ev(g[1]), ev(g[2])
        if op == "U":  # least fixed point of b or (a and X it)
            val = [False] * n
            for _ in range(n + 1):
                val = [b[k] or (a[k] and val[nxt[k]]) for k in range(n)]
            return val
        val = [True] * n  # R: greatest fixed point of b and (a or X it)
        for _ in range(n + 1):
            val = [b[k] and (a[k] or val[nxt[k]]) for k in range(n)]
        return val

    return ev(f)[0]


def random_word(rng: random.Random, n_aps: int) -> tuple[list, list]:
    letter = lambda: {i for i in range(n_aps) if rng.random() < 0.5}  # noqa: E731
    return [letter() for _ in range(rng.randrange(0, 4))], [letter() for _ in range(rng.randrange(1, 4))]


@pytest.mark.parametrize("seed", range(8))
def test_the_automaton_accepts_exactly_the_lasso_words_that_satisfy_the_formula(seed):
    rng = random.Random(seed)
    for _ in range(60):
        f = random_formula(rng, 3, 2)
        a = translate(f)
        for _ in range(12):
            prefix, cycle = random_word(rng, 2)
            assert accepts(a, prefix, cycle) == holds_on_lasso(f, prefix, cycle), (f, prefix, cycle)


def test_the_lasso_reading_is_not_trivial():
    # the reference semantics tells these apart, so the comparison above can fail
    assert holds_on_lasso(("G", ("F", ("ap", 0))), [], [{0}, set()])
    assert not holds_on_lasso(("F", ("G", ("ap", 0))), [], [{0}, set()])
    assert holds_on_lasso(("U", ("ap", 0), ("ap", 1)), [{0}, {0}], [{1}])
    assert not holds_on_lasso(("U", ("ap", 0), ("ap", 1)), [{0}, set()], [{1}])


def test_negation_normal_form_pushes_negations_to_the_propositions():
    f = nnf(("not", ("U", ("ap", 0), ("G", ("ap", 1)))))
    assert f == ("R", ("not", ("ap", 0)), ("U", ("true",), ("not", ("ap", 1))))


def test_a_contradiction_has_no_run_and_a_tautology_accepts_every_word():
    never = translate(("and", ("ap", 0), ("not", ("ap", 0))))
    assert not never.edges[never.initial]  # no edge: no run
    always = translate(("or", ("G", ("ap", 0)), ("F", ("not", ("ap", 0)))))
    rng = random.Random(1)
    for _ in range(20):
        assert accepts(always, *random_word(rng, 1))


def test_simplification_shrinks_the_automaton_and_keeps_the_meaning():
    from cpn.checks.buchi import simplify

    p, q = ("ap", 0), ("ap", 1)
    f = ("U", ("F", ("G", ("F", p))), ("F", q))  # (F G F p) U (F q) = F q
    assert simplify(nnf(f)) == nnf(("F", q))
    assert len(translate(f)) == len(translate(("F", q)))
    assert simplify(nnf(("F", ("G", ("F", p))))) == nnf(("G", ("F", p)))
    assert simplify(nnf(("G", ("F", ("G", p))))) == nnf(("F", ("G", p)))
