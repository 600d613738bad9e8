"""The predecessors CTL needs (`reverse_csr`) computed by a counting sort in native code are those
of the sort in Python: every arc's source under its target, in the order of the arcs."""

from array import array

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cpn.checks import ctl
from cpn.statespace import graphnative


@st.composite
def graphs(draw):
    n = draw(st.integers(1, 30))
    succ = [sorted(draw(st.lists(st.integers(0, n - 1), max_size=5))) for _ in range(n)]
    nexp = draw(st.integers(0, n))  # a partial graph: only the first states were expanded
    offsets, dst = array("q", [0]), array("i")
    for u in range(nexp):
        dst.extend(succ[u])
        offsets.append(len(dst))
    return n, offsets, dst


def _plain(n, offsets, dst):
    """Predecessors by definition: for each target, the sources of its arcs in arc order."""
    into = [[] for _ in range(n)]
    for u in range(len(offsets) - 1):
        for i in range(offsets[u], offsets[u + 1]):
            into[dst[i]].append(u)
    return into


@settings(max_examples=300, deadline=None)
@given(graphs())
def test_native_predecessors_are_the_python_ones(monkeypatch_case):
    n, offsets, dst = monkeypatch_case
    if graphnative.library() is None:
        pytest.skip("no native code here")
    saved = graphnative.MIN_ITEMS
    graphnative.MIN_ITEMS = 0
    try:
        got = graphnative.reverse(n, offsets, dst)
    finally:
        graphnative.MIN_ITEMS = saved
    assert got is not None
    pred_off, pred = got
    assert pred_off.typecode == "q" and pred.typecode == "i" and len(pred_off) == n + 1
    assert [list(pred[pred_off[v]:pred_off[v + 1]]) for v in range(n)] == _plain(n, offsets, dst)
    if len(offsets) == n + 1:  # the Python fallback reads every state's arcs
        graphnative.enabled, was = False, graphnative.enabled
        try:
            assert ctl.reverse_csr(n, offsets, dst) == got
        finally:
            graphnative.enabled = was
