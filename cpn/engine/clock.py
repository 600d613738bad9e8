"""Which transitions read the model clock: `intTime()` or `time()` in a guard, an arc inscription, a delay
or a priority, directly or through the functions and values they use (docs/semantics.md, Time).

Both engines use this: a transition that reads the clock is bound afresh at every time it is examined,
time condensation is refused for a model that reads it, and the explorer's time-growth watch does not
apply to such a model.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass

from cpn.diagnostics import Diagnostic, Span
from cpn.errors import ConfigurationError
from cpn.expr import nodes as A
from cpn.expr.binding import children
from cpn.values.builtins import TIME_BUILTINS


@dataclass(frozen=True)
class ClockRead:
    """Where a transition instance first reads the clock: the span of the `intTime()` (or of the call of
    the function that reads it) and the element it belongs to."""

    transition: str  # "Page'Trans 1"
    element: str  # "the guard", "the inscription of arc 'P' -> 'T'", "the delay", "the priority"
    span: Span | None
    via: str | None = None  # "'late' reads it at m.cpnet:2:15" when the read is inside a called function


def clock_reads(net) -> dict[int, ClockRead]:
    """Transition index -> its first read of the clock, for every transition instance that reads it;
    found once per net (a net is not changed once made; every engine of it asks: the one that searches,
    those that print its traces), a copy each time."""
    found = _READS.get(net)
    if found is None:
        found = _READS[net] = _clock_reads(net)
    return dict(found)


#: the clock reads of the nets engines were built for, while the nets live
_READS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _clock_reads(net) -> dict[int, ClockRead]:
    globals_ = global_readers(net.globals.decls)
    out: dict[int, ClockRead] = {}
    for t in net.transitions:
        parts = [("the guard", g) for g in t.guards]
        parts += [(f"the inscription of arc {a.label}".rstrip(), a.expr) for a in t.arcs]
        parts += [("the delay", t.delay), ("the priority", t.priority)]
        for element, e in parts:
            span = first_read(e, globals_)
            if span is not None:
                name = called_reader(e, globals_)
                via = f"'{name[0]}' reads it at {name[1]}" if name is not None else None
                out[t.index] = ClockRead(t.name, element, span, via)
                break
    return out


def global_readers(decls) -> dict[int, Span]:
    """Symbol uid -> span of a clock read, for every global `fun` or `val` that reads the clock (a value
    counts too: it may hold a function), following calls between them to a fixpoint."""
    bodies: dict[int, list] = {}
    for d in decls:
        if isinstance(d, A.FunDecl):
            bodies[d.ref.uid] = [c.body for c in d.clauses]
        else:
            bodies[d.pat.ref.uid] = [d.expr]
    readers: dict[int, Span] = {}
    changed = True
    while changed:
        changed = False
        for uid, exprs in bodies.items():
            if uid in readers:
                continue
            for e in exprs:
                span = first_read(e, readers)
                if span is not None:
                    readers[uid] = span
                    changed = True
                    break
    return readers


def first_read(e, readers: dict[int, Span]) -> Span | None:
    """The span of the first clock read in e: a time built-in, or a name of a reader in `readers`."""
    if e is None:
        return None
    stack = [e]
    while stack:
        x = stack.pop()
        if isinstance(x, A.App):
            if first_read(x.fn, readers) is not None:
                return x.span  # the whole call: `intTime()`, `late(x)`
            stack.append(x.arg)  # its function was just read
            continue
        if isinstance(x, A.Name):
            if x.ref.kind == "builtin" and x.ref.name in TIME_BUILTINS:
                return x.span
            if x.ref.kind in ("fun", "val") and x.ref.uid in readers:
                return x.span
            continue
        stack.extend(reversed(children(x)))
    return None


def called_reader(e, readers: dict[int, Span]):
    """(name, span of its clock read) of the first global function or value read in e that reads the
    clock, when e does not read it directly first; else None."""
    stack = [e]
    while stack:
        x = stack.pop()
        if isinstance(x, A.Name):
            if x.ref.kind == "builtin" and x.ref.name in TIME_BUILTINS:
                return None
            if x.ref.kind in ("fun", "val") and x.ref.uid in readers:
                return x.ref.name, readers[x.ref.uid]
            continue
        stack.extend(reversed(children(x)))
    return None


class TimeCondensationRefused(ConfigurationError):
    """Time condensation was asked for a model that reads the clock (exit status 64)."""

    def __init__(self, read: ClockRead, source: str | None):
        self.read = read
        self.source = source
        self.diagnostic = Diagnostic(
            "E0601",
            f"time condensation cannot be used: {read.element} of transition '{read.transition}' reads the "
            "model clock, and time condensation sets the clock to 0 in every state, so the condensed state "
            "space would be that of another model",
            read.span,
            notes=[read.via] if read.via else [],
            hint="Explore without --time-condensation (a model that reads the clock is not stopped by the "
                 "time-growth watch; bound an infinite one with --max-states or --max-seconds), or express "
                 "the timing with token delays (@+) instead of reading intTime().")
        super().__init__(f"{read.span}: {self.diagnostic.message}" if read.span else self.diagnostic.message)

    def render(self) -> str:
        return self.diagnostic.render(self.source)


def refuse_condensation(net, reads: dict[int, ClockRead]) -> None:
    """Raise TimeCondensationRefused for the first transition (in net order) that reads the clock."""
    if reads:
        first = reads[min(reads)]
        raise TimeCondensationRefused(first, net.source)
