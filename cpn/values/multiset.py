"""Immutable, hashable multisets and their algebra (``++``, ``--``, scalar ``n`e``, inclusion).

`TimedMultiset` is the value of an inscription with delays (``e @+ d``): (value, count, delay) items.
Imports the standard library only.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any


class MultisetError(ValueError):
    """``m1 -- m2`` where m2 is not included in m1, or a negative coefficient."""


class Multiset:
    """A finite multiset over hashable values.

    Examples
    --------
    >>> m = Multiset.of(1, 2) + Multiset([3])
    >>> m.count(1), sorted(m.items()), (m - Multiset.of(1)).count(1)
    (2, [(1, 2), (3, 1)], 1)
    """

    __slots__ = ("_d", "_hash")

    def __init__(self, items: Mapping[Any, int] | Iterable[Any] | None = None):
        d: dict = {}
        if isinstance(items, Multiset):
            d = dict(items._d)
        elif isinstance(items, Mapping):
            for k, n in items.items():
                if n < 0:
                    raise MultisetError(f"negative coefficient {n}")
                if n:
                    d[k] = d.get(k, 0) + n
        elif items is not None:
            for k in items:
                d[k] = d.get(k, 0) + 1
        self._d = d
        self._hash = None

    @classmethod
    def _from_dict(cls, d: dict) -> Multiset:
        m = cls.__new__(cls)
        m._d = d
        m._hash = None
        return m

    @classmethod
    def of(cls, value: Any, count: int = 1) -> Multiset:
        """``count`value``: one value with a multiplicity."""
        if count < 0:
            raise MultisetError(f"negative coefficient {count} in {count}`...")
        return cls._from_dict({value: count} if count else {})

    def __add__(self, other: Multiset) -> Multiset:
        if len(other._d) > len(self._d):
            self, other = other, self
        d = dict(self._d)
        for k, n in other._d.items():
            d[k] = d.get(k, 0) + n
        return Multiset._from_dict(d)

    def __sub__(self, other: Multiset) -> Multiset:
        d = dict(self._d)
        for k, n in other._d.items():
            have = d.get(k, 0)
            if have < n:
                raise MultisetError("the subtracted multiset is not included in the multiset it is subtracted from")
            if have == n:
                del d[k]
            else:
                d[k] = have - n
        return Multiset._from_dict(d)

    def scale(self, n: int) -> Multiset:
        if n < 0:
            raise MultisetError(f"negative coefficient {n}")
        return Multiset._from_dict({k: c * n for k, c in self._d.items()} if n else {})

    def __le__(self, other: Multiset) -> bool:
        od = other._d
        return all(od.get(k, 0) >= n for k, n in self._d.items())

    def __ge__(self, other: Multiset) -> bool:
        return other <= self

    def __eq__(self, other: object) -> bool:
        if isinstance(other, Multiset):
            return self._d == other._d
        return NotImplemented

    def __hash__(self) -> int:
        if self._hash is None:
            self._hash = hash(frozenset(self._d.items()))
        return self._hash

    def __len__(self) -> int:
        return sum(self._d.values())

    size = __len__

    def __iter__(self):
        for k, n in self._d.items():
            for _ in range(n):
                yield k

    def __contains__(self, value: Any) -> bool:
        return value in self._d

    def count(self, value: Any) -> int:
        """The multiplicity of value (`cf`)."""
        return self._d.get(value, 0)

    def items(self):
        """(value, multiplicity) pairs."""
        return self._d.items()

    def distinct(self):
        """The values, each once."""
        return self._d.keys()

    def __bool__(self) -> bool:
        return bool(self._d)

    def __repr__(self) -> str:
        inner = " ++ ".join(f"{n}`{k!r}" for k, n in self._d.items())
        return f"Multiset({inner or 'empty'})"


EMPTY = Multiset()


class TimedMultiset:
    """Tokens with delays, the value of ``ms @+ d``: a list of (value, count, delay)."""

    __slots__ = ("items",)

    def __init__(self, items: list[tuple[Any, int, int]]):
        self.items = items

    @staticmethod
    def lift(m: Multiset | TimedMultiset, delay: int = 0) -> TimedMultiset:
        if isinstance(m, TimedMultiset):
            if not delay:
                return m
            return TimedMultiset([(v, n, d + delay) for v, n, d in m.items])
        return TimedMultiset([(v, n, delay) for v, n in m.items()])

    def __add__(self, other):
        return TimedMultiset(self.items + TimedMultiset.lift(other).items)

    __radd__ = __add__

    def untimed(self) -> Multiset:
        d: dict = {}
        for v, n, _ in self.items:
            d[v] = d.get(v, 0) + n
        return Multiset._from_dict({k: n for k, n in d.items() if n})

    def __len__(self):
        return sum(n for _, n, _ in self.items)

    def __eq__(self, other):
        if isinstance(other, (TimedMultiset, Multiset)):
            a = self.untimed() if isinstance(self, TimedMultiset) else self
            b = other.untimed() if isinstance(other, TimedMultiset) else other
            return a == b
        return NotImplemented

    def __hash__(self):
        return hash(self.untimed())
