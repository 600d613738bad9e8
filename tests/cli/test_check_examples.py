"""The repository's scenarios hold, and the broken example of the CI guide fails readably."""

import json
import os
import pathlib

import pytest

from cpn.cli.main import main

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_every_example_scenario_holds(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(ROOT)
    code = main(["check", "specs/examples", "--reports", str(tmp_path), "--no-timings"])
    out, err = capsys.readouterr()
    assert code == 0, out + err
    assert "violated" not in out and "unknown" not in out
    runs = sorted(p.name for p in tmp_path.glob("*.json"))
    assert "stop-and-wait.json" in runs and "ms-N=3.json" in runs
    assert not any("broken" in r for r in runs)  # the broken variant is not under specs/


def test_the_broken_example_fails_with_a_readable_shortest_trace(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(ROOT)
    code = main(["check", "docs/ci/broken", "--reports", str(tmp_path), "--no-timings"])
    out, _ = capsys.readouterr()
    assert code == 1
    assert ("docs/ci/broken/stop_and_wait.toml:22:8: violated: stop-and-wait-broken: 'it only stops when every "
            "packet is acknowledged'") in out
    # the shortest trace: send packet 1, lose it; times are model times (replayed without condensation)
    assert "1. @0  StopAndWait'Send 1: {n=1}" in out
    assert "2. @2  StopAndWait'TransmitPacket 1: {n=1, ok=false}" in out
    assert "3. @" not in out.split("'it only stops")[1].split("\n\n")[0]
    doc = json.loads((tmp_path / "stop-and-wait-broken.json").read_text(encoding="utf-8"))
    verdicts = {p["name"]: p["verdict"] for p in doc["properties"]}
    assert verdicts["at most one packet and one acknowledgement in transit"] == "holds"
    assert verdicts["completion is always possible"] == "violated"


def test_the_guide_files_exist_and_run_the_gate():
    wf = (ROOT / "docs/ci/github-workflow.yml").read_text(encoding="utf-8")
    assert "cpn-verify check" in wf and "--junit" in wf and "--sarif" in wf and "--baseline" in wf
    pc = (ROOT / "docs/ci/pre-commit-config.yaml").read_text(encoding="utf-8")
    assert "cpn-verify check" in pc
    guide = (ROOT / "docs/ci-guide.md").read_text(encoding="utf-8")
    for path in ("docs/ci/github-workflow.yml", "docs/ci/pre-commit-config.yaml", "docs/ci/broken"):
        assert path in guide and os.path.exists(ROOT / path)


def test_output_does_not_depend_on_the_hash_seed(tmp_path):
    import subprocess
    import sys

    outs = []
    for seed in ("1", "2"):
        rep = tmp_path / seed
        rep.mkdir()
        res = subprocess.run([sys.executable, "-m", "cpn", "check", "docs/ci/broken", "specs/examples/stations.toml",
                              "--no-timings", "--reports", str(rep), "--sarif", str(rep / "s.sarif")],
                             cwd=ROOT, capture_output=True, text=True, env={**os.environ, "PYTHONHASHSEED": seed})
        assert res.returncode == 1
        files = {p.name: p.read_text(encoding="utf-8") for p in sorted(rep.iterdir())}
        outs.append((res.stdout, files))
    assert outs[0] == outs[1]


# the one mutant of specs/modbus/mutants/ that the gate below runs (a small one)
GATE_MUTANT = "specs/modbus/mutants/bcast-as-unicast.toml"
# scenarios the gate below does not run because another test runs each in full through the gate's own
# run_scenario and asserts the gate's verdict (no state space is searched twice in the suite): the file
# and the test that runs it
MUTANTS_TEST = ("tests/modbus/test_modbus_mutants.py", "test_mutant_is_caught_by_the_property_it_breaks")
TCP_MUTANTS_TEST = ("tests/modbus/test_modbus_tcp.py", "test_each_tcp_mutant_is_caught_by_the_property_written_for_it")
RUN_ELSEWHERE = {
    "specs/modbus/modbus_a_100.toml": ("tests/modbus/test_modbus_a_reserved_ids.py",
                                       "test_the_100_slave_scenario_holds_and_exercises_the_reserved_ids"),
    **{f"specs/modbus/{name}.toml": ("tests/statespace/test_native_timed.py",
                                     "test_modbus_scenario_checks_search_natively_with_the_python_verdicts")
       for name in ("A_1", "D_4_faults")},
}


def _run_elsewhere(spec: str):
    """The (test file, test) that runs scenario `spec` in full instead of the gate test, or None."""
    if spec in RUN_ELSEWHERE:
        return RUN_ELSEWHERE[spec]
    if "/mutants/" not in spec or spec == GATE_MUTANT:
        return None
    return TCP_MUTANTS_TEST if pathlib.Path(spec).name.startswith("tcp_") else MUTANTS_TEST


@pytest.mark.slow  # 21 s; in CI, the installation check runs the gate as the README's main command
def test_the_repository_gate_passes(tmp_path, capsys, monkeypatch):
    # `check` with no argument finds every scenario under specs/ (examples, MODBUS, Modbus-A) and every
    # mutant; every scenario holds, and each mutant's bug is caught. It runs them all but those another test
    # runs in full (_run_elsewhere; test_the_scenarios_the_gate_test_leaves_out_are_run_elsewhere)
    from cpn.gate import scenario as scenarios

    monkeypatch.chdir(ROOT)
    found: list[str] = []
    every = scenarios.scenario_files

    def gate_files(paths):
        found.extend(every(paths))
        return [f for f in found if _run_elsewhere(pathlib.Path(f).as_posix()) is None]

    monkeypatch.setattr(scenarios, "scenario_files", gate_files)
    code = main(["check", "--no-reports", "--no-timings", "--quiet"])
    out, err = capsys.readouterr()
    assert code == 0, out + err
    assert "violated (expected)" in out and "(expected holds)" not in out
    on_disk = {p.relative_to(ROOT).as_posix() for p in (ROOT / "specs").rglob("*.toml")}
    assert {pathlib.Path(f).as_posix() for f in found} == on_disk and GATE_MUTANT in on_disk


def test_the_scenarios_the_gate_test_leaves_out_are_run_elsewhere():
    """Each scenario the gate test leaves out is run by the test named for it: the mutants' test runs every
    file of specs/modbus/mutants/, and each other test names its scenario file."""
    import importlib.util

    on_disk = sorted(p.relative_to(ROOT).as_posix() for p in (ROOT / "specs").rglob("*.toml"))
    left_out = {spec: _run_elsewhere(spec) for spec in on_disk if _run_elsewhere(spec) is not None}
    assert set(RUN_ELSEWHERE) <= set(left_out) and any(t == MUTANTS_TEST for t in left_out.values())
    for spec, (path, test) in left_out.items():
        text = (ROOT / path).read_text(encoding="utf-8")
        assert f"\ndef {test}(" in text, f"{path} has no {test}, which runs {spec} for the gate test"
        if (path, test) not in (MUTANTS_TEST, TCP_MUTANTS_TEST):
            assert f'"{pathlib.Path(spec).stem}' in text, f"{path} does not name {spec}"
    where = importlib.util.spec_from_file_location("mutants_test", ROOT / MUTANTS_TEST[0])
    module = importlib.util.module_from_spec(where)
    where.loader.exec_module(module)
    mutants = {spec for spec, t in left_out.items() if t == MUTANTS_TEST} | {GATE_MUTANT}
    assert {f"specs/modbus/mutants/{name}.toml" for name in module.FILES} == mutants
