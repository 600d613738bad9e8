"""CPN Tools' option realtimestamp makes the model time a real: `time ()` is a real there (a token
`("car", time ())` of a `string * real` colour set, the fuel-station models) and `ModelTime.toString` takes
it; `=` on values holding reals is defined, as CPN Tools defines it on every colour set (`q = []`)."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import ModelError
from tests.io.test_cpntools import DECLS, arc, cpn_xml, page, place, trans

REAL_TIME = '<options><option name="realtimestamp"><value><boolean>true</boolean></value></option></options>'
COLSETS = ('<color id="C4"><id>R</id><real/></color><color id="C5"><id>STR</id><string/></color>'
           '<color id="C6"><id>Car</id><product><id>STR</id><id>R</id></product></color>'
           '<color id="C7"><id>Queue</id><list><id>Car</id></list></color>'
           '<var id="V2"><type><id>Queue</id></type><id>q</id></var>'
           '<ml id="M2">fun len (q : Queue) = if q = [] then 0 else 1 + len (tl q)</ml>')


def _net(out: str, out_cs: str = "Car") -> str:
    body = (place("P1", "Waiting", "Queue", "[]") + place("P2", "Out", out_cs) + place("P3", "Count", "INT")
            + trans("T1", "Arrive") + arc("A1", "PtoT", "T1", "P1", "q") + arc("A2", "TtoP", "T1", "P2", out)
            + arc("A3", "TtoP", "T1", "P3", "len q"))
    return page("PG1", "Top", body)


def test_time_is_a_real_with_realtimestamp(tmp_path):
    model = tmp_path / "m.cpn"
    model.write_text(cpn_xml(DECLS + COLSETS, _net('("car", time ())'), extra=REAL_TIME))
    engine = cpn.load(str(model)).engine()
    steps = list(engine.successors(engine.initial_state()))
    assert len(steps) == 1


def test_time_is_an_integer_without_the_option(tmp_path):
    model = tmp_path / "m.cpn"
    model.write_text(cpn_xml(DECLS + COLSETS, _net('("car", time ())')))
    with pytest.raises(ModelError) as exc:
        cpn.load(str(model))
    assert "E0301" in {d.code for d in exc.value.diagnostics}


def test_model_time_to_string_takes_the_real_time(tmp_path):
    model = tmp_path / "m.cpn"
    model.write_text(cpn_xml(DECLS + COLSETS, _net("ModelTime.toString (time ())", "STR"), extra=REAL_TIME))
    loaded = cpn.load(str(model))
    assert loaded.net is not None
