"""The compiled engine against the reference interpreter on the Standard ML forms and library that CPN Tools
models compute with (docs/cpnml.md): `val rec`, CPN Tools' list library, `empty` beside a list, `option`,
`order` and `Date`; `datatype`; the colour sets `bool with (no, yes)` and `string with "a".."z" and m..n`."""

import pytest

import cpn
from tests.engine.test_differential import _compare

CASES = {
    "val_rec_and_list_library": """
colset C = int with 0..3;
colset L = list C;
var x : C;
var l : L;
val rec len = fn [] => 0 | _ :: t => 1 + len t;
fun drop (y : C) (m : L) = if m = [] then empty else if hd m = y then drop y (tl m) else hd m :: drop y (tl m);
place P : L = 1`[0, 1, 2, 1];
place N : C;
trans T [len l > 1];
arc P -> T : l;
arc T -> P : listsub (union (intersect l [1, 2]) (remdupl (rmall 0 l))) [hd (filter (fn y => y > 0) l)];
arc T -> N : len (drop 1 l) mod 4;
""",
    "option_order_date": """
colset C = int with 0..3;
colset S = string;
var x : C;
val start = Date.date {day = 31, hour = 23, minute = 59, month = Date.Dec, offset = NONE, second = 59, year = 1999};
fun later (s : C) = Date.date {day = Date.day start, hour = Date.hour start, minute = Date.minute start,
  month = Date.month start, offset = Date.offset start, second = Date.second start + s, year = Date.year start};
fun num (SOME n) = n | num NONE = 0;
place P : C = 1`0;
place Q : S;
trans T [x < 3 andalso Date.compare (later x, start) <> LESS andalso Int.compare (x, 3) = LESS];
arc P -> T : x;
arc T -> P : (x + num (Int.fromString (Int.toString x)) + Option.getOpt (Int.fromString "1", 0)) mod 4;
arc T -> Q : Date.fmt "%Y-%m-%d %H:%M:%S" (later x) ^ (case Date.month (later x) of Date.Jan => " Jan" | _ => "");
""",
    "bool_and_string_with": """
colset Answer = bool with (no, yes);
colset Lower = string with "a".."c" and 0..3;
var a : Answer;
var s : Lower;
fun flip no = yes | flip yes = no;
place P : Answer = 1`no ++ 1`yes;
place Q : Lower = 1`"" ++ 1`"b";
trans T [not a orelse String.size s < 2];
arc P -> T : a;
arc Q -> T : s;
arc T -> P : flip a;
arc T -> Q : if a = yes then s ^ "a" else s;
""",
    "datatype": """
colset C = int with 0..3;
datatype Msg = Ping | Data of C;
var m : Msg;
fun next Ping = Data 0 | next (Data n) = if n < 3 then Data (n + 1) else Ping;
place P : Msg = 1`Ping ++ 1`(Data 2);
trans T [m <> Data 1];
arc P -> T : m;
arc T -> P : next m;
""",
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_engines_agree(name):
    model = cpn.loads(CASES[name], f"{name}.cpnet")
    _compare(model, condensation=False, limit=80)
