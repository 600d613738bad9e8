"""Did-you-mean: in another case for colour sets ('intt' -> 'INT'), and naming a place as a place."""

import pytest

import cpn
from cpn.cli.main import main
from cpn.errors import ModelError


@pytest.mark.parametrize("name,want", [("intt", "Did you mean 'INT'?"),
                                       ("pkts", "Did you mean 'Pkt' (declared at 2:1)?")])
def test_unknown_colour_set_gets_a_did_you_mean_in_another_case(name, want):
    with pytest.raises(ModelError) as info:
        cpn.loads(f"net X;\ncolset Pkt = int;\nplace A : {name};\n", "x.cpnet")
    d = info.value.diagnostics[0]
    assert d.message == f"unknown colour set '{name}'"
    assert d.hint.startswith(want), d.hint


def test_a_did_you_mean_calls_a_place_a_place(tmp_path, capsys):
    (tmp_path / "m.cpnet").write_text("net S;\ncolset U = unit;\nplace Idle : U = 1`();\ntrans T;\n"
                                      "arc Idle -> T : ();\n", encoding="utf-8")
    (tmp_path / "s.toml").write_text('model = "m.cpnet"\n[[property]]\nname = "p"\nkind = "invariant"\n'
                                     'expr = "size (S\'Idel 1) <= 1"\n', encoding="utf-8")
    code = main(["check", "--reports", str(tmp_path / "r"), str(tmp_path / "s.toml")])
    err = capsys.readouterr().err
    assert code == 65
    assert "Did you mean the place 'S'Idle'?" in err
    assert "the constant 'S'Idle'" not in err
