"""The Model Checking Contest's property files: the reader (`cpn.properties.contest`) and the answers of
`cpn-verify mcc` against the contest's published verdicts, on a sample of small instances (the whole
corpus is compared by `cpn-verify validate`)."""

from __future__ import annotations

import json
import os

import pytest

from cpn.cli.main import main
from cpn.cli.mcc import ContestModel, answer_file
from cpn.properties import contest as c
from tests._shared import SHARED, needs_shared

VALIDATION = os.environ.get("CPN_VALIDATION_DIR", SHARED + "/validation")

XML = """<?xml version="1.0"?>
<property-set xmlns="http://mcc.lip6.fr/">
  <property>
    <id>M-CTLFireability-00</id>
    <formula>
      <all-paths><until><before><is-fireable><transition>t</transition></is-fireable></before>
        <reach><integer-le><integer-constant>2</integer-constant><tokens-count><place>p</place><place>q</place>
        </tokens-count></integer-le></reach></until></all-paths>
    </formula>
  </property>
  <property><id>M-UpperBounds-01</id><formula><place-bound><place>p</place></place-bound></formula></property>
</property-set>
"""


def test_the_reader_builds_the_formula_tree():
    props = c.read_text(XML, "f.xml")
    assert [p.id for p in props] == ["M-CTLFireability-00", "M-UpperBounds-01"]
    assert [p.examination for p in props] == ["CTLFireability", "UpperBounds"]
    f = props[0].formula
    assert f == c.Quant("A", c.Temporal("U", (c.Fireable(("t",)), c.IntLe(c.IntConst(2), c.Tokens(("p", "q"))))))
    assert c.show(f) == "A (fireable(t) U 2 <= tokens(p, q))"
    assert c.is_ltl(f) and not c.is_state_formula(f)
    assert props[1].formula == c.PlaceBound(("p",))
    assert c.names_used(f) == ({"p", "q"}, {"t"})


def test_an_unknown_element_is_reported_at_its_line_and_column():
    bad = XML.replace("<integer-le>", "<integer-lt>").replace("</integer-le>", "</integer-lt>")
    with pytest.raises(c.ContestFormatError) as err:
        c.read_text(bad, "f.xml")
    d = err.value.diagnostics[0]
    assert (d.span.file, d.span.line) == ("f.xml", 7) and "integer-lt" in d.message
    with pytest.raises(c.ContestFormatError) as err:
        c.read_text("<property-set><property>", "g.xml")
    assert err.value.diagnostics[0].code == "E0501"


# the smallest instances of each kind; Philosophers-COL-000005 has two dead markings, where the contest's
# CTL reads paths as finite (CTLFireability-15) and its LTL as stuttering
SAMPLE = ["ERK-PT-000001", "ResAllocation-PT-R003C002", "Sudoku-COL-AN02", "Philosophers-COL-000005",
          "DatabaseWithMutex-COL-02"]


@needs_shared
@pytest.mark.parametrize("name", SAMPLE)
def test_the_answers_agree_with_the_published_verdicts(name):
    folder = os.path.join(VALIDATION, name)
    with open(os.path.join(folder, "formulas", "oracle.json"), encoding="utf-8") as fh:
        oracle = json.load(fh)["verdicts"]
    model = ContestModel.load(os.path.join(folder, "model.pnml"))
    wrong = []
    for exam, verdicts in oracle.items():
        for a in answer_file(model, os.path.join(folder, "formulas", f"{exam}.xml")):
            found = a.value if not isinstance(a.value, bool) else ("TRUE" if a.value else "FALSE")
            if found != verdicts[a.id]:
                wrong.append((a.id, verdicts[a.id], found))
    assert not wrong
    assert sum(map(len, oracle.values())) == 112


@needs_shared
def test_mcc_prints_one_line_per_formula_in_the_contests_format(capsys):
    folder = os.path.join(VALIDATION, "Philosophers-PT-000005")
    assert main(["mcc", os.path.join(folder, "model.pnml"), os.path.join(folder, "formulas", "UpperBounds.xml"),
                 "--stats"]) == 0
    out, err = capsys.readouterr()
    lines = out.splitlines()
    assert len(lines) == 16 and all(line.startswith("FORMULA Philosophers-PT-000005-UpperBounds-") for line in lines)
    with open(os.path.join(folder, "formulas", "oracle.json"), encoding="utf-8") as fh:
        oracle = json.load(fh)["verdicts"]["UpperBounds"]
    assert {line.split()[1]: int(line.split()[2]) for line in lines} == oracle
    assert "states generated" in err


@needs_shared
def test_reachability_stops_at_the_first_witness_and_a_limit_cannot_compute(capsys, tmp_path):
    folder = os.path.join(VALIDATION, "Philosophers-PT-000005")
    model = ContestModel.load(os.path.join(folder, "model.pnml"))
    xml = tmp_path / "r.xml"
    xml.write_text(XML.replace("M-CTL", "M-Reach").replace("<all-paths><until><before><is-fireable><transition>t"
                                                           "</transition></is-fireable></before>",
                                                           "<exists-path><finally>")
                   .replace("</reach></until></all-paths>", "</finally></exists-path>").replace("<reach>", "")
                   .replace("<place>p</place><place>q</place>", "<place>Catch1_1</place><place>Catch1_2</place>")
                   .replace("<place>p</place>", "<place>Eat_1</place>"))
    first = model.answer(c.read_file(str(xml))[0])
    assert first.value is True and first.states < 243  # 2 philosophers holding one fork: found early
    assert main(["mcc", os.path.join(folder, "model.pnml"), str(xml), "--max-states", "10"]) == 2
    out, err = capsys.readouterr()
    assert "FORMULA M-UpperBounds-01 CANNOT_COMPUTE" in out and "max-states" in err


@needs_shared
def test_a_place_the_model_lacks_is_reported_at_the_formula(tmp_path, capsys):
    folder = os.path.join(VALIDATION, "Philosophers-PT-000005")
    xml = tmp_path / "b.xml"
    xml.write_text(XML.replace("<place>p</place></place-bound>", "<place>Eat_9</place></place-bound>")
                   .replace("<place>q</place>", "<place>Eat_2</place>"))
    assert main(["mcc", os.path.join(folder, "model.pnml"), str(xml)]) == 65
    out, err = capsys.readouterr()
    assert not out  # nothing answered: every name is checked first, and every wrong one reported
    assert "b.xml:6:" in err and "transition 't'" in err and "place 'p'" in err
    assert "b.xml:11:" in err and "'Eat_9'" in err and "Did you mean 'Eat_" in err
