"""`cpn-verify check`: exit statuses, positioned errors, reports, JUnit, SARIF, baseline."""

import json
import os

import pytest

from cpn.cli.main import main
from tests.checks._nets import COUNTER, LOOP
from tests.cli._schemas import check_junit, check_sarif

HOLDS = """
[[property]]
name = "one token"
kind = "invariant"
expr = "size (C'P 1) = 1"
"""
VIOLATED = HOLDS + """
[[property]]
name = "never two"
kind = "invariant"
expr = "C'P 1 <> (1`2)"
"""


def write(tmp_path, name, body, model=COUNTER):
    (tmp_path / "c.cpnet").write_text(model, encoding="utf-8")
    path = tmp_path / name
    path.write_text('model = "c.cpnet"\n' + body, encoding="utf-8")
    return str(path)


def run(args, tmp_path, capsys):
    code = main(["check", "--reports", str(tmp_path / "reports"), *args])
    out, err = capsys.readouterr()
    return code, out, err


def test_exit_statuses(tmp_path, capsys):
    assert run([write(tmp_path, "ok.toml", HOLDS)], tmp_path, capsys)[0] == 0
    assert run([write(tmp_path, "bad.toml", VIOLATED)], tmp_path, capsys)[0] == 1
    code, out, err = run([write(tmp_path, "partial.toml", HOLDS), "--max-states", "2"], tmp_path, capsys)
    assert code == 2 and "unknown" in out
    assert run([str(tmp_path / "missing.toml")], tmp_path, capsys)[0] == 64
    assert run([write(tmp_path, "x.toml", HOLDS), "--max-states", "0"], tmp_path, capsys)[0] == 64


def test_a_violation_prints_the_shortest_trace_at_the_property_line(tmp_path, capsys):
    code, out, _ = run([write(tmp_path, "bad.toml", VIOLATED)], tmp_path, capsys)
    assert code == 1
    assert "bad.toml:10:8: violated:" in out  # the 'kind' line of the second property
    assert "  1. @0  C'Inc 1: {n=0}" in out and "  2. @0  C'Inc 1: {n=1}" in out and "3. @0" not in out
    assert "C'P 1  - 1`1" in out and "C'P 1  + 1`2" in out


@pytest.mark.parametrize("body, where, code", [
    ("[explore]\nmax_state = 3\n", ":3:1: error[E0702]", "unknown exploration option"),
    ('[[property]]\nkind = "invarant"\n', ":3:8: error[E0702]", "Did you mean 'invariant'"),
    ('[[property]]\nkind = "invariant"\nexpr = "size (C\'Q 1) = 1"\n', ":4:15: error[E0703]", "no place 'C'Q' in the net"),
    ('[[property]]\nkind = "invariant"\nexpr = """\nsize (C\'P 1)\n  = true"""\n', ":6:5: error[E0301]",
     "type mismatch"),
    ('[[property]]\nkind = "invariant"\nexpr = "size (C\'P 1) = "\n', ":4:", "error[E0101]"),
    ('[[property]]\nkind = "invariant"\nexpr = "size (C\'P 7) = 1"\n', ":4:19: error[E0703]", "no instance 7"),
    ('[[property]]\nkind = "bound"\nplace = "C\'P 2"\nupper = 1\n', ":4:10: error[E0703]", "Did you mean"),
    ('[[property]]\nkind = "dead_transitions"\nexpected = ["C\'Inc 1", "C\'Dec 1"]\n', ":4:25: error[E0703]",
     "no transition instance"),
    ("[[property]\nkind = 1\n", ":2:", "error[E0701]: not valid TOML"),
    ('[parameters]\nN = "1..x"\n', ":3:5: error[E0704]", "inclusive range"),
    ('[[parameters]]\nN = 1\n[[parameters]]\nM = 2\n', ":4:3: error[E0704]", "the first row sets N"),
    ('[[property]]\nkind = "ctl"\nformula = "AG (List.all (fn x => AF x) [true])"\n', ":4:", "error[E0702]"),
    ('[[property]]\nkind = "invariant"\nexpr = "enabled \\"C\'Dec 1\\""\n', ":4:17: error[E0703]",
     "no transition instance or binding element"),
])
def test_malformed_scenarios_give_positioned_errors_and_exit_65(tmp_path, capsys, body, where, code):
    path = write(tmp_path, "bad.toml", body)
    status, out, err = run([path], tmp_path, capsys)
    assert status == 65, err
    assert f"{path}{where}" in err, err
    assert code in err
    assert "Traceback" not in err


