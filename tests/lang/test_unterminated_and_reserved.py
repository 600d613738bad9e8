"""The rough edges of the front end: an unterminated comment or string is reported where it opens,
a reserved word where a name is expected is reported at the word; in `.cpnet` text
and in the CPN ML text of `.cpn` files."""

import pytest

import cpn
from cpn.errors import ModelError
from tests._models import cpn_document


def _first(text: str, name: str = "m.cpnet"):
    with pytest.raises(ModelError) as info:
        cpn.loads(text, name)
    assert "Traceback" not in info.value.render()
    return info.value.diagnostics[0]


def _first_cpn(tmp_path, mls=(), guard="[x > 0]", arc="x", var="x"):
    path = tmp_path / "m.cpn"
    path.write_text(cpn_document([("C", "<int/>")], [(var, "C")], list(mls), [("P", "C", "1`1"), ("Q", "C", "")],
                                 [("T", guard)], [("P", "T", arc), ("T", "Q", arc)]), encoding="iso-8859-1")
    with pytest.raises(ModelError) as info:
        cpn.load(path)
    return path, path.read_text(encoding="iso-8859-1").splitlines(), info.value.diagnostics[0]


# ------------------------------------------------------------------ 2a: unterminated comments and strings

@pytest.mark.parametrize("text,line,col", [
    ("colset C = int;\nval x = 1; (* a comment\nplace P : C;\nplace Q : C;\n", 2, 12),
    ("colset C = int;\nplace P : C = 1`(1 + 2) (* [ ( {\n\n", 2, 25),
    ("(* never closed", 1, 1),
])
def test_an_unterminated_comment_is_reported_where_it_opens(text, line, col):
    d = _first(text)
    assert (d.code, d.span.line, d.span.col) == ("E0102", line, col)
    assert d.message == f"the comment opened at m.cpnet:{line}:{col} is never closed"
    assert "never closed" in d.message and "'('" not in d.message and "'*)'" in d.hint


def test_an_unterminated_string_is_reported_where_it_opens():
    d = _first('colset S = string;\nval s = "abc;\nplace P : S;\n')
    assert (d.code, d.span.line, d.span.col) == ("E0102", 2, 9)
    assert d.message == "the string opened at m.cpnet:2:9 is never closed"


def test_comment_and_string_openers_inside_each_other_open_nothing():
    m = cpn.loads('colset S = string;\nval s = "(* not a comment";\n(* a "quote *)\nplace P : S = 1`s;\n', "m.cpnet")
    e = m.engine()
    assert e.format_marking(e.initial_state(), 0) == '1`"(* not a comment"'


def test_comments_nest_as_in_sml():
    m = cpn.loads("colset C = int;\n(* a (* b *) c *)\nplace P : C = 1`1;\n", "m.cpnet")
    assert [p.name for p in m.net.places] == ["Top'P 1"]
    d = _first("colset C = int;\n(* a (* b *) c\nplace P : C = 1`1;\n")
    assert (d.code, d.span.line, d.span.col) == ("E0102", 2, 1)


@pytest.mark.parametrize("where", ["declaration", "guard", "arc"])
def test_an_unterminated_comment_in_the_cpn_ml_of_a_cpn_file(tmp_path, where):
    mls = ["fun f x = x + 1; (* add one"] if where == "declaration" else ["fun f x = x + 1;"]
    guard = "[f x > 0 (* positive ]" if where == "guard" else "[f x > 0]"
    arc = "x (* the token" if where == "arc" else "x"
    path, lines, d = _first_cpn(tmp_path, mls, guard, arc)
    assert d.code == "E0102" and d.span.file == str(path)
    assert lines[d.span.line - 1][d.span.col - 1:].startswith("(*")
    assert f"the comment opened at {path}:{d.span.line}:{d.span.col} is never closed" in d.message


def test_an_unterminated_string_in_the_cpn_ml_of_a_cpn_file(tmp_path):
    path, lines, d = _first_cpn(tmp_path, ['val s = "abc;', "fun f x = x + size s;"])
    assert d.code == "E0102" and lines[d.span.line - 1][d.span.col - 1:].startswith('"abc;')
    assert f"the string opened at {path}:{d.span.line}:{d.span.col} is never closed" in d.message


# ------------------------------------------------------------------ 2b: reserved words as names

@pytest.mark.parametrize("text,word,line,col", [
    ("val end = 3;", "end", 1, 5),
    ("fun val x = x;", "val", 1, 5),
    ("colset C = int;\nvar type : C;", "type", 2, 5),
    ("colset C = int;\nvar x, of : C;", "of", 2, 8),
    ("colset case = int;", "case", 1, 8),
    ("val x = let val in = 3 in 1 end;", "in", 1, 17),
    ("fun f end = 1;", "end", 1, 7),
    ("val x = fn then => 1;", "then", 1, 12),
    ("colset R = record open : INT;", "open", 1, 19),
    ("val x = {type = 1};", "type", 1, 10),
    # read as a name, 'end' made the ';' after it the unexpected token: the message is about 'end'
    ("colset C = int;\nval x = let val a = 1 in end;", "end", 2, 26),
])
def test_a_reserved_word_used_as_a_name_is_reported_at_the_word(text, word, line, col):
    d = _first(text)
    assert (d.code, d.span.line, d.span.col, d.params["found"]) == ("E0101", line, col, word)
    assert f"'{word}' is a reserved word" in d.message and d.hint


def test_places_and_transitions_may_be_called_like_reserved_words():
    # they are no ML names: CPN Tools names places freely
    m = cpn.loads("colset C = int;\nvar x : C;\nplace open : C = 1`1;\ntrans end;\narc open -> end : x;\n")
    assert [p.name for p in m.net.places] == ["Top'open 1"]


def test_a_reserved_word_in_the_cpn_ml_of_a_cpn_file(tmp_path):
    path, lines, d = _first_cpn(tmp_path, ["fun f x = x + end;"], "[f x > 0]")
    assert d.code == "E0101" and "'end' is a reserved word" in d.message
    assert lines[d.span.line - 1][d.span.col - 1:].startswith("end;")


def test_a_variable_named_type_in_a_cpn_file(tmp_path):
    path, lines, d = _first_cpn(tmp_path, guard="[type > 0]", arc="type", var="type")
    assert d.code == "E0101" and "'type' is a reserved word" in d.message and "<var" in lines[d.span.line - 1]


def test_a_statement_cut_short_says_end_of_the_file():
    d = _first("colset C = int;\nval x = let val a = 1 in")
    assert d.code == "E0101" and d.message.startswith("unexpected end of the file, expected ")
