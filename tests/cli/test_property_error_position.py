"""A property text that raises in a reachable marking is reported at the text that raised (its `expr`,
`formula`, ... value), not at the property's `kind` line: that is where the user must change it."""

import json

from cpn.cli.main import main

NET = """net T;
colset U = unit;
place Bus : U = 1`();
place Other : U;
trans Go;
arc Bus -> Go;
arc Go -> Other;
"""

SPEC = """model = "m.cpnet"
[[property]]
name = "p"
kind = "invariant"
description = "the text divides by zero"
expr = "size (T'Bus 1) div 0 = 0"
"""


def _spec(tmp_path) -> str:
    (tmp_path / "m.cpnet").write_text(NET, encoding="utf-8")
    path = tmp_path / "s.toml"
    path.write_text(SPEC, encoding="utf-8")
    return str(path)


def test_the_error_is_printed_at_the_expr_line(tmp_path, capsys):
    assert main(["check", _spec(tmp_path), "--no-reports"]) == 65
    out, err = capsys.readouterr()
    assert "s.toml:6:8: error:" in out and "s.toml:4:" not in out
    assert "division by zero" in out and "Traceback" not in out + err


def test_the_json_report_carries_the_expr_position(tmp_path):
    assert main(["check", _spec(tmp_path), "--reports", str(tmp_path / "r"), "--quiet"]) == 65
    (report,) = (tmp_path / "r").glob("*.json")
    (p,) = json.loads(report.read_text(encoding="utf-8"))["properties"]
    assert (p["verdict"], p["line"], p["column"]) == ("error", 6, 8)


def test_the_sweep_line_search_reports_the_expr_position_too(tmp_path, capsys):
    args = ["check", _spec(tmp_path), "--no-reports", "--progress", "size (T'Other 1)"]
    assert main(args) == 65
    assert "s.toml:6:8: error:" in capsys.readouterr().out
