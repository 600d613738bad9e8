"""`val x = 1;;` in a CPN Tools declaration (nets written by the XPDL converter end declarations so): SML
reads the second ';' as an empty declaration, and so do we; the positions after it do not move."""

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
