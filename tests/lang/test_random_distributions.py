"""CPN Tools' random distribution functions: `simulate` draws them from one generator seeded by --seed (the
same seed, the same run), `lint` accepts the model with a warning at each call (W0105), and `explore` and
`check` refuse it with one error per call (E0206), at the call, naming the distribution."""

from __future__ import annotations

import json

import pytest

from cpn.cli.main import main

# each distribution with arguments in its domain; the token is the draw scaled to an integer
DRAWS = {
    "uniform": "round (10.0 * uniform (0.0, 10.0))",
    "exponential": "round (100.0 * exponential (0.5))",
    "normal": "round (100.0 * normal (5.0, 4.0))",
    "erlang": "round (100.0 * erlang (3, 0.5))",
    "gamma": "round (100.0 * gamma (2.0, 3.0))",
    "beta": "round (1000.0 * beta (2.0, 3.0))",
    "chisq": "round (100.0 * chisq 3)",
    "student": "round (100.0 * student 5)",
    "weibull": "round (100.0 * weibull (2.0, 1.5))",
    "rayleigh": "round (100.0 * rayleigh 2.0)",
    "poisson": "poisson 20.0",
    "binomial": "binomial (50, 0.5)",
    "discrete": "discrete (1, 1000)",
    "bernoulli": "bernoulli 0.5",
}


def model(tmp_path, name: str, draw: str):
    path = tmp_path / f"{name}.cpnet"
    # the draw sits in a function: a draw that only simulation makes (called directly in an output arc with
    # constant arguments, discrete and bernoulli are a choice instead, tests/lang/test_finite_draws.py)
    path.write_text(f"colset U = unit;\nfun draw () = {draw};\nplace A : U = 1`();\nplace Out : INT;\n"
                    "trans t;\narc A -> t : ();\narc t -> A : ();\narc t -> Out : draw ();\n")
    return str(path)


def run(capsys, path: str, seed: int) -> dict:
    out = str(path) + f".{seed}.json"
    assert main(["simulate", path, "--seed", str(seed), "--steps", "12", "--json", out, "--quiet"]) == 0
    capsys.readouterr()
    with open(out) as fh:
        return json.load(fh)["final_marking"]


@pytest.mark.parametrize("name", sorted(DRAWS))
def test_one_seed_one_run_another_seed_another(tmp_path, capsys, name):
    path = model(tmp_path, name, DRAWS[name])
    first = run(capsys, path, 7)
    assert sum(int(t.split("`")[0]) for t in first["Top'Out 1"].split("++")) == 12
    assert run(capsys, path, 7) == first
    # twelve draws: another seed gives another multiset (bernoulli: 2^12 runs, so try a few seeds)
    assert any(run(capsys, path, seed) != first for seed in (8, 9, 10))


def test_a_draw_repeats_no_value_of_an_earlier_marking(tmp_path, capsys):
    # the marking of A is the same before every step: each occurrence still draws anew
    first = run(capsys, model(tmp_path, "uniform", DRAWS["uniform"]), 3)
    assert len(first["Top'Out 1"].split("++")) > 1


def test_lint_warns_at_the_call_and_explore_refuses_once_per_call(tmp_path, capsys):
    path = tmp_path / "q.cpnet"
    path.write_text("colset U = unit;\ncolset TU = unit timed;\n"
                    "fun expTime (m : int) = floor (exponential (1.0 / real m) + 0.5);\n"
                    "fun twice m = expTime m + expTime m;\n"
                    "place Next : TU = 1`();\ntrans Arrive @+ twice 4;\narc Next -> Arrive : ();\n"
                    "arc Arrive -> Next : ();\n")
    assert main(["lint", str(path)]) == 0
    err = capsys.readouterr().err
    assert err.count("warning[W0105]") == 1
    assert f"{path}:3:32: warning[W0105]: 'exponential' draws a random value" in err
    assert "explore and check cannot analyse it" in err
    assert main(["explore", str(path)]) == 65
    err = capsys.readouterr().err
    assert err.count("error[E0206]") == 1
    assert f"{path}:3:32: error[E0206]: 'exponential' draws a random value: a state space cannot hold it" in err
    assert "replace exponential(...) by a finite choice" in err
    assert "expTime" not in err.split("error[E0206]")[1].split("\n")[0]  # the distribution, not its caller
    assert "Traceback" not in err
    assert main(["simulate", str(path), "--steps", "3", "--seed", "1"]) == 0


