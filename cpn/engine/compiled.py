"""The compiled engine: generated binding functions, interned place markings, memoised transitions.

A state is a tuple of per-place multiset ids (plus the clock for timed nets). The enabled bindings of a
transition depend only on the markings of the places it reads, so each transition memoises its result
per tuple of those ids (LTSmin's transition groups): most states reuse a result computed before.
"""

from __future__ import annotations

import copy
import functools
import operator
from itertools import chain

from cpn.engine import codegen
from cpn.engine.api import P_NORMAL, EngineAPI
from cpn.engine.runtime import RUNTIME
from cpn.engine.timedsuccessors import NEG_INF, TimedSuccessors, ready_time
from cpn.errors import EvaluationError
from cpn.expr import nodes as E
from cpn.expr.evaluate import FUNCTION_FILE, run_deep_again
from cpn.values.builtins import MLError
from cpn.values.colours import format_multiset, outside
from cpn.values.multiset import MultisetError

# what a function of the model may raise while it is evaluated: reported with the binding (`_blame`)
_EVALUATION_ERRORS = (MLError, MultisetError, ArithmeticError, IndexError, TypeError, ValueError, KeyError)
#: after this many lookups, a transition whose results were reused less than MEMO_MISS_RATE of the time
#: stops keeping them (DP(12): most (Think, Forks) pairs occur once; MS(8): most Reply keys recur)
MEMO_PROBE: int = 4096
MEMO_MISS_RATE: float = 0.8
#: a transition keeps at most this many results; past it they are dropped (MS(8)'s Reply sees 111,537 keys,
#: each about once)
MEMO_MAX: int = 1 << 16


@functools.lru_cache(maxsize=4096)
def compiled_code(src: str, filename: str):
    """The code object of generated source, compiled once per process: a net loaded with other constant
    values, or a mutant, generates the same text for most transitions (values are in the namespace, not in
    the text). A code object is immutable; each engine executes it in a namespace of its own."""
    return compile(src, filename, "exec")


def canonical_key(d: dict):
    """A hashable key equal for equal multisets: the sorted items, flattened (a third of the memory of a
    frozenset of pairs), or a frozenset when the values cannot be ordered (mixed union values)."""
    try:
        items = sorted(d.items())
    except TypeError:
        return frozenset(d.items())
    return tuple(chain.from_iterable(items))


def _untimed(d: dict) -> dict:
    """A timed marking's untimed view: (value, timestamp) -> count becomes value -> count."""
    view: dict = {}
    for (v, _ts), n in d.items():
        view[v] = view.get(v, 0) + n
    return view


class _Places:
    """Interning of place markings: per place, id -> dict and frozenset key -> id."""

    def __init__(self, places):
        self.places = places
        n = len(places)
        self.dicts: list[list[dict]] = [[] for _ in range(n)]
        self.views: list[list[dict]] = [[] for _ in range(n)]  # untimed view (value -> count)
        self.index: list[dict] = [{} for _ in range(n)]
        self.counts: list[list[int]] = [[] for _ in range(n)]
        self.timed = [p.timed for p in places]
        self.pending: dict[int, int] = {}  # place -> its first id not in `index` yet (append_new)
        # timed places: per marking id, the id of its untimed view (equal views, equal ids), filled as asked
        self.untimed_ids: list[list[int]] = [[] for _ in range(n)]
        self._untimed_index: list[dict] = [{} for _ in range(n)]
        for p in range(n):
            self.intern(p, {})

    def untimed_id(self, p: int, i: int) -> int:
        """The id of the untimed view of marking i of timed place p (the ids of the markings up to i are
        filled on the way)."""
        ids, index, views = self.untimed_ids[p], self._untimed_index[p], self.views[p]
        while len(ids) <= i:
            ids.append(index.setdefault(frozenset(views[len(ids)].items()), len(index)))
        return ids[i]

    def intern(self, p: int, d: dict) -> int:
        key = canonical_key(d)
        idx = self.index[p]
        i = idx.get(key)
        if i is None:
            if self.pending and p in self.pending:
                self.index_pending(p)
                i = idx.get(key)
                if i is not None:
                    return i
            i = len(self.dicts[p])
            idx[key] = i
            self.dicts[p].append(d)
            self.views[p].append(_untimed(d) if self.timed[p] else d)
            self.counts[p].append(sum(d.values()))
        return i

    def append_new(self, p: int, dicts: list[dict]) -> None:
        """Append markings of place p that native code interned (distinct, and distinct from those here:
        their ids follow on); their keys go into `index` when it is next needed (`index_pending`)."""
        if not dicts:
            return
        self.pending.setdefault(p, len(self.dicts[p]))
        self.dicts[p].extend(dicts)
        self.views[p].extend(map(_untimed, dicts) if self.timed[p] else dicts)
        self.counts[p].extend([sum(d.values()) for d in dicts])

    def index_pending(self, p: int) -> None:
        """Put the keys of place p's markings appended by `append_new` into `index`."""
        start = self.pending.pop(p, None)
        if start is None:
            return
        idx, dicts = self.index[p], self.dicts[p]
        for i in range(start, len(dicts)):
            if idx.setdefault(canonical_key(dicts[i]), i) != i:
                raise RuntimeError(f"native tables out of step with the engine (place {p}: a marking has two ids)")


