"""State encoding: interned place markings decode to what was encoded, equal markings share one id."""

from hypothesis import given, settings
from hypothesis import strategies as st

import cpn

SRC = """colset C = int with 0..3; colset P = product C * C; colset T = int with 0..3 timed;
place A : C; place B : P; place D : T;"""
MODEL = cpn.loads(SRC, "enc.cpnet")

markings = st.tuples(
    st.dictionaries(st.integers(0, 3), st.integers(1, 3), max_size=4),
    st.dictionaries(st.tuples(st.integers(0, 3), st.integers(0, 3)), st.integers(1, 3), max_size=4),
    st.dictionaries(st.tuples(st.integers(0, 3), st.integers(0, 9)), st.integers(1, 3), max_size=4),
)


@settings(max_examples=200)
@given(markings, markings)
def test_decode_encode_roundtrip(m1, m2):
    e = MODEL.engine()
    s1 = tuple(e.store.intern(p, dict(d)) for p, d in enumerate(m1)) + (0,)
    s2 = tuple(e.store.intern(p, dict(reversed(list(d.items())))) for p, d in enumerate(m2)) + (0,)
    assert e.marking(s1) == [dict(d) for d in m1]
    assert e.token_counts(s1) == tuple(sum(d.values()) for d in m1)
    assert (s1 == s2) == (list(m1) == list(m2))


def test_untimed_projection_merges_timestamps():
    e = MODEL.engine()
    a = (0, 0, e.store.intern(2, {(1, 0): 1, (1, 5): 1}), 0)
    b = (0, 0, e.store.intern(2, {(1, 3): 2}), 7)
    assert a != b
    assert e.untimed(a) == e.untimed(b)
