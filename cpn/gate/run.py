"""Running a scenario: load the model with the run's values, compile the properties, explore once with
the on-the-fly checks attached, then decide every property on the graph.

Imports `cpn.model`, `cpn.statespace`, `cpn.checks.*` and layer 0.
"""

from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass, field

from cpn.checks.columns import TransitionIndex
from cpn.checks.verdict import Status, Verdict, evidence_to
from cpn.diagnostics import Diagnostic
from cpn.errors import ConfigurationError, ModelError
from cpn.gate.scenario import Run, Scenario
from cpn.properties.build import build_checks
from cpn.properties.kinds import Check, DeadlockFree, GraphView, Reachable
from cpn.properties.ltl import Ltl
from cpn.properties.predicates import PredicateError, PropertyLanguage
from cpn.properties.reduction import stubborn_plan
from cpn.properties.spec import PropertySpec
from cpn.properties.structure import structural
from cpn.properties.symmetry import decide_over_orbits, symmetry_plan
from cpn.properties.vacuity import vacuity
from cpn.statespace import ExploreOptions, Explorer


@dataclass
class PropertyResult:
    spec: PropertySpec
    verdict: Verdict
    seconds: float
    reads: tuple = ()  # the place instances the property's texts read (indices), for the reports
    warnings: list = field(default_factory=list)  # why it holds vacuously (cpn.properties.vacuity)

    def __repr__(self) -> str:  # short: the property, its verdict, how many warnings (not their text)
        return (f"PropertyResult(spec={self.spec!r}, verdict={self.verdict!r}, seconds={self.seconds:.3g}, "
                f"warnings={len(self.warnings)})")

    @property
    def as_expected(self) -> bool:
        return self.verdict.status.value == self.spec.expect

    @property
    def gate_status(self) -> Status:
        """HOLDS when the verdict is the expected one; VIOLATED when the expectation is missed either way."""
        v = self.verdict.status
        if v in (Status.ERROR, Status.UNKNOWN):
            return v
        return Status.HOLDS if self.as_expected else Status.VIOLATED


@dataclass
class RunResult:
    """The outcome of one run of a scenario: the exploration and one verdict per property."""

    scenario: Scenario
    run: Run
    exploration: object
    engine: object
    results: list[PropertyResult]
    explore_seconds: float
    check_seconds: float
    options: dict = field(default_factory=dict)

    @property
    def status(self) -> Status:
        """The run's outcome for the gate: the worst verdict that is not the one its property expects (a
        property with `expect = "violated"` that is violated counts as holding; one that holds counts as
        violated: the bug it stands for is no longer caught)."""
        statuses = {r.gate_status for r in self.results}
        for s in (Status.ERROR, Status.VIOLATED, Status.UNKNOWN):
            if s in statuses:
                return s
        return Status.HOLDS


class _DeadlockWatch:
    """Wraps an engine: sees every state the explorer expands, in order, and notes the first dead one."""

    def __init__(self, engine):
        self._engine = engine
        self.expanded = 0
        self.first_dead: int | None = None

    def __getattr__(self, name):
        return getattr(self._engine, name)

    def successors(self, s):
        out = self._engine.successors(s)
        if not out and self.first_dead is None:
            self.first_dead = self.expanded
        self.expanded += 1
        return out


class _Monitor:
    """The explorer's stop predicate: evaluates the on-the-fly checks on every stored state, in order."""

    def __init__(self, checks: list[Check], watch: _DeadlockWatch | None, stop_at_first: bool, only_witnesses: bool,
                 lasso: set | None = None):
        self.checks = checks
        self.lasso = lasso  # the markings of an LTL violation found on the fly, not yet stored
        self.watch = watch
        self.stop_at_first = stop_at_first
        self.may_stop = stop_at_first  # else it only observes (the partitioned search calls it afterwards)
        self.only_witnesses = only_witnesses  # every property of the scenario is a `reachable` one
        self.sid = 0

    def __call__(self, state) -> bool:
        sid = self.sid
        self.sid += 1
        violated = False
        for c in self.checks:
            if c.error is not None:
                continue
            try:
                if c.observe(sid, state) and not isinstance(c, Reachable):
                    violated = True
            except PredicateError as exc:
                c.error = exc  # decided: the property's text fails in this marking (exit status 65)
                violated = True
        if self.watch is not None and self.watch.first_dead is not None:
            violated = True
        if self.lasso is not None:
            self.lasso.discard(state)
            if not self.lasso:
                violated = True  # every marking of the lasso is stored: its trace can be shown
        if not self.stop_at_first:
            return False
        # a violation fails the gate whatever else holds; a witness stops the search only when nothing
        # else is waiting for the rest of the graph
        return violated or (self.only_witnesses and all(c.found is not None for c in self.checks))

    def observe_many(self, states) -> None:
        """`self(state)` for each of `states` in turn, a check at a time (the native search shows the states
        it stored a batch at a time, and only to be observed: it does not stop at a violation)."""
        sid = self.sid
        self.sid += len(states)
        for c in self.checks:
            if c.error is not None:
                continue
            try:
                c.observe_many(sid, states)
            except PredicateError as exc:
                c.error = exc
        if self.lasso is not None:
            self.lasso.difference_update(states)


