"""The typed syntax tree of `cpn.lang` to the closed form a net holds (`cpn.expr.nodes`).

With `cpn.net.lower`, the only place where `cpn.net` reads `cpn.lang`: every name becomes a `Ref` (shared
per declared symbol), type annotations are dropped, record patterns keep the labels of their colour set, and
the inferred types are dropped but those of list literals and of constants' names (`closed_type`).
"""

from __future__ import annotations

from dataclasses import fields
from typing import Any

from cpn._util.deep import left_spine
from cpn.expr import nodes as E
from cpn.lang import ast as A
from cpn.lang import types as T
from cpn.lang.symbols import ConInfo, Symbol

# what the front end annotated and the net does without
_LEFT_BEHIND = frozenset({"ty", "op_ty", "ran_var", "type_expr", "result_type"})
#: per node class, the names of the fields a closed node keeps (`dataclasses.fields` is slow per call)
_KEPT_FIELDS: dict[type, tuple[str, ...]] = {}
#: the names whose type a closed node keeps, as `closed_type` gives it (besides list literals and calls of the
#: library): a constant's value alone does not say whether a tuple is a product or a list, nor `[]` of what
_TYPED_NAMES = frozenset({"val", "param"})


def _library_call(e) -> bool:
    """Whether application e calls a library function (`List.map f`, `List.map f l`): its type says what
    list it makes."""
    while isinstance(e, A.App):
        e = e.fn
    return isinstance(e, A.Name) and getattr(e.ref, "kind", None) == "builtin"


def closed_type(t) -> tuple:
    """The front end's type `t` as plain tuples, for the engines (`cpn.expr.nodes`, `ty` of a list literal and
    of a constant's name): `("int",)`, `("bool",)`, `("unit",)`, `("string",)`, `("real",)`, `(colour set,)`
    for an enumeration, index or union, `("list", t)`, `("ms", t)`, `("*", (t, ...))` for a product,
    `("{}", ((label, t), ...))` for a record (labels in order), `("->",)` for a function, `("'",)` for a
    type not fixed (a polymorphic function's)."""
    t = T.prune(t)
    if isinstance(t, T.TCon):
        return (t.name, *(closed_type(a) for a in t.args))
    if isinstance(t, T.TTuple):
        return ("*", tuple(closed_type(x) for x in t.items))
    if isinstance(t, T.TRecord):
        return ("{}", tuple((label, closed_type(x)) for label, x in t.fields))
    if isinstance(t, T.TFun):
        return ("->",)
    return ("'",)


class Translator:
    """Translates expressions, patterns and declarations; one per net, so that equal symbols share a Ref."""

    def __init__(self) -> None:
        self._refs: dict[int, tuple] = {}  # id of a symbol -> (symbol, Ref)
        self._done: dict[int, tuple] = {}  # id of a syntax node -> (node, translation): instances share it

    def ref(self, sym: Symbol) -> E.Ref:
        got = self._refs.get(id(sym))
        if got is not None and got[0] is sym:
            return got[1]
        data = sym.data
        if isinstance(data, ConInfo):
            data = E.Constructor(data.colset, data.tag, data.kind, data.has_arg)
        elif sym.kind not in ("var", "csop"):
            data = None  # the front end's own annotations (types, declarations) stay behind
        r = E.Ref(sym.name, sym.kind, sym.uid, data)
        self._refs[id(sym)] = (sym, r)
        return r

    # ------------------------------------------------------------------ expressions
    def expr(self, e: A.Expr | None) -> Any:
        if e is None:
            return None
        done = self._done.get(id(e))
        if done is not None and done[0] is e:
            return done[1]
        if isinstance(e, A.Annot):
            x = self.expr(e.expr)
        elif isinstance(e, A.BinOp):
            x = self._binop(e)
        else:
            x = self._copy(e)
        self._done[id(e)] = (e, x)  # the node is kept, so that its id is not reused
        return x

    def exprs(self, es: list[A.Expr]) -> list:
        return [self.expr(x) for x in es]

    def _binop(self, e):
        # the left spine in a loop (a chain of any length is one frame deep), sharing nodes done before
        first, spine = left_spine(e, A.BinOp, lambda n: n is not e and self._done.get(id(n), (None,))[0] is n)
        x = self.expr(first)
        for node in spine:
            x = E.BinOp(node.span, node.op, x, self.expr(node.right))
            self._done[id(node)] = (node, x)
        return x

    def _copy(self, node):
        """The node in closed form: its parts translated, its name resolved to a Ref, what the type checker
        annotated (`ty`, `op_ty`, `ran_var`) and the type annotations left behind. One rule for every
        node, so that a new expression form needs no line here."""
        cls = type(node)
        names = _KEPT_FIELDS.get(cls)
        if names is None:
            names = _KEPT_FIELDS[cls] = tuple(f.name for f in fields(cls) if f.name not in _LEFT_BEHIND)
        parts = {}
        for name in names:
            v = getattr(node, name)
            parts[name] = self.ref(v) if name == "ref" else self._part(v)
        if (cls is A.ListE or (cls is A.Name and getattr(node.ref, "kind", None) in _TYPED_NAMES)
                or (cls is A.App and _library_call(node))) and node.ty is not None:
            parts["ty"] = closed_type(node.ty)
        return cls(**parts)

    def _part(self, v):
        if isinstance(v, A.Expr):
            return self.expr(v)
        if isinstance(v, A.Pat):
            return self.pat(v)
        if isinstance(v, A.ValDecl | A.FunDecl | A.Clause):
            return self._copy(v)
        if isinstance(v, A.Decl):
            raise TypeError(f"unsupported declaration {type(v).__name__} inside let")
        if isinstance(v, list):
            return [self._part(x) for x in v]
        if isinstance(v, tuple):
            return tuple(self._part(x) for x in v)
        return v  # a constant, an operator, a label

    # ------------------------------------------------------------------ patterns
    def pat(self, p: A.Pat) -> E.Pat:
        return self.pat(p.pat) if isinstance(p, A.PAnnot) else self._copy(p)

    # ------------------------------------------------------------------ declarations
    def decl(self, d: A.Decl) -> E.ValDecl | E.FunDecl:
        return self._part(d)

    def fun(self, d: A.FunDecl) -> E.FunDecl:
        return self._copy(d)

    def globals(self, model: A.Model, values: dict[int, Any]) -> E.Globals:
        """The global constants and functions of a checked model; `values` maps the uid of each checked
        constant to its value (a function-valued one is evaluated again from its declaration)."""
        out = E.Globals()
        for d in A.flat_decls(model.decls):
            if isinstance(d, A.FunDecl) and isinstance(d.ref, Symbol):
                out.decls.append(self.fun(d))
            elif isinstance(d, A.ValDecl) and isinstance(d.pat, A.PVar) and d.pat.ref is not None \
                    and d.pat.ref.uid in values:
                out.decls.append(E.ValDecl(d.span, self.pat(d.pat), self.expr(d.expr)))
                v = values[d.pat.ref.uid]
                if not callable(v):
                    out.constants[d.pat.ref.uid] = v
        return out
