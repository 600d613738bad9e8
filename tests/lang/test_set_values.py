"""`--set` values: parsed as CPN ML before the model is checked, one usage error (exit status 64) naming the
value and the declaration it replaces, in `.cpnet` and `.cpn` files, and the model left unchanged."""

import pytest

import cpn
from cpn.errors import ModelError
from cpn.lang.parser import parse

SETS = """val N = 3;
colset S = int with 0..N;
colset P2 = product S * S;
var x : S;
place P : S = S.all();
place Q : P2;
trans T [x < N];
arc P -> T : x;
arc T -> Q : (x, x);
"""


@pytest.mark.parametrize("value,expected", [
    ("abc", "expected an int for 'N' declared at m.cpnet:1:5, found 'abc'"),
    ("1.5", "expected an int for 'N' declared at m.cpnet:1:5, found a real"),
    ('"x"', "expected an int for 'N' declared at m.cpnet:1:5, found a string"),
    ("1 +", "not a CPN ML expression"),
    ("3; val M = 4", "not a CPN ML expression"),
    ("1 div 0", "evaluating the value failed"),
])
def test_a_bad_set_value_is_one_usage_error_naming_the_value(value, expected):
    from cpn.errors import ConfigurationError

    with pytest.raises(ConfigurationError) as info:
        cpn.loads(SETS, "m.cpnet", set={"N": value})
    exc = info.value
    assert (exc.code, exc.exit_status) == ("E0305", 64)
    assert str(exc).startswith(f"--set N={value}: ") and expected in str(exc)
    assert str(exc).count("\n") == 0


def test_an_unknown_constant_is_a_usage_error_with_a_suggestion():
    from cpn.errors import ConfigurationError

    with pytest.raises(ConfigurationError) as info:
        cpn.loads(SETS.replace("val N", "val Limit").replace("..N", "..Limit").replace("< N", "< Limit"),
                  "m.cpnet", set={"Limt": "3"})
    assert [p.message for p in info.value.problems] == ["the model has no constant 'val Limt'"]
    assert "'Limit'" in info.value.hint


@pytest.mark.parametrize("value", ["-1", " - 1", "~1"])
def test_a_negative_number_may_be_written_with_a_minus(value):
    m = cpn.loads("val D = 3;\ncolset C = int with ~5..5;\nplace P : C = 1`D;", "m.cpnet", set={"D": value})
    assert m.net.places[0].initial == {-1: 1}


def test_set_values_are_parsed_before_checking_and_leave_the_model_unchanged():
    from cpn.lang.overrides import parse_overrides
    from cpn.lang.typecheck import check

    model = parse(SETS, "m.cpnet")
    original = model.decls[0].expr
    overrides = parse_overrides({"N": "-2"})
    assert overrides["N"].text == "-2"
    with pytest.raises(ModelError) as info:  # 0..~2 is an empty range: a model error, reported once
        check(model, overrides)
    [d] = info.value.diagnostics
    assert (d.code, d.span.line, d.notes) == ("E0304", 2, ["'N' is given with --set N=-2"])
    assert model.decls[0].expr is original  # the declaration still holds the model's own value


@pytest.mark.parametrize("argv", [["lint"], ["explore", "--quiet"], ["simulate"]])
@pytest.mark.parametrize("value", ["N=abc", "N=1.5", "NOPE=3"])
def test_the_command_line_exits_64_with_one_error(tmp_path, capsys, argv, value):
    from cpn.cli.main import main

    path = tmp_path / "m.cpnet"
    path.write_text(SETS)
    assert main(argv + ["--set", value, str(path)]) == 64
    err = capsys.readouterr().err
    assert err.count("error") == 1 and f"--set {value}" in err


def test_a_bad_set_value_for_a_cpn_file_names_the_declaration_in_the_cpn_file(tmp_path):
    from cpn.errors import ConfigurationError
    from tests.io.test_cpntools import DECLS, arc, cpn_xml, page, place, trans

    body = place("P1", "A", "S", "1`0") + trans("T1", "T", cond="[x &lt; N]") + arc("A1", "PtoT", "T1", "P1", "x")
    path = tmp_path / "n.cpn"
    path.write_text(cpn_xml(DECLS, page("PG1", "Top", body)), encoding="iso-8859-1")
    assert cpn.load(path, set={"N": "-1"}).net.places[0].name == "Top'A 1"
    with pytest.raises(ConfigurationError) as info:
        cpn.load(path, set={"N": "1.5"})
    text = str(info.value)
    assert text.startswith(f"--set N=1.5: expected an int for 'N' declared at {path}:")
    assert "as .cpnet" not in text
