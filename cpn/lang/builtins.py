"""The CPN ML library subset: the names and their types (the implementations are
`cpn.values.builtins`, which the engines call at run time).

Every function value takes one argument (SML): tuples for several arguments, curried otherwise.
"""

from __future__ import annotations

from cpn.diagnostics import Span
from cpn.lang import types as T
from cpn.lang.symbols import ConInfo, Symbol
from cpn.values import draws, effects, sml_basis
from cpn.values.builtins import FUNCTIONS, TIME_BUILTINS, MLError
from cpn.values.multiset import MultisetError


def _tokens(text):
    import re

    return re.findall(r"''?[a-z]|->|\*|\(|\)|[A-Za-z][A-Za-z0-9.]*", text)


def parse_type(text: str | T.Scheme) -> T.Scheme:
    """The type scheme a library type text writes, read once per process: a scheme is only instantiated,
    never written into (its variables are replaced by fresh ones at each use), so every checker shares it."""
    if isinstance(text, T.Scheme):  # a type the notation cannot write (Date.date's record argument)
        return text
    got = _SCHEMES.get(text)
    if got is None:
        got = _SCHEMES[text] = _parse_type(text)
    return got


_SCHEMES: dict[str, T.Scheme] = {}


def _parse_type(text: str) -> T.Scheme:
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
        while peek() in ("list", "ms", "option", "ref"):
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


