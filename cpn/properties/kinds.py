"""The property kinds of docs/specs.md: each turns a `PropertySpec` into a check with one `Verdict`.

Invariants, reachability and deadlock freedom observe states while the graph is generated (`observe`);
every check then decides on the graph it has (`decide`): a violation found in a partial graph is real
(every stored state is reachable, every expanded state's arcs are complete), anything else that needs
the whole graph is unknown with the reason the search stopped. The checks of a scenario's properties are
built from their texts by `cpn.properties.build`. Imports `cpn.checks.*`, `cpn.statespace`, `cpn.lang`
(types) and layer 0.
"""

from __future__ import annotations

import operator
from array import array
from collections import deque

from cpn.checks.ctl import Kripke, reverse_csr
from cpn.checks.verdict import Status, Verdict, evidence_to, path_evidence
from cpn.diagnostics import Diagnostic
from cpn.engine.protocol import has
from cpn.errors import ModelError
from cpn.properties.predicates import PredicateError, PropertyLanguage
from cpn.properties.spec import PropertySpec
from cpn.statespace.scc import strongly_connected_components
from cpn.values.multiset import Multiset


class GraphView:
    """What the checks share about one finished (or stopped) exploration, computed at most once."""

    def __init__(self, exploration, engine, lang: PropertyLanguage, stop_note: str | None = None):
        self.x = exploration
        self.g = exploration.graph
        self.engine = engine
        self.lang = lang
        self.complete = exploration.complete
        self.stop_note = stop_note
        self._labels = None
        self._kripke = None
        self._pred = None
        self._scc = None
        self._atom_cache: dict = {}

    @property
    def reason(self) -> str:
        x = self.x
        why = self.stop_note or x.stop_reason.describe(x.options)
        return (f"the state space is partial: the search stopped because {why}; "
                f"{x.unexpanded:,} of {x.n_states:,} states were not expanded")

    def labels(self) -> array:
        """The transition instance of every arc."""
        if self._labels is None:
            self._labels = self.lang.transition_index.arc_transitions(self.g.bes)
        return self._labels

    def predecessors(self) -> tuple:
        """The arcs into every state, in CSR form: (pred_off, pred) (cpn.checks.ctl.reverse_csr)."""
        if self._pred is None:
            self._pred = reverse_csr(self.g.n_states, self.g.offsets, self.g.dst)
        return self._pred

    def kripke(self, fairness: list | None = None) -> Kripke:
        """The graph for CTL; with fairness (binding-element tests), arcs are labelled by binding element."""
        self.predecessors()
        if fairness:
            bes = self.g.bes
            distinct = sorted(set(bes))
            sets = [{be for be in distinct if test(be)} for test in fairness]
            return Kripke(self.g.n_states, self.g.offsets, self.g.dst, bes, sets, self._pred, self.scc())
        if self._kripke is None:
            self._kripke = Kripke(self.g.n_states, self.g.offsets, self.g.dst, self.g.bes, None, self._pred,
                                  self.scc())
        return self._kripke

    def scc(self):
        if self._scc is None:
            self._scc = strongly_connected_components(self.g.n_states, self.g.offsets, self.g.dst)
        return self._scc

    def truth(self, compiled) -> bytearray:
        """The states where a compiled predicate holds (evaluated once per predicate)."""
        got = self._atom_cache.get(id(compiled))
        if got is None:
            ctx = self.lang.ctx
            ctx.graph = self.g
            fn = compiled.fn
            got = bytearray(1 if fn(i, s) else 0 for i, s in enumerate(self.g.states))
            self._atom_cache[id(compiled)] = got
        return got


class Check:
    """One property. `on_the_fly` checks get `observe(state_id, state)` for every stored state, in order."""

    on_the_fly = False

    def __init__(self, spec: PropertySpec):
        self.spec = spec
        self.found: int | None = None  # the first state observed to violate (or witness) the property
        self.error: PredicateError | None = None  # the property's text failed in a marking

    def observe(self, sid: int, state) -> bool:
        return False

    def observe_many(self, sid: int, states) -> bool:
        """`observe` of each of `states` in turn (the first has id `sid`); whether one violated (or
        witnessed) the property."""
        hit = False
        for i, state in enumerate(states):
            hit = self.observe(sid + i, state) or hit
        return hit

    def decide(self, view: GraphView) -> Verdict:
        raise NotImplementedError