def test_a_value_outside_the_domain_is_a_run_time_error(tmp_path, capsys):
    path = model(tmp_path, "bad", "round (exponential (~1.0))")
    assert main(["simulate", path, "--steps", "2"]) == 65
    err = capsys.readouterr().err
    assert "exponential: the intensity ~1.0 is not positive" in err or "intensity -1.0 is not positive" in err
    assert "Traceback" not in err


def test_sml_random_generators_are_simulated_and_refused_by_explore(tmp_path, capsys):
    # SML/NJ's Random as a CPN Tools model uses it: a generator from two seeds, a function drawing from it
    path = tmp_path / "r.cpnet"
    path.write_text("colset U = unit;\n"
                    "fun pick (s1 : int, s2 : int) =\n"
                    "  let val prox = Random.randRange (1, 36) val rs = Random.rand (s1, s2) in [prox rs, prox rs] end;\n"
                    "place A : U = 1`();\nplace Out : INT;\nplace Again : INT;\ntrans t;\narc A -> t : ();\n"
                    "arc t -> Out : pick (1, 2);\narc t -> Again : pick (1, 2);\n")
    out = tmp_path / "r.json"
    assert main(["simulate", str(path), "--json", str(out), "--quiet"]) == 0
    marking = json.loads(out.read_text())["final_marking"]
    # the same seeds give the same sequence (as in SML/NJ); a generator advances as it draws
    assert marking["Top'Out 1"] == marking["Top'Again 1"]
    assert all(1 <= int(t.split("`")[1]) <= 36 for t in marking["Top'Out 1"].split("++"))
    capsys.readouterr()
    assert main(["explore", str(path)]) == 65
    err = capsys.readouterr().err
    assert err.count("error[E0206]") == 2
    assert f"{path}:3:18: error[E0206]: 'Random.randRange' draws a random value" in err
    assert f"{path}:3:52: error[E0206]: 'Random.rand' draws a random value" in err


def test_check_refuses_a_scenario_whose_model_draws(tmp_path, capsys):
    model(tmp_path, "m", DRAWS["normal"])
    (tmp_path / "s.toml").write_text('name = "s"\nmodel = "m.cpnet"\n\n[[property]]\nname = "none dead"\n'
                                     'kind = "dead_markings"\ncount = 0\n')
    assert main(["check", str(tmp_path / "s.toml"), "--no-reports"]) == 65
    err = capsys.readouterr().err
    assert err.count("error[E0206]") == 1 and "m.cpnet:2:30: error[E0206]: 'normal' draws a random value" in err


def test_lint_says_a_model_that_draws_is_for_simulation_only(tmp_path, capsys):
    path = model(tmp_path, "u", DRAWS["uniform"])
    out = tmp_path / "lint.json"
    assert main(["lint", path, "--json", str(out)]) == 0
    assert "simulate only: explore and check cannot analyse it" in capsys.readouterr().out
    [entry] = json.loads(out.read_text())["models"]
    assert entry["simulation_only"] is True and [d["code"] for d in entry["diagnostics"]] == ["W0105"]
    plain = tmp_path / "plain.cpnet"
    plain.write_text("colset U = unit;\nplace A : U = 1`();\ntrans t;\narc A -> t : ();\n")
    assert main(["lint", str(plain), "--json", str(out)]) == 0
    assert json.loads(out.read_text())["models"][0]["simulation_only"] is False
