"""A diagnostic on a very long line shows a window around its column and shortens long names; its caret
stays under its character after wide (CJK) characters."""

import pytest

from cpn.diagnostics import Diagnostic, Span, display_width, excerpt, render
from cpn.errors import ModelError
from cpn.lang.parser import parse

LONG = 80_000


def _error(text: str, name: str = "m.cpnet") -> ModelError:
    with pytest.raises(ModelError) as info:
        parse(text, name)
    return info.value


def _caret_under(rendered: str) -> str:
    """The character of the source line above the first caret of a rendered diagnostic."""
    lines = rendered.splitlines()
    i = next(k for k, line in enumerate(lines) if line.lstrip(" ").startswith("|") and "^" in line)
    src, caret = lines[i - 1], lines[i]
    col = caret.index("^")
    # the source line is 'N | text', the caret line '  | ^': the same prefix width
    cells = 0
    for ch in src:
        if cells == col:
            return ch
        cells += display_width(ch)
    raise AssertionError(f"no character above the caret in {src!r}")


def test_a_diagnostic_on_a_long_line_shows_a_window_around_the_column():
    text = "net L;\nval x = " + "1 + " * (LONG // 4) + "$ + 1;\n"
    err = _error(text)
    d = err.diagnostics[0]
    assert d.span.col > LONG
    out = err.render()
    assert max(len(line) for line in out.splitlines()) < 200, "the whole line or a caret line across it"
    assert "..." in out
    assert _caret_under(out) == "$"


def test_a_long_span_on_a_long_line_has_a_short_caret():
    shown, caret = excerpt("x" * LONG + " y", 1, LONG)
    assert len(shown) < 200 and len(caret) < 200
    assert shown.endswith("...") and caret.lstrip().startswith("^")


def test_a_long_name_is_shortened_in_the_message_and_the_hint():
    d = Diagnostic("E0201", "unknown name '" + "a" * LONG + "'", Span("m.cpnet", 1, 5, 1, 4 + LONG),
                   hint="Did you mean the constant '" + "b" * LONG + "'?")
    out = render(d, "val " + "a" * LONG + ";")
    assert len(out) < 1000
    assert f"({LONG:,} characters)" in out


def test_a_short_line_is_shown_whole():
    out = _error("val x = 3 $ 4;").render()
    assert "1 | val x = 3 $ 4;" in out and "..." not in out
    assert _caret_under(out) == "$"


def test_the_caret_stays_under_its_character_after_wide_characters():
    out = _error('net W;\ncolset C = int with 0..2;\nplace "溢出缓冲" : C = 1`0 $;\n').render()
    assert _caret_under(out) == "$"
