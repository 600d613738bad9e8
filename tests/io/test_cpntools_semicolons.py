"""Declarations of CPN Tools nets as people and tools write them. `val x = 1;;` (the XPDL converter ends
declarations so): SML reads the second ';' as an empty declaration, and so do we; the positions after it
do not move. `colset s = unit with student`: a colour set of one named colour."""

from __future__ import annotations

import cpn
from tests.io.test_cpntools import DECLS, arc, cpn_xml, page, place, trans


def test_a_double_semicolon_ends_a_declaration(tmp_path):
    decls = DECLS + '<ml id="M2">val K = 2;;</ml><ml id="M3">val L = ";;";;\nfun f x = (x + K) mod 4;;</ml>'
    body = (place("P1", "A", "S", "1`0") + trans("T1", "t", cond='[L = ";;"]') + arc("A1", "PtoT", "T1", "P1", "x")
            + arc("A2", "TtoP", "T1", "P1", "f x"))
    path = tmp_path / "m.cpn"
    path.write_text(cpn_xml(decls, page("PG1", "Top", body)))
    e = cpn.load(path).engine()
    [(_, s)] = e.successors(e.initial_state())
    assert e.format_marking(s, 0) == "1`2"


def test_a_unit_colour_set_with_a_named_value(tmp_path):
    # CPN Tools' `colset s = unit with student`: one colour, written `student` (the name of a distribution too)
    decls = DECLS + ('<color id="C8"><id>s</id><unit><with><id>student</id></with></unit></color>'
                     '<var id="V2"><type><id>s</id></type><id>z</id></var><ml id="M2">val two = 2`student;</ml>')
    body = (place("P1", "A", "s", "two") + place("P2", "B", "s") + trans("T1", "t")
            + arc("A1", "PtoT", "T1", "P1", "z") + arc("A2", "TtoP", "T1", "P2", "z"))
    path = tmp_path / "m.cpn"
    path.write_text(cpn_xml(decls, page("PG1", "Top", body)))
    model = cpn.load(path)
    assert not [w for w in model.warnings if w.code == "W0105"]
    e = model.engine()
    [(_, s)] = e.successors(e.initial_state())
    assert (e.format_marking(s, 0), e.format_marking(s, 1)) == ("1`student", "1`student")
