"""SML's `val rec f = fn ... => ... | ...`, at the top level and inside `let` (CPN Tools models written by
converters use it): the function `fun f ... | f ...`, in `.cpnet` and `.cpn` files (docs/cpnml.md)."""

from __future__ import annotations

import cpn
from cpn.io.cpntools import translate_text

DECLS = """colset INT = int;
colset IL = list INT;
var x : INT;
"""

MODEL = DECLS + """val rec len = fn [] => 0 | _ :: t => 1 + len t;
fun sum l = let val rec s = fn [] => 0 | h :: t => h + s t
                val k = 1
            in s l + k - 1 end;
place P : INT = 1`0; place Q : INT; trans T; arc P -> T : x; arc T -> Q : len [4, 5, 6] * 10 + sum [1, 2];
"""


def test_val_rec_is_a_recursive_function_at_the_top_level_and_in_let():
    e = cpn.loads(MODEL, "t.cpnet").engine()
    [(_be, s1)] = list(e.successors(e.initial_state()))
    assert e.format_marking(s1, 1) == "1`33"


CPN = """<?xml version="1.0" encoding="iso-8859-1"?>
<workspaceElements><cpnet>
<globbox>
<color id="c1"><id>INT</id><int/></color>
<var id="v1"><type><id>INT</id></type><id>x</id></var>
<ml id="m1">val rec count = fn [] =&gt; 0 | _ :: t =&gt; 1 + count t</ml>
</globbox>
<page id="pg"><pageattr name="Top"/>
<place id="p1"><text>P</text><type><text>INT</text></type><initmark><text>1`0</text></initmark></place>
<place id="p2"><text>Q</text><type><text>INT</text></type></place>
<trans id="t1"><text>T</text></trans>
<arc id="a1" orientation="PtoT"><transend idref="t1"/><placeend idref="p1"/><annot><text>x</text></annot></arc>
<arc id="a2" orientation="TtoP"><transend idref="t1"/><placeend idref="p2"/><annot><text>count [7, 8]</text></annot></arc>
</page>
<instances><instance id="i1" page="pg"/></instances>
</cpnet></workspaceElements>
"""


def test_val_rec_in_a_cpn_file_is_kept_as_the_function_the_net_uses():
    text = translate_text(CPN).text
    assert "val rec count" in text
    e = cpn.loads(text, "t.cpnet").engine()
    [(_be, s1)] = list(e.successors(e.initial_state()))
    assert e.format_marking(s1, 1) == "1`2"
