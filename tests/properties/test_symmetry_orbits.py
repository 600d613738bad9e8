"""Under symmetry, an `invariant` or `reachable` property whose text names one module instance (or tells
the symmetric values apart) is decided through the orbits of the quotient's representatives, and gets
the verdict of the unreduced state space (random nets with one module instance per value, and a
client/lock net)."""

from __future__ import annotations

import random
import re

import pytest

from cpn.checks.verdict import Status
from cpn.gate.run import run_scenario
from cpn.gate.scenario import loads_scenario
from tests.statespace._instance_nets import random_instance_net
from tests.statespace.test_statespace_instance_symmetry import CLIENTS


def _verdicts(tmp_path, model: str, props: list[tuple[str, str]], symmetry: str | None) -> dict:
    (tmp_path / "m.cpnet").write_text(model, encoding="utf-8")
    head = 'model = "m.cpnet"\n[explore]\nmax_states = 5000\n' + (f'symmetry = ["{symmetry}"]\n' if symmetry else "")
    body = "".join(f'[[property]]\nname = "p{k}"\nkind = "{kind}"\nexpr = "{text}"\n'
                   for k, (kind, text) in enumerate(props))
    s = loads_scenario(head + body, str(tmp_path / "s.toml"))
    r = run_scenario(s, s.runs[0])
    return r, {p.spec.name: p.verdict for p in r.results}


def test_one_client_in_its_critical_section(tmp_path):
    props = [("invariant", "size (Client'Crit 1) + size (Client'Crit 2) <= 1"),
             ("reachable", "size (Client'Crit 2) = 1"),
             ("invariant", "size (Client'Crit 3) = 0"),
             ("reachable", "size (Client'Crit 1) = 1 andalso size (Client'Wait 3) = 1"),
             ("reachable", "size (Client'Crit 1) = 1 andalso size (Client'Crit 3) = 1")]
    full, want = _verdicts(tmp_path, CLIENTS, props, None)
    quot, got = _verdicts(tmp_path, CLIENTS, props, "C")
    assert quot.exploration.n_states < full.exploration.n_states  # really reduced
    assert [v.status for v in want.values()] == [Status.HOLDS, Status.HOLDS, Status.VIOLATED, Status.HOLDS,
                                                 Status.VIOLATED]
    assert {n: v.status for n, v in got.items()} == {n: v.status for n, v in want.items()}
    # the images tested are the full graph's markings
    assert f"{full.exploration.n_states:,} markings" in got["p0"].message
    assert got["p2"].evidence is not None and "orbit" in got["p2"].message


def _module_places(net: str) -> tuple[str, list[str], int]:
    module = re.search(r"module (\w+)\(", net).group(1)
    body = net[net.index(f"module {module}("):]
    body = body[:body.index("}")]
    places = re.findall(r"^\s*place (\w+) :", body, re.M)
    instances = len(re.findall(rf"= {module}\(", net))
    return module, places, instances


@pytest.mark.parametrize("seed", range(12))
def test_random_instance_nets_agree_with_the_full_graph(tmp_path, seed):
    net = random_instance_net(seed)
    module, places, instances = _module_places(net)
    if not places:
        pytest.skip("no place inside the module")
    rng = random.Random(seed)
    props = []
    for _ in range(6):
        p, i, k = rng.choice(places), rng.randint(1, instances), rng.randint(0, 2)
        props.append((rng.choice(["invariant", "reachable"]),
                      rng.choice([f"size ({module}'{p} {i}) <= {k}", f"size ({module}'{p} {i}) >= {k}"])))
    full, want = _verdicts(tmp_path, net, props, None)
    if not full.exploration.complete:
        pytest.skip("more than 5,000 markings")
    quot, got = _verdicts(tmp_path, net, props, "S")
    for name, v in want.items():
        assert got[name].status is v.status, (name, props, got[name].message)
        assert got[name].status is not Status.UNKNOWN
