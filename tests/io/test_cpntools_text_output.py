"""CPN Tools models that write text (TextIO, print) in a code segment that binds output variables or in a
declared function the net calls: they load, `simulate` runs them writing nothing, and `explore` refuses them
with one error per call of the library function, at it in the .cpn file (E0206)."""

from __future__ import annotations

import pytest

import cpn
from cpn.cli.main import main
from cpn.errors import ModelError
from tests.io.test_cpntools import DECLS, arc, cpn_xml, page, place, trans

LOG = '<ml id="M2">fun log s = let val f = TextIO.openAppend "t.log" in TextIO.output (f, s) end;</ml>'


def model(tmp_path):
    body = (place("P1", "A", "S", "1`0") + place("P2", "B", "S")
            + trans("T1", "t", cond='[log "t" = ()]',
                    code="input (x);\noutput (y);\naction (TextIO.print (Int.toString x); x + 1);")
            + arc("A1", "PtoT", "T1", "P1", "x") + arc("A2", "TtoP", "T1", "P2", "y"))
    path = tmp_path / "m.cpn"
    path.write_text(cpn_xml(DECLS + LOG, page("PG1", "Top", body)))
    return path


def test_text_output_in_a_code_segment_and_a_function_is_simulated(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    path = model(tmp_path)
    assert main(["simulate", str(path), "--steps", "3", "--seed", "1"]) == 0
    assert cpn.load(str(path)).net is not None
    assert not (tmp_path / "t.log").exists()


def test_explore_refuses_each_call_at_its_place_in_the_file(tmp_path):
    path = model(tmp_path)
    with pytest.raises(ModelError) as info:
        cpn.load(str(path)).engine()
    names = sorted(d.params["name"] for d in info.value.diagnostics)
    assert names == ["TextIO.openAppend", "TextIO.output", "TextIO.print"]
    lines = path.read_text().splitlines()
    for d in info.value.diagnostics:
        assert d.code == "E0206" and d.span.file == str(path)
        assert lines[d.span.line - 1][d.span.col - 1:].startswith(d.params["name"])
