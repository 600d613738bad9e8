"""Values of `val` constants given from outside the model (`--set NAME=VALUE`, `cpn.load(set=...)`): each
is parsed once, before the model is checked, and checked against the constant it replaces. A bad value is
one usage error naming the value (`ConfigurationError`), never a cascade of model errors.

`OverrideChecks` is a mixin of `cpn.lang.typecheck.Checker`, which provides inference and diagnostics.
Imports `cpn.lang.*` and layer 0.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any, Callable

from cpn._util import did_you_mean
from cpn.diagnostics import Span
from cpn.errors import ConfigurationError, ModelError
from cpn.expr.evaluate import run_deep
from cpn.lang import ast as A
from cpn.lang import types as T
from cpn.lang.builtins import MLError
from cpn.lang.parser import parse

_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_']*\Z")
_NEGATIVE = re.compile(r"\s*-\s*(\d+(?:\.\d+)?)\s*\Z")


@dataclass(frozen=True)
class Override:
    """One value given for a constant: the text as given and its parsed expression."""

    name: str
    text: str
    expr: A.Expr

    def __str__(self) -> str:
        return f"--set {self.name}={self.text}"


@dataclass(frozen=True)
class OverrideProblem:
    """Why a given value does not fit; `{declared}` in the message stands for the position of `declared`."""

    override: Override
    message: str
    hint: str | None = None
    declared: Span | None = None

    def text(self, where: Callable[[Span], str] = str) -> str:
        declared = where(self.declared) if self.declared is not None else "?"
        return f"{self.override}: {self.message.replace('{declared}', declared)}"


def usage_error(problems: list[OverrideProblem], where: Callable[[Span], str] = str) -> ConfigurationError:
    """One usage error for every value that does not fit; `where` writes a declaration's position."""
    lines = [p.text(where) for p in problems]
    hints = [p.hint for p in problems if p.hint]
    exc = ConfigurationError(lines[0] if len(lines) == 1 else "\n".join(["bad --set values:"] + ["  " + x for x in lines]),
                             hint=hints[0] if len(hints) == 1 else None, code="E0305")
    exc.problems = list(problems)
    return exc


def parse_override(name: str, text: str) -> Override:
    """Parse the value of one constant; `-1` is read as CPN ML's `~1`. Raises ConfigurationError."""
    if not _NAME.match(name):
        raise ConfigurationError(f"--set {name}={text}: '{name}' is not the name of a constant",
                                 hint="Write --set NAME=VALUE with the name of a 'val' of the model.", code="E0305")
    ml = text.strip()
    neg = _NEGATIVE.match(ml)
    if neg:
        ml = "~" + neg.group(1)
    try:
        decls = parse(f"val {name} = {ml};", f"--set {name}").decls
        if len(decls) != 1 or not isinstance(decls[0], A.ValDecl):
            raise ModelError([])
        decl = decls[0]
    except ModelError as exc:
        first = exc.diagnostics[0].message if exc.diagnostics else "it is more than one expression"
        last = f"val {name} = {ml};".rfind(";") + 1
        if exc.diagnostics and exc.diagnostics[0].span and exc.diagnostics[0].span.col == last:
            first = first.replace("found ';'", "found the end of the value")
        raise ConfigurationError(
            f"--set {name}={text}: the value is not a CPN ML expression ({first})",
            hint=f"Write the value as in the model: --set {name}=8, --set {name}=-1 (or ~1), "
                 f"--set {name}=true, --set '{name}=\"text\"'.", code="E0305") from None
    return Override(name, text, decl.expr)


def parse_overrides(values: dict[str, str] | None) -> dict[str, Override]:
    """Parse every value once (before the model is checked)."""
    return {name: v if isinstance(v, Override) else parse_override(name, v) for name, v in (values or {}).items()}


def _article(ty: str) -> str:
    return ("an " if ty[:1] in "aeiou" else "a ") + ty


class OverrideChecks:
    """Checking overridden constants against their declarations (mixed into the Checker)."""

    def override_value(self, d: A.ValDecl, ov: Override) -> tuple[T.Type, Any] | None:
        """(type, value) of the constant declared by d with the value given by ov, or None when ov does not
        fit: then the problem is recorded and the model's own value is used, so that nothing follows from it."""
        where = "{declared}"
        expected = self.infer_top(d.expr)
        if expected is not None and d.type_expr is not None:
            at = self.type_of_annotation(d.type_expr)
            if at is not None and not self.unify(expected, at, d.expr.span, f"the value of '{d.name}'"):
                expected = None
        before = len(self.diags)
        found = self.infer_top(ov.expr)
        errors = self.diags[before:]
        del self.diags[before:]  # errors of the given value are reported once, as a usage error
        want = f"{_article(T.show(expected))} for '{d.name}' declared at {where}" if expected is not None else \
            f"a value for '{d.name}' declared at {where}"
        if found is None:
            first = errors[0] if errors else None
            if first is not None and first.code == "E0201" and "name" in first.params:
                hint = (f"A string is written in quotes: --set '{d.name}=\"{ov.text}\"'."
                        if expected is not None and T.prune(expected) == T.STRING else None)
                self.override_problem(ov, f"expected {want}, found '{first.params['name']}', a name the model "
                                      "does not declare", hint, d.pat.span)
            else:
                detail = first.message if first is not None else "it does not type-check"
                self.override_problem(ov, f"expected {want}, but {detail}", declared=d.pat.span)
            return None
        if expected is not None:
            try:
                T.unify(found, expected)
            except T.UnifyError:
                self.override_problem(ov, f"expected {want}, found {_article(T.show(found))}",
                                      declared=d.pat.span)
                return None
        try:
            value = run_deep(self.ev.eval, ov.expr, {})
        except (MLError, ArithmeticError, RecursionError) as exc:
            self.override_problem(ov, f"evaluating the value failed: {exc}")
            return None
        return found, value

    def override_problem(self, ov: Override, message: str, hint: str | None = None,
                         declared: Span | None = None) -> None:
        self.override_problems.append(OverrideProblem(ov, message, hint, declared))

    def unused_overrides(self) -> None:
        vals = [n for n, s in self.globals.items() if s.kind == "val"]
        for name in sorted(set(self.overrides) - self.used_overrides):
            cand = did_you_mean(name, vals)
            self.override_problem(self.overrides[name], f"the model has no constant 'val {name}'",
                                  f"Did you mean '{cand}'?" if cand else
                                  "Only constants declared with 'val' can be set" +
                                  (f"; this model has {', '.join(sorted(vals))}." if vals else
                                   "; this model has none."))

    def note_overrides(self, errors: list) -> None:
        """A model error on a line that names a constant given from outside says so (the value may be why)."""
        used = [self.overrides[n] for n in sorted(self.used_overrides)]
        if not used:
            return
        lines = self.model.source.splitlines()
        for d in errors:
            if d.span is None or d.span.file != self.file or not 1 <= d.span.line <= len(lines):
                continue
            for ov in used:
                if re.search(rf"(?<![\w'])(?<!\w\.){re.escape(ov.name)}(?![\w'])", lines[d.span.line - 1]):
                    d.notes.append(f"'{ov.name}' is given with {ov}")

    def raise_override_problems(self) -> None:
        if self.override_problems:
            raise usage_error(self.override_problems)
