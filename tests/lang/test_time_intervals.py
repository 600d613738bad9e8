"""CPN Tools 4's time intervals `@+[a,b]` on transitions and output arcs: the delay is chosen in the
binding, one binding element per integer of a..b, so the state space stays exhaustive (docs/semantics.md)."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import ModelError

DECLS = """colset C = int with 0..2 timed;
colset U = unit timed;
var x : C;
val HI = 2;
"""


def space(text: str) -> tuple[int, int]:
    e = cpn.loads(DECLS + text, "t.cpnet").engine()
    s0 = e.initial_state()
    seen, frontier, arcs = {s0}, [s0], 0
    while frontier:
        nxt = []
        for s in frontier:
            for _be, s1 in e.successors(s):
                arcs += 1
                if s1 not in seen:
                    seen.add(s1)
                    nxt.append(s1)
        frontier = nxt
    return len(seen), arcs


def test_a_transition_interval_is_one_binding_per_delay():
    # 0@0 -> 1@1 | 1@2 (clock 0); then 2@2, 2@3 (clock 1) and 2@3, 2@4 (clock 2): 7 states, 6 arcs
    assert space("place P : C = 1`0;\ntrans T [x < 2] @+[1,HI];\narc P -> T : x;\narc T -> P : x + 1;") == (7, 6)


def test_an_arc_interval_is_one_binding_per_delay():
    e = cpn.loads(DECLS + "place Q : U = 1`();\nplace R : U;\ntrans V;\narc Q -> V : ();\n"
                  "arc V -> R : () @+[0, 3];", "t.cpnet").engine()
    succ = list(e.successors(e.initial_state()))
    assert len(succ) == 4 and len({s for _, s in succ}) == 4


@pytest.mark.parametrize("text, fragment", [
    ("place P : C = 1`0;\ntrans T @+[x, 2];\narc P -> T : x;\narc T -> P : x;", "depends on the binding"),
    ("place P : C = 1`0;\ntrans T @+[2, 1];\narc P -> T : x;\narc T -> P : x;", "0 <= a <= b"),
    ("place P : C = 1`0 @+[1, 2];", "only as a transition delay or on an output arc"),
])
def test_what_is_no_time_interval_is_one_error(text, fragment):
    with pytest.raises(ModelError) as info:
        cpn.loads(DECLS + text, "t.cpnet")
    [d] = info.value.diagnostics
    assert fragment in d.message
