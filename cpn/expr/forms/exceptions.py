"""`raise e` and `e handle pat => e1 | ...`: SML's exceptions (docs/language.md).

An exception value is the tag ``"E#uid"`` of its constructor, or ``(tag, argument)``; `raise` throws it as
`cpn.values.builtins.MLRaise`, `handle` catches it while evaluating its expression. The compiled engine
leaves both to the evaluator, the C generator leaves the transition to Python.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from cpn.expr.form import NO_MATCH, Form, match_rules, register, show_rules
from cpn.expr.nodes import Expr, Pat
from cpn.values.builtins import MLRaise


@dataclass(slots=True, eq=False)
class Raise(Expr):
    """`raise e`: e is an exception value (the tag ``"E#uid"`` of its constructor, or ``(tag, argument)``)."""

    expr: Expr
    ty: Any = None


@dataclass(slots=True, eq=False)
class Handle(Expr):
    """`e handle pat => e1 | ...`: the rules see the exceptions raised by `raise` while evaluating e."""

    expr: Expr
    rules: list[tuple[Pat, Expr]]
    ty: Any = None


@register
class RaiseForm(Form, node=Raise, rule="raise_", parts=("expr",)):

    def infer(self, tc, e, env):
        T = tc.types
        tc.must(tc.infer(e.expr, env), T.EXN, e.expr.span, "the operand of 'raise' (an exception)")
        return T.TVar()

    def evaluate(self, ev, e, env):
        raise MLRaise(ev.eval(e.expr, env), f"{e.span.file}:{e.span.line}:{e.span.col}")

    def show(self, e, pp):
        return f"(raise {pp.expr(e.expr)})"


@register
class HandleForm(Form, node=Handle, rule="handle", parts=("expr", "rules")):

    def infer(self, tc, e, env):
        T = tc.types
        t = tc.infer(e.expr, env)
        for pat, body in e.rules:
            binds: dict = {}
            tc.must(tc.infer_pat(pat, binds), T.EXN, pat.span, "a pattern of 'handle' (an exception)")
            tc.must(tc.infer(body, env.child(binds)), t, body.span,
                    "the rules of 'handle' (each must have the type of the expression it handles)")
        return t

    def evaluate(self, ev, e, env):
        try:
            return ev.eval(e.expr, env)
        except MLRaise as exc:
            v = match_rules(ev, e.rules, exc.value, env)
            if v is NO_MATCH:
                raise
            return v

    def show(self, e, pp):
        return f"({pp.expr(e.expr)} handle {show_rules(pp, e.rules)})"
