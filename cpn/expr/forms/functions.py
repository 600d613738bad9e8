"""Function values: `fn pat => e | ...`, `op +` (an infix operator as a function of a pair) and `#label`
(the function selecting a record field or tuple component)."""

from __future__ import annotations

from cpn.expr.form import Form, register, show_rules
from cpn.expr.nodes import Fn, OpFun, Select
from cpn.values.builtins import binop


@register
class FnForm(Form, node=Fn, rule="fn", parts=("rules",)):

    def infer(self, tc, e, env):
        T = tc.types
        at, rt = T.TVar(), T.TVar()
        sink, tc.ran_sink = tc.ran_sink, None  # a function may be applied many times: its draws are draws
        try:
            for pat, body in e.rules:
                binds: dict = {}
                tc.must(tc.infer_pat(pat, binds), at, pat.span, "the argument pattern of 'fn'")
                tc.must(tc.infer(body, env.child(binds)), rt, body.span, "the rules of 'fn'")
        finally:
            tc.ran_sink = sink
        return T.TFun(at, rt)

    def evaluate(self, ev, e, env):
        return ev.closure([([p], b) for p, b in e.rules], env, "fn")

    def show(self, e, pp):
        return f"(fn {show_rules(pp, e.rules)})"


@register
class OpFunForm(Form, node=OpFun, rule="opfun"):
    def infer(self, tc, e, env):
        T = tc.types
        a, b, r = tc.op_types(e.op, e)
        return T.TFun(T.TTuple([a, b]), r)

    def evaluate(self, ev, e, env):
        return lambda pair: binop(e.op, pair[0], pair[1])

    def show(self, e, pp):
        return f"(op {e.op})"


@register
class SelectForm(Form, node=Select, rule="select"):
    def infer(self, tc, e, env):
        T = tc.types
        a, r = T.TVar(), T.TVar()
        tc.pending.append((e, a, r, "sel"))  # its index is known when the record's type is (resolve_pending)
        return T.TFun(a, r)

    def evaluate(self, ev, e, env):
        idx = e.index
        return lambda v: v[idx]

    def compile(self, ec, e):
        return f"(lambda r: r[{e.index}])"

    def show(self, e, pp):
        return f"#{e.label}"
