"""The expression tree (`cpn.expr.nodes`) as CPN ML text, in canonical form: every compound subexpression is
parenthesised, so that the text parses back to the same tree. The one printer of expressions, patterns and
type annotations: the language prints its declarations with it (`cpn.lang.pretty`), the reports the
inscriptions of a net (drawings, messages).

Examples
--------
>>> import cpn
>>> t = cpn.loads("colset N = int with 0..3; var x : N; place P : N = 1`0;"
...               " trans t [x < 3]; arc P -> t : x; arc t -> P : if x = 0 then 1`(x + 1) else empty;").net.transitions[0]
>>> expr(t.guards[0]), expr(t.arcs[1].expr)
('(x < 3)', '(if (x = 0) then (1 ` (x + 1)) else empty)')
"""

from __future__ import annotations

from types import SimpleNamespace

from cpn._util.deep import left_spine
from cpn.expr import nodes as N
from cpn.expr.forms import form_of


def string(s: str) -> str:
    """A CPN ML string literal."""
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n").replace("\t", "\\t") + '"'


def const(v, kind: str) -> str:
    """A constant of kind 'int', 'real', 'string', 'bool' or 'unit'."""
    if kind == "int":
        return f"~{-v}" if v < 0 else str(v)
    if kind == "real":
        return repr(float(v)).replace("-", "~")
    if kind == "string":
        return string(v)
    if kind == "bool":
        return "true" if v else "false"
    return "()"


def expr(e: N.Expr) -> str:
    """CPN ML text of an expression."""
    if isinstance(e, N.Const):
        return const(e.value, e.kind)
    if isinstance(e, N.Name):
        return e.name
    if isinstance(e, N.App):
        return f"({expr(e.fn)} {atom(e.arg)})"
    if isinstance(e, N.BinOp):
        first, spine = left_spine(e, N.BinOp)  # a chain of any length in a loop
        text = expr(first)
        for node in spine:
            text = f"({text} {node.op} {expr(node.right)})"
        return text
    form = form_of(e)  # a form that declares its own rules (cpn.expr.forms)
    if form is not None:
        return form.show(e, PRINTER)
    raise TypeError(f"cannot print {type(e).__name__}")


def atom(e: N.Expr) -> str:
    """The text of e, parenthesised unless it is one already (an argument, a delay)."""
    text = expr(e)
    return text if text.startswith(("(", "[", "{")) or isinstance(e, (N.Const, N.Name)) and not text.startswith("~") \
        else f"({text})"


def pat(p: N.Pat) -> str:
    """CPN ML text of a pattern."""
    if isinstance(p, N.PWild):
        return "_"
    if isinstance(p, N.PVar):
        return p.name
    if isinstance(p, N.PConst):
        return f"({const(p.value, p.kind)})" if p.kind == "int" and p.value < 0 else const(p.value, p.kind)
    if isinstance(p, N.PTuple):
        return "(" + ", ".join(pat(x) for x in p.items) + ")"
    if isinstance(p, N.PList):
        return "[" + ", ".join(pat(x) for x in p.items) + "]"
    if isinstance(p, N.PCons):
        return f"({pat(p.head)} :: {pat(p.tail)})"
    if isinstance(p, N.PCon):
        return f"({p.name} ({pat(p.arg)}))"
    if isinstance(p, N.PRecord):
        inner = [f"{label} = {pat(q)}" for label, q in p.fields] + (["..."] if p.flexible else [])
        return "{" + ", ".join(inner) + "}"
    if isinstance(p, N.PAs):
        return f"({p.name} as {pat(p.pat)})"
    if isinstance(p, N.PAnnot):
        return f"({pat(p.pat)} : {ty(p.type_expr)})"
    raise TypeError(f"cannot print {type(p).__name__}")


def ty(t: N.TypeExpr) -> str:
    """CPN ML text of a type annotation."""
    if isinstance(t, N.TName):
        return t.name
    if isinstance(t, N.TPost):
        return f"{ty(t.arg)} {t.name}" if not isinstance(t.arg, N.TTuple) else f"({ty(t.arg)}) {t.name}"
    return " * ".join(f"({ty(x)})" if isinstance(x, N.TTuple) else ty(x) for x in t.items)


def clauses(d: N.FunDecl, sep: str = " | ") -> str:
    """`fun f p1 = e1 | f p2 = e2` (without the semicolon); `sep` goes between the clauses."""
    parts = []
    for c in d.clauses:
        params = " ".join(f"({pat(p)})" for p in c.params)
        rt = f" : {ty(c.result_type)}" if c.result_type is not None else ""
        parts.append(f"{d.name} {params}{rt} = {expr(c.body)}")
    return "fun " + sep.join(parts)


def exception(d: N.ExceptionDecl) -> str:
    return f"exception {d.name}" + (f" of {ty(d.type_expr)}" if d.type_expr is not None else "") + ";"


def declaration(d: N.Decl, sep: str = " | ") -> str:
    """A declaration of a `let` (or of a `local` block): `val`, `fun` or `exception`, with its semicolon."""
    if isinstance(d, N.ValDecl):
        return f"val {pat(d.pat)} = {expr(d.expr)};"
    if isinstance(d, N.ExceptionDecl):
        return exception(d)
    return clauses(d, sep) + ";"


#: what a form's printing rule calls back (`cpn.expr.form.Form.show`)
PRINTER = SimpleNamespace(expr=expr, atom=atom, pat=pat, ty=ty, declaration=declaration)

__all__ = ["atom", "clauses", "const", "declaration", "exception", "expr", "pat", "string", "ty"]
