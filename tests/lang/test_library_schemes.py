"""The library's type schemes are read once per process and shared by every checker: a scheme is only
instantiated, so a use at one type in one model does not bind its variables for another."""

import cpn
from cpn.lang import types as T
from cpn.lang.builtins import parse_type


def test_a_library_type_text_is_read_once_and_instantiated_fresh():
    s = parse_type("'a list -> 'a")
    assert parse_type("'a list -> 'a") is s and len(s.vars) == 1
    a, b = s.instantiate(), s.instantiate()
    assert isinstance(a, T.TFun) and T.prune(a.res) is not T.prune(b.res)


def test_models_that_use_one_library_function_at_two_types_both_check():
    ints = cpn.loads("colset I = int; colset L = list I; var l : L; place P : L = 1`[1, 2]; place Q : I;"
                     " trans t [hd l > 0]; arc P -> t : l; arc t -> Q : hd l;")
    strings = cpn.loads('colset S = string; colset L = list S; var l : L; place P : L = 1`["a"]; place Q : S;'
                        ' trans t [hd l <> ""]; arc P -> t : l; arc t -> Q : hd l;')
    marked = []
    for model in (ints, strings):
        e = model.engine()
        [(_, s)] = e.successors(e.initial_state())
        marked.append(e.marking(s)[1])
    assert marked == [{1: 1}, {"a": 1}]
    assert T.prune(parse_type("'a list -> 'a").vars[0]) is parse_type("'a list -> 'a").vars[0]  # never bound
