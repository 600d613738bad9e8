"""A small XML element tree that remembers where each element starts, for diagnostics of foreign formats.

ElementTree drops positions; this tree is built with `xml.parsers.expat` so that every element knows the
line and column of its start tag (and of its first character data). Namespaces are stripped (PNML uses
one). External entities are never fetched. Imports the standard library and layer 0 only.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from xml.parsers import expat

from cpn.diagnostics import Diagnostic, Span
from cpn.errors import ModelError


@dataclass(slots=True, eq=False)
class Element:
    """One XML element: local tag name, attributes, children, its own text, and positions."""

    tag: str
    attrib: dict[str, str]
    line: int
    col: int
    children: list[Element] = field(default_factory=list)
    text: str = ""
    text_line: int = 0
    text_col: int = 0

    @property
    def attrs(self) -> dict[str, str]:
        return self.attrib

    def get(self, name: str, default: str | None = None) -> str | None:
        return self.attrib.get(name, default)

    def find(self, *path: str) -> Element | None:
        """The first element reached by following child tags `path`, or None."""
        node: Element | None = self
        for tag in path:
            if node is None:
                return None
            node = next((c for c in node.children if c.tag == tag), None)
        return node

    def findall(self, tag: str) -> list[Element]:
        return [c for c in self.children if c.tag == tag]

    def iter(self, tag: str | None = None) -> Iterator[Element]:
        """Every element of the subtree (this one included), depth first, in document order."""
        stack = [self]
        while stack:
            node = stack.pop()
            if tag is None or node.tag == tag:
                yield node
            stack.extend(reversed(node.children))

    def elements(self) -> list[Element]:
        """The children, without PNML's layout-only elements (graphics, toolspecific)."""
        return [c for c in self.children if c.tag not in ("graphics", "toolspecific")]

    def child_text(self, tag: str) -> str:
        """The text of the `<text>` of child `tag` (CPN Tools' inscription layout), or ''."""
        child = self.find(tag, "text")
        return child.text if child is not None else ""

    def span(self, file: str) -> Span:
        return Span(file, self.line, self.col)


def _local(name: str) -> str:
    # expat with namespace_separator gives "uri local"; keep the local part
    return name.rsplit(" ", 1)[-1]


def parse_xml(data: bytes | str, path: str, *, strip_text: bool, malformed: str, empty: str,
              hint: str) -> Element:
    """Parse a whole document; malformed XML raises `ModelError` E0501 with `malformed` and `hint`."""
    parser = expat.ParserCreate(namespace_separator=" ")
    parser.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
    root: list[Element] = []
    stack: list[Element] = []
    texts: list[list[str]] = []

    def start(name, attrs):
        el = Element(_local(name), {_local(k): v for k, v in attrs.items()},
                     parser.CurrentLineNumber, parser.CurrentColumnNumber + 1)
        if stack:
            stack[-1].children.append(el)
        else:
            root.append(el)
        stack.append(el)
        texts.append([])

    def end(name):
        el = stack.pop()
        text = "".join(texts.pop())
        el.text = text.strip() if strip_text else text

    def chars(data):
        if texts:
            if not texts[-1]:
                stack[-1].text_line = parser.CurrentLineNumber
                stack[-1].text_col = parser.CurrentColumnNumber + 1
            texts[-1].append(data)

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.CharacterDataHandler = chars
    try:
        parser.Parse(data, True)
    except expat.ExpatError as exc:
        raise ModelError([Diagnostic("E0501", f"{malformed}: {expat.ErrorString(exc.code)}",
                                     Span(path, exc.lineno, exc.offset + 1), hint=hint)]) from None
    if not root:
        raise ModelError([Diagnostic("E0501", empty, Span(path, 1, 1))])
    return root[0]
