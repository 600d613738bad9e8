"""The two kinds of warning a property that holds can get carry their own diagnostic code, W0702 (it holds
vacuously) and W0703 (it follows from the net's structure), in every output of `check`: standard error,
the text, Markdown and JSON reports, JUnit and SARIF. The verdicts and the exit status stay the same."""

import json

from cpn.cli.main import main
from cpn.diagnostics import CODES
from cpn.properties.vacuity import STRUCTURAL, VACUOUS, warning_code

# a job moves between Idle and Busy; the counter only grows up to 2
MODEL = """net M;
colset U = unit;
colset N = int with 0..2;
var n : N;
place Idle : U = 1`();
place Busy : U;
place Count : N = 1`0;
trans start;
arc Idle -> start : ();
arc start -> Busy : ();
trans stop;
arc Busy -> stop : ();
arc stop -> Idle : ();
trans tick [n < 2];
arc Count -> tick : n;
arc tick -> Count : n + 1;
"""

SCENARIO = """model = "m.cpnet"

[[property]]
name = "two busy jobs stop the counter"
kind = "invariant"
expr = "not (size (M'Busy 1) = 2) orelse M'Count 1 = (1`0)"

[[property]]
name = "at most one busy job"
kind = "bound"
place = "M'Busy 1"
at_most = 1

[[property]]
name = "idle or busy"
kind = "invariant"
expr = "size (M'Idle 1) = 0 orelse size (M'Busy 1) = 0"
"""

VACUOUS_NAME, STRUCTURAL_NAME, PLAIN_NAME = "two busy jobs stop the counter", "at most one busy job", "idle or busy"


def run_check(tmp_path, capsys):
    (tmp_path / "m.cpnet").write_text(MODEL, encoding="utf-8")
    spec = tmp_path / "jobs.toml"
    spec.write_text(SCENARIO, encoding="utf-8")
    out = tmp_path / "out"
    out.mkdir()
    code = main(["check", str(spec), "--no-timings", "--reports", str(out / "r"), "--junit", str(out / "j.xml"),
                 "--sarif", str(out / "s.json")])
    _, err = capsys.readouterr()
    return code, err, out


def test_the_codes_are_registered_and_told_apart():
    assert (VACUOUS, STRUCTURAL) == ("W0702", "W0703")
    assert CODES[VACUOUS] == "property holds vacuously"
    assert CODES[STRUCTURAL] == "property follows from the net's structure"
    assert warning_code("holds vacuously: there is no dead marking, so its predicate is never tested") == VACUOUS
    assert warning_code("follows from the net's structure: place invariants ...") == STRUCTURAL


def test_each_output_of_check_gives_the_code(tmp_path, capsys):
    code, err, out = run_check(tmp_path, capsys)
    assert code == 0
    # standard error, at the property's position
    assert "jobs.toml:5:8: warning[W0702]: jobs: 'two busy jobs stop the counter' (invariant) holds vacuously: " \
           "the premise 'size (M'Busy 1) = 2'" in err
    assert "jobs.toml:10:8: warning[W0703]: jobs: 'at most one busy job' (bound) follows from the net's structure" \
        in err
    assert err.count("warning[") == 2
    # the JSON report keeps the texts and their codes side by side
    doc = json.loads((out / "r" / "jobs.json").read_text(encoding="utf-8"))
    props = {p["name"]: p for p in doc["properties"]}
    assert props[VACUOUS_NAME]["warning_codes"] == ["W0702"]
    assert props[STRUCTURAL_NAME]["warning_codes"] == ["W0703"]
    assert "warnings" not in props[PLAIN_NAME] and "warning_codes" not in props[PLAIN_NAME]
    assert all(p["verdict"] == "holds" for p in doc["properties"])
    # the text report, under each property's verdict and message
    text = (out / "r" / "jobs.txt").read_text(encoding="utf-8").splitlines()
    at = next(i for i, line in enumerate(text) if VACUOUS_NAME in line)
    assert text[at + 2].strip().startswith("warning[W0702]: holds vacuously: the premise 'size (M'Busy 1) = 2'")
    at = next(i for i, line in enumerate(text) if STRUCTURAL_NAME in line)
    assert text[at + 2].strip().startswith("warning[W0703]: follows from the net's structure")
    at = next(i for i, line in enumerate(text) if PLAIN_NAME in line)
    assert not any("warning" in line for line in text[at:])
    # the Markdown report, in a section of its own after the table
    md = (out / "r" / "jobs.md").read_text(encoding="utf-8")
    section = md.split("## Warnings", 1)[1]
    assert f"- {VACUOUS_NAME} (`" in section and "jobs.toml:5:8`): warning[W0702]: holds vacuously" in section
    assert "jobs.toml:10:8`): warning[W0703]: follows from the net's structure" in section
    assert PLAIN_NAME not in section
    # JUnit: in the test case's system-out
    xml = (out / "j.xml").read_text(encoding="utf-8")
    assert xml.count("<system-out>warning[W0702]: holds vacuously") == 1
    assert xml.count("<system-out>warning[W0703]: follows from the net's structure") == 1
    assert 'failures="0"' in xml
    # SARIF: one rule per code, each result at its property's line
    log = json.loads((out / "s.json").read_text(encoding="utf-8"))
    rules = log["runs"][0]["tool"]["driver"]["rules"]
    results = log["runs"][0]["results"]
    assert sorted((r["ruleId"], r["locations"][0]["physicalLocation"]["region"]["startLine"]) for r in results) == [
        ("cpn/W0702", 5), ("cpn/W0703", 10)]
    assert all(rules[r["ruleIndex"]]["id"] == r["ruleId"] and r["level"] == "warning" for r in results)
    assert {r["properties"]["code"] for r in results} == {"W0702", "W0703"}
    assert all(r["message"]["text"].startswith(f"warning[{r['properties']['code']}]: jobs: ") for r in results)


def test_a_report_written_without_codes_gets_them_from_the_text():
    from cpn.report.verdicts import property_warnings

    old = {"warnings": ["holds vacuously: x", "follows from the net's structure: y"]}
    assert property_warnings(old) == [("W0702", "holds vacuously: x"), ("W0703", "follows from the net's structure: y")]
    assert property_warnings({}) == []


def test_the_html_page_of_a_run_lists_the_warnings_with_their_codes(tmp_path, capsys):
    (tmp_path / "m.cpnet").write_text(MODEL, encoding="utf-8")
    spec = tmp_path / "jobs.toml"
    spec.write_text(SCENARIO, encoding="utf-8")
    assert main(["check", str(spec), "--no-timings", "--no-reports", "--html", str(tmp_path / "html")]) == 0
    capsys.readouterr()
    page = next(p for p in (tmp_path / "html").iterdir() if p.name != "index.html").read_text(encoding="utf-8")
    assert f"<code>warning[W0702]</code> {VACUOUS_NAME}: holds vacuously" in page
    assert f"<code>warning[W0703]</code> {STRUCTURAL_NAME}: follows from the net&#x27;s structure" in page \
        or f"<code>warning[W0703]</code> {STRUCTURAL_NAME}: follows from the net's structure" in page
    assert PLAIN_NAME + ":" not in page.split('<ul class="warnings">')[1].split("</ul>")[0]
