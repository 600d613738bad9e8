"""`explore` on a model that draws random values says it once per draw: the error that refuses it
(E0206), not also the warning `lint` gives for it (W0105), at the same place."""

from cpn.cli.main import main

MODEL = """colset I = int;
var x : I;
place p : I = 1`0;
place q : I;
trans t;
arc p -> t : x;
arc t -> q : x + round (exponential 1.0);
"""


def test_explore_reports_a_draw_once_as_an_error(tmp_path, capsys):
    path = tmp_path / "draw.cpnet"
    path.write_text(MODEL, encoding="utf-8")
    for extra in ([], ["--sweep-line"]):
        assert main(["explore", str(path), *extra]) == 65
        err = capsys.readouterr().err
        assert err.count("error[E0206]: 'exponential' draws a random value") == 1
        assert "W0105" not in err
    assert main(["lint", str(path)]) == 0
    assert "warning[W0105]: 'exponential' draws a random value" in capsys.readouterr().err