def run_scenario(scenario: Scenario, run: Run, overrides: dict | None = None, progress=None,
                 model=None) -> RunResult:
    """Explore one run of a scenario and decide its properties.

    Raises ModelError (the model or a property text is wrong) and ConfigurationError (no model file).
    `overrides` replaces exploration options of the scenario (`max_states`, ...; `max_seconds = 0`: no
    time limit); `default_max_memory_mb` and `default_max_seconds` apply only where the scenario sets no
    such limit; `set` (the command line's constant values, already in `run.values`) is recorded in the
    options, and a value the model refuses stays an error of the command line. `model`, a loaded model,
    replaces the scenario's model file (a mutant of it, cpn.gate.mutation).
    """
    opts = _run_options(scenario, overrides)
    if model is None:
        model = _load_model(scenario, run, opts)
    engine = model.engine(time_condensation=bool(opts.get("time_condensation", False)))
    index = TransitionIndex(engine)
    lang = PropertyLanguage(model.net, engine, index)
    checks = build_checks(scenario.properties, lang, scenario.source)
    if opts.get("sweep_line"):  # the sweep-line method: no graph, the properties it can decide (docs/specs.md)
        from cpn.gate.sweep import sweep_run

        x, decided, t_x, t_c = sweep_run(scenario, engine, lang, checks, opts, progress)
        return RunResult(scenario, run, x, engine, [PropertyResult(c.spec, v, s) for c, v, s in decided], t_x, t_c,
                         opts)
    watch = _DeadlockWatch(engine) if any(isinstance(c, DeadlockFree) for c in checks) else None
    options, refused = _explore_options(scenario, model, engine, lang, checks, opts, watch)
    t0 = time.perf_counter()
    x = Explorer(watch if watch is not None else engine, options, progress=progress).run()
    explore_seconds = time.perf_counter() - t0
    x.engine = engine
    if watch is not None and (x.backend != "python" or watch.expanded < x.graph.expanded):
        # the partitioned search expanded the states in other processes or threads, the native search in C
        # (all of them, or the first ones before it handed over): the first dead state by number
        watch.first_dead = next(iter(x.graph.dead_states()), None)
    note = None
    if x.stop_reason.value == "predicate":
        note = "stop_at_first_violation is set and a violation (or witness) was found"
    view = GraphView(x, engine, lang, note)
    t1 = time.perf_counter()
    results = [_decide(c, view, refused, watch) for c in checks]
    return RunResult(scenario, run, x, engine, results, explore_seconds, time.perf_counter() - t1, opts)


def _run_options(scenario: Scenario, overrides: dict | None) -> dict:
    """The scenario's exploration options with the command line's over them (see `run_scenario`)."""
    overrides = dict(overrides or {})
    default_memory = overrides.pop("default_max_memory_mb", None)
    default_seconds = overrides.pop("default_max_seconds", None)
    opts = {**scenario.explore, **{k: v for k, v in overrides.items() if v is not None}}
    if "max_memory_mb" not in opts and default_memory is not None:
        opts["max_memory_mb"] = default_memory
    if "max_seconds" not in opts and default_seconds is not None:
        # the scenario sets no time limit: the command's default applies, and the report says so
        opts["max_seconds"] = default_seconds
        opts["max_seconds_is_default"] = True
    if opts.get("max_seconds") == 0:  # `--max-seconds 0`: no time limit, whatever the scenario says
        opts["max_seconds"] = None
    return opts


