"""Property texts: CPN ML expressions over markings, type-checked against the net and compiled once.

A property text is parsed by the model's parser and typed by the model's type checker in a scope that adds,
to the model's declarations, the place instances by the names the report prints (`Page'place n`, and
ASK-CTL's `Mark.Page'place n`), `sum`/`forall`/`exists` over every instance of a module's place, and
`enabled "transition or binding element"`. It is then compiled to a Python function of a state by the
engine's expression compiler, as inscriptions are. Errors point into the scenario file (docs/specs.md).
Imports `cpn.lang`, `cpn.engine`, `cpn.values` and layer 0.
"""

from __future__ import annotations

import dataclasses
import io
import operator
import pickle
import re
from collections import OrderedDict
from collections.abc import Callable
from itertools import repeat

from cpn._util import did_you_mean
from cpn.diagnostics import Diagnostic, Span
from cpn.engine.protocol import capability, has
from cpn.errors import ModelError
from cpn.expr import nodes as E
from cpn.expr.evaluate import Evaluator
from cpn.lang import ast as A
from cpn.lang import types as T
from cpn.lang.builtins import MLError, parse_type
from cpn.lang.checked import Env
from cpn.lang.parser import parse
from cpn.lang.symbols import Symbol
from cpn.lang.typecheck import Checker
from cpn.net.translate import Translator
from cpn.values.multiset import Multiset, MultisetError

PREFIX = "val it = "

#: the parses of property texts, pickled (the type checker annotates the tree it is given, so each use
#: gets its own copy): a scenario's texts are the same in each of its runs and mutants, and many scenario
#: files share their texts. The file name the spans carry is pickled by reference (`_Pickler`), so one
#: parse serves every file that has the text.
_PARSES: OrderedDict = OrderedDict()
PARSES_KEPT: int = 4096


class _Pickler(pickle.Pickler):
    def __init__(self, fh, filename: str):
        super().__init__(fh, pickle.HIGHEST_PROTOCOL)
        self.filename = filename

    def persistent_id(self, obj):
        return "file" if obj is self.filename else None


class _Unpickler(pickle.Unpickler):
    def __init__(self, data: bytes, filename: str):
        super().__init__(io.BytesIO(data))
        self.filename = filename

    def persistent_load(self, pid):
        return self.filename


def _parse_text(text: str, filename: str) -> A.Model:
    kept = _PARSES.get(text)
    if kept is not None:
        _PARSES.move_to_end(text)
        return _Unpickler(kept, filename).load()
    m = parse(text, filename)  # a syntax error is raised, not kept
    out = io.BytesIO()
    try:
        _Pickler(out, filename).dump(m)
    except RecursionError:  # nested too deeply to pickle: parsed again the next time
        return m
    _PARSES[text] = out.getvalue()
    if len(_PARSES) > PARSES_KEPT:
        _PARSES.popitem(last=False)
    return m
    if len(_PARSES) > PARSES_KEPT:
        _PARSES.popitem(last=False)
    return m
CTL_UNARY = {"AG": "AG", "AF": "AF", "EF": "EF", "EG": "EG", "AX": "AX", "EX": "EX",
             "INV": "AG", "POS": "EF", "EV": "AF", "ALONG": "EG"}
CTL_BINARY = {"AU", "EU"}
CTL_ARC = {"EXB", "AXB"}  # ASK-CTL's modal operators over the binding element that occurs
# LTL (kind = "ltl"); a model's own declaration of one of these names wins (the long names remain)
LTL_UNARY = {"G": "G", "F": "F", "X": "X", "ALWAYS": "G", "EVENTUALLY": "F", "NEXT": "X"}
LTL_BINARY = {"U": "U", "R": "R", "UNTIL": "U", "RELEASE": "R"}
_INSTANCE = re.compile(r"^(.*) (\d+)$")


class PredicateError(Exception):
    """A property text raised an ML exception in some marking."""

    def __init__(self, message: str, state_id: int | None, span: Span | None = None):
        super().__init__(message)
        self.state_id = state_id
        self.span = span  # the text's value in the scenario file, where the reports place the error


