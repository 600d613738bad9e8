"""Mutation testing of a gate: run the scenarios that check a model on mutants of it (`cpn.gate.mutants`)
and say which property catches each one, and which mutants no property catches.

A mutant is *killed* when some property of some run of the scenarios misses its expected verdict (or
its text fails in a marking, or the model fails while it is explored: the gate would fail); it *survives*
when every run passes. Mutants that do not load, whose labelled state space equals the original's
(equivalent), or whose search a limit stopped before anything failed (undecided) are counted apart.
Imports `cpn.checks`, `cpn.model`, `cpn.lang` and layer 0.
"""

from __future__ import annotations

import hashlib
import os
import time
from dataclasses import dataclass, field

from cpn.checks.verdict import Status
from cpn.gate.mutants import Mutant, mutants, select

KILLED = "killed"
SURVIVED = "survived"
EQUIVALENT = "equivalent"
NOT_LOADABLE = "not loadable"
UNDECIDED = "undecided"
OUTCOMES = (KILLED, SURVIVED, EQUIVALENT, NOT_LOADABLE, UNDECIDED)

# a mutant's search stops after this many times the original's states (plus a floor), and after this many
# times its seconds: a mutant that makes the state space grow without end is undecided, not a hang
STATES_FACTOR = 10
STATES_FLOOR = 1_000
SECONDS_FACTOR = 10
SECONDS_FLOOR = 10.0
# a mutant's search runs in Python where the original has at most this many states: building the native
# search of each mutant's net takes a compiler run (2.5 s for DP(5), whose 82 states Python searches in
# milliseconds); larger state spaces repay it
PYTHON_SEARCH_STATES = 20_000


@dataclass
class Killer:
    """A property that caught a mutant: its verdict and the length of its counterexample (steps)."""

    scenario: str
    run: str
    prop: str
    verdict: str  # 'violated' (or 'holds' for a property that expects to be violated; 'error')
    steps: int | None


@dataclass
class Outcome:
    mutant: Mutant
    outcome: str
    killers: list[Killer] = field(default_factory=list)
    reason: str = ""  # why it did not load, was undecided, or which run-time error killed it
    seconds: float = 0.0


@dataclass
class ModelMutation:
    """The mutants of one model and their outcomes under every scenario run that checks the model."""

    model: str  # the model file, as the scenarios name it (relative to the working directory)
    source: str
    scenarios: list[str]  # scenario files
    runs: int
    generated: int  # mutants of the model before any sample was drawn
    selected: int
    outcomes: list[Outcome] = field(default_factory=list)
    original: list[dict] = field(default_factory=list)  # per run: scenario, run, states, arcs, seconds
    property_names: dict = field(default_factory=dict)  # scenario file -> its property names, in order
    problem: str | None = None  # the original does not pass its gate: nothing was mutated
    problem_status: str | None = None  # 'violated', 'unknown' or 'error'
    seconds: float = 0.0

    def count(self, outcome: str) -> int:
        return sum(1 for o in self.outcomes if o.outcome == outcome)

    @property
    def not_run(self) -> int:
        """Selected mutants the time budget left out."""
        return self.selected - len(self.outcomes) if self.problem is None else 0

    @property
    def score(self) -> float | None:
        """Killed / (killed + survived), in percent; None when no mutant was decided."""
        return _score(self.count(KILLED), self.count(SURVIVED))


@dataclass
class MutationReport:
    models: list[ModelMutation]
    seed: int
    max_mutants: int | None
    max_seconds: float | None
    workers: int
    seconds: float = 0.0

    def count(self, outcome: str) -> int:
        return sum(m.count(outcome) for m in self.models)

    @property
    def score(self) -> float | None:
        return _score(self.count(KILLED), self.count(SURVIVED))

    @property
    def not_run(self) -> int:
        return sum(m.not_run for m in self.models)

    @property
    def mutants_run(self) -> int:
        return sum(len(m.outcomes) for m in self.models)


def _score(killed: int, survived: int) -> float | None:
    return None if killed + survived == 0 else 100.0 * killed / (killed + survived)


# ---------------------------------------------------------------------------------------------- driver


