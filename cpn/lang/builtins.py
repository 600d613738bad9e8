"""The CPN ML library subset: names, types and Python implementations on our value representation.

Every function value takes one argument (SML): tuples for several arguments, curried otherwise.
"""

from __future__ import annotations

from cpn.lang import types as T
from cpn.values.multiset import Multiset, MultisetError, TimedMultiset


class MLError(Exception):
    """A run-time error of CPN ML code (an SML exception such as Empty, Subscript, Div, Match)."""


def _tokens(text):
    import re

    return re.findall(r"''?[a-z]|->|\*|\(|\)|[A-Za-z]+", text)


def parse_type(text: str) -> T.Type:
    toks = _tokens(text)
    tvars: dict[str, T.TVar] = {}
    pos = 0

    def peek():
        return toks[pos] if pos < len(toks) else None

    def take():
        nonlocal pos
        pos += 1
        return toks[pos - 1]

    def arrow():
        left = product()
        if peek() == "->":
            take()
            return T.TFun(left, arrow())
        return left

    def product():
        items = [postfix()]
        while peek() == "*":
            take()
            items.append(postfix())
        return items[0] if len(items) == 1 else T.TTuple(items)

    def postfix():
        t = atom()
        while peek() in ("list", "ms"):
            t = T.TCon(take(), (t,))
        return t

    def atom():
        tok = take()
        if tok == "(":
            t = arrow()
            take()
            return t
        if tok.startswith("'"):
            if tok not in tvars:
                tvars[tok] = T.TVar(eq=tok.startswith("''"))
            return tvars[tok]
        return T.TCon(tok)

    t = arrow()
    return T.Scheme(list(tvars.values()), t)


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
    out = []
    for x in lst:
        if x not in out:
            out.append(x)
    return tuple(out)


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


# name -> (type, implementation)
BUILTINS: dict[str, tuple[str, object]] = {
    "not": ("bool -> bool", lambda b: not b),
    "Bool.not": ("bool -> bool", lambda b: not b),
    "length": ("'a list -> int", len),
    "List.length": ("'a list -> int", len),
    "rev": ("'a list -> 'a list", lambda lst: lst[::-1]),
    "List.rev": ("'a list -> 'a list", lambda lst: lst[::-1]),
    "hd": ("'a list -> 'a", _hd),
    "List.hd": ("'a list -> 'a", _hd),
    "tl": ("'a list -> 'a list", _tl),
    "List.tl": ("'a list -> 'a list", _tl),
    "null": ("'a list -> bool", lambda lst: not lst),
    "List.null": ("'a list -> bool", lambda lst: not lst),
    "List.nth": ("'a list * int -> 'a", _nth),
    "List.take": ("'a list * int -> 'a list", _take),
    "List.drop": ("'a list * int -> 'a list", _drop),
    "List.last": ("'a list -> 'a", _last),
    "List.concat": ("'a list list -> 'a list", lambda ls: tuple(x for lst in ls for x in lst)),
    "List.map": ("('a -> 'b) -> 'a list -> 'b list", lambda f: lambda lst: tuple(f(x) for x in lst)),
    "map": ("('a -> 'b) -> 'a list -> 'b list", lambda f: lambda lst: tuple(f(x) for x in lst)),
    "List.filter": ("('a -> bool) -> 'a list -> 'a list", lambda f: lambda lst: tuple(x for x in lst if f(x))),
    "List.exists": ("('a -> bool) -> 'a list -> bool", lambda f: lambda lst: any(f(x) for x in lst)),
    "List.all": ("('a -> bool) -> 'a list -> bool", lambda f: lambda lst: all(f(x) for x in lst)),
    "List.foldl": ("('a * 'b -> 'b) -> 'b -> 'a list -> 'b", _foldl),
    "List.foldr": ("('a * 'b -> 'b) -> 'b -> 'a list -> 'b", _foldr),
    "foldl": ("('a * 'b -> 'b) -> 'b -> 'a list -> 'b", _foldl),
    "foldr": ("('a * 'b -> 'b) -> 'b -> 'a list -> 'b", _foldr),
    "List.tabulate": ("int * (int -> 'a) -> 'a list", _tabulate),
    "mem": ("''a list -> ''a -> bool", lambda lst: lambda x: x in lst),
    "rm": ("''a -> ''a list -> ''a list", _rm),
    "remdupl": ("''a list -> ''a list", _remdupl),
    "contains": ("''a list -> ''a list -> bool", lambda a: lambda b: all(x in a for x in b)),
    "ins": ("'a list -> 'a -> 'a list", lambda lst: lambda x: lst + (x,)),
    "ins_new": ("''a list -> ''a -> ''a list", lambda lst: lambda x: lst if x in lst else lst + (x,)),
    "union": ("''a list -> ''a list -> ''a list", lambda a: lambda b: a + tuple(x for x in b if x not in a)),
    "intersect": ("''a list -> ''a list -> ''a list", lambda a: lambda b: tuple(x for x in a if x in b)),
    "list_to_ms": ("'a list -> 'a ms", _list_to_ms),
    "Int.toString": ("int -> string", _int_to_string),
    "Int.max": ("int * int -> int", lambda a: max(a)),
    "Int.min": ("int * int -> int", lambda a: min(a)),
    "Int.abs": ("int -> int", abs),
    "abs": ("int -> int", abs),
    "Bool.toString": ("bool -> string", lambda b: "true" if b else "false"),
    "String.size": ("string -> int", len),
    "String.concat": ("string list -> string", lambda lst: "".join(lst)),
    "String.substring": ("string * int * int -> string", _substring),
    "real": ("int -> real", float),
    "Real.fromInt": ("int -> real", float),
    "floor": ("real -> int", _floor),
    "ceil": ("real -> int", _ceil),
    "round": ("real -> int", _round),
    "trunc": ("real -> int", int),
    "Real.toString": ("real -> string", lambda x: repr(x).replace("-", "~")),
    "size": ("'a ms -> int", _size),
    "empty": ("'a ms", Multiset()),
    "ms_to_col": ("'a ms -> 'a", _ms_to_col),
    "cf": ("''a * ''a ms -> int", _cf),
    "ignore": ("'a -> unit", lambda x: ()),
    "IntInf.toInt": ("int -> int", lambda x: x),
    "IntInf.fromInt": ("int -> int", lambda x: x),
    "intTime": ("unit -> int", None),  # needs the clock: the evaluator supplies it
    "time": ("unit -> int", None),
}

TIME_BUILTINS = frozenset({"intTime", "time"})

# colour set operations CS.all(), CS.size() ...: op -> type with 'cs' standing for the colour set's type
COLSET_OPS: dict[str, str] = {
    "all": "unit -> cs ms",
    "size": "unit -> int",
    "ran": "unit -> cs",
    "ord": "cs -> int",
    "col": "int -> cs",
    "legal": "cs -> bool",
    "mkstr": "cs -> string",
    "mult": "cs1 ms * cs2 ms -> cs ms",
}

__all__ = ["BUILTINS", "COLSET_OPS", "MLError", "MultisetError", "parse_type", "TIME_BUILTINS"]
