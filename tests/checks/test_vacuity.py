"""Vacuity: properties that hold for a reason that says nothing about the protocol are warned about in
check's output, its JSON reports, JUnit and SARIF; the verdicts and the exit status stay the same."""

import json
import pathlib

import cpn
from cpn.cli.main import main

HERE = pathlib.Path(__file__).parent / "vacuity"
RING = str(HERE / "ring.toml")


def warnings_by_property():
    (result,) = cpn.check(RING)
    assert result.status.value == "holds"
    return {r.spec.name: r.warnings for r in result.results}


def test_which_properties_hold_vacuously():
    w = warnings_by_property()
    assert w["dead markings at 0"] == ["holds vacuously: there is no dead marking, so its predicate is never tested"]
    premise = ("holds vacuously: the premise 'size (Ring'P 1) = 2' of its implication is true in no reachable "
               "marking")
    assert w["never two"] == [premise]  # not P orelse Q
    assert w["if two"] == [premise]  # if P then Q else true
    assert w["one at three"] == []  # its premise holds in one marking
    assert w["three"] == []  # AF p: p cannot be replaced by false
    # the response comes whatever the request: AG (not P orelse AF Q) holds with P replaced by true
    assert w["two leads to three"] == ["holds vacuously in 'not (Ring'P 1 = (1`2))': the formula holds just as "
                                       "well with it replaced by false"]
    assert w["never reached premise"][0] == premise
    assert len(w["never reached premise"]) == 3


def test_warnings_reach_the_output_junit_and_sarif(tmp_path, capsys):
    junit, sarif = tmp_path / "j.xml", tmp_path / "s.json"
    code = main(["check", RING, "--reports", str(tmp_path / "r"), "--junit", str(junit), "--sarif", str(sarif)])
    err = capsys.readouterr().err
    assert code == 0
    assert "ring.toml:11:8: warning[W0702]: ring: 'never two' (invariant) holds vacuously: the premise" in err
    assert "ring.toml:16:8" not in err  # 'one at three'
    doc = json.loads((tmp_path / "r" / "ring.json").read_text(encoding="utf-8"))
    assert [p["name"] for p in doc["properties"] if p.get("warnings")] == [
        "dead markings at 0", "never two", "if two", "two leads to three", "never reached premise"]
    xml = junit.read_text(encoding="utf-8")
    assert xml.count("<system-out>warning[W0702]: holds vacuously") == 5 and 'failures="0"' in xml
    log = json.loads(sarif.read_text(encoding="utf-8"))
    results = log["runs"][0]["results"]
    assert {r["ruleId"] for r in results} == {"cpn/W0702"} and {r["level"] for r in results} == {"warning"}
    assert len(results) == 7
    rules = log["runs"][0]["tool"]["driver"]["rules"]
    assert all(rules[r["ruleIndex"]]["id"] == r["ruleId"] for r in results)
    assert results[1]["locations"][0]["physicalLocation"]["region"] == {"startLine": 11, "startColumn": 8}
