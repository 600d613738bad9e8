"""Strings in the generated C (`ctables.StrDom`: a string is the list of its characters' codes, interned):
tokens, variables, strings in products, literals and constants, `^`, `String.size`, `=` and `<>`. The native
search's graph must be the Python search's own, with every transition in C (the engine expands no state);
what C does not evaluate (a restricted string colour set, the other string functions) stays with the
engine, transition by transition."""

import os

import pytest

import cpn
from cpn.statespace import ExploreOptions, Explorer
from cpn.statespace.store import packed_unavailable
from tests.engine._explore import same_exploration
from tests.statespace._native import both_searches

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(__file__)))
NATIVE = packed_unavailable()
pytestmark = pytest.mark.skipif(NATIVE is not None, reason=f"native code unavailable: {NATIVE}")
STRINGS = os.path.join(ROOT, "tests", "statespace", "models", "strings_timed.cpnet")




@pytest.mark.parametrize("condensation", [False, True], ids=["timed", "condensed"])
def test_a_timed_net_of_strings_runs_wholly_in_c(condensation, fills):
    model = cpn.load(STRINGS)
    code, why = model.engine().timed_groups().native_code()
    assert why is None and code.left == {}
    c = both_searches(model.engine(time_condensation=condensation), model.engine(time_condensation=condensation))
    assert c.complete and c.notes == [] and fills[0] == 0
    assert c.n_states == 131  # with and without condensation alike


def test_the_untimed_net_of_strings_runs_wholly_in_c():
    text = open(STRINGS, encoding="utf-8").read().replace(" timed;", ";").replace(" @+ 1", "").replace(
        " @+ 2", "").replace(" @+ 3", "")
    model = cpn.loads(text, "strings.cpnet")
    code, why = model.engine().native_code()
    assert why is None and code.left == {}
    engine = model.engine()
    c = both_searches(engine, model.engine())
    words = {v for s in c.graph.states for v in engine.marking(s)[0]}
    assert c.complete and {"", "ab", "he", "abc", "hec"} <= words


def test_characters_beyond_ascii_and_the_empty_string_round_trip():
    text = ('colset S = string; var x : S;\nplace P : S = 1`"\u00e9t\u00e9" ++ 1`"";\n'
            'trans t [String.size x < 4]; arc P -> t : x; arc t -> P : x ^ "\u00e0";')
    model = cpn.loads(text, "u.cpnet")
    code, why = model.engine().native_code()
    assert why is None and code.left == {}
    engine = model.engine()
    c = both_searches(engine, model.engine())
    assert {v for s in c.graph.states for v in engine.marking(s)[0]} >= {"", "\u00e9t\u00e9\u00e0"}


@pytest.mark.parametrize("colset,use", [
    ('string with "a".."z"', 'x ^ "c"'),  # a restricted colour set: its members are the engine's to check
    ("string", "x ^ Int.toString (String.size x)"),  # a string function C does not know
])
def test_what_c_does_not_evaluate_stays_with_the_engine(colset, use):
    text = (f"colset S = {colset}; var x : S;\nplace P : S = 1`\"ab\";\n"
            f"trans t [String.size x < 4]; arc P -> t : x; arc t -> P : {use};")
    model = cpn.loads(text, "left.cpnet")
    code, why = model.engine().native_code()
    assert (why is not None) or code.left, "the transition should be left to the engine"
    c = Explorer(model.engine(), ExploreOptions(backend="auto")).run()
    py = Explorer(model.engine(), ExploreOptions(backend="python", packed_states=False)).run()
    same_exploration(c, py)
