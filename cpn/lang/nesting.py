"""How deeply the expressions of a model nest: what the loader reports when a model is too deep to read.

A chain of operators (`a + b + ... + z`, which the walkers follow in a loop) is one level, whatever its
length; each parenthesised operand, `if`, `let`, application or tuple inside another adds one. Iterative,
so it works on any model. Imports `cpn.lang.ast` and layer 0.
"""

from __future__ import annotations

import dataclasses

from cpn.diagnostics import Diagnostic, Span
from cpn.lang import ast as A


def deepest(decls: list) -> tuple[A.Expr, int] | None:
    """The outermost expression that holds the most deeply nested one, and that depth (None: no expression).

    >>> from cpn.lang.parser import parse
    >>> e, depth = deepest(parse("val a = 1 + 2 + 3 + 4; val b = f (g (h 1));").decls)
    >>> depth, e.span.col
    (4, 32)
    """
    best: tuple[A.Expr, int] | None = None
    stack: list[tuple[object, int, A.Expr | None]] = [(d, 0, None) for d in reversed(decls)]
    while stack:
        node, depth, top = stack.pop()
        if isinstance(node, A.Expr):
            top = top or node
            depth += 1
            if best is None or depth > best[1]:
                best = (top, depth)
        if isinstance(node, (list, tuple)):
            stack.extend((x, depth, top) for x in reversed(node))
            continue
        if not dataclasses.is_dataclass(node) or isinstance(node, type):
            continue
        for f in dataclasses.fields(node):
            if f.name in ("span", "ty", "ref", "op_ty", "ran_var", "type_expr"):
                continue
            child = getattr(node, f.name)
            # the left operand of an operator continues its chain: one level for the whole chain
            same = isinstance(node, A.BinOp) and f.name == "left" and isinstance(child, A.BinOp)
            stack.append((child, depth - 1 if same else depth, top))
    return best


def too_deep(decls: list, filename: str) -> Diagnostic:
    """E0206 for a model that is nested too deeply to be read, at the expression that nests deepest."""
    found = deepest(decls)
    if found is None:
        span, depth = Span(filename, 1, 1), None
    else:
        span, depth = found[0].span, found[1]
    levels = f" ({depth:,} levels of parentheses, 'if', 'let' or operands inside each other)" if depth else ""
    return Diagnostic("E0206", f"this expression is nested too deeply to be read{levels}", span,
                      hint="Split it with 'let' or auxiliary functions (a chain such as a + b + ... + z is not "
                      "nesting, however long; 1 + (1 + (1 + ...)) is).")
