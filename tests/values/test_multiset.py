"""The multiset algebra obeys its laws."""

from hypothesis import given
from hypothesis import strategies as st

from cpn.values.multiset import Multiset, MultisetError

values = st.one_of(st.integers(-3, 3), st.tuples(st.integers(0, 2), st.booleans()), st.text(max_size=2))
multisets = st.dictionaries(values, st.integers(0, 4), max_size=6).map(Multiset)


@given(multisets, multisets, multisets)
def test_sum_is_associative_and_commutative(a, b, c):
    assert (a + b) + c == a + (b + c)
    assert a + b == b + a


@given(multisets)
def test_empty_is_neutral(a):
    assert a + Multiset() == a
    assert a - Multiset() == a


@given(multisets, multisets)
def test_subtraction_undoes_addition(a, b):
    assert (a + b) - b == a
    assert b <= a + b
    assert len(a + b) == len(a) + len(b)


@given(multisets, multisets)
def test_subtraction_requires_inclusion(a, b):
    if b <= a:
        assert (a - b) + b == a
    else:
        try:
            a - b
        except MultisetError:
            pass
        else:
            raise AssertionError("subtracting a multiset that is not included must fail")


@given(multisets, st.integers(0, 4))
def test_scalar(a, n):
    assert len(a.scale(n)) == n * len(a)
    total = Multiset()
    for _ in range(n):
        total = total + a
    assert a.scale(n) == total


@given(multisets, multisets)
def test_equal_multisets_hash_equal(a, b):
    c = Multiset(dict(reversed(list(a.items()))))
    assert c == a and hash(c) == hash(a)
    if a == b:
        assert hash(a) == hash(b)
