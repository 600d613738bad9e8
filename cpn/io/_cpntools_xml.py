"""A minimal XML element tree with line and column positions, for reading CPN Tools `.cpn` files.

ElementTree drops positions; this tree is built with `xml.parsers.expat` so that every element knows
where it starts in the file. Imports the standard library and `cpn.diagnostics`/`cpn.errors` only.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from xml.parsers import expat

from cpn.diagnostics import Diagnostic, Span
from cpn.errors import ModelError


@dataclass(slots=True)
class Element:
    """One XML element: tag, attributes, children, concatenated character data and its position."""

    tag: str
    attrs: dict[str, str]
    line: int
    col: int
    children: list[Element] = field(default_factory=list)
    parts: list[str] = field(default_factory=list)
    text_line: int = 0
    text_col: int = 0

    @property
    def text(self) -> str:
        """The element's own character data (not that of its children)."""
        return "".join(self.parts)

    def find(self, tag: str) -> Element | None:
        for child in self.children:
            if child.tag == tag:
                return child
        return None

    def findall(self, tag: str) -> list[Element]:
        return [c for c in self.children if c.tag == tag]

    def iter(self, tag: str):
        """Every descendant (and self) with this tag, in document order."""
        stack = [self]
        while stack:
            node = stack.pop()
            if node.tag == tag:
                yield node
            stack.extend(reversed(node.children))

    def child_text(self, tag: str) -> str:
        """The text of the `<text>` of child `tag` (CPN Tools' inscription layout), or ''."""
        child = self.find(tag)
        if child is None:
            return ""
        t = child.find("text")
        return t.text if t is not None else ""


def parse_xml(data: bytes, path: str) -> Element:
    """Parse a whole document into an `Element` tree; raise `ModelError` (E0501) if it is not XML."""
    parser = expat.ParserCreate()
    root_holder: list[Element] = []
    stack: list[Element] = []

    def start(tag, attrs):
        el = Element(tag, dict(attrs), parser.CurrentLineNumber, parser.CurrentColumnNumber + 1)
        if stack:
            stack[-1].children.append(el)
        else:
            root_holder.append(el)
        stack.append(el)

    def end(tag):
        stack.pop()

    def chars(data):
        if stack:
            el = stack[-1]
            if not el.parts:
                el.text_line = parser.CurrentLineNumber
                el.text_col = parser.CurrentColumnNumber + 1
            el.parts.append(data)

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.CharacterDataHandler = chars
    # The DOCTYPE names an external DTD on a server that no longer exists: never fetch it.
    parser.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
    try:
        parser.Parse(data, True)
    except expat.ExpatError as exc:
        raise ModelError([Diagnostic(
            "E0501", f"not a well-formed CPN Tools file: {expat.ErrorString(exc.code)}",
            Span(path, exc.lineno, exc.offset + 1),
            hint="Open and save the model again in CPN Tools, or check that the file was not truncated.",
        )]) from None
    if not root_holder:
        raise ModelError([Diagnostic("E0501", "empty XML document", Span(path, 1, 1))])
    return root_holder[0]
