"""The partitioned search: with 1 and 2 worker processes, the same states, arcs, dead
markings, bounds and report as the one-process search, on the repository's models and a corpus sample;
limits stop it and say so; what it cannot run falls back to one process with a note."""

from __future__ import annotations

import glob
import os
import pickle
from collections import Counter

import pytest

import cpn
from cpn.engine.transfer import transfer_for
from cpn.statespace import ExploreOptions, Explorer, StopReason
from cpn.statespace.chooser import why_not_partitioned
from cpn.statespace.parallel import PartitionWorker
from tests._shared import ROOT, SHARED, needs_shared
from tests.statespace._partition import Observer, canonical, compare, summary

MODELS = sorted(os.path.relpath(p, ROOT) for p in glob.glob(os.path.join(ROOT, "models", "**", "*.cpnet"),
                                                               recursive=True))
MODELS += ["bench/nets/dp.cpnet:5", "bench/nets/ms.cpnet:3"]

CORPUS = ["CSRepetitions-COL-02", "DatabaseWithMutex-COL-02", "LamportFastMutEx-COL-2", "NeoElection-COL-2",
          "SafeBus-COL-03", "CPNBook-LimitProtocol", "Sudoku-COL-AN02", "TokenRing-PT-005",
          "QuasiCertifProtocol-COL-02", "Philosophers-PT-000005"]


def _load(spec: str):
    path, _, n = spec.partition(":")
    return cpn.load(os.path.join(ROOT, path), set={"N": n} if n else None)


@pytest.mark.parametrize("spec", MODELS)
def test_repository_models_have_the_same_state_space_with_1_and_2_workers(spec):
    compare(_load(spec), max_states=20000)


@needs_shared
@pytest.mark.parametrize("name", CORPUS)
def test_corpus_sample_has_the_same_state_space_with_1_and_2_workers(name):
    folder = os.path.join(SHARED, "validation", name)
    if not os.path.isdir(folder):
        pytest.skip(f"no validation corpus at {folder}")
    path = os.path.join(folder, next(f for f in sorted(os.listdir(folder)) if f.endswith((".pnml", ".cpn"))))
    got = compare(cpn.load(path), workers=(2,), max_states=30000)
    assert got["stop"] is StopReason.COMPLETE


def test_the_partition_hash_is_the_same_in_every_engine_and_process():
    net = _load("bench/nets/ms.cpnet:3").net
    from cpn.engine import compile_net

    a, b = transfer_for(compile_net(net)), transfer_for(compile_net(pickle.loads(pickle.dumps(net))))
    e = a.engine
    # b meets the markings in another order: its intern ids differ, the exported states and hashes do not
    states = [s for _, s in e.successors(e.initial_state())]
    for s in reversed(states):
        b.import_state(a.export_state(s))
    for s in states:
        t = b.import_state(a.export_state(s))
        assert b.export_state(t) == a.export_state(s) and b.stable_hash(t) == a.stable_hash(s)
    # the same hash in a fresh interpreter (salted str hashes would differ): a worker process started
    # with spawn computes the owner of the initial state
    import multiprocessing as mp

    with mp.get_context("spawn").Pool(1) as pool:
        assert pool.apply(_hash_of_initial_state, (pickle.dumps(net),)) == a.stable_hash(e.initial_state())


def _hash_of_initial_state(blob: bytes) -> int:
    w = PartitionWorker(blob, False, 0, 1)
    return w.transfer.stable_hash(w.engine.initial_state())


def test_a_state_space_larger_than_a_step_and_a_union_colour_set():
    # more states than one step of a worker (several steps per level), and values the transfer must keep
    net = """colset N = int with 0..40; colset V = union A + B : N; var x : N; var v : V;
    place P : N = 1`0; place Q : N = 1`0; place R : V = 1`A;
    trans inc [x < 40]; arc P -> inc : x; arc inc -> P : x + 1;
    trans up [x < 40]; arc Q -> up : x; arc up -> Q : x + 1;
    trans flip; arc R -> flip : v; arc flip -> R : (case v of A => B(0) | B(k) => if k < 2 then B(k + 1) else A);"""
    from cpn.statespace import parallel

    old = parallel.STEP_STATES
    parallel.STEP_STATES = 64
    try:
        got = compare(cpn.loads(net), workers=(2,))
    finally:
        parallel.STEP_STATES = old
    assert sum(got["states"].values()) == 41 * 41 * 4


@pytest.mark.parametrize("threads", [False, True])
@pytest.mark.parametrize("limit", ["max_states", "max_arcs"])
def test_a_limit_stops_the_partitioned_search_and_the_graph_is_consistent(limit, threads):
    model = _load("bench/nets/ms.cpnet:4")
    x = Explorer(model.engine(), ExploreOptions(workers=2, threads=threads, **{limit: 500})).run()
    assert x.backend == ("threads" if threads else "workers")
    assert x.stop_reason.value == limit and not x.complete and x.unexpanded > 0
    g = x.graph
    assert (g.n_states if limit == "max_states" else g.n_arcs) >= 500
    assert g.n_states < 3321 and len(g.offsets) == g.expanded + 1 and g.n_arcs == g.offsets[-1]
    assert all(0 <= d < g.n_states for d in g.dst)
    # the unexpanded states come last and are never dead; the expanded ones are all the states of the
    # levels before the last one expanded
    full = summary(Explorer(model.engine(), ExploreOptions()).run())
    part = summary(x)
    assert all(full["depth"][s] == d for s, d in part["depth"].items())
    assert set(part["dead"]) <= set(full["dead"])


