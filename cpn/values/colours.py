"""Colour sets at run time: membership, enumeration, order and CPN ML printing of values.

Values are plain Python values (docs/internals.md): enumerations and indexes are ints, products,
records and lists are tuples, unions are ints or (tag, value) pairs.
Imports layer 0 only.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

#: colour sets with at most this many values can be enumerated (free variables, `CS.all()`, `CS.ran()`).
MAX_ENUMERABLE: int = 100_000


def format_int(v: int) -> str:
    """CPN ML text of an integer (``~3`` for -3)."""
    return f"~{-v}" if v < 0 else str(v)


def format_string(v: str) -> str:
    """CPN ML text of a string, quoted and escaped."""
    return '"' + v.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'


class ColourSet:
    """A colour set: a named set of values with an order.

    Examples
    --------
    >>> ph = IndexCS("PH", "ph", 1, 3)
    >>> ph.values(), ph.contains(4), ph.format(2), ph.describe()
    ([1, 2, 3], False, 'ph(2)', 'PH')
    """

    kind = "?"
    finite = True

    def __init__(self, name: str, timed: bool = False):
        self.name = name
        self.timed = timed

    def contains(self, v: Any) -> bool:
        """Whether v is a value of the colour set."""
        raise NotImplementedError

    def values(self) -> list | None:
        """All values in CPN ML order, or None if the colour set is infinite or too large."""
        return None

    def size(self) -> int | None:
        """The number of values (`CS.size()`), or None if the colour set is not enumerable."""
        vals = self.values()
        return None if vals is None else len(vals)

    def format(self, v: Any) -> str:
        """CPN ML text of a value of the colour set."""
        return repr(v)

    def sort_key(self, v: Any) -> Any:
        """A key ordering values as CPN Tools prints them in multisets."""
        return v

    def ord(self, v: Any) -> int:
        """The position of v among the values (`CS.ord`)."""
        vals = self.values()
        if vals is None:
            raise ValueError(f"colour set {self.name} is not enumerable")
        return vals.index(v)

    def describe(self) -> str:
        """The colour set's declaration, as error messages quote it."""
        return self.name

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.name}>"


class UnitCS(ColourSet):
    kind = "unit"

    def contains(self, v):
        return v == ()

    def values(self):
        return [()]

    def format(self, v):
        return "()"


class BoolCS(ColourSet):
    kind = "bool"

    def __init__(self, name, timed=False, false="false", true="true"):
        super().__init__(name, timed)
        self.names = (false, true)  # `bool with (no, yes)` writes false as no and true as yes

    def contains(self, v):
        return isinstance(v, bool)

    def values(self):
        return [False, True]

    def format(self, v):
        return self.names[bool(v)]


class IntCS(ColourSet):
    kind = "int"

    def __init__(self, name, low=None, high=None, timed=False):
        super().__init__(name, timed)
        self.low, self.high = low, high
        self.finite = low is not None

    def contains(self, v):
        if not isinstance(v, int) or isinstance(v, bool):
            return False
        return self.low is None or self.low <= v <= self.high

    def values(self):
        if self.low is None or self.high - self.low + 1 > MAX_ENUMERABLE:
            return None
        return list(range(self.low, self.high + 1))

    def size(self):
        return None if self.low is None else max(0, self.high - self.low + 1)

    def ord(self, v):
        return v - self.low

    def format(self, v):
        return format_int(v)

    def describe(self):
        return f"int with {format_int(self.low)}..{format_int(self.high)}" if self.low is not None else "int"


class StringCS(ColourSet):
    kind = "string"
    finite = False

    def __init__(self, name, timed=False, chars=None, lengths=None):
        super().__init__(name, timed)
        self.chars, self.lengths = chars, lengths  # `string with "a".."z" and 3..9`

    def contains(self, v):
        if not isinstance(v, str):
            return False
        if self.chars is not None and not all(self.chars[0] <= c <= self.chars[1] for c in v):
            return False
        return self.lengths is None or self.lengths[0] <= len(v) <= self.lengths[1]

    def format(self, v):
        return format_string(v)


class RealCS(ColourSet):
    kind = "real"
    finite = False

    def contains(self, v):
        return isinstance(v, (int, float)) and not isinstance(v, bool)

    def format(self, v):
        return repr(float(v)).replace("-", "~")


class EnumCS(ColourSet):
    kind = "enum"

    def __init__(self, name, constants: list[str], timed=False):
        super().__init__(name, timed)
        self.constants = list(constants)

    def contains(self, v):
        return isinstance(v, int) and not isinstance(v, bool) and 0 <= v < len(self.constants)

    def values(self):
        return list(range(len(self.constants)))

    def ord(self, v):
        return v

    def format(self, v):
        return self.constants[v]


