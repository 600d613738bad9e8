"""The command line uses the reports' public modules only: no `cpn.report._x` import."""

import ast
import pathlib

import cpn

CLI = pathlib.Path(cpn.__file__).resolve().parent / "cli"


def _private_report_imports(source: str) -> list[str]:
    out = []
    for node in ast.walk(ast.parse(source)):
        names = []
        if isinstance(node, ast.ImportFrom) and node.module:
            names = [node.module] + [f"{node.module}.{a.name}" for a in node.names]
        elif isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        out += [n for n in names if n.startswith("cpn.report.") and any(p.startswith("_") for p in n.split(".")[2:])]
    return out


def test_the_command_line_imports_no_private_module_of_the_reports():
    found = {str(p.relative_to(CLI)): _private_report_imports(p.read_text()) for p in sorted(CLI.rglob("*.py"))}
    assert {k: v for k, v in found.items() if v} == {}


def test_a_private_report_import_is_found():
    assert _private_report_imports("from cpn.report._words import noun\n") == [
        "cpn.report._words", "cpn.report._words.noun"]
    assert _private_report_imports("from cpn.report import _words\n") == ["cpn.report._words"]
    assert _private_report_imports("from cpn.report.words import noun\n") == []