class MarkingContext:
    """The marking a compiled predicate reads: the state, its id, and (when known) the finished graph."""

    def __init__(self, engine, transition_of: Callable[[int], int]):
        self.engine = engine
        self.transition_of = transition_of
        self.state = None
        self.sid: int | None = None
        self.graph = None
        n = len(engine.places)
        self._columns = has(engine, "place_view")
        self._cache: list[dict] = [{} for _ in range(n)]
        self._enabled_state = None
        self._enabled: list[int] = []

    def mk(self, s, p: int) -> Multiset:
        if self._columns:
            key = s[p]
            m = self._cache[p].get(key)
            if m is None:
                m = Multiset(self.engine.place_view(s, p))
                self._cache[p][key] = m
            return m
        ms = self.engine.marking(s)[p]
        if getattr(self.engine.places[p], "timed", False) and getattr(self.engine, "is_timed", False):
            view: dict = {}
            for (v, _ts), k in ms.items():
                view[v] = view.get(v, 0) + k
            ms = view
        return Multiset(ms)

    def enabled_bes(self) -> list[int]:
        g, sid = self.graph, self.sid
        if g is not None and sid is not None and g.is_expanded(sid):
            return list(g.bes[g.offsets[sid]:g.offsets[sid + 1]])
        if self._enabled_state is not self.state:
            self._enabled_state = self.state
            self._enabled = [be for be, _ in self.engine.successors(self.state)]
        return self._enabled


class _Accessor:
    """The value of a place name in a property: instance number -> marking of the current state."""

    def __init__(self, ctx: MarkingContext, name: str, instances: dict[int, int]):
        self.ctx = ctx
        self.name = name
        self.instances = instances
        self.places = sorted(set(instances.values()))

    def __call__(self, i):
        p = self.instances.get(i)
        if p is None:
            raise MLError(f"'{self.name}' has no instance {i} (it has {_ranges(sorted(self.instances))})")
        return self.ctx.mk(self.ctx.state, p)


def _ranges(nums: list[int]) -> str:
    if not nums:
        return "none"
    if nums == list(range(nums[0], nums[-1] + 1)) and len(nums) > 2:
        return f"{nums[0]}..{nums[-1]}"
    return ", ".join(map(str, nums))


def _accessor_arg(a):
    if not isinstance(a, _Accessor):
        raise MLError("sum, forall and exists take a place name (Page'place), not another function")
    return a


def _sum(a):
    acc = Multiset()
    for p in _accessor_arg(a).places:
        acc = acc + a.ctx.mk(a.ctx.state, p)
    return acc


def _forall(a):
    _accessor_arg(a)
    return lambda f: all(f(a.ctx.mk(a.ctx.state, p)) for p in a.places)


def _exists(a):
    _accessor_arg(a)
    return lambda f: any(f(a.ctx.mk(a.ctx.state, p)) for p in a.places)


_MISS = object()  # no value memoised for a key yet


@dataclasses.dataclass
class Compiled:
    """A compiled property text: `fn(state_id, state)` returns its value; `uses_enabled` says it reads
    the enabled binding elements (then it is evaluated on the finished graph, not during generation)."""

    text: str
    expr: A.Expr
    fn: Callable
    uses_enabled: bool
    span: Span | None
    reads: tuple = ()  # the place instances whose markings the text reads (indices)
    # `first(sid, states, wanted)`: the position in `states` (whose first has id `sid`) of the first state
    # where the value is `wanted` (a bool), or None; the states before it are evaluated in order, so an
    # error is raised at the first state that fails, as calling `fn` on each would
    first: Callable | None = None

    def first_where(self, sid: int, states, wanted: bool) -> int | None:
        """`first`, or `fn` on each state in turn where there is none."""
        if self.first is not None:
            return self.first(sid, states, wanted)
        fn = self.fn
        for i, s in enumerate(states):
            if bool(fn(sid + i, s)) is wanted:
                return i
        return None