@pytest.mark.parametrize("threads", [False, True])
def test_max_seconds_stops_the_partitioned_search(threads):
    # the threads search DP(14) in about 0.4 s: they get a net that takes seconds
    x = Explorer(_load("bench/nets/dp.cpnet:16" if threads else "bench/nets/dp.cpnet:14").engine(),
                 ExploreOptions(workers=2, max_seconds=0.5, threads=threads)).run()
    assert x.stop_reason is StopReason.MAX_SECONDS and x.unexpanded > 0 and x.seconds < 30


@pytest.mark.parametrize("threads", [False, True])
def test_max_memory_counts_the_workers_memory(threads):
    # every process uses tens of MiB: a limit of 1 MiB stops at the first look
    x = Explorer(_load("bench/nets/dp.cpnet:8").engine(),
                 ExploreOptions(workers=2, max_memory_mb=1, threads=threads)).run()
    assert x.stop_reason is StopReason.MAX_MEMORY and x.n_states >= 1


@pytest.mark.parametrize("threads", [False, True])
def test_an_observing_stop_predicate_sees_every_state_in_breadth_first_order(threads):
    model = _load("bench/nets/dp.cpnet:5")

    one, two = Observer(), Observer()
    x = Explorer(model.engine(), ExploreOptions(stop_predicate=one)).run()
    y = Explorer(model.engine(), ExploreOptions(workers=2, stop_predicate=two, threads=threads)).run()
    assert y.backend == ("threads" if threads else "workers") and x.complete and y.complete
    assert two.seen == list(y.graph.states)
    assert Counter(canonical(x.engine, s) for s in one.seen) == Counter(canonical(y.engine, s) for s in two.seen)


@pytest.mark.parametrize("options,why", [
    ({"reduction": "stubborn"}, "stubborn sets"),
    ({"max_successors": 1}, "branching options"),
    ({"stop_predicate": lambda s: False}, "stop predicate"),
])
def test_what_the_partitioned_search_cannot_run_falls_back_with_a_note(options, why):
    model = _load("bench/nets/dp.cpnet:4")
    x = Explorer(model.engine(), ExploreOptions(workers=2, **options)).run()
    y = Explorer(model.engine(), ExploreOptions(**options)).run()
    assert x.backend in ("c", "python") and (x.n_states, x.n_arcs) == (y.n_states, y.n_arcs)
    assert any(n.startswith("the search ran in one process") and why in n for n in x.notes), x.notes


def test_timed_nets_and_the_reference_interpreter_fall_back():
    timed = cpn.load(os.path.join(ROOT, "models/examples/timer_cancel.cpnet"))
    assert "timed nets" in why_not_partitioned(timed.engine(), ExploreOptions(workers=2))
    ref = _load("bench/nets/dp.cpnet:3").engine(reference=True)
    assert "reference interpreter" in why_not_partitioned(ref, ExploreOptions(workers=2))
    x = Explorer(ref, ExploreOptions(workers=2)).run()
    y = Explorer(_load("bench/nets/dp.cpnet:3").engine(), ExploreOptions()).run()
    assert x.complete and x.n_states == y.n_states and x.backend == "python"
    assert any("reference interpreter" in n for n in x.notes)


def test_an_error_in_a_worker_is_reported_by_the_one_process_search_with_its_trace():
    from cpn.errors import EvaluationError

    net = cpn.loads("colset N = int with 0..5; var x : N; place P : N = 1`0;"
                    " trans inc; arc P -> inc : x; arc inc -> P : 10 div (3 - x);")
    with pytest.raises(EvaluationError) as err:
        Explorer(net.engine(), ExploreOptions(workers=2)).run()
    assert err.value.trace


@pytest.mark.parametrize("threads", [False, True])
def test_ctrl_c_stops_the_partitioned_search_with_a_consistent_partial_graph(threads):
    import signal

    calls = []

    def progress(p):
        if not calls:
            os.kill(os.getpid(), signal.SIGINT)  # what Ctrl-C sends; the workers ignore it
        calls.append(p)

    # the threads search DP(12) in a few dozen milliseconds: they get a net too large to end before Ctrl-C
    spec, total = ("bench/nets/dp.cpnet:16", 1331714) if threads else ("bench/nets/dp.cpnet:12", 39202)
    engine = _load(spec).engine()
    x = Explorer(engine, ExploreOptions(workers=2, progress_interval=0.0, threads=threads), progress=progress).run()
    assert x.backend == ("threads" if threads else "workers")
    assert x.stop_reason is StopReason.INTERRUPTED and x.unexpanded > 0 and x.n_states < total
    g = x.graph
    assert len(g.offsets) == g.expanded + 1 and g.n_arcs == g.offsets[-1] and all(0 <= d < g.n_states for d in g.dst)
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler  # given back after the search
