"""Independent jobs of one command on several processes of this machine, their results in order.

`check` runs its scenario runs this way (`--jobs`): each run is explored in a process of a pool, and the
results come back in the order the runs were given, with what each run printed, so the output and the
reports are those of one process. Imports only the standard library.

The pool's processes are forked where the system can (Linux), so they start in a few milliseconds with
the command's state: its loaded scenarios and the parses of the models it has kept. Ctrl-C is the
command's: the processes ignore it, and the command stops them and reports what had finished.
"""

from __future__ import annotations

import contextlib
import io
import multiprocessing
import os
import signal
import sys
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import ProcessPoolExecutor


def usable_cpus() -> int:
    """The processors this process may run on (its affinity mask, as a container or `taskset` sets it)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def default_jobs(n_items: int) -> int:
    """One process per usable processor, no more than there are jobs."""
    return max(1, min(usable_cpus(), n_items))


def _ignore_interrupt() -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C reaches the whole process group: the parent acts


class _Captured:
    """`fn(item)` with what it prints to standard output and standard error, kept to be printed in order."""

    def __init__(self, fn: Callable):
        self.fn = fn

    def __call__(self, item):
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            value = self.fn(item)
        return value, out.getvalue(), err.getvalue()


def ordered_map(fn: Callable, items: Iterable, jobs: int) -> Iterator:
    """Yield `fn(item)` for each item, in the items' order, computed by `jobs` processes; each result is
    yielded as soon as it and those before it are done, after what `fn` printed for it.

    `fn` must be a module-level function (where processes are not forked, it and the items are pickled).
    An exception of `fn` is raised here, at its item; a process that ends without a result (killed, out of
    memory, a crash) raises `BrokenProcessPool` here, at the first item it leaves undone. On
    KeyboardInterrupt (and on any exception) the processes are stopped at once.
    """
    method = "fork" if "fork" in multiprocessing.get_all_start_methods() else "spawn"
    pool = ProcessPoolExecutor(jobs, mp_context=multiprocessing.get_context(method), initializer=_ignore_interrupt)
    captured = _Captured(fn)
    try:
        futures = [pool.submit(captured, item) for item in items]
        for f in futures:
            value, out, err = f.result()
            sys.stdout.write(out)
            sys.stderr.write(err)
            yield value
    except BaseException:
        _stop(pool)
        raise
    pool.shutdown()


def _stop(pool: ProcessPoolExecutor) -> None:
    """Stop the pool's processes now, the runs they are in the middle of included (the executor has no
    public call for it before Python 3.14: its own record of its processes)."""
    for process in list((getattr(pool, "_processes", None) or {}).values()):
        process.terminate()
    pool.shutdown(wait=True, cancel_futures=True)
