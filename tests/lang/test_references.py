"""Reference variables (`ref e`, `!x`, `x := e`): simulate runs them, each run starting from the values the
declarations gave them; `lint` warns at each `ref` (W0106), and `explore` and `check` refuse the net with one
error per `ref` the net uses (E0206), where a function the net never calls is no use."""

from __future__ import annotations

import json

import pytest

import cpn
from cpn.cli.main import main
from cpn.errors import ModelError

NET = """colset INT = int;
var n : INT;
val counter = ref 0;
val alias = counter;
fun next () = (counter := !counter + 1; !alias);
fun unused () = ref 5;
place A : INT = 1`0;
place B : INT;
trans t;
arc A -> t : n;
arc t -> B : next ();
arc t -> A : n;
"""


def write(tmp_path, text=NET):
    path = tmp_path / "r.cpnet"
    path.write_text(text)
    return str(path)


def run(model, steps):
    engine = model.engine(simulation=True, reference=True)
    s = engine.initial_state()
    for _ in range(steps):
        [(_be, fire)] = engine.successors(s, lazy=True)
        s = fire()
    return engine.format_marking(s, 1)


def test_assignments_are_seen_by_later_occurrences_and_through_every_name_of_the_cell(tmp_path):
    model = cpn.load(write(tmp_path))
    assert run(model, 3) == "1`1++1`2++1`3"


def test_each_engine_starts_from_the_values_of_the_declarations(tmp_path):
    model = cpn.load(write(tmp_path))
    assert run(model, 2) == "1`1++1`2"
    assert run(model, 2) == "1`1++1`2"  # not 1`3++1`4: the first run's assignments are its own


def test_explore_refuses_each_ref_the_net_uses_at_the_ref(tmp_path):
    path = write(tmp_path)
    with pytest.raises(ModelError) as info:
        cpn.load(path).engine()
    # one error, at `ref 0` (line 3); `unused`'s ref is never called
    assert [(d.code, d.params["name"], d.span.line, d.span.col) for d in info.value.diagnostics] == \
        [("E0206", "ref", 3, 15)]
    [d] = info.value.diagnostics
    assert "reference variable" in d.message and "keep the value in a place" in d.hint


def test_lint_warns_and_simulate_is_reproducible(tmp_path):
    path = write(tmp_path)
    out = tmp_path / "lint.json"
    assert main(["lint", path, "--json", str(out)]) == 0
    [entry] = json.loads(out.read_text())["models"]
    assert entry["simulation_only"] is True
    assert [(d["code"], d["line"]) for d in entry["diagnostics"]] == [("W0106", 3)]
    runs = []
    for k in range(2):
        dest = tmp_path / f"run{k}.json"
        assert main(["simulate", path, "--steps", "4", "--seed", "7", "--json", str(dest)]) == 0
        runs.append(json.loads(dest.read_text()))
    assert runs[0]["final_marking"] == runs[1]["final_marking"] == {"Top'A 1": "1`0",
                                                                   "Top'B 1": "1`1++1`2++1`3++1`4"}


def test_explore_exits_65_with_the_error_and_no_traceback(tmp_path, capsys):
    assert main(["explore", write(tmp_path)]) == 65
    err = capsys.readouterr().err
    assert "error[E0206]" in err and "Traceback" not in err


@pytest.mark.parametrize("text, col", [
    ("val r = ref 1; val x : string = !r;", 33),  # !r is an int
    ("val r = ref 1; val u = r := \"a\";", 24),  # an int cell holds no string: at the cell
    ("val x = 1; val y = !x;", 21),  # x is no reference: at the operand
    ("val r : int ref = ref true;", 19),
])
def test_type_errors_are_positioned(text, col):
    with pytest.raises(ModelError) as info:
        cpn.loads(text + " colset U = unit; place A : U; trans t; arc A -> t;", "r.cpnet")
    assert [(d.code, d.span.line, d.span.col) for d in info.value.diagnostics if d.code.startswith("E")] == \
        [("E0301", 1, col)]