def _state_name(view: GraphView, sid: int) -> str:
    if sid == 0:
        return "the initial marking (marking 1)"
    depth = 0
    v = sid
    while v > 0:
        v = view.g.parent[v]
        depth += 1
    return f"marking {sid + 1} ({depth} step{'s' if depth != 1 else ''} from the initial marking)"


# ----------------------------------------------------------------------------- on the fly
class _MarkingSearch(Check):
    """Looks for a marking in which the predicate has the value `wanted`: while the graph is generated
    (`observe`), or over the graph where the predicate reads `enabled` (the successors must be known)."""

    wanted: bool

    def __init__(self, spec, pred):
        super().__init__(spec)
        self.pred = pred
        self.on_the_fly = not pred.uses_enabled

    def observe(self, sid, state):
        if self.found is None and bool(self.pred.fn(sid, state)) is self.wanted:
            self.found = sid
            return True
        return False

    def observe_many(self, sid, states):
        if self.found is not None:
            return False
        i = self.pred.first_where(sid, states, self.wanted)
        if i is None:
            return False
        self.found = sid + i
        return True

    def search(self, view) -> int | None:
        """The first marking found (the first expanded one in the graph's order, over the graph)."""
        if not self.on_the_fly:
            t = view.truth(self.pred)
            self.found = next((i for i in range(view.g.n_states)
                               if bool(t[i]) is self.wanted and view.g.is_expanded(i)), None)
        return self.found


class Invariant(_MarkingSearch):
    wanted = False  # a marking where it is false

    def decide(self, view):
        found = self.search(view)
        if found is not None:
            return Verdict.violated(f"false in {_state_name(view, found)}", evidence_to(view.g, found))
        if view.complete:
            return Verdict.holds(f"true in all {view.g.n_states:,} reachable markings")
        return Verdict.unknown(f"true in the {view.g.n_states:,} markings found; {view.reason}")


class Reachable(_MarkingSearch):
    wanted = True  # a witness

    def decide(self, view):
        found = self.search(view)
        if found is not None:
            return Verdict.holds(f"witness: {_state_name(view, found)}", evidence_to(view.g, found))
        if view.complete:
            return Verdict.violated(f"no reachable marking satisfies it ({view.g.n_states:,} markings)")
        return Verdict.unknown(f"not found in the {view.g.n_states:,} markings found; {view.reason}")


class DeadlockFree(Check):
    on_the_fly = True  # through the engine proxy of the gate (dead states are seen when expanded)

    def decide(self, view):
        dead = self.found
        if dead is None:
            off = view.g.offsets
            dead = next((i for i in range(len(off) - 1) if off[i] == off[i + 1]), None)
        if dead is not None:
            return Verdict.violated(f"{_state_name(view, dead)} is dead", evidence_to(view.g, dead))
        if view.complete:
            return Verdict.holds(f"none of the {view.g.n_states:,} reachable markings is dead")
        return Verdict.unknown(f"no dead marking among the {view.g.expanded:,} expanded markings; {view.reason}")


# ----------------------------------------------------------------------------- on the graph
class DeadMarkings(Check):
    def __init__(self, spec, pred):
        super().__init__(spec)
        self.pred = pred

    def decide(self, view):
        g = view.g
        dead = g.dead_states()
        f = self.spec.fields
        if self.pred is not None:
            ctx = view.lang.ctx
            ctx.graph = g
            for d in dead:
                if not self.pred.fn(d, g.states[d]):
                    return Verdict.violated(f"dead {_state_name(view, d)} does not satisfy the predicate",
                                            evidence_to(g, d))
        ev = evidence_to(g, dead[0]) if dead else None
        if "count" in f and len(dead) != f["count"] and (view.complete or len(dead) > f["count"]):
            return Verdict.violated(f"{len(dead):,} dead markings, expected {f['count']:,}", ev, count=len(dead))
        if "count_modulo_time" in f:
            n = len({view.engine.untimed(g.states[d]) for d in dead})
            if n != f["count_modulo_time"] and (view.complete or n > f["count_modulo_time"]):
                return Verdict.violated(f"{n:,} dead markings modulo time, expected {f['count_modulo_time']:,}", ev,
                                        count_modulo_time=n)
        if not view.complete:
            return Verdict.unknown(f"{len(dead):,} dead markings so far; {view.reason}")
        return Verdict.holds(f"{len(dead):,} dead marking{'s' if len(dead) != 1 else ''}", count=len(dead))


