"""A property that reads the clock is refused under time condensation (E0601), as a model that reads it
is: a condensed state space has the clock 0 in every state, so the property would silently judge
another model (`size (B 1) = 0 orelse intTime() < 30` held with condensation, and is violated without)."""

import pytest

from cpn.cli.main import main
from cpn.errors import ModelError
from cpn.gate.run import run_scenario
from cpn.gate.scenario import load_scenario
from tests.checks._nets import scenario

TIMED = """net T;
colset U = unit timed;
fun late () = intTime () >= 30;
place A : U = 1`();
place B : U;
trans Go;
arc A -> Go;
arc Go -> B : () @+ 5;
trans Back;
arc B -> Back;
arc Back -> A : () @+ 20;
"""
# the clock grows by 25 per round; with condensation the state space has 2 states


def _scenario(tmp_path, condensed: bool, prop: str) -> str:
    explore = "[explore]\ntime_condensation = true\n" if condensed else "[explore]\nmax_states = 40\n"
    return scenario(tmp_path, TIMED, explore + prop)


INVARIANT = '[[property]]\nname = "early"\nkind = "invariant"\nexpr = "size (T\'B 1) = 0 orelse intTime () < 30"\n'


def _refusal(tmp_path, prop: str):
    s = load_scenario(_scenario(tmp_path, True, prop))
    with pytest.raises(ModelError) as info:
        run_scenario(s, s.runs[0])
    (d,) = info.value.diagnostics
    return d


def test_a_property_reading_the_clock_is_refused_at_its_position(tmp_path):
    d = _refusal(tmp_path, INVARIANT)
    assert d.code == "E0601"
    # line 7 of the scenario (2 lines of [explore], the model line, then the property's 4 lines)
    assert (d.span.file.endswith("s.toml"), d.span.line, d.span.col) == (True, 7, 33)
    assert "time_condensation = true" in d.hint and "--time-condensation" in d.hint


def test_without_condensation_the_same_property_is_decided(tmp_path):
    s = load_scenario(_scenario(tmp_path, False, INVARIANT))
    (result,) = run_scenario(s, s.runs[0]).results
    assert result.verdict.status.value == "violated"  # B is marked at time 30


def test_a_clock_read_through_a_model_function_names_the_function(tmp_path):
    d = _refusal(tmp_path, '[[property]]\nkind = "reachable"\nexpr = "late ()"\n')
    assert d.code == "E0601" and d.span.line == 6 and d.span.col == 9
    assert any("'late' reads it at" in n and "s.cpnet:3:" in n for n in d.notes)


def test_a_ctl_formula_and_a_bound_reading_the_clock_are_refused(tmp_path):
    d = _refusal(tmp_path, '[[property]]\nkind = "ctl"\nformula = "AG (intTime () < 100)"\n')
    assert d.code == "E0601" and d.span.col == 16
    d = _refusal(tmp_path, '[[property]]\nkind = "bound"\nplace = "T\'B 1"\nupper = "intTime ()"\n')
    assert d.code == "E0601" and d.span.line == 7


def test_a_property_without_the_clock_is_checked_under_condensation(tmp_path):
    s = load_scenario(_scenario(tmp_path, True, '[[property]]\nkind = "invariant"\nexpr = "size (T\'B 1) <= 1"\n'))
    (result,) = run_scenario(s, s.runs[0]).results
    assert result.verdict.status.value == "holds"


def test_the_command_exits_65_with_the_positioned_error(tmp_path, capsys):
    path = _scenario(tmp_path, True, INVARIANT)
    assert main(["check", path, "--reports", str(tmp_path / "reports")]) == 65
    err = capsys.readouterr().err
    assert "s.toml:7:33: error[E0601]" in err and "hint:" in err and "Traceback" not in err


def test_a_progress_measure_reading_the_clock_is_refused_under_condensation(tmp_path, capsys):
    model = tmp_path / "t.cpnet"
    model.write_text(TIMED, encoding="utf-8")
    args = ["explore", str(model), "--sweep-line", "--progress", "intTime ()", "--quiet"]
    assert main(args + ["--time-condensation"]) == 65
    err = capsys.readouterr().err
    assert "--progress:1:1: error[E0601]" in err and "Traceback" not in err
