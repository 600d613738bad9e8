"""`cpn-verify lint` and `simulate`: exit statuses and output."""

import glob
import os
import subprocess
import sys

import pytest

from cpn.cli.main import main

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(__file__)))
MODELS = [os.path.join(ROOT, "models", "examples", n) for n in ("stations.cpnet", "stop_and_wait.cpnet")]
MODELS += [os.path.join(ROOT, "bench", "nets", n) for n in ("dp.cpnet", "ms.cpnet")]


def test_lint_clean_models(capsys):
    assert main(["lint", *MODELS]) == 0
    assert "ok (9 place instances" in capsys.readouterr().out


def test_lint_bad_model(tmp_path, capsys):
    bad = tmp_path / "bad.cpnet"
    bad.write_text("colset C = int;\nvar x : D;\nplace P : C\nplace Q : C;\n")
    assert main(["lint", str(bad)]) == 65
    err = capsys.readouterr().err
    assert "bad.cpnet:4:1: error[E0101]" in err
    assert "Traceback" not in err


def test_missing_file_is_a_usage_error(capsys):
    assert main(["lint", "no/such/file.cpnet"]) == 64


def test_bad_usage():
    assert main(["simulate"]) == 64
    assert main(["frobnicate"]) == 64


ALL_MODELS = sorted(glob.glob(os.path.join(ROOT, "**", "*.cpnet"), recursive=True))
# models that stop with an evaluation error on purpose
FAILING = {"div_zero.cpnet", "uncaught.cpnet"}


@pytest.mark.parametrize("path", ALL_MODELS, ids=lambda p: os.path.relpath(p, ROOT))
def test_simulate_every_model_of_the_repository(path, capsys):
    status = main(["simulate", path, "--steps", "15", "--seed", "3"])
    assert status == (65 if os.path.basename(path) in FAILING else 0), capsys.readouterr().err


def test_simulate_is_reproducible(capsys):
    main(["simulate", MODELS[1], "--steps", "30", "--seed", "7"])
    a = capsys.readouterr().out
    main(["simulate", MODELS[1], "--steps", "30", "--seed", "7"])
    assert capsys.readouterr().out == a


def test_simulate_set_overrides_a_val(capsys):
    assert main(["simulate", MODELS[3], "--set", "N=2", "--steps", "0", "--show-marking"]) == 0
    assert "MS'SIdle 1: 1`1++1`2" in capsys.readouterr().out


def test_evaluation_error_while_simulating(tmp_path, capsys):
    m = tmp_path / "div.cpnet"
    m.write_text("colset C = int with 0..3;\nvar x : C;\nplace P : C = 1`0;\ntrans t [10 div x > 1];\n"
                 "arc P -> t : x;\n")
    assert main(["simulate", str(m)]) == 65
    err = capsys.readouterr().err
    assert "div.cpnet:4:10: error[E0401]" in err and "x=0" in err


def test_console_script_runs():
    out = subprocess.run([sys.executable, "-m", "cpn", "lint", MODELS[0]], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
