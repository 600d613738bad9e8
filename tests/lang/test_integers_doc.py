"""docs/language.md and docs/cpnml.md, "Integers": `int` is unbounded, `intinf` is the same type, `div` and
`mod` round towards minus infinity; each example value of the pages is computed by the engine."""

import pathlib
import re

import pytest

import cpn
from cpn.errors import ModelError

ROOT = pathlib.Path(__file__).resolve().parents[2]


def _section(doc: str, heading: str) -> str:
    text = (ROOT / "docs" / doc).read_text(encoding="utf-8")
    start = text.index(heading)
    end = text.find("\n#", start + len(heading))
    return text[start:end if end >= 0 else len(text)]


def _value(expr: str) -> int:
    m = cpn.loads(f"net J;\ncolset I = int;\nval x = {expr};\nplace P : I = 1`x;\n")
    e = m.engine()
    (marking,) = e.marking(e.initial_state())
    (v,) = marking
    return v


def _ml_int(text: str) -> int:
    return int(text.replace(",", "").replace("~", "-"))


_NUMBER = r"(~?\d(?:[\d,]*\d)?)"
# "`e` is `v`", "`val X = e;` is v" (language.md) and "`e = v`" (cpnml.md)
_IS = re.compile(r"`(?:val \w+ = )?([^`;=]*\d[^`;=]*?);?`\s+is\s+`?" + _NUMBER)
_EQ = re.compile(r"`([^`=]+?) = " + _NUMBER + "`")
EXAMPLES = [(m.group(1).strip(), m.group(2))
            for doc, heading in (("language.md", "### Integers"), ("cpnml.md", "## Integers"))
            for pattern in (_IS, _EQ) for m in pattern.finditer(_section(doc, heading))]


def test_the_pages_give_examples():
    assert len(EXAMPLES) >= 5, EXAMPLES


@pytest.mark.parametrize("expr, value", EXAMPLES)
def test_each_documented_value(expr, value):
    assert _value(expr) == _ml_int(value)


def test_int_is_unbounded_and_intinf_is_the_same_type():
    assert _value("1073741823 * 1073741823 * 1073741823") == 1073741823 ** 3
    m = cpn.loads("net J;\ncolset II = intinf;\nval a : II = 5;\nval b : int = a * 1000000000000;\n"
                  "colset I = int;\nplace P : I = 1`b;\n")
    e = m.engine()
    assert e.marking(e.initial_state()) == [{5000000000000: 1}]
    for doc, heading in (("language.md", "### Integers"), ("cpnml.md", "## Integers")):
        assert "unbounded" in _section(doc, heading)


def test_all_of_an_unbounded_int_is_an_error():
    with pytest.raises(ModelError) as info:
        cpn.loads("net J;\ncolset I = int;\nplace P : I = I.all();\n")
    assert info.value.diagnostics[0].code == "E0401"