class PropertyLanguage:
    """The scope and compiler of property texts for one net and one engine."""

    def __init__(self, net, engine, transition_of: Callable[[int], int]):
        checked = net.checked
        self.net = net
        self.checked = checked
        self.engine = engine
        self.transition_index = transition_of
        self._clock_readers: dict | None = None
        self.ctx = MarkingContext(engine, transition_of)
        # texts are type-checked by the language and compiled and evaluated in the net's expression form
        self.ev = Evaluator(net.colsets, net.globals)
        self._tr = Translator()
        self._checker = _checker_for(checked)
        self.accessors: dict[str, _Accessor] = {}
        names: dict[str, Symbol] = {}
        self.symbols: dict[int, _Accessor] = {}
        groups: dict[str, dict[int, int]] = {}
        self.place_cstype: dict[str, T.Type] = {}
        for p in engine.places:
            for full in [p.name, *getattr(p, "aliases", [])]:
                m = _INSTANCE.match(full)
                if not m:
                    continue
                groups.setdefault(m.group(1), {})[int(m.group(2))] = p.index
                self.place_cstype[m.group(1)] = checked.cstypes.get(p.colour_set.name, T.TVar())
        for base, inst in groups.items():
            acc = _Accessor(self.ctx, base, inst)
            self.accessors[base] = acc
            for spelling in (base, f"Mark.{base}"):
                sym = Symbol(spelling, "val", T.TFun(T.INT, T.ms(self.place_cstype[base])), what="the place")
                names[spelling] = sym
                self.symbols[sym.uid] = acc
                self.ev.globals[sym.uid] = checked.evaluator.globals[sym.uid] = acc
        self.transition_names = _transition_names(engine)
        self._be_texts: dict[str, int] | None = None
        self._enabled_cache: dict[str, Callable[[], bool]] = {}
        self.special: dict[str, Symbol] = {}
        for name, ty, value in (("sum", "(int -> 'a ms) -> 'a ms", _sum),
                                ("forall", "(int -> 'a ms) -> ('a ms -> bool) -> bool", _forall),
                                ("exists", "(int -> 'a ms) -> ('a ms -> bool) -> bool", _exists),
                                ("enabled", "string -> bool", self._enabled)):
            if name in checked.globals:
                continue  # the model's own declaration wins
            sym = Symbol(name, "val", parse_type(ty), what="the property function")  # polymorphic where it says 'a
            names[name] = sym
            self.special[name] = sym
            self.ev.globals[sym.uid] = checked.evaluator.globals[sym.uid] = value
        self.env = self._checker.genv.child(names)
        self.ctl_symbols: dict[str, Symbol] = {}
        for name in CTL_UNARY:
            self.ctl_symbols[name] = Symbol(name, "builtin", T.TFun(T.BOOL, T.BOOL))
        for name in CTL_BINARY:
            self.ctl_symbols[name] = Symbol(name, "builtin", T.TFun(T.TTuple([T.BOOL, T.BOOL]), T.BOOL))
        for name in CTL_ARC:
            self.ctl_symbols[name] = Symbol(name, "builtin", T.TFun(T.TTuple([T.STRING, T.BOOL]), T.BOOL))
        self.ctl_env = self.env.child(self.ctl_symbols)
        self.ltl_symbols: dict[str, Symbol] = {}
        for name in LTL_UNARY.keys() | LTL_BINARY.keys() | CTL_ARC:
            if name not in checked.globals:
                arg = T.BOOL if name in LTL_UNARY else T.TTuple([T.STRING if name in CTL_ARC else T.BOOL, T.BOOL])
                self.ltl_symbols[name] = Symbol(name, "builtin", T.TFun(arg, T.BOOL))
        self.ltl_env = self.env.child(self.ltl_symbols)

    # ------------------------------------------------------------------ binding-element atoms
    def resolve_transitions(self, name: str) -> list[int] | None:
        """Transition instance indices named by `Page'trans n` or (every instance) `Page'trans`."""
        return self.transition_names.get(name)

    def _enabled(self, text: str) -> bool:
        test = self._enabled_cache.get(text)
        if test is None:
            test = self._enabled_test(text)
            self._enabled_cache[text] = test
        return test()

    def _enabled_test(self, text: str) -> Callable[[], bool]:
        ctx = self.ctx
        ts = self.resolve_transitions(text)
        if ts is not None:
            wanted = set(ts)
            t_of = ctx.transition_of
            known: dict[int, int] = {}  # binding element -> 1 if it is one of a wanted transition, else 0

            def is_wanted(be: int) -> int:
                got = known.get(be)
                if got is None:
                    got = known[be] = 1 if t_of(be) in wanted else 0
                return got

            # per arc of the graph read last (arcs are only appended): 1 where its binding element is one of
            # a wanted transition, so that a state of the graph is tested by a slice, not a call per arc
            marks: list = [None, bytearray()]

            def test() -> bool:
                g, sid = ctx.graph, ctx.sid
                if g is None or sid is None or not g.is_expanded(sid):
                    return any(t_of(be) in wanted for be in ctx.enabled_bes())
                m, n = marks[1], len(g.bes)
                if marks[0] is not g or len(m) > n:
                    marks[0], m = g, bytearray()
                    marks[1] = m
                if len(m) < n:
                    m.extend(map(is_wanted, g.bes[len(m):n]))
                offsets = g.offsets
                return any(m[offsets[sid]:offsets[sid + 1]])

            return test
        match = self.binding_pattern(text)
        return lambda: any(match(be) for be in ctx.enabled_bes())

    def arc_pattern(self, op: str, pat: A.Expr, text: str, origin, span: Span) -> Callable[[int], bool]:
        """The binding-element test of `EXB`'s or `AXB`'s first argument `pat` in the property text `text`
        (a CTL or LTL formula); an error at its place unless it is a string literal naming a transition
        or binding element of the net."""
        if not (isinstance(pat, A.Const) and isinstance(pat.value, str)) or (
                self.resolve_transitions(pat.value) is None and not self._known_be(pat.value)):
            raise _remap(ModelError([Diagnostic(
                "E0703", f"'{op}' takes a transition or binding element of the net as a string literal",
                pat.span, hint=f"For example: {op} (\"Slave'Reply\", true).")]), text, origin, span)
        return self.binding_pattern(pat.value)

    def binding_pattern(self, text: str) -> Callable[[int], bool]:
        """A test of binding elements for `Page'trans n: {var=value, ...}`, where the braces may list only
        some of the variables (`{ok=true}`: every binding with ok=true); without an instance number, any
        instance matches."""
        tname, _, rest = text.partition(":")
        ts = set(self.resolve_transitions(tname.strip()) or ())
        want = _binding_values(rest)
        fmt = self.engine.format_binding_element
        t_of = self.transition_index
        cache: dict[int, bool] = {}

        def match(be: int) -> bool:
            got = cache.get(be)
            if got is None:
                got = t_of(be) in ts and _binding_values(fmt(be).partition(":")[2]).items() >= want.items()
                cache[be] = got
            return got

        return match

    # ------------------------------------------------------------------ checking
    def check(self, text: str, origin, fallback: Span, want: T.Type, what: str, ctl: bool = False,
              ltl: bool = False) -> A.Expr:
        """Parse and type `text`; raise ModelError with spans in the scenario file."""
        try:
            m = _parse_text(f"{PREFIX}{text};", fallback.file)
        except ModelError as exc:
            raise _remap(exc, text, origin, fallback) from None
        if len(m.decls) != 1 or not isinstance(m.decls[0], A.ValDecl):
            raise _remap(ModelError([Diagnostic("E0101", f"{what} must be one expression", None)]), text, origin,
                         fallback)
        expr = m.decls[0].expr
        ck = self._checker
        ck.diags = []
        expr = self._quoted_places(expr, ck)
        env = self.ctl_env if ctl else self.ltl_env if ltl else self.env
        t = ck.infer_top(expr, env) if not ck.diags else None
        if t is not None:
            ck.unify(t, want, expr.span, what)
        self._unknown_places(ck.diags)
        if not ck.diags:
            self._validate(expr, ck)
        if not ck.diags:
            self._refuse_clock_under_condensation(expr, what)
        if ck.diags:
            raise _remap(ModelError(list(ck.diags)), text, origin, fallback)
        return expr

    def _refuse_clock_under_condensation(self, expr: A.Expr, what: str) -> None:
        """A text that reads the clock cannot be decided on a condensed state space, whose clock is 0 in
        every state: refused (E0601) as a model that reads the clock is (cpn.engine.clock)."""
        if not capability(self.engine, "time_condensation", False):
            return
        from cpn.engine import clock

        if self._clock_readers is None:
            self._clock_readers = clock.global_readers(self.net.globals.decls)
        translated = self._tr.expr(expr)
        span = clock.first_read(translated, self._clock_readers)
        if span is None:
            return
        via = clock.called_reader(translated, self._clock_readers)
        self._checker.diags.append(Diagnostic(
            "E0601",
            f"time condensation cannot be used: {what} reads the model clock, and time condensation sets the "
            "clock to 0 in every state, so the text would not read the model's clock",
            span, notes=[f"'{via[0]}' reads it at {via[1]}"] if via else [],
            hint="Explore without time condensation (time_condensation = true in a scenario's [explore], "
                 "--time-condensation on the command line; a timed state space that grows only because time "
                 "grows is then stopped by the time-growth watch, or bound it with until_time), or write the "
                 "text without reading the clock."))

    def _quoted_places(self, expr: A.Expr, ck) -> A.Expr:
        """`Mark "Page'a place" 1`: a place whose name is not an identifier (declared with a string)
        is named by a string after `Mark`; the pair becomes the place's accessor."""
        def fix(node):
            if (isinstance(node, A.App) and isinstance(node.fn, A.Name) and node.fn.name == "Mark"
                    and isinstance(node.arg, A.Const) and isinstance(node.arg.value, str)):
                name = node.arg.value
                if name not in self.accessors:
                    cand = did_you_mean(name, list(self.accessors))
                    ck.error("E0703", f"no place '{name}' in the net", node.arg.span,
                             hint=f"Did you mean '{cand}'?" if cand else "Write the place as Page'place, without "
                             "the instance number, which follows the string: Mark \"Page'a place\" 1.")
                    return node
                return A.Name(node.span, f"Mark.{name}")
            for f in dataclasses.fields(node):
                if f.name in ("span", "ty", "ref"):
                    continue
                v = getattr(node, f.name)
                if isinstance(v, A.Expr):
                    setattr(node, f.name, fix(v))
                elif isinstance(v, list):
                    v[:] = [fix(x) if isinstance(x, A.Expr) else _fix_rule(x, fix) for x in v]
            return node

        return fix(expr)

    def _unknown_places(self, diags: list[Diagnostic]) -> None:
        """An unknown name written as a place (`Page'place`, `Mark.Page'place`) is reported as a place the
        net does not have, with the nearest place name, instead of as an unknown value."""
        for k, d in enumerate(diags):
            name = d.params.get("name") if d.code == "E0201" else None
            if not isinstance(name, str) or ("'" not in name and not name.startswith("Mark.")):
                continue
            prefix = "Mark." if name.startswith("Mark.") else ""
            base = name[len(prefix):]
            cand = did_you_mean(base, list(self.accessors))
            diags[k] = Diagnostic(
                "E0703", f"no place '{base}' in the net", d.span, notes=d.notes, params=d.params,
                hint=f"Did you mean the place '{prefix}{cand}'?" if cand else
                "Name a place as Page'place (every instance) or Page'place n (instance n); the report lists "
                "the places of the net.")

    def _validate(self, expr: A.Expr, ck) -> None:
        for node in walk(expr):
            if not isinstance(node, A.App) or not isinstance(node.fn, A.Name) or node.fn.ref is None:
                continue
            uid = node.fn.ref.uid
            acc = self.symbols.get(uid)
            if acc is not None and isinstance(node.arg, A.Const) and node.arg.value not in acc.instances:
                ck.error("E0703", f"'{acc.name}' has no instance {node.arg.value}", node.arg.span,
                         hint=f"Its instances are {_ranges(sorted(acc.instances))}.")
            if node.fn.ref in (self.special.get("sum"), self.special.get("forall"), self.special.get("exists")):
                if not (isinstance(node.arg, A.Name) and node.arg.ref is not None and node.arg.ref.uid in self.symbols):
                    ck.error("E0703", f"'{node.fn.name}' takes a place name (Page'place) as its first argument",
                             node.arg.span, hint=f"For example: {node.fn.name} Slave'Idle.")
            if node.fn.ref is self.special.get("enabled"):
                if not (isinstance(node.arg, A.Const) and isinstance(node.arg.value, str)):
                    ck.error("E0703", "'enabled' takes a transition or binding element as a string literal",
                             node.arg.span, hint="For example: enabled \"Master'Send 1\".")
                elif self.resolve_transitions(node.arg.value) is None and not self._known_be(node.arg.value):
                    tname = node.arg.value.split(":")[0].strip()
                    cand = did_you_mean(tname, list(self.transition_names))
                    ck.error("E0703", f"no transition instance or binding element '{node.arg.value}' in the net",
                             node.arg.span, hint=f"Did you mean '{cand}'?" if cand else
                             "Name a transition instance as the report prints it: \"Page'trans 1\".")

    def _known_be(self, text: str) -> bool:
        tname, colon, rest = text.partition(":")
        if not colon or tname.strip() not in self.transition_names:
            return False
        names = {v for t in self.transition_names[tname.strip()] for v in self.engine.transitions[t].variables}
        return set(_binding_values(rest)) <= names

    # ------------------------------------------------------------------ compiling
    def compile(self, text: str, origin, fallback: Span, want: T.Type, what: str) -> Compiled:
        expr = self.check(text, origin, fallback, want, what)
        return self.compile_checked(text, expr, fallback)

    def compile_checked(self, text: str, expr: A.Expr, span: Span | None) -> Compiled:
        uses_enabled = any(isinstance(n, A.Name) and n.ref is self.special.get("enabled") and n.ref is not None
                           for n in walk(expr))
        ev, engine = self.ev, self.engine
        uses_time = self._reads_clock(expr)
        env = {"CTX": self.ctx, "MK": self.ctx.mk, "TIMEFN": lambda _u: engine.clock(self.ctx.state),
               "SETTIME": lambda s: setattr(ev, "time", engine.clock(s))}
        prologue = "    CTX.sid = I\n    CTX.state = S\n" + ("    SETTIME(S)\n" if uses_time else "")
        translated = self._tr.expr(expr)
        compiler = capability(engine, "predicate_compiler")
        if compiler is not None:
            places = {uid: acc.instances for uid, acc in self.symbols.items()}
            raw = compiler(ev, places).function(translated, env, prologue, f"<property {text[:40]}>")
        else:  # an engine without the compiler: the tree-walking evaluator, which reads places by accessors
            def raw(sid, state, node=translated, ctx=self.ctx):
                ctx.sid, ctx.state = sid, state
                if uses_time:
                    ev.time = engine.clock(state)
                return ev.eval(node, {})
        errors = (MLError, MultisetError, ZeroDivisionError, IndexError, RecursionError)
        reads = sorted({p for n in walk(expr) if isinstance(n, A.Name) and n.ref is not None
                        and n.ref.uid in self.symbols for p in self.symbols[n.ref.uid].places})
        places_read = tuple(reads)
        if uses_enabled or not has(self.engine, "place_view"):
            def fn(sid, state, raw=raw):
                try:
                    return raw(sid, state)
                except errors as exc:
                    raise PredicateError(f"evaluating '{text}' failed: {exc}", sid, span) from None
        else:
            # The value depends only on the markings of the places the text reads, which states share:
            # memoised by their intern ids, as the engine memoises a transition's bindings.
            if uses_time and getattr(self.engine, "is_timed", False):
                reads.append(len(self.engine.places))  # the clock, the last item of a timed state
            key_of = operator.itemgetter(*reads) if reads else (lambda s: ())
            memo: dict = {}
            get = memo.get

            def fn(sid, state, raw=raw):
                key = key_of(state)
                v = get(key, fn)
                if v is fn:
                    try:
                        v = raw(sid, state)
                    except errors as exc:
                        raise PredicateError(f"evaluating '{text}' failed: {exc}", sid, span) from None
                    memo[key] = v
                return v

            def first(sid, states, wanted, raw=raw):
                # the keys and the values known are looked up in C (map); Python evaluates only the states
                # whose key is new, in order, up to the first known `wanted` value
                keys = list(map(key_of, states))
                vals = list(map(get, keys, repeat(_MISS, len(keys))))
                n = len(vals)
                try:
                    w = vals.index(wanted)  # (the values are bools: the text's type is bool)
                except ValueError:
                    w = n
                i = 0
                while True:
                    try:
                        m = vals.index(_MISS, i, w)
                    except ValueError:
                        return w if w < n else None
                    key = keys[m]
                    v = get(key, _MISS)
                    if v is _MISS:
                        try:
                            v = raw(sid + m, states[m])
                        except errors as exc:
                            raise PredicateError(f"evaluating '{text}' failed: {exc}", sid + m, span) from None
                        memo[key] = v
                    if bool(v) is wanted:
                        return m
                    i = m + 1

            return Compiled(text, expr, fn, uses_enabled, span, places_read, first)
        return Compiled(text, expr, fn, uses_enabled, span, places_read)

    def _reads_clock(self, expr: A.Expr) -> bool:
        """Whether the text reads the clock, directly or through the model's functions and values."""
        from cpn.engine import clock

        if self._clock_readers is None:
            self._clock_readers = clock.global_readers(self.net.globals.decls)
        return clock.first_read(self._tr.expr(expr), self._clock_readers) is not None

    def constant(self, text: str, origin, fallback: Span, want: T.Type, what: str):
        """The value of a text that reads no marking (an expected bound: `N`, `ADDR.all()`)."""
        expr = self.check(text, origin, fallback, want, what)
        if any(isinstance(n, A.Name) and n.ref is not None and (n.ref.uid in self.symbols
               or n.ref in self.special.values()) for n in walk(expr)):
            raise _remap(ModelError([Diagnostic("E0702", f"{what} must not read the marking", expr.span)]), text,
                         origin, fallback)
        try:
            return self.ev.eval(self._tr.expr(expr), {})
        except (MLError, MultisetError) as exc:
            raise _remap(ModelError([Diagnostic("E0401", f"evaluating {what} failed: {exc}", expr.span)]), text,
                         origin, fallback) from None


