"""Reading PNML with positions: the shared tree of `cpn.io.xmltree`, with this format's messages."""

from __future__ import annotations

from cpn.io.xmltree import Element
from cpn.io.xmltree import parse_xml as _parse_xml

__all__ = ["Element", "parse_xml"]


def parse_xml(data: bytes, filename: str) -> Element:
    """Parse a PNML document into `Element`s; malformed XML raises `ModelError` E0501."""
    return _parse_xml(
        data, filename, strip_text=True, malformed="the file is not well-formed XML",
        empty="the file contains no XML element",
        hint="Check that the file is a complete PNML document (it may be truncated or not XML at all).")
