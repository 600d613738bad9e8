"""`cpn-verify validate --help` gives validate's own exit statuses, each with one meaning: it verifies no
property, so the commands' common list (where 1 is "a property is violated") is not printed."""

import re

from cpn.cli.main import build_parser


def _help() -> str:
    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")
    return sub.choices["validate"].format_help()


def test_each_exit_status_is_listed_once():
    text = _help()
    statuses = re.findall(r"^  (\d+) ", text[text.index("exit statuses:"):], re.M)
    assert statuses == ["0", "1", "2", "64", "70", "73", "130"]
    assert "a property is violated" not in text
    assert text.count("exit statuses:") == 1 and "Exit status:" not in text


def test_exit_1_names_the_mismatch_and_error_rows():
    text = _help()
    one = text[text.index("\n  1 "):text.index("\n  2 ")]
    assert "'mismatch'" in one and "'error'" in one


def test_the_other_commands_keep_the_common_list():
    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")
    assert "a property is violated" in sub.choices["explore"].format_help()