class IndexCS(ColourSet):
    kind = "index"

    def __init__(self, name, constructor: str, low: int, high: int, timed=False):
        super().__init__(name, timed)
        self.constructor, self.low, self.high = constructor, low, high

    def contains(self, v):
        return isinstance(v, int) and not isinstance(v, bool) and self.low <= v <= self.high

    def values(self):
        return list(range(self.low, self.high + 1)) if self.high - self.low < MAX_ENUMERABLE else None

    def ord(self, v):
        return v - self.low

    def format(self, v):
        return f"{self.constructor}({format_int(v)})"


class ProductCS(ColourSet):
    kind = "product"

    def __init__(self, name, components: list[ColourSet], timed=False):
        super().__init__(name, timed)
        self.components = list(components)
        self.finite = all(c.finite for c in components)

    def contains(self, v):
        return (isinstance(v, tuple) and len(v) == len(self.components)
                and all(c.contains(x) for c, x in zip(self.components, v)))

    def values(self):
        total = 1
        parts = []
        for c in self.components:
            vals = c.values()
            if vals is None:
                return None
            total *= len(vals)
            if total > MAX_ENUMERABLE:
                return None
            parts.append(vals)
        import itertools

        return [tuple(p) for p in itertools.product(*parts)]

    def format(self, v):
        return "(" + ",".join(c.format(x) for c, x in zip(self.components, v)) + ")"

    def describe(self):
        return "product " + " * ".join(c.name for c in self.components)

    def sort_key(self, v):
        return tuple(c.sort_key(x) for c, x in zip(self.components, v))


class RecordCS(ColourSet):
    kind = "record"

    def __init__(self, name, fields: list[tuple[str, ColourSet]], timed=False):
        super().__init__(name, timed)
        self.fields = sorted(fields, key=lambda f: f[0])
        self.labels = [f[0] for f in self.fields]
        self.finite = all(c.finite for _, c in fields)

    def contains(self, v):
        return (isinstance(v, tuple) and len(v) == len(self.fields)
                and all(c.contains(x) for (_, c), x in zip(self.fields, v)))

    def values(self):
        return ProductCS(self.name, [c for _, c in self.fields]).values()

    def format(self, v):
        return "{" + ",".join(f"{label}={c.format(x)}" for (label, c), x in zip(self.fields, v)) + "}"

    def describe(self):
        return "record " + " * ".join(f"{label}:{c.name}" for label, c in self.fields)

    def sort_key(self, v):
        return tuple(c.sort_key(x) for (_, c), x in zip(self.fields, v))


class ListCS(ColourSet):
    kind = "list"
    finite = False

    def __init__(self, name, elem: ColourSet, low=None, high=None, timed=False):
        super().__init__(name, timed)
        self.elem, self.low, self.high = elem, low, high

    def contains(self, v):
        if not isinstance(v, tuple):
            return False
        if self.low is not None and not (self.low <= len(v) <= self.high):
            return False
        return all(self.elem.contains(x) for x in v)

    def format(self, v):
        return "[" + ",".join(self.elem.format(x) for x in v) + "]"

    def describe(self):
        return f"list {self.elem.name}" + (f" with {self.low}..{self.high}" if self.low is not None else "")

    def sort_key(self, v):
        return tuple(self.elem.sort_key(x) for x in v)


class UnionCS(ColourSet):
    kind = "union"

    def __init__(self, name, constructors: list[tuple[str, ColourSet | None]], timed=False):
        super().__init__(name, timed)
        self.constructors = list(constructors)
        self.finite = all(c is None or c.finite for _, c in constructors)

    def contains(self, v):
        if isinstance(v, tuple):
            if len(v) != 2 or not isinstance(v[0], int) or not 0 <= v[0] < len(self.constructors):
                return False
            cs = self.constructors[v[0]][1]
            return cs is not None and cs.contains(v[1])
        return isinstance(v, int) and 0 <= v < len(self.constructors) and self.constructors[v][1] is None

    def values(self):
        out = []
        for i, (_, cs) in enumerate(self.constructors):
            if cs is None:
                out.append(i)
            else:
                vals = cs.values()
                if vals is None:
                    return None
                out.extend((i, x) for x in vals)
            if len(out) > MAX_ENUMERABLE:
                return None
        return out

    def describe(self):
        return "union " + " + ".join(name if cs is None else f"{name}:{cs.name}" for name, cs in self.constructors)

    def format(self, v):
        if isinstance(v, tuple):
            name, cs = self.constructors[v[0]]
            inner = cs.format(v[1])
            return f"{name}({inner[1:-1]})" if inner.startswith("(") and inner.endswith(")") else f"{name}({inner})"
        return self.constructors[v][0]

    def sort_key(self, v):
        if isinstance(v, tuple):
            return (v[0], self.constructors[v[0]][1].sort_key(v[1]))
        return (v, ())


