"""Tuples `(a, b)`, lists `[a, b]` and records `{x = a, y = b}`: each a Python tuple (a record's fields in the
alphabetical order of their labels, docs/internals.md)."""

from __future__ import annotations

from cpn.expr.form import Form, register
from cpn.expr.nodes import ListE, RecordE, TupleE


def _tuple_code(ec, items) -> str:
    return "(" + "".join(ec.expr(x) + ", " for x in items) + ")"


@register
class TupleForm(Form, node=TupleE, rule="tuple_", parts=("items",)):
    def parse(self, span, items):
        return TupleE(span, list(items))

    def infer(self, tc, e, env):
        return tc.types.TTuple([tc.infer(x, env) for x in e.items])

    def evaluate(self, ev, e, env):
        return tuple([ev.eval(x, env) for x in e.items])

    def compile(self, ec, e):
        return _tuple_code(ec, e.items)

    def show(self, e, pp):
        return "(" + ", ".join(pp.expr(x) for x in e.items) + ")"


@register
class ListForm(TupleForm, node=ListE, rule="list_"):
    """A list's value, subexpressions and code are a tuple's."""

    def parse(self, span, items):
        return ListE(span, [i for i in items if i is not None])

    def infer(self, tc, e, env):
        elem = tc.types.TVar()
        for x in e.items:
            tc.must(tc.infer(x, env), elem, x.span, "the elements of a list")
        return tc.types.lst(elem)

    def show(self, e, pp):
        return "[" + ", ".join(pp.expr(x) for x in e.items) + "]"


@register
class RecordForm(Form, node=RecordE, rule="record_", parts=("fields",)):
    def parse(self, span, items):
        return RecordE(span, [i for i in items if i is not None])

    def infer(self, tc, e, env):
        labels = [label for label, _ in e.fields]
        if len(set(labels)) != len(labels):
            tc.error("E0301", "a record expression names a field twice", e.span)
            tc.abort()
        return tc.types.TRecord([(label, tc.infer(x, env)) for label, x in e.fields])

    def evaluate(self, ev, e, env):
        vals = {label: ev.eval(x, env) for label, x in e.fields}
        return tuple(vals[label] for label in sorted(vals))

    def compile(self, ec, e):
        return _tuple_code(ec, [x for _, x in sorted(e.fields, key=lambda f: f[0])])

    def show(self, e, pp):
        return "{" + ", ".join(f"{label} = {pp.expr(x)}" for label, x in e.fields) + "}"