def _load_model(scenario: Scenario, run: Run, opts: dict):
    """The scenario's model with the run's values; an error of the model or of the scenario's values is
    reported at the scenario file."""
    from cpn.model import load

    try:
        return load(scenario.model, set=run.values)
    except ModelError as exc:
        raise _at_scenario(exc, scenario) from None
    except ConfigurationError as exc:
        named = _names_in(exc)
        if getattr(exc, "code", None) != "E0305" or (named and named <= set(opts.get("set") or {})):
            raise  # no such model file, or a value of the command line's --set: not the scenario's fault
        raise _values_at_scenario(exc, scenario) from None


def _explore_options(scenario: Scenario, model, engine, lang, checks: list, opts: dict, watch):
    """(the search's options, {check: why the reduction cannot decide it}): the monitor of the properties
    decided on the fly, LTL searched on the fly first, the reduction and its plan."""
    fly = [c for c in checks if c.on_the_fly and not isinstance(c, DeadlockFree)]
    stop_first = bool(opts.get("stop_at_first_violation", False))
    only_witnesses = all(isinstance(c, Reachable) and c.on_the_fly for c in checks)
    lasso = None
    if opts.get("reduction") is None and opts.get("symmetry") is None:
        lasso = _ltl_on_the_fly([c for c in checks if isinstance(c, Ltl)], engine, lang, opts)
    if not stop_first:
        lasso = None  # the whole state space is explored for the other properties anyway
    monitor = (_Monitor(fly, watch, stop_first, only_witnesses, lasso)
               if (fly or watch is not None or lasso is not None) else None)
    reduction = opts.get("reduction")
    visible, refused = stubborn_plan(checks) if reduction == "stubborn" else (None, {})
    scalars = ()
    if reduction == "symmetry" or opts.get("symmetry") is not None:
        if reduction == "stubborn":
            raise ConfigurationError("'reduction = \"stubborn\"' and 'symmetry' cannot be combined",
                                     hint="Choose one reduction.")
        reduction = "symmetry"
        scalars = symmetric_colour_sets(model, opts.get("symmetry") or None, scenario)
        refused = symmetry_plan(checks, model.net, scalars)
    options = ExploreOptions(max_states=opts.get("max_states"), max_arcs=opts.get("max_arcs"),
                             max_seconds=opts.get("max_seconds"), max_memory_mb=opts.get("max_memory_mb"),
                             stop_predicate=monitor, time_condensation=bool(opts.get("time_condensation", False)),
                             detect_time_growth=bool(opts.get("detect_time_growth", True)),
                             until_time=opts.get("until_time"),
                             reduction=reduction, visible_places=visible, symmetry=scalars,
                             workers=opts.get("workers"), ray=opts.get("ray"), backend=opts.get("backend", "auto"))
    return options, refused


def _decide(c: Check, view: GraphView, refused: dict, watch) -> PropertyResult:
    """The verdict of one property on the explored graph, with the warnings that it holds vacuously or by
    the net's structure alone."""
    x = view.x
    if isinstance(c, DeadlockFree) and watch is not None:
        c.found = watch.first_dead
    t = time.perf_counter()
    try:
        if c.error is not None:
            raise c.error
        verdict = c.decide(view)
        if x.reduction is not None and c in refused:
            verdict = decide_over_orbits(c, view) if x.reduction == "symmetry" else None
            verdict = verdict if verdict is not None else Verdict.unknown(refused[c])
        elif x.reduction is not None and verdict.status is not Status.UNKNOWN:
            how = "stubborn sets" if x.reduction == "stubborn" else "symmetry, one state per orbit"
            verdict.message += f" (graph reduced by {how}, {x.n_states:,} states: this property is preserved)"
    except PredicateError as exc:
        ev = evidence_to(x.graph, exc.state_id) if exc.state_id is not None else None
        verdict = Verdict(Status.ERROR, str(exc), ev, at=exc.span)
    try:
        warnings = vacuity(c, view, verdict) + structural(c, view, verdict) if x.reduction is None else []
    except PredicateError:  # a premise alone fails in a marking where the whole text does not
        warnings = []
    return PropertyResult(c.spec, verdict, time.perf_counter() - t, _places_read(c), warnings)


#: the markings the LTL searches on the fly may generate (through the engine, in Python); past it the
#: formula is decided on the explored graph, which the native search builds faster
LTL_FLY_STATES: int = 200_000


