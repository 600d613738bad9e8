"""Mutants of a `.cpnet` model: small changes of its text that resemble a protocol implementer's mistakes.

Each mutant is one edit of the source text at the span of a node of the syntax tree (`cpn.lang.ast`), so
it is shown as a unified diff with its `file:line:col`. The list is in source order and the same for the
same text; `select` draws a sample from it with a seed. Imports `cpn.lang` and layer 0 only.
"""

from __future__ import annotations

import dataclasses
import difflib
import random
from dataclasses import dataclass

from cpn.diagnostics import Span
from cpn.lang import ast

# the operators, in the order a mutant's description names them (docs/mutation.md)
OPERATORS: dict[str, str] = {
    "guard-negated": "a guard replaced by its negation",
    "guard-dropped": "a guard replaced by true (weakened)",
    "conjunct-dropped": "one side of an 'andalso' dropped (a condition weakened)",
    "disjunct-dropped": "one side of an 'orelse' dropped (a condition strengthened)",
    "comparison-changed": "a comparison off by one (< and <=, > and >=) or negated (= and <>)",
    "constant-changed": "an integer constant plus or minus one",
    "boolean-flipped": "true and false exchanged",
    "arithmetic-changed": "+ and - exchanged",
    "if-swapped": "the two branches of an 'if' exchanged",
    "arc-removed": "an arc deleted",
    "arc-one-way": "a double arc '<->' made one-way (its token consumed, or put, only)",
    "token-duplicated": "an arc's or initial marking's tokens doubled",
    "token-dropped": "an initial marking emptied",
    "delay-changed": "a delay plus one, or removed",
    "priority-changed": "a transition's priority removed, or given a high one (priority 100)",
}

_COMPARISONS = {"<": "<=", "<=": "<", ">": ">=", ">=": ">", "=": "<>", "<>": "="}
_ARITHMETIC = {"+": "-", "-": "+"}
HIGH_PRIORITY = 100  # P_HIGH: a priority above the default of a transition without one


@dataclass(frozen=True)
class Mutant:
    """One edit of a model's text: replace `source[start:end]` by `text`.

    `number` is the mutant's place in the model's full list (1-based): the same mutant has the same
    number whatever sample is drawn.
    """

    number: int
    operator: str
    description: str
    span: Span
    start: int
    end: int
    text: str

    @property
    def ident(self) -> str:
        return f"M{self.number}"

    def apply(self, source: str) -> str:
        """The mutant's model text."""
        return source[:self.start] + self.text + source[self.end:]

    def diff(self, source: str, context: int = 1) -> str:
        """A unified diff of the model text (original, then mutant), with `context` lines around."""
        name = self.span.file
        lines = difflib.unified_diff(source.splitlines(keepends=True), self.apply(source).splitlines(keepends=True),
                                     f"{name}", f"{name} ({self.ident})", n=context)
        return "".join(line if line.endswith("\n") else line + "\n" for line in lines)


def mutants(model: ast.Model, skip_values: frozenset = frozenset()) -> list[Mutant]:
    """Every mutant of a parsed model, in source order, numbered from 1; edits that give the same text
    are kept once. `skip_values` names `val` constants whose declared value no run uses (every run sets
    them): changing it could change nothing."""
    finder = _Finder(model.source, model.file, skip_values)
    finder.decls(model.decls, "")
    out, seen = [], set()
    for m in sorted(finder.found, key=lambda m: (m.start, m.end, list(OPERATORS).index(m.operator), m.text)):
        key = (m.start, m.end, m.text)
        if key in seen or model.source[m.start:m.end] == m.text:
            continue
        seen.add(key)
        out.append(dataclasses.replace(m, number=len(out) + 1))
    return out


def select(found: list[Mutant], limit: int | None, seed: int) -> list[Mutant]:
    """At most `limit` mutants drawn with the seed (all of them without a limit), in source order."""
    if limit is None or limit >= len(found):
        return list(found)
    return sorted(random.Random(seed).sample(found, limit), key=lambda m: m.number)


