"""The tests that read the shared data (`../shared`, CPN_SHARED_DIR) say so, and without the data they skip,
except under CI, where they fail (tests/_shared.py, tests/conftest.py)."""

from __future__ import annotations

import ast
import os
import subprocess
import sys

import pytest

from tests._shared import ROOT

TESTS = os.path.join(ROOT, "tests")


def _names(node: ast.AST) -> set[str]:
    return {n.id for n in ast.walk(node) if isinstance(n, ast.Name)} | \
        {n.attr for n in ast.walk(node) if isinstance(n, ast.Attribute)}


def _marked(decorators: list[ast.expr]) -> bool:
    return any("needs_shared" in _names(d) for d in decorators)


def unmarked_readers(source: str) -> list[str]:
    """The tests of a module that read the shared data (through SHARED, or a module-level name, helper or
    fixture computed from it) without the `needs_shared` mark on them or on the module."""
    tree = ast.parse(source)
    if any(isinstance(n, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "pytestmark" for t in n.targets)
           and "needs_shared" in _names(n.value) for n in tree.body):
        return []
    tainted = {"SHARED"}
    defs: dict[str, ast.AST] = {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            defs[node.name] = node
    changed = True
    while changed:  # module-level names and helpers computed from the shared data, to a fixed point
        changed = False
        for node in tree.body:
            if isinstance(node, (ast.Assign, ast.AnnAssign)) and _names(node.value or ast.Constant(None)) & tainted:
                targets = node.targets if isinstance(node, ast.Assign) else [node.target]
                new = {n.id for t in targets for n in ast.walk(t) if isinstance(n, ast.Name)} - tainted
                if new:
                    tainted |= new
                    changed = True
            elif isinstance(node, ast.FunctionDef) and not node.name.startswith("test") \
                    and node.name not in tainted and _names(node) & tainted:
                tainted.add(node.name)
                changed = True

    def tests_of(body, prefix="", class_marked=False):
        for node in body:
            if isinstance(node, ast.ClassDef) and node.name.startswith("Test"):
                yield from tests_of(node.body, node.name + "::", _marked(node.decorator_list))
            elif isinstance(node, ast.FunctionDef) and node.name.startswith("test"):
                yield prefix + node.name, node, class_marked

    bad = []
    for name, fn, class_marked in tests_of(tree.body):
        args = {a.arg for a in fn.args.args}
        reads = (_names(fn) | args) & tainted
        if reads and not (class_marked or _marked(fn.decorator_list)):
            bad.append(f"{name} (reads {', '.join(sorted(reads))})")
    return bad


def test_every_test_that_reads_the_shared_data_is_marked():
    bad = []
    for folder, _, files in os.walk(TESTS):
        for f in sorted(files):
            if f.endswith(".py") and f.startswith("test_"):
                path = os.path.join(folder, f)
                with open(path, encoding="utf-8") as fh:
                    bad += [f"{os.path.relpath(path, ROOT)}::{t}" for t in unmarked_readers(fh.read())]
    assert not bad, "tests that read the shared data without `needs_shared`:\n" + "\n".join(bad)


def test_the_check_finds_an_unmarked_reader():
    src = ("import os\nfrom tests._shared import SHARED, needs_shared\n"
           "CORPUS = os.path.join(SHARED, 'validation')\n"
           "def _first():\n    return sorted(os.listdir(CORPUS))[0]\n"
           "def test_a():\n    assert _first()\n"
           "@needs_shared\ndef test_b():\n    assert CORPUS\n"
           "def test_c():\n    assert 1\n")
    assert unmarked_readers(src) == ["test_a (reads _first)"]
    assert unmarked_readers("import pytest\nfrom tests._shared import SHARED, needs_shared\n"
                            "pytestmark = needs_shared\ndef test_a():\n    assert SHARED\n") == []


MODULE = os.path.join("tests", "validation", "test_validation_cli.py")


def _run_without_shared(tmp_path, ci: bool) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k != "CI"}
    env["CPN_SHARED_DIR"] = str(tmp_path / "absent")
    if ci:
        env["CI"] = "true"
    return subprocess.run([sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-rs", MODULE],
                          cwd=ROOT, env=env, capture_output=True, text=True, timeout=300)


@pytest.mark.parametrize("ci", [False, True])
def test_without_the_shared_data_tests_skip_or_fail_under_ci(tmp_path, ci):
    out = _run_without_shared(tmp_path, ci)
    text = out.stdout + out.stderr
    if ci:
        assert out.returncode == 1, text
        assert "the shared test data is missing" in text and "CI must have it" in text
    else:
        assert out.returncode == 0, text
        assert "skipped" in text and "the shared test data is absent" in text and "failed" not in text
