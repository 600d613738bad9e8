"""The partitioned search on a Ray cluster (`--ray [ADDRESS]`): the workers of `cpn.statespace.parallel`
as Ray actors, one per CPU of the cluster unless `--workers` says otherwise.

Each step of a worker returns its batches as separate objects of Ray's object store, and the coordinator
hands each batch's reference to the worker it is for: the batches go from worker to worker (through the
object store of their machines), and the coordinator only reads the small status of every worker. Ray is
an optional dependency (`pip install 'cpn-verify[ray]'`); every machine of the cluster needs cpn-verify
installed (docs/scaling.md).

`address`: "local" starts a Ray instance on this machine for this search (stopped after it); "auto"
connects to the cluster started on this machine with `ray start --head`; anything else is the address of
a cluster's head (host:port). A Ray already initialised in this process is used as it is.
"""

from __future__ import annotations

from cpn.errors import ConfigurationError
from cpn.statespace.options import Backend
from cpn.statespace.parallel import PartitionWorker, WorkerFailed


def ray_unavailable() -> str | None:
    """Why Ray cannot be used here (None if it can)."""
    try:
        import ray  # noqa: F401
    except ImportError:
        return "Ray is not installed"
    return None


class _RayWorker:
    """A `PartitionWorker` as a Ray actor: a step returns its status and one object per batch."""

    def __init__(self, net_blob: bytes, time_condensation: bool, me: int, n: int):
        self.worker = PartitionWorker(net_blob, time_condensation, me, n)

    def seed(self, c):
        self.worker.seed(c)

    def step(self, budget: int, advance: bool, *inboxes):
        status, batches = self.worker.step(budget, advance, inboxes)
        return (status, *batches)

    def collect(self) -> bytes:
        return self.worker.collect()


class RayWorkers:
    """The transport of the partitioned search over Ray actors (see the module)."""

    name = Backend.RAY

    def __init__(self, n: int | None, net_blob: bytes, time_condensation: bool, address: str):
        why = ray_unavailable()
        if why is not None:
            raise ConfigurationError(f"{why}: the search on a Ray cluster needs it",
                                     hint="pip install 'cpn-verify[ray]'")
        import ray

        self.ray = ray
        self.started = False
        if not ray.is_initialized():
            try:
                if address == "local":
                    ray.init(include_dashboard=False, log_to_driver=False, configure_logging=False)
                    self.started = True
                else:
                    ray.init(address=address, log_to_driver=False, configure_logging=False)
            except (ConnectionError, RuntimeError, ValueError) as exc:
                raise ConfigurationError(f"cannot connect to the Ray cluster at '{address}': {exc}",
                                         hint="start it with 'ray start --head' (then --ray auto) or name "
                                              "its head as --ray HOST:PORT") from None
        cpus = max(1, int(ray.cluster_resources().get("CPU", 1)))
        self.n = n = n or cpus
        actor = ray.remote(_RayWorker).options(num_cpus=min(1.0, cpus / n))
        self.actors = [actor.remote(net_blob, time_condensation, w, n) for w in range(n)]

    def _get(self, refs):
        try:
            return self.ray.get(refs)
        except self.ray.exceptions.RayError as exc:
            cause = getattr(exc, "cause", None) or exc
            raise WorkerFailed(str(cause).splitlines()[0] if str(cause) else type(cause).__name__) from None

    def call(self, w: int, name: str, *args):
        return self._get(getattr(self.actors[w], name).remote(*args))

    def step(self, budget: int, advance: bool, inboxes: list[list]) -> tuple[list, list]:
        """One step of every worker: (their statuses, outboxes[w][d] the reference of w's batch for d)."""
        n = self.n
        statuses, outboxes = [], []
        for w, a in enumerate(self.actors):
            refs = a.step.options(num_returns=n + 1).remote(budget, advance, *inboxes[w])
            statuses.append(refs[0])
            outboxes.append(list(refs[1:]))
        statuses = self._get(statuses)
        # a batch that would be empty is still a reference: the sizes in the statuses say which are
        return statuses, [[b if w != d and statuses[w][7][d] else None for d, b in enumerate(row)]
                          for w, row in enumerate(outboxes)]

    def collect(self) -> list[bytes]:
        return self._get([a.collect.remote() for a in self.actors])

    def close(self) -> None:
        for a in getattr(self, "actors", []):
            try:
                self.ray.kill(a)
            except Exception:  # noqa: BLE001 - an actor already gone
                pass
        self.actors = []
        if self.started:
            self.ray.shutdown()
