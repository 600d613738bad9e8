"""A model that reads the clock refuses time condensation with the same exit status from `explore` and from
`check` (64, a usage refusal: the option does not apply to the model; docs/semantics.md, Time)."""

from cpn.cli.main import main

CLOCK_GUARD = """net T;
colset U = unit timed;
place A : U = 1`();
place B : U;
trans Go [intTime () < 30];
arc A -> Go;
arc Go -> B : () @+ 5;
trans Back;
arc B -> Back;
arc Back -> A : () @+ 20;
"""


def _model(tmp_path):
    path = tmp_path / "m.cpnet"
    path.write_text(CLOCK_GUARD, encoding="utf-8")
    return path


def test_explore_refuses_condensation_of_a_clock_reading_model_with_64(tmp_path, capsys):
    assert main(["explore", str(_model(tmp_path)), "--time-condensation", "--quiet"]) == 64
    err = capsys.readouterr().err
    assert "m.cpnet:5:11: error[E0601]" in err and "Traceback" not in err


def test_check_refuses_condensation_of_a_clock_reading_model_with_64(tmp_path, capsys):
    _model(tmp_path)
    spec = tmp_path / "s.toml"
    spec.write_text('model = "m.cpnet"\n[explore]\ntime_condensation = true\n'
                    '[[property]]\nkind = "invariant"\nexpr = "size (T\'B 1) <= 1"\n', encoding="utf-8")
    assert main(["check", str(spec), "--no-reports"]) == 64
    err = capsys.readouterr().err
    assert "m.cpnet:5:11: error[E0601]" in err and "hint:" in err and "Traceback" not in err

