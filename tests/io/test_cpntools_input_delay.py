"""A delay on an input arc (`c@+5` on an arc to a transition, CPN Tools' preempting time stamps) is imported
as it is written: the transition may remove the token up to 5 time units before its timestamp
(docs/semantics.md, Time). A double arc (BOTHDIR) with a delay is refused with one error at its
inscription; a delay on an input arc from an untimed place is the front end's error, at the arc's XML."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import ModelError
from tests.io.test_cpntools import DECLS, arc, cpn_xml, page, place, trans

TIMED = '<color id="C9"><id>TI</id><int/><timed/></color><var id="V9"><type><id>TI</id></type><id>c</id></var>'


def _net(tmp_path, annot: str, orient: str = "PtoT", colset: str = "TI"):
    """P1 holds 0 with timestamp 8; 'Go' takes it by an arc inscribed `annot`, 'Late' by `c` (`s` where
    the places hold the untimed colour set S)."""
    v = "c" if colset == "TI" else "s"
    body = (place("P1", "A", colset, "1`0@+8" if colset == "TI" else "1`0") + place("P2", "B", colset)
            + trans("T1", "Go") + trans("T2", "Late")
            + arc("A1", orient, "T1", "P1", annot) + arc("A2", "TtoP", "T1", "P2", f"({v} + 1) mod 4")
            + arc("A3", "PtoT", "T2", "P1", v) + arc("A4", "TtoP", "T2", "P2", v))
    model = tmp_path / "m.cpn"
    model.write_text(cpn_xml(DECLS + TIMED + '<var id="V8"><type><id>S</id></type><id>s</id></var>',
                             page("PG1", "Top", body)))
    return model


def test_a_delay_on_an_input_arc_lets_the_transition_take_the_token_early(tmp_path):
    model = cpn.load(str(_net(tmp_path, "c@+5")))
    go = model.net.transition("Top'Go 1")
    assert [a.preemption for a in go.arcs] == [5, 0]
    for reference in (False, True):
        e = model.engine(reference=reference)
        succ = e.successors(e.initial_state())
        # the help's example: the token is stamped 8; 'Go' (c@+5) occurs at 3, 'Late' (c) would wait until 8
        assert [(e.format_binding_element(be), e.clock(t), e.marking(t)) for be, t in succ] == \
            [("Top'Go 1: {c=0}", 3, [{}, {(1, 3): 1}])]


def test_an_input_arc_without_a_delay_waits_for_the_timestamp(tmp_path):
    model = cpn.load(str(_net(tmp_path, "c")))
    e = model.engine()
    succ = e.successors(e.initial_state())
    assert sorted((e.format_binding_element(be), e.clock(t)) for be, t in succ) == \
        [("Top'Go 1: {c=0}", 8), ("Top'Late 1: {c=0}", 8)]


def test_a_double_arc_with_a_delay_is_one_error_naming_it(tmp_path):
    with pytest.raises(ModelError) as exc:
        cpn.load(str(_net(tmp_path, "c@+5", orient="BOTHDIR")))
    errors = [d for d in exc.value.diagnostics if d.code.startswith("E")]
    assert [d.code for d in errors] == ["E0502"]
    assert "double arc with a time delay" in errors[0].message and "'c@+5'" in errors[0].message
    assert "two arcs" in errors[0].hint


def test_a_delay_on_an_input_arc_from_an_untimed_place_is_refused_at_the_arc(tmp_path):
    path = _net(tmp_path, "s@+5", colset="S")
    with pytest.raises(ModelError) as exc:
        cpn.load(str(path))
    errors = [d for d in exc.value.diagnostics if d.code.startswith("E")]
    assert [d.code for d in errors] == ["E0301"]  # and no echo about the variable the arc binds
    assert "not timed" in errors[0].message and errors[0].span.file == str(path)
    assert "timed" in errors[0].hint
