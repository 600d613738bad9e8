"""`cpn-verify validate`: the table, the JSON file and the exit statuses, on a two-instance corpus."""

from __future__ import annotations

import json
import os
import shutil

from cpn.cli.main import main
from tests._shared import SHARED, needs_shared

VALIDATION = os.environ.get("CPN_VALIDATION_DIR", SHARED + "/validation")
SOURCE = os.path.join(VALIDATION, "TokenRing-PT-005", "model.pnml")

pytestmark = needs_shared


def _corpus(tmp_path, states: int, extra: list | None = None):
    os.makedirs(tmp_path / "TR")
    shutil.copy(SOURCE, tmp_path / "TR" / "model.pnml")
    inst = {"name": "TR", "format": "pnml-pt", "file": "TR/model.pnml", "states": states, "arcs": 365,
            "max_tokens_per_marking": 6, "max_tokens_in_place": 1, "deadlock_reachable": False,
            "dead_markings": 0, "mcc_global_properties": {"OneSafe": True, "Liveness": False,
                                                          "QuasiLiveness": False, "StableMarking": False}}
    (tmp_path / "expected.json").write_text(json.dumps({"instances": [inst] + (extra or [])}))
    return str(tmp_path)


def test_all_match(tmp_path, capsys):
    d = _corpus(tmp_path, 166)
    out_json = tmp_path / "r.json"
    assert main(["validate", d, "--json", str(out_json)]) == 0
    out = capsys.readouterr().out
    assert "TR" in out and "match" in out and "4/4" in out
    res = json.loads(out_json.read_text())["results"][0]
    assert res["status"] == "match" and res["found"]["states"] == 166 and res["found"]["arcs"] == 365


def test_mismatch_exits_1_and_names_the_figure(tmp_path, capsys):
    d = _corpus(tmp_path, 167)
    assert main(["validate", d]) == 1
    assert "states: expected 167, found 166" in capsys.readouterr().out


def test_partial_exits_2_and_skips_are_reported(tmp_path, capsys):
    big = {"name": "Big", "format": "pnml-pt", "file": "TR/model.pnml", "states": 10**9}
    cpn_tools = {"name": "Other", "format": "unknown-format", "file": "x", "states": 1}
    d = _corpus(tmp_path, 166, [big, cpn_tools])
    assert main(["validate", d, "--max-states", "50", "--only", "TR", "--only", "B*"]) == 2
    assert main(["validate", d, "--only", "TR", "--only", "Big", "--skip-larger-than", "1000"]) == 0
    out = capsys.readouterr().out
    assert "partial" in out and "skipped" in out and "Other" not in out


def test_broken_model_is_an_error_row(tmp_path, capsys):
    bad = {"name": "Bad", "format": "pnml-pt", "file": "bad.pnml", "states": 1}
    d = _corpus(tmp_path, 166, [bad])
    (tmp_path / "bad.pnml").write_text("<pnml><net")
    assert main(["validate", d, "--only", "Bad"]) == 1
    assert "E0501" in capsys.readouterr().out


def test_bad_usage(tmp_path):
    assert main(["validate", str(tmp_path)]) == 64
    d = _corpus(tmp_path, 166)
    assert main(["validate", d, "--only", "nothing"]) == 64
