"""The MODBUS model's slaves are one family of instances over 1..MAXS (`instance Slave[i : 1..MAXS]`):
the same instances Slave1..Slave16 as the declarations written out before, and as many as MAXS says
(specs/modbus/B_32_slaves.toml: scenario B with 32 slaves)."""

import os
import re

import cpn
from cpn.gate.scenario import load_scenario

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MODEL = os.path.join(ROOT, "models", "modbus", "modbus.cpnet")


def _slaves(model):
    return [pi.decl.name for pi in model.net.instances if pi.page == "Slave"]


def test_the_slaves_are_one_family_over_maxs():
    with open(MODEL, encoding="utf-8") as fh:
        text = fh.read()
    assert re.findall(r"^instance Slave\S*", text, re.M) == ["instance Slave[i"]
    model = cpn.load(MODEL)
    assert _slaves(model) == [f"Slave{k}" for k in range(1, 17)]
    # slave k is the module's instance k, with me = k
    assert {(t.instance, tuple(t.params.values())) for t in model.net.transitions if t.page == "Slave"} == \
        {(k, (k,)) for k in range(1, 17)}
    assert _slaves(cpn.load(MODEL, set={"MAXS": "32"})) == [f"Slave{k}" for k in range(1, 33)]


def test_the_32_slave_scenario_has_32_slaves_and_the_family_properties():
    scenario = load_scenario(os.path.join(ROOT, "specs", "modbus", "B_32_slaves.toml"))
    (run,) = scenario.runs
    assert str(run.values["NS"]) == str(run.values["MAXS"]) == "32"
    (p1,) = [p for p in scenario.properties if "every slave is in one state" in p.name]
    assert "Slave'Idle 32" in p1.fields["expr"] and "Slave'Idle 33" not in p1.fields["expr"]
