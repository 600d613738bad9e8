"""MODBUS/TCP with a gateway to the serial line (models/modbus/modbus_tcp.cpnet): the model uses the serial
line's modules of modbus.cpnet instead of copying them, the TCP property set holds on small
configurations, decided on the quotient by the symmetry of clients and servers with the full graph's
counts, and each mutant of specs/modbus/mutants/tcp_*.toml is caught by the property written for it,
with a shortest counterexample."""

import importlib.util
import os
import subprocess
import sys

import pytest

import cpn
from cpn.checks.verdict import Status
from cpn.gate.run import run_scenario
from cpn.gate.scenario import load_scenario
from tests._graphs import bfs_distances

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MODEL = os.path.join(ROOT, "models", "modbus", "modbus_tcp.cpnet")
SPECS = os.path.join(ROOT, "specs", "modbus")
_spec = importlib.util.spec_from_file_location("bench_modbus_tcp", os.path.join(ROOT, "bench", "modbus_tcp.py"))
bench = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(bench)
NAMES = {key: name for key, name, _, _ in bench.PROPERTIES}
SMALL = {"LATE": "([] : INT list)", "TPROC": "[1]"}


def test_model_runs_tcp_clients_against_the_serial_slaves_of_modbus_cpnet():
    m = cpn.load(MODEL, set={**SMALL, "NC": 3, "NSV": 2})
    instances = [pi.decl.name for pi in m.net.instances if pi.decl is not None]
    assert instances == ["Client1", "Client2", "Client3", "Server1", "Server2", "Stack", "Gateway", "Bus",
                         "Slave1", "Slave2"]
    # the serial modules are modbus.cpnet's own (used, not copied): their transitions point into that file
    serial = [t for t in m.net.transitions if t.name.split("'")[0] in ("Bus", "Slave")]
    assert serial and {os.path.basename(t.span.file) for t in serial} == {"modbus.cpnet"}
    with open(MODEL, encoding="utf-8") as fh:
        text = fh.read()
    assert 'use "modbus.cpnet";' in text and "module Slave" not in text and "module Bus" not in text


def _run(path, row=0, **explore):
    scenario = load_scenario(path)
    return run_scenario(scenario, scenario.runs[row], explore or None)


@pytest.mark.parametrize("spec, row", [("tcp.toml", 0), ("tcp_gateway.toml", 0), ("tcp_mixed.toml", 1)])
def test_the_tcp_properties_hold_on_a_small_configuration(spec, row):
    result = _run(os.path.join(SPECS, spec), row)
    assert result.exploration.complete
    verdicts = {r.spec.name: r.verdict.status for r in result.results}
    assert set(verdicts.values()) == {Status.HOLDS}, verdicts
    for key in ("tid-connection", "depth", "no-loss", "eventually", "gw-codes"):
        assert verdicts[NAMES[key]] is Status.HOLDS


def test_contradictory_writes_are_a_finding_shown_as_a_trace():
    result = _run(os.path.join(SPECS, "tcp.toml"), 0)
    (finding,) = [r for r in result.results if r.spec.name == NAMES["contradictory-writes"]]
    assert finding.spec.kind == "reachable" and finding.verdict.status is Status.HOLDS
    witness = finding.verdict.evidence
    assert witness is not None and witness.path[0] == 0 and len(witness.path) > 1


def test_symmetry_quotient_decides_every_property_with_the_full_graph_counts():
    path = os.path.join(SPECS, "tcp.toml")
    full = _run(path, 3)   # NC = 2, NSV = 2: two clients, two servers
    quotient = _run(path, 3, reduction="symmetry")
    g_full, g_quot = full.exploration.graph, quotient.exploration.graph
    assert g_quot.n_states < g_full.n_states
    stats = quotient.exploration.reduction_stats   # the orbit sizes add up to the full graph
    assert (stats["full_states"], stats["full_arcs"]) == (g_full.n_states, g_full.n_arcs)
    options = quotient.exploration.options
    assert options.reduction == "symmetry"
    assert {r.spec.name: r.verdict.status for r in quotient.results} == \
        {r.spec.name: r.verdict.status for r in full.results}
    assert all(r.verdict.status is Status.HOLDS for r in quotient.results)


def test_every_tcp_mutant_has_its_file_and_the_files_are_what_the_bench_writes():
    files = sorted(f for f in os.listdir(os.path.join(SPECS, "mutants")) if f.startswith("tcp_"))
    assert files == sorted(m.replace("-", "_") + ".toml" for m, _, _, _ in bench.MUTANTS)
    assert len(files) >= 10
    for fname, name, description, sets, rows, skip in bench.SCENARIOS:
        with open(os.path.join(SPECS, fname), encoding="utf-8") as fh:
            assert fh.read() == bench.scenario_text(name, description, sets, rows, skip), fname


@pytest.mark.parametrize("mutant, sets, broken", [(m, s, b) for m, _, s, b in bench.MUTANTS],
                         ids=[m for m, *_ in bench.MUTANTS])
def test_each_tcp_mutant_is_caught_by_the_property_written_for_it(mutant, sets, broken):
    result = _run(os.path.join(SPECS, "mutants", mutant.replace("-", "_") + ".toml"))
    assert result.exploration.complete
    violated = {r.spec.name for r in result.results if r.verdict.status is Status.VIOLATED}
    assert NAMES[broken[0]] in violated
    assert violated == {NAMES[k] for k in broken}   # what the file marks, and nothing else
    assert result.status is Status.HOLDS            # the gate passes: the bug is caught
    dist = None
    for r in result.results:
        if r.verdict.status is not Status.VIOLATED or r.spec.kind == "reachable":
            continue
        ev = r.verdict.evidence
        assert ev is not None and ev.path[0] == 0, r.spec.name
        if r.spec.kind in ("invariant", "bound"):   # decided on the fly: the shortest trace to a bad marking
            dist = dist or bfs_distances(result.exploration.graph)
            assert len(ev.path) - 1 == dist[ev.path[-1]], r.spec.name


@pytest.mark.parametrize("mutant", [m for m, *_ in bench.MUTANTS])
def test_the_nominal_model_breaks_none_of_the_properties_on_a_mutant_configuration(mutant):
    """The mutant's configuration with TMUTANT = "none": every property holds, so each violation above is
    the bug's."""
    scenario = load_scenario(os.path.join(SPECS, "mutants", mutant.replace("-", "_") + ".toml"))
    run = scenario.runs[0]
    nominal = type(run)(run.name + " nominal", run.params, {**run.values, "TMUTANT": '"none"'})
    result = run_scenario(scenario, nominal)
    assert {r.verdict.status for r in result.results} == {Status.HOLDS}, mutant


def test_committed_tcp_reports_are_what_check_writes(tmp_path):
    r = subprocess.run([sys.executable, "-m", "cpn", "check", "specs/modbus/tcp_gateway.toml", "--no-timings", "-q",
                        "--reports", str(tmp_path)], cwd=ROOT, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    written = sorted(os.listdir(tmp_path))
    assert len(written) == 12   # four runs, three reports each
    for name in written:
        with open(os.path.join(ROOT, "reports", "modbus", name), encoding="utf-8") as fh:
            assert (tmp_path / name).read_text(encoding="utf-8") == fh.read(), name
