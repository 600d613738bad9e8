"""CPN ML types for inference: constructors, tuples, records, functions, and unification variables.

Colour sets map onto these structurally, as in CPN ML: `int with 1..5` is `int`, a product is a tuple,
enumerations, indexes and unions are nominal datatypes named after their colour set.
"""

from __future__ import annotations

import itertools


class Type:
    __slots__ = ()


class TVar(Type):
    __slots__ = ("id", "inst", "eq", "overload", "append")
    _ids = itertools.count()

    def __init__(self, eq: bool = False, overload: tuple[str, ...] | None = None):
        self.id = next(TVar._ids)
        self.inst: Type | None = None
        self.eq = eq  # an equality type variable (''a)
        self.overload = overload  # e.g. ('int', 'real') for +, defaulting to the first
        # `l1 ++ l2` of two lists of type `append`: `append` itself where a list is expected (CPN Tools'
        # multisets are lists, `++` appends them), else `append ms` (the default, decided by the checker)
        self.append: Type | None = None


class TCon(Type):
    __slots__ = ("name", "args")

    def __init__(self, name: str, args: tuple[Type, ...] = ()):
        self.name = name
        self.args = tuple(args)


class TTuple(Type):
    __slots__ = ("items",)

    def __init__(self, items):
        self.items = tuple(items)


class TRecord(Type):
    __slots__ = ("fields",)

    def __init__(self, fields):
        self.fields = tuple(sorted(fields, key=lambda f: f[0]))  # ((label, type), ...)

    def labels(self):
        return [f[0] for f in self.fields]


class TFun(Type):
    __slots__ = ("arg", "res")

    def __init__(self, arg: Type, res: Type):
        self.arg = arg
        self.res = res


INT = TCon("int")
BOOL = TCon("bool")
STRING = TCon("string")
EXN = TCon("exn")  # exceptions (`exception E`, `raise`, `handle`)
UNIT = TCon("unit")
REAL = TCon("real")


def ms(t: Type) -> TCon:
    return TCon("ms", (t,))


def lst(t: Type) -> TCon:
    return TCon("list", (t,))


def prune(t: Type) -> Type:
    while isinstance(t, TVar) and t.inst is not None:
        t = t.inst
    return t


class UnifyError(Exception):
    pass


def _occurs(v: TVar, t: Type) -> bool:
    t = prune(t)
    if t is v:
        return True
    if isinstance(t, TCon):
        return any(_occurs(v, a) for a in t.args)
    if isinstance(t, TTuple):
        return any(_occurs(v, a) for a in t.items)
    if isinstance(t, TRecord):
        return any(_occurs(v, a) for _, a in t.fields)
    if isinstance(t, TFun):
        return _occurs(v, t.arg) or _occurs(v, t.res)
    return False


def _admits_eq(t: Type) -> bool:
    t = prune(t)
    if isinstance(t, TFun):
        return False
    if isinstance(t, TCon):  # reals too: CPN Tools defines '=' and '<>' on every colour set
        return all(_admits_eq(a) for a in t.args)
    if isinstance(t, TTuple):
        return all(_admits_eq(a) for a in t.items)
    if isinstance(t, TRecord):
        return all(_admits_eq(a) for _, a in t.fields)
    return True


def _bind(v: TVar, t: Type) -> None:
    if _occurs(v, t):
        raise UnifyError("a value cannot contain itself (recursive type)")
    t = prune(t)
    if v.append is not None:
        if isinstance(t, TVar):
            if t.append is None:
                _bind(t, v)  # the plain variable takes the reading of '++' still to be decided
                return
            unify(t.append, v.append)
        elif isinstance(t, TCon) and t.name == "list":
            unify(t, v.append)
        elif isinstance(t, TCon) and t.name == "ms":
            unify(t, TCon("ms", (v.append,)))
        else:
            raise UnifyError("")
    if v.overload is not None:
        if isinstance(t, TVar):
            if t.overload is None:
                t.overload = v.overload
            else:
                common = tuple(x for x in t.overload if x in v.overload)
                if not common:
                    raise UnifyError("no common type")
                t.overload = common
        elif not (isinstance(t, TCon) and t.name in v.overload and not t.args):
            raise UnifyError(f"expected {' or '.join(v.overload)}")
    if v.eq:
        if isinstance(t, TVar):
            t.eq = True
        elif not _admits_eq(t):
            raise UnifyError("equality is not defined on this type")
    v.inst = t


