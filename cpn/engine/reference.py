"""The reference interpreter: a slow, plainly correct successor function, the oracle of the tests.

It shares nothing with the compiled engine but the net's expressions and the tree-walking evaluator: bindings are
found by trying every combination of candidate values (from the tokens, the guard and the colour sets)
and keeping those that satisfy the definition of enabling; firing evaluates every inscription afresh.
"""

from __future__ import annotations

import functools
import itertools

from cpn.engine.api import P_NORMAL, EngineAPI
from cpn.errors import EvaluationError
from cpn.expr import binding as B
from cpn.expr import nodes as A
from cpn.expr.evaluate import global_cells, run_deep_again
from cpn.values.builtins import MLError
from cpn.values.colours import format_multiset
from cpn.values.multiset import Multiset, MultisetError, TimedMultiset

NEG_INF = float("-inf")


class ReferenceEngine(EngineAPI):
    """The `Engine` protocol by the definitions: states are tuples of frozensets of (token, count)."""

    reference = True

    def __init__(self, net, time_condensation: bool = False):
        self._setup(net, time_condensation)
        self.uids = {name: sym.uid for name, sym in net.variables.items()}
        # the net's reference cells: an evaluation run again on a deep stack starts from their values
        self._cells = global_cells(self.ev.globals)

    # -- states are tuples of frozensets of (key, count), plus the clock for timed nets
    def initial_state(self):
        s = tuple(frozenset(p.initial.items()) for p in self.places)
        return s + (0,) if self.is_timed else s

    def marking(self, s):
        return [dict(fs) for fs in s[: len(self.places)]]

    def token_counts(self, s):
        return tuple(sum(n for _, n in fs) for fs in s[: len(self.places)])

    def untimed(self, s):
        out = []
        for p, fs in zip(self.places, s):
            if p.timed:
                d: dict = {}
                for (v, _), n in fs:
                    d[v] = d.get(v, 0) + n
                out.append(frozenset(d.items()))
            else:
                out.append(fs)
        return tuple(out)

    def format_marking(self, s, p):
        pl = self.places[p]
        return format_multiset(pl.colour_set, s[p], timed=pl.timed)

    # -- evaluation helpers
    def _eval(self, e, env, t, what):
        try:
            saved = [c.value for c in self._cells]
            try:
                return self.ev.eval(e, env)
            except RecursionError:
                pass  # a function of the model recursing deeply: again on a deep stack, outside this handler
            for c, v in zip(self._cells, saved):  # so that the assignments of the first attempt count once
                c.value = v
            return run_deep_again(self.ev.eval, e, env)
        except (MLError, MultisetError, ArithmeticError, IndexError, TypeError, RecursionError) as exc:
            binding = {}
            for name in t.variables:
                if self.uids[name] in env:
                    binding[name] = self.net.colsets[self.net.variables[name].data].format(env[self.uids[name]])
            text = ", ".join(f"{k}={v}" for k, v in binding.items())
            raise EvaluationError(f"{what} of transition '{t.name}' failed"
                                  + (f" for binding <{text}>" if text else "") + f": {exc}",
                                  e.span, t.name, binding) from None

    def arc_tokens(self, e, env, t) -> list[tuple]:
        """The tokens of arc inscription e of transition t in environment env (`binding_env`): a list of
        (value, count, delay)."""
        v = self._eval(e, env, t, "an arc inscription")
        if isinstance(v, TimedMultiset):
            return [(x, n, d) for x, n, d in v.items]
        if isinstance(v, Multiset):
            return [(x, n, 0) for x, n in v.items()]
        return [(v, 1, 0)]

    def binding_env(self, t, assignment: dict) -> dict:
        """The environment in which transition t's inscriptions are evaluated for a binding (variable name
        -> value): its module parameters and its variables by uid."""
        env = dict(t.params)
        for name, v in assignment.items():
            env[self.uids[name]] = v
        return env

    # -- candidate values of variables
    def _collect(self, e, value, out):
        """Loose matching: every variable in a pattern position of e gets the matching part of value."""
        if B.is_var(e):
            out.setdefault(e.name, []).append(value)
        elif isinstance(e, (A.TupleE, A.ListE)):
            if isinstance(value, tuple) and len(value) == len(e.items):
                for x, v in zip(e.items, value):
                    self._collect(x, v, out)
        elif isinstance(e, A.RecordE):
            for (_, x), v in zip(sorted(e.fields, key=lambda f: f[0]), value):
                self._collect(x, v, out)
        elif isinstance(e, A.App) and B.is_constructor_fn(e.fn):
            info = e.fn.ref.data
            if info.kind == "index":
                self._collect(e.arg, value, out)
            elif isinstance(value, tuple) and value[0] == info.tag:
                self._collect(e.arg, value[1], out)
        elif isinstance(e, A.BinOp) and e.op == "::":
            if isinstance(value, tuple) and value:
                self._collect(e.left, value[0], out)
                self._collect(e.right, value[1:], out)

    def _summands(self, e):
        if isinstance(e, A.BinOp) and e.op in ("++", "+++"):
            return self._summands(e.left) + self._summands(e.right)
        if isinstance(e, A.BinOp) and e.op == "`":
            return [e.right]
        if isinstance(e, A.ToMs):
            return [e.expr]
        return []

    def _bindings(self, t, marking):
        views = [_view(p, marking[p.index]) for p in self.places]
        cands: dict[str, list] = {}
        for a in t.arcs:
            if a.kind.consumes and a.expr is not None:
                for term in self._summands(a.expr):
                    found: dict[str, list] = {}
                    for tok in views[a.place]:
                        self._collect(term, tok, found)
                    for name, vals in found.items():
                        cands.setdefault(name, []).extend(vals)
        order = [v for v in t.variables if v in cands]
        free = [v for v in t.variables if v not in cands and v in t.free]
        domains = [sorted(set(cands[v]), key=repr) for v in order]
        domains += [list(self.net.colsets[self.net.variables[v].data].values()) for v in free]
        names = order + free
        rest = [v for v in t.variables if v not in names]
        conj = B.guard_conjuncts(t.guards)
        for combo in itertools.product(*domains):
            assignment = dict(zip(names, combo))
            binders: set[int] = set()  # the conjuncts `v = e` that bound v: e is evaluated once (it may draw)
            ok = True
            for v in rest:  # bound by a guard conjunct pattern = expr
                if v in assignment:
                    continue
                for i, c in enumerate(conj):
                    gb = B.guard_binder(c, set(assignment))
                    if gb is None or v not in B.pattern_vars(gb[0]):
                        continue
                    items = gb[0].items if isinstance(gb[0], A.TupleE) else [gb[0]]
                    if all(B.is_var(x) for x in items) and not B.pattern_vars(gb[0]) & set(assignment):
                        binders.add(i)  # it holds by construction: not tested again
                    val = self._eval(gb[1], self.binding_env(t, assignment), t, "the guard")
                    found = {}
                    self._collect(gb[0], val, found)
                    for k, vals in found.items():
                        assignment.setdefault(k, vals[0])
                    break
                if v not in assignment:
                    ok = False
                    break
                cs = self.net.colsets[self.net.variables[v].data]
                if not cs.contains(assignment[v]):
                    ok = False
                    break
            if ok:
                yield assignment, binders

    def _enabled(self, t, marking, assignment, binders=frozenset()):
        """(consumed per place, ready time) if the binding is enabled (ignoring time), else None."""
        env = self.binding_env(t, assignment)
        need: dict[int, dict] = {}
        for a in t.arcs:
            if a.kind.consumes and a.expr is not None:
                for v, n, _ in self.arc_tokens(a.expr, env, t):
                    if n < 0:
                        return None
                    d = need.setdefault(a.place, {})
                    d[v] = d.get(v, 0) + n
        for p, d in need.items():
            view = _view_counts(self.places[p], marking[p])
            if any(view.get(v, 0) < n for v, n in d.items()):
                return None
        for i, g in enumerate(B.guard_conjuncts(t.guards)):
            if i not in binders and not self._eval(g, env, t, "the guard"):
                return None
        for a in t.arcs:
            if a.kind.blocks:
                view = _view_counts(self.places[a.place], marking[a.place])
                if a.expr is None:
                    if view:
                        return None
                else:
                    inh: dict = {}
                    for v, n, _ in self.arc_tokens(a.expr, env, t):
                        inh[v] = inh.get(v, 0) + n
                    if (not any(inh.values()) and view) or (any(inh.values()) and all(
                            view.get(v, 0) >= n for v, n in inh.items())):
                        return None
        ready = NEG_INF
        early = self.preemption[t.index]
        for p, d in need.items():
            if self.places[p].timed:
                for v, n in d.items():
                    stamps = sorted(ts for (w, ts), k in marking[p].items() if w == v for _ in range(k))
                    ready = max(ready, stamps[n - 1] - early.get(p, 0))
        return need, ready

    def successors(self, s, lazy: bool = False):
        """The enabled binding elements and their successors (docs/semantics.md, Time); with `lazy`, each
        successor is a function that computes it (simulate fires only the binding element it chooses, so
        that the output arcs of the others are not evaluated).

        Each transition is examined at the state's clock and at every later timestamp of a token on the
        places it removes tokens from, in increasing order; at a time t, its enabled bindings are those
        whose tokens are ready at t and whose guard holds with the clock at t. The first time at which
        some transition has an enabled binding is the occurrence time of all the enabled bindings."""
        n = len(self.places)
        marking = [dict(fs) for fs in s[:n]]
        clock = s[-1] if self.is_timed else 0
        examined = [self._examined_at(t, marking, clock) for t in self.transitions]
        now = []
        f = clock
        for f in sorted(set().union(*examined)) if examined else ():
            self.ev.time = f
            for t in self.transitions:
                if f not in examined[t.index]:
                    continue
                for assignment, binders in self._bindings(t, marking):
                    r = self._enabled(t, marking, assignment, binders)
                    if r is not None and r[1] <= f:
                        now.append((t, assignment, r[0]))
            if now:
                break
        if not now:
            return []
        self.ev.time = f
        if any(t.priority is not None for t in self.transitions):
            prios = [self._eval(t.priority, self.binding_env(t, a), t, "the priority") if t.priority is not None else P_NORMAL
                     for t, a, _ in now]
            best = min(prios)
            now = [c for c, p in zip(now, prios) if p == best]
        out = []
        for t, assignment, need in now:
            be = self._intern_be(t.index, tuple(assignment[v] for v in t.variables))
            out.append((be, functools.partial(self._fire, t, marking, assignment, need, f) if lazy
                        else self._fire(t, marking, assignment, need, f)))
        return out

    def _examined_at(self, t, marking, clock) -> set:
        """The times at which transition t is examined: the clock and the later times at which the tokens
        on the timed places it removes tokens from become ready (their timestamps, less the delay of an
        input arc `e @+ k`)."""
        times = {clock}
        early = self.preemption[t.index]
        for p in self.timed_inputs[t.index]:
            k = early.get(p, 0)
            times.update(ts - k for (_v, ts) in marking[p] if ts - k > clock)
        return times

    def _fire(self, t, marking, assignment, need, f):
        self.ev.time = f
        env = self.binding_env(t, assignment)
        m = [dict(d) for d in marking]
        early = self.preemption[t.index]
        for p, d in need.items():
            if self.places[p].timed:
                latest = f + early.get(p, 0)  # the largest timestamp available at f
                for v, n in d.items():
                    while n:
                        ts = max(ts for (w, ts) in m[p] if w == v and ts <= latest)
                        m[p][(v, ts)] -= 1
                        if not m[p][(v, ts)]:
                            del m[p][(v, ts)]
                        n -= 1
            else:
                for v, n in d.items():
                    m[p][v] -= n
                    if not m[p][v]:
                        del m[p][v]
        for a in t.arcs:
            if a.kind.empties:
                m[a.place] = {}
        if t.action is not None:  # a code segment: once per occurrence, before the delay and the output arcs
            v = self._eval(t.action, env, t, "the action")
            if len(t.outputs) == 1:
                env[self.uids[t.outputs[0]]] = v
            else:
                for name, x in zip(t.outputs, v if t.outputs else ()):
                    env[self.uids[name]] = x
        td = self._eval(t.delay, env, t, "the delay") if t.delay is not None else 0
        for a in t.arcs:
            if a.kind.produces and a.expr is not None:
                pl = self.places[a.place]
                items = self.arc_tokens(a.expr, env, t)  # a double arc puts back its own inscription
                for v, n, d in items:
                    if not pl.colour_set.contains(v):
                        raise EvaluationError(f"transition '{t.name}' puts a value outside colour set "
                                              f"{pl.colour_set.name} on place '{pl.name}'", a.span, t.name,
                                              code="E0402")
                    key = (v, f + td + d) if pl.timed else v
                    if n:
                        m[a.place][key] = m[a.place].get(key, 0) + n
        if self.is_timed and self.time_condensation:
            for p in self.places:
                if p.timed:
                    d2: dict = {}
                    for (v, ts), k in m[p.index].items():
                        key = (v, max(ts - f, 0))
                        d2[key] = d2.get(key, 0) + k
                    m[p.index] = d2
            f = 0
        s = tuple(frozenset(d.items()) for d in m)
        return s + (f,) if self.is_timed else s


def _view(place, d):
    return list(_view_counts(place, d))


def _view_counts(place, d):
    if not place.timed:
        return d
    out: dict = {}
    for (v, _), n in d.items():
        out[v] = out.get(v, 0) + n
    return out