class _Finder:
    """Walks the declarations and collects the mutants of each guard, inscription, marking and value."""

    def __init__(self, source: str, file: str, skip_values: frozenset):
        self.source = source
        self.file = file
        self.skip_values = skip_values
        self.found: list[Mutant] = []
        self._starts = [0]
        for i, c in enumerate(source):
            if c == "\n":
                self._starts.append(i + 1)

    # ------------------------------------------------------------------ positions and edits

    def offset(self, line: int, col: int) -> int:
        return self._starts[line - 1] + col - 1

    def bounds(self, span: Span) -> tuple[int, int]:
        """Offsets [start, end) of a span (its end column is inclusive)."""
        end_line = span.end_line if span.end_line is not None else span.line
        end_col = span.end_col if span.end_col is not None else span.col
        return self.offset(span.line, span.col), self.offset(end_line, end_col) + 1

    def text(self, node) -> str:
        return self.text_of(node.span)

    def text_of(self, span: Span) -> str:
        a, b = self.bounds(span)
        return self.source[a:b]

    def add(self, operator: str, where: str, start: int, end: int, text: str) -> None:
        line = self.source.count("\n", 0, start) + 1
        col = start - self._starts[line - 1] + 1
        last = max(start, end - 1)
        end_line = self.source.count("\n", 0, last) + 1
        span = Span(self.file, line, col, end_line, last - self._starts[end_line - 1] + 1)
        old = " ".join(self.source[start:end].split())
        new = " ".join(text.split())
        what = f"'{_short(old)}' -> '{_short(new)}'" if old else f"'{_short(new)}' added"
        if not new:
            what = f"'{_short(old)}' removed"
        self.found.append(Mutant(0, operator, f"{where}: {what}", span, start, end, text))

    def replace(self, operator: str, where: str, node, text: str) -> None:
        a, b = self.bounds(node.span)
        self.add(operator, where, a, b, text)

    # ------------------------------------------------------------------ declarations

    def decls(self, decls: list, module: str) -> None:
        inside = f" of module '{module}'" if module else ""
        for d in decls:
            if isinstance(d, ast.ModuleDecl):
                self.decls(d.body, d.name)
            elif isinstance(d, ast.LocalDecl):
                self.decls(d.private + d.public, module)
            elif isinstance(d, ast.ValDecl):
                if d.name is not None and d.name not in self.skip_values:
                    self.expr(d.expr, f"the value of '{d.name}'")
            elif isinstance(d, ast.FunDecl):
                for c in d.clauses:
                    self.expr(c.body, f"function '{d.name}'")
            elif isinstance(d, ast.PlaceDecl) and d.init is not None:
                where = f"the initial marking of place '{d.name}'{inside}"
                self.replace("token-duplicated", where, d.init, f"({self.text(d.init)}) ++ ({self.text(d.init)})")
                a, _ = self.bounds(d.name_span)
                eq = self.source.rfind("=", a, self.bounds(d.init.span)[0])
                if eq >= 0:  # `place P : C = init;` -> `place P : C;`
                    self.add("token-dropped", where, self._trim_left(eq), self.bounds(d.init.span)[1], "")
                self.expr(d.init, where)
            elif isinstance(d, ast.TransDecl):
                self.transition(d, inside)
            elif isinstance(d, ast.ArcDecl):
                self.arc(d, inside)

    def _trim_left(self, i: int) -> int:
        while i > 0 and self.source[i - 1] in " \t":
            i -= 1
        return i

    def transition(self, d: ast.TransDecl, inside: str) -> None:
        name = f"transition '{d.name}'{inside}"
        for g in d.guards:
            where = f"the guard of {name}"
            self.replace("guard-negated", where, g, f"not ({self.text(g)})")
            self.replace("guard-dropped", where, g, "true")
            self.expr(g, where)
        if d.delay is not None:
            where = f"the delay of {name}"
            self.replace("delay-changed", where, d.delay, f"({self.text(d.delay)}) + 1")
            a, b = self.bounds(d.delay.span)
            at = self.source.rfind("@+", 0, a)
            if at >= 0:
                self.add("delay-changed", where, self._trim_left(at), b, "")
            self.expr(d.delay, where)
        if d.priority is not None:
            where = f"the priority of {name}"
            a, b = self.bounds(d.priority.span)
            kw = self.source.rfind("priority", 0, a)
            if kw >= 0:
                self.add("priority-changed", where, self._trim_left(kw), b, "")
            self.expr(d.priority, where)
        else:
            end = self.bounds(d.span)[1] - 1  # the ';'
            if self.source[end] == ";":
                self.add("priority-changed", f"the priority of {name}", end, end, f" priority {HIGH_PRIORITY}")

    def arc(self, d: ast.ArcDecl, inside: str) -> None:
        arrow = "->" if d.kind in ("->", "inhibitor", "reset") else "<->"
        name = f"arc '{d.src}' {arrow} '{d.dst}'{inside}"
        start, end = self.bounds(d.span)
        while end < len(self.source) and self.source[end] in " \t":
            end += 1
        if end < len(self.source) and self.source[end] == "\n" and (start == 0 or self.source[start - 1] == "\n"):
            end += 1  # the arc's whole line
        self.add("arc-removed", name, start, end, "")
        if d.kind == "<->":
            a = self.bounds(d.src_span)[1]
            b = self.bounds(d.dst_span)[0]
            op = self.source.find("<->", a, b)
            if op >= 0:  # the token is only taken, or only put (the arc turned round)
                self.add("arc-one-way", name, op, op + 3, "->")
                self.add("arc-one-way", name, self.bounds(d.src_span)[0], self.bounds(d.dst_span)[1],
                         f"{self.text_of(d.dst_span)} -> {self.text_of(d.src_span)}")
        if d.expr is None or d.kind in ("inhibitor", "reset"):
            if d.expr is not None:
                self.expr(d.expr, f"the inscription of {name}")
            return
        where = f"the inscription of {name}"
        body = d.expr
        if isinstance(body, ast.BinOp) and body.op == "@+":
            body = body.left
        self.replace("token-duplicated", where, body, f"({self.text(body)}) ++ ({self.text(body)})")
        self.expr(d.expr, where)

    # ------------------------------------------------------------------ expressions

    def expr(self, e, where: str) -> None:
        """The mutants of every node of an expression (children first in source order)."""
        for node in _nodes(e):
            self.node(node, where)

    def node(self, e, where: str) -> None:
        if isinstance(e, ast.Const):
            if e.kind == "int" and isinstance(e.value, int) and not isinstance(e.value, bool):
                for v in (e.value + 1, e.value - 1):
                    self.replace("constant-changed", where, e, _ml_int(v))
            elif e.kind == "bool":
                self.replace("boolean-flipped", where, e, "false" if e.value else "true")
        elif isinstance(e, ast.BinOp):
            if e.op in _COMPARISONS or e.op in _ARITHMETIC:
                a = self.bounds(e.left.span)[1]
                b = self.bounds(e.right.span)[0]
                i = _find_operator(self.source, e.op, a, b)
                if i is not None:
                    if e.op in _COMPARISONS:
                        self.add("comparison-changed", where, i, i + len(e.op), _COMPARISONS[e.op])
                    elif not _is_string_or_real(e):
                        self.add("arithmetic-changed", where, i, i + len(e.op), _ARITHMETIC[e.op])
            elif e.op in ("andalso", "orelse"):
                op = "conjunct-dropped" if e.op == "andalso" else "disjunct-dropped"
                self.replace(op, where, e, f"({self.text(e.left)})")
                self.replace(op, where, e, f"({self.text(e.right)})")
            elif e.op == "@+":
                self.replace("delay-changed", where, e.right, f"({self.text(e.right)}) + 1")
                self.replace("delay-changed", where, e, f"({self.text(e.left)})")
        elif isinstance(e, ast.If):
            self.replace("if-swapped", where, e,
                         f"(if {self.text(e.cond)} then {self.text(e.else_)} else {self.text(e.then)})")