def unify(a: Type, b: Type) -> None:
    a, b = prune(a), prune(b)
    if a is b:
        return
    if isinstance(a, TVar):
        _bind(a, b)
        return
    if isinstance(b, TVar):
        _bind(b, a)
        return
    if isinstance(a, TCon) and isinstance(b, TCon):
        if a.name != b.name or len(a.args) != len(b.args):
            raise UnifyError("")
        for x, y in zip(a.args, b.args):
            unify(x, y)
        return
    if isinstance(a, TTuple) and isinstance(b, TTuple):
        if len(a.items) != len(b.items):
            raise UnifyError("tuples of different lengths")
        for x, y in zip(a.items, b.items):
            unify(x, y)
        return
    if isinstance(a, TRecord) and isinstance(b, TRecord):
        if a.labels() != b.labels():
            raise UnifyError("records with different fields")
        for (_, x), (_, y) in zip(a.fields, b.fields):
            unify(x, y)
        return
    if isinstance(a, TFun) and isinstance(b, TFun):
        unify(a.arg, b.arg)
        unify(a.res, b.res)
        return
    raise UnifyError("")


def default_overloads(t: Type) -> None:
    """Resolve still-open overloaded variables to their default (int for arithmetic)."""
    t = prune(t)
    if isinstance(t, TVar):
        if t.overload:
            t.inst = TCon(t.overload[0])
        return
    for sub in _children(t):
        default_overloads(sub)


def _children(t: Type):
    if isinstance(t, TCon):
        return t.args
    if isinstance(t, TTuple):
        return t.items
    if isinstance(t, TRecord):
        return [x for _, x in t.fields]
    if isinstance(t, TFun):
        return (t.arg, t.res)
    return ()


def free_vars(t: Type, acc: set | None = None) -> set:
    acc = set() if acc is None else acc
    t = prune(t)
    if isinstance(t, TVar):
        acc.add(t)
    else:
        for sub in _children(t):
            free_vars(sub, acc)
    return acc


class Scheme:
    """A type generalised over some variables (let-polymorphism)."""

    __slots__ = ("vars", "type")

    def __init__(self, vars_, type_):
        self.vars = tuple(vars_)
        self.type = type_

    def instantiate(self) -> Type:
        if not self.vars:
            return self.type
        mapping = {v: TVar(eq=v.eq, overload=v.overload) for v in self.vars}
        return _subst(self.type, mapping)


def _subst(t: Type, mapping) -> Type:
    t = prune(t)
    if isinstance(t, TVar):
        return mapping.get(t, t)
    if isinstance(t, TCon):
        return TCon(t.name, tuple(_subst(a, mapping) for a in t.args)) if t.args else t
    if isinstance(t, TTuple):
        return TTuple([_subst(a, mapping) for a in t.items])
    if isinstance(t, TRecord):
        return TRecord([(label, _subst(a, mapping)) for label, a in t.fields])
    if isinstance(t, TFun):
        return TFun(_subst(t.arg, mapping), _subst(t.res, mapping))
    return t


def show(t: Type, names: dict | None = None) -> str:
    """CPN ML notation of a type: `int * string list`, `PH ms`."""
    names = {} if names is None else names
    t = prune(t)
    if isinstance(t, TVar):
        if t.overload:
            return t.overload[0]
        if t.append is not None:
            return show(TCon("ms", (t.append,)), names)
        if t not in names:
            names[t] = ("''" if t.eq else "'") + "abcdefghijklmnopqrstuvwxyz"[len(names) % 26]
        return names[t]
    if isinstance(t, TCon):
        if not t.args:
            return t.name
        inner = show(t.args[0], names)
        if isinstance(prune(t.args[0]), (TTuple, TFun)):
            inner = f"({inner})"
        return f"{inner} {t.name}"
    if isinstance(t, TTuple):
        if not t.items:
            return "unit"
        return " * ".join(
            f"({show(x, names)})" if isinstance(prune(x), (TTuple, TFun)) else show(x, names) for x in t.items
        )
    if isinstance(t, TRecord):
        return "{" + ", ".join(f"{label}: {show(x, names)}" for label, x in t.fields) + "}"
    if isinstance(t, TFun):
        a = show(t.arg, names)
        if isinstance(prune(t.arg), TFun):
            a = f"({a})"
        return f"{a} -> {show(t.res, names)}"
    return "?"
