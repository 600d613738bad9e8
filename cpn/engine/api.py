"""What both engines share: set-up, binding elements (interned ids, their bindings and text), the clock,
and conveniences built on `successors` (docs/internals.md)."""

from __future__ import annotations

from dataclasses import dataclass

from cpn.engine.clock import clock_reads, refuse_condensation
from cpn.expr.evaluate import Evaluator
from cpn.values.colours import format_multiset

#: the priority of a transition without one (CPN Tools' P_NORMAL)
P_NORMAL: int = 1000


@dataclass(frozen=True, slots=True)
class BindingElement:
    """A transition instance (its index) and a binding of its variables (name -> value)."""

    transition: int  # index into engine.transitions
    binding: dict


class EngineAPI:
    """Mixed into the compiled engine and the reference interpreter."""

    def _setup(self, net, time_condensation: bool) -> None:
        self.net = net
        self.places = net.places
        self.transitions = net.transitions
        self.is_timed = net.is_timed
        self.time_condensation = bool(time_condensation) and self.is_timed
        # transition index -> where it reads the clock (only a timed net has a clock that moves)
        self.clock_reads = clock_reads(net) if self.is_timed else {}
        self.reads_clock = bool(self.clock_reads)
        if self.time_condensation and self.reads_clock:
            refuse_condensation(net, self.clock_reads)
        # per transition: the timed places it removes tokens from (their timestamps are the times at
        # which it is examined, besides the state's clock)
        self.timed_inputs = [sorted({a.place for a in t.arcs if a.kind.consumes and a.expr is not None
                                     and self.places[a.place].timed}) for t in self.transitions]
        # per transition: place -> how long before their timestamps its input arcs may remove tokens from
        # it (`e @+ k` on an input arc, CPN Tools' preempting time stamps; the net has one k per place)
        self.preemption = [{a.place: a.preemption for a in t.arcs if a.preemption} for t in self.transitions]
        self.ev = Evaluator(net.colsets, net.globals)
        self._be_index: dict = {}
        self._be: list[tuple[int, tuple]] = []  # binding element id -> (transition, values of its variables)

    def _intern_be(self, t: int, vals: tuple) -> int:
        key = (t, vals)
        i = self._be_index.get(key)
        if i is None:
            i = len(self._be)
            self._be_index[key] = i
            self._be.append(key)
        return i

    def binding_element(self, be: int) -> BindingElement:
        t, vals = self._be[be]
        return BindingElement(t, dict(zip(self.transitions[t].variables, vals)))

    def format_binding_element(self, be: int) -> str:
        """CPN Tools' text of a binding element: ``Top'Send 1: {a=1, f=3}``."""
        t, vals = self._be[be]
        tr = self.transitions[t]
        parts = [f"{n}={self.net.colsets[self.net.variables[n].data].format(v)}" for n, v in zip(tr.variables, vals)]
        return f"{tr.name}: {{{', '.join(parts)}}}"

    def format_multiset(self, p: int, ms: dict) -> str:
        """CPN ML text of an untimed multiset (value -> count) of place p's colour set."""
        return format_multiset(self.places[p].colour_set, ms.items())

    def clock(self, state) -> int:
        return state[-1] if self.is_timed else 0

    def successor_groups(self):
        """The successor function as transition groups for a native search (`TransitionGroups`), or
        None where the engine cannot give them (the reference interpreter; timed nets; priorities)."""
        return None

    def timed_groups(self):
        """A timed net's or a net with priorities' successor function as groups for a native search
        (`cpn.engine.timedgroups.TimedGroups`), or None where the engine cannot give them."""
        return None

    def predicate_compiler(self, evaluator, places: dict):
        """A compiler of property texts in the net's expression form (`cpn.engine.propertycode`), which
        calls the model's compiled functions where the engine has them."""
        from cpn.engine.propertycode import PredicateCompiler

        return PredicateCompiler(evaluator, places, getattr(self, "functions", None) or {})

    def enabled(self, state) -> list:
        """The enabled binding elements of `state`, in the engine's fixed order."""
        return [self.binding_element(be) for be, _ in self.successors(state)]

    def fire(self, state, binding_element):
        """The marking reached by firing one enabled binding element.

        `binding_element` is a binding element id, a `BindingElement`, or its text
        (``"Top'Send 1: {a=1, f=3}"``). Raises ValueError if it is not enabled in `state`.
        """
        for be, succ in self.successors(state):
            if be == binding_element or self.format_binding_element(be) == binding_element \
                    or self.binding_element(be) == binding_element:
                return succ
        raise ValueError(f"{binding_element!r} is not enabled in this state")
