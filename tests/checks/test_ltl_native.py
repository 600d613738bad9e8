"""LTL over a complete graph in native code (`graphnative.ltl_accepting_cycle`, Couvreur's search of the
product in C) gives the verdict of the on-the-fly search in Python (`cpn.checks.ltl.check_ltl`), which
tests/checks/test_ltl.py checks against the paths of the system, on random systems and formulas."""

import random
from array import array

import pytest

from cpn.checks.buchi import translate
from cpn.checks.ltl import check_ltl
from cpn.statespace import graphnative
from tests.checks.test_ltl import random_kripke
from tests.checks.test_ltl_buchi import random_formula


def _csr(k, n):
    offsets, dst = array("q", [0]), array("i")
    for s in range(n):
        dst.extend(k.succ[s])
        offsets.append(len(dst))
    return offsets, dst


def _native(n, offsets, dst, props, f):
    aut = translate(("not", f))
    saved, graphnative.MIN_ITEMS = graphnative.MIN_ITEMS, 0
    try:
        return graphnative.ltl_accepting_cycle(n, offsets, dst, props, aut.moves, aut.initial, len(aut),
                                                      aut.n_acc)
    finally:
        graphnative.MIN_ITEMS = saved


@pytest.mark.parametrize("seed", range(8))
def test_native_product_search_agrees_with_the_search_on_the_fly(seed):
    if graphnative.library() is None:
        pytest.skip("no native code here")
    rng = random.Random(700 + seed)
    outcomes = set()
    for _ in range(120):
        n = rng.randrange(1, 8)
        k = random_kripke(rng, n, 3)
        f = random_formula(rng, 3, 3)
        offsets, dst = _csr(k, n)
        props = [bytearray(1 if i in k.labels[s] else 0 for s in range(n)) for i in range(3)]
        got = _native(n, offsets, dst, props, f)
        assert got is not None
        holds = check_ltl(k, f, k.props(3)).holds
        assert (not got[0]) == holds, (f, k.succ, k.labels)
        assert got[1] >= 1
        outcomes.add(holds)
    assert outcomes == {True, False}


def test_a_dead_state_repeats_forever_in_the_product():
    if graphnative.library() is None:
        pytest.skip("no native code here")
    # 0 -> 1, 1 dead; p holds in 1 only: F G p holds, G p does not
    offsets, dst = array("q", [0, 1, 1]), array("i", [1])
    p = [bytearray([0, 1])]
    assert _native(2, offsets, dst, p, ("F", ("G", ("ap", 0))))[0] is False
    assert _native(2, offsets, dst, p, ("G", ("ap", 0)))[0] is True
