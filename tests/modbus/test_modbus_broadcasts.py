"""Broadcasts that do something, and properties that are protocol rules (MODBUS models).

A broadcast write is processed by every slave in a thesis scenario of every family, so the turnaround
delay and t2 protect something; the SuperSlave's window comes from the tw its super-request carries;
SS-P3 is a timing property on a stopwatch the properties read, not on the SuperSlave's own window.
Every scenario file carries the property set of its family; the properties that hold by the net's
structure are labelled; the dead paths a file states follow from its configuration.
"""

import importlib.util
import os
import re
import tomllib

import pytest

from cpn.checks.verdict import Status
from cpn.gate.run import run_scenario
from cpn.gate.scenario import load_scenario

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SPECS = os.path.join(ROOT, "specs", "modbus")
MODEL = os.path.join(ROOT, "models", "modbus", "modbus.cpnet")
_spec = importlib.util.spec_from_file_location("bench_modbus", os.path.join(ROOT, "bench", "modbus.py"))
bench = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(bench)

FAMILY_FILES = {n: stem for n, stem, _ in bench.SCENARIOS} | {n: stem for n, stem, _, _ in bench.EXTRAS}


def _run(stem, **values):
    scenario = load_scenario(os.path.join(SPECS, stem + ".toml"))
    base = scenario.runs[0]
    run = type(base)(base.name, base.params, {**base.values, **values})
    result = run_scenario(scenario, run)
    assert result.exploration.complete
    return result


def _violated(result):
    return {r.spec.name.split(" ")[0].rstrip(":") for r in result.results
            if r.verdict.status is Status.VIOLATED and bench.STRUCTURAL not in r.spec.name}


def _toml(stem):
    with open(os.path.join(SPECS, stem + ".toml"), "rb") as fh:
        return tomllib.load(fh)


@pytest.mark.parametrize("family", "ABCD")
def test_every_family_has_a_thesis_scenario_whose_slaves_all_process_a_broadcast_write(family):
    stems = [stem for n, stem, sets in bench.SCENARIOS if n[0] == family and bench._broadcast_writes(sets)]
    assert stems, family
    result = _run(stems[0])
    (prop,) = [r for r in result.results if r.spec.name.startswith("S-P4 (where a broadcast write is sent)")]
    assert prop.verdict.status is Status.HOLDS  # a marking with every slave processing it is reachable
    assert result.status is Status.HOLDS


def test_a_broadcast_write_is_a_write_code_every_slave_accepts():
    for _, _, sets in bench.SCENARIOS:
        for i in bench._broadcast_writes(sets):
            a, c, _, _ = bench._frames(sets)[i - 1]
            assert a == 0 and c in (5, 6, 15, 16)
    # without the write codes in the slaves, the same frame is dropped by every slave (01)
    a2 = dict(bench.SCENARIOS[1][2])
    assert bench._broadcast_writes(a2) == [1]
    assert bench._broadcast_writes({k: v for k, v in a2.items() if k != "WFCS"}) == []


def test_the_turnaround_protects_the_broadcast_write():
    # a 1 ms turnaround lets the next request reach a slave still processing the broadcast write (S-P10)
    assert "S-P10" in _violated(_run("A_2", MUTANT='"short-turnaround"'))
    assert "S-P10" in _violated(_run("C_1", MUTANT='"short-turnaround"'))


def _slave_module(text):
    start = text.index("module Slave(")
    return text[start:text.index("(* ====", start)]


def test_tw_travels_in_the_super_request():
    with open(MODEL, encoding="utf-8") as fh:
        text = fh.read()
    slave = re.sub(r"\(\*.*?\*\)", "", _slave_module(text), flags=re.S)
    assert not re.search(r"\bTW\b", slave)  # the SuperSlave reads no window constant ...
    assert "#tw f" in slave                  # ... but the window its request carries


def test_ss_p3_is_stated_on_times_not_on_the_window_token():
    (ss_p3,) = [p for p in _toml("D_2")["property"] if p["name"].startswith("SS-P3")]
    assert "Window" not in ss_p3["expr"] and "SuperStarts" in ss_p3["expr"]
    assert "SS-P3" not in _violated(_run("D_2"))


@pytest.mark.parametrize("mutant", ["super-window-long", "late-super"])
def test_ss_p3_catches_a_broadcast_after_receipt_plus_tw(mutant):
    assert "SS-P3" in _violated(_run("D_2", MUTANT=f'"{mutant}"'))


def test_bcast_reply_is_caught_by_thesis_scenarios_of_two_families():
    families = set()
    for stem in ("A_2", "D_3"):
        if _violated(_run(stem, MUTANT='"bcast-reply"')):
            families.add(stem[0])
    assert families == {"A", "D"}
    assert os.path.exists(os.path.join(SPECS, "mutants", "bcast-reply.toml"))


def _family_core(props):
    """The property names of a file without those that depend on its frames (conditional and dead facts)."""
    return sorted(p["name"] for p in props
                  if not p["name"].startswith(bench.DEAD) and "(where " not in p["name"]
                  and not p["name"].startswith("S-P6: a frame for the absent address"))


def test_every_scenario_file_carries_the_property_set_of_its_family():
    by_family = {}
    for name, stem in FAMILY_FILES.items():
        by_family.setdefault(name[0], []).append((stem, _family_core(_toml(stem)["property"])))
    for family, files in by_family.items():
        (first_stem, first), *rest = files
        for stem, core in rest:
            assert core == first, (family, first_stem, stem)


def test_structural_properties_are_labelled_and_say_why():
    for stem in FAMILY_FILES.values():
        props = _toml(stem)["property"]
        labelled = [p for p in props if bench.STRUCTURAL in p["name"]]
        assert {p["name"].split(" ")[0] for p in labelled} == {"S-P1", "S-P9"}, stem
        assert all("not counted as verification" in p["description"] for p in labelled)
    # every property check finds to follow from the net's structure carries the label
    result = _run("A_1")
    warned = [r.spec.name for r in result.results if any("structure" in w for w in r.warnings)]
    assert warned and all(bench.STRUCTURAL in n for n in warned)


def test_dead_paths_are_protocol_facts_of_the_configuration():
    a1 = dict(bench.SCENARIOS[0][2])
    facts = {f for f, _ in bench._dead_facts(a1)}
    assert any(f.startswith("no broadcast in the frames") for f in facts)
    assert any(f.startswith("no super-request") for f in facts)
    # the same configuration with a broadcast in its frames states no such fact: derived, not a snapshot
    with_bcast = {f for f, _ in bench._dead_facts({**a1, "ADRS": "[0,3,5]"})}
    assert not any(f.startswith("no broadcast in the frames") for f in with_bcast)
    d2 = {f for f, _ in bench._dead_facts(dict(bench.SCENARIOS[14][2]))}
    assert not any(f.startswith("no super-request") for f in d2)
    # each file states exactly the facts of its configuration, and they hold
    for name, stem, sets in bench.SCENARIOS:
        stated = {p["name"] for p in _toml(stem)["property"] if p["name"].startswith(bench.DEAD)}
        assert stated == {f"{bench.DEAD} {f}" for f, _ in bench._dead_facts({**bench.DEFAULTS, **sets})}, name


def test_a_dead_fact_catches_a_path_the_configuration_excludes():
    # A.3's broadcasts are read codes: a slave that processes one breaks the fact (and S-P4)
    broken = {r.spec.name for r in _run("A_3", MUTANT='"bcast-any-code"').results
              if r.verdict.status is Status.VIOLATED}
    assert any(n.startswith(bench.DEAD) and "no slave processes a broadcast" in n for n in broken)
