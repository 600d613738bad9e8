"""Reference variables in CPN Tools nets (`globref`, `val x = ref e`, `!x`, `x := e`) and the code segments
that use them: translated as they are written, a code segment that assigns references becoming the
transition's action; `simulate` runs the net, `explore` refuses each reference variable and each action
(E0206) at its element in the `.cpn` file (docs/semantics.md, "Reference variables and actions")."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import ModelError
from cpn.io.cpntools import translate_text
from tests.io.test_cpntools import DECLS, arc, cpn_xml, page, place, trans

COUNTER = DECLS + '<globref id="G1"><id>c</id><ml>0</ml></globref>'


def write(tmp_path, decls, body, name="r.cpn"):
    path = tmp_path / name
    path.write_text(cpn_xml(decls, page("PG1", "Top", body)), encoding="iso-8859-1")
    return path


def fire(model, steps):
    engine = model.engine(simulation=True, reference=True)
    s = engine.initial_state()
    for _ in range(steps):
        succ = engine.successors(s, lazy=True)
        if not succ:
            break
        s = succ[0][1]()
    return engine, s


def test_an_assigned_globref_is_a_reference_and_a_code_segment_that_assigns_it_an_action(tmp_path):
    # t reads !c in its guard and sets c: it occurs once (CPN Tools: the guard holds for c = 0 only)
    body = (place("P1", "A", "S", "1`0++1`1") + trans("T1", "t", cond="[x = !c]", code="action c := 1;")
            + arc("A1", "PtoT", "T1", "P1", "x"))
    path = write(tmp_path, COUNTER, body)
    text = translate_text(path.read_text(encoding="iso-8859-1"), "r.cpn").text
    assert "val c = ref (0);" in text and "action (c := 1)" in text
    engine = cpn.load(path).engine(simulation=True, reference=True)
    s, occurred = engine.initial_state(), []
    while succ := engine.successors(s, lazy=True):
        [(be, occur)] = succ  # one enabled at a time: the guard reads c
        occurred.append(engine.format_binding_element(be))
        s = occur()
    assert occurred == ["Top't 1: {x=0}", "Top't 1: {x=1}"]  # 1 only once the action has set c
    with pytest.raises(ModelError) as info:
        cpn.load(path).engine()
    found = sorted((d.code, d.params["name"], d.span.line) for d in info.value.diagnostics)
    xml = path.read_text(encoding="iso-8859-1").splitlines()
    line_of = {tag: next(i + 1 for i, x in enumerate(xml) if tag in x) for tag in ('<globref id="G1"', "action c")}
    assert [(c, n) for c, n, _ in found] == [("E0206", "action"), ("E0206", "ref")]
    assert {n: ln for _, n, ln in found} == {"ref": line_of['<globref id="G1"'], "action": line_of["action c"]}


def test_a_code_segment_with_outputs_that_reads_references_binds_them_at_each_occurrence(tmp_path):
    body = (place("P1", "A", "S", "1`0") + place("P2", "B", "INT")
            + trans("T1", "t", code="input (x);\noutput (y);\naction (c := !c + 1; !c mod 4);")
            + arc("A1", "PtoT", "T1", "P1", "x") + arc("A2", "TtoP", "T1", "P1", "x")
            + arc("A3", "TtoP", "T1", "P2", "y"))
    engine, s = fire(cpn.load(write(tmp_path, COUNTER, body)), 5)
    assert engine.format_marking(s, 1) == "1`0++2`1++1`2++1`3"  # !c mod 4 after each of 5 increments


def test_a_globref_the_net_never_names_is_left_out_and_the_net_explored(tmp_path):
    # assigned by a monitor's code only (a declaration no inscription uses): no reference in the net
    decls = COUNTER + '<ml id="M2">fun reset () = c := 0</ml>'
    body = place("P1", "A", "S", "1`0") + trans("T1", "t") + arc("A1", "PtoT", "T1", "P1", "x")
    engine = cpn.load(write(tmp_path, decls, body)).engine()
    assert len(engine.successors(engine.initial_state())) == 1


def test_a_code_segment_that_only_reads_references_binds_nothing_and_is_dropped(tmp_path):
    body = (place("P1", "A", "S", "1`0") + trans("T1", "t", code="input (x);\naction print (Int.toString (!c));")
            + arc("A1", "PtoT", "T1", "P1", "x"))
    path = write(tmp_path, COUNTER, body)
    text = translate_text(path.read_text(encoding="iso-8859-1"), "r.cpn").text
    assert not any(line.startswith("trans") and " action " in line for line in text.splitlines())
    engine = cpn.load(path).engine()
    assert len(engine.successors(engine.initial_state())) == 1