# the fields of a `bound` property (docs/specs.md): the exact forms under their names that read as exact,
# each with the older spelling that means the same; then the one-sided forms
INTEGER_LIMITS = (("upper_equals", "upper"), ("lower_equals", "lower"), ("at_most", None), ("at_least", None))
MULTISET_LIMITS = (("upper_multiset_equals", "upper_multiset"), ("lower_multiset_equals", "lower_multiset"),
                   ("at_most_multiset", None), ("at_least_multiset", None))
_UPPER_SIDE = {"upper_equals", "at_most", "upper_multiset_equals", "at_most_multiset"}
_EXACT = {"upper_equals", "lower_equals", "upper_multiset_equals", "lower_multiset_equals"}


def judge_integer_limit(key: str, want: int, hi: int, lo: int, complete: bool) -> tuple[str, str]:
    """(outcome, text) of one integer limit, given the largest and smallest values found: 'violated' as
    soon as a value found breaks it (also on a partial state space), 'holds' only on a complete one."""
    upper = key in _UPPER_SIDE
    got = hi if upper else lo
    which = "upper" if upper else "lower"
    beyond = got > want if upper else got < want
    if key in _EXACT:
        if got == want and complete:
            return "holds", f"{which} bound {got}"
        if got != want and (complete or beyond):
            return "violated", f"best {which} bound is {got}, expected {want}"
        return "unknown", f"{which} bound {got} so far, expected {want}"
    if beyond:
        return "violated", (f"reaches {got}, more than at_most = {want}" if upper
                            else f"falls to {got}, less than at_least = {want}")
    if complete:
        return "holds", f"{'at most' if upper else 'at least'} {want} (best {which} bound {got})"
    return "unknown", f"{which} bound {got} so far ({key} = {want})"


def judge_multiset_limit(key: str, want_text: str, got_text: str, broken: bool, equal: bool,
                         complete: bool) -> tuple[str, str]:
    """(outcome, text) of one multiset limit: `broken` says a marking found is not included in it (for
    an upper limit) or does not include it (lower); `equal`, that the best bound found equals it."""
    which = "upper" if key in _UPPER_SIDE else "lower"
    if broken:
        if key in _EXACT:
            return "violated", f"a marking breaks the expected {which} multiset bound {want_text}"
        return "violated", (f"a marking is not included in at_most_multiset = {want_text}" if which == "upper"
                            else f"a marking does not include at_least_multiset = {want_text}")
    if not complete:
        return "unknown", f"{which} multiset bound ({key})"
    if key in _EXACT and not equal:
        return "violated", f"best {which} multiset bound is {got_text}, expected {want_text}"
    if key in _EXACT:
        return "holds", f"{which} multiset bound"
    return "holds", f"{'at most' if which == 'upper' else 'at least'} {want_text} (best {which} multiset bound)"


