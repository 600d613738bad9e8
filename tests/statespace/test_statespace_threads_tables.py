"""The threads of `--workers N` run the net's C themselves, each in
a context of its own (a speed-up on two cores) over one set of tables of markings, deltas and binding elements (`_cnet.c`, a lock
per table, reads without one), and compute the results of caches that rarely hit anew (as one process
does). The graph is the one-process search's whatever the number of threads, more threads than cores
included; every marking and binding element is numbered once; the results computed anew are the cached
ones. The markings C made come back to the engine unindexed, and are indexed when it next needs them."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from array import array

import pytest

import cpn
from cpn.statespace import ExploreOptions, Explorer, native
from tests._shared import ROOT
from tests.engine.randomnets import random_net
from tests.statespace._partition import consistent, summary

# the random nets of test_statespace_threads.py (their libraries are cached by their source)
SEEDS = list(range(3, 1000, 23))[:16]


def _load(spec: str):
    path, _, n = spec.partition(":")
    return cpn.load(os.path.join(ROOT, path), set={"N": n} if n else None)


def _threaded(engine, n: int, **opts):
    x = Explorer(engine, ExploreOptions(workers=n, **opts)).run()
    assert x.backend == "threads", x.notes
    return x


def _numbered_once(engine) -> None:
    """Each place's markings and deltas, and the binding elements, are distinct (the threads' tables came
    back to the engine with one id for each)."""
    for tables in (engine.store.dicts, engine._deltas):
        for p, ms in enumerate(tables):
            keys = [frozenset(d.items()) for d in ms]
            assert len(set(keys)) == len(keys), f"a multiset of place {p} has two ids"
    assert len(set(engine._be)) == len(engine._be), "a binding element has two ids"


#: two larger nets; MS(5) is a long test (`--slow`, about 8 s each on a 2-core machine)
LARGER = ["bench/nets/dp.cpnet:7", pytest.param("bench/nets/ms.cpnet:5", marks=pytest.mark.slow)]

@pytest.mark.parametrize("spec", LARGER)
def test_more_threads_than_cores_give_the_one_process_graph(spec):
    want = summary(Explorer(_load(spec).engine(), ExploreOptions()).run())
    for n in (4, 6, 6):
        engine = _load(spec).engine()
        x = _threaded(engine, n)
        assert summary(x) == want, f"{n} threads"
        assert sum(x.partition["worker_states"]) == x.n_states and len(x.partition["computed"]) == n
        _numbered_once(engine)


@pytest.mark.parametrize("seed", SEEDS[:8])
def test_random_nets_with_six_threads(seed):
    model = cpn.loads(random_net(seed))
    if model.net.is_timed:
        pytest.skip("a timed random net")
    one = Explorer(model.engine(), ExploreOptions(max_states=3000)).run()
    engine = model.engine()
    x = _threaded(engine, 6, max_states=3000)
    if one.complete:
        assert summary(x) == summary(one)
    else:  # which states a limit leaves depends on the order within the last level: state by state
        consistent(x)
    _numbered_once(engine)


@pytest.mark.parametrize("spec", LARGER)
def test_threads_computing_results_anew_give_the_cached_graph(spec, monkeypatch):
    want = summary(Explorer(_load(spec).engine(), ExploreOptions()).run())  # every result cached
    monkeypatch.setattr(native, "UNCACHED_AFTER", 2)  # a cache that misses once of two stops storing
    for n in (1, 2, 3):
        x = _threaded(_load(spec).engine(), n)
        assert summary(x) == want, f"{n} threads"
        assert all(k > 0 for k in x.partition["uncached"]), x.partition
    monkeypatch.setattr(native, "UNCACHED_AFTER", 0)  # never: every result cached by every thread
    x = _threaded(_load(spec).engine(), 2)
    assert summary(x) == want and x.partition["uncached"] == [0, 0]


def test_the_engine_searches_again_after_the_threads():
    """The tables are the engine's alone once the threads end: a second threaded search and the
    one-process native search of the same engine give the same graph."""
    engine = _load("bench/nets/dp.cpnet:7").engine()
    first = summary(_threaded(engine, 2))
    assert summary(_threaded(engine, 3)) == first
    again = Explorer(engine, ExploreOptions(backend="c")).run()
    assert again.backend == "c" and summary(again) == first


def test_markings_made_in_c_are_indexed_when_the_python_engine_next_needs_them():
    """The markings C made come back to the engine without their keys (`append_new`, the serial part of
    the threads' assembly); the engine's interning finds each with C's id, and indexes them only then."""
    engine = _load("bench/nets/dp.cpnet:6").engine()
    x = Explorer(engine, ExploreOptions(backend="c")).run()
    assert x.backend == "c"
    places = engine.store
    assert places.pending, "the markings C made are not indexed yet"
    for p, ds in enumerate(places.dicts):
        for i, d in enumerate(list(ds)):
            assert places.intern(p, dict(reversed(list(d.items())))) == i  # found, in any token order
    assert not places.pending
    one = summary(Explorer(_load("bench/nets/dp.cpnet:6").engine(), ExploreOptions(backend="python")).run())
    assert summary(x) == one


def test_a_marking_appended_twice_is_an_error_when_indexed():
    engine = _load("bench/nets/dp.cpnet:3").engine()
    engine.initial_state()
    places = engine.store
    p = next(p for p, ds in enumerate(places.dicts) if ds[-1])
    places.append_new(p, [dict(places.dicts[p][-1])])
    with pytest.raises(RuntimeError, match="a marking has two ids"):
        places.intern(p, {"no such token": 1})


def test_the_threads_store_builds_its_table_when_a_state_is_first_looked_up():
    """The assembled graph's records are appended without the store's hash table (cs_append), which is
    built when a state is first looked up or added."""
    g = _threaded(_load("bench/nets/ms.cpnet:5").engine(), 2).graph
    store = g.store
    unbuilt = store.nbytes()
    assert all(store.find(s) == i for i, s in enumerate(g.states))
    assert store.nbytes() > unbuilt
    n = g.n_states
    s = g.states[n - 1]
    new = tuple(v + 70000 for v in s)  # no such marking ids: a new state, its fields widened
    dst = array("i")
    assert store.add_successors([(0, s), (0, new), (0, g.states[0])], dst) == [1]
    assert list(dst) == [n - 1, n, 0] and store.find(new) == n and len(store) == n + 1


_RACES = """
import sys
import cpn._util.cbuild as cbuild
flags = cbuild.cflags
cbuild.cflags = lambda: flags() + ["-fsanitize=thread", "-g"]
import cpn
from cpn.statespace import ExploreOptions, Explorer, native
native.UNCACHED_AFTER = int(sys.argv[1])
for net in ("dp", "ms"):
    model = cpn.load(f"bench/nets/{net}.cpnet", set={"N": "5"})
    x = Explorer(model.engine(), ExploreOptions(workers=3)).run()
    assert x.backend == "threads", x.notes
    print(net, x.n_states, x.n_arcs)
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="ThreadSanitizer's run-time is looked for on Linux")
def test_the_threads_race_on_no_memory_under_thread_sanitizer():
    """The library built with -fsanitize=thread (the tables read without a lock, their locks, the kept
    arrays): ThreadSanitizer reports no data race with 3 threads, results cached or computed anew."""
    cc = shutil.which("gcc")
    found = subprocess.run([cc, "-print-file-name=libtsan.so"], capture_output=True, text=True) if cc else None
    runtime = found.stdout.strip() if found else ""
    if not os.path.isabs(runtime):
        pytest.skip("no ThreadSanitizer run-time (gcc's libtsan)")
    env = {**os.environ, "LD_PRELOAD": runtime, "TSAN_OPTIONS": "report_signal_unsafe=0 halt_on_error=0",
           "CC": cc}
    for after in ("0", "2"):
        run = subprocess.run([sys.executable, "-c", _RACES, after], cwd=ROOT, env=env, capture_output=True,
                             text=True, timeout=300)
        assert "ThreadSanitizer" not in run.stderr, run.stderr[-3000:]
        assert run.returncode == 0, run.stderr[-3000:]
        assert run.stdout.split() == ["dp", "82", "265", "ms", "12393", "76545"]


def test_threads_that_cannot_start_leave_the_search_to_the_processes(monkeypatch):
    """th_start fails: the threaded search is freed at once (its tables shared with the engine's context
    of the net's C, which is still alive), and the processes search, with a note."""
    from types import SimpleNamespace

    from cpn.statespace import threads

    real = native.library

    def failing(code=None, timed=False):
        lib = real(code, timed)
        if lib is None or code is None:
            return lib

        class Lib:
            def __getattr__(self, name):
                return getattr(lib.lib, name)

            def th_start(self, h):
                return -1

        return SimpleNamespace(ffi=lib.ffi, lib=Lib(), path=lib.path)

    monkeypatch.setattr(threads.native, "library", failing)
    x = Explorer(_load("bench/nets/dp.cpnet:5").engine(), ExploreOptions(workers=2)).run()
    assert x.backend == "workers" and x.n_states == 82
    assert any("the threads could not be started" in n for n in x.notes), x.notes
