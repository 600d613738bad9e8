"""A name used above its declaration is unknown there, as in SML, and the hint says it is declared further
down (the XPDL converter's nets declare `startDate` below the function that uses it)."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import ModelError


@pytest.mark.parametrize("later", ["val later = 3;", "fun later () = 3;"])
def test_a_use_above_the_declaration_hints_that_it_is_declared_further_down(later):
    use = "later ()" if later.startswith("fun") else "later"
    with pytest.raises(ModelError) as info:
        cpn.loads(f"colset INT = int;\nfun f x = x + {use};\n{later}\nplace P : INT = 1`(f 1);\n", "t.cpnet")
    [d] = info.value.diagnostics
    assert (d.code, d.span.line, d.span.col) == ("E0201", 2, 15)
    assert "declared further down" in d.hint


def test_a_name_declared_nowhere_keeps_the_ordinary_hint():
    with pytest.raises(ModelError) as info:
        cpn.loads("colset INT = int;\nfun f x = x + zzz;\n", "t.cpnet")
    [d] = info.value.diagnostics
    assert "further down" not in (d.hint or "")