class Bound(Check):
    """`limits`: field -> expected integer; `multiset_limits`: field -> expected Multiset (with `place`)."""

    def __init__(self, spec, places: list[int] | None, fn, limits: dict, multiset_limits: dict):
        super().__init__(spec)
        self.places = places  # place instances, or None for an integer expression
        self.fn = fn
        self.limits = limits
        self.multiset_limits = multiset_limits

    def decide(self, view):
        g = view.g
        rows = []  # (name, states in BFS order, their values, place or None)
        if self.places is None:
            ctx = view.lang.ctx
            ctx.graph = g
            rows.append((self.spec.fields.get("expr"), None, [self.fn.fn(i, s) for i, s in enumerate(g.states)],
                         None))
        else:
            ms_of = view.lang.ctx.mk
            for p in self.places:
                first = _first_states(view, p)
                rows.append((view.engine.places[p].name, first,
                             [sum(ms_of(g.states[i], p)._d.values()) for i in first], p))
        problems, unknowns, holds = [], [], []
        evidence = None
        for name, states, values, p in rows:
            if not values:
                continue
            hi, hi_at, lo, lo_at = self._extremes(values)
            for key, want in self.limits.items():
                outcome, text = judge_integer_limit(key, want, hi, lo, view.complete)
                {"holds": holds, "violated": problems, "unknown": unknowns}[outcome].append(f"{name}: {text}")
                if outcome == "violated" and evidence is None:
                    upper = key in _UPPER_SIDE
                    at = hi_at if upper else lo_at
                    if key not in _EXACT:  # the shallowest marking beyond the limit, not the extreme one
                        at = next(i for i, v in enumerate(values) if (v > want if upper else v < want))
                    evidence = evidence_to(g, states[at] if states is not None else at)
            if p is None:
                continue
            for key, want in self.multiset_limits.items():
                got, bad_at = self._ms_bound(view, p, "upper" if key in _UPPER_SIDE else "lower", want)
                fmt = view.engine.format_multiset
                outcome, text = judge_multiset_limit(key, fmt(p, dict(want._d)), fmt(p, dict(got._d)),
                                                     bad_at is not None, got == want, view.complete)
                {"holds": holds, "violated": problems, "unknown": unknowns}[outcome].append(f"{name}: {text}")
                if bad_at is not None and evidence is None:
                    evidence = evidence_to(g, bad_at)
        if problems:
            return Verdict.violated("; ".join(problems), evidence)
        if unknowns:
            return Verdict.unknown("; ".join(unknowns) + f"; {view.reason}")
        return Verdict.holds("; ".join(holds))

    @staticmethod
    def _extremes(values):
        hi = lo = None
        hi_at = lo_at = 0
        for i, v in enumerate(values):
            if hi is None or v > hi:
                hi, hi_at = v, i
            if lo is None or v < lo:
                lo, lo_at = v, i
        return hi, hi_at, lo, lo_at

    @staticmethod
    def _ms_bound(view, p, which, want: Multiset):
        """(best multiset bound found, first marking that breaks `want` or None)."""
        acc: dict | None = None
        bad = None
        ms_of = view.lang.ctx.mk
        for i in _first_states(view, p):
            m = ms_of(view.g.states[i], p)
            d = m._d
            if which == "upper":
                if bad is None and not m <= want:
                    bad = i
                acc = dict(d) if acc is None else acc
                for v, k in d.items():
                    if acc.get(v, 0) < k:
                        acc[v] = k
            else:
                if bad is None and not want <= m:
                    bad = i
                acc = dict(d) if acc is None else {v: min(k, d.get(v, 0)) for v, k in acc.items() if d.get(v, 0)}
        return Multiset(acc or {}), bad


def _first_states(view: GraphView, p: int) -> list[int]:
    """For each distinct marking of place p, the first (smallest, so shallowest) state that has it, in
    increasing order; every state when states are not tuples of place columns."""
    states = view.g.states
    if not has(view.engine, "place_view"):
        return list(range(len(states)))
    first: dict = {}
    setdefault = first.setdefault
    for i, key in enumerate(map(operator.itemgetter(p), states)):
        setdefault(key, i)
    return sorted(first.values())


class DeadTransitions(Check):
    def __init__(self, spec, expected: set[int]):
        super().__init__(spec)
        self.expected = expected

    def decide(self, view):
        labels = view.labels()
        occurring = set(labels)
        sym = getattr(view.g, "symmetry", None)
        if sym is not None and sym.moves_instances:
            occurring = sym.close_transitions(occurring)  # the same transition of another instance occurs
        all_t = {t.index for t in view.engine.transitions}
        dead = all_t - occurring
        names = view.engine.transitions
        alive_but_expected = sorted(self.expected & occurring)
        if alive_but_expected:
            t = alive_but_expected[0]
            same = {t}
            if sym is not None and sym.moves_instances:  # an arc of the same transition of any instance
                same = next((set(o) for o in sym.transition_orbits() if t in o), same)
            arc = next(a for a in range(len(labels)) if labels[a] in same)
            src = _arc_source(view.g, arc)
            ev = evidence_to(view.g, src, then=[src, view.g.dst[arc]])
            return Verdict.violated(f"{', '.join(names[i].name for i in alive_but_expected)} can occur "
                                    "(expected to be dead)", ev)
        if not view.complete:
            return Verdict.unknown(f"{len(dead):,} transition instances have not occurred so far; {view.reason}")
        unexpected = sorted(dead - self.expected)
        if unexpected:
            return Verdict.violated(f"dead but not expected to be: {', '.join(names[i].name for i in unexpected)}",
                                    dead=[names[i].name for i in sorted(dead)])
        return Verdict.holds(f"{len(dead)} dead transition instance{'s' if len(dead) != 1 else ''}"
                             + (f": {', '.join(names[i].name for i in sorted(dead))}" if dead else ""))


