"""The SML Basis Library's `option`, `order` and `Date` as CPN Tools models compute with them (docs/cpnml.md,
"Library"): values, types, patterns, and a model's own constructors of the same names."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import EvaluationError, ModelError

DECLS = """colset INT = int;
colset STRING = string;
colset SL = list STRING;
var x : INT;
"""


def strings_after_one_step(value: str, decls: str = "") -> str:
    text = DECLS + decls + f"place P : INT = 1`0; place Q : SL; trans T; arc P -> T : x; arc T -> Q : {value};"
    e = cpn.loads(text, "t.cpnet").engine()
    [(_be, s1)] = list(e.successors(e.initial_state()))
    return e.format_marking(s1, 1)


D2000 = "Date.date {day = 1, hour = 0, minute = 0, month = Date.Jan, offset = NONE, second = 0, year = 2000}"


@pytest.mark.parametrize("value, expected", [
    # Date.date normalises: 86,461 seconds are a day, a minute and a second
    ('[Date.fmt "%Y-%m-%dT%H:%M:%S" (Date.date {day = 1, hour = 0, minute = 0, month = Date.Jan, '
     'offset = NONE, second = 86461, year = 2000})]', '1`["2000-01-02T00:01:01"]'),
    (f"[Date.toString ({D2000})]", '1`["Sat Jan 01 00:00:00 2000"]'),
    (f"[Int.toString (Date.year ({D2000}) + Date.day ({D2000}))]", '1`["2001"]'),
    (f'[if Date.month ({D2000}) = Date.Jan andalso Date.compare ({D2000}, {D2000}) = EQUAL then "y" else "n"]',
     '1`["y"]'),
    ('[Int.toString (Option.getOpt (Int.fromString " ~12ab", 0)), Int.toString (getOpt (Int.fromString "x", 7))]',
     '1`["~12","7"]'),
    ('[case Int.fromString "42" of SOME n => Int.toString (n + 1) | NONE => "none"]', '1`["43"]'),
    ('[case String.compare ("a", "b") of LESS => "lt" | EQUAL => "eq" | GREATER => "gt"]', '1`["lt"]'),
    ('[if isSome (SOME 1) andalso not (Option.isSome (NONE : INT option)) then "y" else "n"]', '1`["y"]'),
])
def test_option_order_and_date(value, expected):
    assert strings_after_one_step(value) == expected


def test_a_date_needs_every_field_of_the_right_type():
    with pytest.raises(ModelError) as info:
        strings_after_one_step('[Date.toString (Date.date {day = 1, hour = 0, minute = 0, month = 1, '
                               'offset = NONE, second = 0, year = 2000})]')
    assert [d.code for d in info.value.diagnostics] == ["E0301"]


def test_val_of_none_is_a_run_time_error():
    with pytest.raises(EvaluationError) as info:
        strings_after_one_step('[Int.toString (valOf (Int.fromString "x"))]')
    assert "exception Option" in str(info.value)


def test_a_model_may_declare_constructors_named_as_the_library_s():
    decls = "colset Answer = with NONE | LESS;\n"
    assert strings_after_one_step('[if NONE = NONE then "y" else "n"]', decls) == '1`["y"]'