class SubsetCS(ColourSet):
    kind = "subset"

    def __init__(self, name, base: ColourSet, predicate: Callable[[Any], bool] | None = None,
                 members: Iterable | None = None, timed=False):
        super().__init__(name, timed)
        self.base = base
        self.predicate = predicate
        self.members = list(members) if members is not None else None
        self._member_set = set(self.members) if self.members is not None else None
        self.finite = self.members is not None or base.finite

    def contains(self, v):
        if not self.base.contains(v):
            return False
        if self._member_set is not None:
            return v in self._member_set
        return bool(self.predicate(v))

    def values(self):
        if self.members is not None:
            return sorted(self.members, key=self.base.sort_key)
        vals = self.base.values()
        return None if vals is None else [v for v in vals if self.predicate(v)]

    def format(self, v):
        return self.base.format(v)

    def sort_key(self, v):
        return self.base.sort_key(v)


class AliasCS(ColourSet):
    """`colset B = A;`: another name for a colour set."""

    def __init__(self, name, base: ColourSet, timed=False):
        super().__init__(name, timed)
        self.base = base
        self.kind = base.kind
        self.finite = base.finite

    def contains(self, v):
        return self.base.contains(v)

    def values(self):
        return self.base.values()

    def size(self):
        return self.base.size()

    def ord(self, v):
        return self.base.ord(v)

    def format(self, v):
        return self.base.format(v)

    def sort_key(self, v):
        return self.base.sort_key(v)

    def describe(self):
        return self.base.describe()


def declared(cs: ColourSet) -> str:
    """A colour set for messages: its name, and its declaration where that says more (`PEND = product ID * NO`)."""
    text = cs.describe()
    return cs.name if text == cs.name else f"{cs.name} = {text}"


def outside(cs: ColourSet, v: Any) -> str:
    """Why `v` is not a value of `cs`, for messages: the colour set as declared and, for a product, record,
    list or union, the part of `v` that is out of its colour set.

    >>> pend = ProductCS("PEND", [IntCS("ID", 1, 2), IntCS("NO", 0, 3)])
    >>> outside(pend, (1, 5))
    'PEND = product ID * NO: its component 2, 5, is outside NO = int with 0..3'
    """
    return declared(cs) + _why(cs, v)


def _safe_format(cs: ColourSet, v: Any) -> str:
    try:
        return cs.format(v)
    except Exception:  # noqa: BLE001 - a value outside the colour set may not print as one of its values
        return repr(v)


def _why(cs: ColourSet, v: Any) -> str:
    while isinstance(cs, AliasCS):
        cs = cs.base
    parts: list[tuple[str, ColourSet, Any]] = []
    if isinstance(cs, ProductCS) and isinstance(v, tuple) and len(v) == len(cs.components):
        parts = [(f"its component {i}", c, x) for i, (c, x) in enumerate(zip(cs.components, v), 1)]
    elif isinstance(cs, RecordCS) and isinstance(v, tuple) and len(v) == len(cs.fields):
        parts = [(f"its field {label}", c, x) for (label, c), x in zip(cs.fields, v)]
    elif isinstance(cs, ListCS) and isinstance(v, tuple):
        if cs.low is not None and not cs.low <= len(v) <= cs.high:
            return f": its length {len(v)} is outside {cs.low}..{cs.high}"
        parts = [(f"its element {i}", cs.elem, x) for i, x in enumerate(v, 1)]
    elif (isinstance(cs, UnionCS) and isinstance(v, tuple) and len(v) == 2 and isinstance(v[0], int)
          and 0 <= v[0] < len(cs.constructors) and cs.constructors[v[0]][1] is not None):
        name, arg = cs.constructors[v[0]]
        parts = [(f"the argument of {name}", arg, v[1])]
    elif isinstance(cs, SubsetCS) and cs.base.contains(v):
        return f": it is a value of {cs.base.name} but not of the subset"
    for what, c, x in parts:
        if not c.contains(x):
            return f": {what}, {_safe_format(c, x)}, is outside {outside(c, x)}"
    return ""


def format_multiset(cs: ColourSet, items: Iterable[tuple[Any, int]], timed: bool = False) -> str:
    """CPN ML text of a multiset: ``1`ph(1)++2`ph(2)``; ``empty`` when empty.

    For timed multisets the items are ((value, timestamp), count) and print as ``1`x@5``.
    """
    items = [(v, n) for v, n in items if n]
    if not items:
        return "empty"
    if timed:
        items.sort(key=lambda it: (cs.sort_key(it[0][0]), it[0][1]))
        return "+++".join(f"{n}`{cs.format(v)}@{t}" for (v, t), n in items)
    items.sort(key=lambda it: cs.sort_key(it[0]))
    return "++".join(f"{n}`{cs.format(v)}" for v, n in items)
