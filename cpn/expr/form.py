"""What an expression form of CPN ML declares, and the table of the forms that declared it.

A form (one node class of `cpn.expr`, or a family of them in one module under `cpn/expr/forms/`) says, in
one place, how it is built from the parse tree, its subexpressions, its type rule, its value, its Python
code and its text. The modules that walk the tree look a node's form up (`form_of`) instead of naming its
class: the transformer from the parse tree (`cpn.lang.transform`), the type checker (`cpn.lang.infer`), the
evaluator, the binding analysis and the printer of `cpn.expr`, and the compiler of `cpn.engine.codegen`.
So a new form is its grammar rule, its module, and its line in `cpn/expr/forms/__init__.py`.

Nothing here imports the language or the engine: a rule receives the object that applies it (the type
checker, the evaluator, the expression compiler, the printer) and calls back into it.

Examples
--------
>>> from cpn.expr import forms
>>> form = forms.BY_RULE["handle"]  # `e handle pat => e1`, built from the grammar's rule `handle`
>>> forms.form_of(form.node(None, None, [])) is form
True
"""

from __future__ import annotations

from typing import Any

from cpn.expr.nodes import Expr


class Form:
    """The rules of one expression form; a subclass overrides those its node needs.

    `node` is the node class, `rule` the name (the alias in `cpn/lang/grammar.lark`) of the parse-tree rule
    the parser builds it from, None if the parser does not build it (a node the type checker inserts).
    """

    node: type[Expr]
    rule: str | None = None
    #: the node's fields that hold its subexpressions, in order: an expression, or a list of expressions,
    #: of (pattern, expression) rules or of (label, expression) fields
    parts: tuple[str, ...] = ()

    def __init_subclass__(cls, node: type[Expr] | None = None, rule: str | None = None,
                          parts: tuple[str, ...] | None = None, **kwargs) -> None:
        """`class IfForm(Form, node=If, rule="if_", parts=("cond", "then", "else_"))`: the three attributes
        in the class line."""
        super().__init_subclass__(**kwargs)
        for name, value in (("node", node), ("rule", rule), ("parts", parts)):
            if value is not None:
                setattr(cls, name, value)

    def parse(self, span, items: list) -> Expr:
        """The node of a parse-tree rule: `items` are its children, already transformed (a token, such as
        the operator of `op +`, as a plain string)."""
        return self.node(span, *[str(x) if isinstance(x, str) else x for x in items])

    def children(self, e) -> list[Expr]:
        """The subexpressions of e, the bodies of its rules included (`cpn.expr.binding.children`): those
        its `parts` hold."""
        out = []
        for name in self.parts:
            v = getattr(e, name)
            if v.__class__ is list:
                out.extend(x[1] if x.__class__ is tuple else x for x in v)
            else:
                out.append(v)
        return out

    def infer(self, tc, e, env) -> Any:
        """The type of e. `tc` is the language's type checker: `tc.infer(x, env)`, `tc.must(found, expected,
        span, what)`, `tc.infer_pat(p, binds)`, `tc.types` (the types, `cpn.lang.types`); `env.child(binds)`."""
        raise NotImplementedError(f"no type rule for {type(e).__name__}")

    def evaluate(self, ev, e, env: dict) -> Any:
        """The value of e: `ev` is the evaluator (`ev.eval(x, env)`, `ev.match(p, v, env)`)."""
        raise NotImplementedError(f"no evaluation of {type(e).__name__}")

    def compile(self, ec, e) -> str | None:
        """A Python expression computing e (`ec.expr(x)` compiles a subexpression), or None to leave e to
        the evaluator, as the compiler of `cpn.engine.codegen` does with what it cannot compile."""
        return None

    def show(self, e, pp) -> str:
        """The canonical text of e: `pp` is the printer (`pp.expr`, `pp.atom`, `pp.pat`, `pp.ty`,
        `pp.declaration`)."""
        raise NotImplementedError(f"cannot print {type(e).__name__}")


#: what `match_rules` returns when no rule matches
NO_MATCH = object()


def match_rules(ev, rules: list, v, env: dict):
    """The value of the body of the first rule `(pat, body)` whose pattern matches v, or NO_MATCH (`case`,
    `handle`)."""
    for pat, body in rules:
        env2 = dict(env)
        if ev.match(pat, v, env2):
            return ev.eval(body, env2)
    return NO_MATCH


def show_rules(pp, rules: list) -> str:
    """`pat => e | pat => e` (`case`, `fn`, `handle`)."""
    return " | ".join(f"{pp.pat(p)} => {pp.expr(b)}" for p, b in rules)


#: node class -> its form
FORMS: dict[type, Form] = {}
#: parse-tree rule -> the form built from it
BY_RULE: dict[str, Form] = {}


def register(cls: type[Form]) -> type[Form]:
    """Class decorator: enters a form in the tables (once per node class and per rule)."""
    form = cls()
    if form.node in FORMS:
        raise ValueError(f"two forms of {form.node.__name__}")
    FORMS[form.node] = form
    if form.rule is not None:
        if form.rule in BY_RULE:
            raise ValueError(f"two forms built from rule {form.rule!r}")
        BY_RULE[form.rule] = form
    return cls


def form_of(e) -> Form | None:
    """The registered form of a node, or None for a node its walkers still name."""
    return FORMS.get(e.__class__)
