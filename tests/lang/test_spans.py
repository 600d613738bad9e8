"""Positions of syntax-tree nodes."""


def test_a_span_over_several_lines_ends_at_its_last_character():
    """The end column of a multi-line expression was clamped to its start column (9:14 for an
    expression ending at 9:10): carets and drawn inscriptions were cut in the wrong place."""
    from cpn.lang.parser import parse

    m = parse("colset C = int with 0..3;\nvar k : C;\nplace P : C = 1`0;\ntrans T;\narc P -> T : k;\n"
              "arc T -> P : if k < 3\n  then k + 1\n  else 0;\n", "m.cpnet")
    s = m.decls[-1].expr.span
    assert (s.line, s.col, s.end_line, s.end_col) == (6, 14, 8, 8)
