"""`cpn-verify explore` on real .cpnet models: exit statuses, JSON, and independence from the hash seed."""

import json
import os
import subprocess
import sys

import pytest

from cpn.cli.main import main

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
MODELS = os.path.join(ROOT, "tests", "statespace", "models")
NETS = os.path.join(ROOT, "bench", "nets")


def test_explore_dp_complete(capsys, tmp_path):
    out = tmp_path / "dp.json"
    assert main(["explore", os.path.join(NETS, "dp.cpnet"), "--set", "N=5", "--json", str(out)]) == 0
    text = capsys.readouterr().out
    assert "     Nodes:  82\n     Arcs:   265\n" in text and "Status: Full" in text
    assert "Shortest trace to dead marking" in text
    d = json.loads(out.read_text())
    assert d["statespace"]["states"] == 82 and d["dead_markings"]["count"] == 1
    assert d["options"]["set"] == {"N": "5"}


def test_explore_partial_exit_2(capsys):
    assert main(["explore", os.path.join(MODELS, "counter.cpnet"), "--max-states", "25", "--quiet"]) == 2
    captured = capsys.readouterr()
    assert "Status: Partial" in captured.out
    assert "24 unexpanded" not in captured.out and "1 unexpanded node)" in captured.out


def test_explore_time_growth_exit_2_with_hint(capsys):
    assert main(["explore", os.path.join(MODELS, "ticker.cpnet")]) == 2
    err = capsys.readouterr().err
    assert "--time-condensation" in err
    assert main(["explore", os.path.join(MODELS, "ticker.cpnet"), "--time-condensation"]) == 0
    assert "time condensation: on" in capsys.readouterr().out


def test_explore_bad_model_65(tmp_path, capsys):
    bad = tmp_path / "bad.cpnet"
    bad.write_text("colset U = unit;\nplace P : Phil;\n")
    assert main(["explore", str(bad)]) == 65
    assert "bad.cpnet:2:" in capsys.readouterr().err


def _json_with_seed(seed: str, model: str, *args: str) -> dict:
    code = ("import sys; from cpn.cli.main import main; "
            f"sys.exit(main(['explore', {model!r}, '--json', '-', *{list(args)!r}]))")
    env = dict(os.environ, PYTHONHASHSEED=seed)
    p = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 0, p.stderr
    d = json.loads(p.stdout)
    for k in ("seconds", "peak_memory_mb"):
        d["statespace"].pop(k)
    d["scc"].pop("seconds")
    d.pop("report_seconds")
    d.pop("report_part_seconds")
    return d


@pytest.mark.parametrize("model,args", [("register.cpnet", ()), ("timed_merge.cpnet", ())])
def test_results_do_not_depend_on_hash_seed(model, args):
    path = os.path.join(MODELS, model)
    assert _json_with_seed("1", path, *args) == _json_with_seed("12345", path, *args)


def test_ms_results_do_not_depend_on_hash_seed():
    path = os.path.join(NETS, "ms.cpnet")
    a = _json_with_seed("3", path, "--set", "N=2")
    b = _json_with_seed("4", path, "--set", "N=2")
    assert a == b and a["statespace"]["states"] > 0
