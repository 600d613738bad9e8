"""A scenario file given to a model command (and a model given to `check`) says which command reads it; a
missing model file is quoted alike by every command."""

import pytest

from cpn.cli.main import main
from cpn.errors import ModelError
from cpn.lang.parser import parse


def _error(text: str, name: str = "m.cpnet") -> ModelError:
    with pytest.raises(ModelError) as info:
        parse(text, name)
    return info.value


SCENARIO = 'name = "dp"\nmodel = "m.cpnet"\n[[property]]\nname = "x"\nkind = "deadlock_free"\n'


@pytest.mark.parametrize("command", ["lint", "explore"])
def test_a_scenario_given_to_a_model_command_hints_at_check(tmp_path, capsys, command):
    path = tmp_path / "s.toml"
    path.write_text(SCENARIO, encoding="utf-8")
    code = main([command, str(path)])
    err = capsys.readouterr().err
    assert code == 65
    assert f"cpn-verify check {path}" in err
    assert err.count("error[") == 1, err


def test_a_syntax_error_in_a_model_gets_no_scenario_hint():
    d = _error("net N;\nplace A : INT\nplace B : INT;\n").diagnostics[0]
    assert "check" not in (d.hint or "")


@pytest.mark.parametrize("command", ["lint", "explore", "simulate", "convert"])
def test_a_missing_model_file_is_quoted_by_every_command(tmp_path, capsys, command):
    missing = str(tmp_path / "nope.cpnet")
    code = main([command, missing] + (["-o", str(tmp_path / "x.pnml")] if command == "convert" else []))
    err = capsys.readouterr().err
    assert code == 64
    assert f"no such model file: '{missing}'" in err


def test_a_model_read_as_a_scenario_is_told_apart_from_a_scenario_with_a_place_key():
    from cpn.diagnostics import other_command_hint

    hint = other_command_hint("m.cpnet", "net M;\ncolset C = int;\nplace A : C;\n", "scenario")
    assert "cpn-verify lint m.cpnet" in hint
    # a property's `place = "..."` key is TOML, not a place declaration
    assert other_command_hint("s.toml", '[[property]]\nkind = "bound"\nplace = "M\'A 1"\n', "scenario") is None
    assert other_command_hint("m.cpnet", "net M;\n", "model") is None


def test_a_model_given_to_check_hints_at_lint_and_explore(tmp_path, capsys):
    path = tmp_path / "m.cpnet"
    path.write_text("net M;\ncolset C = int with 0..1;\nplace A : C = 1`0;\n", encoding="utf-8")
    code = main(["check", "--reports", str(tmp_path / "r"), str(path)])
    err = capsys.readouterr().err
    assert code == 65
    assert f"cpn-verify lint {path}" in err and f"cpn-verify explore {path}" in err
    assert "TOML is described" not in err
