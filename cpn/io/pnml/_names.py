"""Identifiers and names for PNML translation: valid, unique, deterministic CPN ML identifiers and
quoted `.cpnet` place/transition names. Imports the stdlib only."""

from __future__ import annotations

import re

_IDENT = re.compile(r"[A-Za-z][A-Za-z0-9_']*\Z")

# Words the .cpnet grammar or the CPN ML library already uses: never generated as identifiers.
RESERVED: frozenset[str] = frozenset("""
    abstype and andalso as case colset datatype div do else end eqtype exception fn fun functor handle if
    in include infix infixr let local mod nonfix of op open orelse raise rec sharing sig signature struct
    structure then type val var where while with withtype not true false empty unit bool int intinf string
    real time index product record list union subset by timed net place trans arc inhibitor reset module
    instance port out io fusion priority o all ran size hd tl length rev mem nil ref ms_to_col intTime
    map filter exists app foldl foldr null ord chr abs max min succ pred col ceil cf contains ignore ins
    ins_new intersect list_to_ms remdupl rm round trunc floor legal mkstr mult
""".split())


def is_identifier(text: str) -> bool:
    """True when `text` is a CPN ML identifier that the generator may use as it is."""
    return bool(_IDENT.match(text)) and text not in RESERVED


def sanitize(text: str) -> str:
    """Turn any text into an identifier-shaped string (possibly reserved, possibly taken)."""
    s = re.sub(r"[^A-Za-z0-9_]", "_", text or "")
    s = re.sub(r"_+", "_", s).strip("_") or "x"
    if not s[0].isalpha():
        s = "c" + s if s[0] != "_" else "c" + s
    return s


class Namespace:
    """Hands out unique identifiers, first come first served, so the result depends only on call order."""

    def __init__(self) -> None:
        self.taken: set[str] = set()

    def ident(self, *candidates: str | None) -> str:
        """The first candidate that is a free identifier as it stands, else the first sanitized one
        made unique with a numeric suffix."""
        cands = [c for c in candidates if c]
        for c in cands:
            if is_identifier(c) and c not in self.taken:
                self.taken.add(c)
                return c
        for c in cands:
            s = sanitize(c)
            if is_identifier(s) and s not in self.taken:
                self.taken.add(s)
                return s
        base = sanitize(cands[0] if cands else "x")
        if base in RESERVED:
            base += "_"
        n = 2
        while f"{base}_{n}" in self.taken:
            n += 1
        self.taken.add(f"{base}_{n}")
        return f"{base}_{n}"


def quote_name(name: str) -> str:
    """A place or transition name as `.cpnet` text: bare when it is an identifier, else a string."""
    if is_identifier(name):
        return name
    return '"' + name.replace("\\", "\\\\").replace('"', '\\"').replace("\n", " ") + '"'


class NodeNames:
    """Unique place and transition names that keep the PNML name (with the id added on a clash)."""

    def __init__(self) -> None:
        self.taken: set[str] = set()

    def name(self, name: str | None, node_id: str) -> str:
        name = (name or "").replace("\n", " ").strip() or node_id
        for cand in (name, f"{name} ({node_id})"):
            if cand not in self.taken:
                self.taken.add(cand)
                return cand
        n = 2
        while f"{name} ({node_id} {n})" in self.taken:
            n += 1
        self.taken.add(f"{name} ({node_id} {n})")
        return f"{name} ({node_id} {n})"
