"""The typed syntax tree of `cpn.lang` to the closed form a net holds (`cpn.expr.nodes`).

With `cpn.net.lower`, the only place where `cpn.net` reads `cpn.lang`: every name becomes a `Ref` (shared
per declared symbol), type annotations are dropped, record patterns keep the labels of their colour set.
"""

from __future__ import annotations

from typing import Any

from cpn._util.deep import left_spine
from cpn.expr import nodes as E
from cpn.lang import ast as A
from cpn.lang.symbols import ConInfo, Symbol


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
        x = getattr(self, "_x_" + type(e).__name__)(e)
        self._done[id(e)] = (e, x)  # the node is kept, so that its id is not reused
        return x

    def exprs(self, es: list[A.Expr]) -> list:
        return [self.expr(x) for x in es]

    def _x_Const(self, e):
        return E.Const(e.span, e.value, e.kind)

    def _x_Name(self, e):
        return E.Name(e.span, e.name, ref=self.ref(e.ref))

    def _x_Select(self, e):
        return E.Select(e.span, e.label, index=e.index)

    def _x_TupleE(self, e):
        return E.TupleE(e.span, self.exprs(e.items))

    def _x_RecordE(self, e):
        return E.RecordE(e.span, [(label, self.expr(x)) for label, x in e.fields])

    def _x_ListE(self, e):
        return E.ListE(e.span, self.exprs(e.items))

    def _x_App(self, e):
        return E.App(e.span, self.expr(e.fn), self.expr(e.arg))

    def _x_BinOp(self, e):
        # the left spine in a loop (a chain of any length is one frame deep), sharing nodes done before
        first, spine = left_spine(e, A.BinOp, lambda n: n is not e and self._done.get(id(n), (None,))[0] is n)
        x = self.expr(first)
        for node in spine:
            x = E.BinOp(node.span, node.op, x, self.expr(node.right))
            self._done[id(node)] = (node, x)
        return x

    def _x_Neg(self, e):
        return E.Neg(e.span, self.expr(e.operand))

    def _x_If(self, e):
        return E.If(e.span, self.expr(e.cond), self.expr(e.then), self.expr(e.else_))

    def _x_Case(self, e):
        return E.Case(e.span, self.expr(e.subject), [(self.pat(p), self.expr(b)) for p, b in e.rules])

    def _x_Fn(self, e):
        return E.Fn(e.span, [(self.pat(p), self.expr(b)) for p, b in e.rules])

    def _x_Raise(self, e):
        return E.Raise(e.span, self.expr(e.expr))

    def _x_Handle(self, e):
        return E.Handle(e.span, self.expr(e.expr), [(self.pat(p), self.expr(b)) for p, b in e.rules])

    def _x_Let(self, e):
        return E.Let(e.span, [self.decl(d) for d in e.decls], self.expr(e.body))

    def _x_Seq(self, e):
        return E.Seq(e.span, self.exprs(e.items))

    def _x_Annot(self, e):
        return self.expr(e.expr)

    def _x_ToMs(self, e):
        return E.ToMs(e.span, self.expr(e.expr))

    def _x_OpFun(self, e):
        return E.OpFun(e.span, e.op)

    # ------------------------------------------------------------------ patterns
    def pat(self, p: A.Pat) -> E.Pat:
        if isinstance(p, A.PWild):
            return E.PWild(p.span)
        if isinstance(p, A.PVar):
            return E.PVar(p.span, p.name, ref=self.ref(p.ref))
        if isinstance(p, A.PConst):
            return E.PConst(p.span, p.value, p.kind)
        if isinstance(p, A.PTuple):
            return E.PTuple(p.span, [self.pat(x) for x in p.items])
        if isinstance(p, A.PList):
            return E.PList(p.span, [self.pat(x) for x in p.items])
        if isinstance(p, A.PCons):
            return E.PCons(p.span, self.pat(p.head), self.pat(p.tail))
        if isinstance(p, A.PCon):
            return E.PCon(p.span, p.name, self.pat(p.arg), ref=self.ref(p.ref))
        if isinstance(p, A.PRecord):
            return E.PRecord(p.span, [(label, self.pat(q)) for label, q in p.fields], p.flexible,
                             ty_labels=list(p.ty_labels))
        if isinstance(p, A.PAs):
            return E.PAs(p.span, p.name, self.pat(p.pat), ref=self.ref(p.ref))
        if isinstance(p, A.PAnnot):
            return self.pat(p.pat)
        raise TypeError(f"unknown pattern {type(p).__name__}")

    # ------------------------------------------------------------------ declarations
    def decl(self, d: A.Decl) -> E.ValDecl | E.FunDecl:
        if isinstance(d, A.ValDecl):
            return E.ValDecl(d.span, self.pat(d.pat), self.expr(d.expr))
        if isinstance(d, A.FunDecl):
            return self.fun(d)
        raise TypeError(f"unsupported declaration {type(d).__name__} inside let")

    def fun(self, d: A.FunDecl) -> E.FunDecl:
        clauses = [E.Clause(c.span, [self.pat(p) for p in c.params], self.expr(c.body)) for c in d.clauses]
        return E.FunDecl(d.span, d.name, clauses, ref=self.ref(d.ref))

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
