"""Positions and diagnostics: `Span`, `Diagnostic`, the registry of message codes, and rendering.

Imports the standard library only.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field


@dataclass(frozen=True, slots=True)
class Span:
    """A range of source text: 1-based line and column, end inclusive of the last character."""

    file: str
    line: int
    col: int
    end_line: int | None = None
    end_col: int | None = None

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.col}"


class Severity(enum.Enum):
    ERROR = "error"
    WARNING = "warning"


# every code a diagnostic is emitted with -> its short title (a test keeps the two the same)
CODES: dict[str, str] = {
    # syntax
    "E0101": "syntax error",
    "E0102": "unterminated comment or string",
    # names
    "E0201": "unknown name",
    "E0202": "duplicate declaration",
    "E0203": "arc between two places or two transitions",
    "E0204": "bad module instance",
    "E0205": "bad fusion set",
    "E0206": "unsupported construct",
    # types
    "E0301": "type mismatch",
    "E0302": "unbound variable",
    "E0303": "value outside its colour set",
    "E0304": "bad colour set",
    "E0305": "bad constant override",
    # evaluation while firing
    "E0401": "evaluation error",
    "E0402": "token outside its colour set",
    # foreign formats
    "E0501": "unreadable file",
    "E0502": "unsupported element",
    # options that do not apply to the model
    "E0601": "option not applicable to the model",
    "E0602": "declared symmetry is not a symmetry of the net",
    # scenario files (docs/specs.md)
    "E0701": "scenario file is not valid TOML",
    "E0702": "bad scenario key or value",
    "E0703": "name not in the net",
    "E0704": "bad parameter table",
    # warnings
    "W0101": "unbound port",
    "W0103": "empty model",
}


@dataclass(slots=True)
class Diagnostic:
    """A message about a model: a stable code, a position, typed parameters, and text."""

    code: str
    message: str
    span: Span | None = None
    hint: str | None = None
    notes: list[str] = field(default_factory=list)
    params: dict = field(default_factory=dict)
    severity: Severity = Severity.ERROR

    def sort_key(self):
        s = self.span
        return (s.file, s.line, s.col) if s else ("", 0, 0)

    def render(self, source: str | None = None) -> str:
        return render(self, source)


def _source_line(source: str | None, line: int) -> str | None:
    if source is None:
        return None
    lines = source.splitlines()
    if 1 <= line <= len(lines):
        # invisible characters (NUL, other controls) are shown as U+FFFD so that the caret still lines up
        return "".join(c if c.isprintable() else "\ufffd" for c in lines[line - 1].expandtabs(1))
    return None


def render(diag: Diagnostic, source: str | None = None) -> str:
    """Render a diagnostic in the house style: position, code, message, source line, caret, hint."""
    sev = diag.severity.value
    head = f"{diag.span}: {sev}[{diag.code}]: {diag.message}" if diag.span else f"{sev}[{diag.code}]: {diag.message}"
    out = [head]
    if diag.span is not None:
        text = _source_line(source, diag.span.line)
        if text is not None:
            num = str(diag.span.line)
            pad = " " * len(num)
            col = max(diag.span.col, 1)
            if diag.span.end_line == diag.span.line and diag.span.end_col and diag.span.end_col >= col:
                width = diag.span.end_col - col + 1
            else:
                width = 1
            width = max(1, min(width, max(1, len(text) - col + 1)))
            out.append(f"{pad} |")
            out.append(f"{num} | {text}")
            out.append(f"{pad} | {' ' * (col - 1)}{'^' * width}")
    for note in diag.notes:
        out.append(f"note: {note}")
    if diag.hint:
        out.append(f"hint: {diag.hint}")
    return "\n".join(out)