def mutate(scenarios: list, *, seed: int = 0, max_mutants: int | None = None, max_seconds: float | None = None,
           workers: int = 1, overrides: dict | None = None, mutant_max_states: int | None = None,
           all_runs: bool = False, on_outcome=None) -> MutationReport:
    """Mutation testing of the models the scenarios check.

    Scenarios that check the same model form one gate: a mutant of the model is killed when a run of any
    of them fails. `max_mutants` draws that many mutants per model with `seed` (the same mutants for the
    same seed); `max_seconds` bounds the whole run (mutants not started by then are counted as not run);
    `workers` processes run mutants side by side. `overrides` are the scenario options of `run_scenario`
    for the original runs. A killed mutant stops at the first run that catches it; with `all_runs` it goes
    on through every run, so that every property that catches it is known. `on_outcome(model, outcome)`
    is called as each mutant is decided.
    A model that cannot be read, or whose original runs fail to load or evaluate, is reported with its
    `problem` and not mutated.
    """
    t0 = time.perf_counter()
    deadline = None if max_seconds is None else t0 + max_seconds
    report = MutationReport([], seed, max_mutants, max_seconds, workers)
    groups: dict[str, list] = {}
    for s in scenarios:
        groups.setdefault(s.model, []).append(s)
    from cpn.model import caching

    for model_path, group in groups.items():
        with caching():  # the original runs load their model once per set of values, as `check` does
            report.models.append(_mutate_model(model_path, group, seed, max_mutants, deadline, workers,
                                               dict(overrides or {}), mutant_max_states, all_runs, on_outcome))
    report.seconds = time.perf_counter() - t0
    return report


def _mutate_model(model_path, group, seed, max_mutants, deadline, workers, overrides, mutant_max_states,
                  all_runs, on_outcome) -> ModelMutation:
    from cpn.errors import ConfigurationError, EvaluationError, ModelError
    from cpn.gate.run import run_scenario
    from cpn.lang.parser import parse
    from cpn.model import importer_for, source_of

    t0 = time.perf_counter()
    runs = [(s, r) for s in group for r in s.runs]
    shown = os.path.relpath(model_path) if not os.path.relpath(model_path).startswith("..") else model_path
    try:
        source = source_of(model_path)
    except (ModelError, ConfigurationError, OSError) as exc:
        result = ModelMutation(shown, "", [s.path for s in group], len(runs), 0, 0)
        result.problem = f"the model cannot be read: {exc.render() if hasattr(exc, 'render') else exc}"
        result.problem_status = "error"
        return result
    filename = f"{shown} (as .cpnet)" if importer_for(model_path) is not None else shown
    result = ModelMutation(shown, source, [s.path for s in group], len(runs), 0, 0,
                           property_names={s.path: [p.name for p in s.properties] for s in group})
    originals = []
    for s, r in runs:
        try:
            rr = run_scenario(s, r, overrides)
        except (ModelError, ConfigurationError, EvaluationError) as exc:
            result.problem = f"the original model cannot be checked: run '{r.name}' of {s.path}: {exc.render()}"
            result.problem_status = "error"
            result.seconds = time.perf_counter() - t0
            return result
        originals.append(rr)
        x = rr.exploration
        result.original.append({"scenario": s.path, "run": r.name, "states": x.graph.n_states if x.graph else None,
                                "arcs": x.graph.n_arcs if x.graph else None, "seconds": rr.explore_seconds})
        status = rr.status
        if status is not Status.HOLDS:
            bad = next(p for p in rr.results if p.gate_status is status)
            result.problem = (f"the original model does not pass the gate: run '{r.name}' of {s.path}: property "
                              f"'{bad.spec.name}' is {bad.verdict.status.value}")
            result.problem_status = status.value
            result.seconds = time.perf_counter() - t0
            return result
    # every run sets these constants: the value the model declares is never used
    skip = frozenset.intersection(*[frozenset(r.values) for _, r in runs]) if runs else frozenset()
    found = mutants(parse(source, filename), skip)
    chosen = select(found, max_mutants, seed)
    result.generated, result.selected = len(found), len(chosen)
    limits = []
    for rr in originals:
        x = rr.exploration
        states = mutant_max_states or (STATES_FACTOR * x.graph.n_states + STATES_FLOOR if x.graph else None)
        small = x.graph is not None and x.graph.n_states <= PYTHON_SEARCH_STATES
        limits.append({"max_states": states, "max_seconds": max(SECONDS_FACTOR * rr.explore_seconds, SECONDS_FLOOR),
                       "backend": "python" if small else "auto"})
    job = _Job(filename, source, runs, limits, [_counts(rr) for rr in originals],
               overrides.get("default_max_memory_mb") or overrides.get("max_memory_mb"), all_runs)
    digests: dict[int, str] = {}

    def finish(outcome: Outcome, got: list | None) -> None:
        if got is not None:  # same counts in every run: equivalent if the labelled graphs are the same
            for i, _ in got:
                if i not in digests:  # the original's digest, once per run
                    digests[i] = graph_digest(originals[i].exploration)
            outcome.outcome = EQUIVALENT if all(d == digests[i] for i, d in got) else SURVIVED
        result.outcomes.append(outcome)
        if on_outcome is not None:
            on_outcome(result, outcome)

    if workers <= 1:
        for m in chosen:
            if deadline is not None and time.perf_counter() >= deadline:
                break
            finish(*job.evaluate(m, _remaining(deadline)))
    else:
        _run_parallel(job, chosen, workers, deadline, finish)
    result.outcomes.sort(key=lambda o: o.mutant.number)
    result.seconds = time.perf_counter() - t0
    return result


