"""The Model Checking Contest's property files: XML to a neutral formula tree.

A property file (`<property-set>` of `<property>`, each with an `<id>` and a `<formula>`) of any of the
seven examinations (ReachabilityCardinality, ReachabilityFireability, CTLCardinality, CTLFireability,
LTLCardinality, LTLFireability, UpperBounds) becomes a list of `ContestProperty`, whose `formula` is a
tree of the classes below:

- path quantifiers `Quant("A" | "E", f)` (`all-paths`, `exists-path`) and temporal operators
  `Temporal("X" | "F" | "G" | "U", args)` (`next`, `finally`, `globally`, `until` with `before` and
  `reach`);
- Boolean connectives `Not`, `And`, `Or` (`negation`, `conjunction`, `disjunction`) and `Bool`;
- atoms: `IntLe(a, b)` (`integer-le`) over `IntConst` and `Tokens(places)` (`tokens-count`: the sum of
  the tokens of the places; over a coloured place, all its tokens whatever their colour), and
  `Fireable(transitions)` (`is-fireable`: one of the transitions has an enabled binding);
- `PlaceBound(places)` (`place-bound`, the formula of UpperBounds): the largest number of tokens the
  places hold together in a reachable marking.

Places and transitions are named by their PNML id. Every node keeps the line and column of its element.
An unknown element is a `ContestFormatError` with `file:line:col`. Imports `cpn.io.xmltree` (the XML tree
with positions) and the standard library.

Examples
--------
>>> props = read_text('''<property-set xmlns="http://mcc.lip6.fr/"><property><id>M-00</id>
... <formula><exists-path><finally><is-fireable><transition>t1</transition></is-fireable></finally>
... </exists-path></formula></property></property-set>''')
>>> props[0].id, show(props[0].formula)
('M-00', 'E F fireable(t1)')
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field

from cpn.diagnostics import Diagnostic, Span
from cpn.errors import ModelError
from cpn.io.xmltree import Element, parse_xml

EXAMINATIONS: tuple[str, ...] = ("ReachabilityCardinality", "ReachabilityFireability", "CTLCardinality",
                                 "CTLFireability", "LTLCardinality", "LTLFireability", "UpperBounds")


# ----------------------------------------------------------------------------- the tree
@dataclass(frozen=True)
class Node:
    line: int = field(default=0, compare=False, kw_only=True)
    col: int = field(default=0, compare=False, kw_only=True)


@dataclass(frozen=True)
class Bool(Node):
    value: bool


@dataclass(frozen=True)
class Not(Node):
    arg: Node


@dataclass(frozen=True)
class And(Node):
    args: tuple


@dataclass(frozen=True)
class Or(Node):
    args: tuple


@dataclass(frozen=True)
class Quant(Node):
    path: str  # "A" or "E"
    arg: Node


@dataclass(frozen=True)
class Temporal(Node):
    op: str  # "X", "F", "G", "U"
    args: tuple


@dataclass(frozen=True)
class IntConst(Node):
    value: int


@dataclass(frozen=True)
class Tokens(Node):
    places: tuple


@dataclass(frozen=True)
class IntLe(Node):
    left: Node
    right: Node


@dataclass(frozen=True)
class Fireable(Node):
    transitions: tuple


@dataclass(frozen=True)
class PlaceBound(Node):
    places: tuple


@dataclass(frozen=True)
class ContestProperty:
    id: str
    formula: Node
    file: str = ""
    line: int = 0

    @property
    def examination(self) -> str:
        """The examination, from the id (``<model>-<examination>-<nn>``), or ''."""
        for name in EXAMINATIONS:
            if f"-{name}-" in self.id:
                return name
        return ""


class ContestFormatError(ModelError):
    """A property file that is not the contest's XML (every problem found, each with file:line:col)."""


# ----------------------------------------------------------------------------- reading
def read_file(path: str | os.PathLike) -> list[ContestProperty]:
    """The properties of a contest property file, in file order."""
    path = os.fspath(path)
    try:
        with open(path, "rb") as fh:
            data = fh.read()
    except OSError as exc:
        raise ContestFormatError([_diag(f"cannot read the property file: {exc.strerror}", path, 1, 1,
                                        code="E0501")]) from None
    return read_text(data, path)


