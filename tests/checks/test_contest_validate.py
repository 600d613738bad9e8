"""`cpn-verify validate` compares every formula verdict with the contest's published ones (oracle.json)."""

from __future__ import annotations

import json
import os
import shutil

from cpn.cli.main import main
from tests._shared import SHARED, needs_shared

VALIDATION = os.environ.get("CPN_VALIDATION_DIR", SHARED + "/validation")
NAME = "ERK-PT-000001"  # 13 states: the whole comparison takes a second

pytestmark = needs_shared


def _corpus(tmp_path, flip: str | None = None) -> str:
    with open(os.path.join(VALIDATION, "expected.json"), encoding="utf-8") as fh:
        inst = next(i for i in json.load(fh)["instances"] if i["name"] == NAME)
    shutil.copytree(os.path.join(VALIDATION, NAME), tmp_path / NAME)
    (tmp_path / "expected.json").write_text(json.dumps({"instances": [inst]}))
    if flip:
        path = tmp_path / NAME / "formulas" / "oracle.json"
        doc = json.loads(path.read_text())
        exam = flip.rsplit("-", 2)[1]
        old = doc["verdicts"][exam][flip]
        doc["verdicts"][exam][flip] = {"TRUE": "FALSE", "FALSE": "TRUE"}.get(old, old + 1 if isinstance(old, int) else old)
        path.write_text(json.dumps(doc))
    return str(tmp_path)


def test_every_formula_agrees_and_the_totals_are_per_examination(tmp_path, capsys):
    d = _corpus(tmp_path)
    out_json = tmp_path / "r.json"
    assert main(["validate", d, "--json", str(out_json)]) == 0
    out = capsys.readouterr().out
    assert "formulas: 112 agree, 0 disagree, 0 unknown" in out
    assert "at most 300 s per instance" in out  # the time limit is stated
    doc = json.loads(out_json.read_text())
    totals = doc["formula_totals"]
    assert totals["total"] == {"agree": 112, "disagree": 0, "unknown": 0}
    assert all(totals[e]["agree"] == 16 for e in totals if e != "total") and len(totals) == 8
    res = doc["results"][0]
    assert set(res["examination_ratio"]) == set(totals) - {"total"}
    assert all(f["states"] <= 13 for f in res["formulas"])  # no formula generates more than the state space


def test_a_verdict_that_differs_is_reported_and_fails(tmp_path, capsys):
    d = _corpus(tmp_path, flip=f"{NAME}-LTLFireability-03")
    assert main(["validate", d]) == 1
    out = capsys.readouterr().out
    assert "formulas: 111 agree, 1 disagree" in out and f"disagree: {NAME}-LTLFireability-03: published" in out


def test_a_time_limit_leaves_formulas_unknown(tmp_path, capsys):
    d = _corpus(tmp_path)
    assert main(["validate", d, "--formula-max-states", "2"]) == 2
    assert "unknown" in capsys.readouterr().out
    assert main(["validate", d, "--no-formulas"]) == 0
    assert "formulas:" not in capsys.readouterr().out