def _arc_source(g, arc: int) -> int:
    import bisect

    return bisect.bisect_right(g.offsets, arc) - 1


class LiveTransitions(Check):
    def __init__(self, spec, transitions: list[int] | None):
        super().__init__(spec)
        self.transitions = transitions

    def decide(self, view):
        if not view.complete:
            return Verdict.unknown(view.reason)
        dec = view.scc()
        labels = view.labels()
        g = view.g
        terms = sorted(dec.terminal_components(), key=lambda c: min(dec.nodes(c)))
        present = []
        for c in terms:
            seen = set()
            for u in dec.nodes(c):
                seen.update(labels[g.offsets[u]:g.offsets[u + 1]])
            present.append(seen)
        wanted = self.transitions if self.transitions is not None else [t.index for t in view.engine.transitions]
        bad = [t for t in wanted if not all(t in s for s in present)]
        if not bad:
            return Verdict.holds(f"{len(wanted)} transition instance{'s' if len(wanted) != 1 else ''} live")
        t = bad[0]
        at = _nearest_never(view, t)
        names = ", ".join(view.engine.transitions[i].name for i in bad)
        return Verdict.violated(f"not live: {names}; {view.engine.transitions[t].name} can never occur after "
                                f"{_state_name(view, at)}", evidence_to(g, at))


def _nearest_never(view, t: int) -> int:
    """The marking nearest to the initial one from which transition instance t can never occur (it reaches
    no arc of t): E[true U "t occurs"] is false there. States are numbered breadth first, so the smallest
    such number is the nearest. Called only when such a marking exists."""
    g = view.g
    labels = view.labels()
    occurs = bytearray(t in labels[g.offsets[u]:g.offsets[u + 1]] for u in range(g.n_states))
    can = view.kripke().eu(bytearray([1]) * g.n_states, occurs)
    return can.index(0)


class Home(Check):
    def __init__(self, spec, pred):
        super().__init__(spec)
        self.pred = pred

    def decide(self, view):
        if not view.complete:
            return Verdict.unknown(view.reason)
        g = view.g
        n = g.n_states
        if self.pred is None and not self.spec.fields.get("initial"):
            dec = view.scc()
            terms = sorted(dec.terminal_components(), key=lambda c: min(dec.nodes(c)))
            if len(terms) == 1:
                return Verdict.holds(f"{len(dec.nodes(terms[0])):,} home markings")
            at = min(dec.nodes(terms[1]))
            return Verdict.violated(f"no home marking: {len(terms)} terminal strongly connected components; "
                                    f"none of them can be left, e.g. after {_state_name(view, at)}",
                                    evidence_to(g, at))
        if self.pred is not None:
            target = view.truth(self.pred)
        else:
            target = bytearray(n)
            target[0] = 1
        # from every state some terminal SCC is reachable, and every state of a terminal SCC reaches all of
        # it: the target is reachable from everywhere iff every terminal SCC contains a target state
        dec = view.scc()
        if all(any(target[v] for v in dec.nodes(c)) for c in dec.terminal_components()):
            return Verdict.holds("reachable from every reachable marking")
        k = view.kripke()
        reach = k.eu(bytearray([1]) * n, target)
        bad = next((i for i in range(n) if not reach[i]), None)
        if bad is None:
            return Verdict.holds("reachable from every reachable marking")
        return Verdict.violated(f"cannot be reached from {_state_name(view, bad)}", evidence_to(g, bad))