def _nodes(e):
    """The expression nodes of `e`, itself first, then its parts (declarations of a `let` included)."""
    stack = [e]
    while stack:
        node = stack.pop()
        if isinstance(node, ast.Expr):
            yield node
        if isinstance(node, (ast.Expr, ast.Decl, ast.Clause)):
            parts = []
            for f in dataclasses.fields(node):
                if f.name in ("span", "ty", "ref", "op_ty", "ran_var", "type_expr"):
                    continue
                parts.append(getattr(node, f.name))
            stack.extend(reversed(list(_flatten(parts))))


def _flatten(values):
    for v in values:
        if isinstance(v, (list, tuple)):
            yield from _flatten(v)
        elif isinstance(v, (ast.Expr, ast.Decl, ast.Clause)):
            yield v


def _find_operator(source: str, op: str, a: int, b: int) -> int | None:
    """Where the operator `op` stands between two operands (source[a:b]), skipping parentheses."""
    gap = source[a:b]
    i = gap.find(op)
    while i >= 0:
        after = gap[i + len(op):i + len(op) + 1]
        before = gap[i - 1:i] if i > 0 else ""
        # '<' of '<>' or '<=', '=' of '<=' or '>=', '-' of '->' are other operators
        if after not in ("=", ">") and before not in ("<", ">"):
            return a + i
        i = gap.find(op, i + 1)
    return None


def _is_string_or_real(e: ast.BinOp) -> bool:
    return any(isinstance(x, ast.Const) and x.kind in ("string", "real") for x in (e.left, e.right))


def _ml_int(v: int) -> str:
    return f"~{-v}" if v < 0 else str(v)


def _short(text: str, limit: int = 60) -> str:
    return text if len(text) <= limit else text[:limit - 3] + "..."
