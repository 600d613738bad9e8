"""Reading CPN Tools `.cpn` XML with positions: the shared tree of `cpn.io.xmltree`, with this format's messages."""

from __future__ import annotations

from cpn.io.xmltree import Element
from cpn.io.xmltree import parse_xml as _parse_xml

__all__ = ["Element", "parse_xml"]


def parse_xml(data: bytes, path: str) -> Element:
    """Parse a whole `.cpn` document; raise `ModelError` (E0501) if it is not XML."""
    return _parse_xml(
        data, path, strip_text=False, malformed="not a well-formed CPN Tools file", empty="empty XML document",
        hint="Open and save the model again in CPN Tools, or check that the file was not truncated.")