def read_text(data: bytes | str, filename: str = "<properties>") -> list[ContestProperty]:
    if isinstance(data, str):
        data = data.encode("utf-8")
    try:
        root = parse_xml(data, filename, strip_text=True, malformed="the property file is not well-formed XML",
                         empty="the property file contains no XML element",
                         hint="Model Checking Contest property files start with <property-set>.")
    except ModelError as exc:
        raise ContestFormatError(exc.diagnostics, exc.sources) from None
    reader = _Reader(filename)
    props = reader.property_set(root)
    if reader.problems:
        raise ContestFormatError(reader.problems)
    return props


_UNARY = {"all-paths": ("Q", "A"), "exists-path": ("Q", "E"), "finally": ("T", "F"), "globally": ("T", "G"),
          "next": ("T", "X"), "negation": ("N", None)}


class _Reader:
    def __init__(self, filename: str) -> None:
        self.file = filename
        self.problems: list = []

    def fail(self, el: Element, message: str, hint: str | None = None) -> Node:
        self.problems.append(_diag(message, self.file, el.line, el.col, hint))
        return Bool(True, line=el.line, col=el.col)

    def property_set(self, root: Element) -> list[ContestProperty]:
        if root.tag != "property-set":
            self.fail(root, f"expected <property-set>, found <{root.tag}>",
                      "Model Checking Contest property files start with <property-set>.")
            return []
        out = []
        for p in root.children:
            if p.tag != "property":
                self.fail(p, f"expected <property>, found <{p.tag}>")
                continue
            ident = p.find("id")
            formula = p.find("formula")
            if ident is None or formula is None or len(formula.children) != 1:
                self.fail(p, "a <property> needs an <id> and a <formula> with one element")
                continue
            out.append(ContestProperty(ident.text.strip(), self.node(formula.children[0]), self.file, p.line))
        return out

    def node(self, el: Element) -> Node:
        pos = {"line": el.line, "col": el.col}
        tag, kids = el.tag, el.children
        if tag in _UNARY:
            if len(kids) != 1:
                return self.fail(el, f"<{tag}> takes one element, found {len(kids)}")
            kind, op = _UNARY[tag]
            arg = self.node(kids[0])
            if kind == "Q":
                return Quant(op, arg, **pos)
            return Temporal(op, (arg,), **pos) if kind == "T" else Not(arg, **pos)
        if tag in ("conjunction", "disjunction"):
            if not kids:
                return self.fail(el, f"<{tag}> needs at least one element")
            args = tuple(self.node(k) for k in kids)
            return And(args, **pos) if tag == "conjunction" else Or(args, **pos)
        if tag == "until":
            before, reach = el.find("before"), el.find("reach")
            if before is None or reach is None or len(before.children) != 1 or len(reach.children) != 1:
                return self.fail(el, "<until> needs <before> and <reach>, each with one element")
            return Temporal("U", (self.node(before.children[0]), self.node(reach.children[0])), **pos)
        if tag in ("true", "false"):
            return Bool(tag == "true", **pos)
        if tag == "integer-le":
            if len(kids) != 2:
                return self.fail(el, f"<integer-le> compares two integers, found {len(kids)} elements")
            return IntLe(self.integer(kids[0]), self.integer(kids[1]), **pos)
        if tag == "is-fireable":
            return Fireable(self.names(el, "transition"), **pos)
        if tag == "place-bound":
            return PlaceBound(self.names(el, "place"), **pos)
        return self.fail(el, f"unknown element <{tag}> in a formula",
                         "The contest's formulas use all-paths, exists-path, next, finally, globally, until, "
                         "negation, conjunction, disjunction, integer-le, tokens-count, is-fireable, place-bound.")

    def integer(self, el: Element) -> Node:
        pos = {"line": el.line, "col": el.col}
        if el.tag == "integer-constant":
            try:
                return IntConst(int(el.text.strip()), **pos)
            except ValueError:
                return self.fail(el, f"<integer-constant> holds '{el.text.strip()}', not an integer")
        if el.tag == "tokens-count":
            return Tokens(self.names(el, "place"), **pos)
        return self.fail(el, f"<{el.tag}> is not an integer expression",
                         "Integers are <integer-constant> or <tokens-count>.")

    def names(self, el: Element, tag: str) -> tuple:
        out = []
        for k in el.children:
            if k.tag != tag:
                self.fail(k, f"<{el.tag}> lists <{tag}> elements, found <{k.tag}>")
            else:
                out.append(k.text.strip())
        return tuple(out)  # may be empty: the contest writes <place-bound/> for a bound of no place (0)


