"""Strings in the generated C (`ctables.StrDom`: a string is the list of its characters' codes, interned):
tokens, variables, strings in products, literals and constants, `^`, `String.size`, `=` and `<>`. The native
search's graph must be the Python search's own, with every transition in C (the engine expands no state);
a restricted colour set (`string with "a".."z" and 1..5`) is the strings' domain with its tokens checked in C;
what C does not evaluate (the other string functions) stays with the engine, transition by transition."""

import os

import pytest

import cpn
from cpn.statespace import ExploreOptions, Explorer
from cpn.statespace.store import packed_unavailable
from tests.engine._explore import same_exploration
from tests.statespace._native import both_searches, same_error, wholly_in_c

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(__file__)))
NATIVE = packed_unavailable()
pytestmark = pytest.mark.skipif(NATIVE is not None, reason=f"native code unavailable: {NATIVE}")
STRINGS = os.path.join(ROOT, "tests", "statespace", "models", "strings_timed.cpnet")


@pytest.mark.parametrize("condensation", [False, True], ids=["timed", "condensed"])
def test_a_timed_net_of_strings_runs_wholly_in_c(condensation, fills):
    model = cpn.load(STRINGS)
    wholly_in_c(model)
    c = both_searches(model.engine(time_condensation=condensation), model.engine(time_condensation=condensation))
    assert c.complete and c.notes == [] and fills[0] == 0
    assert c.n_states == 131  # with and without condensation alike


def test_the_untimed_net_of_strings_runs_wholly_in_c():
    text = open(STRINGS, encoding="utf-8").read().replace(" timed;", ";").replace(" @+ 1", "").replace(
        " @+ 2", "").replace(" @+ 3", "")
    model = cpn.loads(text, "strings.cpnet")
    wholly_in_c(model)
    engine = model.engine()
    c = both_searches(engine, model.engine())
    words = {v for s in c.graph.states for v in engine.marking(s)[0]}
    assert c.complete and {"", "ab", "he", "abc", "hec"} <= words


def test_characters_beyond_ascii_and_the_empty_string_round_trip():
    text = ('colset S = string; var x : S;\nplace P : S = 1`"\u00e9t\u00e9" ++ 1`"";\n'
            'trans t [String.size x < 4]; arc P -> t : x; arc t -> P : x ^ "\u00e0";')
    model = cpn.loads(text, "u.cpnet")
    wholly_in_c(model)
    engine = model.engine()
    c = both_searches(engine, model.engine())
    assert {v for s in c.graph.states for v in engine.marking(s)[0]} >= {"", "\u00e9t\u00e9\u00e0"}


RESTRICTED = {
    # tokens of a restricted colour set made in C, checked there (length and characters)
    "tokens": 'colset S = string with "a".."c" and 0..3; var x : S;\nplace P : S = 1`"a" ++ 1`"";\n'
              'trans t [String.size x < 3]; arc P -> t : x; arc t -> P : x ^ "b";',
    # a guard binds a restricted string: only the members of its colour set bind it ("bz" and "abcd" do not)
    "guard": 'colset S = string with "a".."c" and 1..3; colset T = string; var x : S; var y : T;\n'
             'place P : T = 1`"a" ++ 1`"bz" ++ 1`"abcd" ++ 1`"cc";\nplace Q : S;\n'
             'trans t [x = y]; arc P -> t : y; arc t -> Q : x;',
    # in a product, timed
    "timed": 'colset S = string with "a".."b" and 0..2; colset I = int with 0..3;'
             ' colset P = product S * I timed; var x : S; var i : I;\nplace A : P = 1`("", 0);\n'
             'trans t [i < 3 andalso String.size x < 2] @+ 1; arc A -> t : (x, i);'
             ' arc t -> A : (x ^ "a", i + 1) ++ (x ^ "b", i + 1) @+ 1;',
}


@pytest.mark.parametrize("name", sorted(RESTRICTED))
def test_a_restricted_string_colour_set_runs_wholly_in_c(name, fills):
    model = cpn.loads(RESTRICTED[name], f"{name}.cpnet")
    wholly_in_c(model)
    engine = model.engine()
    c = both_searches(engine, model.engine())
    assert c.complete and c.notes == [] and fills[0] == 0
    if name == "guard":
        words = {v for s in c.graph.states for v in engine.marking(s)[1]}
        assert words == {"a", "cc"} and c.n_states == 4


def test_a_string_outside_its_colour_set_is_the_same_error_in_c():
    model = cpn.loads('colset S = string with "a".."c"; var x : S;\nplace P : S = 1`"a";\n'
                      'trans t [String.size x < 3]; arc P -> t : x; arc t -> P : x ^ "z";', "bad.cpnet")
    assert 'puts "az" on place' in same_error(model)


def test_a_string_function_c_does_not_know_stays_with_the_engine():
    text = ("colset S = string; var x : S;\nplace P : S = 1`\"ab\";\n"
            "trans t [String.size x < 4]; arc P -> t : x; arc t -> P : x ^ Int.toString (String.size x);")
    model = cpn.loads(text, "left.cpnet")
    code, why = model.engine().native_code()
    assert (why is not None) or code.left, "the transition should be left to the engine"
    c = Explorer(model.engine(), ExploreOptions(backend="auto")).run()
    py = Explorer(model.engine(), ExploreOptions(backend="python", packed_states=False)).run()
    same_exploration(c, py)
