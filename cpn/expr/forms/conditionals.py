"""`if c then a else b` and `case e of pat => e1 | ...`.

Their type rules read `empty` beside a list as `[]` (CPN Tools' multisets are lists) and a single value
beside a multiset as ``1`value`` (the type checker's `empty_as_list` and `join_branches`).
"""

from __future__ import annotations

from cpn.expr.form import NO_MATCH, Form, match_rules, register, show_rules
from cpn.expr.nodes import Case, If
from cpn.values.builtins import MLError


@register
class IfForm(Form, node=If, rule="if_", parts=("cond", "then", "else_")):

    def infer(self, tc, e, env):
        tc.must(tc.infer(e.cond, env), tc.types.BOOL, e.cond.span, "the condition of 'if'")
        if tc.is_empty_ms(e.then, env) and not tc.is_empty_ms(e.else_, env):
            et = tc.infer(e.else_, env)
            e.then = tc.empty_as_list(e.then, et)
            tt = tc.infer(e.then, env)
        else:
            tt = tc.infer(e.then, env)
            e.else_ = tc.empty_as_list(e.else_, tt, env)
            et = tc.infer(e.else_, env)
        return tc.join_branches(e, "then", "else_", tt, et)

    def evaluate(self, ev, e, env):
        return ev.eval(e.then if ev.eval(e.cond, env) else e.else_, env)

    def compile(self, ec, e):
        return f"({ec.expr(e.then)} if {ec.expr(e.cond)} else {ec.expr(e.else_)})"

    def show(self, e, pp):
        return f"(if {pp.expr(e.cond)} then {pp.expr(e.then)} else {pp.expr(e.else_)})"


@register
class CaseForm(Form, node=Case, rule="case", parts=("subject", "rules")):

    def infer(self, tc, e, env):
        st = tc.infer(e.subject, env)
        rt = None
        # a rule whose body is `empty` after one that is not: `empty` beside a list is `[]` (empty_as_list)
        first = next((i for i, (_p, b) in enumerate(e.rules) if not tc.is_empty_ms(b, env)), 0)
        for i in [first] + [i for i in range(len(e.rules)) if i != first]:
            pat, body = e.rules[i]
            binds: dict = {}
            tc.must(tc.infer_pat(pat, binds), st, pat.span, "a case pattern")
            inner = env.child(binds)
            if rt is not None:
                body = tc.empty_as_list(body, rt, inner)
                e.rules[i] = (pat, body)
            bt = tc.infer(body, inner)
            if rt is None:
                rt = bt
            else:
                tc.must(bt, rt, body.span, "the rules of 'case' (all must have the same type)")
        return rt

    def evaluate(self, ev, e, env):
        v = match_rules(ev, e.rules, ev.eval(e.subject, env), env)
        if v is NO_MATCH:
            raise MLError("no rule of the case-expression matches (SML exception Match)")
        return v

    def show(self, e, pp):
        return f"(case {pp.expr(e.subject)} of {show_rules(pp, e.rules)})"