def _remaining(deadline: float | None) -> float | None:
    return None if deadline is None else max(0.5, deadline - time.perf_counter())


def _run_parallel(job, chosen, workers, deadline, finish) -> None:
    import concurrent.futures as cf
    import multiprocessing

    ctx = multiprocessing.get_context("spawn")  # no state of this process (threads, caches) is copied
    with cf.ProcessPoolExecutor(max_workers=workers, mp_context=ctx, initializer=_worker_init,
                                initargs=(job,)) as pool:
        pending = list(chosen)
        running: set = set()
        while pending or running:
            while pending and len(running) < workers and (deadline is None or time.perf_counter() < deadline):
                running.add(pool.submit(_worker_evaluate, pending.pop(0), _remaining(deadline)))
            if not running:
                break
            done, running = cf.wait(running, return_when=cf.FIRST_COMPLETED)
            for f in sorted(done, key=lambda f: f.result()[0].mutant.number):
                finish(*f.result())


_JOB = None


def _worker_init(job) -> None:
    global _JOB
    _JOB = job


def _worker_evaluate(mutant: Mutant, remaining: float | None):
    return _JOB.evaluate(mutant, remaining)


def _counts(rr) -> tuple | None:
    """What a mutant's state space must match before its graph is compared: states, arcs, dead states."""
    x = rr.exploration
    if x.graph is None or not x.complete:
        return None
    return x.graph.n_states, x.graph.n_arcs, len(x.graph.dead_states())