class NoLivelock(Check):
    def __init__(self, spec, progress: list | None):
        super().__init__(spec)
        self.progress = progress  # binding-element tests (PropertyLanguage.binding_pattern), as fairness's

    def decide(self, view):
        g = view.g
        n = g.n_states
        labels = None
        avoid = -1
        if self.progress:
            bes = g.bes
            good = {be for be in set(bes) if any(test(be) for test in self.progress)}
            labels = array("b", (1 if be in good else 0 for be in bes))
            avoid = 1
        dec = strongly_connected_components(n, g.offsets, g.dst, labels, avoid)
        best = None
        for c in range(dec.count):
            if dec.nontrivial[c]:
                m = min(dec.nodes(c))
                if best is None or m < best[0]:
                    best = (m, c)
        if best is None:
            if view.complete:
                return Verdict.holds("no cycle" + (" avoids the progress transitions" if self.progress else ""))
            return Verdict.unknown(f"no such cycle among the expanded markings; {view.reason}")
        s, c = best
        inside = set(dec.nodes(c))
        cycle, arcs = _cycle(g, s, inside, labels, avoid)
        what = "a cycle without progress" if self.progress else "a cycle"
        return Verdict.violated(f"{what} of {len(cycle)} step{'s' if len(cycle) != 1 else ''} through "
                                f"{_state_name(view, s)}", evidence_to(g, s, cycle=cycle, cycle_arcs=arcs))


def _cycle(g, s: int, inside: set, labels, avoid) -> tuple[list[int], list[int]]:
    """A shortest cycle s -> ... -> s inside the SCC, using no arc labelled `avoid`: (states, arc indices)."""
    parent: dict[int, tuple[int, int]] = {}
    queue = deque([s])
    seen = {s}
    while queue:
        u = queue.popleft()
        for a in range(g.offsets[u], g.offsets[u + 1]):
            if labels is not None and labels[a] == avoid:
                continue
            v = g.dst[a]
            if v == s:
                states, arcs = [s], [a]
                while u != s:
                    pu, pa = parent[u]
                    states.append(u)
                    arcs.append(pa)
                    u = pu
                return states[::-1], arcs[::-1]
            if v in inside and v not in seen:
                seen.add(v)
                parent[v] = (u, a)
                queue.append(v)
    raise AssertionError("a state of a nontrivial SCC lies on a cycle")


class Ctl(Check):
    def __init__(self, spec, formula, atoms: list, fairness: list[set]):
        super().__init__(spec)
        self.formula = formula
        self.atoms = atoms
        self.fairness = fairness

    def decide(self, view):
        if not view.complete:
            return Verdict.unknown(view.reason)
        k = view.kripke(self.fairness)
        atoms = [view.truth(a) for a in self.atoms]
        memo: dict = {}
        sat = k.label(self.formula, atoms, memo)
        if sat[0]:
            return Verdict.holds("true in the initial marking")
        path, cycle = k.explain(self.formula, atoms, 0, False, memo)
        arcs = getattr(k, "last_cycle_arcs", None) if cycle else None
        if arcs is not None and len(arcs) != len(cycle):
            arcs = None
        ev = path_evidence(view.g, path, cycle, arcs, k.arc_hints) if len(path) > 1 or cycle else None
        end = path[-1]
        if cycle:
            msg = f"false in the initial marking: a {'fair ' if self.fairness else ''}cycle through {_state_name(view, end)}"
        elif len(path) > 1 and k.dead[end]:
            msg = f"false in the initial marking: the path ends in dead {_state_name(view, end)}"
        elif len(path) > 1:
            msg = f"false in the initial marking: see {_state_name(view, end)}"
        else:
            msg = "false in the initial marking"
        return Verdict.violated(msg, ev)


def _slice(text, origin, e) -> str:
    """The source text of a sub-expression of a property text (for messages about one CTL atom)."""
    from cpn.properties.predicates import PREFIX

    sp = e.span
    if sp is None or sp.end_line is None or sp.end_col is None:
        return text
    wrapped = f"{PREFIX}{text};"
    starts = [0]
    for line in wrapped.splitlines(keepends=True):
        starts.append(starts[-1] + len(line))
    if sp.end_line >= len(starts):
        return text
    a = starts[sp.line - 1] + sp.col - 1 - len(PREFIX)
    b = starts[sp.end_line - 1] + sp.end_col - len(PREFIX)
    return text[a:b].strip() if 0 <= a < b <= len(text) else text


def _ctl_error(e, text, origin, span) -> ModelError:
    from cpn.properties.predicates import _remap

    return _remap(ModelError([Diagnostic(
        "E0702", "a temporal operator can only be combined with not, andalso, orelse and if-then-else",
        e.span, hint="Move the temporal operator out of the function, let or case expression.")]),
        text, origin, span)


__all__ = ["Check", "GraphView", "PredicateError", "Status"]
