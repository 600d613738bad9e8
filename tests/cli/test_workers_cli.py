"""`--workers N` for `explore` and `check`, and `workers = N` in a scenario's [explore]
table: the same figures, verdicts and counterexample lengths as one process; bad values are usage errors;
`--ray` without Ray installed says how to install it."""

import json
import os
import re
import shutil

import pytest

from cpn.cli.main import main
from tests._shared import ROOT

DP = os.path.join(ROOT, "bench", "nets", "dp.cpnet")

# DP has one dead marking (everyone holds the left fork): deadlock_free is violated, and an invariant that
# no two neighbours eat at once holds; one that nobody ever eats is violated at depth 2
SCENARIO = """model = "dp.cpnet"
[set]
N = "5"
[explore]
{explore}

[[property]]
name = "no deadlock"
kind = "deadlock_free"

[[property]]
name = "nobody eats"
kind = "invariant"
expr = "size (DP'Eat 1) = 0"

[[property]]
name = "at most two eat"
kind = "invariant"
expr = "size (DP'Eat 1) <= 2"

[[property]]
name = "someone holds a left fork"
kind = "reachable"
expr = "size (DP'HasLeft 1) > 0"

[[property]]
name = "home"
kind = "home"
"""


def _figures(text: str) -> list[str]:
    """The text report without what names nodes (numbered in another breadth-first order), the steps of
    a trace (another shortest path may be chosen), the date, the seconds and the notes."""
    skip = r"\[\d|[Mm]arking \d|^\s+\d+\. |Report generated|Note:|^\s*Secs:"
    return [line for line in text.splitlines() if line.strip() and not re.search(skip, line)]


def test_explore_with_workers_prints_the_same_report(tmp_path, capsys):
    assert main(["explore", DP, "--set", "N=6", "--json", str(tmp_path / "one.json")]) == 0
    one = capsys.readouterr()
    assert main(["explore", DP, "--set", "N=6", "--workers", "2", "--json", str(tmp_path / "two.json")]) == 0
    two = capsys.readouterr()
    assert "the search ran in 2 threads of this process" in two.err
    assert _figures(one.out) == _figures(two.out) and "Dead Markings" in one.out
    a = json.loads((tmp_path / "one.json").read_text(encoding="utf-8"))
    b = json.loads((tmp_path / "two.json").read_text(encoding="utf-8"))
    for key in ("states", "arcs", "complete", "levels"):
        assert a["statespace"][key] == b["statespace"][key]
    for key in ("scc", "bounds", "multiset_bounds", "fairness", "live_transitions", "dead_transitions", "tokens"):
        if isinstance(a[key], dict):
            a[key].pop("seconds", None)
            b[key].pop("seconds", None)
        assert a[key] == b[key], key
    assert a["dead_markings"]["count"] == b["dead_markings"]["count"] == 1
    assert [d["marking"] for d in a["dead_markings"]["listed"]] == [d["marking"] for d in b["dead_markings"]["listed"]]
    assert len(a["dead_markings"]["trace"]) == len(b["dead_markings"]["trace"])


def test_explore_with_workers_stops_at_a_limit_and_says_so(capsys):
    assert main(["explore", DP, "--set", "N=8", "--workers", "2", "--max-states", "300"]) == 2
    err = capsys.readouterr().err
    assert "partial state space: stopped because max_states=300 was reached" in err


@pytest.mark.parametrize("value", ["0", "-2"])
def test_workers_must_be_positive(value, capsys):
    assert main(["explore", DP, "--workers", value]) == 64
    assert "--workers must be at least 1" in capsys.readouterr().err


def test_ray_without_ray_installed_is_a_usage_error_with_a_hint(monkeypatch, capsys):
    from cpn.statespace import distributed

    monkeypatch.setattr(distributed, "ray_unavailable", lambda: "Ray is not installed")
    assert main(["explore", DP, "--ray"]) == 64
    err = capsys.readouterr().err
    assert "--ray: Ray is not installed" in err and "pip install 'cpn-verify[ray]'" in err
    assert main(["check", os.path.join(ROOT, "specs", "examples", "dp.toml"), "--ray", "auto", "--no-reports"]) == 64


def _check(tmp_path, explore: str, *args) -> dict:
    (tmp_path / "s.toml").write_text(SCENARIO.format(explore=explore), encoding="utf-8")
    out = tmp_path / ("r" + str(len(os.listdir(tmp_path))))
    status = main(["check", str(tmp_path / "s.toml"), "--reports", str(out), "--no-timings", "-q", *args])
    (doc,) = [json.loads(p.read_text(encoding="utf-8")) for p in out.glob("*.json")]
    return status, doc


def _verdicts(doc):
    return [(p["name"], p["verdict"], len(p.get("trace", {}).get("steps", []))) for p in doc["properties"]]


def test_check_with_workers_gives_the_same_verdicts_and_counterexample_lengths(tmp_path):
    shutil.copy(DP, tmp_path / "dp.cpnet")
    one_status, one = _check(tmp_path, "")
    two_status, two = _check(tmp_path, "", "--workers", "2")
    three_status, three = _check(tmp_path, "workers = 2")  # the scenario's own [explore] option
    assert one_status == two_status == three_status == 1
    assert _verdicts(one) == _verdicts(two) == _verdicts(three)
    assert dict((n, v) for n, v, _ in _verdicts(one)) == {
        "no deadlock": "violated", "nobody eats": "violated", "at most two eat": "holds",
        "someone holds a left fork": "holds", "home": "holds"}
    assert [n for _, _, n in _verdicts(one)][:2] == [5, 2]  # shortest counterexamples: 5 and 2 steps
    assert one["statespace"]["states"] == two["statespace"]["states"] == three["statespace"]["states"]


def test_check_with_workers_and_stop_at_first_violation(tmp_path):
    shutil.copy(DP, tmp_path / "dp.cpnet")
    _, one = _check(tmp_path, "stop_at_first_violation = true")
    _, two = _check(tmp_path, "stop_at_first_violation = true", "--workers", "2")
    # the search must stop at the first violation: it runs in one process, and says so
    assert _verdicts(one) == _verdicts(two)
    assert one["statespace"]["states"] == two["statespace"]["states"] < 82


def test_check_of_the_repository_scenarios_with_workers(tmp_path, capsys):
    specs = os.path.join(ROOT, "specs", "examples")
    main(["check", specs, "--reports", str(tmp_path / "a"), "--no-timings"])
    one = capsys.readouterr().out
    main(["check", specs, "--reports", str(tmp_path / "b"), "--no-timings", "--workers", "2"])
    two = capsys.readouterr().out
    assert one == two and "holds" in one
    for name in os.listdir(tmp_path / "a"):
        if name.endswith(".json"):
            a = json.loads((tmp_path / "a" / name).read_text(encoding="utf-8"))
            b = json.loads((tmp_path / "b" / name).read_text(encoding="utf-8"))
            assert _verdicts(a) == _verdicts(b), name
            assert a["statespace"]["states"] == b["statespace"]["states"]


@pytest.mark.parametrize("value", ["0", "true", "1.5"])
def test_a_bad_workers_value_in_a_scenario_is_an_error_at_its_line(tmp_path, value, capsys):
    shutil.copy(DP, tmp_path / "dp.cpnet")
    (tmp_path / "s.toml").write_text(SCENARIO.format(explore=f"workers = {value}"), encoding="utf-8")
    assert main(["check", str(tmp_path / "s.toml"), "--no-reports"]) == 65
    err = capsys.readouterr().err
    assert "s.toml:5:11: error[E0702]: 'workers' must be a positive number" in err
