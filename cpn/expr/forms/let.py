"""`let decls in e end`: local values (`val pat = e`) and functions (`fun`), then the body; a body of
several expressions (`let ... in a; b end`) is a sequence. The compiled engine leaves it to the evaluator
except in a function's body (`cpn.engine.codegen.FunctionCodegen`)."""

from __future__ import annotations

from cpn.expr.form import Form, register
from cpn.expr.nodes import Decl, ExceptionDecl, FunDecl, Let, Seq, ValDecl


@register
class LetForm(Form, node=Let, rule="let_"):
    def parse(self, span, items):
        decls = [i for i in items if isinstance(i, Decl)]
        exprs = [i for i in items if not isinstance(i, Decl)]
        body = exprs[0] if len(exprs) == 1 else Seq(span, exprs)
        if not decls:  # `let in e end`, which CPN Tools accepts: e
            return body
        return Let(span, decls, body)

    def children(self, e):
        out = []
        for d in e.decls:
            if isinstance(d, ValDecl):
                out.append(d.expr)
            elif isinstance(d, FunDecl):
                out.extend(c.body for c in d.clauses)
        return out + [e.body]

    def infer(self, tc, e, env):
        inner = env.child()
        for d in e.decls:
            if isinstance(d, ValDecl):
                t = tc.infer(d.expr, inner)
                binds: dict = {}
                tc.must(tc.infer_pat(d.pat, binds), t, d.pat.span, "the pattern of 'val'")
                inner = inner.child(binds)
            elif isinstance(d, FunDecl):
                sink, tc.ran_sink = tc.ran_sink, None  # a local function may be called many times: its
                outer_appends = tc.appends[:]  # draws are draws; the enclosing code's open `l1 ++ l2`
                tc.appends.clear()  # are decided by the enclosing code, not at the end of this function
                try:
                    sym = tc.fun_decl(d, inner)
                finally:
                    tc.ran_sink = sink
                    tc.appends[:0] = outer_appends
                if sym is None:
                    tc.abort()
                inner = inner.child({d.name: sym})
            elif isinstance(d, ExceptionDecl):
                tc.error("E0206", "an exception declared inside 'let' is not supported", d.span,
                         hint="Declare it at the top level, or in the first part of 'local ... in ... end'.")
                tc.abort()
        return tc.infer(e.body, inner)

    def evaluate(self, ev, e, env):
        env = dict(env)
        for d in e.decls:
            ev.declare(d, env)
        return ev.eval(e.body, env)

    def show(self, e, pp):
        body = pp.expr(e.body.items[0]) + "".join("; " + pp.expr(x) for x in e.body.items[1:]) \
            if isinstance(e.body, Seq) else pp.expr(e.body)
        return "let " + " ".join(pp.declaration(d) for d in e.decls) + f" in {body} end"
