"""PNML writing: read-write-read gives the same net (the same .cpnet text, hence the same state space)."""

from __future__ import annotations

import glob
import os

import pytest

from cpn.errors import ModelError
from cpn.io.pnml import translate, translate_text, write, write_text
from tests._shared import SHARED, needs_shared

VALIDATION = os.environ.get("CPN_VALIDATION_DIR", SHARED + "/validation")
CORPUS = sorted(glob.glob(os.path.join(VALIDATION, "*", "model.pnml")))


def _body(text: str) -> list[str]:
    return text.splitlines()[1:]  # the first line is a comment naming the source file


@needs_shared
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


# ---------------------------------------------------------------------- same state space

def _figures(path):
    import cpn
    from cpn.cli.validate import explore_figures

    f = explore_figures(cpn.load(str(path)).engine())
    return (f.states, f.arcs, f.max_tokens_per_marking, f.max_of_one_colour_in_place, f.dead_markings,
            f.properties)


SMALL = ["TokenRing-COL-005", "DatabaseWithMutex-COL-02", "Sudoku-COL-AN02", "BridgeAndVehicles-COL-V04P05N02",
         "ResAllocation-PT-R003C005", "IBM319-PT-none"]


@needs_shared
@pytest.mark.parametrize("name", SMALL)
def test_written_pnml_has_the_same_state_space(name, tmp_path):
    src = os.path.join(VALIDATION, name, "model.pnml")
    out = tmp_path / "again.pnml"
    write(translate(src), out)
    assert _figures(out) == _figures(src)


CPNET = """
colset PH = with p0 | p1 | p2 | p3;
colset R = int with 1..3;
colset PR = product PH * R;
var p, q : PH;
var r : R;
place Think : PH = PH.all();
place Fork : PH = PH.all();
place Eat : PR;
place Count : R = 1`1;
trans Take [PH.ord p < 3];
trans TakeLast [p = p3];
trans Put;
arc Think -> Take : p;
arc Fork -> Take : p ++ PH.col ((PH.ord p + 1) mod 4);
arc Count -> Take : r;
arc Take -> Count : if r = 3 then 1 else r + 1;
arc Take -> Eat : (p, r);
arc Think -> TakeLast : p;
arc Fork -> TakeLast : p ++ PH.col ((PH.ord p + 1) mod 4);
arc TakeLast -> Eat : (p, 1);
arc Eat -> Put : (p, r);
arc Put -> Think : p;
arc Put -> Fork : p ++ PH.col ((PH.ord p + 1) mod 4);
"""


def test_cpnet_model_written_and_read_back_has_the_same_state_space(tmp_path):
    src = tmp_path / "phil.cpnet"
    src.write_text(CPNET)
    out = tmp_path / "phil.pnml"
    write(src, out)
    text = out.read_text()
    assert "<successor>" in text and "<lessthan>" in text and "<finiteintrange" in text
    assert _figures(out) == _figures(src)


HIERARCHICAL = """
colset U = unit;
module Stage {
  port in  In  : U;
  port out Out : U;
  place Busy : U;
  trans start;
  trans stop;
  arc In -> start;
  arc start -> Busy;
  arc Busy -> stop;
  arc stop -> Out : 2`();
}
place A : U = 2`();
place B : U;
place C : U;
instance S1 = Stage { In = A, Out = B };
instance S2 = Stage { In = B, Out = C };
"""


def test_net_with_modules_is_written_flattened_as_a_pt_net(tmp_path):
    import cpn

    model = cpn.loads(HIERARCHICAL, "stages.cpnet")
    out = tmp_path / "stages.pnml"
    write(model, out)
    text = out.read_text()
    assert "ptnet" in text and "<text>Stage'Busy 2</text>" in text
    assert _figures(out) == _figures_of(model)
    with pytest.raises(ModelError) as info:
        write_text(HIERARCHICAL)
    assert info.value.diagnostics[0].code == "E0502"


def _figures_of(model):
    from cpn.cli.validate import explore_figures

    f = explore_figures(model.engine())
    return (f.states, f.arcs, f.max_tokens_per_marking, f.max_of_one_colour_in_place, f.dead_markings,
            f.properties)


@needs_shared
def test_flat_net_object_is_written(tmp_path):
    import cpn

    if not hasattr(cpn, "load"):
        pytest.skip("cpn.load does not exist yet")
    src = os.path.join(VALIDATION, "TokenRing-COL-005", "model.pnml")
    model = cpn.load(src)
    out = tmp_path / "tr.pnml"
    write(model.net, out)
    assert _figures(out) == _figures(src)