class TransitionGroups:
    """`successors` split per transition, for a search that caches each transition's result itself.

    Group k reads the places `groups[k][0]` and only writes the places `groups[k][1]`. `results(k, key)`
    gives, for the ids `key` of the places it reads, its enabled binding elements in the engine's order,
    each as the values (binding element, new id of every read place, delta id of every written place),
    all in one flat list; the id of
    written place p after the binding is `add(p, old id, delta id)`. A successor of state s is s with
    those ids put in: the same states in the same order as `successors(s)`.
    """

    def __init__(self, engine: CompiledEngine):
        self._engine = engine
        self.groups = [(tuple(i.read), tuple(i.writes)) for i in engine._plan]

    def caller_caches(self) -> None:
        """The caller keeps every result from now on: the engine stops memoising its own copies."""
        for info in self._engine._plan:
            info.store_results = False
            info.memo.clear()

    def engine_caches(self) -> None:
        """The caller stops caching: the engine memoises its results again (as when it was built)."""
        for info in self._engine._plan:
            info.store_results = True
            info.lookups = 0

    def results(self, k: int, key: tuple) -> list[int]:
        """The entries of group k for `key`, one after the other in one flat list."""
        e = self._engine
        info = e._plan[k]
        nr = len(info.read)
        memo_key = key if nr > 1 else (key[0] if nr == 1 else ())
        res = info.memo.get(memo_key)
        if res is None:
            res = e._miss(info, memo_key)
        if not info.writes:
            return [v for entry in res for v in entry]
        out: list[int] = []
        extend = out.extend
        cut = 1 + nr
        for entry in res:
            extend(entry[:cut])
            extend(entry[cut + 1::2])
        return out

    def add(self, p: int, cur: int, did: int) -> int:
        return self._engine._add(p, cur, did)