def _diag(message: str, file: str, line: int, col: int, hint: str | None = None, code: str = "E0502") -> Diagnostic:
    return Diagnostic(code, message, Span(file, line, col), hint=hint)


# ----------------------------------------------------------------------------- structure
def is_state_formula(f: Node) -> bool:
    """Whether f has no path quantifier and no temporal operator (an atom of the temporal logics)."""
    if isinstance(f, (Quant, Temporal)):
        return False
    if isinstance(f, Not):
        return is_state_formula(f.arg)
    if isinstance(f, (And, Or)):
        return all(is_state_formula(a) for a in f.args)
    return True


def is_ltl(f: Node) -> bool:
    """Whether f is ``A phi`` with phi free of path quantifiers (the contest's LTL examinations)."""
    return isinstance(f, Quant) and f.path == "A" and _no_quantifier(f.arg)


def _no_quantifier(f: Node) -> bool:
    if isinstance(f, Quant):
        return False
    if isinstance(f, (Temporal, And, Or)):
        return all(_no_quantifier(a) for a in f.args)
    if isinstance(f, Not):
        return _no_quantifier(f.arg)
    return True


def show(f: Node) -> str:
    """A compact text of a formula (for messages and reports)."""
    if isinstance(f, Bool):
        return "true" if f.value else "false"
    if isinstance(f, Not):
        return f"!{show(f.arg)}"
    if isinstance(f, (And, Or)):
        sym = " && " if isinstance(f, And) else " || "
        return "(" + sym.join(show(a) for a in f.args) + ")"
    if isinstance(f, Quant):
        return f"{f.path} {show(f.arg)}"
    if isinstance(f, Temporal):
        if f.op == "U":
            return f"({show(f.args[0])} U {show(f.args[1])})"
        return f"{f.op} {show(f.args[0])}"
    if isinstance(f, IntLe):
        return f"{show(f.left)} <= {show(f.right)}"
    if isinstance(f, IntConst):
        return str(f.value)
    if isinstance(f, Tokens):
        return "tokens(" + ", ".join(f.places) + ")"
    if isinstance(f, Fireable):
        return "fireable(" + ", ".join(f.transitions) + ")"
    if isinstance(f, PlaceBound):
        return "bound(" + ", ".join(f.places) + ")"
    raise TypeError(f"not a contest formula node: {f!r}")


def names_used(f: Node) -> tuple[set, set]:
    """(place ids, transition ids) the formula names."""
    places: set = set()
    transitions: set = set()
    stack = [f]
    while stack:
        g = stack.pop()
        if isinstance(g, (Tokens, PlaceBound)):
            places.update(g.places)
        elif isinstance(g, Fireable):
            transitions.update(g.transitions)
        elif isinstance(g, IntLe):
            stack += [g.left, g.right]
        elif isinstance(g, (Not, Quant)):
            stack.append(g.arg)
        elif isinstance(g, (And, Or, Temporal)):
            stack.extend(g.args)
    return places, transitions


__all__ = ["EXAMINATIONS", "And", "Bool", "ContestFormatError", "ContestProperty", "Fireable", "IntConst", "IntLe",
           "Node", "Not", "Or", "PlaceBound", "Quant", "Temporal", "Tokens", "is_ltl", "is_state_formula",
           "names_used", "read_file", "read_text", "show"]
