"""The repository's scenarios hold, and the broken example of the CI guide fails readably (issue 10)."""

import json
import os
import pathlib

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


def test_the_repository_gate_passes(tmp_path, capsys, monkeypatch):
    # every scenario under specs/ (examples, MODBUS, Modbus-A) holds, and every mutant's bug is caught
    monkeypatch.chdir(ROOT)
    code = main(["check", "--no-reports", "--no-timings", "--quiet"])
    out, err = capsys.readouterr()
    assert code == 0, out + err
    assert "violated (expected)" in out and "(expected holds)" not in out
