"""Record patterns with `...`, field punning, type annotations inside record fields."""

import pytest

import cpn
from cpn.expr.pretty import pat as pretty_pat
from cpn.lang.parser import parse
from tests._models import figures


@pytest.mark.parametrize("name", ["records.cpnet", "records.cpn"])
@pytest.mark.parametrize("reference", [False, True])
def test_the_records_model_has_its_hand_checked_figures(name, reference):
    # only {seq=1,data=2} passes the guard: 2 states, 1 arc, 1 dead marking
    assert figures(name, reference=reference) == (2, 1, 1)


@pytest.mark.parametrize("src,value", [("fun g ({seq = s, ...} : R) = s;", 2), ("fun g ({seq = s ...} : R) = s;", 2),
                                       ("fun g ({seq : C, ...} : R) = seq;", 2), ("fun g ({...} : R) = 1;", 1),
                                       ("fun g {seq, data} = seq + data;", 5)])
def test_record_patterns_parse_and_bind_their_fields(src, value):
    decls = "colset C = int; colset R = record seq : C * data : C;\n"
    model = cpn.loads(decls + src + "\nval v = g {seq = 2, data = 3};", "m.cpnet")
    assert list(model.net.globals.constants.values()) == [value]


def test_a_flexible_record_pattern_prints_as_written():
    [fun] = parse("fun g ({seq = s, ...} : R) = s;", "m.cpnet").decls
    assert pretty_pat(fun.clauses[0].params[0]) == "({seq = s, ...} : R)"


def test_an_unresolved_flexible_record_is_refused_as_in_sml():
    # SML/NJ refuses it too ("unresolved flex record"): nothing tells which record type it is
    with pytest.raises(cpn.ModelError) as info:
        cpn.loads("colset C = int; colset R = record seq : C * data : C;\nfun g {seq = s, ...} = s;", "m.cpnet")
    assert info.value.diagnostics[0].code == "E0301"
