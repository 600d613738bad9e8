"""Reference variables as CPN Tools models use them where they carry no state: `val x = ref 0` that nothing
assigns is the constant 0, and a variable that a code segment assigns (`action x := e`, e pure) and that only
the output arcs and the delay of the same transition read is an output variable of the code segment (CPN Tools
runs the action before it evaluates the output arcs). Read anywhere else, or assigned a random or
side-effecting value, it is a reference variable: simulated, refused by explore and check at the `ref` and at
the action (tests/io/test_cpntools_references.py)."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import ModelError
from cpn.io.cpntools import translate_text
from tests.io.test_cpntools import DECLS, arc, cpn_xml, page, place, trans

CODE = "input (x)\naction\nnext := (x + 1) mod 4"


def _net(decls: str, code: str = CODE, out: str = "(!next)", cond: str = "") -> str:
    body = (place("P1", "A", "S", "1`0") + trans("T1", "t", code=code, cond=cond)
            + arc("A1", "PtoT", "T1", "P1", "x") + arc("A2", "TtoP", "T1", "P1", out))
    return cpn_xml(DECLS + decls, page("PG1", "Top", body))


def _states(tmp_path, xml: str) -> int:
    model = tmp_path / "m.cpn"
    model.write_text(xml)
    engine = cpn.load(str(model)).engine()
    seen, todo = set(), [engine.initial_state()]
    while todo:
        s = todo.pop()
        if s in seen:
            continue
        seen.add(s)
        todo += [s1 for _be, s1 in engine.successors(s)]
    return len(seen)


def test_a_ref_assigned_by_the_code_segment_and_read_by_its_outputs_is_an_output_variable(tmp_path):
    xml = _net('<ml id="M2">val next = ref 0;</ml>')
    text = translate_text(xml).text
    assert "let val next = (x + 1) mod 4 in" in text
    assert all("ref" not in line.split("(*")[0] for line in text.splitlines())
    # A cycles 0 -> 1 -> 2 -> 3 -> 0: the value read is the one the occurrence assigned
    assert _states(tmp_path, xml) == 4


def test_a_ref_that_nothing_assigns_is_its_initial_value(tmp_path):
    decls = '<ml id="M2">val start = ref 2;</ml>'
    body = place("P1", "A", "S", "1`(!start)")
    model = tmp_path / "m.cpn"
    model.write_text(cpn_xml(DECLS + decls, page("PG1", "Top", body)))
    assert cpn.load(str(model)).net.places[0].initial == {2: 1}


def _refused_by_explore(tmp_path, xml: str) -> list[str]:
    model = tmp_path / "m.cpn"
    model.write_text(xml)
    with pytest.raises(ModelError) as exc:
        cpn.load(str(model)).engine()
    return sorted(d.params["name"] for d in exc.value.diagnostics)


def test_a_ref_read_by_the_guard_is_a_reference_variable(tmp_path):
    xml = _net('<ml id="M2">val next = ref 0;</ml>', cond="x &lt;&gt; (!next)")
    assert "action (next := (x + 1) mod 4)" in translate_text(xml).text
    assert _refused_by_explore(tmp_path, xml) == ["action", "ref"]


def test_a_ref_assigned_a_random_value_is_a_reference_variable(tmp_path):
    code = "input (x)\naction\nnext := discrete (0, 3)"
    xml = _net('<ml id="M2">val next = ref 0;</ml>', code=code)
    assert _refused_by_explore(tmp_path, xml) == ["action", "discrete", "ref"]


def test_a_globref_assigned_by_the_code_segment_and_read_by_its_outputs_is_an_output_variable(tmp_path):
    xml = _net('<globref id="G1"><id>next</id><ml>0</ml></globref>')
    assert "let val next = (x + 1) mod 4 in" in translate_text(xml).text
    assert _states(tmp_path, xml) == 4
