"""Colour-set declarations to run-time colour sets (`cpn.values.colours`) and their CPN ML types: bounds
and predicates are evaluated, constructors declared.

A mixin of `cpn.lang.typecheck.Checker`, which provides inference, evaluation and diagnostics.
Imports `cpn.lang.*`, `cpn.values` and layer 0.
"""

from __future__ import annotations

from cpn.lang import ast as A
from cpn.lang import types as T
from cpn.lang.builtins import MLError
from cpn.lang.symbols import ConInfo, Symbol
from cpn.values import colours as C


class ColourSetConstruction:
    """`colset` declarations (mixed into the Checker)."""

    def const_int(self, e: A.Expr | None, what: str) -> int | None:
        if e is None:
            return None
        t = self.infer_top(e)
        if t is None:
            return None
        if not self.unify(t, T.INT, e.span, f"{what} must be an integer"):
            return None
        try:
            return self.ev.eval(e, {})
        except (MLError, ArithmeticError, TypeError, IndexError, KeyError) as exc:
            self.error("E0401", f"evaluating {what} failed: {exc}", e.span)
            return None

    def colset_decl(self, d: A.ColsetDecl) -> None:
        b = d.body
        name = d.name
        if name in self.colsets and name in self.predefined:
            self.predefined.discard(name)
            del self.colsets[name]
        if name in self.colsets:
            self.error("E0202", f"colour set '{name}' is declared twice", d.span,
                       notes=[f"first declared at {self._where(self.cs_spans[name])}"],
                       hint="Rename one of them; colour-set names must be unique.", name=name)
            return
        timed = d.timed
        cs: C.ColourSet | None = None
        ty: T.Type | None = None
        k = b.kind
        if k == "datatype":
            if b.pred is not None or any(arg == name for _, arg in b.fields):
                at = b.pred.span if b.pred is not None else b.span
                self.error("E0206", f"datatype '{name}': a constructor's argument must be a colour set (no tuple, "
                           "list or the datatype itself)", at,
                           hint=f"Declare a colour set for the argument ('colset {name}Arg = product A * B;') and "
                                f"write 'Con of {name}Arg', or declare '{name}' as a union colour set.")
                return
            k = "union"
        if k == "unit":
            cs, ty = C.UnitCS(name, timed), T.UNIT
        elif k == "bool":
            cs, ty = C.BoolCS(name, timed, *b.names), T.BOOL
            for value, c in zip((False, True), b.names):  # `bool with (no, yes)`: no is false, yes is true
                self._declare_global(Symbol(c, "con", ty, b.span, ConInfo(name, value, "enum", False)))
        elif k in ("int",):
            lo, hi = self.const_int(b.low, "the lower bound"), self.const_int(b.high, "the upper bound")
            if b.low is not None and (lo is None or hi is None):
                return
            if lo is not None and hi < lo:
                self.error("E0304", f"colour set '{name}' has an empty range {lo}..{hi}", b.span,
                           hint="The lower bound must not exceed the upper bound.")
                return
            cs, ty = C.IntCS(name, lo, hi, timed), T.INT
        elif k == "time":
            cs, ty = C.IntCS(name, None, None, timed), T.INT
        elif k == "string":
            lmin, lmax = self.const_int(b.low, "the shortest length"), self.const_int(b.high, "the longest length")
            if b.low is not None and (lmin is None or lmax is None):
                return
            if any(len(c) != 1 for c in b.names) or (b.names and b.names[0] > b.names[1]) or \
                    (lmin is not None and not 0 <= lmin <= lmax):
                self.error("E0304", f"colour set '{name}' has an empty or malformed range", b.span,
                           hint='Write string with "a".."z" (two single characters, the first not after the '
                                "second) and optionally 'and 3..9' (lengths, the shortest first).")
                return
            cs, ty = C.StringCS(name, timed, tuple(b.names) or None, (lmin, lmax) if b.low is not None else None), \
                T.STRING
        elif k == "real":
            cs, ty = C.RealCS(name, timed), T.REAL
        elif k == "enum":
            if len(set(b.names)) != len(b.names):
                self.error("E0304", f"enumeration '{name}' lists a constant twice", b.span)
                return
            cs, ty = C.EnumCS(name, b.names, timed), T.TCon(name)
            for i, c in enumerate(b.names):
                self._declare_global(Symbol(c, "con", ty, b.span, ConInfo(name, i, "enum", False)))
        elif k == "index":
            lo, hi = self.const_int(b.low, "the lower bound"), self.const_int(b.high, "the upper bound")
            if lo is None or hi is None:
                return
            if hi < lo:
                self.error("E0304", f"index colour set '{name}' has an empty range {lo}..{hi}", b.span)
                return
            cs, ty = C.IndexCS(name, b.names[0], lo, hi, timed), T.TCon(name)
            self._declare_global(Symbol(b.names[0], "con", T.TFun(T.INT, ty), b.span,
                                        ConInfo(name, 0, "index", True)))
        elif k == "product":
            comps = [self.lookup_colset(n, b.span) for n in b.names]
            if None in comps:
                return
            cs = C.ProductCS(name, comps, timed)
            ty = T.TTuple([self.cstypes[n] for n in b.names])
        elif k == "record":
            labels = [f for f, _ in b.fields]
            if len(set(labels)) != len(labels):
                self.error("E0304", f"record '{name}' has a field twice", b.span)
                return
            comps = [(f, self.lookup_colset(n, b.span)) for f, n in b.fields]
            if any(c is None for _, c in comps):
                return
            cs = C.RecordCS(name, comps, timed)
            ty = T.TRecord([(f, self.cstypes[n]) for f, n in b.fields])
        elif k == "list":
            elem = self.lookup_colset(b.names[0], b.span)
            if elem is None:
                return
            lo, hi = self.const_int(b.low, "the lower bound"), self.const_int(b.high, "the upper bound")
            cs = C.ListCS(name, elem, lo, hi, timed)
            ty = T.lst(self.cstypes[b.names[0]])
        elif k == "union":
            ty = T.TCon(name)
            cons = []
            for i, (cname, csname) in enumerate(b.fields):
                arg = self.lookup_colset(csname, b.span) if csname else None
                if csname and arg is None:
                    return
                cons.append((cname, arg))
                cty = T.TFun(self.cstypes[csname], ty) if csname else ty
                self._declare_global(Symbol(cname, "con", cty, b.span, ConInfo(name, i, "union", bool(csname))))
            cs = C.UnionCS(name, cons, timed)
        elif k in ("subset_by", "subset_with"):
            base = self.lookup_colset(b.names[0], b.span)
            if base is None:
                return
            bty = self.cstypes[b.names[0]]
            t = self.infer_top(b.pred)
            if t is None:
                return
            if k == "subset_by":
                if not self.unify(t, T.TFun(bty, T.BOOL), b.pred.span, "the predicate of a subset colour set"):
                    return
                try:
                    pred = self.ev.eval(b.pred, {})
                except MLError as exc:
                    self.error("E0401", f"evaluating the predicate failed: {exc}", b.pred.span)
                    return
                cs = C.SubsetCS(name, base, predicate=pred, timed=timed)
            else:
                if not self.unify(t, T.lst(bty), b.pred.span, "the members of a subset colour set"):
                    return
                cs = C.SubsetCS(name, base, members=self.ev.eval(b.pred, {}), timed=timed)
            ty = bty
        elif k == "alias":
            base = self.lookup_colset(b.names[0], b.span)
            if base is None:
                return
            cs, ty = C.AliasCS(name, base, timed or base.timed), self.cstypes[b.names[0]]
        if cs is None:
            self.error("E0206", f"unsupported colour set kind '{k}'", b.span)
            return
        self.colsets[name] = cs
        self.cstypes[name] = ty
        self.cs_spans[name] = d.span
