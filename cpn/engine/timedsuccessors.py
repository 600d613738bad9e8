"""The compiled engine's successor function of a timed net (docs/semantics.md, Time), mixed into
`cpn.engine.compiled.CompiledEngine`.

A state's occurrence time is the clock if a binding element is ready then, else the earliest time one
is; the binding elements ready at it occur (with priorities, those of the most urgent priority among them). Transitions that do not read the clock have bindings and ready
times that do not depend on the time (the engine memoises them per tuple of read place ids,
`CompiledEngine._timed_miss`); the effects of those that touch a timed place depend on the occurrence time
and are memoised per (binding element, read ids, time) (`_fired`). A transition that reads the clock is
bound afresh at each time it is examined. Under time condensation every timestamp of a successor is moved
back by the occurrence time (`_shift`).
"""

from __future__ import annotations

from cpn.engine.api import P_NORMAL

NEG_INF = float("-inf")
INF = float("inf")


class TimedSuccessors:
    """The successors of a timed net's states. Mixed into `CompiledEngine`, whose place markings
    (`store`), memos, transition plans (`_fixed`, `_readers`), `_timed_miss`, `_add`, `_sub`, `_delta` and
    `_check_tokens` it uses."""

    def _writes(self, info, keys, consumed, produced, f, td):
        """New place ids after firing: (sets, adds). f is the firing time for timed places."""
        store = self.store
        sets = []
        adds = []
        prod: dict[int, list] = {}
        for p, items in produced:
            self._check_tokens(info, p, items)
            prod.setdefault(p, []).extend(items)
        for i, p in enumerate(info.read):
            cur = keys[i]
            c = consumed[i]
            if not c and p not in prod and p not in info.resets:
                continue
            timed = store.timed[p]
            if not timed and p not in info.resets:
                nid = cur
                if c:
                    nid = self._sub(p, nid, self._delta(p, c))
                items = prod.get(p)
                if items:
                    delta: dict = {}
                    for v, n, _dl in items:
                        if n:
                            delta[v] = delta.get(v, 0) + n
                    if delta:
                        nid = self._add(p, nid, self._delta(p, delta))
                if nid != cur:
                    sets.append((p, nid))
                continue
            d = dict(store.dicts[p][cur])
            if c:
                if timed:
                    _remove_timed(d, c, f + info.early[i])
                else:
                    for v, n in c.items():
                        left = d[v] - n
                        if left:
                            d[v] = left
                        else:
                            del d[v]
            if p in info.resets:
                d = {}
            for v, n, dl in prod.get(p, ()):
                if n:
                    k = (v, f + td + dl) if timed else v
                    d[k] = d.get(k, 0) + n
            nid = store.intern(p, d)
            if nid != cur:
                sets.append((p, nid))
        for p in info.writes:
            items = prod.get(p)
            if not items:
                continue
            timed = store.timed[p]
            delta: dict = {}
            for v, n, dl in items:
                if n:
                    k = (v, f + td + dl) if timed else v
                    delta[k] = delta.get(k, 0) + n
            if delta:
                did = self._delta(p, delta)
                adds.append((p, did, self._add_memo[p].setdefault(did, {})))
        return tuple(sets), tuple(adds)

    def _timed_successors(self, s: tuple) -> list:
        """Successors of a state of a timed net (docs/semantics.md, Time).

        Transitions that do not read the clock have bindings and ready times that do not depend on the
        time: they are computed once per input markings. A transition that reads the clock is bound afresh
        at each time it is examined (the clock, and the later timestamps of the tokens on the places it
        removes tokens from), in increasing order, up to the earliest time the others can occur at."""
        clock = s[-1]
        fixed = []  # (ready time, info, key, entry)
        append = fixed.append
        for info in self._fixed:
            key = info.getter(s)
            res = info.memo.get(key)
            if res is None:
                res = self._timed_miss(info, key, clock)
            for entry in res:
                append((entry[0], info, key, entry))
        now = [c for c in fixed if c[0] <= clock]
        if now:
            f = clock
        elif fixed:
            f = min(c[0] for c in fixed)
            now = [c for c in fixed if c[0] <= f]
        else:
            f = INF
        if self._readers:
            t, early = self._readers_at(s, clock, f)
            if t < f:  # a transition that reads the clock occurs before the others can
                f, now = t, early
            else:
                now.extend(early)
            now.sort(key=_by_transition)  # the fixed order: transitions in net order (stable within one)
        if f == INF:
            return []
        out = []
        fired = self._fired
        for _ready, info, key, entry in now:
            be, sets, adds = fired(info, key, entry, f)
            lst = list(s)
            for pos, nid in sets:
                lst[pos] = nid
            for pos, did, _memo in adds:
                lst[pos] = self._add(pos, lst[pos], did)
            if self.time_condensation:
                if f:
                    for p in range(len(self.places)):
                        if self.store.timed[p]:
                            lst[p] = self._shift(p, lst[p], f)
                lst[-1] = 0
            else:
                lst[-1] = f
            out.append((be, tuple(lst)))
        if self._has_priorities and len(out) > 1:
            prio = [entry[-1] if info.uses_time else self._prio.get(entry[1], P_NORMAL) for _r, info, _k, entry in now]
            best = min(prio)
            out = [o for o, p in zip(out, prio) if p == best]
        return out

    def _fired(self, info, key, entry, f) -> tuple:
        """(binding element, sets, adds) of an entry of `info`'s result for the read ids `key` occurring at
        time f (`_writes`). The effects of a transition that touches a timed place depend on f: they are
        computed once per (binding element, read ids, f)."""
        if not info.timed:
            return entry[1], entry[2], entry[3]
        be = entry[1]
        fk = (be, key, f)
        w = self._fire_memo.get(fk)
        if w is None:
            _, _, keys, consumed, produced, td, _pr = entry
            w = self._writes(info, keys, consumed, produced, f, td)
            self._fire_memo[fk] = w
        return be, w[0], w[1]

    def _readers_at(self, s: tuple, clock, f):
        """The occurrence time (at most f, the earliest time of the transitions that do not read the clock)
        and the enabled (ready, info, key, entry) of the transitions that read the clock, examined at the clock and
        at the later timestamps of their own input tokens."""
        readers = []
        times = {clock}
        for info in self._readers:
            rkey = info.getter(s)
            stamps = self._stamps(info, rkey, clock)
            readers.append((info, rkey, stamps))
            times.update(t for t in stamps if t < f)
        if f != INF:
            times.add(f)
        for t in sorted(times):
            now = []
            for info, rkey, stamps in readers:
                if t != clock and t not in stamps:
                    continue
                key = (rkey, t)
                res = info.memo.get(key)
                if res is None:
                    res = self._timed_miss(info, key, t)
                for entry in res:
                    if entry[0] <= t:
                        now.append((entry[0], info, key, entry))
            if now or t == f:
                return t, now
        return INF, []

    def _stamps(self, info, rkey, clock) -> frozenset:
        """The times later than the clock at which the tokens on the timed places a transition removes
        tokens from become ready: their timestamps, less an input arc's delay `e @+ k` (`rkey`: the ids of
        the places it reads)."""
        if not info.inputs:
            return frozenset()
        keys = rkey if len(info.read) > 1 else (rkey,)
        out: set = set()
        for i in info.inputs:
            p = info.read[i]
            memo = self._stamps_memo[p]
            got = memo.get(keys[i])
            if got is None:
                got = memo[keys[i]] = frozenset(ts for (_v, ts) in self.store.dicts[p][keys[i]])
            k = info.early[i]
            out.update(got if not k else (ts - k for ts in got))
        return frozenset(t for t in out if t > clock)

    def _shift(self, p: int, i: int, f: int) -> int:
        memo = self._shift_memo[p]
        k = (i, f)
        nid = memo.get(k)
        if nid is None:
            d: dict = {}
            for (v, ts), n in self.store.dicts[p][i].items():
                key = (v, max(ts - f, 0))
                d[key] = d.get(key, 0) + n
            nid = self.store.intern(p, d)
            memo[k] = nid
        return nid


def _by_transition(candidate) -> int:
    return candidate[1].t.index


def ready_time(d: dict, need: dict) -> float:
    """The earliest time at which the tokens `need` (value -> count) are all ready in timed multiset d."""
    ready = NEG_INF
    for v, n in need.items():
        stamps = sorted(ts for (w, ts), k in d.items() if w == v for _ in range(k))
        t = stamps[n - 1]
        if t > ready:
            ready = t
    return ready


def _remove_timed(d: dict, need: dict, f) -> None:
    """Remove, for each value, the tokens with the largest timestamps not after f (the occurrence time plus
    the input arcs' delay `e @+ k`)."""
    for v, n in need.items():
        stamps = sorted((ts for (w, ts) in d if w == v and ts <= f), reverse=True)
        for ts in stamps:
            if not n:
                break
            k = d[(v, ts)]
            take = min(k, n)
            n -= take
            if k == take:
                del d[(v, ts)]
            else:
                d[(v, ts)] = k - take