class CompiledEngine(TimedSuccessors, EngineAPI):
    """Successor function of a net, compiled to Python; see docs/internals.md for the protocol."""

    reference = False

    def __init__(self, net, time_condensation: bool = False):
        self._setup(net, time_condensation)
        self.store = _Places(net.places)
        self._add_memo: list[dict] = [{} for _ in net.places]  # place -> delta id -> {id: id}
        self._sub_memo: list[dict] = [{} for _ in net.places]
        self._members: list[set] = [set() for _ in net.places]  # values known to be in the colour set
        self._recipes: dict[int, tuple] = {}  # binding element -> its effect (untimed transitions)
        self._nstates = 0  # calls of successors(), to judge how often memoised results are reused
        self._delta_index: list[dict] = [{} for _ in net.places]
        self._deltas: list[list[dict]] = [[] for _ in net.places]
        self._shift_memo: list[dict] = [{} for _ in net.places]
        self._fire_memo: dict = {}
        self._has_priorities = any(t.priority is not None for t in net.transitions)
        self._prio: dict[int, int] = {}
        self._compile()

    # ------------------------------------------------------------------ compilation
    def _compile_functions(self) -> dict:
        """Compile the model's global functions of one argument; the rest stay with the evaluator."""
        ns = codegen.Namespace()
        functions: dict[int, object] = {}
        var_uids = {name: sym.uid for name, sym in self.net.variables.items()}
        fc = codegen.FunctionCodegen(ns, self.ev, functions, var_uids)
        sources = []
        decls = [d for d in self.net.globals.decls if isinstance(d, E.FunDecl)]
        for d in decls:
            functions[d.ref.uid] = None  # visible to its own recursive calls and to later functions
            src = fc.compile(d)
            if src is None:
                del functions[d.ref.uid]  # stays with the evaluator
            else:
                sources.append((d, src))
        glob = dict(RUNTIME)
        glob.update(ns.objects)
        ev = self.ev
        glob["TIMEFN"] = lambda _u: ev.time
        for d, src in sources:
            exec(compiled_code(src, f"{FUNCTION_FILE}{d.name}>"), glob)  # noqa: S102 - generated from the AST
        for d, _ in sources:
            functions[d.ref.uid] = glob[f"_F{d.ref.uid}"]
        return functions

    def _compile(self) -> None:
        self._plan = []
        self.functions = self._compile_functions()
        self.sources: dict[int, str] = {}
        timed_places = {p.index for p in self.places if p.timed}
        for t in self.transitions:
            read = []
            for a in t.arcs:
                if a.kind.reads and a.place not in read:
                    read.append(a.place)
            writes = []
            for a in t.arcs:
                if a.kind.produces and a.place not in read and a.place not in writes:
                    writes.append(a.place)
            ns = codegen.Namespace()
            gen = codegen.TransitionCodegen(t, self.net, ns, self.ev, read)
            gen.ec.functions = self.functions
            fname, src = gen.generate()
            # read the clock directly or through the functions it calls (cpn.engine.clock)
            uses_time = t.index in self.clock_reads
            glob = dict(RUNTIME)
            glob.update(ns.objects)
            glob["EVAL"] = self.ev.eval
            ev = self.ev
            glob["TIMEFN"] = lambda _u, ev=ev: ev.time
            filename = f"<cpn transition {t.name}>"
            code = compiled_code(src, filename)
            exec(code, glob)  # noqa: S102 - source generated from the typed AST, not from model text
            fn = glob[fname]
            self.sources[t.index] = src
            timed_t = uses_time or any(p in timed_places for p in read + writes)
            if len(read) == 0:
                getter = _const_key
            elif len(read) == 1:
                getter = operator.itemgetter(read[0])
            else:
                getter = operator.itemgetter(*read)
            resets = {a.place for a in t.arcs if a.kind.empties}
            info = _TInfo(t, fn, read, writes, getter, {}, timed_t, uses_time, resets, gen.blame, filename)
            info.inputs = [read.index(p) for p in self.timed_inputs[t.index]]
            info.early = [self.preemption[t.index].get(p, 0) for p in read]
            self._plan.append(info)
        self._fast = [(i.getter, i.memo.get, i) for i in self._plan]
        self._fixed = [i for i in self._plan if not i.uses_time]
        self._readers = [i for i in self._plan if i.uses_time]
        self._stamps_memo: list[dict] = [{} for _ in self.places]
        self._flat = not self.is_timed and not self._has_priorities
        if self._flat:
            self._count = [0]
            self.successors = self._generate_successors()

    def uncondensed(self) -> CompiledEngine:
        """This engine without time condensation (itself if it has none): its twin sharing the compiled
        transitions, the interned markings and the memo tables, none of which depends on condensation (it
        only moves the successors' timestamps back by the occurrence time). What replays a condensed trace
        to print its model times, without compiling the net again."""
        if not self.time_condensation:
            return self
        twin = self.__dict__.get("_twin")
        if twin is None:
            twin = copy.copy(self)
            twin.time_condensation = False
            self._twin = twin
        return twin

    # ------------------------------------------------------------------ protocol
    def initial_state(self) -> tuple:
        ids = [self.store.intern(p.index, dict(p.initial)) for p in self.places]
        if self.is_timed:
            ids.append(0)
        return tuple(ids)

    def marking(self, s: tuple) -> list[dict]:
        d = self.store.dicts
        return [dict(d[p][s[p]]) for p in range(len(self.places))]

    def token_counts(self, s: tuple) -> tuple:
        c = self.store.counts
        return tuple(c[p][s[p]] for p in range(len(self.places)))

    def place_view(self, s: tuple, p: int) -> dict:
        """The untimed multiset of place p in state s (value -> count); do not mutate."""
        return self.store.views[p][s[p]]

    def untimed(self, s: tuple):
        """The state less its clock, each timed place's marking id replaced by the id of its untimed view."""
        if not self.is_timed:
            return s
        store = self.store
        out = list(s[:len(self.places)])
        for p in self._timed_positions:
            i = out[p]
            ids = store.untimed_ids[p]
            out[p] = ids[i] if i < len(ids) else store.untimed_id(p, i)
        return tuple(out)

    @functools.cached_property
    def _timed_positions(self) -> tuple[int, ...]:
        return tuple(p for p in range(len(self.places)) if self.store.timed[p])

    def format_marking(self, s: tuple, p: int) -> str:
        pl = self.places[p]
        return format_multiset(pl.colour_set, self.store.dicts[p][s[p]].items(), timed=pl.timed)

    def forget_memo(self) -> None:
        """Empty the memo tables of transition results (keyed by the markings of the places a transition
        reads) and of single occurrences: this changes no result, only what is computed again (the
        sweep-line method calls it as it leaves markings behind)."""
        for info in self._plan:
            info.memo.clear()  # in place: the generated successor function keeps bound `memo.get` methods
        self._fire_memo.clear()

    def successor_groups(self) -> TransitionGroups | None:
        """The untimed successor function without priorities as LTSmin's transition groups: one per
        transition, with the places it reads and those it only writes (None for other nets)."""
        return TransitionGroups(self) if self._flat else None

    def timed_groups(self):
        """A timed net's or a net with priorities' successor function as groups whose binding elements are
        then selected at once (`cpn.engine.timedgroups`); None for other nets and where a transition
        reads the clock (it is examined at more times than the clock and the occurrence time)."""
        if self._flat or self.reads_clock:
            return None
        from cpn.engine.timedgroups import TimedGroups

        return TimedGroups(self)

    def native_code(self):
        """(the C of this net's transitions, None) for the native search (`cpn.engine.ccodegen`), or
        (None, why) where no place marking can be held in C; computed once."""
        got = getattr(self, "_native_code", None)
        if got is None:
            from cpn.engine import ccodegen

            try:
                got = (ccodegen.native_code(self), None) if self._flat else \
                    (None, "the net is timed" if self.is_timed else "the net has priorities")
            except ccodegen.NotNative as exc:
                got = (None, str(exc))
            self._native_code = got
        return got

    # ------------------------------------------------------------------ successors
    def successors(self, s: tuple) -> list[tuple[int, tuple]]:
        self._nstates += 1
        if self.is_timed:
            return self._timed_successors(s)
        out = []
        append = out.append
        for getter, memo_get, info in self._fast:
            key = getter(s)
            res = memo_get(key)
            if res is None:
                res = self._miss(info, key)
            if not res:
                continue
            for be, sets, adds in res:
                lst = list(s)
                for pos, nid in sets:
                    lst[pos] = nid
                if adds:
                    # adds go to places the transition does not read: their id is the state's
                    for pos, did, memo in adds:
                        nid = memo.get(s[pos])
                        lst[pos] = nid if nid is not None else self._add(pos, s[pos], did)
                append((be, tuple(lst)))
        if self._has_priorities and out:
            out = self._by_priority(out)
        return out

    def _add(self, p: int, cur: int, did: int) -> int:
        """The id of place p's marking `cur` plus the tokens of delta `did` (memoised per delta)."""
        memo = self._add_memo[p].setdefault(did, {})
        nid = memo.get(cur)
        if nid is None:
            d = dict(self.store.dicts[p][cur])
            for v, n in self._deltas[p][did].items():
                d[v] = d.get(v, 0) + n
            nid = self.store.intern(p, d)
            memo[cur] = nid
        return nid

    def _sub(self, p: int, cur: int, did: int) -> int:
        """The id of place p's marking `cur` minus the tokens of delta `did` (included; memoised)."""
        memo = self._sub_memo[p].setdefault(did, {})
        nid = memo.get(cur)
        if nid is None:
            d = dict(self.store.dicts[p][cur])
            for v, n in self._deltas[p][did].items():
                left = d[v] - n
                if left:
                    d[v] = left
                else:
                    del d[v]
            nid = self.store.intern(p, d)
            memo[cur] = nid
        return nid

    def _delta(self, p: int, d: dict) -> int:
        key = frozenset(d.items())
        idx = self._delta_index[p]
        i = idx.get(key)
        if i is None:
            i = len(self._deltas[p])
            idx[key] = i
            self._deltas[p].append(d)
        return i

    def _call(self, info, views):
        try:
            return info.fn(*views)
        except RecursionError:
            pass  # retried below, outside this handler, so that the first attempt's frames are freed
        except _EVALUATION_ERRORS as exc:
            raise self._blame(info, exc) from None
        try:
            # a function of the model recursed deeper than Python's limit: again on a deep stack
            return run_deep_again(info.fn, *views)
        except (*_EVALUATION_ERRORS, RecursionError) as exc:
            raise self._blame(info, exc) from None

    def _blame(self, info, exc) -> EvaluationError:
        tb = exc.__traceback__
        line = None
        local = {}
        while tb is not None:
            if tb.tb_frame.f_code.co_filename == info.filename:
                line = tb.tb_lineno
                local = tb.tb_frame.f_locals
            tb = tb.tb_next
        kind, obj = info.blame.get(line, ("transition", None))
        t = info.t
        binding = {}
        for i, v in enumerate(t.variables):
            if f"v{i}" in local:
                cs = self.net.colsets[self.net.variables[v].data]
                try:
                    binding[v] = cs.format(local[f"v{i}"])
                except Exception:  # noqa: BLE001
                    binding[v] = repr(local[f"v{i}"])
        # the transition instance ("M'T 2"): a module instantiated twice has two transitions named T
        what = {"guard": f"the guard of transition '{t.name}'", "arc": f"the inscription of arc "
                f"{getattr(obj, 'label', '')} of transition '{t.name}'", "delay": f"the delay of transition '{t.name}'",
                "priority": f"the priority of transition '{t.name}'"}.get(kind, f"transition '{t.name}'")
        bind_text = ", ".join(f"{k}={v}" for k, v in binding.items())
        msg = f"{what} failed for binding <{bind_text}>: {_reason(exc)}" if bind_text else f"{what} failed: {_reason(exc)}"
        span = getattr(obj, "span", None) or t.span
        hint = "Guards and inscriptions are evaluated for every candidate binding; guard the failing operation."
        return EvaluationError(msg, span, t.name, binding, hint, self.net.source)

    def _miss(self, info, key):
        """Enabled bindings of an untimed transition on the place markings `key`, with their effects."""
        read = info.read
        keys = key if len(read) > 1 else ((key,) if read else ())
        views = [self.store.views[p][i] for p, i in zip(read, keys)]
        res = []
        recipes = self._recipes
        sub_memo, add_memo = self._sub_memo, self._add_memo
        if self._flat:
            frecipes = info.frecipes
            for item in self._call(info, views):
                r = frecipes.get(item[0])
                if r is None:
                    r = frecipes[item[0]] = self._flat_recipe(info, item)
                entry = [r[0]]
                for cur, step in zip(keys, r[1]):
                    if step is None:
                        entry.append(cur)
                        continue
                    p, sd, smemo, ad, amemo, reset = step
                    nid = 0 if reset else cur
                    if smemo is not None:
                        n2 = smemo.get(nid)
                        nid = n2 if n2 is not None else self._sub(p, nid, sd)
                    if amemo is not None:
                        n2 = amemo.get(nid)
                        nid = n2 if n2 is not None else self._add(p, nid, ad)
                    entry.append(nid)
                res.append(tuple(entry) + r[2])
            return self._keep(info, key, res)
        for bvals, consumed, produced, _td, pr in self._call(info, views):
            be = self._intern_be(info.t.index, bvals)
            if self._has_priorities:
                self._prio[be] = pr if pr is not None else P_NORMAL
            recipe = recipes.get(be)
            if recipe is None:
                recipe = recipes[be] = self._recipe(info, consumed, produced)
            changes, adds = recipe
            sets = []
            for i, p, sd, ad, reset in changes:
                cur = keys[i]
                nid = 0 if reset else cur
                if sd is not None and not reset:
                    m = sub_memo[p].get(sd)
                    n2 = m.get(nid) if m is not None else None
                    nid = n2 if n2 is not None else self._sub(p, nid, sd)
                if ad is not None:
                    m = add_memo[p].get(ad)
                    n2 = m.get(nid) if m is not None else None
                    nid = n2 if n2 is not None else self._add(p, nid, ad)
                if nid != cur:
                    sets.append((p, nid))
            res.append((be, tuple(sets), adds))
        return self._keep(info, key, res)

    def _keep(self, info, key, res):
        """Memoise a transition's result for `key`, unless its inputs rarely repeat."""
        info.lookups += 1
        if info.store_results:
            if len(info.memo) >= MEMO_MAX:
                info.memo.clear()
            info.memo[key] = res
            nstates = self._count[0] if self._flat else self._nstates
            if info.lookups == MEMO_PROBE and MEMO_PROBE > nstates * MEMO_MISS_RATE:
                # this transition's input markings rarely repeat: stop keeping its results
                info.store_results = False
                info.memo.clear()
        return res

    def _flat_recipe(self, info, item) -> tuple:
        """For one binding of an untimed transition: its binding element, how each read place changes
        (None: unchanged), and the constant tail of its memo entries: (add memo, delta id) for every place
        the transition only writes (the empty delta where this binding puts nothing)."""
        bvals, consumed, produced, _td, _pr = item
        be = self._intern_be(info.t.index, bvals)
        changes, adds = self._recipe(info, consumed, produced)
        steps: list = [None] * len(info.read)
        for i, p, sd, ad, reset in changes:
            # the memo dicts themselves, so that a miss costs one lookup per place
            smemo = self._sub_memo[p].setdefault(sd, {}) if sd is not None and not reset else None
            amemo = self._add_memo[p].setdefault(ad, {}) if ad is not None else None
            steps[i] = (p, sd, smemo, ad, amemo, reset)
        added = {p: (memo, did) for p, did, memo in adds}
        tail: list = []
        for p in info.writes:
            got = added.get(p)
            if got is None:
                did = self._delta(p, {})
                got = (self._add_memo[p].setdefault(did, {}), did)
            tail.extend(got)
        return be, tuple(steps), tuple(tail)

    def _generate_successors(self):
        """One Python function computing all successors of an untimed net without priorities: the state is
        unpacked once, each transition's memoised results are patched into a tuple display."""
        n = len(self.places)
        svars = [f"s{i}" for i in range(n)]
        lines = ["def successors(s):"]
        lines.append(f"    {', '.join(svars)}{',' if n == 1 else ''} = s" if n else "    pass")
        lines.append("    COUNT[0] += 1")
        lines.append("    out = []")
        lines.append("    append = out.append")
        glob = {"COUNT": self._count, "ADD": self._add, "MISS": self._miss}
        for k, info in enumerate(self._plan):
            glob[f"G{k}"] = info.memo.get
            glob[f"I{k}"] = info
            read, writes = info.read, info.writes
            if len(read) == 0:
                key = "()"
            elif len(read) == 1:
                key = f"s{read[0]}"
            else:
                key = "(" + ", ".join(f"s{p}" for p in read) + ")"
            lines.append(f"    key = {key}")
            lines.append(f"    res = G{k}(key)")
            lines.append("    if res is None:")
            lines.append(f"        res = MISS(I{k}, key)")
            names = ["be"] + [f"r{p}" for p in read]
            for p in writes:
                names += [f"m{p}", f"d{p}"]
            lines.append(f"    for {', '.join(names)}{',' if len(names) == 1 else ''} in res:")
            for p in writes:
                lines.append(f"        x{p} = m{p}.get(s{p})")
                lines.append(f"        if x{p} is None:")
                lines.append(f"            x{p} = ADD({p}, s{p}, d{p})")
            comps = []
            for p in range(n):
                comps.append(f"r{p}" if p in read else f"x{p}" if p in writes else f"s{p}")
            lines.append(f"        append((be, ({', '.join(comps)}{',' if n == 1 else ''})))")
        lines.append("    return out")
        src = "\n".join(lines)
        exec(compiled_code(src, f"<cpn successors of {self.net.name}>"), glob)  # noqa: S102 - generated
        self.successors_source = src
        return glob["successors"]

    def _recipe(self, info, consumed, produced):
        """The effect of one binding element of an untimed transition on each place it touches."""
        prod: dict[int, dict] = {}
        for p, items in produced:
            self._check_tokens(info, p, items)
            d = prod.setdefault(p, {})
            for v, n, _dl in items:
                if n:
                    d[v] = d.get(v, 0) + n
        changes = []
        for i, p in enumerate(info.read):
            c = consumed[i]
            reset = p in info.resets
            sd = self._delta(p, c) if c else None
            ad = self._delta(p, prod[p]) if prod.get(p) else None
            if sd is not None or ad is not None or reset:
                changes.append((i, p, sd, ad, reset))
        adds = []
        for p in info.writes:
            if prod.get(p):
                did = self._delta(p, prod[p])
                adds.append((p, did, self._add_memo[p].setdefault(did, {})))
        return tuple(changes), tuple(adds)

    def _by_priority(self, out):
        prio = self._prio
        best = min(prio.get(be, P_NORMAL) for be, _ in out)
        return [(be, s) for be, s in out if prio.get(be, P_NORMAL) == best]

    def _check_tokens(self, info, p, items):
        known = self._members[p]
        cs = self.places[p].colour_set
        for v, _n, _d in items:
            if v in known:
                continue
            if cs.contains(v):
                known.add(v)
            else:
                arc = next((a for a in info.t.arcs if a.place == p and a.kind.produces), None)
                raise EvaluationError(
                    f"transition '{info.t.name}' puts {_fmt(cs, v)} on place '{self.places[p].name}', "
                    f"outside its colour set {outside(cs, v)}",
                    arc.span if arc else info.t.span, info.t.name, None,
                    f"Make the inscription of arc {arc.label if arc else ''} produce values of {cs.name}.",
                    self.net.source, code="E0402")

    # ------------------------------------------------------------------ timed nets (cpn.engine.timedsuccessors)
    def _timed_miss(self, info, key, clock):
        """A transition's entries for the read ids `key` (and the time, where it reads the clock), bound at
        `clock` and kept in its memo: (ready time, binding element, read ids, consumed, produced, delay,
        priority) where it touches a timed place (its effects depend on the occurrence time: `_fired`),
        else (-inf, binding element, sets, adds)."""
        read = info.read
        rkey = key[0] if info.uses_time else key
        keys = rkey if len(read) > 1 else ((rkey,) if read else ())
        views = [self.store.views[p][i] for p, i in zip(read, keys)]
        self.ev.time = clock
        bindings = self._call(info, views)
        res = []
        for bvals, consumed, produced, td, pr in bindings:
            be = self._intern_be(info.t.index, bvals)
            if self._has_priorities:
                self._prio[be] = pr if pr is not None else P_NORMAL
            if info.timed:
                ready = NEG_INF
                for i, p in enumerate(read):
                    c = consumed[i]
                    if c and self.store.timed[p]:
                        r = ready_time(self.store.dicts[p][keys[i]], c) - info.early[i]
                        if r > ready:
                            ready = r
                # the priority travels with the entry: for a transition that reads the clock it may
                # differ from one time to another
                res.append((ready, be, keys, consumed, produced, td, pr if pr is not None else P_NORMAL))
            else:
                sets, adds = self._writes(info, keys, consumed, produced, 0, 0)
                res.append((NEG_INF, be, sets, adds))
        if len(info.memo) >= MEMO_MAX:
            info.memo.clear()
        info.memo[key] = res
        return res


class _TInfo:
    __slots__ = ("t", "fn", "read", "writes", "getter", "memo", "timed", "uses_time", "resets", "blame",
                 "filename", "lookups", "store_results", "frecipes", "inputs", "early")

    def __init__(self, t, fn, read, writes, getter, memo, timed, uses_time, resets, blame, filename):
        self.t, self.fn, self.read, self.writes, self.getter = t, fn, read, writes, getter
        self.memo, self.timed, self.uses_time, self.resets = memo, timed, uses_time, resets
        self.blame, self.filename = blame, filename
        self.lookups = 0
        self.store_results = True
        self.frecipes: dict = {}  # binding values -> flat recipe (generated successor function)
        self.inputs: list[int] = []  # positions in `read` of the timed places it removes tokens from
        self.early: list[int] = []  # per read place: its input arcs' delay `e @+ k` (CPN Tools' preemption)


def _const_key(_s):
    return ()


def _reason(exc: BaseException) -> str:
    if isinstance(exc, ZeroDivisionError):
        return "division by zero"
    if isinstance(exc, RecursionError):
        return "recursion too deep"
    return str(exc) or type(exc).__name__


def _fmt(cs, v):
    try:
        return cs.format(v)
    except Exception:  # noqa: BLE001
        return repr(v)

