"""`(e1; e2; ...; en)`: the expressions evaluated in order, the value of the last; and SML's `e1 before e2`:
both evaluated in order, the value of the first (`loop ins before TextIO.closeIn ins`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from cpn.expr.form import Form, register
from cpn.expr.nodes import Expr, Seq


@dataclass(slots=True, eq=False)
class Before(Expr):
    """`first before then`: `then` (of type unit) is evaluated after `first`, whose value it is."""

    first: Expr
    then: Expr
    ty: Any = None


@register
class SeqForm(Form, node=Seq, rule="seq", parts=("items",)):
    def parse(self, span, items):
        return Seq(span, list(items))

    def infer(self, tc, e, env):
        t = None
        for x in e.items:
            t = tc.infer(x, env)
        return t

    def evaluate(self, ev, e, env):
        v = None
        for x in e.items:
            v = ev.eval(x, env)
        return v

    def show(self, e, pp):
        return "(" + "; ".join(pp.expr(x) for x in e.items) + ")"


@register
class BeforeForm(Form, node=Before, rule="before", parts=("first", "then")):

    def infer(self, tc, e, env):
        t = tc.infer(e.first, env)
        tc.must(tc.infer(e.then, env), tc.types.UNIT, e.then.span, "the right operand of 'before' (unit)")
        return t

    def evaluate(self, ev, e, env):
        v = ev.eval(e.first, env)
        ev.eval(e.then, env)
        return v

    def show(self, e, pp):
        return f"({pp.expr(e.first)} before {pp.expr(e.then)})"
