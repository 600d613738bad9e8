"""The `check` gate never passes what it has not proven: a reader that leaves early, report folders
checked before any work, unique report names, a scenario that checks nothing, `--quiet`, `--set`, and
the default time limit of a run."""

import json
import os
import re
import subprocess
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# a counter that counts to LIMIT; "never HALF" is violated after HALF steps, so its trace is long
LONG = """net C;
val LIMIT = 400;
colset N = int with 0..LIMIT;
var n : N;
place P : N = 1`0;
trans Inc [n < LIMIT];
arc P -> Inc : n;
arc Inc -> P : n + 1;
"""


def scenario(folder, name="s.toml", body="", model=LONG, head=""):
    """Write `c.cpnet` and a scenario naming it in `folder`; returns the scenario's path."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "c.cpnet").write_text(model, encoding="utf-8")
    path = folder / name
    path.write_text(head + 'model = "c.cpnet"\n' + body, encoding="utf-8")
    return str(path)


def prop(name, expr, kind="invariant"):
    return f'[[property]]\nname = "{name}"\nkind = "{kind}"\nexpr = "{expr}"\n'


# five violated invariants, each with a trace of 200 steps or more: far more than a pipe's buffer
VIOLATIONS = "".join(prop(f"never {k}", f"C'P 1 <> (1`{k})") for k in (200, 210, 220, 230, 240))


def cli(*args, cwd=None, stdout=subprocess.PIPE, stderr=subprocess.PIPE, close=()):
    """Run `cpn-verify` in a subprocess; the pipes named in `close` lose their reader at once."""
    p = subprocess.Popen([sys.executable, "-m", "cpn", *args], cwd=cwd, stdout=stdout, stderr=stderr,
                         stdin=subprocess.DEVNULL, text=True)
    for name in close:
        getattr(p, name).close()  # nobody reads it any more: every write to it fails with EPIPE
    out = p.stdout.read() if p.stdout and "stdout" not in close else ""
    err = p.stderr.read() if p.stderr and "stderr" not in close else ""
    p.wait(timeout=300)
    return p.returncode, out, err


# ---------------------------------------------------------------- a reader that goes away early


def test_a_closed_standard_output_keeps_the_verdict_of_check(tmp_path):
    spec = scenario(tmp_path, body=VIOLATIONS)
    code, _, err = cli("check", "--no-reports", spec, close=("stdout",))
    assert code == 1, err
    assert "Traceback" not in err and "BrokenPipe" not in err


def test_a_closed_standard_output_after_some_lines_keeps_the_verdict(tmp_path):
    spec = scenario(tmp_path, body=VIOLATIONS)
    p = subprocess.Popen([sys.executable, "-m", "cpn", "check", "--no-reports", spec], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, stdin=subprocess.DEVNULL, text=True)
    first = [p.stdout.readline() for _ in range(3)]  # `| head -n 3`
    p.stdout.close()
    err = p.stderr.read()
    assert p.wait(timeout=300) == 1, err
    assert "violated" in first[0]


def test_a_closed_standard_error_keeps_the_status_of_a_bad_model(tmp_path):
    bad = tmp_path / "bad.cpnet"
    bad.write_text("colset C = int;\nplace P : D;\n" * 200, encoding="utf-8")
    for command in ("lint", "explore"):
        code, _, _ = cli(command, str(bad), close=("stderr",))
        assert code == 65, command


def test_a_closed_standard_output_keeps_the_status_of_explore_and_lint(tmp_path):
    model = tmp_path / "c.cpnet"
    model.write_text(LONG, encoding="utf-8")
    code, _, err = cli("explore", str(model), "--max-listed", "0", close=("stdout",))
    assert code == 0 and "Traceback" not in err
    code, _, err = cli("explore", str(model), "--max-states", "5", close=("stdout",))
    assert code == 2 and "Traceback" not in err
    code, _, err = cli("lint", str(model), close=("stdout",))
    assert code == 0 and "Traceback" not in err


# ---------------------------------------------------------------- in-process runs


def check(*args, capsys):
    from cpn.cli.main import main

    code = main(["check", *args])
    out, err = capsys.readouterr()
    return code, out, err


def report(folder, stem):
    return json.loads((folder / f"{stem}.json").read_text(encoding="utf-8"))


SMALL = LONG.replace("val LIMIT = 400;", "val LIMIT = 3;")
HOLDS = prop("below four", "size (C'P 1) = 1")
BROKEN = prop("never two", "C'P 1 <> (1`2)")


# ---------------------------------------------------------------- report folders, checked before any work


def test_a_reports_path_that_is_a_file_is_refused_before_any_work(tmp_path, capsys):
    spec = scenario(tmp_path, body=HOLDS, model=SMALL)
    (tmp_path / "taken").write_text("x", encoding="utf-8")
    for where in (tmp_path / "taken", tmp_path / "taken" / "sub"):
        code, out, err = check(spec, "--reports", str(where), capsys=capsys)
        assert code == 73, err
        assert f"cannot write --reports {where}" in err and "Traceback" not in err
        assert out == ""  # no run started: no summary


def test_the_default_reports_folder_in_a_read_only_working_directory(tmp_path):
    spec = scenario(tmp_path, body=HOLDS, model=SMALL)
    if os.access("/proc", os.W_OK) and not os.path.exists("/proc/self"):
        pytest.skip("no read-only /proc here")
    code, out, err = cli("check", spec, cwd="/proc")
    assert code == 73, err
    assert "cannot write --reports reports" in err and "--no-reports" in err and "Traceback" not in err
    assert out == ""


# ---------------------------------------------------------------- unique report names


def test_two_scenarios_with_the_same_file_name_get_their_own_reports(tmp_path, capsys):
    scenario(tmp_path / "specs" / "fieldbus", "basic.toml", BROKEN, model=SMALL)
    scenario(tmp_path / "specs" / "modbus", "basic.toml", HOLDS, model=SMALL)
    reports = tmp_path / "reports"
    code, out, err = check(str(tmp_path / "specs"), "--reports", str(reports), "--no-timings", capsys=capsys)
    assert code == 1, err
    assert sorted(p.name for p in reports.glob("*.json")) == ["fieldbus-basic.json", "modbus-basic.json"]
    assert report(reports, "fieldbus-basic")["verdict"] == "violated"
    assert report(reports, "modbus-basic")["verdict"] == "holds"
    assert [line.split()[0] for line in out.splitlines() if line.endswith("holds") or "violated  1" in line] == [
        "fieldbus/basic", "modbus/basic"]


def test_the_baseline_pairs_runs_of_the_same_file_name_correctly(tmp_path, capsys):
    a = scenario(tmp_path / "specs" / "a", "basic.toml", HOLDS, model=SMALL)
    scenario(tmp_path / "specs" / "b", "basic.toml", HOLDS, model=SMALL)
    before, after = tmp_path / "before", tmp_path / "after"
    assert check(str(tmp_path / "specs"), "--reports", str(before), capsys=capsys)[0] == 0
    scenario(tmp_path / "specs" / "a", "basic.toml", HOLDS + BROKEN, model=SMALL)
    code, out, _ = check(str(tmp_path / "specs"), "--reports", str(after), "--baseline", str(before), capsys=capsys)
    assert code == 1
    assert "a/basic: new property 'never two' is violated" in out
    assert "b/basic" not in out.split("changes since the baseline")[1]
    assert a  # the scenario that changed is the one the baseline names


def test_a_name_given_twice_is_refused_at_its_line(tmp_path, capsys):
    first = scenario(tmp_path / "one", "x.toml", HOLDS, model=SMALL, head='name = "gate"\n')
    second = scenario(tmp_path / "two", "y.toml", BROKEN, model=SMALL, head='# the same name\nname = "gate"\n')
    reports = tmp_path / "reports"
    code, out, err = check(first, second, "--reports", str(reports), capsys=capsys)
    assert code == 65, err
    assert f"{second}:2:8: error[E0702]: the run 'gate' would write the reports of the run 'gate' of {first}" in err
    assert "Give each scenario its own name" in err
    assert report(reports, "gate")["file"] == first  # the first one ran; nothing overwrote its reports


def test_a_baseline_with_two_reports_of_one_run_name_compares_neither(tmp_path, capsys):
    spec = scenario(tmp_path, "gate.toml", HOLDS, model=SMALL)
    before = tmp_path / "before"
    assert check(spec, "--reports", str(before), capsys=capsys)[0] == 0
    doc = report(before, "gate")
    (before / "copy.json").write_text(json.dumps({**doc, "verdict": "violated"}), encoding="utf-8")
    code, out, _ = check(spec, "--no-reports", "--baseline", str(before), capsys=capsys)
    assert code == 0
    assert "gate: not compared: the baseline holds 2 reports of a run of this name (copy.json, gate.json)" in out


# ---------------------------------------------------------------- a gate that checks nothing


def test_a_scenario_without_properties_is_warned_about_and_counted(tmp_path, capsys):
    empty = scenario(tmp_path, "empty.toml", "", model=SMALL)
    code, out, err = check(empty, "--no-reports", "--no-timings", capsys=capsys)
    assert code == 0
    assert f"{empty}:1:1: warning[W0701]: the scenario states no property" in err
    row = next(line for line in out.splitlines() if line.startswith("empty "))
    assert row.endswith("holds    no property")
    assert "1 run checked no property, the scenario states none: empty" in out


def test_a_missing_baseline_folder_is_bad_usage_before_any_work(tmp_path, capsys):
    spec = scenario(tmp_path, body=HOLDS, model=SMALL)
    for missing in (tmp_path / "nowhere", tmp_path / "c.cpnet"):
        code, out, err = check(spec, "--reports", str(tmp_path / "r"), "--baseline", str(missing), capsys=capsys)
        assert code == 64, err
        assert f"--baseline {missing}: " in err and "hint: name the --reports folder" in err and out == ""
        assert not (tmp_path / "r").exists()


# ---------------------------------------------------------------- --quiet keeps the results


def test_quiet_keeps_the_position_and_the_trace_of_a_violation(tmp_path, capsys):
    spec = scenario(tmp_path, body=BROKEN, model=SMALL)
    code, out, _ = check(spec, "--quiet", "--no-reports", capsys=capsys)
    assert code == 1
    assert f"{os.path.relpath(spec)}:4:8: violated: s: 'never two' (invariant)" in out
    assert "1. @0  C'Inc 1: {n=0}" in out and "2. @0  C'Inc 1: {n=1}" in out


def test_the_documented_pre_commit_hook_says_where_and_why(tmp_path, capsys, monkeypatch):
    hook = open(os.path.join(ROOT, "docs", "ci", "pre-commit-config.yaml"), encoding="utf-8").read()
    entry = re.search(r"^\s*entry:\s*(.+)$", hook, re.MULTILINE).group(1).split()
    assert entry[:2] == ["cpn-verify", "check"]
    scenario(tmp_path / "specs", "gate.toml", BROKEN, model=SMALL)
    monkeypatch.chdir(tmp_path)  # pre-commit runs a hook from the repository's root
    code, out, err = check(*entry[2:], capsys=capsys)
    assert code == 1, err
    assert "specs/gate.toml:4:8: violated: gate: 'never two'" in out and "2. @0  C'Inc 1: {n=1}" in out
    assert not (tmp_path / "reports").exists()


# ---------------------------------------------------------------- --set


def test_set_overrides_a_constant_and_the_reports_say_so(tmp_path, capsys):
    spec = scenario(tmp_path, body=HOLDS, model=SMALL)
    reports = tmp_path / "reports"
    code, out, err = check(spec, "--reports", str(reports), "--set", "LIMIT=7", "--no-timings", capsys=capsys)
    assert code == 0, err
    doc = report(reports, "s-LIMIT=7")
    assert doc["run"] == "s[LIMIT=7]" and doc["statespace"]["states"] == 8  # 4 with the model's LIMIT = 3
    assert doc["values"] == {"LIMIT": "7"} and doc["options"]["set"] == {"LIMIT": "7"}
    assert out.splitlines()[1].split()[:2] == ["s[LIMIT=7]", "8"]
    assert "values      LIMIT=7" in (reports / "s-LIMIT=7.txt").read_text(encoding="utf-8")


def test_set_replaces_a_parameter_of_the_table(tmp_path, capsys):
    spec = scenario(tmp_path, body="[parameters]\nLIMIT = [1, 2]\n" + HOLDS, model=SMALL)
    code, out, err = check(spec, "--no-reports", "--set", "LIMIT=5", "--no-timings", capsys=capsys)
    assert code == 0, err
    rows = [line.split()[:2] for line in out.splitlines()[1:] if line.startswith("s[")]
    assert rows == [["s[LIMIT=5]", "6"]]


def test_set_of_a_constant_the_model_lacks_is_bad_usage(tmp_path, capsys):
    spec = scenario(tmp_path, body=HOLDS, model=SMALL)
    code, _, err = check(spec, "--no-reports", "--set", "NN=3", capsys=capsys)
    assert code == 64, err
    assert "--set NN=3: the model has no constant 'val NN'" in err and "Traceback" not in err
    code, _, err = check(spec, "--no-reports", "--set", "NN", capsys=capsys)
    assert code == 64 and "--set expects NAME=VALUE" in err


# ---------------------------------------------------------------- the default time limit of a run


def test_a_run_says_when_its_scenario_sets_no_time_limit(tmp_path, capsys):
    plain = scenario(tmp_path, "plain.toml", HOLDS, model=SMALL)
    limited = scenario(tmp_path, "limited.toml", "[explore]\nmax_seconds = 120\n" + HOLDS, model=SMALL)
    reports = tmp_path / "reports"
    code, out, _ = check(plain, limited, "--reports", str(reports), "--no-timings", capsys=capsys)
    assert code == 0
    rows = {line.split()[0]: line for line in out.splitlines()[1:3]}
    assert "  600 s (default)  holds" in rows["plain"] and "  120 s  " in rows["limited"]
    assert "(default)" not in rows["limited"]
    opts = report(reports, "plain")["options"]
    assert opts["max_seconds"] == 600 and opts["max_seconds_is_default"] is True
    assert "max_seconds_is_default" not in report(reports, "limited")["options"]
    code, out, _ = check(plain, limited, "--no-reports", "--max-seconds", "30", capsys=capsys)
    assert [line.split()[3:5] for line in out.splitlines()[1:3]] == [["30", "s"], ["30", "s"]]
    code, out, _ = check(plain, "--no-reports", "--max-seconds", "0", capsys=capsys)
    assert code == 0 and out.splitlines()[1].split()[3] == "none"
    assert check(plain, "--no-reports", "--max-seconds", "-1", capsys=capsys)[0] == 64


UNBOUNDED = """net U;
colset N = int;
var n : N;
place P : N = 1`0;
trans Inc;
arc P -> Inc : n;
arc Inc -> P : n + 1;
"""


def test_the_default_time_limit_ends_an_unbounded_model_with_a_partial_report(tmp_path, capsys, monkeypatch):
    import cpn.cli.check

    # a default too small for any search, so that the test depends on no measured time
    monkeypatch.setattr(cpn.cli.check, "DEFAULT_MAX_SECONDS", 1e-6)
    spec = scenario(tmp_path, "u.toml", prop("small", "size (U'P 1) = 1"), model=UNBOUNDED)
    code, out, err = check(spec, "--no-reports", "--max-memory", "0", capsys=capsys)
    assert code == 2, err
    assert "(partial)" in out and "1e-06 s (default)" in out
    assert "u: stopped by the default time limit of 1e-06 s a run; set max_seconds" in out