def _fix_rule(x, fix):
    """Rewrite the expressions inside a (pattern, expression) rule or (label, expression) field."""
    if isinstance(x, tuple):
        return tuple(fix(y) if isinstance(y, A.Expr) else y for y in x)
    return x


def _binding_values(text: str) -> dict[str, str]:
    """{var: value text} of ``{a=1, f=(1,3)}`` (blanks removed; commas inside brackets kept)."""
    body = re.sub(r"\s+", "", text).strip()
    if body.startswith("{") and body.endswith("}"):
        body = body[1:-1]
    out: dict[str, str] = {}
    depth, start = 0, 0
    for i, c in enumerate(body + ","):
        if c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        elif c == "," and depth == 0:
            item = body[start:i]
            start = i + 1
            if item:
                k, _, v = item.partition("=")
                out[k] = v
    return out


def _transition_names(engine) -> dict[str, list[int]]:
    out: dict[str, list[int]] = {}
    for t in engine.transitions:
        out.setdefault(t.name, []).append(t.index)
        m = _INSTANCE.match(t.name)
        if m:
            out.setdefault(m.group(1), []).append(t.index)
    return out


def walk(e):
    """Every expression node under `e`, `e` included, also inside the declarations of a `let` and the
    clauses and rules of functions and cases (a place read there is still a read)."""
    stack = [e]
    while stack:
        n = stack.pop()
        cls = type(n)
        names = _WALKED.get(cls, _MISS)
        if names is _MISS:  # per class: the fields walked into, or None (not a node)
            names = _WALKED[cls] = tuple(f.name for f in dataclasses.fields(cls) if f.name not in ("span", "ty", "ref")) \
                if dataclasses.is_dataclass(cls) else None
        if names is not None:
            if isinstance(n, (A.Expr, E.Expr)):  # the checked text, or its form in the net's expressions
                yield n
            stack.extend([getattr(n, name) for name in names])
        elif isinstance(n, (list, tuple)):
            stack.extend(n)


