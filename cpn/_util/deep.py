"""Deep structures without deep Python recursion: the left spine of an operator chain, and a call run on a
stack large enough for deep recursion in a model's own functions.

Stdlib only; no domain knowledge (the node classes are given by the caller).
"""

from __future__ import annotations

import sys
import threading
from collections.abc import Callable
from typing import Any


def left_spine(e: Any, cls: type, stop: Callable[[Any], bool] | None = None) -> tuple[Any, list]:
    """The leftmost operand and the nodes of the left spine of `e`, innermost first.

    `a + b + c` is `(a + b) + c`: its spine is `[a + b, (a + b) + c]` and its leftmost operand `a`. A walker
    evaluates the operand, then each node of the spine with its right operand, in a loop: one Python frame
    for the whole chain instead of one per term. Nodes of class `cls` are followed through their `left`
    field, unless `stop(node)` says that node is no part of the chain.
    """
    nodes = []
    while isinstance(e, cls) and not (stop is not None and stop(e)):
        nodes.append(e)
        e = e.left
    nodes.reverse()
    return e, nodes


#: the stack of the thread that runs a deep evaluation (virtual memory: only the pages touched are used)
DEEP_STACK_BYTES: int = 1024 * 1024 * 1024
#: Python frames allowed there: 10,000 levels of a model's recursive function take 40,000 to 80,000 frames
#: in the tree-walking evaluator, and a CPN Tools model that walks a year hour by hour (22,000 levels and
#: more) needed between 200,000 and 300,000; the stack holds this many frames of the deepest kind measured
#: (about 2 KiB of C stack each for a call through a Python object's __call__) with room to spare
DEEP_RECURSION_LIMIT: int = 400_000

_deep_lock = threading.Lock()


def call_deep(fn: Callable[..., Any], *args: Any) -> Any:
    """`fn(*args)` on a thread with a DEEP_STACK_BYTES stack and DEEP_RECURSION_LIMIT Python frames.

    For a computation that hit Python's recursion limit on the ordinary stack (a model's function recursing
    thousands of levels deep): it is run again from the start, so it must have no effect but its result.
    Its exception, RecursionError included, is raised here. One at a time: the recursion limit is the
    interpreter's, raised while the thread runs and put back after.
    """
    result: list = []
    error: list = []

    def run() -> None:
        try:
            result.append(fn(*args))
        except BaseException as exc:  # noqa: BLE001 - handed to the caller's thread
            error.append(exc)

    with _deep_lock:
        old_limit = sys.getrecursionlimit()
        old_size = threading.stack_size()
        worker = None
        # where the address space is limited (ulimit -v), a smaller stack with a limit to match
        for size, limit in ((DEEP_STACK_BYTES, DEEP_RECURSION_LIMIT), (DEEP_STACK_BYTES // 8, DEEP_RECURSION_LIMIT // 8)):
            try:
                threading.stack_size(size)
                worker = threading.Thread(target=run, name="cpn-deep-evaluation", daemon=True)
                sys.setrecursionlimit(max(old_limit, limit))
                worker.start()
                break
            except (RuntimeError, ValueError, MemoryError):
                sys.setrecursionlimit(old_limit)
                worker = None
            finally:
                threading.stack_size(old_size)
        if worker is None:
            raise RecursionError("no thread with a deep stack could be started")
        try:
            worker.join()
        finally:
            sys.setrecursionlimit(old_limit)
    if error:
        raise error[0]
    return result[0]


def deepest_recursion(exc: BaseException, label: Callable[[Any], str | None]) -> tuple[str, int] | None:
    """The function that recursed in the traceback of `exc` and how many of its calls were nested there.

    `label(frame)` names the function a frame runs (None for frames of no interest). The function with
    the most frames wins; of two with as many, the innermost.
    """
    counts: dict[str, int] = {}
    last = None
    tb = exc.__traceback__
    while tb is not None:
        name = label(tb.tb_frame)
        if name is not None:
            counts[name] = counts.get(name, 0) + 1
            last = name
        tb = tb.tb_next
    if not counts:
        return None
    name = max(counts, key=lambda k: (counts[k], k == last))
    return name, counts[name]


def run_deep(fn: Callable[..., Any], args: tuple, too_deep: Callable[[RecursionError], BaseException],
             label: Callable[[Any], str | None]) -> Any:
    """`fn(*args)`; if that runs out of Python's recursion limit, once more by `call_deep`. Past what the deep
    stack allows, `too_deep(message)` is raised with the traceback of the recursion (which tells where it
    started), the message naming the function that recursed (`deepest_recursion` with `label`)."""
    try:
        return fn(*args)
    except RecursionError:
        pass  # the retry runs outside this handler, so that the first attempt's frames are freed
    return run_deep_again(fn, args, too_deep, label)


def run_deep_again(fn: Callable[..., Any], args: tuple, too_deep: Callable[[RecursionError], BaseException],
                   label: Callable[[Any], str | None]) -> Any:
    """The second half of `run_deep`: `fn(*args)` by `call_deep`, after it ran out of the ordinary stack."""
    try:
        return call_deep(fn, *args)
    except RecursionError as exc:
        found = deepest_recursion(exc, label)
        message = "recursion too deep" if found is None else (
            f"recursion too deep in function '{found[0]}' ({found[1]:,} nested calls, more than can be evaluated)")
        raise too_deep(message).with_traceback(exc.__traceback__) from None
