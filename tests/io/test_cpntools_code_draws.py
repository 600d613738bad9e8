"""A code segment's action runs once per occurrence, before the output arcs and the delay (CPN Tools): an
action that draws and whose outputs several inscriptions read is one draw that they all read, in explore
(one binding element per value of the draw) and in simulate (any seed)."""

from __future__ import annotations

import json

import pytest

import cpn
from cpn.cli.main import main
from cpn.errors import ModelError
from cpn.io.cpntools import translate_text
from tests.io.test_cpntools import DECLS, arc, cpn_xml, page, place, trans

REALS = '<color id="C9"><id>R</id><real/></color><var id="V9"><type><id>R</id></type><id>r</id><id>q</id></var>'
TIMED = '<color id="C8"><id>TS</id><timed/><int/></color>'


def _net(code, outputs=("y", "y"), decls=DECLS, cs="S", cond="", time="", out_cs=None):
    body = place("P1", "A", "S", "1`0") + trans("T1", "t", cond=cond, time=time, code=code)
    body += arc("A1", "PtoT", "T1", "P1", "x")
    for i, annot in enumerate(outputs):
        body += place(f"Q{i}", "BCDEF"[i], out_cs or cs) + arc(f"O{i}", "TtoP", "T1", f"Q{i}", annot)
    return cpn_xml(decls, page("PG1", "Top", body))


def _load(tmp_path, xml):
    path = tmp_path / "m.cpn"
    path.write_text(xml)
    return path, cpn.load(path)


def _successors(model, reference=False):
    e = model.engine(reference=reference)
    places = [p.index for p in e.places]
    return sorted((e.format_binding_element(be), tuple(e.format_marking(s, p) for p in places[1:]))
                  for be, s in e.successors(e.initial_state()))


CODE = "input (x)\noutput (y)\naction\ndiscrete (0, 3)"


def test_a_draw_read_by_two_arcs_is_one_choice_in_explore(tmp_path):
    _, model = _load(tmp_path, _net(CODE))
    succ = _successors(model)
    assert len(succ) == 4  # one binding element per value of the one draw (16 when each arc drew its own)
    assert sorted(m for _, m in succ) == [(f"1`{v}", f"1`{v}") for v in range(4)]
    assert succ == _successors(model, reference=True)


@pytest.mark.parametrize("backend", ["python", "c"])
def test_both_searches_explore_the_one_choice(tmp_path, backend, capsys):
    path, _ = _load(tmp_path, _net(CODE))
    assert main(["explore", str(path), "--backend", backend, "--json", "-"]) == 0
    space = json.loads(capsys.readouterr().out)["statespace"]
    assert (space["states"], space["arcs"]) == (5, 4)


def test_the_translation_binds_the_outputs_once_in_the_guard():
    text = translate_text(_net(CODE)).text
    assert "trans t [y = (discrete (0, 3))];" in text
    assert text.count("discrete (0, 3)") == 1
    assert "arc t -> B : y;" in text and "arc t -> C : y;" in text


@pytest.mark.parametrize("seed", [0, 1, 2, 7])
def test_simulate_gives_both_arcs_the_same_draw(tmp_path, seed):
    path, _ = _load(tmp_path, _net(CODE))
    out = tmp_path / "run.json"
    assert main(["simulate", str(path), "--steps", "1", "--seed", str(seed), "--json", str(out)]) == 0
    final = json.loads(out.read_text())["final_marking"]
    assert final["Top'B 1"] == final["Top'C 1"]


@pytest.mark.parametrize("seed", [0, 3, 5])
def test_a_continuous_draw_is_drawn_once_per_occurrence_in_simulate(tmp_path, seed):
    xml = _net("input (x)\noutput (r)\naction\nuniform (0.0, 1.0)", ("r", "r"), decls=DECLS + REALS, out_cs="R")
    path, _ = _load(tmp_path, xml)
    out = tmp_path / "run.json"
    assert main(["simulate", str(path), "--steps", "1", "--seed", str(seed), "--json", str(out)]) == 0
    final = json.loads(out.read_text())["final_marking"]
    assert final["Top'B 1"] == final["Top'C 1"]
    assert final["Top'B 1"] not in ("1`0.0", "1`1.0")  # a value of uniform, not a choice of its bounds


def test_a_continuous_draw_read_by_two_arcs_is_still_refused_by_explore(tmp_path):
    xml = _net("input (x)\noutput (r)\naction\nuniform (0.0, 1.0)", ("r", "r"), decls=DECLS + REALS, out_cs="R")
    _, model = _load(tmp_path, xml)
    with pytest.raises(ModelError) as info:
        model.engine()
    [d] = info.value.diagnostics
    assert d.code == "E0206" and "'uniform' draws a random value" in d.message
    assert (d.span.line, d.span.col) == (12, 1)  # the action, on the line after 'action' in the .cpn file


def test_a_pure_action_read_by_two_arcs_is_unchanged():
    text = translate_text(_net("input (x)\noutput (y)\naction\n(x + 1) mod 4")).text
    assert text.count("(let val y = (x + 1) mod 4 in y end)") == 2
    assert "trans t;" in text


def test_a_draw_read_by_one_arc_is_unchanged(tmp_path):
    xml = _net(CODE, ("y", "x"))
    assert "(let val y = discrete (0, 3) in y end)" in translate_text(xml).text
    assert len(_successors(_load(tmp_path, xml)[1])) == 4


def test_two_outputs_an_existing_guard_and_the_delay(tmp_path):
    code = "input (x)\noutput (y, z)\naction\n(discrete (0, 1), CS.ran ())"
    decls = DECLS + TIMED + '<color id="C7"><id>CS</id><int><with><ml>0</ml><ml>1</ml></with></int></color>' \
        + '<var id="V7"><type><id>CS</id></type><id>z</id></var>'
    xml = _net(code, ("y", "z", "y + z"), decls=decls, cond="[x = 0]", time="@+ y", out_cs="TS")
    text = translate_text(xml).text
    assert "trans t [x = 0, (y, z) = ((discrete (0, 1), CS.ran ()))] @+ y;" in text
    _, model = _load(tmp_path, xml)
    succ = _successors(model)
    assert len(succ) == 4  # two draws of two values each, made once
    for _be, (b, c, d) in succ:
        y, z = int(b.split("`")[1].split("@")[0]), int(c.split("`")[1].split("@")[0])
        assert d.startswith(f"1`{y + z}@{y}") and b.endswith(f"@{y}")
    assert succ == _successors(model, reference=True)


def test_the_time_inscription_is_the_second_reader(tmp_path):
    xml = _net(CODE, ("y",), decls=DECLS + TIMED, time="@+ y", out_cs="TS")
    assert "trans t [y = (discrete (0, 3))] @+ y;" in translate_text(xml).text
    succ = _successors(_load(tmp_path, xml)[1])
    assert sorted(m for _, m in succ) == [(f"1`{v}@{v}",) for v in range(4)]


def test_undeclared_output_variables_keep_the_let():
    # CPN Tools requires output variables to be declared; a file that does not declare them keeps the `let`
    text = translate_text(_net(CODE.replace("(y)", "(w)"), ("w", "w"))).text
    assert text.count("(let val w = discrete (0, 3) in w end)") == 2
