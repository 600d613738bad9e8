"""The search chooser (`cpn.statespace.chooser`) and its one enum, `Backend`: the option and the result,
the reason given where a search cannot run, and the back end set from a scenario file."""

import json
import pathlib

import pytest

import cpn
from cpn.cli.main import main
from cpn.statespace import Backend, ExploreOptions, Explorer, chooser
from cpn.statespace.store import packed_unavailable

NATIVE = packed_unavailable()
REPO = pathlib.Path(__file__).resolve().parents[2]
COUNTER = ("colset N = int with 0..3; var x : N; place P : N = 1`0;"
           " trans inc [x < 3]; arc P -> inc : x; arc inc -> P : x + 1;")


def test_the_option_takes_the_command_lines_words_and_nothing_else():
    assert Backend.option_words() == ("auto", "python", "c")
    assert ExploreOptions().backend is Backend.AUTO
    assert ExploreOptions(backend="python").backend is Backend.PYTHON
    assert ExploreOptions(backend=Backend.C).backend == "c"
    for bad in ("threads", "C", "native", None):
        with pytest.raises(ValueError, match="backend must be one of 'auto', 'python', 'c'"):
            ExploreOptions(backend=bad)


def test_the_result_is_a_member_whose_word_the_reports_print():
    x = Explorer(cpn.loads(COUNTER).engine(), ExploreOptions(backend="python")).run()
    assert x.backend is Backend.PYTHON and x.backend == "python" and json.dumps(x.backend) == '"python"'
    assert {b.value for b in Backend} == {"auto", "python", "c", "threads", "workers", "ray"}


@pytest.mark.skipif(NATIVE is not None, reason=f"no native code: {NATIVE}")
def test_one_process_chooses_c_or_says_why_not():
    engine = cpn.loads(COUNTER).engine()
    s0 = engine.initial_state()
    assert chooser.one_process(engine, ExploreOptions(), s0, False) == (Backend.C, None)
    backend, why = chooser.one_process(engine, ExploreOptions(backend="python"), s0, False)
    assert backend is Backend.PYTHON and why == "the Python back end was asked for"
    backend, why = chooser.one_process(engine, ExploreOptions(), s0, True)
    assert backend is Backend.PYTHON and "does not reduce" in why
    assert Explorer(engine, ExploreOptions()).run().backend is Backend.C


def test_the_partitioned_search_says_why_it_does_not_apply():
    engine = cpn.loads(COUNTER).engine()
    x = Explorer(engine, ExploreOptions(workers=2, reduction="stubborn")).run()
    assert x.backend in (Backend.PYTHON, Backend.C) and x.n_states == 4
    assert "the search ran in one process: stubborn sets" in x.notes[0]


def _scenario(tmp_path, line: str) -> str:
    path = tmp_path / "s.toml"
    path.write_text(f'model = "{REPO}/bench/nets/dp.cpnet"\n[explore]\n{line}\n[set]\nN = 4\n\n'
                    '[[property]]\nname = "no deadlock"\nkind = "dead_markings"\ncount = 1\n')
    return str(path)


@pytest.mark.skipif(NATIVE is not None, reason=f"no native code: {NATIVE}")
@pytest.mark.parametrize("word, ran", [("python", "python"), ("c", "c"), ("auto", "c")])
def test_a_scenario_file_sets_the_back_end(tmp_path, word, ran):
    (run,) = cpn.check(_scenario(tmp_path, f'backend = "{word}"'))
    assert run.exploration.backend == ran and run.exploration.options.backend == word
    x = run.exploration
    again = Explorer(x.engine, ExploreOptions(backend="python")).run()  # the same graph with each
    assert (x.n_states, x.n_arcs) == (again.n_states, again.n_arcs) and x.complete


@pytest.mark.parametrize("value", ['"threads"', '"C"', "1", "true"])
def test_a_bad_back_end_in_a_scenario_file_is_a_positioned_error(tmp_path, capsys, value):
    assert main(["check", "--reports", str(tmp_path / "r"), _scenario(tmp_path, f"backend = {value}")]) == 65
    err = capsys.readouterr().err
    assert "s.toml:3:11: error[E0702]: 'backend' must be one of 'auto', 'python', 'c'" in err
    assert "Traceback" not in err


def test_the_command_line_takes_the_options_words():
    """`--backend` keeps its choices spelt out (the command line imports no state space to print --help):
    they are the enum's option words."""
    from cpn.cli.main import build_parser

    parser = build_parser()
    sub = next(a for a in parser._actions if a.choices and "explore" in a.choices).choices["explore"]
    (backend,) = [a for a in sub._actions if "--backend" in a.option_strings]
    assert tuple(backend.choices) == Backend.option_words() and backend.default == Backend.AUTO
