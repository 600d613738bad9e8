"""The partitioned search (`--workers N`): the breadth-first search in N processes, each owning a part of
the states, then the graph assembled in the calling process so that every analysis runs unchanged.

How it works (as in Helena, LTSmin and DiVinE's distributed searches):

- Every state belongs to worker `stable_hash(state) % N` (`cpn.engine.transfer`: the same in every
  process, unlike Python's salted `hash()` of strings). Each worker compiles the net itself (the net is
  pickled to it), keeps the states it owns (their ids, BFS levels and parents) and expands them with
  its own engine.
- The search is level-synchronous: a worker expands the states of the current BFS level it owns, at
  most `budget` of them per step, and sends every successor owned by another worker to that worker in
  one batch per step (a state as one canonical key per place, the arc as its source, position and
  binding element). The coordinator starts the next level only when every worker has expanded its part
  of this one and every batch was delivered, so each state is reached first at its BFS depth and its
  parent pointer gives a shortest path, as in the one-process search.
- The coordinator looks at the limits (states, arcs, seconds, the memory of all the processes) and the
  progress hook after every step; Ctrl-C (which the workers ignore) stops it the same way. The batches
  still in flight are then delivered (their states stored unexpanded) and the workers send their parts.
- Assembly: the expanded states first, by (level, worker, order of arrival), then the unexpanded ones;
  every state is imported into the caller's engine, every binding element too, and the arcs of a state
  are put in the order its worker's engine gave them. The result is an ordinary `Exploration` whose graph
  has the same states, arcs, dead markings and bounds as the one-process search (only the numbering of
  states and the order of arcs may differ).

Where the partitioned search does not apply (timed nets, reductions, branching options, a stop predicate
that may stop the search, the reference interpreter), `cpn.statespace.chooser.why_not_partitioned` says
why and the caller searches in one process; `run_partitioned` returns None with a one-line reason where
the workers could not start or failed. A stop predicate that only observes the states
(its attribute `may_stop` is False, as the property checks' monitor without stop_at_first_violation) is
called on every state of the assembled graph in breadth-first order, as the one-process search calls it.
The transport is pluggable: `LocalWorkers` (processes of this machine, through pipes) here, a Ray
cluster in `cpn.statespace.distributed`; `cpn.statespace.chooser` chooses it.
"""

from __future__ import annotations

import gc
import pickle
import signal
import time
from array import array
from bisect import bisect_right
from operator import getitem

from cpn.engine.protocol import capability
from cpn.errors import EvaluationError
from cpn.statespace._memory import current_rss_mb, peak_rss_mb
from cpn.statespace.graph import StateGraph
from cpn.statespace.options import Backend, ExploreOptions, StopReason
from cpn.statespace.result import Exploration, Progress, observe
from cpn.statespace.store import new_store

#: states a worker expands per step at most: the limits and Ctrl-C are looked at between steps
STEP_STATES: int = 4096
#: a worker remembers the owner of at most this many states of other workers (cleared when full)
REMOTE_CACHE: int = 1 << 18


class WorkerFailed(Exception):
    """A worker stopped with an error (the caller repeats the search in one process to report it)."""


# ------------------------------------------------------------------------------------------ worker