# name -> type; the implementations are `cpn.values.builtins.FUNCTIONS`
TYPES: dict[str, str] = {
    "not": "bool -> bool",
    "Bool.not": "bool -> bool",
    "length": "'a list -> int",
    "List.length": "'a list -> int",
    "rev": "'a list -> 'a list",
    "List.rev": "'a list -> 'a list",
    "hd": "'a list -> 'a",
    "List.hd": "'a list -> 'a",
    "tl": "'a list -> 'a list",
    "List.tl": "'a list -> 'a list",
    "null": "'a list -> bool",
    "List.null": "'a list -> bool",
    "List.nth": "'a list * int -> 'a",
    "List.take": "'a list * int -> 'a list",
    "List.drop": "'a list * int -> 'a list",
    "List.last": "'a list -> 'a",
    "List.concat": "'a list list -> 'a list",
    "List.map": "('a -> 'b) -> 'a list -> 'b list",
    "map": "('a -> 'b) -> 'a list -> 'b list",
    "List.filter": "('a -> bool) -> 'a list -> 'a list",
    "List.exists": "('a -> bool) -> 'a list -> bool",
    "List.all": "('a -> bool) -> 'a list -> bool",
    "List.foldl": "('a * 'b -> 'b) -> 'b -> 'a list -> 'b",
    "List.foldr": "('a * 'b -> 'b) -> 'b -> 'a list -> 'b",
    "foldl": "('a * 'b -> 'b) -> 'b -> 'a list -> 'b",
    "foldr": "('a * 'b -> 'b) -> 'b -> 'a list -> 'b",
    "List.tabulate": "int * (int -> 'a) -> 'a list",
    "mem": "''a list -> ''a -> bool",
    "rm": "''a -> ''a list -> ''a list",
    "remdupl": "''a list -> ''a list",
    "contains": "''a list -> ''a list -> bool",
    "ins": "'a list -> 'a -> 'a list",
    "ins_new": "''a list -> ''a -> ''a list",
    "union": "''a list -> ''a list -> ''a list",
    "intersect": "''a list -> ''a list -> ''a list",
    "rmall": "''a -> ''a list -> ''a list",
    "contains_all": "''a list -> ''a list -> bool",
    "listsub": "''a list -> ''a list -> ''a list",
    "app": "('a -> unit) -> 'a list -> unit",
    "List.app": "('a -> unit) -> 'a list -> unit",
    # CPN Tools' filter of a multiset (a list there): a multiset given to it is the list of its elements
    "filter": "('a -> bool) -> 'a list -> 'a list",
    "list_to_ms": "'a list -> 'a ms",
    "ms_to_list": "'a ms -> 'a list",
    "Int.toString": "int -> string",
    "Int.max": "int * int -> int",
    "Int.min": "int * int -> int",
    "Int.abs": "int -> int",
    "abs": "int -> int",
    "Bool.toString": "bool -> string",
    "String.size": "string -> int",
    "String.concat": "string list -> string",
    "String.substring": "string * int * int -> string",
    "substring": "string * int * int -> string",
    "String.isPrefix": "string -> string -> bool",
    "String.isSuffix": "string -> string -> bool",
    "String.isSubstring": "string -> string -> bool",
    # characters (#"a") are strings of one character here
    "String.tokens": "(string -> bool) -> string -> string list",
    "String.explode": "string -> string list",
    "explode": "string -> string list",
    "String.implode": "string list -> string",
    "implode": "string list -> string",
    "List.partition": "('a -> bool) -> 'a list -> 'a list * 'a list",
    "ListMergeSort.sort": "('a * 'a -> bool) -> 'a list -> 'a list",
    "sort": "('a * 'a -> bool) -> 'a list -> 'a list",
    "real": "int -> real",
    "Real.fromInt": "int -> real",
    "floor": "real -> int",
    "ceil": "real -> int",
    "round": "real -> int",
    "trunc": "real -> int",
    **{f"Real.{f}": "real -> int" for f in ("floor", "ceil", "round", "trunc")},
    "Real.toString": "real -> string",
    "ListPair.map": "('a * 'b -> 'c) -> 'a list * 'b list -> 'c list",
    "ListPair.zip": "'a list * 'b list -> ('a * 'b) list",
    "ListPair.unzip": "('a * 'b) list -> 'a list * 'b list",
    "size": "'a ms -> int",
    "empty": "'a ms",
    "ms_to_col": "'a ms -> 'a",
    "cf": "''a * ''a ms -> int",
    "ignore": "'a -> unit",
    "IntInf.toInt": "int -> int",
    "IntInf.fromInt": "int -> int",
    "intTime": "unit -> int",
    "time": "unit -> int",
    # CPN Tools' ModelTime: the model time, an integer here (a real where '@++' makes it one in simulate)
    "ModelTime.fromInt": "int -> int",
    **{f"Math.{f}": "real -> real" for f in ("sqrt", "sin", "cos", "tan", "atan", "exp", "ln", "log10")},
    "Math.pi": "real",
    "Math.e": "real",
    "Math.atan2": "real * real -> real",
    "Math.pow": "real * real -> real",
    "ModelTime.time": "unit -> int",
    "fromInt": "int -> int",
    "toReal": "int -> real",
}
# ModelTime.toString of an integer model time, or of a real one (CPN Tools' option realtimestamp, '@++')
_MT = T.TVar(overload=("int", "real"))
TYPES["ModelTime.toString"] = T.Scheme([_MT], T.TFun(_MT, T.TCon("string")))

# the SML Basis Library's option, order and Date, which CPN Tools models compute with (cpn.values.sml_basis)
_DATE, _MONTH = T.TCon("Date.date"), T.TCon("Date.month")
TYPES.update({
    "Option.getOpt": "'a option * 'a -> 'a",
    "getOpt": "'a option * 'a -> 'a",
    "Option.valOf": "'a option -> 'a",
    "valOf": "'a option -> 'a",
    "Option.isSome": "'a option -> bool",
    "isSome": "'a option -> bool",
    "Int.fromString": "string -> int option",
    "Real.fromString": "string -> real option",
    "IntInf.toLarge": "int -> int",
    "IntInf.fromLarge": "int -> int",
    "Int.compare": "int * int -> order",
    "String.compare": "string * string -> order",
    "Date.date": T.Scheme([], T.TFun(T.TRecord([
        ("day", T.INT), ("hour", T.INT), ("minute", T.INT), ("month", _MONTH),
        ("offset", T.TCon("option", (T.TCon("Time.time"),))), ("second", T.INT), ("year", T.INT)]), _DATE)),
    **{f"Date.{f}": "Date.date -> int" for f in ("year", "day", "hour", "minute", "second")},
    "Date.month": "Date.date -> Date.month",
    "Date.weekDay": "Date.date -> Date.weekday",
    "Date.offset": "Date.date -> Time.time option",
    "Date.compare": "Date.date * Date.date -> order",
    "Date.fmt": "string -> Date.date -> string",
    "Date.toString": "Date.date -> string",
    "OS.Path.concat": "string * string -> string",
})
FUNCTIONS.update(sml_basis.FUNCTIONS)
# the library's own types, which an annotation may name (`: Date.month`)
LIBRARY_TYPES: frozenset[str] = frozenset({"Date.date", "Date.month", "Date.weekday", "Time.time",
                                           "TextIO.instream", "TextIO.outstream"})
