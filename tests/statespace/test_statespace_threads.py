"""`--workers N` as threads of one process (`cpn.statespace.threads`, `_threads.c`) on
nets whose every transition is in generated C: with 1, 2 and 3 threads the same states, arcs, dead
markings, bounds, levels and report as the one-process native search, on DP, MS, the repository's untimed
models and random nets; limits, Ctrl-C and the progress hook work; a key the C cannot evaluate makes the
search run again by processes, with a note; where threads do not apply, the processes run, with a note."""

from __future__ import annotations

import glob
import os
import signal

import pytest

import cpn
from cpn.report import build_report, to_json
from cpn.statespace import ExploreOptions, Explorer, StopReason
from cpn.statespace.chooser import why_not_threaded
from tests._shared import ROOT
from tests.engine.randomnets import random_net
from tests.statespace._partition import Observer, compare, consistent, summary

THREADS = (1, 2, 3)
MODELS = sorted(os.path.relpath(p, ROOT) for p in glob.glob(os.path.join(ROOT, "models", "**", "*.cpnet"),
                                                               recursive=True))


def _load(spec: str):
    path, _, n = spec.partition(":")
    return cpn.load(os.path.join(ROOT, path), set={"N": n} if n else None)


@pytest.mark.parametrize("spec", ["bench/nets/dp.cpnet:6", "bench/nets/ms.cpnet:4"])
def test_dp_and_ms_with_1_2_3_threads_as_one_process(spec):
    got = compare(_load(spec), workers=THREADS, threads=True)
    assert got["backends"] == ["threads"] * len(THREADS)


def test_ms5_graph_is_consistent_state_by_state():
    for n in THREADS:
        x = Explorer(_load("bench/nets/ms.cpnet:5").engine(), ExploreOptions(workers=n)).run()
        assert x.backend == "threads" and x.complete and (x.n_states, x.n_arcs) == (12393, 76545)
        assert x.partition["threads"] == n and sum(x.partition["worker_states"]) == x.n_states
        consistent(x)


@pytest.mark.parametrize("spec", MODELS)
def test_repository_models_with_threads(spec):
    model = _load(spec)
    if model.net.is_timed:
        pytest.skip("timed nets are searched in one process")
    compare(model, workers=(2, 3), threads=True, max_states=20000)


def test_most_repository_models_run_in_threads():
    """The models above are not all searched by processes: the threads run most untimed ones."""
    ran, untimed = 0, 0
    for spec in MODELS:
        engine = _load(spec).engine()
        if engine.is_timed:
            continue
        untimed += 1
        why, _code = why_not_threaded(engine, ExploreOptions(workers=2), engine.initial_state())
        ran += why is None
    assert untimed and ran >= untimed // 2, (ran, untimed)


# the random nets whose C tests/engine/test_generated_c.py builds too (the libraries are cached by their source)
SEEDS = list(range(3, 1000, 23))[:16]


@pytest.mark.parametrize("seed", SEEDS)
def test_random_nets_with_threads(seed):
    model = cpn.loads(random_net(seed))
    if model.net.is_timed:
        pytest.skip("a timed random net")
    one = Explorer(model.engine(), ExploreOptions(max_states=3000)).run()
    if one.complete:
        compare(model, workers=THREADS, threads=True, max_states=3000)
        return
    # an unbounded net: which states a limit leaves in the graph depends on the order within the last
    # level, so the graph is checked state by state instead
    for n in THREADS:
        x = Explorer(model.engine(), ExploreOptions(workers=n, max_states=3000)).run()
        assert x.stop_reason is StopReason.MAX_STATES and x.n_states >= 3000
        consistent(x)


def test_random_nets_run_in_threads():
    ran = 0
    for seed in SEEDS:
        engine = cpn.loads(random_net(seed)).engine()
        if not engine.is_timed:
            ran += why_not_threaded(engine, ExploreOptions(workers=2), engine.initial_state())[0] is None
    assert ran >= 12


# a recursion deeper than the C's limit (ccodegen.MAX_DEPTH) from the fourth level on: the C hands that key
# to the Python engine, which computes it; the threads cannot, so the processes search again
DEEP = """colset N = int with 0..5;
var x : N;
fun depth n = if n = 0 then 0 else 1 + depth (n - 1);
place P : N = 1`0;
place Q : N;
trans inc [x < 5 andalso depth (x * 30) >= 0];
arc P -> inc : x;
arc inc -> P : x + 1;
arc inc -> Q : x;
"""


@pytest.mark.parametrize("n", THREADS)
def test_a_key_the_c_cannot_evaluate_runs_the_search_again_by_processes(n):
    model = cpn.loads(DEEP)
    one = Explorer(model.engine(), ExploreOptions()).run()
    x = Explorer(model.engine(), ExploreOptions(workers=n)).run()
    assert x.backend == "workers" and x.complete
    assert any(note.startswith("processes, not threads: the net's C met a binding") for note in x.notes), x.notes
    assert summary(x)["states"] == summary(one)["states"] and (x.n_states, x.n_arcs) == (6, 5)


