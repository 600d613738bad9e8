"""`cpn-verify mcc MODEL.pnml PROPERTIES.xml`: answer a Model Checking Contest property file.

Every formula of the file is answered on standard output in the contest's format, one line each, in file
order: ``FORMULA <id> TRUE|FALSE TECHNIQUES ...``, ``FORMULA <id> <bound> TECHNIQUES ...`` for
UpperBounds, or ``FORMULA <id> CANNOT_COMPUTE`` (the reason on standard error) when a limit stops it.
Reachability (``E F p``, ``A G p``) is searched on the fly and stops at the first witness; LTL (``A phi``)
on the fly with a Büchi automaton (`cpn.checks.ltl`); UpperBounds and every other CTL formula on the state
space, generated once for the whole file (`cpn.checks.ctl`). The contest reads a path that ends in a
deadlock as repeating its last marking forever (docs/mcc.md).
"""

from __future__ import annotations

import argparse
import operator
import sys
import time
from array import array
from collections import deque
from dataclasses import dataclass
from operator import itemgetter

from cpn.cli._common import ExitStatus, UsageError, add_quiet_option
from cpn.properties import contest as c

TECHNIQUES = "TECHNIQUES EXPLICIT SEQUENTIAL_PROCESSING"
DEFAULT_MAX_STATES = 3_000_000
#: the markings a reachability search generates on the fly before the whole state space takes over
FLY_STATES = 25_000


EPILOG = """exit statuses:
  0   every formula answered (TRUE, FALSE or a bound: a FALSE answer is an answer, not a failure)
  2   some formula could not be answered within the limits (CANNOT_COMPUTE)
  64  bad usage, or a file that does not exist
  65  a model or property file that cannot be read, or a formula naming a place or transition the
      model does not have (every such name is reported, with its line and column, before any answer)
  70  internal error (a bug in cpn-verify: please report it)
"""


