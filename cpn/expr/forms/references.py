"""`!e` and `e1 := e2`: reading and assigning SML's reference variables (docs/semantics.md).

A reference is a `cpn.values.effects.Cell`, made by the library function `ref` (CPN Tools' `globref x = e`
is `val x = ref e`). Its value is no part of the marking, so a net that makes one is simulated only: the
type checker marks each `ref` as simulation only, as it does the clock and text output. The compiled engine
leaves both forms to the evaluator; the C generator leaves the transition to Python.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from cpn.expr.form import Form, register
from cpn.expr.nodes import Expr


@dataclass(slots=True, eq=False)
class Deref(Expr):
    """`!e`: the value of reference e."""

    expr: Expr
    ty: Any = None


@dataclass(slots=True, eq=False)
class Assign(Expr):
    """`target := value`: the reference `target` holds `value` from now on; the expression is `()`."""

    target: Expr
    value: Expr
    ty: Any = None


def _ref_type(tc, inner):
    return tc.types.TCon("ref", (inner,))


@register
class DerefForm(Form, node=Deref, rule="deref", parts=("expr",)):

    def infer(self, tc, e, env):
        inner = tc.types.TVar()
        tc.must(tc.infer(e.expr, env), _ref_type(tc, inner), e.expr.span, "the operand of '!' (a reference)")
        return inner

    def evaluate(self, ev, e, env):
        return ev.eval(e.expr, env).value

    def show(self, e, pp):
        return f"(!{pp.atom(e.expr)})"


@register
class AssignForm(Form, node=Assign, rule="assign", parts=("target", "value")):

    def infer(self, tc, e, env):
        T = tc.types
        inner = tc.infer(e.value, env)
        tc.must(tc.infer(e.target, env), _ref_type(tc, inner), e.target.span,
                "the left operand of ':=' (a reference to a value of the right operand's type)")
        return T.UNIT

    def evaluate(self, ev, e, env):
        cell = ev.eval(e.target, env)
        cell.value = ev.eval(e.value, env)
        return ()

    def show(self, e, pp):
        return f"({pp.expr(e.target)} := {pp.expr(e.value)})"