def test_assignment_is_looser_than_every_other_operator_and_bang_binds_an_atom():
    model = cpn.loads("val r = ref [1]; val u = r := 0 :: !r @ [2]; val v = (r := tl (!r); hd (!r));"
                      "colset U = unit; place A : U; trans t; arc A -> t;", "r.cpnet")
    assert model.net.checked is not None
    with pytest.raises(ModelError):
        cpn.loads("val r = ref 1; val x = ! ;", "r.cpnet")


ACTION = """colset INT = int;
colset P = product INT * INT;
var n, m, k : INT;
val counter = ref 10;
place A : INT = 1`0;
place B : P;
place C : INT;
trans t output (m, k) action (counter := !counter + 1; (!counter, 2 * !counter));
trans u action (counter := 0);
arc A -> t : n;
arc t -> B : (m, k);
arc t -> A : n;
arc C -> u : n;
"""


def test_an_action_runs_once_per_occurrence_before_the_output_arcs_and_binds_its_outputs(tmp_path):
    model = cpn.load(write(tmp_path, ACTION))
    engine = model.engine(simulation=True, reference=True)
    s = engine.initial_state()
    for _ in range(2):
        [(be, fire)] = engine.successors(s, lazy=True)  # u has no token: only t, never fired twice a step
        s = fire()
    assert engine.format_marking(s, 1) == "1`(11,22)++1`(12,24)"
    assert engine.format_binding_element(be) == "Top't 1: {n=0}"  # the outputs are no part of the binding


def test_an_action_is_simulation_only_with_one_error_at_it(tmp_path):
    path = write(tmp_path, ACTION)
    with pytest.raises(ModelError) as info:
        cpn.load(path).engine()
    lines = ACTION.splitlines()
    assert [(d.code, d.params["name"], d.span.line, d.span.col) for d in info.value.diagnostics] == [
        ("E0206", "ref", 4, 15),
        ("E0206", "action", 8, lines[7].index("action (") + 8),
        ("E0206", "action", 9, lines[8].index("counter :=") + 1)]  # at the action (its parentheses are no node)


@pytest.mark.parametrize("trans, code, col", [
    ("trans t output (z) action 1;", "E0201", 27),  # z is not declared
    ("trans t output (n) action 1;", "E0206", 27),  # n is bound by the input arc
    ('trans t output (m) action "x";', "E0301", 27),  # m is an INT
])
def test_output_variables_are_declared_unbound_variables_of_the_action_s_type(tmp_path, trans, code, col):
    text = "colset INT = int; var n, m : INT; place A : INT = 1`0; place B : INT;\n" \
           f"{trans}\narc A -> t : n; arc t -> B : m;\n"
    with pytest.raises(ModelError) as info:
        cpn.load(write(tmp_path, text))
    assert [(d.code, d.span.line, d.span.col) for d in info.value.diagnostics if d.code.startswith("E")] == \
        [(code, 2, col)]


def test_an_action_prints_as_it_reads():
    from cpn.lang.parser import parse
    from cpn.lang.pretty import decl

    [d] = [x for x in parse("trans t output (m, k) action (1, 2);", "a.cpnet").decls]
    assert decl(d) == "trans t output (m, k) action (1, 2);"


def test_an_evaluation_run_again_on_a_deep_stack_assigns_once(tmp_path):
    # f counts its calls in a cell and recurses beyond Python's ordinary stack: the first attempt's
    # assignments are undone before the evaluation is run again
    text = NET.replace("fun unused () = ref 5;",
                       "fun f (k : int) = (counter := !counter + 1; if k = 0 then 0 else f (k - 1));") \
              .replace("arc t -> B : next ();", "arc t -> B : f 5000 + !counter;")
    engine = cpn.load(write(tmp_path, text)).engine(simulation=True, reference=True)
    [(_be, fire)] = engine.successors(engine.initial_state(), lazy=True)
    assert engine.format_marking(fire(), 1) == "1`5001"
