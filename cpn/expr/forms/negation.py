"""`~ e`: the negation of an int or a real (`~3` is the constant -3 already in the parser)."""

from __future__ import annotations

from cpn.expr.form import Form, register
from cpn.expr.nodes import Const, Neg


@register
class NegForm(Form, node=Neg, rule="neg", parts=("operand",)):
    def parse(self, span, items):
        x = items[0]
        if isinstance(x, Const) and x.kind in ("int", "real"):
            return Const(span, -x.value, x.kind)
        return Neg(span, x)

    def infer(self, tc, e, env):
        t = tc.infer(e.operand, env)
        tc.must(t, tc.types.TVar(overload=("int", "real")), e.span, "'~'")
        return t

    def evaluate(self, ev, e, env):
        return -ev.eval(e.operand, env)

    def compile(self, ec, e):
        return f"(-{ec.expr(e.operand)})"

    def show(self, e, pp):
        return f"(~ {pp.atom(e.operand)})"
