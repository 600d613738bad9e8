"""PNML writing: read-write-read gives the same net (the same .cpnet text, hence the same state space)."""

from __future__ import annotations

import glob
import os

import pytest

from cpn.errors import ModelError
from cpn.io.pnml import translate, translate_text, write, write_text

VALIDATION = os.environ.get("CPN_VALIDATION_DIR", "/work/shared/validation")
CORPUS = sorted(glob.glob(os.path.join(VALIDATION, "*", "model.pnml")))


def _body(text: str) -> list[str]:
    return text.splitlines()[1:]  # the first line is a comment naming the source file


@pytest.mark.skipif(not CORPUS, reason="validation corpus not found")
@pytest.mark.parametrize("path", CORPUS, ids=lambda p: os.path.basename(os.path.dirname(p)))
def test_read_write_read_is_the_same_net(path, tmp_path):
    first = translate(path)
    out = tmp_path / "again.pnml"
    write(first, out)
    assert _body(translate(out)) == _body(first)


def test_pt_writer_output():
    text = write_text("colset DOT = unit;\nplace p : DOT = 2`();\nplace q : DOT;\ntrans t;\n"
                      "arc p -> t : 2`();\narc t -> q;\ninhibitor q -> t : 3`();\nreset p -> t;\n", net_id="n")
    assert 'type="http://www.pnml.org/version-2009/grammar/ptnet"' in text
    assert "<initialMarking><text>2</text></initialMarking>" in text
    assert '<arc id="a1" source="p" target="t"><inscription><text>2</text></inscription></arc>' in text
    assert '<arc id="a3" source="q" target="t"><inscription><text>3</text></inscription><type value="inhibitor"/></arc>' in text
    again = translate_text(text)
    assert "place p : DOT = 2`();" in again and "inhibitor q -> t : 3`();" in again and "reset p -> t;" in again


def test_double_arc_is_written_as_two_arcs():
    text = write_text("colset C = with a | b;\nvar x : C;\nplace p : C = C.all();\ntrans t [x <> a];\n"
                      "arc p <-> t : x;\n")
    again = translate_text(text)
    assert "arc p -> t : 1`x;" in again and "arc t -> p : 1`x;" in again
    assert "trans t [x <> a];" in again
    assert "place p : C = C.all();" in again


def test_nets_outside_pnml_are_refused_with_positions():
    src = ("colset S = string;\nvar s : S;\nplace p : S = 1`\"a\";\ntrans t @+ 5;\narc p -> t : s;\n"
           "arc t -> p : s ^ \"b\";\n")
    with pytest.raises(ModelError) as info:
        write_text(src)
    diags = info.value.diagnostics
    assert {d.code for d in diags} == {"E0502"}
    lines = sorted(d.span.line for d in diags)
    assert 1 in lines and 4 in lines and 6 in lines
