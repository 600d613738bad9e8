"""What a delay on an input arc (`e @+ k`, CPN Tools' preempting time stamps) may be, and the positioned
error for each thing it may not: k is a constant (numbers, `val`s, module parameters) of 0 or more, it ends
the inscription, the place is timed, the arc is an input arc, and two arcs that take tokens from one place
for one transition have the same delay (docs/semantics.md, Time)."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import ModelError

DECLS = """colset TU = unit timed;
colset U = unit;
colset C = int with 0..3;
colset TC = int with 0..3 timed;
var x, n : C;
fun f () = 2;
val NEG = ~2;
place P : TU = 1`();
place R : TC = 1`1;
place S : U = 1`();
"""
LINE = DECLS.count("\n") + 1  # the line of the first statement after DECLS


def errors(text: str) -> list[tuple[str, int, int, str, str]]:
    """(code, line, col, message, hint) of each error of DECLS + text."""
    with pytest.raises(ModelError) as exc:
        cpn.loads(DECLS + text, "m.cpnet")
    return [(d.code, d.span.line, d.span.col, d.message, d.hint or "") for d in exc.value.diagnostics
            if d.code.startswith("E")]


@pytest.mark.parametrize("arc, col, message, hint", [
    ("arc P -> t : () @+ n;", 20, "not a constant: it uses the variable 'n'", "'val' constants"),
    ("arc P -> t : () @+ intTime();", 20, "not a constant: it reads the clock ('intTime')", "'val' constants"),
    ("arc P -> t : () @+ f ();", 20, "not a constant: it calls the function 'f'", "a 'val' may call a function"),
    ("arc P -> t : () @+ C.ran();", 20, "not a constant: it draws a random value ('C.ran')", "'val' constants"),
    ("arc P -> t : () @+ discrete(1, 3);", 20, "not a constant: it draws a random value ('discrete')", ""),
    ("arc S -> t : () @+ 1;", 14, "place 'S' holds U, which is not timed", "Declare the colour set timed"),
    ("arc P <-> t : () @+ 1;", 15, "the inscription of a double arc ('P' <-> 't') has a time delay",
     "write an input arc 'arc P -> t : e @+ k;' and an output arc"),
    ("inhibitor P -> t : () @+ 1;", 20, "inhibitor arc", "this arc removes no tokens"),
    ("arc R -> t : if x = 1 then 1`x @+ 1 else 1`x;", 14, "does not end its inscription", "Write the delay once"),
    ("arc R -> t : 1`x @+ 1 ++ 1`x;", 14, "does not end its inscription", "different delays need different arcs"),
    ("arc P -> t : () @++ 1.0;", 14, "real-valued delay '@++'", "write '@+ k' with a constant k"),
    ("arc P -> t : () @+ [1,2];", 20, "allowed only as a transition delay or on an output arc", ""),
])
def test_a_delay_an_input_arc_cannot_have_is_one_positioned_error(arc, col, message, hint):
    (code, line, c, msg, h), = errors(f"trans t;\n{arc}\n")
    assert (line, c) == (LINE + 1, col) and code in ("E0206", "E0301")
    assert message in msg and hint in h


@pytest.mark.parametrize("arcs, at, message, hint", [
    ("arc P -> t : () @+ NEG;", "NEG", "the delay of input arc 'P' -> 't' is -2: it must not be negative", "0 or more"),
    ("arc R -> t : 1`x @+ 1; arc R -> t : 1`x @+ 2;", "2;",
     "transition 't' removes tokens from place 'R' by two arcs with different delays (1 and 2)", "'e1 ++ e2 @+ k'."),
    ("arc R <-> t : x; arc R -> t : x @+ 1;", "1;", "by two arcs with different delays (0 and 1)",
     "a double arc takes its tokens with no delay"),
])
def test_a_delay_known_once_the_net_is_built_is_checked_then(arcs, at, message, hint):
    (code, line, col, msg, h), = errors(f"trans t;\n{arcs}\n")
    assert (code, line, col) == ("E0301" if "negative" in message else "E0206", LINE + 1, arcs.rindex(at) + 1)
    assert message in msg and hint in h


def test_a_negative_delay_in_a_module_instance_is_reported_once_at_its_position():
    text = ("module M(d : C) {\nplace A : TU; trans t; arc A -> t : () @+ (d - 3);\n}\n"
            "instance M1 = M(d = 1); instance M2 = M(d = 1); instance M3 = M(d = 3);\n")
    assert [e[:4] for e in errors(text)] == [("E0301", LINE + 1, 44, "the delay of input arc 'A' -> 't' is -2: it "
                                              "must not be negative")]


def test_a_refused_delay_leaves_no_echo_about_the_variables_the_arc_binds():
    """The arc still binds 'x' (no E0302 on the output arc)."""
    text = "place T : C; trans t;\narc R -> t : x @+ n;\narc t -> T : x;\n"
    assert [e[0] for e in errors(text)] == ["E0206"]


def test_accepted_delays_numbers_vals_parameters_and_sums():
    text = DECLS + """val D = 3;
    trans a; arc P -> a : () @+ (2 * D + 1);
    trans b; arc R -> b : 1`x ++ 1`1 @+ D;
    trans c; arc R -> c : x @+ 0;
    module M(d : C) { place A : TU; trans t; arc A -> t : () @+ d; }
    instance M1 = M(d = 2);
    """
    net = cpn.loads(text, "m.cpnet").net
    assert [(t.transition, [a.preemption for a in t.arcs]) for t in net.transitions] == \
        [("a", [7]), ("b", [3]), ("c", [0]), ("t", [2])]


def test_the_cli_shows_the_error_with_its_caret_and_hint(tmp_path, capsys):
    from cpn.cli.main import main

    path = tmp_path / "m.cpnet"
    path.write_text(DECLS + "trans t;\narc P -> t : () @+ n;\n")
    assert main(["lint", str(path)]) == 65
    err = capsys.readouterr().err
    assert f"m.cpnet:{LINE + 1}:20: error[E0206]: the delay of input arc 'P' -> 't' is not a constant" in err
    assert "arc P -> t : () @+ n;\n   |" in err and "^" in err and "hint: An input arc's delay" in err