_WALKED: dict[type, tuple[str, ...] | None] = {}


def _checker_for(checked) -> Checker:
    """A type checker in the scope of a checked model: a fresh checker (its own bookkeeping, whatever the
    checker keeps) whose colour sets, global names and evaluator are those of the model."""
    ck = Checker(checked.model, {})
    ck.colsets = checked.colsets
    ck.cstypes = checked.cstypes
    ck.globals = checked.globals
    ck.ev = checked.evaluator
    ck.net_name = checked.net_name
    ck.genv = Env(checked.globals)
    return ck


def _remap(exc: ModelError, text: str, origin, fallback: Span) -> ModelError:
    """The same diagnostics, with spans moved from the wrapped text into the scenario file."""
    wrapped = f"{PREFIX}{text};"
    starts = [0]
    for line in wrapped.splitlines(keepends=True):
        starts.append(starts[-1] + len(line))
    out = []
    for d in exc.diagnostics:
        s = d.span
        if origin is None or s is None or s.line < 1 or s.line > len(starts) - 1:
            span = fallback
        else:
            a = starts[s.line - 1] + s.col - 1 - len(PREFIX)
            if s.end_line and s.end_col and s.end_line <= len(starts) - 1:
                b = starts[s.end_line - 1] + s.end_col - 1 - len(PREFIX)
            else:
                b = a
            a = max(0, min(a, len(text)))
            b = max(a, min(b, max(len(text) - 1, 0)))
            span = origin.span(a, b)
        out.append(dataclasses.replace(d, span=span))
    src = origin.source if origin is not None else None
    return ModelError(out, {fallback.file: src} if src is not None else {})