class PartitionWorker:
    """One worker of the partitioned search: the states it owns, the arcs of those it expanded, its engine.

    Arcs are kept by their source, in the order the engine gave them (the arcs of the i-th expanded state
    follow those of the (i-1)-th): the binding element and the destination's local id, or -1 where another
    worker owns the destination. That worker records (source worker, arc position, its local id) when the
    successor arrives. A state's parent is the arc that found it first: (worker, arc position).
    """

    def __init__(self, net_blob: bytes, time_condensation: bool, me: int, n: int):
        from cpn.engine import compile_net
        from cpn.engine.transfer import transfer_for

        self.engine = compile_net(pickle.loads(net_blob), time_condensation=time_condensation)
        self.transfer = transfer_for(self.engine)
        self.me, self.n = me, n
        self.states: list = []
        self.ids: dict = {}
        self.level = array("i")
        self.parent_w = array("i")
        self.parent_pos = array("q")
        self.expanded = array("q")  # local ids, in the order they were expanded
        self.degree = array("i")  # number of arcs of each expanded state (same order)
        self.dst = array("q")  # per arc: the local id of its destination, -1 if another worker owns it
        self.bes = array("i")  # per arc: its binding element (in this worker's engine)
        self.in_w = array("i")  # arcs of other workers into this worker's states: source worker,
        self.in_pos = array("q")  # position of the arc there,
        self.in_dst = array("q")  # and the local id of the destination here
        self.lvl = 0
        self.cur: list[int] = []
        self.pos = 0
        self.nxt: list[int] = []
        self.sent = 0
        self.remote: dict = {}  # successors owned by other workers met before: their owner
        k = len(self.engine.places)
        # per worker and place: a flag per place id, set once the key of that id was sent to the worker
        self.key_sent = [[bytearray() for _ in range(k)] for _ in range(n)]
        self.tables = [[{} for _ in range(k)] for _ in range(n)]  # per sender and place: its id -> ours

    def seed(self, c: tuple) -> None:
        """Store the initial state (exported form): this worker owns it."""
        s = self.transfer.import_state(c)
        self.ids[s] = 0
        self.states.append(s)
        self.level.append(0)
        self.parent_w.append(-1)
        self.parent_pos.append(-1)
        self.cur.append(0)

    def _new(self, s, w: int, pos: int) -> int:
        j = self.ids[s] = len(self.states)
        self.states.append(s)
        self.level.append(self.lvl + 1)
        self.parent_w.append(w)
        self.parent_pos.append(pos)
        self.nxt.append(j)
        return j

    def step(self, budget: int, advance: bool, inboxes) -> tuple:
        """Store the batches sent to this worker, start the next level if told to, expand at most `budget`
        states of the current level: (status, one batch (bytes or None) per worker)."""
        # as in the one-process search: the cyclic collector would walk every stored state again and again
        enabled = gc.isenabled()
        gc.disable()
        try:
            return self._step(budget, advance, inboxes)
        finally:
            if enabled:
                gc.enable()

    def _step(self, budget: int, advance: bool, inboxes) -> tuple:
        ids_get = self.ids.get
        new = self._new
        for w, blob in enumerate(inboxes):
            if not blob:
                continue
            positions, states, keys, refs = pickle.loads(blob)
            tables = self.tables[w]
            for p, their_ids, ks in keys:
                tables[p].update(zip(their_ids, self.transfer.import_place_keys(p, ks)))
            self.in_w.extend(array("i", [w]) * len(positions))
            self.in_pos.extend(positions)
            in_dst = self.in_dst.append
            resolved = [-1] * len(states)
            for pos, x in zip(positions, refs):
                j = resolved[x]
                if j < 0:
                    s = tuple(map(getitem, tables, states[x]))  # the sender's ids to ours
                    j = ids_get(s)
                    if j is None:
                        j = new(s, w, pos)
                    resolved[x] = j
                in_dst(j)
        if advance:
            self.cur, self.nxt, self.pos = self.nxt, [], 0
            self.lvl += 1
        n, me = self.n, self.me
        # per worker: positions of the arcs, their states (each once), keys of new place ids, and for
        # each arc the index of its state in the batch
        out = [(array("q"), [], [], array("i")) for _ in range(n)]
        in_batch = [{} for _ in range(n)]
        successors = self.engine.successors
        owner = self.transfer.stable_hash
        key_sent = self.key_sent
        states = self.states
        known = self.remote
        known_get = known.get
        end = min(len(self.cur), self.pos + budget)
        expanded_append, degree_append = self.expanded.append, self.degree.append
        dst_append, bes_append = self.dst.append, self.bes.append
        pos = len(self.dst)
        for sid in self.cur[self.pos:end]:
            succ = successors(states[sid])
            expanded_append(sid)
            degree_append(len(succ))
            for be, t in succ:
                bes_append(be)
                j = ids_get(t)
                if j is None:
                    d = known_get(t)
                    if d is None:
                        d = owner(t) % n if n > 1 else me
                        if d != me:
                            if len(known) >= REMOTE_CACHE:
                                known.clear()
                            known[t] = d
                    if d == me:
                        j = new(t, me, pos)
                    else:
                        j = -1
                        box = out[d]
                        x = in_batch[d].get(t)
                        if x is None:
                            x = in_batch[d][t] = len(box[1])
                            box[1].append(t)
                            try:
                                every_key_sent = all(map(getitem, key_sent[d], t))
                            except IndexError:
                                every_key_sent = False
                            if not every_key_sent:
                                self._send_keys(t, key_sent[d], box[2])
                        box[0].append(pos)
                        box[3].append(x)
                dst_append(j)
                pos += 1
        self.pos = end
        batches = []
        for box in out:
            if box[1]:
                self.sent += len(box[0])
                batches.append(pickle.dumps(box, protocol=pickle.HIGHEST_PROTOCOL))
            else:
                batches.append(None)
        return self.status([len(b) if b else 0 for b in batches]), batches

    def _send_keys(self, t: tuple, sent: list[bytearray], keys: list) -> None:
        """Add to a batch the keys of the place ids of `t` its receiver was not sent yet."""
        tr = self.transfer
        for p, i in enumerate(t):
            flags = sent[p]
            if i >= len(flags):
                flags.extend(bytes(max(i + 1 - len(flags), len(flags))))
            if not flags[i]:
                flags[i] = 1
                keys.append((p, (i,), tr.place_keys(p, i, i + 1)))

    def status(self, sizes=()) -> tuple:
        """(states stored, states expanded, arcs, left in this level, found for the next level, successors
        sent to other workers so far, resident MiB, bytes of this step's batch for each worker, CPU seconds)."""
        return (len(self.states), len(self.expanded), len(self.dst), len(self.cur) - self.pos, len(self.nxt),
                self.sent, current_rss_mb(), list(sizes), time.process_time())

    def collect(self) -> bytes:
        """This worker's part of the graph, exported (pickled)."""
        tr = self.transfer
        part = {
            "states": self.states, "keys": [tr.place_keys(p) for p in range(len(self.engine.places))],
            "level": self.level, "parent_w": self.parent_w,
            "parent_pos": self.parent_pos, "expanded": self.expanded, "degree": self.degree, "dst": self.dst,
            "bes": self.bes, "in_w": self.in_w, "in_pos": self.in_pos, "in_dst": self.in_dst,
            "be_keys": tr.export_binding_elements(),
        }
        return pickle.dumps(part, protocol=pickle.HIGHEST_PROTOCOL)


