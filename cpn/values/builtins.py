"""The run-time meaning of the CPN ML library subset and of the infix operators, on the value
representation of `cpn.values` (docs/internals.md): what the engines call while firing.

The language (`cpn.lang.builtins`) gives the same names their types. Every function value takes one
argument (SML): tuples for several arguments, curried otherwise.

>>> FUNCTIONS["List.nth"](((1, 2, 3), 1))
2
>>> binop("div", 7, 2)
3
"""

from __future__ import annotations

import math
from typing import Any

from cpn.values.multiset import Multiset, MultisetError, TimedMultiset


class MLError(Exception):
    """A run-time error of CPN ML code (an SML exception such as Empty, Subscript, Div, Match)."""


class MLRaise(MLError):
    """An exception raised by `raise` in CPN ML code; `handle` catches it, else it is a run-time error.

    `value` is the exception value: its tag `"E#uid"` (no argument) or `("E#uid", argument)`.
    """

    def __init__(self, value, where: str):
        tag, arg = (value if isinstance(value, tuple) else (value, None))
        name = str(tag).split("#")[0]
        shown = name if arg is None else f'{name} "{arg}"' if isinstance(arg, str) else f"{name} {arg!r}"
        super().__init__(f"uncaught exception {shown}, raised by the 'raise' at {where}")
        self.value = value


def _empty(name):
    raise MLError(f"{name} of an empty list (SML exception Empty)")


def _hd(lst):
    if not lst:
        _empty("hd")
    return lst[0]


def _tl(lst):
    if not lst:
        _empty("tl")
    return lst[1:]


def _nth(arg):
    lst, i = arg
    if not 0 <= i < len(lst):
        raise MLError(f"List.nth: index {i} outside a list of length {len(lst)} (SML exception Subscript)")
    return lst[i]


def _take(arg):
    lst, i = arg
    if not 0 <= i <= len(lst):
        raise MLError(f"List.take: {i} outside a list of length {len(lst)} (SML exception Subscript)")
    return lst[:i]


def _drop(arg):
    lst, i = arg
    if not 0 <= i <= len(lst):
        raise MLError(f"List.drop: {i} outside a list of length {len(lst)} (SML exception Subscript)")
    return lst[i:]


def _last(lst):
    if not lst:
        _empty("List.last")
    return lst[-1]


def _rm(x):
    def inner(lst):
        if x in lst:
            i = lst.index(x)
            return lst[:i] + lst[i + 1:]
        return lst
    return inner


def _remdupl(lst):
    """CPN Tools' remdupl keeps the last occurrence of each element: remdupl [1,2,3,2] is [1,3,2]."""
    out = []
    for i, x in enumerate(lst):
        if x not in lst[i + 1:]:
            out.append(x)
    return tuple(out)


def _rmall(x):
    return lambda lst: tuple(y for y in lst if y != x)


def _contains_all(a):
    """CPN Tools' contains_all l1 l2: every element of l2 is in l1, as often as l2 has it."""
    def inner(b):
        rest = list(a)
        for x in b:
            if x not in rest:
                return False
            rest.remove(x)
        return True
    return inner


def _intersect(a):
    """CPN Tools' intersect l1 l2: the elements of l1 that l2 has, each matched once (a multiset's)."""
    def inner(b):
        rest, out = list(b), []
        for x in a:
            if x in rest:
                rest.remove(x)
                out.append(x)
        return tuple(out)
    return inner


def _listsub(a):
    """CPN Tools' listsub l1 l2: l1 without the elements of l2, each removed once; an element of l2 that l1
    has not raises Subtract."""
    def inner(b):
        rest = list(a)
        for x in b:
            if x not in rest:
                raise MLError("listsub: the second list has an element the first has not (exception Subtract)")
            rest.remove(x)
        return tuple(rest)
    return inner


def _app(f):
    def inner(lst):
        for x in lst:
            f(x)
        return ()
    return inner


def _ms_to_col(m):
    if isinstance(m, TimedMultiset):
        m = m.untimed()
    if len(m) != 1:
        raise MLError(f"ms_to_col of a multiset with {len(m)} elements (it needs exactly one)")
    return next(iter(m))


def _size(m):
    return len(m)


def _cf(arg):
    x, m = arg
    if isinstance(m, TimedMultiset):
        m = m.untimed()
    return m.count(x)


def _substring(arg):
    s, i, n = arg
    if i < 0 or n < 0 or i + n > len(s):
        raise MLError("String.substring outside the string (SML exception Subscript)")
    return s[i:i + n]


def _tokens(is_sep):
    """SML's String.tokens: the non-empty runs of characters between separators."""
    def split(s):
        out, cur = [], ""
        for c in s:
            if is_sep(c):
                if cur:
                    out.append(cur)
                cur = ""
            else:
                cur += c
        return tuple(out + [cur] if cur else out)
    return split