# the types whose constructors the library declares; a model may declare constructors of the same names
LIBRARY_CONSTRUCTOR_TYPES: frozenset[str] = frozenset({"exn"} | {t for t, _, _ in sml_basis.CONSTRUCTORS.values()})


def library_constructors() -> list[Symbol]:
    """`NONE`, `SOME`, `LESS`, `EQUAL`, `GREATER` and the months `Date.Jan` .. `Date.Dec`, as symbols."""
    out = []
    for name, (tname, tag, has_arg) in sml_basis.CONSTRUCTORS.items():
        if tname == "option":
            a = T.TVar()
            ty = T.Scheme([a], T.TFun(a, T.TCon("option", (a,))) if has_arg else T.TCon("option", (a,)))
        else:
            ty = T.TCon(tname)
        sym = Symbol(name, "con", ty, Span("<standard declarations>", 0, 0))
        kind = "enum" if tname in ("Date.month", "Date.weekday") else "union"
        sym.data = ConInfo(tname, tag, kind, has_arg)
        out.append(sym)
    return out


# CPN Tools' random distribution functions: simulation only (a net that calls them has no state space)
RANDOM_BUILTINS: frozenset[str] = frozenset(draws.DISTRIBUTIONS)
# the draws over a finite set of values, explored as a choice of every value where that is exact
FINITE_DRAWS: frozenset[str] = frozenset({"discrete", "bernoulli"})
TYPES.update({name: ty for name, (ty, _) in draws.DISTRIBUTIONS.items()})
# the engines find every library function in one table; the draws are defined beside the generator they use
FUNCTIONS.update(draws.FUNCTIONS)

# the machine's clock and text output (cpn.values.effects); those with no state-space meaning are
# simulation only, with what they do and what to change
TYPES.update({name: ty for name, (ty, _) in effects.BUILTINS.items()})
FUNCTIONS.update(effects.FUNCTIONS)
SIMULATION_ONLY_BUILTINS: dict[str, tuple[str, str]] = dict(effects.SIMULATION_ONLY)
STOPS_SIMULATE: frozenset[str] = effects.STOPS_SIMULATE  # simulate stops where they are called

# name -> (type, implementation)
BUILTINS: dict[str, tuple[str, object]] = {name: (ty, FUNCTIONS[name]) for name, ty in TYPES.items()}

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
    "lt": "cs * cs -> bool",
    # `declare input_ms, output, ...`: a value or a multiset read from or written to a file, as CPN Tools
    # writes them; simulate reads no file (it stops there) and writes nothing
    "input_ms": "TextIO.instream -> cs ms",
    "output": "TextIO.outstream * cs -> unit",
    "output_col": "TextIO.outstream * cs -> unit",
    "output_ms": "TextIO.outstream * cs ms -> unit",
}



def record_setter(cs, op: str) -> str | None:
    """The field that `CS.set_<field>` sets, where `cs` is a record colour set with that field (CPN Tools
    declares `set_<field> : cs -> field -> cs` for every record colour set): else None."""
    if op.startswith("set_") and getattr(cs, "kind", None) == "record" and op[4:] in cs.labels:
        return op[4:]
    return None


__all__ = ["BUILTINS", "COLSET_OPS", "MLError", "MultisetError", "RANDOM_BUILTINS", "SIMULATION_ONLY_BUILTINS", "STOPS_SIMULATE",
           "parse_type", "record_setter", "TIME_BUILTINS"]