@dataclass
class _Job:
    """What evaluating one mutant needs; sent once to each worker process."""

    filename: str
    source: str
    runs: list  # (Scenario, Run)
    limits: list  # per run: max_states, max_seconds
    counts: list  # per run: the original's (states, arcs, dead states), or None
    max_memory_mb: float | None
    all_runs: bool = False  # a killed mutant goes on through every run (what each property catches)

    def evaluate(self, mutant: Mutant, remaining: float | None) -> tuple[Outcome, list | None]:
        """The mutant's outcome, and the digests of its state spaces (run index, digest) when every run
        passes with the original's counts (the caller compares them with the original's), else None."""
        from cpn.errors import ConfigurationError, EvaluationError, ModelError
        from cpn.gate.run import run_scenario
        from cpn.lang.parser import parse

        t0 = time.perf_counter()
        text = mutant.apply(self.source)
        undecided = None
        digests: list | None = []
        loaded: dict = {}
        tree = None
        caught: list[Killer] = []
        failed = ""  # the first run-time error of the mutant, when it killed it
        for i, (scenario, run) in enumerate(self.runs):
            limits = dict(self.limits[i])
            if remaining is not None:
                limits["max_seconds"] = min(limits["max_seconds"], remaining)
            if self.max_memory_mb is not None:
                limits["max_memory_mb"] = self.max_memory_mb
            try:
                # the runs share the parse of the mutant; runs with the same values its type check and lowering
                key = tuple(sorted((k, str(v)) for k, v in run.values.items()))
                model = loaded.get(key)
                if model is None:
                    if tree is None:
                        tree = parse(text, self.filename)
                    model = loaded[key] = _load_parsed(tree, text, self.filename, run.values)
            except RecursionError:
                return Outcome(mutant, NOT_LOADABLE, reason="the mutant's expressions are nested too deeply",
                               seconds=time.perf_counter() - t0), None
            except (ModelError, ConfigurationError) as exc:
                if caught or failed:
                    continue
                return Outcome(mutant, NOT_LOADABLE, reason=_first_line(exc),
                               seconds=time.perf_counter() - t0), None
            try:
                rr = run_scenario(scenario, run, limits, model=model)
            except EvaluationError as exc:
                failed = failed or f"run '{run.name}': the model fails: {_first_line(exc)}"
                if not self.all_runs:
                    break
                continue
            except (ModelError, ConfigurationError) as exc:
                if caught or failed:
                    continue
                return Outcome(mutant, NOT_LOADABLE, reason=_first_line(exc),
                               seconds=time.perf_counter() - t0), None
            caught += [Killer(scenario.path, run.name, p.spec.name, p.verdict.status.value, _steps(p.verdict))
                       for p in rr.results if p.gate_status in (Status.VIOLATED, Status.ERROR)]
            if (caught or failed) and not self.all_runs:
                break
            if caught or failed:
                continue
            if rr.status is Status.UNKNOWN and undecided is None:
                x = rr.exploration
                undecided = (f"run '{run.name}': the search stopped ({x.stop_reason.value}) after "
                             f"{x.graph.n_states if x.graph else 0:,} states before any property failed")
            if digests is not None and self.counts[i] is not None and _counts(rr) == self.counts[i]:
                digests.append((i, graph_digest(rr.exploration)))
            else:
                digests = None
        seconds = time.perf_counter() - t0
        if caught or failed:
            return Outcome(mutant, KILLED, caught, reason=failed, seconds=seconds), None
        if undecided is not None:
            return Outcome(mutant, UNDECIDED, reason=undecided, seconds=seconds), None
        return Outcome(mutant, SURVIVED, seconds=seconds), digests


def _load_parsed(tree, text: str, filename: str, values: dict):
    """`cpn.model.loads` from a parsed model: the type checker annotates and rewrites the tree it is
    given, so each load checks a copy (a copy of the MODBUS model takes half the time of its parse)."""
    import copy

    from cpn.errors import ModelError
    from cpn.lang.nesting import too_deep
    from cpn.lang.overrides import parse_overrides
    from cpn.lang.typecheck import check
    from cpn.model import Model, normalise_overrides
    from cpn.net.lower import lower

    overrides = parse_overrides(normalise_overrides(values))
    try:
        checked = check(copy.deepcopy(tree), overrides)
        net = lower(checked)
    except RecursionError:
        raise ModelError([too_deep(tree.decls, filename)], {filename: text}) from None
    return Model(filename, text, net, checked.warnings)


def _steps(verdict) -> int | None:
    ev = verdict.evidence
    if ev is None:
        return None
    return len(ev.path) - 1 + len(ev.cycle)


def _first_line(exc) -> str:
    text = exc.render() if hasattr(exc, "render") else str(exc)
    return next((line.strip() for line in text.splitlines() if line.strip()), type(exc).__name__)


def graph_digest(x) -> str:
    """A digest of the labelled state space: every marking (as CPN ML text per place, with the clock of a
    timed net), the initial one, and every arc with its binding element's text. Two nets with the same
    digest have the same behaviour for every property that reads markings and binding elements."""
    g, e = x.graph, x.engine
    places = range(len(e.places))
    keys = []
    for s in g.states:
        key = "|".join(e.format_marking(s, p) for p in places)
        keys.append(f"{key}@{e.clock(s)}" if e.is_timed else key)
    texts: dict = {}
    arcs = []
    off, dst, bes = g.offsets, g.dst, g.bes
    for i in range(g.expanded):
        for a in range(off[i], off[i + 1]):
            be = bes[a]
            if be not in texts:
                texts[be] = e.format_binding_element(be)
            arcs.append(f"{keys[i]}\t{texts[be]}\t{keys[dst[a]]}")
    h = hashlib.sha256()
    h.update("\n".join(p.name for p in e.places).encode())
    h.update(b"\0" + keys[0].encode() + b"\0")
    for k in sorted(keys):
        h.update(k.encode() + b"\n")
    h.update(b"\0")
    for a in sorted(arcs):
        h.update(a.encode() + b"\n")
    return h.hexdigest()
