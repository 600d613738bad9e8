"""`check --jobs N`: runs checked in N processes give the output, the reports and the exit status of one
process; Ctrl-C stops them and the check reports what had finished."""

import os
import pathlib
import re
import signal
import subprocess
import sys
import time

import pytest

from cpn.cli.main import main
from tests.checks._nets import COUNTER

ROOT = pathlib.Path(__file__).resolve().parents[2]

# four runs of the counter, one of them with a value the model refuses (an error of the scenario, exit 65),
# one with a violated property (its shortest trace is printed)
ROWS = """model = "c.cpnet"
[[parameters]]
M = 3
[[parameters]]
M = 2
[[parameters]]
M = "true"
[[parameters]]
M = 1
[[property]]
name = "top"
kind = "bound"
expr = "ms_to_col (C'P 1)"
upper = "M"
[[property]]
name = "below two"
kind = "invariant"
expr = "ms_to_col (C'P 1) < 2"
"""


def _scenarios(tmp_path) -> list[str]:
    model = COUNTER.replace("colset N = int with 0..3;", "val M = 3;\ncolset N = int with 0..M;").replace(
        "[n < 3]", "[n < M]")
    (tmp_path / "c.cpnet").write_text(model, encoding="utf-8")
    (tmp_path / "rows.toml").write_text(ROWS, encoding="utf-8")
    return [str(tmp_path / "rows.toml"), str(ROOT / "specs/examples")]


def _check(tmp_path, name: str, *args: str):
    reports = tmp_path / name
    html = tmp_path / f"{name}-html"
    p = subprocess.run([sys.executable, "-m", "cpn", "check", *_scenarios(tmp_path), "--no-timings",
                        "--reports", str(reports), "--junit", str(tmp_path / f"{name}.xml"), "--html", str(html),
                        *args], cwd=ROOT, capture_output=True, text=True, timeout=600)
    files = {f.name: f.read_text(encoding="utf-8") for f in sorted(reports.iterdir())}
    pages = {f.name: f.read_text(encoding="utf-8") for f in sorted(html.iterdir())}  # --no-timings: no date
    return (p.returncode, p.stdout, p.stderr, files, (tmp_path / f"{name}.xml").read_text(encoding="utf-8"),
            pages)


def test_runs_in_several_processes_print_and_write_what_one_process_does(tmp_path):
    one = _check(tmp_path, "one", "--jobs", "1")
    two = _check(tmp_path, "two", "--jobs", "2")
    auto = _check(tmp_path, "auto")
    assert one[0] == 65 and "violated" in one[1] and "error" in one[2] and "Traceback" not in one[2]
    # three reports for each run that loads: 3 rows of 4, and the 6 runs of the 4 examples
    assert len(one[3]) == 3 * 9 and sum(name.startswith("rows") for name in one[3]) == 3 * 3
    assert "index.html" in one[5] and len(one[5]) == 1 + 9  # a page per run that loads, and the index
    assert two == one and auto == one


def test_jobs_must_be_positive(tmp_path, capsys):
    assert main(["check", *_scenarios(tmp_path), "--no-reports", "--jobs", "0"]) == 64
    assert "--jobs must be at least 1, got 0" in capsys.readouterr().err


@pytest.mark.skipif(not hasattr(signal, "SIGINT") or os.name != "posix", reason="needs POSIX signals")
def test_ctrl_c_stops_the_processes_and_reports_the_runs_that_finished(tmp_path):
    # a scenario of many runs, each a search of a few seconds; Ctrl-C once some have finished
    model = "val N = 0;\ncolset C = int with 0..1999999;\nvar n : C;\nplace P : C = 1`0;\n" \
            "trans t [n < 1999999];\narc P -> t : n;\narc t -> P : n + 1 + 0 * N;\n"
    (tmp_path / "long.cpnet").write_text(model, encoding="utf-8")
    rows = "".join(f"[[parameters]]\nN = {i}\n" for i in range(12))
    (tmp_path / "long.toml").write_text(
        f'model = "long.cpnet"\n[explore]\nbackend = "python"\nmax_states = 60000\n{rows}'
        '[[property]]\nname = "one"\nkind = "invariant"\nexpr = "size (Top\'P 1) = 1"\n', encoding="utf-8")
    p = subprocess.Popen([sys.executable, "-m", "cpn", "check", str(tmp_path / "long.toml"), "--jobs", "2",
                          "--no-timings", "--reports", str(tmp_path / "r")], cwd=ROOT, stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, start_new_session=True)
    time.sleep(4)
    os.killpg(p.pid, signal.SIGINT)  # what Ctrl-C sends: the whole process group
    try:
        out, err = p.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        raise
    assert p.returncode == 130, out + err
    m = re.search(r"^interrupted: (\d+) of 12 runs not checked$", err, re.M)
    assert m and "Traceback" not in err, err
    finished = [line.split()[0] for line in out.splitlines() if line.startswith("long[")]
    assert finished == [f"long[N={i}]" for i in range(12 - int(m.group(1)))], (finished, err)
    assert len(list((tmp_path / "r").glob("*.json"))) == len(finished)


@pytest.mark.parametrize("where", ["scenario", "command line"])
def test_runs_whose_search_has_workers_of_its_own_are_checked_one_at_a_time(tmp_path, capsys, where):
    # a pool's processes cannot start the partitioned search's own
    explore = "[explore]\nworkers = 2\nbackend = \"python\"\n" if where == "scenario" else ""
    (tmp_path / "ms.toml").write_text(
        f'model = "{(ROOT / "bench/nets/ms.cpnet").as_posix()}"\n{explore}'
        "[[parameters]]\nN = 2\n[[parameters]]\nN = 3\n"
        '[[property]]\nname = "no dead marking"\nkind = "dead_markings"\ncount = 0\n', encoding="utf-8")
    extra = ["--workers", "2"] if where == "command line" else []
    assert main(["check", str(tmp_path / "ms.toml"), "--no-reports", "--jobs", "2", *extra]) == 0
    out, err = capsys.readouterr()
    assert "note: the runs are checked one at a time" in err and "ms[N=3]" in out


def _dies_at_the_second_row(item):
    """A run whose process is killed (as the system's out-of-memory killer would), the others as they are."""
    from cpn.cli import check

    if item[1].name == "rows[M=2]":
        os.kill(os.getpid(), signal.SIGKILL)
    return check.__dict__["_real_check_run"](item)


@pytest.mark.skipif(os.name != "posix", reason="forks the pool's processes")
def test_a_process_that_dies_is_an_error_with_the_runs_not_checked(tmp_path, capsys, monkeypatch):
    from cpn.cli import check

    monkeypatch.setitem(check.__dict__, "_real_check_run", check._check_run)
    monkeypatch.setattr(check, "_check_run", _dies_at_the_second_row)
    code = main(["check", _scenarios(tmp_path)[0], "--no-reports", "--no-timings", "--jobs", "2"])
    out, err = capsys.readouterr()
    assert code == 70, err
    assert "error: a process checking the runs ended without a result" in err and "Traceback" not in err
    # the pool's other runs end with it; those reported before are kept
    m = re.search(r"(\d) of 4 runs not checked, from '(rows\[M=\w+\])' on", err)
    assert m and int(m.group(1)) >= 3 and m.group(2) in ("rows[M=3]", "rows[M=2]"), err
