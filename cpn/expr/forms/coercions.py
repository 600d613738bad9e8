"""The forms that change only how a value is typed: `e : T` (a type annotation, which lowering drops), and
``1`e`` where the type checker found a single value where a multiset is expected (`ToMs`, never parsed)."""

from __future__ import annotations

from cpn.expr.form import Form, register
from cpn.expr.nodes import Annot, ToMs
from cpn.values.multiset import Multiset, TimedMultiset


@register
class AnnotForm(Form, node=Annot, rule="annot", parts=("expr",)):

    def infer(self, tc, e, env):
        t = tc.infer(e.expr, env)
        at = tc.type_of_annotation(e.type_expr)
        if at is None:
            tc.abort()
        tc.must(t, at, e.span, "a type annotation")
        return t

    def evaluate(self, ev, e, env):
        return ev.eval(e.expr, env)

    def show(self, e, pp):
        return f"({pp.expr(e.expr)} : {pp.ty(e.type_expr)})"


@register
class ToMsForm(Form, node=ToMs, parts=("expr",)):

    def infer(self, tc, e, env):
        return tc.types.ms(tc.infer(e.expr, env))

    def evaluate(self, ev, e, env):
        v = ev.eval(e.expr, env)
        return v if isinstance(v, (Multiset, TimedMultiset)) else Multiset.of(v)

    def compile(self, ec, e):
        return f"MS1({ec.expr(e.expr)})"

    def show(self, e, pp):
        return pp.expr(e.expr)
