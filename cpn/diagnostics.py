"""Positions and diagnostics: `Span`, `Diagnostic`, the registry of message codes, and rendering.

Imports the standard library only.
"""

from __future__ import annotations

import enum
import re
import unicodedata
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
    "W0102": "delay without effect",
    "W0103": "empty model",
    "W0104": "random draw explored as a choice",
    "W0105": "random draw: simulation only",
    "W0106": "real time, reference or side effect: simulation only",
    "W0701": "scenario states no property",
    "W0702": "property holds vacuously",
    "W0703": "property follows from the net's structure",
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


def display_width(text: str) -> int:
    """The number of terminal cells `text` takes: 2 for a wide (CJK) or full-width character, 0 for a combining
    mark, 1 for any other (unicodedata.east_asian_width)."""
    if text.isascii():
        return len(text)
    return sum(_cell(c) for c in text)


def _cell(c: str) -> int:
    if unicodedata.combining(c):
        return 0
    return 2 if unicodedata.east_asian_width(c) in ("W", "F") else 1


def ljust_cells(text: str, width: int) -> str:
    """`text` padded with spaces to `width` terminal cells (str.ljust counts characters)."""
    return text + " " * max(0, width - display_width(text))


# the widest source line a diagnostic shows whole; a longer one is shown as a window around the column
SOURCE_WIDTH: int = 100
# columns of context shown before the column in such a window
SOURCE_CONTEXT: int = 40
ELLIPSIS: str = "..."


def _source_line(source: str | None, line: int) -> str | None:
    if source is None:
        return None
    lines = source.splitlines()
    if 1 <= line <= len(lines):
        # invisible characters (NUL, other controls) are shown as U+FFFD so that the caret still lines up
        return "".join(c if c.isprintable() else "\ufffd" for c in lines[line - 1].expandtabs(1))
    return None


def excerpt(text: str, col: int, width: int = 1, limit: int = SOURCE_WIDTH) -> tuple[str, str]:
    """A source line and the caret line under columns col..col+width-1 (1-based, in characters), both at
    most about `limit` terminal cells wide: a longer line is cut to a window around the column, each cut
    end marked with an ellipsis. The caret is placed by display width, so that it stays under its character
    after wide (CJK) characters.

    >>> excerpt("val x = 1 $ 2;", 11)
    ('val x = 1 $ 2;', '          ^')
    >>> shown, caret = excerpt("x" * 1000 + "$" + "y" * 1000, 1001)
    >>> len(shown) <= 110, shown.startswith("..."), shown.endswith("..."), shown[len(caret) - 1]
    (True, True, True, '$')
    """
    col = max(1, min(col, len(text) + 1))
    width = max(1, min(width, len(text) - col + 1))
    if display_width(text) <= limit:
        return text, " " * display_width(text[:col - 1]) + "^" * max(1, display_width(text[col - 1:col - 1 + width]))
    before = min(col - 1, SOURCE_CONTEXT)
    start = col - 1 - before
    # the marked text, the context before it and the context after it share the limit
    width = min(width, max(1, limit - before - 2 * len(ELLIPSIS)))
    end = start
    used = 0
    while end < len(text) and used + _cell(text[end]) <= limit:
        used += _cell(text[end])
        end += 1
    end = max(end, col - 1 + width)
    head = ELLIPSIS if start > 0 else ""
    tail = ELLIPSIS if end < len(text) else ""
    shown = head + text[start:end] + tail
    pad = len(head) + display_width(text[start:col - 1])
    return shown, " " * pad + "^" * max(1, display_width(text[col - 1:col - 1 + width]))


def render(diag: Diagnostic, source: str | None = None) -> str:
    """Render a diagnostic in the house style: position, code, message, source line, caret, hint."""
    sev = diag.severity.value
    message = shorten_words(diag.message)
    head = f"{diag.span}: {sev}[{diag.code}]: {message}" if diag.span else f"{sev}[{diag.code}]: {message}"
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
            shown, caret = excerpt(text, col, width)
            out.append(f"{pad} |")
            out.append(f"{num} | {shown}")
            out.append(f"{pad} | {caret}")
    for note in diag.notes:
        out.append(f"note: {shorten_words(note)}")
    if diag.hint:
        out.append(f"hint: {shorten_words(diag.hint)}")
    return "\n".join(out)


# a scenario file's text: a property table, or the key that names the model (docs/specs.md)
_SCENARIO_TEXT = re.compile(r"^[ \t]*(\[\[property\]\]|model[ \t]*=)", re.MULTILINE)
# a model's text: a statement keyword at the start of a line, not a TOML key (`place = "P'A 1"`)
_MODEL_TEXT = re.compile(r"^[ \t]*(net|colset|var|val|fun|place|port|trans|arc|module|instance)[ \t]+[^=\s]",
                         re.MULTILINE)


def other_command_hint(path: str, text: str, reading: str) -> str | None:
    """The hint for a file given to the wrong command: a scenario file read as a model (`reading="model"`,
    by `lint`, `explore`, `simulate`) or a model read as a scenario file (`reading="scenario"`, by `check`);
    None if the text does not look like the other kind.

    >>> other_command_hint("s.toml", 'model = "m.cpnet"', "model").split(":")[0]
    "'s.toml' is a scenario file, not a model"
    >>> other_command_hint("m.cpnet", "net M;\\ncolset C = int;", "scenario").split(":")[0]
    "'m.cpnet' is a model, not a scenario file"
    """
    if reading == "model" and _SCENARIO_TEXT.search(text):
        return (f"'{path}' is a scenario file, not a model: run its properties with 'cpn-verify check {path}' "
                "(lint, explore and simulate read models: .cpnet, .pnml, .cpn).")
    if reading == "scenario" and _MODEL_TEXT.search(text):
        return (f"'{path}' is a model, not a scenario file: lint it with 'cpn-verify lint {path}' or explore it "
                f"with 'cpn-verify explore {path}'. 'check' runs scenario files (.toml), which name a model and the "
                "properties it must have (docs/specs.md).")
    return None


# a word (a run without spaces: a name, a value, a token) longer than this is cut in rendered messages
LONG_WORD: int = 100
_LONG_WORD = re.compile(r"\S{%d,}" % (LONG_WORD + 1))


def shorten_words(text: str) -> str:
    """`text` with every word longer than LONG_WORD characters cut in its middle, saying how long it is (a
    name of 80,000 characters is quoted in a message as its start, its end and its length).

    >>> shorten_words("unknown name '" + "a" * 200 + "'")
    "unknown name 'aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa...aaaaaaaaaaaaaaaaaaaa' (200 characters)"
    """
    return _LONG_WORD.sub(_shorten, text)


def _shorten(m: re.Match) -> str:
    word = m.group()
    core = word.strip("'\"()[]{},.;:")
    if len(core) <= LONG_WORD:
        return word
    at = word.index(core)
    head, tail = word[:at], word[at + len(core):]
    return f"{head}{core[:60]}{ELLIPSIS}{core[-20:]}{tail} ({len(core):,} characters)"
