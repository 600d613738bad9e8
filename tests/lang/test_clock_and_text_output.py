"""The machine's clock and text output (`Time.now`, `SMLTime.*`, `Date.fromTimeLocal`, `TextIO`): the pure
conversions are functions like any other; what reads the clock or the time zone, or writes text, runs in
`simulate` (text output written nowhere), `lint` warns at it (W0106), and `explore` and `check` refuse the
net with one error per use (E0206) naming the built-in, where the net uses it (a function the net never
calls is no use)."""

from __future__ import annotations

import json

import pytest

import cpn
from cpn.cli.main import main
from cpn.errors import ModelError
from cpn.values import effects

NET = """colset U = unit;
colset S = string;
fun stamp (n : int) = Date.fmt "%Y-%m-%d" (Date.fromTimeLocal (SMLTime.fromSeconds n));
fun log (s : string) =
  let val f = TextIO.openAppend "trace.log" val _ = TextIO.output (f, s) in TextIO.closeOut f end;
fun never (s : string) = TextIO.print s;
place A : U = 1`();
place B : S;
trans t [log "t" = ()];
arc A -> t : ();
arc t -> B : stamp 86400;
"""


def write(tmp_path, text=NET):
    path = tmp_path / "c.cpnet"
    path.write_text(text)
    return str(path)


def test_explore_refuses_each_use_naming_the_builtin_called(tmp_path):
    path = write(tmp_path)
    with pytest.raises(ModelError) as info:
        cpn.load(path).engine()
    found = sorted((d.code, d.params["name"], d.span.line, d.span.col) for d in info.value.diagnostics)
    # log's calls of TextIO (line 5) and stamp's Date.fromTimeLocal (line 3); never's TextIO.print is unused
    lines = NET.splitlines()
    assert found == [("E0206", name, line, lines[line - 1].index(name) + 1) for name, line in
                     (("Date.fromTimeLocal", 3), ("TextIO.closeOut", 5), ("TextIO.openAppend", 5),
                      ("TextIO.output", 5))]
    assert all("log" not in d.message.split(":")[0] for d in info.value.diagnostics)


def test_lint_warns_and_simulate_runs_writing_nothing(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    path = write(tmp_path)
    out = tmp_path / "lint.json"
    assert main(["lint", path, "--json", str(out)]) == 0
    [entry] = json.loads(out.read_text())["models"]
    assert entry["simulation_only"] is True
    assert sorted(d["code"] for d in entry["diagnostics"]) == ["W0106"] * 4
    run = tmp_path / "run.json"
    assert main(["simulate", path, "--steps", "2", "--seed", "1", "--json", str(run)]) == 0
    steps = json.loads(run.read_text())["steps"]
    assert [s["binding_element"] for s in steps] == ["Top't 1: {}"]
    assert not (tmp_path / "trace.log").exists()  # text output is dropped


def test_a_function_with_output_the_net_never_calls_leaves_the_state_space_alone(tmp_path):
    text = NET.replace('trans t [log "t" = ()];', "trans t;").replace("stamp 86400", '"x"')
    engine = cpn.load(write(tmp_path, text)).engine()
    assert len(engine.successors(engine.initial_state())) == 1


def test_the_pure_conversions_are_functions_of_their_argument():
    f = effects.FUNCTIONS
    assert f["Date.fromTimeUniv"](f["SMLTime.fromSeconds"](86400 * 366 + 3723))[:6] == (1971, 0, 2, 1, 2, 3)
    assert f["Time.toSeconds"](f["Time.fromReal"](2.75)) == 2
    assert set(effects.SIMULATION_ONLY) >= {"Time.now", "SMLTime.now", "Date.fromTimeLocal", "TextIO.output"}
    assert not {"SMLTime.fromSeconds", "Date.fromTimeUniv", "TextIO.stdOut"} & set(effects.SIMULATION_ONLY)
