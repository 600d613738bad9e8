"""Symbols: what a name in a model refers to, as resolved by the type checker."""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field
from typing import Any

from cpn.diagnostics import Span

_uids = itertools.count(1)


@dataclass(slots=True, eq=False)
class Symbol:
    """A declared name.

    kind: 'var' (transition variable), 'val' (global constant), 'fun' (global function), 'con'
    (constructor of an enumeration, index or union), 'builtin' (library function), 'csop' (`CS.all` and
    friends), 'local' (bound by a pattern), 'param' (module parameter).
    """

    name: str
    kind: str
    type: Any = None  # a Type or a Scheme
    span: Span | None = None
    data: Any = None
    what: str | None = None  # how messages name it when its kind says too little ("the place" for Page'place)
    uid: int = field(default_factory=lambda: next(_uids))

    @property
    def pyname(self) -> str:
        safe = "".join(c if c.isalnum() else "_" for c in self.name)
        return f"{safe}_{self.uid}"


@dataclass(slots=True)
class ConInfo:
    """A constructor: enumeration constant, index constructor `ph`, or union constructor."""

    colset: str
    tag: int  # position (enum, union); unused for index
    kind: str  # 'enum' 'index' 'union'
    has_arg: bool
