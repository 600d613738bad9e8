"""The CTL fixpoints in native code (`graphnative.eu`, `ex`, `eg`, `label_rows`) give the states the
brute-force fixpoints of tests/checks/test_ctl.py give, on random graphs (the native code is used only
above `graphnative.MIN_ITEMS` arcs, so the tests lower it to 0)."""

import random
from array import array
from contextlib import contextmanager

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cpn.checks.ctl import Atom, Kripke, Temporal
from cpn.statespace import graphnative
from tests.checks.test_ctl import Brute, formula, graph


@contextmanager
def native_always():
    """Native code for graphs of any size (skips the test where there is none)."""
    if graphnative.library() is None:
        pytest.skip("no native code here")
    saved, graphnative.MIN_ITEMS = graphnative.MIN_ITEMS, 0
    try:
        yield
    finally:
        graphnative.MIN_ITEMS = saved


def _bits(s: set, n: int) -> bytearray:
    return bytearray(1 if u in s else 0 for u in range(n))


@settings(max_examples=200, deadline=None)
@given(st.integers(0, 10**9), st.integers(1, 12), st.sampled_from([0.1, 0.25, 0.5]))
def test_native_fixpoints_match_brute_force(seed, n, p_arc):
    rng = random.Random(seed)
    succ, offsets, dst, labels = graph(rng, n, p_arc)
    brute = Brute(succ, [])
    phi_set = {u for u in range(n) if rng.random() < 0.6}
    psi_set = {u for u in range(n) if rng.random() < 0.3}
    phi, psi = _bits(phi_set, n), _bits(psi_set, n)
    with native_always():
        k = Kripke(n, offsets, dst, labels)
        eu = graphnative.eu(n, k.pred_off, k.pred, phi, psi)
        ex = graphnative.ex(n, k.pred_off, k.pred, phi)
        eg = graphnative.eg(n, offsets, dst, k.pred_off, k.pred, k.dead, phi)
        atoms = [phi, psi]
        for op, args in (("EU", (Atom(0), Atom(1))), ("EX", (Atom(0),)), ("EG", (Atom(0),))):
            want = brute.sat(Temporal(op, args), [phi_set, psi_set])
            got = {"EU": eu, "EX": ex, "EG": eg}[op]
            assert got is not None and {u for u in range(n) if got[u]} == want, op
            # and the labelling, which calls them, agrees
            assert {u for u in range(n) if k.label(Temporal(op, args), atoms, {})[u]} == want, op


@settings(max_examples=150, deadline=None)
@given(st.integers(0, 10**9), st.integers(1, 12), st.sampled_from([0.1, 0.25, 0.5]))
def test_native_labelling_matches_brute_force(seed, n, p_arc):
    rng = random.Random(seed)
    succ, offsets, dst, labels = graph(rng, n, p_arc)
    brute = Brute(succ, [])
    atom_sets = [{u for u in range(n) if rng.random() < 0.5} for _ in range(3)]
    atoms = [_bits(s, n) for s in atom_sets]
    with native_always():
        k = Kripke(n, offsets, dst, labels)
        for _ in range(6):
            f = formula(rng, 3, 3)
            got = {u for u in range(n) if k.label(f, atoms, {})[u]}
            assert got == brute.sat(f, atom_sets), f


def test_native_eg_keeps_dead_states_and_cycles_only():
    with native_always():
        _eg_example()


def _eg_example():
    # 0 -> 1 -> 2 (dead), 3 -> 4 -> 3, 5 -> 6 where 6 is outside phi
    n = 7
    offsets = array("q", [0, 1, 2, 2, 3, 4, 5, 5])
    dst = array("i", [1, 2, 4, 3, 6])
    k = Kripke(n, offsets, dst, array("i", [0] * len(dst)))
    phi = bytearray([1, 1, 1, 1, 1, 1, 0])
    got = graphnative.eg(n, offsets, dst, k.pred_off, k.pred, k.dead, phi)
    assert list(got) == [1, 1, 1, 1, 1, 0, 0]
    assert list(graphnative.eu(n, k.pred_off, k.pred, bytearray([1, 1, 0, 0, 0, 0, 0]),
                               bytearray([0, 0, 1, 0, 0, 0, 0]))) == [1, 1, 1, 0, 0, 0, 0]
    assert list(graphnative.ex(n, k.pred_off, k.pred, bytearray([0, 0, 1, 1, 0, 0, 0]))) == [0, 1, 0, 0, 1, 0, 0]


@settings(max_examples=100, deadline=None)
@given(st.integers(0, 10**9), st.integers(1, 12))
def test_native_label_rows_are_the_arcs_labels(seed, n):
    rng = random.Random(seed)
    succ, offsets, dst, labels = graph(rng, n, 0.3, n_labels=4)
    with native_always():
        rows = graphnative.label_rows(n, offsets, labels, 4)
    if not len(labels):
        assert rows is None or all(not any(r) for r in rows)
        return
    want = [bytearray(1 if any(lab == t for lab, _v in succ[u]) else 0 for u in range(n)) for t in range(4)]
    assert rows == want


@settings(max_examples=100, deadline=None)
@given(st.lists(st.lists(st.integers(-5, 5), min_size=6, max_size=6), min_size=1, max_size=3),
       st.integers(-5, 5))
def test_native_integer_columns(cols, c):
    cols = [array("q", col) for col in cols]
    with native_always():
        total = graphnative.add_columns(cols)
        assert list(total) == [sum(x) for x in zip(*cols)]
        assert list(graphnative.less_equal(cols[0], total)) == [a <= b for a, b in zip(cols[0], total)]
        assert list(graphnative.less_equal(total, c)) == [a <= c for a in total]
        assert list(graphnative.less_equal(c, total)) == [c <= a for a in total]