def add_parser(subparsers) -> argparse.ArgumentParser:
    p = subparsers.add_parser("mcc", help="answer a Model Checking Contest property file on a PNML model",
                              description=__doc__.split("\n\n")[1], epilog=EPILOG,
                              formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("model", metavar="MODEL", help="the PNML model (P/T or symmetric net)")
    p.add_argument("properties", metavar="PROPERTIES", help="the contest's XML property file")
    p.add_argument("--max-states", type=int, default=DEFAULT_MAX_STATES, metavar="N",
                   help=f"give up (CANNOT_COMPUTE) a formula whose search passes N states (default {DEFAULT_MAX_STATES:,})")
    p.add_argument("--max-seconds", type=float, metavar="S", help="give up the formulas not answered after S seconds")
    p.add_argument("--stats", action="store_true", help="after each answer, print on standard error the states "
                   "the formula generated and its time")
    add_quiet_option(p)
    return p


# ----------------------------------------------------------------------------- answering
class CannotCompute(Exception):
    """A limit (states, time) stopped a formula's search."""


class _FlyBudget(Exception):
    """An on-the-fly search passed its budget (`ContestModel.fly_states`): the state space takes over."""


@dataclass
class Answer:
    id: str
    value: object  # True, False, an int (UpperBounds), or None (CANNOT_COMPUTE)
    reason: str = ""
    states: int = 0  # the distinct markings this formula's search generated
    seconds: float = 0.0
    technique: str = ""

    def line(self) -> str:
        if self.value is None:
            return f"FORMULA {self.id} CANNOT_COMPUTE"
        v = ("TRUE" if self.value else "FALSE") if isinstance(self.value, bool) else str(self.value)
        return f"FORMULA {self.id} {v} {TECHNIQUES}{' ' + self.technique if self.technique else ''}"


class ContestModel:
    """A contest model and what its formulas need: the engine, the PNML ids of places and transitions,
    the markings generated so far (shared by the formulas), and the whole state space once built."""

    def __init__(self, engine, node_names: dict[str, str], max_states: int = DEFAULT_MAX_STATES,
                 graph_max_states: int | None = None,
                 deadline: float | None = None, ctl_stutter: bool = False) -> None:
        from cpn.checks.ltl import Cache

        self.ctl_stutter = ctl_stutter

        self.engine = engine
        self.cache = Cache(engine)
        self._new_cache = lambda: Cache(engine)
        self.max_states = max_states  # the markings one search through `successors` may generate
        # the states of the whole state space built by the explorer (natively, far cheaper per state)
        self.graph_max_states = graph_max_states or max_states
        self.fly_states = FLY_STATES
        self.deadline = deadline
        self._tnames = {t.name: i for i, t in enumerate(engine.transitions)}
        self._be_transition: dict[int, int] = {}
        body = {_body(p.name): i for i, p in enumerate(engine.places)}
        tbody = {_body(t.name): i for i, t in enumerate(engine.transitions)}
        self.place = {pid: body[name] for pid, name in node_names.items() if name in body}
        self.transition = {tid: tbody[name] for tid, name in node_names.items() if name in tbody}
        self._counts: dict = {}
        self._fire: dict = {}
        self._graph = None
        self._kripke = None
        self._rows = None
        self.explored = 0  # the states of the whole state space, once it was built
        self._columns = None
        self._qcols: dict | None = None
        self._arc_transitions = None
        self._file = ""

    def forget(self) -> None:
        """Forget the markings generated so far (to time a property file on its own)."""
        self.cache = self._new_cache()
        self._counts, self._fire, self._graph, self._columns, self._kripke = {}, {}, None, None, None
        self._qcols = None
        self._rows = None
        self.explored = 0

    @classmethod
    def load(cls, path: str, **kw) -> ContestModel:
        import cpn
        from cpn.io.pnml import translate_with_origins

        model = cpn.load(path)
        return cls(model.engine(), translate_with_origins(path).node_names, **kw)

    # ------------------------------------------------------------------ atoms
    def counts(self, s) -> tuple:
        got = self._counts.get(s)
        if got is None:
            got = self._counts[s] = self.engine.token_counts(s)
        return got

    def fireable(self, s) -> frozenset:
        got = self._fire.get(s)
        if got is None:
            got = self._fire[s] = frozenset(map(self.transition_of, (be for be, _t in self.cache.successors(s))))
        return got

    def transition_of(self, be: int) -> int:
        """The transition instance (index) of a binding element."""
        t = self._be_transition.get(be)
        if t is None:
            tr = self.engine.binding_element(be).transition
            t = self._be_transition[be] = tr if isinstance(tr, int) else self._tnames[tr.name]
        return t

    def predicate(self, f: c.Node):
        """A function state -> value of a state formula (or integer expression)."""
        if isinstance(f, c.Bool):
            return lambda s, v=f.value: v
        if isinstance(f, c.Not):
            g = self.predicate(f.arg)
            return lambda s: not g(s)
        if isinstance(f, (c.And, c.Or)):
            parts = [self.predicate(a) for a in f.args]
            if isinstance(f, c.And):
                return lambda s: all(p(s) for p in parts)
            return lambda s: any(p(s) for p in parts)
        if isinstance(f, c.IntLe):
            left, right = self.predicate(f.left), self.predicate(f.right)
            return lambda s: left(s) <= right(s)
        if isinstance(f, c.IntConst):
            return lambda s, v=f.value: v
        if isinstance(f, (c.Tokens, c.PlaceBound)):
            idx = [self._index(self.place, p, "place", f) for p in f.places]
            if not idx:
                return lambda s: 0
            if len(idx) == 1:
                return lambda s, i=idx[0]: self.counts(s)[i]
            pick = itemgetter(*idx)
            return lambda s: sum(pick(self.counts(s)))
        if isinstance(f, c.Fireable):
            want = frozenset(self._index(self.transition, t, "transition", f) for t in f.transitions)
            return lambda s: not want.isdisjoint(self.fireable(s))
        raise CannotCompute(f"not a state formula: {c.show(f)}")

    def _index(self, table: dict, name: str, what: str, f: c.Node) -> int:
        if name not in table:
            from cpn._util import did_you_mean
            from cpn.diagnostics import Diagnostic, Span

            near = did_you_mean(name, list(table))
            raise c.ContestFormatError([Diagnostic(
                "E0502", f"the formula names the {what} '{name}', which the model does not have",
                Span(self._file, f.line, f.col),
                hint=f"Did you mean '{near}'?" if near else f"Formulas name a {what} by its PNML id.")])
        return table[name]

    def check_names(self, props: list[c.ContestProperty]) -> None:
        """Every place and transition the formulas name is the model's, else one error listing them all."""
        problems = []
        for prop in props:
            self._file = prop.file
            stack = [prop.formula]
            while stack:
                f = stack.pop()
                if isinstance(f, (c.Tokens, c.PlaceBound, c.Fireable)):
                    table, what = (self.transition, "transition") if isinstance(f, c.Fireable) else (self.place, "place")
                    for name in (f.transitions if isinstance(f, c.Fireable) else f.places):
                        try:
                            self._index(table, name, what, f)
                        except c.ContestFormatError as exc:
                            problems += exc.diagnostics
                elif isinstance(f, c.IntLe):
                    stack += [f.left, f.right]
                elif isinstance(f, (c.Not, c.Quant)):
                    stack.append(f.arg)
                elif isinstance(f, (c.And, c.Or, c.Temporal)):
                    stack.extend(f.args)
        if problems:
            raise c.ContestFormatError(problems)

    def _tick(self, n: int, limit: int | None = None) -> None:
        if n > (self.max_states if limit is None else limit):
            if limit is not None and limit < self.max_states:
                raise _FlyBudget
            raise CannotCompute(f"the search passed --max-states {self.max_states:,}")
        if self.deadline is not None and n % 512 == 0 and time.monotonic() > self.deadline:
            raise CannotCompute("the time limit was reached")

    # ------------------------------------------------------------------ searches
    def reach(self, target, limit: int | None = None) -> bool:
        """Whether some reachable marking satisfies `target`: breadth first, stopping at the first. Past
        `limit` markings (below --max-states) it raises `_FlyBudget`."""
        s0 = self.cache.initial_state()
        seen = {s0}
        queue = deque([s0])
        while queue:
            s = queue.popleft()
            if target(s):
                return True
            for _be, t in self.cache.successors(s):
                if t not in seen:
                    seen.add(t)
                    self._tick(len(seen), limit)
                    queue.append(t)
        return False

    def reachable(self, f: c.Node) -> bool:
        """Whether some reachable marking satisfies the state formula f: on the fly up to `fly_states`
        markings (a witness close to the initial marking is found without the whole state space), then,
        where the state space is to be built anyway, over all of it at once (the explorer generates it
        natively, far faster per marking than the search through `successors`), else on the fly up to
        --max-states. Each way is exact: only the time differs."""
        if self._graph is not None:
            return any(self.vector(f))
        p = self.predicate(f)
        fly = self.fly_states if self.graph_max_states > self.fly_states else None
        if fly is None or fly >= self.max_states:
            return self.reach(p)
        try:
            return self.reach(p, fly)
        except _FlyBudget:
            pass
        try:
            self.graph()
        except CannotCompute:
            return self.reach(p)  # the whole state space is out of reach: on the fly as far as allowed
        return any(self.vector(f))

    def graph(self):
        """The whole state space as (states, offsets, dst), built once by the explorer (natively where it
        can); `_arc_transitions` holds the transition instance of every arc."""
        if self._graph is None:
            if self.ctl_stutter:
                return self._python_graph()
            from cpn.statespace import ExploreOptions, Explorer
            from cpn.statespace.options import default_max_memory_mb

            seconds = None if self.deadline is None else self.deadline - time.monotonic()
            if seconds is not None and seconds <= 0:
                raise CannotCompute("the time limit was reached")
            x = Explorer(self.engine, ExploreOptions(max_states=self.graph_max_states, max_seconds=seconds,
                                                     max_memory_mb=default_max_memory_mb())).run()
            if not x.complete:
                raise CannotCompute(f"the state space is partial: {x.stop_reason.describe(x.options)}")
            g = x.graph
            self._arc_transitions = _arc_transitions(g.bes, self.transition_of)
            self.explored = x.n_states
            self._graph = (g.states, g.offsets, g.dst)
        return self._graph

    def _python_graph(self):
        """The state space built through `successors`, a dead marking with a self-loop (the stuttering
        reading of CTL, which the contest does not use: kept to compare the two readings)."""
        s0 = self.cache.initial_state()
        ids = {s0: 0}
        states = [s0]
        offsets, dst, trans = array("q", [0]), array("i"), array("i")
        k = 0
        while k < len(states):
            s = states[k]
            succ = self.cache.successors(s)
            if not succ:
                dst.append(k)
                trans.append(-1)
            for be, t in succ:
                trans.append(self.transition_of(be))
                j = ids.get(t)
                if j is None:
                    j = ids[t] = len(states)
                    states.append(t)
                    self._tick(len(states))
                dst.append(j)
            offsets.append(len(dst))
            k += 1
        self._graph = (states, offsets, dst)
        self._arc_transitions = trans
        return self._graph

    # ------------------------------------------------------------------ atoms over the whole state space
    def vector(self, f: c.Node):
        """The value of a state formula (a bytearray) or integer expression (a list) in every state of
        the state space, in `graph()` order, computed a column at a time."""
        from cpn.statespace import graphnative

        states, offsets, _dst = self.graph()
        n = len(states)
        if isinstance(f, c.Bool):
            return bytearray([f.value]) * n
        if isinstance(f, c.IntConst):
            return [f.value] * n
        if isinstance(f, c.Not):
            return self.vector(f.arg).translate(_NOT)
        if isinstance(f, (c.And, c.Or)):
            parts = [int.from_bytes(self.vector(a), "little") for a in f.args]
            acc = parts[0]
            for x in parts[1:]:
                acc = acc & x if isinstance(f, c.And) else acc | x
            return bytearray(acc.to_bytes(n, "little"))
        if isinstance(f, c.IntLe):
            left, right = self.ints(f.left), self.ints(f.right)
            if isinstance(left, int) and isinstance(right, int):
                return bytearray([left <= right]) * n
            fast = graphnative.less_equal(left, right)
            if fast is not None:
                return fast
            left = [left] * n if isinstance(left, int) else left
            right = [right] * n if isinstance(right, int) else right
            return bytearray(map(operator.le, left, right))
        if isinstance(f, (c.Tokens, c.PlaceBound)):
            return self.ints(f)
        if isinstance(f, c.Fireable):
            rows = self.enabled_rows()
            acc = 0
            for t in {self._index(self.transition, t, "transition", f) for t in f.transitions}:
                acc |= int.from_bytes(rows[t], "little")
            return bytearray(acc.to_bytes(n, "little"))
        raise CannotCompute(f"not a state formula: {c.show(f)}")

    def ints(self, f: c.Node):
        """The value of an integer expression: an int when it is a constant, else its value in every state
        (an array "q", in `graph()` order)."""
        from cpn.statespace import graphnative

        if isinstance(f, c.IntConst):
            return f.value
        if not isinstance(f, (c.Tokens, c.PlaceBound)):
            raise CannotCompute(f"not an integer expression: {c.show(f)}")
        n = len(self.graph()[0])
        idx = [self._index(self.place, p, "place", f) for p in f.places]
        if not idx:
            return array("q", bytes(8 * n))
        if self._qcols is None:
            self._qcols = {}
        cols = []
        for i in idx:
            col = self._qcols.get(i)
            if col is None:
                col = self._qcols[i] = array("q", self.columns()[i])
            cols.append(col)
        if len(cols) == 1:
            return cols[0]
        fast = graphnative.add_columns(cols)
        return fast if fast is not None else array("q", map(sum, zip(*cols)))

    def columns(self) -> list:
        """Per place, its number of tokens in every state of the state space: with the compiled engine's
        layout (item p of a state is the intern id of place p's multiset) a column at a time from its
        tables, else a state at a time."""
        if self._columns is None:
            from cpn.checks.columns import has_place_columns, state_chunks
            from cpn.engine.protocol import capability

            states = self.graph()[0]
            counts = getattr(capability(self.engine, "store"), "counts", None)
            if counts is not None and len(counts) == len(self.engine.places) and has_place_columns(self.engine,
                                                                                                    states):
                cols: list = [[] for _ in counts]
                for chunk in state_chunks(states):
                    for p, col in enumerate(cols):
                        col.extend(map(counts[p].__getitem__, map(itemgetter(p), chunk)))
                self._columns = cols
            else:
                self._columns = list(zip(*map(self.counts, states))) if len(states) else []
        return self._columns

    def enabled_rows(self) -> list:
        """Per transition instance, the states (a bytearray) where it has an enabled binding."""
        if self._rows is None:
            from cpn.statespace import graphnative

            states, offsets, _dst = self.graph()
            n = len(states)
            self._rows = graphnative.label_rows(n, offsets, self._arc_transitions, len(self.engine.transitions))
            if self._rows is not None:
                return self._rows
            rows = [bytearray(n) for _ in self.engine.transitions]
            trans = self._arc_transitions
            for u in range(n):
                for a in range(offsets[u], offsets[u + 1]):
                    rows[trans[a]][u] = 1
            self._rows = rows
        return self._rows

    def answer(self, prop: c.ContestProperty) -> Answer:
        t0 = time.perf_counter()
        before = self.cache.expanded
        built = self._graph
        self._file = prop.file
        try:
            value, technique = self._answer(prop.formula)
            ans = Answer(prop.id, value, technique=technique)
        except CannotCompute as exc:
            ans = Answer(prop.id, None, reason=str(exc))
        ans.states = self.cache.expanded - before + (self.explored if built is None and self._graph is not None else 0)
        ans.seconds = time.perf_counter() - t0
        return ans

    def _answer(self, f: c.Node) -> tuple[object, str]:
        if isinstance(f, c.PlaceBound):
            return max(self.ints(f)), ""
        if isinstance(f, c.Quant) and isinstance(f.arg, c.Temporal) and f.arg.op in ("F", "G") \
                and c.is_state_formula(f.arg.args[0]):
            if f.path == "E" and f.arg.op == "F":
                return self.reachable(f.arg.args[0]), "TOPOLOGICAL"
            if f.path == "A" and f.arg.op == "G":
                return not self.reachable(c.Not(f.arg.args[0])), "TOPOLOGICAL"
        if c.is_ltl(f):
            return self._ltl(f.arg), "LTL_NFA"
        return self._ctl(f), ""

    def _ltl(self, phi: c.Node) -> bool:
        """On the fly up to `fly_states` markings (a counterexample close to the initial marking is found
        without the whole state space), then, where the state space is to be built anyway, the product
        of all of it with the automaton searched in native code, else on the fly up to --max-states."""
        from cpn.checks.ltl import check_ltl

        if self._graph is not None:
            got = self._ltl_on_graph(phi)
            if got is not None:
                return got
        props: list = []
        formula = _to_ltl(phi, props, self.predicate)
        fly = self.fly_states if self.graph_max_states > self.fly_states else None
        if fly is not None and fly < self.max_states and self._graph is None:
            res = check_ltl(self.cache, formula, props, max_states=fly, deadline=self.deadline, counterexample=False)
            if res.holds is not None:
                return res.holds
            if self.deadline is not None and time.monotonic() > self.deadline:
                raise CannotCompute(res.reason)
            try:
                self.graph()
            except CannotCompute:
                pass
            else:
                got = self._ltl_on_graph(phi)
                if got is not None:
                    return got
        res = check_ltl(self.cache, formula, props, max_states=self.max_states, deadline=self.deadline,
                        counterexample=False)
        if res.holds is None:
            raise CannotCompute(res.reason)
        return res.holds

    def _ltl_on_graph(self, phi: c.Node) -> bool | None:
        """Whether every path of the whole state space satisfies phi, by the product in native code; None
        where that is not available."""
        from cpn.checks.buchi import translate
        from cpn.statespace import graphnative

        states, offsets, dst = self.graph()
        props: list = []
        formula = _to_ltl(phi, props, self.vector)
        aut = translate(("not", formula))
        got = graphnative.ltl_accepting_cycle(len(states), offsets, dst, props, aut.moves, aut.initial, len(aut),
                                              aut.n_acc)
        return None if got is None else not got[0]

    def _ctl(self, f: c.Node) -> bool:
        from cpn.checks import ctl

        states, offsets, dst = self.graph()
        atoms: list[bytearray] = []
        formula = _to_ctl(f, atoms, self.vector)
        if self._kripke is None:
            self._kripke = ctl.Kripke(len(states), offsets, dst, labels=array("i", bytes(4 * len(dst))))
        self._kripke.deadline = self.deadline
        try:
            return bool(self._kripke.label(formula, atoms)[0])
        except ctl.OutOfTime as exc:
            raise CannotCompute(str(exc)) from None


_NOT = bytes([1, 0] + [0] * 254)


def _arc_transitions(bes, transition_of) -> array:
    """The transition instance of every arc (an array "i") from the arcs' binding elements."""
    from cpn.statespace import graphnative

    distinct = graphnative.distinct_ids(bes) if isinstance(bes, array) else None
    if distinct is not None:
        table = [0] * (distinct[-1] + 1 if distinct else 1)
        for be in distinct:
            table[be] = transition_of(be)
        got = graphnative.map_ids(bes, table, "i")
        if got is not None:
            return got
    table_d = {be: transition_of(be) for be in set(bes)}
    return array("i", map(table_d.__getitem__, bes))


def _body(name: str) -> str:
    """A place or transition instance name without its page and instance number: "Top'P 1" -> "P"."""
    name = name.split("'", 1)[-1]
    return name.rsplit(" ", 1)[0] if name.endswith(" 1") else name


def _to_ltl(f: c.Node, props: list, predicate) -> tuple:
    """The `cpn.checks.buchi` formula of a path formula; its largest state subformulas become
    propositions (their predicates appended to `props`)."""
    if c.is_state_formula(f):
        props.append(predicate(f))
        return ("ap", len(props) - 1)
    if isinstance(f, c.Not):
        return ("not", _to_ltl(f.arg, props, predicate))
    if isinstance(f, (c.And, c.Or)):
        op = "and" if isinstance(f, c.And) else "or"
        out = _to_ltl(f.args[0], props, predicate)
        for a in f.args[1:]:
            out = (op, out, _to_ltl(a, props, predicate))
        return out
    if isinstance(f, c.Temporal):
        return (f.op, *(_to_ltl(a, props, predicate) for a in f.args))
    raise CannotCompute(f"a path quantifier inside an LTL formula: {c.show(f)}")


def _to_ctl(f: c.Node, atoms: list, label):
    """The `cpn.checks.ctl` formula of a CTL state formula; its largest atomic parts become atoms."""
    from cpn.checks import ctl

    if c.is_state_formula(f):
        atoms.append(label(f))
        return ctl.Atom(len(atoms) - 1, c.show(f))
    if isinstance(f, c.Not):
        return ctl.Not(_to_ctl(f.arg, atoms, label))
    if isinstance(f, (c.And, c.Or)):
        out = _to_ctl(f.args[0], atoms, label)
        for a in f.args[1:]:
            out = (ctl.And if isinstance(f, c.And) else ctl.Or)(out, _to_ctl(a, atoms, label))
        return out
    if isinstance(f, c.Quant) and isinstance(f.arg, c.Temporal):
        args = tuple(_to_ctl(a, atoms, label) for a in f.arg.args)
        return ctl.Temporal(f.path + f.arg.op, args)
    raise CannotCompute(f"not a CTL formula: {c.show(f)}")


def answer_file(model: ContestModel, path: str) -> list[Answer]:
    return [model.answer(p) for p in c.read_file(path)]


def run(args) -> int:
    import os

    for path in (args.model, args.properties):
        if not os.path.exists(path):
            raise UsageError(f"{path}: no such file")
    props = c.read_file(args.properties)
    deadline = time.monotonic() + args.max_seconds if args.max_seconds else None
    model = ContestModel.load(args.model, max_states=args.max_states, deadline=deadline)
    model.check_names(props)
    status = ExitStatus.OK
    for prop in props:
        ans = model.answer(prop)
        print(ans.line(), flush=True)
        if ans.value is None:
            status = ExitStatus.UNKNOWN
            print(f"{prop.id}: cannot compute: {ans.reason}", file=sys.stderr)
        if args.stats:
            print(f"{prop.id}: {ans.states:,} states generated, {ans.seconds:.3f} s", file=sys.stderr)
    return status
