"""A small hand-written engine implementing the engine protocol of docs/internals.md, for tests.

Nets are given explicitly: places with an initial multiset, and binding elements ("modes") each with
the tokens they remove and add. Timed places hold `(value, timestamp)` keys; a mode removes the
earliest ready token of each value it needs and stamps its output tokens with `clock + delay`.
"""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class ToyPlace:
    name: str
    colour_set: str = "UNIT"
    timed: bool = False


@dataclass
class ToyTransition:
    name: str


@dataclass
class ToyBindingElement:
    transition: int
    binding: dict


@dataclass
class Mode:
    transition: int
    binding: dict
    pre: dict  # place index -> {value: count}
    post: dict  # place index -> {value: count}
    delay: int = 0


@dataclass
class ToyEngine:
    places: list
    transitions: list
    modes: list
    init: list  # per place: {value: count} (timed places: {(value, ts): count})
    is_timed: bool = False
    reads_clock: bool = False  # no toy net reads the clock
    clock_reads: dict = field(default_factory=dict)
    _tables: list = field(default_factory=list)
    _ids: list = field(default_factory=list)

    def __post_init__(self):
        self._tables = [[] for _ in self.places]
        self._ids = [{} for _ in self.places]

    # ---- interning -------------------------------------------------------------------------
    def _intern(self, p: int, ms: dict) -> int:
        key = frozenset((k, v) for k, v in ms.items() if v)
        ids = self._ids[p]
        i = ids.get(key)
        if i is None:
            i = len(self._tables[p])
            ids[key] = i
            self._tables[p].append(dict(key))
        return i

    def _state(self, ms_list, clock):
        s = tuple(self._intern(p, ms) for p, ms in enumerate(ms_list))
        return s + (clock,) if self.is_timed else s

    # ---- protocol --------------------------------------------------------------------------
    def initial_state(self):
        return self._state(self.init, 0)

    def clock(self, s):
        return s[-1] if self.is_timed else 0

    def marking(self, s):
        return [dict(self._tables[p][s[p]]) for p in range(len(self.places))]

    def token_counts(self, s):
        return tuple(sum(self._tables[p][s[p]].values()) for p in range(len(self.places)))

    def untimed(self, s):
        out = []
        for p, pl in enumerate(self.places):
            ms = self._tables[p][s[p]]
            if pl.timed:
                u = {}
                for (v, _ts), n in ms.items():
                    u[v] = u.get(v, 0) + n
                out.append(frozenset(u.items()))
            else:
                out.append(s[p])
        return tuple(out)

    def _try(self, mode, marking, clock):
        """Return (new marking, earliest time the mode can fire) or None if it never can."""
        new = [dict(m) for m in marking]
        ready = clock
        for p, need in mode.pre.items():
            ms = new[p]
            for v, n in need.items():
                if self.places[p].timed:
                    stamps = sorted(ts for (w, ts), c in ms.items() for _ in range(c) if w == v)
                    if len(stamps) < n:
                        return None
                    for ts in stamps[:n]:
                        ready = max(ready, ts)
                        ms[(v, ts)] -= 1
                else:
                    if ms.get(v, 0) < n:
                        return None
                    ms[v] -= 1 * n
        return new, ready

    def successors(self, s):
        marking = self.marking(s)
        clock = self.clock(s)
        trials = []
        for be, mode in enumerate(self.modes):
            r = self._try(mode, marking, clock)
            if r is not None:
                trials.append((be, mode, r[0], r[1]))
        if not trials:
            return []
        if self.is_timed:
            t = min(ready for *_, ready in trials)
            trials = [x for x in trials if x[3] <= t]
            clock = t
        out = []
        for be, mode, new, _ready in trials:
            for p, add in mode.post.items():
                for v, n in add.items():
                    key = (v, clock + mode.delay) if self.places[p].timed else v
                    new[p][key] = new[p].get(key, 0) + n
            out.append((be, self._state(new, clock)))
        return out

    def binding_element(self, be):
        m = self.modes[be]
        return ToyBindingElement(m.transition, dict(m.binding))

    def format_binding_element(self, be):
        m = self.modes[be]
        b = ", ".join(f"{k}={v}" for k, v in sorted(m.binding.items()))
        return f"{self.transitions[m.transition].name}: {{{b}}}"

    def format_multiset(self, p, ms):
        if not ms:
            return "empty"
        return "++".join(f"{n}`{_fmt(v)}" for v, n in sorted(ms.items(), key=lambda kv: repr(kv[0])) if n)

    def format_marking(self, s, p):
        ms = self._tables[p][s[p]]
        if not ms:
            return "empty"
        if self.places[p].timed:
            return "+++".join(f"{n}`{_fmt(v)}@{ts}" for (v, ts), n in sorted(ms.items()) if n)
        return self.format_multiset(p, ms)


def _fmt(v):
    return "()" if v == () else str(v)


def pt_net(pre, post, m0, tnames=None, pnames=None):
    """A P/T net from pre/post matrices (rows = transitions), all places of colour set UNIT."""
    np_ = len(m0)
    places = [ToyPlace(f"Top'{(pnames or [f'P{i}' for i in range(np_)])[i]} 1") for i in range(np_)]
    names = tnames or [f"T{i}" for i in range(len(pre))]
    transitions = [ToyTransition(f"Top'{n} 1") for n in names]
    modes = []
    for t, (a, b) in enumerate(zip(pre, post)):
        modes.append(Mode(t, {}, {p: {(): n} for p, n in enumerate(a) if n},
                          {p: {(): n} for p, n in enumerate(b) if n}))
    init = [{(): n} if n else {} for n in m0]
    return ToyEngine(places, transitions, modes, init)


def dining_philosophers(n: int) -> ToyEngine:
    """DP(n) of bench/BENCHMARKS.md, coloured: places Think, HasLeft, Eat, Forks of colour set PH."""
    places = [ToyPlace(f"Top'{x} 1", "PH") for x in ("Think", "HasLeft", "Eat", "Forks")]
    transitions = [ToyTransition(f"Top'{x} 1") for x in ("TakeLeft", "TakeRight", "PutDown")]
    modes = []
    for p in range(n):
        modes.append(Mode(0, {"p": p}, {0: {p: 1}, 3: {p: 1}}, {1: {p: 1}}))
    for p in range(n):
        modes.append(Mode(1, {"p": p}, {1: {p: 1}, 3: {(p + 1) % n: 1}}, {2: {p: 1}}))
    for p in range(n):
        r = (p + 1) % n
        post = {0: {p: 1}, 3: {p: 1, r: 1} if r != p else {p: 2}}
        modes.append(Mode(2, {"p": p}, {2: {p: 1}}, post))
    init = [{p: 1 for p in range(n)}, {}, {}, {p: 1 for p in range(n)}]
    return ToyEngine(places, transitions, modes, init)