# ------------------------------------------------------------------------------------------ transport

def _serve(conn, net_blob: bytes, time_condensation: bool, me: int, n: int) -> None:
    """A worker process: answers the coordinator's calls until told to stop."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the coordinator's: it stops the search
    try:
        worker = PartitionWorker(net_blob, time_condensation, me, n)
    except BaseException as exc:  # noqa: BLE001 - reported to the coordinator
        conn.send(("error", _describe(exc)))
        return
    conn.send(("ok", None))
    while True:
        try:
            msg = conn.recv()
        except EOFError:
            return
        name = msg[0]
        if name == "stop":
            return
        try:
            result = getattr(worker, name)(*msg[1:])
        except BaseException as exc:  # noqa: BLE001 - reported to the coordinator
            conn.send(("error", _describe(exc)))
            continue
        conn.send(("ok", result))


def _describe(exc: BaseException) -> str:
    if isinstance(exc, EvaluationError):
        return exc.render() if hasattr(exc, "render") else str(exc)
    return f"{type(exc).__name__}: {exc}"


class LocalWorkers:
    """N worker processes of this machine, each behind a pipe; batches are routed by the coordinator."""

    name = Backend.WORKERS

    def __init__(self, n: int, net_blob: bytes, time_condensation: bool):
        import multiprocessing as mp

        # fork is cheapest (the workers rebuild their engine from the pickled net either way)
        method = "fork" if "fork" in mp.get_all_start_methods() else "spawn"
        ctx = mp.get_context(method)
        self.n = n
        self.conns, self.procs = [], []
        try:
            for w in range(n):
                a, b = ctx.Pipe()
                p = ctx.Process(target=_serve, args=(b, net_blob, time_condensation, w, n), daemon=True,
                                name=f"cpn-verify worker {w}")
                p.start()
                b.close()
                self.conns.append(a)
                self.procs.append(p)
            self._replies(range(n))
        except BaseException:
            self.close()
            raise

    def _replies(self, ws) -> list:
        """The replies of the workers `ws`, all of them even if Ctrl-C comes meanwhile (then re-raised)."""
        out, interrupted, failure = [], False, None
        for w in ws:
            while True:
                try:
                    status, value = self.conns[w].recv()
                    break
                except KeyboardInterrupt:
                    interrupted = True
                except EOFError:
                    status, value = "error", f"worker {w} ended unexpectedly (exit code {self.procs[w].exitcode})"
                    break
            if status == "error" and failure is None:
                failure = f"worker {w}: {str(value).splitlines()[0] if value else value}"
            out.append(value)
        if failure is not None:
            raise WorkerFailed(failure)
        if interrupted:
            raise KeyboardInterrupt
        return out

    def call(self, w: int, name: str, *args):
        self.conns[w].send((name, *args))
        return self._replies([w])[0]

    def step(self, budget: int, advance: bool, inboxes: list[list]) -> tuple[list, list]:
        """One step of every worker: (their statuses, outboxes[w][d] the batch from w to d)."""
        for w in range(self.n):
            self.conns[w].send(("step", budget, advance, inboxes[w]))
        replies = self._replies(range(self.n))
        return [r[0] for r in replies], [r[1] for r in replies]

    def collect(self) -> list[bytes]:
        for w in range(self.n):
            self.conns[w].send(("collect",))
        return self._replies(range(self.n))

    def close(self) -> None:
        for c in self.conns:
            try:
                c.send(("stop",))
                c.close()
            except OSError:
                pass
        for p in self.procs:
            p.join(timeout=5)
            if p.is_alive():
                p.terminate()
                p.join(timeout=5)
        self.conns, self.procs = [], []


# ------------------------------------------------------------------------------------------ coordinator

def net_blob(net) -> bytes:
    """The net, pickled for the workers, without the front end's checked model (`Net.checked`, which the
    engine never reads and the property checks extend with functions that cannot be pickled)."""
    import copy

    light = copy.copy(net)
    if hasattr(light, "checked"):
        light.checked = None
    return pickle.dumps(light, protocol=pickle.HIGHEST_PROTOCOL)


class CtrlC:
    """Ctrl-C only sets `hit` while the coordinator runs (a step is never cut in half: its batches would
    be lost); the coordinator stops at the end of the step. Outside the main thread it changes nothing."""

    def __init__(self):
        self.hit = False
        self._old = None

    def __enter__(self):
        try:
            self._old = signal.signal(signal.SIGINT, self._handle)
        except ValueError:  # not the main thread
            self._old = None
        return self

    def _handle(self, _signum, _frame):
        if self.hit:  # a second Ctrl-C: give up the partial result
            raise KeyboardInterrupt
        self.hit = True

    def __exit__(self, *exc):
        if self._old is not None:
            signal.signal(signal.SIGINT, self._old)
        return False


def run_partitioned(engine, options: ExploreOptions, progress, transport, at_s0: bool = False,
                    threads_note: str | None = None):
    """The partitioned search of `engine` over the workers `transport(net_blob, time_condensation)` starts
    (`cpn.statespace.chooser` chose them: `LocalWorkers`, or Ray's): (Exploration, None), or (None, why)
    where the workers could not start or failed. `at_s0`: the (observing) stop predicate holds in the
    initial state; `threads_note`: why the threads did not search this net (a note of the result)."""
    from cpn.engine.transfer import transfer_for

    t0 = time.perf_counter()
    blob = net_blob(engine.net)
    cond = bool(capability(engine, "time_condensation", False))
    try:
        workers = transport(blob, cond)
    except WorkerFailed as exc:
        return None, f"the search ran in one process: the workers could not start ({exc})"
    try:
        search = _Coordinator(engine, transfer_for(engine), options, progress, workers, t0)
        search.at_s0 = at_s0
        with CtrlC() as ctrl_c:
            search.ctrl_c = ctrl_c
            x = search.run()
        if threads_note is not None:
            x.notes.append(f"processes, not threads: {threads_note}")
        return x, None
    except WorkerFailed as exc:
        # the one-process search meets the same error and reports it with the trace to its state
        return None, f"the search was repeated in one process: {exc}"
    finally:
        workers.close()


class _Coordinator:
    def __init__(self, engine, transfer, options: ExploreOptions, progress, transport, t0: float):
        self.engine, self.transfer, self.options = engine, transfer, options
        self.progress, self.transport, self.t0 = progress, transport, t0
        self.n = transport.n
        self.rss = [0.0] * self.n
        self.cpu = [0.0] * self.n  # the workers' CPU seconds (process time, their start included)
        self.ctrl_c = CtrlC()
        self.bytes_sent = 0  # the batches' bytes, all steps
        self.sent = 0  # successors sent to another worker (one per arc whose target another worker owns)
        self.at_s0 = False  # the stop predicate holds in the initial state (asked by the caller)

    def _memory_mb(self) -> float:
        return current_rss_mb() + sum(self.rss)

    def run(self):
        opts, n, transport = self.options, self.n, self.transport
        self.t_started = time.perf_counter()  # the workers are up
        s0 = self.engine.initial_state()
        c0 = self.transfer.export_state(s0)
        transport.call(self.transfer.stable_hash(s0) % n, "seed", c0)
        max_states = opts.max_states if opts.max_states is not None else 1 << 62
        max_arcs = opts.max_arcs if opts.max_arcs is not None else 1 << 62
        deadline = self.t0 + opts.max_seconds if opts.max_seconds is not None else None
        next_progress = self.t0 + opts.progress_interval
        inboxes = [[None] * n for _ in range(n)]
        advance = False
        states, expanded, arcs = 1, 0, 0
        stop = StopReason.COMPLETE
        if self.at_s0:
            stop = StopReason.PREDICATE
        try:
            while stop is StopReason.COMPLETE:
                if states >= max_states:
                    stop = StopReason.MAX_STATES
                    break
                if arcs >= max_arcs:
                    stop = StopReason.MAX_ARCS
                    break
                budget = _budget(max_states - states, max_arcs - arcs, expanded, arcs, n)
                statuses, outboxes = transport.step(budget, advance, inboxes)
                inboxes = [[outboxes[w][d] for w in range(n)] for d in range(n)]
                states = sum(s[0] for s in statuses)
                expanded = sum(s[1] for s in statuses)
                arcs = sum(s[2] for s in statuses)
                self.rss = [s[6] for s in statuses]
                self.cpu = [s[8] for s in statuses]
                self.bytes_sent += sum(sum(s[7]) for s in statuses)
                self.sent = sum(s[5] for s in statuses)
                in_flight = any(b is not None for row in outboxes for b in row)
                left = sum(s[3] for s in statuses)
                advance = left == 0
                if left == 0 and not in_flight and sum(s[4] for s in statuses) == 0:
                    break  # nothing left to expand, nothing on its way
                now = time.perf_counter()
                if self.ctrl_c.hit:
                    stop = StopReason.INTERRUPTED
                elif deadline is not None and now >= deadline:
                    stop = StopReason.MAX_SECONDS
                elif opts.max_memory_mb is not None and self._memory_mb() >= opts.max_memory_mb:
                    stop = StopReason.MAX_MEMORY
                if self.progress is not None and now >= next_progress:
                    next_progress = now + opts.progress_interval
                    queue = left + sum(s[4] for s in statuses)
                    self.progress(Progress(states, arcs, queue, now - self.t0, self._memory_mb()))
        except KeyboardInterrupt:
            stop = StopReason.INTERRUPTED
        if any(b is not None for row in inboxes for b in row):
            # the batches on their way: their states are stored (unexpanded) and their arcs recorded
            statuses, _ = transport.step(0, False, inboxes)
            self.sent = sum(s[5] for s in statuses)
        t_search = time.perf_counter()
        parts = [pickle.loads(b) for b in transport.collect()]
        t_collect = time.perf_counter()
        g, predicate_state = self._assemble(parts, stop)
        t_assemble = time.perf_counter()
        levels = max((lv for part in parts for lv in (part["level"][i] for i in part["expanded"])), default=0)
        if predicate_state is not None:
            stop = StopReason.PREDICATE
        seconds = time.perf_counter() - self.t0
        if self.progress is not None:
            self.progress(Progress(g.n_states, g.n_arcs, g.n_states - g.expanded, seconds, self._memory_mb()))
        where = "Ray actors" if opts.ray is not None else "worker processes"
        where = where if n > 1 else where.replace("processes", "process").replace("actors", "actor")
        notes = [f"the search ran in {n} {where}, the states partitioned by a hash of each state"]
        return Exploration(engine=self.engine, graph=g, options=opts, stop_reason=stop, seconds=seconds,
                           peak_memory_mb=peak_rss_mb() + sum(self.rss), predicate_state=predicate_state,
                           levels=levels, notes=notes, backend=Backend(self.transport.name),
                           partition={"workers": n, "successors_sent": self.sent, "bytes_sent": self.bytes_sent,
                                      "worker_states": [len(p["states"]) for p in parts],
                                      "worker_cpu_seconds": [round(c, 3) for c in self.cpu],
                                      "seconds": {"start": round(self.t_started - self.t0, 3),
                                                  "search": round(t_search - self.t_started, 3),
                                                  "collect": round(t_collect - t_search, 3),
                                                  "assemble": round(t_assemble - t_collect, 3)}})

    def _assemble(self, parts: list[dict], stop: StopReason) -> tuple[StateGraph, int | None]:
        """The graph of the workers' parts, numbered breadth-first in this process's engine."""
        transfer = self.transfer
        # order: expanded states by (level, worker, arrival), then the unexpanded ones the same way
        expanded_flags = []
        for part in parts:
            flags = bytearray(len(part["states"]))
            for sid in part["expanded"]:
                flags[sid] = 1
            expanded_flags.append(flags)
        order = []
        for done in (1, 0):
            keyed = []
            for w, part in enumerate(parts):
                level, flags = part["level"], expanded_flags[w]
                keyed += [(level[i], w, i) for i in range(len(flags)) if flags[i] == done]
            keyed.sort()
            order += [(w, i) for _lv, w, i in keyed]
        gid = [array("q", bytes(8 * len(p["states"]))) for p in parts]
        for j, (w, i) in enumerate(order):
            gid[w][i] = j
        # binding elements of every worker in this engine
        bemap = [array("i", [transfer.import_binding_element(key) for key in part["be_keys"]]) for part in parts]
        # every worker's place ids in this engine
        maps = [[array("q", transfer.import_place_keys(p, ks)) for p, ks in enumerate(part["keys"])]
                for part in parts]
        g = StateGraph()
        first = order[0]
        s0 = tuple(map(getitem, maps[first[0]], parts[first[0]]["states"][first[1]]))
        g.store = new_store(s0, packed=self.options.packed_states)
        tail = [(0, tuple(map(getitem, maps[w], parts[w]["states"][i]))) for w, i in order[1:]]
        g.store.add_successors(tail, array("i"))
        if len(g.store) != len(order):
            raise RuntimeError("two workers stored the same state (the partition is not a function of the "
                               "marking)")
        tail = None
        # the arcs of each worker's e-th expanded state start at starts[w][e] in its arrays
        starts = []
        for part in parts:
            st, total = array("q"), 0
            for d in part["degree"]:
                st.append(total)
                total += d
            starts.append(st)

        def source(w: int, pos: int) -> tuple[int, int]:
            """(the expanded state's index in worker w's expansion order, its local id) of arc `pos` of w."""
            e = bisect_right(starts[w], pos) - 1
            return e, parts[w]["expanded"][e]

        # parents: the arc that found each state
        parent, parent_be = array("i"), array("i")
        for w, i in order:
            part = parts[w]
            pw = part["parent_w"][i]
            if pw < 0:
                parent.append(-1)
                parent_be.append(-1)
            else:
                pos = part["parent_pos"][i]
                parent.append(gid[pw][source(pw, pos)[1]])
                parent_be.append(bemap[pw][parts[pw]["bes"][pos]])
        g.parent, g.parent_be = parent, parent_be
        # arcs: global offsets from the degrees, in the global order of the expanded states
        n_expanded = sum(len(p["expanded"]) for p in parts)
        degree = array("q", bytes(8 * n_expanded))
        for w, part in enumerate(parts):
            gw = gid[w]
            for sid, d in zip(part["expanded"], part["degree"]):
                degree[gw[sid]] = d
        offsets = array("q", [0]) * (n_expanded + 1)
        total = 0
        for j in range(n_expanded):
            total += degree[j]
            offsets[j + 1] = total
        dst = array("i", bytes(4 * total))
        bes = array("i", bytes(4 * total))
        for w, part in enumerate(parts):
            gw, bm, pdst, pbes = gid[w], bemap[w], part["dst"], part["bes"]
            for e, sid in enumerate(part["expanded"]):
                lo, d = starts[w][e], part["degree"][e]
                g0 = offsets[gw[sid]]
                dst[g0:g0 + d] = array("i", [gw[x] if x >= 0 else -1 for x in pdst[lo:lo + d]])
                bes[g0:g0 + d] = array("i", [bm[b] for b in pbes[lo:lo + d]])
        # the arcs into another worker's states, as that worker recorded them
        for d, part in enumerate(parts):
            gd = gid[d]
            for w, pos, j in zip(part["in_w"], part["in_pos"], part["in_dst"]):
                e, sid = source(w, pos)
                dst[offsets[gid[w][sid]] + pos - starts[w][e]] = gd[j]
        if total and min(dst) < 0:
            raise RuntimeError("an arc's destination was not received from the worker owning it")
        g.offsets, g.dst = offsets, dst
        g.bes = array("H", bes) if not bes or max(bes) < 1 << 16 else bes
        g.store.finish()
        return g, observe(self.options, g, stop)


def _budget(states_left: int, arcs_left: int, expanded: int, arcs: int, n: int) -> int:
    """States each worker may expand in the next step: STEP_STATES, fewer near a states or arcs limit
    (estimated from the arcs per expanded state so far) so that the search stops close to it."""
    per_state = arcs / expanded if expanded else 1.0
    room = min(states_left, arcs_left) / max(per_state, 1.0) / n
    return max(1, min(STEP_STATES, int(room)))


__all__ = ["CtrlC", "LocalWorkers", "PartitionWorker", "STEP_STATES", "WorkerFailed", "run_partitioned"]
