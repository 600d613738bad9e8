"""A misspelt place in a property text is reported as a place the net lacks, at its position, with the
nearest place name (and `Mark.` kept when the text wrote it), never as an unknown constant."""

import pytest

from cpn.cli.main import main
from tests.checks._nets import scenario

MODEL = """
net Top;
colset U = unit;
val Modbus = 1;
module Modbus() {
  place Bus : U = 1`();
  place Idle : U;
  trans t;
  arc Bus -> t;
  arc t -> Idle;
}
instance M = Modbus() {};
"""


@pytest.mark.parametrize(("text", "place", "suggestion"), [
    ("size (Mark.Modbus'Buss 1) <= 1", "Modbus'Buss", "Mark.Modbus'Bus"),
    ("size (Modbus'Buss 1) <= 1", "Modbus'Buss", "Modbus'Bus"),
    ("size (Modbus'Idel 1) <= 1", "Modbus'Idel", "Modbus'Idle"),
])
def test_a_misspelt_place_gets_the_nearest_place(tmp_path, capsys, text, place, suggestion):
    spec = scenario(tmp_path, MODEL, f'[[property]]\nname = "p"\nkind = "invariant"\nexpr = "{text}"\n')
    assert main(["check", spec]) == 65
    err = capsys.readouterr().err
    assert f"no place '{place}' in the net" in err
    assert f"Did you mean the place '{suggestion}'?" in err
    assert "the constant" not in err
    assert "s.toml:5:" in err  # the expr line


def test_a_name_far_from_every_place_says_how_places_are_named(tmp_path, capsys):
    spec = scenario(tmp_path, MODEL, '[[property]]\nname = "p"\nkind = "invariant"\n'
                                     'expr = "size (Zzzz\'Qqqq 1) <= 1"\n')
    assert main(["check", spec]) == 65
    err = capsys.readouterr().err
    assert "no place 'Zzzz'Qqqq' in the net" in err and "Page'place" in err
