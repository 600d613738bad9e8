"""reports/modbus/ holds what `cpn-verify check specs/modbus --no-timings --reports
reports/modbus` writes (a scenario and a mutant are re-checked here; the rest by the same command)."""

import os
import subprocess
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


@pytest.mark.parametrize("spec,stem", [("specs/modbus/A_1.toml", "A.1"),
                                       ("specs/modbus/mutants/ma_E3_ack_lost_same.toml", "Modbus-A-E3-same")])
def test_committed_reports_are_what_check_writes(tmp_path, spec, stem):
    r = subprocess.run([sys.executable, "-m", "cpn", "check", spec, "--no-timings", "-q", "--reports", str(tmp_path)],
                       cwd=ROOT, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    for ext in ("txt", "json", "md"):
        with open(os.path.join(ROOT, "reports", "modbus", f"{stem}.{ext}"), encoding="utf-8") as fh:
            committed = fh.read()
        assert (tmp_path / f"{stem}.{ext}").read_text(encoding="utf-8") == committed, ext


def test_every_scenario_has_its_committed_reports():
    names = os.listdir(os.path.join(ROOT, "reports", "modbus"))
    assert len([n for n in names if n.endswith(".json")]) == 100  # 76 MODBUS and Modbus-A runs, 24 MODBUS/TCP
    assert {n.rsplit(".", 1)[1] for n in names} == {"txt", "json", "md"}


def test_committed_reports_name_files_relative_to_the_repository():
    """The reports are the same in every clone: no absolute path of the machine that wrote them."""
    folder = os.path.join(ROOT, "reports", "modbus")
    for name in os.listdir(folder):
        with open(os.path.join(folder, name), encoding="utf-8") as fh:
            text = fh.read()
        assert ROOT not in text and '"model": "/' not in text, name


@pytest.mark.parametrize("image,args", [
    ("scaling_B.svg", ["--after", "## Scenario B beyond 8 slaves", "--param", "NS", "--states", "states",
                       "with a broadcast: states", "--seconds", "s", "with a broadcast: s"]),
    ("scaling_modbus_a.svg", ["--after", "## Modbus-A beyond 8 slaves", "--param", "N"]),
])
def test_scaling_images_are_drawn_from_the_tables_beside_them(tmp_path, image, args):
    out = tmp_path / image
    r = subprocess.run([sys.executable, os.path.join("bench", "scaling_plot.py"), os.path.join("reports", "README.md"),
                        *args, "-o", str(out)], cwd=ROOT, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with open(os.path.join(ROOT, "reports", image), encoding="utf-8") as fh:
        assert out.read_text(encoding="utf-8") == fh.read()
    with open(os.path.join(ROOT, "reports", "README.md"), encoding="utf-8") as fh:
        assert f"]({image})" in fh.read()