def test_a_missing_model_is_an_error_at_the_model_line(tmp_path, capsys):
    path = tmp_path / "m.toml"
    path.write_text('name = "m"\nmodel = "nowhere.cpnet"\n', encoding="utf-8")
    code, _, err = run([str(path)], tmp_path, capsys)
    assert code == 65 and f"{path}:2:9: error[E0702]: no model file 'nowhere.cpnet'" in err


def test_a_property_that_fails_in_a_marking_is_an_error_with_exit_65(tmp_path, capsys):
    body = '[[property]]\nname = "div"\nkind = "invariant"\nexpr = "10 div (2 - size (C\'P 1) - 1) >= 0"\n'
    code, out, err = run([write(tmp_path, "e.toml", body)], tmp_path, capsys)
    assert code == 65
    assert "error: e: 'div' (invariant): evaluating" in out


def test_parameter_rows(tmp_path, capsys):
    model = COUNTER.replace("colset N = int with 0..3;", "val M = 3;\ncolset N = int with 0..M;").replace(
        "[n < 3]", "[n < M]")
    body = ('[[parameters]]\nM = 2\n[[parameters]]\nM = 1\n'
            '[[property]]\nname = "top"\nkind = "bound"\nexpr = "ms_to_col (C\'P 1)"\nupper = "M"\n')
    code, out, _ = run([write(tmp_path, "rows.toml", body, model=model), "--no-timings"], tmp_path, capsys)
    assert code == 0
    assert [line.split()[:2] for line in out.splitlines()[1:3]] == [["rows[M=2]", "3"], ["rows[M=1]", "2"]]


def test_reports_junit_sarif_and_trace_json(tmp_path, capsys):
    spec = write(tmp_path, "bad.toml", VIOLATED)
    (tmp_path / "out").mkdir()
    junit, sarif = tmp_path / "out" / "junit.xml", tmp_path / "out" / "check.sarif"
    code, out, _ = run([spec, "--junit", str(junit), "--sarif", str(sarif), "--trace-format", "json"], tmp_path,
                       capsys)
    assert code == 1
    lines = [json.loads(x) for x in out.splitlines() if x.startswith("{")]
    assert [s["binding_element"] for s in lines[0]["steps"]] == ["C'Inc 1: {n=0}", "C'Inc 1: {n=1}"]
    assert lines[0]["steps"][1]["consumed"] == {"C'P 1": "1`1"}
    assert check_junit(junit.read_text(encoding="utf-8")) == []
    assert "<failure" in junit.read_text(encoding="utf-8")
    log = json.loads(sarif.read_text(encoding="utf-8"))
    assert check_sarif(log) == []
    # 'one token' holds by the net's structure: a warning of rule cpn/W0703 beside the violation
    (res,) = [r for r in log["runs"][0]["results"] if r["ruleId"] != "cpn/W0703"]
    assert res["locations"][0]["physicalLocation"]["region"] == {"startLine": 10, "startColumn": 8}
    reports = sorted(os.listdir(tmp_path / "reports"))
    assert reports == ["bad.json", "bad.md", "bad.txt"]
    doc = json.loads((tmp_path / "reports" / "bad.json").read_text(encoding="utf-8"))
    assert doc["verdict"] == "violated" and doc["statespace"]["states"] == 4


def test_schema_checks_reject_bad_documents():
    assert check_junit('<testsuites><testsuite name="a" tests="2"><testcase name="x"/></testsuite></testsuites>')
    assert check_junit('<testsuites><testsuite name="a" tests="1"><testcase/></testsuite></testsuites>')
    assert check_sarif({"version": "2.1.0", "runs": [{"tool": {"driver": {}}}]})
    assert check_sarif({"version": "2.1.0", "runs": [{"tool": {"driver": {"name": "x"}},
                                                      "results": [{"message": {"text": "m"}, "level": "bad"}]}]})
    assert check_sarif({"version": "2.1.0", "runs": [], "extra": 1})


def test_deterministic_output(tmp_path, capsys):
    spec = write(tmp_path, "bad.toml", VIOLATED)
    first = run([spec, "--no-timings"], tmp_path, capsys)
    r1 = (tmp_path / "reports" / "bad.json").read_text(encoding="utf-8")
    second = run([spec, "--no-timings"], tmp_path, capsys)
    assert first == second
    assert r1 == (tmp_path / "reports" / "bad.json").read_text(encoding="utf-8")