def _merge_sort(gt):
    """SML/NJ's ListMergeSort.sort: ascending by the greater-than `gt`, equal elements in their order."""
    import functools

    key = functools.cmp_to_key(lambda a, b: 1 if gt((a, b)) else (-1 if gt((b, a)) else 0))
    return lambda lst: tuple(sorted(lst, key=key))


def _lt_sort(lt):
    """CPN Tools' sort: ascending by the less-than `lt`, equal elements in their order."""
    import functools

    key = functools.cmp_to_key(lambda a, b: -1 if lt((a, b)) else (1 if lt((b, a)) else 0))
    return lambda lst: tuple(sorted(lst, key=key))


def _int_to_string(n):
    return f"~{-n}" if n < 0 else str(n)


def _floor(x):
    import math

    return math.floor(x)


def _round(x):
    import math

    f = math.floor(x)
    d = x - f
    if d > 0.5 or (d == 0.5 and f % 2 == 1):
        return f + 1
    return f


def _ceil(x):
    import math

    return math.ceil(x)


def _list_to_ms(lst):
    return Multiset(lst)


def _order_key(v):
    """A total order on the values of one colour set, for the lists CPN Tools' multisets are: numbers,
    strings, enumeration constants (by declaration) and union constructors (by tag) compare as CPN Tools
    orders them; products, records and lists compare component by component (records by field name)."""
    if isinstance(v, tuple):
        out: tuple = ()
        for x in v:
            out += _order_key(x)
        return out
    return (v,)


def _ms_to_list(m):
    """The elements of a multiset, each as often as it occurs, in the order of its colour set."""
    if isinstance(m, TimedMultiset):
        m = m.untimed()
    return tuple(x for x, n in sorted(m.items(), key=lambda it: _order_key(it[0])) for _ in range(n))


def _foldl(f):
    return lambda init: lambda lst: _fold(f, init, lst)


def _foldr(f):
    return lambda init: lambda lst: _fold(f, init, reversed(lst))


def _fold(f, acc, lst):
    for x in lst:
        acc = f((x, acc))
    return acc


def _tabulate(arg):
    n, f = arg
    if n < 0:
        raise MLError("List.tabulate with a negative size (SML exception Size)")
    return tuple(f(i) for i in range(n))



