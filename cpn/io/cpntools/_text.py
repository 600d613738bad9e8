"""The generated `.cpnet` text of a CPN Tools net and the origin of every piece of it.

`Translation.locate` maps a position of the generated text back to the `.cpn` file. Imports
`cpn.diagnostics`, the CPN Tools XML tree and the standard library only.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from cpn.diagnostics import Span
from cpn.io.cpntools import _ml as ml
from cpn.io.cpntools._xml import Element


@dataclass(frozen=True, slots=True)
class Origin:
    """Where a piece of generated text comes from in the `.cpn` file."""

    line: int
    col: int
    element: str  # XML id, e.g. "ID1234"
    page: str | None  # page name, None for the globbox
    what: str  # e.g. "arc inscription of 'Send Packet'"
    file: str | None = None  # the file the text is in, where it is not the `.cpn` file (a `use`d `.sml` file)

    def describe(self) -> str:
        where = f" on page '{self.page}'" if self.page else ""
        in_file = f" of {self.file}" if self.file else ""
        return f"{self.what} ({self.element}{where}) at line {self.line}{in_file}"


@dataclass(slots=True)
class _Piece:
    gen_line: int  # first line in the generated text (1-based)
    gen_col: int  # column where the piece starts
    n_lines: int
    origin: Origin
    exact: bool  # True if the piece is the verbatim text of the XML element


@dataclass(slots=True)
class Translation:
    """The `.cpnet` text of a `.cpn` file and the origin of every generated statement."""

    path: str
    text: str
    pieces: list[_Piece] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    raw_lines: list[str] = field(default_factory=list)  # the `.cpn` file's lines, entities not decoded
    untyped_arcs: dict[str, str] = field(default_factory=dict)  # arc id -> its place without a colour set

    def origin(self, line: int, col: int = 1) -> Span | None:
        """The span in the `.cpn` file that position (line, col) of the text translates (`cpn.io.Translation`)."""
        found = self.locate(line, col)
        return found[0] if found is not None else None

    def locate(self, line: int, col: int = 1) -> tuple[Span, Origin] | None:
        """Map a (line, col) of the generated text to a span in the `.cpn` file and the element's origin."""
        best = None
        for p in self.pieces:
            if p.gen_line <= line < p.gen_line + p.n_lines:
                if line == p.gen_line and col < p.gen_col:
                    continue
                # the verbatim text of an element before the statement; of two, the one that starts last
                # (a guard and a delay on one line: a position in the delay is the delay's)
                if (best is None or (p.exact and not best.exact)
                        or (p.exact == best.exact and (p.gen_line, p.gen_col) > (best.gen_line, best.gen_col))):
                    best = p
        if best is None:
            return None
        o = best.origin
        if best.exact and o.file is not None:  # the text of another file, as it is: no entities
            dl = line - best.gen_line
            return Span(o.file, o.line + dl, (o.col + max(col - best.gen_col, 0)) if dl == 0 else col), o
        if best.exact:
            dl = line - best.gen_line
            if dl == 0:
                return Span(self.path, o.line, self._raw_col(o.line, o.col, max(col - best.gen_col, 0))), o
            return Span(self.path, o.line + dl, self._raw_col(o.line + dl, 1, col - 1)), o
        return Span(o.file or self.path, o.line, o.col), o

    def _raw_col(self, line: int, col: int, chars: int) -> int:
        """The column `chars` characters of element text after (line, col) of the file: an entity or
        character reference (`&gt;`, `&#60;`) is one character of the text and several of the file."""
        if not 0 < line <= len(self.raw_lines):
            return col + chars
        raw = self.raw_lines[line - 1]
        i = col - 1
        while chars > 0 and i < len(raw):
            end = raw.find(";", i) if raw[i] == "&" else -1
            i = end + 1 if end != -1 else i + 1
            chars -= 1
        return i + 1 + chars


