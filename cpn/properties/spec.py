"""A property as a scenario file states it: its kind and fields (`KINDS`, docs/specs.md), the spans of its
values and where the characters of its texts lie in the file (`TextOrigin`), so that an error in a property
text points at its line and column in the file. Imports the standard library and layer 0 only.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from cpn.diagnostics import Span

# kind -> (required fields, optional fields); every kind also takes name and description
KINDS: dict[str, tuple[set, set]] = {
    "invariant": ({"expr"}, set()),
    "reachable": ({"expr"}, set()),
    "deadlock_free": (set(), set()),
    "dead_markings": (set(), {"count", "count_modulo_time", "expr"}),
    "bound": (set(), {"place", "expr", "upper_equals", "lower_equals", "at_most", "at_least",
                      "upper_multiset_equals", "lower_multiset_equals", "at_most_multiset", "at_least_multiset",
                      "upper", "lower", "upper_multiset", "lower_multiset"}),
    "dead_transitions": ({"expected"}, set()),
    "live_transitions": (set(), {"transitions"}),
    "home": (set(), {"expr", "initial"}),
    "no_livelock": (set(), {"progress"}),
    "ctl": ({"formula"}, {"fairness"}),
    "ltl": ({"formula"}, {"weak_fairness", "strong_fairness"}),
}
# a `bound` property's limits (docs/specs.md): an exact one is written `upper_equals`, ...; `upper`, ... are
# its older spellings, still read with the same meaning
BOUND_INTEGER = ("upper_equals", "lower_equals", "at_most", "at_least")
BOUND_MULTISET = ("upper_multiset_equals", "lower_multiset_equals", "at_most_multiset", "at_least_multiset")
BOUND_OLD_SPELLINGS = {"upper": "upper_equals", "lower": "lower_equals", "upper_multiset": "upper_multiset_equals",
                       "lower_multiset": "lower_multiset_equals"}


@dataclass(frozen=True)
class TextOrigin:
    """Where the characters of a string value lie in the file: `offsets[i]` is the file offset of char i."""

    file: str
    source: str
    offsets: tuple

    def __repr__(self) -> str:
        return f"TextOrigin({self.span(0, len(self.offsets) - 2)})"

    def span(self, start: int, end: int | None = None) -> Span:
        """The file span of value characters start..end (end inclusive; clamped to the value)."""
        n = len(self.offsets) - 1
        a = self.offsets[max(0, min(start, n))]
        b = self.offsets[max(0, min(end if end is not None else start, n))]
        la, ca = line_col(self.source, a)
        lb, cb = line_col(self.source, b)
        return Span(self.file, la, ca, lb, cb)


@dataclass
class PropertySpec:
    index: int  # 1-based position in the file
    name: str
    kind: str
    fields: dict
    span: Span  # the property's `kind` value (or its table header)
    spans: dict = field(default_factory=dict)  # field -> Span of its value
    texts: dict = field(default_factory=dict)  # field -> TextOrigin (string fields only)
    description: str = ""
    source: str = ""  # the scenario file's text (for positions inside arrays)
    expect: str = "holds"  # the verdict the gate expects: 'violated' for a mutant that must be caught

    def __repr__(self) -> str:
        # short: the dataclass's own repr prints the scenario file's text once per field that holds it
        return f"PropertySpec({self.index}, {self.name!r}, kind={self.kind!r}, at {self.span})"


def line_col(text: str, offset: int) -> tuple[int, int]:
    """The 1-based line and column of `offset` in `text`."""
    line = text.count("\n", 0, offset) + 1
    col = offset - (text.rfind("\n", 0, offset) + 1) + 1
    return line, col


__all__ = ["BOUND_INTEGER", "BOUND_MULTISET", "BOUND_OLD_SPELLINGS", "KINDS", "PropertySpec", "TextOrigin", "line_col"]