#: name -> implementation; `intTime` and `time` read the clock, which the engine supplies (TIME_BUILTINS)
FUNCTIONS: dict[str, Any] = {
    "not": lambda b: not b,
    "Bool.not": lambda b: not b,
    "length": len,
    "List.length": len,
    "rev": lambda lst: lst[::-1],
    "List.rev": lambda lst: lst[::-1],
    "hd": _hd,
    "List.hd": _hd,
    "tl": _tl,
    "List.tl": _tl,
    "null": lambda lst: not lst,
    "List.null": lambda lst: not lst,
    "List.nth": _nth,
    "List.take": _take,
    "List.drop": _drop,
    "List.last": _last,
    "List.concat": lambda ls: tuple(x for lst in ls for x in lst),
    "List.map": lambda f: lambda lst: tuple(f(x) for x in lst),
    "map": lambda f: lambda lst: tuple(f(x) for x in lst),
    "List.filter": lambda f: lambda lst: tuple(x for x in lst if f(x)),
    "List.exists": lambda f: lambda lst: any(f(x) for x in lst),
    "List.all": lambda f: lambda lst: all(f(x) for x in lst),
    "List.foldl": _foldl,
    "List.foldr": _foldr,
    "foldl": _foldl,
    "foldr": _foldr,
    "List.tabulate": _tabulate,
    "mem": lambda lst: lambda x: x in lst,
    "rm": _rm,
    "remdupl": _remdupl,
    "contains": lambda a: lambda b: all(x in a for x in b),
    "ins": lambda lst: lambda x: lst + (x,),
    "ins_new": lambda lst: lambda x: lst if x in lst else lst + (x,),
    "union": lambda a: lambda b: a + b,  # CPN Tools' union l1 l2 is l1 ^^ l2
    "intersect": _intersect,
    "rmall": _rmall,
    "contains_all": _contains_all,
    "listsub": _listsub,
    "app": _app,
    "List.app": _app,
    "filter": lambda f: lambda lst: tuple(x for x in lst if f(x)),
    "list_to_ms": _list_to_ms,
    "ms_to_list": _ms_to_list,
    "Int.toString": _int_to_string,
    "Int.max": lambda a: max(a),
    "Int.min": lambda a: min(a),
    "Int.abs": abs,
    "abs": abs,
    "Bool.toString": lambda b: "true" if b else "false",
    "String.size": len,
    "String.concat": lambda lst: "".join(lst),
    "String.substring": _substring,
    "substring": _substring,
    "String.isPrefix": lambda a: lambda b: b.startswith(a),
    "String.isSuffix": lambda a: lambda b: b.endswith(a),
    "String.isSubstring": lambda a: lambda b: a in b,
    "String.tokens": _tokens,
    "String.explode": tuple,
    "explode": tuple,
    "String.implode": lambda cs: "".join(cs),
    "implode": lambda cs: "".join(cs),
    "ListMergeSort.sort": _merge_sort,
    "sort": _lt_sort,
    "List.partition": lambda f: lambda lst: (tuple(x for x in lst if f(x)), tuple(x for x in lst if not f(x))),
    "real": float,
    "Real.fromInt": float,
    "floor": _floor,
    "ceil": _ceil,
    "round": _round,
    "trunc": int,
    "Real.floor": _floor,
    "Real.ceil": _ceil,
    "Real.round": _round,
    "Real.trunc": int,
    "Real.toString": lambda x: repr(x).replace("-", "~"),
    # SML's ListPair: the pairs of two lists, as far as the shorter goes
    "ListPair.map": lambda f: lambda ab: tuple(f((x, y)) for x, y in zip(*ab)),
    "ListPair.zip": lambda ab: tuple(zip(*ab)),
    "ListPair.unzip": lambda pairs: (tuple(x for x, _ in pairs), tuple(y for _, y in pairs)),
    "size": _size,
    "empty": Multiset(),
    "ms_to_col": _ms_to_col,
    "cf": _cf,
    "ignore": lambda x: (),
    "IntInf.toInt": lambda x: x,
    "IntInf.fromInt": lambda x: x,
    "intTime": None,
    "time": None,
    "ModelTime.fromInt": lambda x: x,
    # SML's Math (reals): where SML/NJ gives NaN or an infinity (Math.sqrt ~1.0, Math.ln 0.0), so do these
    "Math.pi": math.pi,
    "Math.e": math.e,
    "Math.sqrt": lambda x: math.sqrt(x) if x >= 0 else math.nan,
    "Math.sin": math.sin,
    "Math.cos": math.cos,
    "Math.tan": math.tan,
    "Math.atan": math.atan,
    "Math.atan2": lambda yx: math.atan2(*yx),
    "Math.exp": lambda x: math.exp(x) if x < 709.0 else math.inf,
    "Math.ln": lambda x: math.log(x) if x > 0 else (-math.inf if x == 0 else math.nan),
    "Math.log10": lambda x: math.log10(x) if x > 0 else (-math.inf if x == 0 else math.nan),
    "Math.pow": lambda xy: _pow(*xy),
    "ModelTime.time": None,
    # CPN Tools' model-time conversions at the top level (`toReal (fromInt n)`): the model time is an integer
    "fromInt": lambda x: x,
    "toReal": float,
    "ModelTime.toString": lambda t: _int_to_string(t) if isinstance(t, int) else f"{t:g}".replace("-", "~"),
}

def _pow(x: float, y: float) -> float:
    try:
        return math.pow(x, y)
    except (OverflowError, ValueError):
        return math.inf if x > 0 or float(y).is_integer() else math.nan


TIME_BUILTINS = frozenset({"intTime", "time", "ModelTime.time"})


def binop(op: str, a: Any, b: Any) -> Any:
    """The meaning of an infix operator on evaluated operands (shared with compiled code)."""
    if op == "+":
        return a + b
    if op == "-":
        return a - b
    if op == "*":
        return a * b
    if op == "div":
        if b == 0:
            raise MLError("division by zero (SML exception Div)")
        return a // b
    if op == "mod":
        if b == 0:
            raise MLError("division by zero (SML exception Div)")
        return a % b
    if op == "/":
        if b == 0:
            raise MLError("division by zero (SML exception Div)")
        return a / b
    if op == "^":
        return a + b
    if op == "::":
        return (a,) + b
    if op in ("^^", "@"):
        return a + b
    if op == "=":
        return a == b
    if op == "<>":
        return a != b
    if op == "<":
        return a < b
    if op == "<=":
        return a <= b
    if op == ">":
        return a > b
    if op == ">=":
        return a >= b
    if op == "`":
        if a < 0:
            raise MLError(f"negative coefficient {a} in {a}`...")
        return Multiset.of(b, a)
    if op in ("++", "+++"):
        if isinstance(a, TimedMultiset) or isinstance(b, TimedMultiset):
            return TimedMultiset.lift(a) + TimedMultiset.lift(b)
        return a + b
    if op == "--":
        if isinstance(a, TimedMultiset):
            a = a.untimed()
        if isinstance(b, TimedMultiset):
            b = b.untimed()
        try:
            return a - b
        except MultisetError as exc:
            raise MLError(str(exc)) from None
    if op in ("@+", "@++"):  # '@++': a real-valued delay (simulate only)
        if not isinstance(a, (Multiset, TimedMultiset)):
            a = Multiset.of(a)
        return TimedMultiset.lift(a, b)
    raise MLError(f"unknown operator {op}")


__all__ = ["FUNCTIONS", "MLError", "TIME_BUILTINS", "binop"]
