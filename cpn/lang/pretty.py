"""AST to canonical `.cpnet` source text (for round-trip tests and tools that write models).

The declarations and the net structure; their expressions, patterns and types are printed by the one
printer of the expression tree, `cpn.expr.pretty`, in which every compound subexpression is
parenthesised, so the text parses back to the same syntax tree.
"""

from __future__ import annotations

import re

from cpn.expr.pretty import atom, clauses, declaration, exception, expr, pat, string, ty
from cpn.lang import ast as A

_IDENT = re.compile(r"^[A-Za-z][A-Za-z0-9_']*$")
_KEYWORDS = {"net", "colset", "var", "val", "fun", "place", "port", "trans", "arc", "inhibitor", "reset",
             "module", "instance", "fusion", "priority", "in", "out", "io", "if", "then", "else", "case", "of",
             "fn", "let", "end", "andalso", "orelse", "div", "mod", "op", "as", "with", "timed", "by",
             "unit", "bool", "int", "intinf", "string", "real", "time", "index", "product", "record", "list",
             "union", "subset", "true", "false"}


_CLAUSES = "\n  | "  # between the clauses of a declared function


def name(n: str) -> str:
    """A place, transition or instance name: bare when it is an identifier, quoted otherwise."""
    return n if _IDENT.match(n) and n not in _KEYWORDS else string(n)


def _colset(d: A.ColsetDecl) -> str:
    b = d.body
    k = b.kind
    if k == "datatype":
        cons = " | ".join(f"{c} of {a}" if a else c for c, a in b.fields)
        return f"datatype {d.name} = {cons}{' | ...' if b.pred is not None else ''};"
    rng = f" with {expr(b.low)}..{expr(b.high)}" if b.low is not None else ""
    body = {
        "unit": lambda: "unit", "real": lambda: "real",
        "bool": lambda: "bool" + (f" with ({b.names[0]}, {b.names[1]})" if b.names else ""),
        "string": lambda: "string" + (f" with {string(b.names[0])}..{string(b.names[1])}" if b.names else "")
        + (f" and {expr(b.low)}..{expr(b.high)}" if b.low is not None else ""),
        "time": lambda: "time", "int": lambda: "int" + rng,
        "enum": lambda: "with " + " | ".join(b.names),
        "index": lambda: f"index {b.names[0]} with {expr(b.low)}..{expr(b.high)}",
        "product": lambda: "product " + " * ".join(b.names),
        "record": lambda: "record " + " * ".join(f"{f} : {c}" for f, c in b.fields),
        "list": lambda: f"list {b.names[0]}" + rng,
        "union": lambda: "union " + " + ".join(f"{c} : {t}" if t else c for c, t in b.fields),
        "subset_by": lambda: f"subset {b.names[0]} by {expr(b.pred)}",
        "subset_with": lambda: f"subset {b.names[0]} with {expr(b.pred)}",
        "alias": lambda: b.names[0],
    }[k]()
    return f"colset {d.name} = {body}{' timed' if d.timed else ''};"


def decl(d: A.Decl, indent: str = "") -> str:
    if isinstance(d, A.NetHeader):
        return f"{indent}net {name(d.name)};"
    if isinstance(d, A.ColsetDecl):
        return indent + _colset(d)
    if isinstance(d, A.VarDecl):
        return f"{indent}var {', '.join(n for n, _ in d.names)} : {d.colset};"
    if isinstance(d, A.ValDecl):
        annot = f" : {ty(d.type_expr)}" if d.type_expr is not None else ""
        return f"{indent}val {d.name if d.name is not None else pat(d.pat)}{annot} = {expr(d.expr)};"
    if isinstance(d, A.FunDecl):
        return indent + clauses(d, _CLAUSES) + ";"
    if isinstance(d, A.ExceptionDecl):
        return indent + exception(d)
    if isinstance(d, A.SymmetryDecl):
        return f"{indent}symmetry {', '.join(n for n, _ in d.names)} = {d.kind};"
    if isinstance(d, A.LocalDecl):
        private = " ".join(declaration(x, _CLAUSES) for x in d.private)
        public = " ".join(declaration(x, _CLAUSES) for x in d.public)
        return f"{indent}local {private} in {public} end;"
    if isinstance(d, A.PlaceDecl):
        head = f"port {d.port} " if d.port else "place "
        init = f" = {expr(d.init)}" if d.init is not None else ""
        fusion = f" fusion {name(d.fusion)}" if d.fusion else ""
        return f"{indent}{head}{name(d.name)} : {d.colset}{init}{fusion};"
    if isinstance(d, A.TransDecl):
        guard = f" [{', '.join(expr(g) for g in d.guards)}]" if d.guards else ""
        delay = f" @+ {atom(d.delay)}" if d.delay is not None else ""
        if isinstance(d.delay, A.BinOp) and d.delay.op == "@++":  # a real-valued delay (transform.delay)
            delay = f" @++ {atom(d.delay.right)}"
        prio = f" priority {atom(d.priority)}" if d.priority is not None else ""
        action = ""
        if d.action is not None:
            outputs = f" output ({', '.join(d.outputs)})" if d.outputs else ""
            action = f"{outputs} action {expr(d.action)}"
        return f"{indent}trans {name(d.name)}{guard}{delay}{prio}{action};"
    if isinstance(d, A.ArcDecl):
        ins = f" : {expr(d.expr)}" if d.expr is not None else ""
        src = (f"{d.src_kind} " if d.src_kind else "") + name(d.src)
        dst = (f"{d.dst_kind} " if d.dst_kind else "") + name(d.dst)
        if d.kind not in ("->", "<->"):  # a keyword arc: inhibitor, reset
            return f"{indent}{d.kind} {src} -> {dst}{ins};"
        return f"{indent}arc {src} {d.kind} {dst}{ins};"
    if isinstance(d, A.ModuleDecl):
        params = ", ".join(f"{n} : {c}" for n, c, _ in d.params)
        body = "\n".join(decl(x, indent + "  ") for x in d.body)
        return f"{indent}module {d.name}({params}) {{\n{body}\n{indent}}}"
    if isinstance(d, A.InstanceDecl):
        args = ", ".join(f"{n} = {expr(e)}" for n, e, _ in d.args)
        binds = ", ".join(f"{name(p)} = {name(s)}" for p, _, s, _ in d.binds)
        head = name(d.name)
        if isinstance(d, A.InstanceFamilyDecl):  # instance Slave[i : 1..MAXS] = ...
            head = f"{d.name}[{d.var} : {d.colset or atom(d.low) + '..' + atom(d.high)}]"
        return f"{indent}instance {head} = {d.module}({args})" + (f" {{ {binds} }}" if binds else "") + ";"
    raise TypeError(f"cannot print {type(d).__name__}")


def pretty(model: A.Model) -> str:
    """The canonical text of a parsed model."""
    return "\n".join(decl(d) for d in model.decls) + "\n"
