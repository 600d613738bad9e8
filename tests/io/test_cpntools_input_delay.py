"""A delay on an input arc (`c@+1000` on an arc to a transition, CPN Tools' preemption) is refused with one
error at the inscription that names the construct, not followed by errors about the variables that the
refused arc would have bound."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import ModelError
from tests.io.test_cpntools import DECLS, arc, cpn_xml, page, place, trans

TIMED = '<color id="C9"><id>TI</id><int/><timed/></color><var id="V9"><type><id>TI</id></type><id>c</id></var>'


def _net(tmp_path, annot: str):
    body = (place("P1", "A", "TI", "1`0") + place("P2", "B", "TI") + trans("T1", "Go")
            + arc("A1", "PtoT", "T1", "P1", annot) + arc("A2", "TtoP", "T1", "P2", "c + 1"))
    model = tmp_path / "m.cpn"
    model.write_text(cpn_xml(DECLS + TIMED, page("PG1", "Top", body)))
    return model


def test_a_delay_on_an_input_arc_is_one_error_naming_it(tmp_path):
    with pytest.raises(ModelError) as exc:
        cpn.load(str(_net(tmp_path, "c@+1000")))
    errors = [d for d in exc.value.diagnostics if d.code.startswith("E")]
    assert [d.code for d in errors] == ["E0502"]
    assert "delays on input arcs" in errors[0].message and "'c@+1000'" in errors[0].message


def test_an_input_arc_without_a_delay_loads(tmp_path):
    assert cpn.load(str(_net(tmp_path, "c"))).net is not None