def test_baseline_names_the_property_that_broke(tmp_path, capsys):
    spec = write(tmp_path, "gate.toml", VIOLATED.replace("(1`2)", "(1`7)"))
    assert run([spec], tmp_path, capsys)[0] == 0
    os.rename(tmp_path / "reports", tmp_path / "before")
    spec = write(tmp_path, "gate.toml", VIOLATED)
    code, out, _ = run([spec, "--baseline", str(tmp_path / "before")], tmp_path, capsys)
    assert code == 1
    assert "REGRESSION gate: 'never two' holds -> violated" in out
    assert "1 property broke; changes since the baseline" in out


def test_parameter_table_expands_to_one_run_per_row(tmp_path, capsys):
    model = COUNTER.replace("colset N = int with 0..3;", "val M = 3;\ncolset N = int with 0..M;").replace(
        "[n < 3]", "[n < M]")
    body = '[parameters]\nM = 1..3  # bare\n[[property]]\nname = "top"\nkind = "reachable"\nexpr = "C\'P 1 = (1`M)"\n'
    code, out, _ = run([write(tmp_path, "p.toml", body, model=model), "--no-timings"], tmp_path, capsys)
    assert code == 0
    assert [line.split()[0] for line in out.splitlines()[1:4]] == ["p[M=1]", "p[M=2]", "p[M=3]"]
    assert sorted(os.listdir(tmp_path / "reports"))[:3] == ["p-M=1.json", "p-M=1.md", "p-M=1.txt"]


def test_a_livelock_prints_a_lasso(tmp_path, capsys):
    body = '[[property]]\nname = "no spin"\nkind = "no_livelock"\nprogress = ["L\'Go"]\n'
    code, out, _ = run([write(tmp_path, "l.toml", body, model=LOOP)], tmp_path, capsys)
    assert code == 1
    assert "then forever, the cycle back to marking 1:" in out and "L'Spin 1: {}" in out
    # the token Spin takes from A and puts back is shown as consumed and produced
    assert "L'A 1  - 1`()" in out and "L'A 1  + 1`()" in out


def test_a_value_the_model_does_not_declare_is_an_error_in_the_scenario(tmp_path, capsys):
    path = write(tmp_path, "v.toml", "[set]\nNN = 3\n")
    code, _, err = run([path], tmp_path, capsys)
    assert code == 65
    assert f"{path}:3:6: error[E0305]: the value of 'NN': the model has no constant 'val NN'" in err


def test_stop_at_first_violation_from_the_command_line(tmp_path, capsys):
    spec = write(tmp_path, "bad.toml", VIOLATED)
    code, out, _ = run([spec, "--stop-at-first-violation", "--no-timings"], tmp_path, capsys)
    assert code == 1
    doc = json.loads((tmp_path / "reports" / "bad.json").read_text(encoding="utf-8"))
    assert doc["statespace"]["complete"] is False and doc["statespace"]["stop_reason"] == "predicate"
    assert [p["verdict"] for p in doc["properties"]] == ["unknown", "violated"]


def test_outputs_are_checked_before_any_work(tmp_path, capsys):
    spec = write(tmp_path, "ok.toml", HOLDS)
    code, out, err = run([spec, "--junit", str(tmp_path / "missing" / "j.xml")], tmp_path, capsys)
    assert code == 73 and "does not exist" in err and not out
    code, out, _ = run([spec, "--sarif", "-", "--no-timings"], tmp_path, capsys)
    assert code == 0 and json.loads(out)["version"] == "2.1.0"  # the SARIF alone on standard output


def test_expected_violations_pass_the_gate_and_missed_ones_fail_it(tmp_path, capsys):
    caught = VIOLATED + 'expect = "violated"\n'
    code, out, _ = run([write(tmp_path, "mutant.toml", caught), "--no-timings"], tmp_path, capsys)
    assert code == 0
    assert "1 violated (expected), 1 holds" in out
    missed = HOLDS + 'expect = "violated"\n'
    junit = tmp_path / "j.xml"
    code, out, _ = run([write(tmp_path, "missed.toml", missed), "--junit", str(junit)], tmp_path, capsys)
    assert code == 1
    assert "holds (expected violated)" in out
    text = junit.read_text(encoding="utf-8")
    assert check_junit(text) == [] and "no longer caught" in text
    code, _, err = run([write(tmp_path, "bad.toml", HOLDS + 'expect = "fails"\n')], tmp_path, capsys)
    assert code == 65 and ":7:10: error[E0702]: 'expect' must be" in err
