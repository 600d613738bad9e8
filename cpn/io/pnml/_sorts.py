"""Sorts of PNML symmetric nets and the CPN ML colour sets and helper functions they become.

Imports the stdlib and `cpn.io.pnml._names` only.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field

from cpn.io.pnml._names import Namespace


def int_text(n: int) -> str:
    """An integer as CPN ML text (`~` is the minus sign)."""
    return f"~{-n}" if n < 0 else str(n)


@dataclass(eq=False)
class Sort:
    """One colour set of the translated net.

    kind is 'dot', 'bool', 'enum' (finite or cyclic enumeration, and partitions), 'range' (finite int
    range) or 'product'. `consts` are the CPN ML identifiers of an enumeration's constants in order.
    """

    kind: str
    name: str
    consts: list[str] = field(default_factory=list)
    cyclic: bool = True
    lo: int = 0
    hi: int = 0
    parts: list[Sort] = field(default_factory=list)
    # partition: the sort it partitions and, per constant of that sort, the partition element
    base: Sort | None = None
    element_of: dict[str, str] = field(default_factory=dict)
    helpers: dict[str, str] = field(default_factory=dict)  # "succ"/"pred"/"ord"/"of" -> function name
    origin: object = None  # the PNML element that declares the sort, for diagnostics

    def declaration(self) -> str:
        if self.kind == "dot":
            body = "unit"
        elif self.kind == "bool":
            body = "bool"
        elif self.kind == "enum":
            body = "with " + " | ".join(self.consts)
        elif self.kind == "range":
            body = f"int with {int_text(self.lo)}..{int_text(self.hi)}"
        else:
            body = "product " + " * ".join(p.name for p in self.parts)
        return f"colset {self.name} = {body};"

    def values(self) -> list[str]:
        """Every value of the sort as CPN ML text, in the sort's order."""
        if self.kind == "dot":
            return ["()"]
        if self.kind == "bool":
            return ["false", "true"]
        if self.kind == "enum":
            return list(self.consts)
        if self.kind == "range":
            return [int_text(i) for i in range(self.lo, self.hi + 1)]
        return ["(" + ", ".join(combo) + ")" for combo in itertools.product(*(p.values() for p in self.parts))]

    def size(self) -> int:
        if self.kind == "product":
            n = 1
            for p in self.parts:
                n *= p.size()
            return n
        return len(self.values())

    @property
    def is_ordered(self) -> bool:
        return self.kind in ("enum", "range", "bool")

    # Successor, predecessor and order are written inline with the colour-set functions `S.ord` and
    # `S.col` rather than as generated `fun`s: the engine compiles these (enumeration values are their
    # positions), while a user function goes through the tree-walking evaluator, which made
    # BART-COL-002 (41-constant enumerations compared in guards) 12 times slower.
    def succ(self, x: str) -> str:
        """CPN ML text of the successor of the value `x` (an atomic expression); wraps around."""
        if self.kind == "range":
            lo, hi = int_text(self.lo), int_text(self.hi)
            return f"(if {x} = {hi} then {lo} else {x} + 1)"
        if self.kind == "bool":
            return f"(not {x})"
        return f"{self.name}.col (({self.name}.ord {x} + 1) mod {len(self.consts)})"

    def pred(self, x: str) -> str:
        """CPN ML text of the predecessor of `x`; wraps around."""
        if self.kind == "range":
            lo, hi = int_text(self.lo), int_text(self.hi)
            return f"(if {x} = {lo} then {hi} else {x} - 1)"
        if self.kind == "bool":
            return f"(not {x})"
        n = len(self.consts)
        return f"{self.name}.col (({self.name}.ord {x} + {n - 1}) mod {n})"

    def ord(self, x: str) -> str:
        """CPN ML text of the position of `x` in the sort's order (an int)."""
        if self.kind == "range":
            return x
        if self.kind == "bool":
            return f"(if {x} then 1 else 0)"
        return f"{self.name}.ord {x}"

    def helper(self, op: str, names: Namespace) -> str:
        """The name of helper function `op` ('succ', 'pred', 'ord') for this sort, created on first use."""
        if op not in self.helpers:
            self.helpers[op] = names.ident(f"{op}_{self.name}")
        return self.helpers[op]

    def helper_declarations(self, arg: str) -> list[str]:
        """`fun` declarations of the helpers used, in a fixed order (succ, pred, ord, of); `arg` is
        the name of their parameter."""
        out = []
        for op in ("succ", "pred", "ord", "of"):
            fname = self.helpers.get(op)
            if fname is not None:
                out.append(self._helper_text(op, fname, arg))
        return out

    def _helper_text(self, op: str, fname: str, arg: str) -> str:
        if self.kind == "range":
            lo, hi = int_text(self.lo), int_text(self.hi)
            if op == "succ":
                return f"fun {fname} {arg} = if {arg} = {hi} then {lo} else {arg} + 1;"
            if op == "pred":
                return f"fun {fname} {arg} = if {arg} = {lo} then {hi} else {arg} - 1;"
            return f"fun {fname} {arg} = {arg};"
        if self.kind == "bool":
            if op == "ord":
                return f"fun {fname} {arg} = if {arg} then 1 else 0;"
            return f"fun {fname} {arg} = not {arg};"
        cs = self.consts
        if op == "succ":
            pairs = [(c, cs[(i + 1) % len(cs)]) for i, c in enumerate(cs)]
        elif op == "pred":
            pairs = [(c, cs[(i - 1) % len(cs)]) for i, c in enumerate(cs)]
        elif op == "ord":
            pairs = [(c, str(i)) for i, c in enumerate(cs)]
        else:
            assert self.base is not None
            pairs = [(c, self.element_of[c]) for c in self.base.consts]
        rules = "\n  | ".join(f"{a} => {b}" for a, b in pairs)
        return f"fun {fname} {arg} =\n  case {arg} of\n    {rules};"
