"""The successor function of a timed net, or of a net with priorities, as transition groups whose enabled
binding elements are then selected over all transitions at once (for the native search,
`cpn.statespace.nativetimed`).

In such a net a transition's enabled binding elements still depend only on the markings of the places it
reads, but which of them occur depends on the others: in a timed net those ready at the occurrence time
(the clock if any binding element is ready then, else the earliest time one is), with priorities those of
the smallest priority. So a group gives, per tuple of its read place ids, its binding elements with their
ready time and priority (`ready`), and per (read ids, occurrence time) the effects of those ready then
(`effects`: the time matters only where the transition touches a timed place: its tokens' timestamps).

`expand(s)` computes state s as the compiled engine's own successor function does, in the same order (so
the place markings and binding elements it interns get the ids the Python search gives them) and returns
every value a search needs to expand s from its caches: the groups' ready lists and effects, the written
places' new ids and, under time condensation, the shifted markings' ids. A state whose values are all
cached is expanded without the engine: the engine would compute nothing new for it.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from cpn.engine.api import P_NORMAL
from cpn.engine.timedsuccessors import NEG_INF

#: a written place the binding element puts no token on
NO_DELTA: int = -1


@dataclass
class Expansion:
    """What expanding one state needed (see `TimedGroups.expand`); the successors themselves in `succ`."""

    # per group: its read ids as the engine's memo key (`TimedGroups.ids` gives them as a tuple), and its
    # result for them (`TimedGroups.pairs` gives its ready times and priorities)
    keys: list = field(default_factory=list)
    results: list = field(default_factory=list)
    effects: list = field(default_factory=list)  # (group, read ids, occurrence time, [entry, ...])
    adds: list = field(default_factory=list)  # (place, delta id, old id, new id)
    shifts: list = field(default_factory=list)  # (place, id, occurrence time, new id)
    time: int | None = None  # the occurrence time (None: nothing enabled, or no clock)
    # with `expand(s, successors=True)`: (binding element, state), as `engine.successors(s)`
    succ: list = field(default_factory=list)


class TimedGroups:
    """The groups of a compiled engine whose net is timed or has priorities, without clock readers."""

    def __init__(self, engine):
        self._engine = engine
        plan = engine._plan
        self.groups = [(tuple(i.read), tuple(i.writes)) for i in plan]
        self.clock = engine.is_timed  # the state's last field is the clock
        self.condensation = engine.time_condensation
        self.priorities = engine._has_priorities
        # a group whose effects depend on the occurrence time: it touches a timed place
        self.timed = [bool(engine.is_timed and i.timed) for i in plan]
        self.timed_places = [p for p in range(len(engine.places)) if engine.store.timed[p]] \
            if engine.is_timed else []
        # per group: a written place -> its position among the group's written places
        self._wpos = [{p: i for i, p in enumerate(i.writes)} for i in plan]

    def native_code(self):
        """(the C of the net's transitions for the native timed search, None), or (None, why) where no place
        marking can be held in C (`cpn.engine.ccodegen.timed_native_code`); computed once per engine."""
        e = self._engine
        got = getattr(e, "_timed_native_code", None)
        if got is None:
            from cpn.engine import ccodegen

            try:
                got = (ccodegen.timed_native_code(e), None)
            except ccodegen.NotNative as exc:
                got = (None, str(exc))
            e._timed_native_code = got
        return got

    def native_left(self):
        """(the transitions the net's C would leave to the engine, by index, with why, None), or (None, why)
        where no place marking can be held in C: from the C of one instance of each transition of a module
        (`timed_native_code(probe=True)`), or from the whole net's C where it was made; once per engine."""
        e = self._engine
        got = getattr(e, "_timed_native_code", None)
        if got is not None:
            return (got[0].left, None) if got[0] is not None else got
        got = getattr(e, "_timed_native_left", None)
        if got is None:
            from cpn.engine import ccodegen

            try:
                got = (ccodegen.timed_native_code(e, probe=True).left, None)
            except ccodegen.NotNative as exc:
                got = (None, str(exc))
            e._timed_native_left = got
        return got

    def transition_name(self, t: int) -> str:
        """The name of transition t (for the notes on transitions left to the engine)."""
        return self._engine.transitions[t].name

    def caller_caches(self) -> None:
        """The engine keeps its own memos (a state's expansion reuses them)."""

    def engine_caches(self) -> None:
        """Nothing to restore: the engine's memos were kept."""

    def pairs(self, res) -> list[tuple]:
        """(ready time, priority) of each binding element of a group's result (in `Expansion.results`)."""
        prio = self._engine._prio
        if self.clock:
            return [(entry[0], prio.get(entry[1], P_NORMAL)) for entry in res]
        return [(NEG_INF, prio.get(entry[0], P_NORMAL)) for entry in res]

    def ids(self, g: int, key) -> tuple:
        """Group g's read place ids as a tuple, from the engine's memo key (a bare id for one read place)."""
        n = len(self.groups[g][0])
        return key if n > 1 else ((key,) if n == 1 else ())

    def expand(self, s: tuple, successors: bool = False) -> Expansion:
        """What expanding state s needs (see the module's docstring); with `successors`, the successors too."""
        self._engine._nstates += 1  # as `successors` counts: the engine judges its memos' reuse by it
        x = Expansion()
        if self.clock:
            self._timed(s, x, successors)
        else:
            self._untimed(s, x, successors)
        if successors:
            self._select(x)
        return x

    def _timed(self, s: tuple, x: Expansion, successors: bool) -> None:
        """`CompiledEngine._timed_successors` (no transition reads the clock), recording its values."""
        e = self._engine
        clock = s[-1]
        prio = e._prio
        keys, results = x.keys, x.results
        miss = e._timed_miss
        for getter, memo_get, info in e._fast:
            key = getter(s)
            res = memo_get(key)
            if res is None:
                res = miss(info, key, clock)
            keys.append(key)
            results.append(res)
        plan = e._plan
        fixed = [(k, plan[k], keys[k], res) for k, res in enumerate(results) if res]
        if not fixed:
            return
        first = min(entry[0] for _k, _i, _key, res in fixed for entry in res)
        f = clock if first <= clock else first
        x.time = f
        condense = self.condensation and f
        timed_places = self.timed_places
        fired, add, shift = e._fired, e._add, e._shift
        adds_out, shifts_out, succ = x.adds, x.shifts, x.succ
        for k, info, key, res in fixed:
            entries = []
            read = info.read
            wpos, nw = self._wpos[k], len(info.writes)
            for entry in res:
                if entry[0] > f:
                    continue
                be, sets, adds = fired(info, key, entry, f)
                lst = list(s)
                for pos, nid in sets:
                    lst[pos] = nid
                deltas = [NO_DELTA] * nw
                for pos, did, _memo in adds:
                    old = lst[pos]
                    lst[pos] = nid = add(pos, old, did)
                    deltas[wpos[pos]] = did
                    adds_out.append((pos, did, old, nid))
                entries.append([be, *[lst[p] for p in read], *deltas])
                if condense:
                    for p in timed_places:
                        old = lst[p]
                        lst[p] = nid = shift(p, old, f)
                        shifts_out.append((p, old, f, nid))
                if successors:
                    lst[-1] = 0 if self.condensation else f
                    succ.append((be, tuple(lst), prio.get(be, P_NORMAL)))
            if entries:
                x.effects.append((k, key, f if self.timed[k] else 0, entries))

    def _untimed(self, s: tuple, x: Expansion, successors: bool) -> None:
        """`CompiledEngine.successors` of an untimed net with priorities, recording its values."""
        e = self._engine
        prio = e._prio
        for k, (getter, memo_get, info) in enumerate(e._fast):
            key = getter(s)
            res = memo_get(key)
            if res is None:
                res = e._miss(info, key)
            x.keys.append(key)
            x.results.append(res)
            entries = []
            wpos, nw = self._wpos[k], len(info.writes)
            for be, sets, adds in res:
                lst = list(s)
                for pos, nid in sets:
                    lst[pos] = nid
                deltas = [NO_DELTA] * nw
                for pos, did, memo in adds:
                    nid = memo.get(s[pos])
                    lst[pos] = nid if nid is not None else e._add(pos, s[pos], did)
                    deltas[wpos[pos]] = did
                    x.adds.append((pos, did, s[pos], lst[pos]))
                entries.append([be, *[lst[p] for p in info.read], *deltas])
                if successors:
                    x.succ.append((be, tuple(lst), prio.get(be, P_NORMAL)))
            if entries:
                x.effects.append((k, key, 0, entries))
        x.time = 0

    def _select(self, x: Expansion) -> None:
        """Keep the successors of the smallest priority (with priorities), as the engine does."""
        if self.priorities and len(x.succ) > 1:
            best = min(p for _be, _t, p in x.succ)
            x.succ = [(be, t) for be, t, p in x.succ if p == best]
        else:
            x.succ = [(be, t) for be, t, _p in x.succ]
