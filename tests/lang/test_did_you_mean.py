"""Did-you-mean: in another case for colour sets ('intt' -> 'INT'), naming what the candidate is (a place, a
variable, a constant, a function, a transition, a library function), and none without a strong candidate."""

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


def _diags(src: str, **kw):
    with pytest.raises(ModelError) as info:
        cpn.loads(src, "m.cpnet", **kw)
    return info.value.diagnostics


MISSPELT = """colset Worker = int with 0..3;
val Limit = 3;
var worker : Worker;
fun next w = (w + 1) mod Limit;
place Idle : Worker = Worker.all();
place Busy : Worker;
trans Start [worker < Limit];
trans Stop;
arc Idle -> Start : worker;
arc Start -> Busy : worker;
arc Busy -> Stop : worker;
arc Stop -> Idle : next worker;
"""


@pytest.mark.parametrize("old,new,line,hint", [
    ("place Busy : Worker;", "place Busy : Workr;", 6, "Did you mean 'Worker' (declared at 1:1)?"),
    ("arc Idle -> Start : worker;", "arc Idle -> Start : workr;", 9,
     "Did you mean the variable 'worker' (declared at 3:5)?"),
    ("[worker < Limit]", "[worker < Limt]", 7, "Did you mean the constant 'Limit' (declared at 2:5)?"),
    ("next worker;", "nxt worker;", 12, "Did you mean the function 'next' (declared at 4:1)?"),
    ("arc Busy -> Stop", "arc Bussy -> Stop", 11, "Did you mean the place 'Busy' (declared at 6:7)?"),
    ("arc Idle -> Start", "arc Idle -> Strat", 9, "Did you mean the transition 'Start' (declared at 7:7)?"),
    ("Worker.all()", "Worker.al()", 5, "Did you mean 'Worker.all'?"),
    ("(w + 1) mod Limit", "(w + 1) mod Limit + lenght []", 4, "Did you mean the library function 'length'?"),
])
def test_unknown_names_get_a_suggestion_naming_what_the_candidate_is(old, new, line, hint):
    [d] = _diags(MISSPELT.replace(old, new))
    assert (d.code, d.span.line) == ("E0201", line)
    assert d.hint.startswith(hint)


@pytest.mark.parametrize("old,new", [("[worker < Limit]", "[worker < q]"),
                                     ("place Busy : Worker;", "place Busy : Colour;")])
def test_no_suggestion_without_a_strong_candidate(old, new):
    [d] = _diags(MISSPELT.replace(old, new))
    assert "Did you mean" not in d.hint