def _ltl_on_the_fly(checks: list[Ltl], engine, lang, opts: dict) -> set | None:
    """Decide the `ltl` properties on the fly, before the exploration (the markings each search generates
    kept for the next one), within the run's limits of states and seconds. Returns the markings of the
    first violation's lasso (None when none is violated)."""
    from cpn.checks.ltl import Cache
    from cpn.properties.ltl import lasso_states

    if not checks:
        return None
    cache = Cache(engine)
    seconds = opts.get("max_seconds")
    deadline = time.monotonic() + seconds if seconds else None
    limit = min(opts.get("max_states") or LTL_FLY_STATES, LTL_FLY_STATES)
    first = None
    for c in checks:
        try:
            res = c.search_on_the_fly(cache, lang, limit, deadline)
        except PredicateError as exc:
            c.error = exc  # decided: the formula's text fails in a marking (exit status 65)
            continue
        if res.holds is False and first is None:
            first = lasso_states(res)
    return first


def _places_read(check: Check) -> tuple:
    """The place instances a property names or its texts read (indices, sorted)."""
    out = set(getattr(check, "places", None) or ())
    for text in [getattr(check, "pred", None), getattr(check, "fn", None), *(getattr(check, "atoms", None) or ())]:
        out.update(getattr(text, "reads", ()) or ())
    return tuple(sorted(out))


def symmetric_colour_sets(model, spec: str | None, scenario: Scenario) -> tuple:
    """`model.symmetry(spec)`; a bad spec or a model without declarations is an error of the scenario."""
    try:
        return model.symmetry(spec)
    except ConfigurationError as exc:
        import re

        from cpn.diagnostics import Span

        span = None
        for n, line in enumerate(scenario.source.splitlines(), 1):
            m = re.match(r"\s*(symmetry|reduction)\s*=", line)
            if m:
                span = Span(scenario.path, n, m.start(1) + 1, n, m.end(1))
                if m.group(1) == "symmetry":
                    break
        message = str(exc).replace("--symmetry ", "symmetry = ")
        raise ModelError([Diagnostic("E0702", message, span, hint=exc.hint)],
                         {scenario.path: scenario.source}) from None


def _at_scenario(exc: ModelError, scenario: Scenario) -> ModelError:
    """A value of the scenario that the model rejects (E0305: no such `val`, or not CPN ML) is reported
    at its line in the scenario file."""
    diags = []
    for d in exc.diagnostics:
        name = d.params.get("name") if d.params else None
        if d.code == "E0305" and d.span is None and name in scenario.value_spans:
            d = dataclasses.replace(d, span=scenario.value_spans[name])
        elif d.code == "E0305" and name is None:
            for n, span in scenario.value_spans.items():
                if f"'{n}'" in d.message:
                    d = dataclasses.replace(d, span=span)
                    break
        diags.append(d)
    return ModelError(diags, {**exc.sources, scenario.path: scenario.source})


def _names_in(exc) -> set:
    """The constants an E0305 ConfigurationError names (one '--set NAME=...' line each)."""
    import re

    return {m.group(1) for m in re.finditer(r"^\s*--set ([^=\s]+)=", str(exc), re.MULTILINE)}


def _values_at_scenario(exc, scenario: Scenario) -> ModelError:
    """A value of [set] or of a parameter row that the model refuses (E0305), at its line in the scenario."""
    import re

    diags = []
    for line in str(exc).splitlines():
        m = re.match(r"\s*--set ([^=\s]+)=.*?: (.*)$", line)
        if not m:
            continue
        name, message = m.group(1), m.group(2)
        diags.append(Diagnostic("E0305", f"the value of '{name}': {message}", scenario.value_spans.get(name),
                                hint=None if "not a CPN ML expression" in message else exc.hint))
    if not diags:
        diags = [Diagnostic("E0305", str(exc), None, hint=exc.hint)]
    return ModelError(diags, {scenario.path: scenario.source})


def check(path, **overrides) -> list[RunResult]:
    """Every run of the scenario file `path` (docs/specs.md), with its verdicts.

    Examples
    --------
    >>> import cpn
    >>> [(p.spec.name, p.verdict.status.value) for p in cpn.check("specs/examples/dp.toml")[0].results][:1]
    [('the only dead marking: everyone holds the left fork', 'holds')]
    """
    from cpn.gate.scenario import load_scenario
    from cpn.model import caching

    scenario = load_scenario(path)
    with caching():
        return [run_scenario(scenario, run, overrides) for run in scenario.runs]
