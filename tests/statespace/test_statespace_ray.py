"""The partitioned search on Ray: actors on a local Ray instance (2 CPUs, no dashboard,
started once for this module) give the same state space and report as one process."""

from __future__ import annotations

import os

import pytest

import cpn
from cpn.cli.main import main
from cpn.statespace import ExploreOptions, Explorer, StopReason
from tests._shared import ROOT, SHARED, needs_shared
from tests.statespace._partition import compare

ray = pytest.importorskip("ray", reason="Ray is not installed (pip install 'cpn-verify[ray]')")


@pytest.fixture(scope="module", autouse=True)
def local_ray():
    started = not ray.is_initialized()
    if started:
        ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False, configure_logging=False)
    yield
    if started:
        ray.shutdown()


MODELS = ["bench/nets/dp.cpnet:5", "bench/nets/ms.cpnet:3", "models/examples/broadcast.cpnet",
          "models/examples/stations.cpnet"]


@pytest.mark.parametrize("spec", MODELS)
def test_repository_models_on_ray_have_the_same_state_space(spec):
    path, _, n = spec.partition(":")
    compare(cpn.load(os.path.join(ROOT, path), set={"N": n} if n else None), workers=(2,), ray="local")


@needs_shared
def test_a_corpus_model_on_ray():
    folder = os.path.join(SHARED, "validation", "CSRepetitions-COL-02")
    if not os.path.isdir(folder):
        pytest.skip(f"no validation corpus at {folder}")
    got = compare(cpn.load(os.path.join(folder, "model.pnml")), workers=(2,), ray="local")
    assert got["stop"] is StopReason.COMPLETE


def test_ray_without_workers_uses_the_cluster_cpus_and_a_limit_stops_it():
    model = cpn.load(os.path.join(ROOT, "bench/nets/ms.cpnet"), set={"N": "4"})
    x = Explorer(model.engine(), ExploreOptions(ray="local", max_states=400)).run()
    assert x.backend == "ray" and x.partition["workers"] == 2
    assert x.stop_reason is StopReason.MAX_STATES and 400 <= x.n_states < 3321 and x.unexpanded > 0
    assert x.partition["bytes_sent"] > 0 and x.partition["successors_sent"] > 0


def test_explore_and_check_with_ray_on_the_command_line(tmp_path, capsys):
    dp = os.path.join(ROOT, "bench", "nets", "dp.cpnet")
    assert main(["explore", dp, "--set", "N=5", "--ray", "--workers", "2"]) == 0
    out = capsys.readouterr()
    assert "Nodes:  82" in out.out and "the search ran in 2 Ray actors" in out.err
    spec = os.path.join(ROOT, "specs", "examples", "dp.toml")
    assert main(["check", spec, "--ray", "--no-reports", "--no-timings"]) == 0
    assert "holds" in capsys.readouterr().out
