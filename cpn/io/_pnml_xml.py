"""A small XML tree that remembers where each element starts, for PNML diagnostics.

ElementTree drops line numbers, so PNML is read with `xml.parsers.expat` into `Element`s that keep the
line and column of their start tag. Namespaces are stripped (PNML uses one). Imports the stdlib and
`cpn.diagnostics`/`cpn.errors` only.
"""

from __future__ import annotations

import xml.parsers.expat
from collections.abc import Iterator
from dataclasses import dataclass, field

from cpn.diagnostics import Diagnostic, Span
from cpn.errors import ModelError


@dataclass(slots=True, eq=False)
class Element:
    """One XML element: local tag name, attributes, children, text, and the position of its start tag."""

    tag: str
    attrib: dict[str, str]
    line: int
    col: int
    children: list[Element] = field(default_factory=list)
    text: str = ""

    def get(self, name: str, default: str | None = None) -> str | None:
        return self.attrib.get(name, default)

    def find(self, *path: str) -> Element | None:
        """The first descendant reached by following child tags `path`, or None."""
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
        """The children, ignoring PNML's layout-only elements (graphics, toolspecific)."""
        return [c for c in self.children if c.tag not in ("graphics", "toolspecific")]

    def span(self, file: str) -> Span:
        return Span(file, self.line, self.col)


def _local(name: str) -> str:
    # expat with namespace_separator gives "uri local"; keep the local part.
    return name.rsplit(" ", 1)[-1]


def parse_xml(data: bytes, filename: str) -> Element:
    """Parse an XML document into `Element`s; malformed XML raises `ModelError` E0501."""
    parser = xml.parsers.expat.ParserCreate(namespace_separator=" ")
    root: list[Element] = []
    stack: list[Element] = []
    texts: list[list[str]] = []

    def start(name: str, attrs: dict[str, str]) -> None:
        el = Element(_local(name), {_local(k): v for k, v in attrs.items()},
                     parser.CurrentLineNumber, parser.CurrentColumnNumber + 1)
        if stack:
            stack[-1].children.append(el)
        else:
            root.append(el)
        stack.append(el)
        texts.append([])

    def end(name: str) -> None:
        el = stack.pop()
        el.text = "".join(texts.pop()).strip()

    def chars(data: str) -> None:
        if texts:
            texts[-1].append(data)

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.CharacterDataHandler = chars
    try:
        parser.Parse(data, True)
    except xml.parsers.expat.ExpatError as exc:
        raise ModelError([Diagnostic(
            "E0501", f"the file is not well-formed XML: {xml.parsers.expat.ErrorString(exc.code)}",
            Span(filename, exc.lineno, exc.offset + 1),
            hint="Check that the file is a complete PNML document (it may be truncated or not XML at all).",
        )]) from None
    if not root:
        raise ModelError([Diagnostic("E0501", "the file contains no XML element", Span(filename, 1, 1))])
    return root[0]
