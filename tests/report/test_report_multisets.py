"""Multi-set bounds in the text report (every line in the bound's column) and in JSON (terms with structured
values beside the CPN ML text); the bounds table aligned by display width after wide (CJK) characters."""

import json

import cpn
from cpn.diagnostics import display_width
from cpn.report import build_report, render_text, to_json
from cpn.statespace import Explorer

PAIRS = """net M;
colset K = with req | resp;
colset NO = int with 0..2;
colset PAIR = product K * NO;
colset REC = record kind:K * n:NO;
colset U = unit;
place P : PAIR = 1`(req,0) ++ 2`(resp,1) ++ 1`(resp,2);
place R : REC = 1`{kind=resp, n=2};
place E : U = 1`();
trans T;
arc E -> T : ();
"""


def _report(text, name="m.cpnet"):
    return build_report(Explorer(cpn.loads(text, name).engine()).run(), model="toy")


def test_a_multiset_bound_continues_in_its_column():
    text = render_text(_report(PAIRS))
    block = text[text.index("  Best Upper Multi-set Bounds"):text.index("  Best Lower Multi-set Bounds")]
    lines = block.splitlines()
    i = lines.index("     M'P 1")
    bound = lines[i + 1:i + 4]
    assert [ln.strip() for ln in bound] == ["1`(req,0)++", "2`(resp,1)++", "1`(resp,2)"]
    assert {len(ln) - len(ln.lstrip()) for ln in bound} == {25}, bound


def test_multiset_bounds_in_json_have_structured_terms_beside_the_text():
    d = json.loads(json.dumps(to_json(_report(PAIRS))))
    p = d["multiset_bounds"]["M'P 1"]
    assert p["upper"] == "1`(req,0)++2`(resp,1)++1`(resp,2)"
    assert p["upper_terms"] == [{"colour": "(req,0)", "value": ["req", 0], "count": 1},
                                {"colour": "(resp,1)", "value": ["resp", 1], "count": 2},
                                {"colour": "(resp,2)", "value": ["resp", 2], "count": 1}]
    assert p["lower_terms"] == p["upper_terms"]  # nothing fires that touches P
    r = d["multiset_bounds"]["M'R 1"]
    assert r["upper_terms"] == [{"colour": "{kind=resp,n=2}", "value": {"kind": "resp", "n": 2}, "count": 1}]
    e = d["multiset_bounds"]["M'E 1"]
    assert e["upper_terms"] == [{"colour": "()", "value": None, "count": 1}] and e["lower"] == "empty"
    assert e["lower_terms"] == []


def test_the_bounds_table_is_aligned_after_wide_characters():
    model = ('net W;\ncolset C = int with 0..2;\nplace "溢出" : C = 1`0;\nplace "Überlauf" : C = 1`1;\n'
             'place B : C;\ntrans T;\narc "溢出" -> T : 0;\narc T -> B : 0;\n')
    text = render_text(_report(model, "w.cpnet"))
    block = text[text.index("  Best Integer Bounds"):text.index("  Best Upper Multi-set Bounds")].splitlines()
    rows = [ln for ln in block if ln.startswith("     W'")]
    assert len(rows) == 3
    # the Upper column starts in the same terminal cell on every row
    cells = {display_width(row[:_upper_at(row)]) for row in rows}
    assert len(cells) == 1, rows


def _upper_at(row: str) -> int:
    """The index of the Upper column's first character: the first one after the name's instance number (' 1')
    and the spaces that follow it."""
    after = row.index(" 1 ") + 2
    return after + len(row[after:]) - len(row[after:].lstrip())


def test_the_sweep_line_json_has_the_same_terms():
    from cpn.report.sweep import sweep_to_json
    from cpn.statespace.sweep import SweepLine

    engine = cpn.loads(PAIRS, "m.cpnet").engine()
    d = sweep_to_json(SweepLine(engine, measure=lambda state: 0).run(), "toy")
    full = to_json(_report(PAIRS))
    for place in ("M'P 1", "M'R 1", "M'E 1"):
        assert d["multiset_bounds"][place] == full["multiset_bounds"][place]