@pytest.mark.parametrize("n", THREADS)
@pytest.mark.parametrize("limit,value", [("max_states", 1), ("max_states", 700), ("max_states", 5000),
                                         ("max_arcs", 1), ("max_arcs", 3000)])
def test_limits_stop_the_threads_near_the_limit_with_a_consistent_graph(n, limit, value):
    x = Explorer(_load("bench/nets/ms.cpnet:5").engine(), ExploreOptions(workers=n, **{limit: value})).run()
    assert x.backend == "threads" and x.stop_reason.value == limit and x.unexpanded > 0
    reached = x.n_states if limit == "max_states" else x.n_arcs
    # checked every few dozen states per thread: at most that many expansions past the limit
    assert value <= reached < value + n * 64 * 20
    consistent(x)


def test_max_seconds_progress_and_ctrl_c():
    seen = []

    def progress(p):
        seen.append(p)
        if len(seen) == 2:
            os.kill(os.getpid(), signal.SIGINT)  # what Ctrl-C sends

    x = Explorer(_load("bench/nets/dp.cpnet:16").engine(),
                 ExploreOptions(workers=2, progress_interval=0.0), progress=progress).run()
    assert x.backend == "threads" and x.stop_reason is StopReason.INTERRUPTED and x.unexpanded > 0
    assert seen[-1].states == x.n_states and all(p.states >= 1 for p in seen)
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    y = Explorer(_load("bench/nets/dp.cpnet:16").engine(), ExploreOptions(workers=2, max_seconds=0.2)).run()
    assert y.stop_reason is StopReason.MAX_SECONDS and y.unexpanded > 0 and y.n_states < 1331714
    g = y.graph
    assert len(g.offsets) == g.expanded + 1 and all(0 <= d < g.n_states for d in g.dst)


def test_the_report_says_the_search_ran_in_threads():
    x = Explorer(_load("bench/nets/dp.cpnet:5").engine(), ExploreOptions(workers=2)).run()
    notes = to_json(build_report(x))["notes"]
    assert "the search ran in 2 threads of this process, the states partitioned by a hash of each state" in notes
    y = Explorer(_load("bench/nets/dp.cpnet:5").engine(), ExploreOptions(workers=2, threads=False)).run()
    assert y.backend == "workers" and any("worker processes" in n for n in to_json(build_report(y))["notes"])


@pytest.mark.parametrize("options,why", [
    ({"backend": "python"}, "Python back end"),
    ({"threads": False}, "processes were asked for"),
    ({"packed_states": False}, "tuples"),
])
def test_where_threads_do_not_apply_the_processes_run_with_a_note(options, why):
    model = _load("bench/nets/dp.cpnet:4")
    x = Explorer(model.engine(), ExploreOptions(workers=2, **options)).run()
    assert x.backend == "workers" and x.complete
    if "threads" not in options:
        assert any(n.startswith("processes, not threads") and why in n for n in x.notes), x.notes
    assert why in why_not_threaded(model.engine(), ExploreOptions(workers=2, **options), (0,))[0]


def test_a_transition_left_to_python_keeps_the_processes():
    # a real colour set is not held in C: the net has a transition left to the Python engine
    model = cpn.loads("colset L = real; var l : L;"
                      " place P : L = 1`0.0; trans t [l < 3.0]; arc P -> t : l; arc t -> P : l + 1.0;")
    engine = model.engine()
    why, _ = why_not_threaded(engine, ExploreOptions(workers=2), engine.initial_state())
    assert why is not None
    x = Explorer(engine, ExploreOptions(workers=2)).run()
    assert x.backend == "workers" and x.n_states == 4


def test_an_observing_predicate_sees_each_state_once_when_the_processes_search_again():
    seen = Observer()
    x = Explorer(cpn.loads(DEEP).engine(), ExploreOptions(workers=2, stop_predicate=seen)).run()
    assert x.backend == "workers" and x.complete  # the threads gave up: the C could not evaluate a key
    assert seen.seen == list(x.graph.states)  # the initial state once, then every other in order


def test_an_error_in_the_progress_hook_stops_the_threads_and_is_raised():
    def progress(p):
        raise ValueError("the hook failed")

    engine = _load("bench/nets/dp.cpnet:14").engine()
    with pytest.raises(ValueError, match="the hook failed"):
        Explorer(engine, ExploreOptions(workers=2, progress_interval=0.0), progress=progress).run()
    x = Explorer(engine, ExploreOptions(workers=2, max_states=1000)).run()  # the engine still works
    assert x.backend == "threads" and x.n_states >= 1000
