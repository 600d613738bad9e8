"""CPN Tools' real-valued delays `@++ d` (a transition's or an output arc's): `simulate` runs the model with
the model time a real (seeded, reproducible), `lint` accepts it with a warning at each '@++' (W0106) and says
it is for simulation only, `explore` and `check` refuse it with one error per '@++' (E0206) at its position."""

from __future__ import annotations

import json

import pytest

import cpn
from cpn.cli.main import main
from cpn.errors import ModelError

NET = """colset U = unit timed;
place A : U = 1`();
place B : U;
trans t @++ 1.5;
arc A -> t;
arc t -> B : () @++ 0.25;
trans u;
arc B -> u;
arc u -> A : () @++ uniform (0.0, 1.0);
"""


def write(tmp_path, text=NET):
    path = tmp_path / "r.cpnet"
    path.write_text(text)
    return str(path)


def test_simulate_runs_real_delays_with_a_real_model_time(tmp_path, capsys):
    path = write(tmp_path)
    out = tmp_path / "run.json"
    assert main(["simulate", path, "--steps", "4", "--seed", "3", "--json", str(out)]) == 0
    steps = json.loads(out.read_text())["steps"]
    times = [s["time"] for s in steps]
    # t at 0; u when t's token is ready (1.5 + 0.25); t again after u's uniform draw in [0, 1]
    assert times[:2] == [0, 1.75]
    assert 1.75 <= times[2] <= 2.75 and times[3] == pytest.approx(times[2] + 1.75)
    again = tmp_path / "again.json"
    assert main(["simulate", path, "--steps", "4", "--seed", "3", "--json", str(again)]) == 0
    assert json.loads(again.read_text())["steps"] == steps  # one seed, one run
    assert main(["simulate", path, "--steps", "3", "--seed", "3"]) == 0
    assert "1.750  Top'u 1" in capsys.readouterr().out


def test_lint_accepts_real_delays_for_simulation_only(tmp_path, capsys):
    path = write(tmp_path)
    out = tmp_path / "lint.json"
    assert main(["lint", path, "--json", str(out)]) == 0
    [entry] = json.loads(out.read_text())["models"]
    assert entry["simulation_only"] is True
    assert sorted(d["code"] for d in entry["diagnostics"]) == ["W0105", "W0106", "W0106", "W0106"]
    assert "simulate only" in capsys.readouterr().out


def test_explore_refuses_each_real_delay_at_its_position(tmp_path, capsys):
    path = write(tmp_path)
    with pytest.raises(ModelError) as info:
        cpn.load(path).engine()
    found = sorted((d.code, d.span.line, d.span.col, d.params["name"]) for d in info.value.diagnostics)
    assert found == [("E0206", 4, 9, "@++"), ("E0206", 6, 14, "@++"), ("E0206", 9, 14, "@++"),
                     ("E0206", 9, 21, "uniform")]
    assert main(["explore", path]) == 65
    err = capsys.readouterr().err
    assert err.count("error[E0206]: '@++' is a real-valued delay") == 3
    assert "write an integer delay with '@+'" in err and "warning[W0106]" not in err


def test_a_real_delay_must_be_a_real_and_needs_a_timed_place(tmp_path):
    with pytest.raises(ModelError) as info:
        cpn.load(write(tmp_path, "colset U = unit timed;\nplace A : U = 1`();\ntrans t @++ 2;\narc A -> t;\n"))
    assert [d.code for d in info.value.diagnostics if d.code.startswith("E")] == ["E0301"]
    with pytest.raises(ModelError) as info:
        cpn.load(write(tmp_path, "colset U = unit;\nplace A : U = 1`();\ntrans t;\narc A -> t;\n"
                                 "arc t -> A : () @++ 1.0;\n"))
    [error] = [d for d in info.value.diagnostics if d.code.startswith("E")]
    assert error.code == "E0301" and "not timed" in error.message


def test_integer_delays_keep_an_integer_model_time(tmp_path):
    # the same net with '@+' explores as before: '@++' changes nothing for the nets that do not use it
    text = "colset U = unit timed;\nplace A : U = 1`();\ntrans t @+ 2;\narc A -> t;\narc t -> A : () @+ 1;\n"
    engine = cpn.load(write(tmp_path, text)).engine()
    [(_, s)] = engine.successors(engine.initial_state())
    [(_, s2)] = engine.successors(s)
    assert (engine.clock(s), engine.clock(s2)) == (0, 3) and isinstance(engine.clock(s2), int)


def test_int_time_is_the_real_clock_rounded_down(tmp_path):
    text = ("colset U = unit timed;\nplace A : U = 1`();\nplace Seen : INT;\ntrans t @++ 1.5;\narc A -> t;\n"
            "arc t -> A : () @++ 0.25;\narc t -> Seen : intTime ();\n")
    engine = cpn.load(write(tmp_path, text)).engine(simulation=True, reference=True)
    s = engine.initial_state()
    for _ in range(3):  # at 0, 1.75, 3.5
        [(_, s)] = engine.successors(s)
    assert engine.clock(s) == 3.5 and engine.format_marking(s, 1) == "1`0++1`1++1`3"


def test_real_delays_print_back_as_written():
    from cpn.lang.parser import parse
    from cpn.lang.pretty import pretty

    text = pretty(parse(NET, "r.cpnet"))
    assert "trans t @++ 1.5;" in text and "() @++ 0.25" in text
    assert pretty(parse(text, "r.cpnet")) == text
