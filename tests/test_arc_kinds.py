"""Arc kinds by their effects (cpn/arcs.py): the modules that read what an arc does ask the kind for an
effect, never for its name, so that an arc kind combining existing effects is declared in one place."""

import pathlib
import re

import pytest

import cpn
from cpn.arcs import EFFECTS, ArcKind

CPN = pathlib.Path(cpn.__file__).resolve().parent

# a kind named by its value or its member where one of its effects is meant
BY_NAME = re.compile(r"""\b(a|arc)\.kind\s*(==|!=|is|is not|in|not in)\s*(\(|\[|\{|"|'|ArcKind\.)""")


@pytest.mark.parametrize("module", ["engine/api.py", "engine/stubborn.py", "lang/pages.py", "report/msc.py",
                                    "report/verdicts.py"])
def test_the_modules_that_read_arc_effects_ask_the_kind(module):
    lines = [f"{module}:{i}: {line.strip()}" for i, line in enumerate((CPN / module).read_text().splitlines(), 1)
             if BY_NAME.search(line)]
    assert lines == []


def test_a_test_by_name_is_found():
    assert BY_NAME.search('if a.kind in ("in", "both"):')
    assert BY_NAME.search("if a.kind is ArcKind.INHIBITOR:")
    assert BY_NAME.search('resets = {a.place for a in t.arcs if a.kind == "reset"}')
    assert not BY_NAME.search("if a.kind.consumes and a.expr is not None:")


def test_every_kind_has_its_effects_declared_once():
    assert set(EFFECTS) == set(ArcKind)
    known = {"consumes", "produces", "blocks", "empties"}
    for kind, effects in EFFECTS.items():
        assert effects and effects <= known, kind
        assert {e for e in known if getattr(kind, e)} == effects
        assert kind.reads == bool(effects - {"produces"})
        assert kind.takes == bool(effects & {"consumes", "empties"})
    assert [k.value for k in ArcKind if k.takes] == ["in", "both", "reset"]
