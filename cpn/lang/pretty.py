"""AST to canonical `.cpnet` source text (for round-trip tests and tools that write models).

Every compound subexpression is parenthesised, so the text parses back to the same syntax tree.
Imports `cpn.lang.ast` only.
"""

from __future__ import annotations

import re

from cpn._util.deep import left_spine
from cpn.lang import ast as A

_IDENT = re.compile(r"^[A-Za-z][A-Za-z0-9_']*$")
_KEYWORDS = {"net", "colset", "var", "val", "fun", "place", "port", "trans", "arc", "inhibitor", "reset",
             "module", "instance", "fusion", "priority", "in", "out", "io", "if", "then", "else", "case", "of",
             "fn", "let", "end", "andalso", "orelse", "div", "mod", "op", "as", "with", "timed", "by",
             "unit", "bool", "int", "intinf", "string", "real", "time", "index", "product", "record", "list",
             "union", "subset", "true", "false"}


def string(s: str) -> str:
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n").replace("\t", "\\t") + '"'


def name(n: str) -> str:
    """A place, transition or instance name: bare when it is an identifier, quoted otherwise."""
    return n if _IDENT.match(n) and n not in _KEYWORDS else string(n)


def const(v, kind: str) -> str:
    if kind == "int":
        return f"~{-v}" if v < 0 else str(v)
    if kind == "real":
        return repr(float(v)).replace("-", "~")
    if kind == "string":
        return string(v)
    if kind == "bool":
        return "true" if v else "false"
    return "()"


def expr(e: A.Expr) -> str:
    if isinstance(e, A.Const):
        return const(e.value, e.kind)
    if isinstance(e, A.Name):
        return e.name
    if isinstance(e, A.Select):
        return f"#{e.label}"
    if isinstance(e, A.TupleE):
        return "(" + ", ".join(expr(x) for x in e.items) + ")"
    if isinstance(e, A.RecordE):
        return "{" + ", ".join(f"{label} = {expr(x)}" for label, x in e.fields) + "}"
    if isinstance(e, A.ListE):
        return "[" + ", ".join(expr(x) for x in e.items) + "]"
    if isinstance(e, A.App):
        return f"({expr(e.fn)} {_atom(e.arg)})"
    if isinstance(e, A.BinOp):
        first, spine = left_spine(e, A.BinOp)  # a chain of any length in a loop
        text = expr(first)
        for node in spine:
            text = f"({text} {node.op} {expr(node.right)})"
        return text
    if isinstance(e, A.Neg):
        return f"(~ {_atom(e.operand)})"
    if isinstance(e, A.If):
        return f"(if {expr(e.cond)} then {expr(e.then)} else {expr(e.else_)})"
    if isinstance(e, A.Case):
        return f"(case {expr(e.subject)} of " + " | ".join(f"{pat(p)} => {expr(b)}" for p, b in e.rules) + ")"
    if isinstance(e, A.Fn):
        return "(fn " + " | ".join(f"{pat(p)} => {expr(b)}" for p, b in e.rules) + ")"
    if isinstance(e, A.Raise):
        return f"(raise {expr(e.expr)})"
    if isinstance(e, A.Handle):
        return f"({expr(e.expr)} handle " + " | ".join(f"{pat(p)} => {expr(b)}" for p, b in e.rules) + ")"
    if isinstance(e, A.Let):
        body = expr(e.body.items[0]) + "".join("; " + expr(x) for x in e.body.items[1:]) \
            if isinstance(e.body, A.Seq) else expr(e.body)
        return "let " + " ".join(_decl_in_let(d) for d in e.decls) + f" in {body} end"
    if isinstance(e, A.Seq):
        return "(" + "; ".join(expr(x) for x in e.items) + ")"
    if isinstance(e, A.Annot):
        return f"({expr(e.expr)} : {ty(e.type_expr)})"
    if isinstance(e, A.ToMs):
        return expr(e.expr)
    if isinstance(e, A.OpFun):
        return f"(op {e.op})"
    raise TypeError(f"cannot print {type(e).__name__}")


def _atom(e: A.Expr) -> str:
    text = expr(e)
    return text if text.startswith(("(", "[", "{")) or isinstance(e, (A.Const, A.Name)) and not text.startswith("~") \
        else f"({text})"


