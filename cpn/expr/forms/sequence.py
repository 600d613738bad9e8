"""`(e1; e2; ...; en)`: the expressions evaluated in order, the value of the last."""

from __future__ import annotations

from cpn.expr.form import Form, register
from cpn.expr.nodes import Seq


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
