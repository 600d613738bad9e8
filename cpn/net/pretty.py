"""The net's expressions (`cpn.net.expr`) as CPN ML text, in the canonical form of `cpn.lang.pretty`:
every compound subexpression is parenthesised. For drawings and messages that show an inscription.

Examples
--------
>>> import cpn
>>> t = cpn.loads("colset N = int with 0..3; var x : N; place P : N = 1`0;"
...               " trans t [x < 3]; arc P -> t : x; arc t -> P : if x = 0 then 1`(x + 1) else empty;").net.transitions[0]
>>> expr(t.guards[0]), expr(t.arcs[1].expr)
('(x < 3)', '(if (x = 0) then (1 ` (x + 1)) else empty)')
"""

from __future__ import annotations

from cpn._util.deep import left_spine
from cpn.expr import nodes as E
from cpn.lang.pretty import const


def expr(e: E.Expr) -> str:
    """CPN ML text of an expression."""
    if isinstance(e, E.Const):
        return const(e.value, e.kind)
    if isinstance(e, E.Name):
        return e.name
    if isinstance(e, E.Select):
        return f"#{e.label}"
    if isinstance(e, E.TupleE):
        return "(" + ", ".join(expr(x) for x in e.items) + ")"
    if isinstance(e, E.RecordE):
        return "{" + ", ".join(f"{label} = {expr(x)}" for label, x in e.fields) + "}"
    if isinstance(e, E.ListE):
        return "[" + ", ".join(expr(x) for x in e.items) + "]"
    if isinstance(e, E.App):
        return f"({expr(e.fn)} {_atom(e.arg)})"
    if isinstance(e, E.BinOp):
        first, spine = left_spine(e, E.BinOp)  # a chain of any length in a loop
        text = expr(first)
        for node in spine:
            text = f"({text} {node.op} {expr(node.right)})"
        return text
    if isinstance(e, E.Neg):
        return f"(~ {_atom(e.operand)})"
    if isinstance(e, E.If):
        return f"(if {expr(e.cond)} then {expr(e.then)} else {expr(e.else_)})"
    if isinstance(e, E.Case):
        return f"(case {expr(e.subject)} of " + " | ".join(f"{pat(p)} => {expr(b)}" for p, b in e.rules) + ")"
    if isinstance(e, E.Fn):
        return "(fn " + " | ".join(f"{pat(p)} => {expr(b)}" for p, b in e.rules) + ")"
    if isinstance(e, E.Raise):
        return f"(raise {expr(e.expr)})"
    if isinstance(e, E.Handle):
        return f"({expr(e.expr)} handle " + " | ".join(f"{pat(p)} => {expr(b)}" for p, b in e.rules) + ")"
    if isinstance(e, E.Let):
        return "let " + " ".join(_decl(d) for d in e.decls) + f" in {expr(e.body)} end"
    if isinstance(e, E.Seq):
        return "(" + "; ".join(expr(x) for x in e.items) + ")"
    if isinstance(e, E.ToMs):
        return expr(e.expr)
    if isinstance(e, E.OpFun):
        return f"(op {e.op})"
    raise TypeError(f"cannot print {type(e).__name__}")


def _atom(e: E.Expr) -> str:
    text = expr(e)
    return text if text.startswith(("(", "[", "{")) or isinstance(e, (E.Const, E.Name)) and not text.startswith("~") \
        else f"({text})"


def pat(p: E.Pat) -> str:
    """CPN ML text of a pattern."""
    if isinstance(p, E.PWild):
        return "_"
    if isinstance(p, E.PVar):
        return p.name
    if isinstance(p, E.PConst):
        return f"({const(p.value, p.kind)})" if p.kind == "int" and p.value < 0 else const(p.value, p.kind)
    if isinstance(p, E.PTuple):
        return "(" + ", ".join(pat(x) for x in p.items) + ")"
    if isinstance(p, E.PList):
        return "[" + ", ".join(pat(x) for x in p.items) + "]"
    if isinstance(p, E.PCons):
        return f"({pat(p.head)} :: {pat(p.tail)})"
    if isinstance(p, E.PCon):
        return f"({p.name} ({pat(p.arg)}))"
    if isinstance(p, E.PRecord):
        more = " ..." if len(p.fields) < len(p.ty_labels) else ""
        return "{" + ", ".join(f"{label} = {pat(q)}" for label, q in p.fields) + more + "}"
    if isinstance(p, E.PAs):
        return f"({p.name} as {pat(p.pat)})"
    raise TypeError(f"cannot print {type(p).__name__}")


def _decl(d) -> str:
    if isinstance(d, E.ValDecl):
        return f"val {pat(d.pat)} = {expr(d.expr)};"
    clauses = [f"{d.name} {' '.join(f'({pat(p)})' for p in c.params)} = {expr(c.body)}" for c in d.clauses]
    return "fun " + " | ".join(clauses) + ";"


__all__ = ["expr", "pat"]