def pat(p: A.Pat) -> str:
    if isinstance(p, A.PWild):
        return "_"
    if isinstance(p, A.PVar):
        return p.name
    if isinstance(p, A.PConst):
        return f"({const(p.value, p.kind)})" if p.kind == "int" and p.value < 0 else const(p.value, p.kind)
    if isinstance(p, A.PTuple):
        return "(" + ", ".join(pat(x) for x in p.items) + ")"
    if isinstance(p, A.PList):
        return "[" + ", ".join(pat(x) for x in p.items) + "]"
    if isinstance(p, A.PCons):
        return f"({pat(p.head)} :: {pat(p.tail)})"
    if isinstance(p, A.PCon):
        return f"({p.name} ({pat(p.arg)}))"
    if isinstance(p, A.PRecord):
        inner = [f"{label} = {pat(q)}" for label, q in p.fields] + (["..."] if p.flexible else [])
        return "{" + ", ".join(inner) + "}"
    if isinstance(p, A.PAs):
        return f"({p.name} as {pat(p.pat)})"
    if isinstance(p, A.PAnnot):
        return f"({pat(p.pat)} : {ty(p.type_expr)})"
    raise TypeError(f"cannot print {type(p).__name__}")


def ty(t: A.TypeExpr) -> str:
    if isinstance(t, A.TName):
        return t.name
    if isinstance(t, A.TPost):
        return f"{ty(t.arg)} {t.name}" if not isinstance(t.arg, A.TTuple) else f"({ty(t.arg)}) {t.name}"
    return " * ".join(f"({ty(x)})" if isinstance(x, A.TTuple) else ty(x) for x in t.items)


def _clauses(d: A.FunDecl) -> str:
    parts = []
    for c in d.clauses:
        params = " ".join(f"({pat(p)})" for p in c.params)
        rt = f" : {ty(c.result_type)}" if c.result_type is not None else ""
        parts.append(f"{d.name} {params}{rt} = {expr(c.body)}")
    return "fun " + "\n  | ".join(parts)


def _decl_in_let(d) -> str:
    if isinstance(d, A.ValDecl):
        return f"val {pat(d.pat)} = {expr(d.expr)};"
    if isinstance(d, A.ExceptionDecl):
        return _exception(d)
    return _clauses(d) + ";"


def _exception(d: A.ExceptionDecl) -> str:
    return f"exception {d.name}" + (f" of {ty(d.type_expr)}" if d.type_expr is not None else "") + ";"


def _colset(d: A.ColsetDecl) -> str:
    b = d.body
    k = b.kind
    rng = f" with {expr(b.low)}..{expr(b.high)}" if b.low is not None else ""
    body = {
        "unit": lambda: "unit", "bool": lambda: "bool", "string": lambda: "string", "real": lambda: "real",
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
        return indent + _clauses(d) + ";"
    if isinstance(d, A.ExceptionDecl):
        return indent + _exception(d)
    if isinstance(d, A.SymmetryDecl):
        return f"{indent}symmetry {', '.join(n for n, _ in d.names)} = {d.kind};"
    if isinstance(d, A.LocalDecl):
        private = " ".join(_decl_in_let(x) for x in d.private)
        public = " ".join(_decl_in_let(x) for x in d.public)
        return f"{indent}local {private} in {public} end;"
    if isinstance(d, A.PlaceDecl):
        head = f"port {d.port} " if d.port else "place "
        init = f" = {expr(d.init)}" if d.init is not None else ""
        fusion = f" fusion {name(d.fusion)}" if d.fusion else ""
        return f"{indent}{head}{name(d.name)} : {d.colset}{init}{fusion};"
    if isinstance(d, A.TransDecl):
        guard = f" [{', '.join(expr(g) for g in d.guards)}]" if d.guards else ""
        delay = f" @+ {_atom(d.delay)}" if d.delay is not None else ""
        prio = f" priority {_atom(d.priority)}" if d.priority is not None else ""
        return f"{indent}trans {name(d.name)}{guard}{delay}{prio};"
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
            head = f"{d.name}[{d.var} : {d.colset or _atom(d.low) + '..' + _atom(d.high)}]"
        return f"{indent}instance {head} = {d.module}({args})" + (f" {{ {binds} }}" if binds else "") + ";"
    raise TypeError(f"cannot print {type(d).__name__}")


def pretty(model: A.Model) -> str:
    """The canonical text of a parsed model."""
    return "\n".join(decl(d) for d in model.decls) + "\n"