class _Out:
    """The generated text, line by line, with the origin of every piece."""

    def __init__(self) -> None:
        self.lines: list[str] = []
        self.pieces: list[_Piece] = []

    @property
    def next_line(self) -> int:
        return len(self.lines) + 1

    def raw(self, text: str = "") -> None:
        self.lines.extend(text.split("\n"))

    def stmt(self, parts: list[tuple[str, Origin | None]], origin: Origin, indent: str = "") -> None:
        """Write one statement made of parts; a part with an Origin is verbatim text of that element."""
        line = self.next_line
        self.pieces.append(_Piece(line, 1, 1, origin, False))
        buf = indent
        cur_line = line
        for text, porigin in parts:
            if porigin is not None:
                col = len(buf.rsplit("\n", 1)[-1]) + 1
                n = text.count("\n") + 1
                self.pieces.append(_Piece(cur_line, col, n, porigin, True))
            buf += text
            cur_line = line + buf.count("\n")
        comment = f"  (* {origin.element}" + (f" on page {origin.page}" if origin.page else "") + f", line {origin.line} *)"
        buf += comment
        n_lines = buf.count("\n") + 1
        self.pieces[self._first_index(line)].n_lines = n_lines
        self.lines.extend(buf.split("\n"))

    def _first_index(self, line: int) -> int:
        for i in range(len(self.pieces) - 1, -1, -1):
            if self.pieces[i].gen_line == line and not self.pieces[i].exact:
                return i
        raise AssertionError("statement piece missing")


def _clean(text: str) -> str:
    """Inscription text without surrounding white space, with Unix line ends."""
    return text.replace("\r\n", "\n").replace("\r", "\n").strip()


def _text_origin(el: Element | None, elem_id: str, page: str | None, what: str,
                 owner: Element | None = None) -> Origin:
    """Origin of the `<text>` of an inscription element (its character data, to the column); where the
    element is missing (files written by other tools leave out an empty `<annot>`), its owner's start."""
    if el is None:
        where = owner if owner is not None else Origin(1, 1, elem_id, page, what)
        return Origin(where.line, where.col, elem_id, page, what)
    t = el.find("text")
    if t is not None and t.text:
        # The char data starts where expat reported it; leading white space is stripped by _clean.
        raw = t.text.replace("\r\n", "\n")
        lead = raw[: len(raw) - len(raw.lstrip())]
        line = t.text_line + lead.count("\n")
        col = (len(lead.rsplit("\n", 1)[-1]) + 1) if "\n" in lead else t.text_col + len(lead)
        return Origin(line, col, elem_id, page, what)
    return Origin(el.line, el.col, elem_id, page, what)


def _text_origin_from(line: int, col: int, lead: str, origin: Origin) -> Origin:
    if "\n" in lead:
        return Origin(line + lead.count("\n"), len(lead.rsplit("\n", 1)[-1]) + 1, origin.element, origin.page,
                      origin.what, origin.file)
    return Origin(line, col + len(lead), origin.element, origin.page, origin.what, origin.file)


def _balanced_outer(text: str) -> bool:
    """True if the opening '[' of text is closed by its final ']' (a guard list, not '[a] @ [b]')."""
    depth = 0
    clean = ml.strip_comments(text)
    in_str = False
    for i, ch in enumerate(clean):
        if ch == '"' and (i == 0 or clean[i - 1] != "\\"):
            in_str = not in_str
        if in_str:
            continue
        if ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
            if depth == 0 and i != len(clean) - 1:
                return False
    return True


def _timed_literals(text: str) -> str:
    """CPN Tools writes a timed token as `x@t` (time stamp t); `.cpnet` writes `x @+ t` (the clock is 0)."""
    return re.sub(r"@(?![+@])\s*", "@+ ", text)


def _short(text: str, n: int = 40) -> str:
    one = " ".join(text.split())
    return one if len(one) <= n else one[: n - 3] + "..."
