"""The examples in the docstrings of cpn/ run, as a user would type them at the root of the repository.

Every module under cpn/ with a `>>>` line is a test of its own here, so an example that stops running (a
module that no longer imports, an example doctest does not find, such as one in a comment or in a nested
function) fails instead of silently dropping out."""

import doctest
import importlib
import os
import pathlib
import re

import pytest

ROOT = pathlib.Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "cpn"
PROMPT = re.compile(r"^\s*>>>(?: |$)", re.M)
# optional dependencies (pyproject.toml's extras): a module that needs one is skipped where it is missing
OPTIONAL = {"ray"}


def _modules_with_examples() -> dict[str, int]:
    """Module name -> number of `>>>` lines in its source, for every module of cpn/ that has one."""
    found = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        prompts = len(PROMPT.findall(path.read_text(encoding="utf-8")))
        if prompts:
            parts = path.relative_to(ROOT).with_suffix("").parts
            found[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = prompts
    return found


MODULES = _modules_with_examples()


def test_the_modules_with_examples_are_found():
    # a few modules whose examples the documentation relies on; a scan that finds nothing would make every
    # test below vanish without failing
    assert {"cpn", "cpn.diagnostics", "cpn.values.multiset", "cpn.statespace.explore"} <= set(MODULES)


@pytest.mark.parametrize("name", sorted(MODULES))
def test_the_examples_of_the_module_run(name, monkeypatch):
    try:
        module = importlib.import_module(name)
    except ModuleNotFoundError as exc:
        if exc.name in OPTIONAL:
            pytest.skip(f"{name} needs {exc.name}, which is not installed")
        raise
    tests = [t for t in doctest.DocTestFinder().find(module) if t.examples]
    examples = sum(len(t.examples) for t in tests)
    # every '>>>' line of the source is an example doctest finds and runs (or skips on a +SKIP directive)
    assert examples == MODULES[name], (
        f"{name} has {MODULES[name]} '>>>' lines, and doctest finds {examples} examples: an example outside a "
        "docstring doctest reads (a comment, a nested function) is never run")
    monkeypatch.chdir(ROOT)  # the examples name files relative to the root of the repository
    failed, report = _run(tests)
    assert failed == 0, report


def _run(tests) -> tuple[int, str]:
    """(failed examples, doctest's report) of running `tests`."""
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    report: list[str] = []
    for test in sorted(tests, key=lambda t: t.name):
        runner.run(test, out=report.append)
    return runner.summarize(verbose=False).failed, "".join(report)


def test_a_failing_example_fails_the_test(tmp_path, monkeypatch):
    """The runner above reports a wrong example (the test of the test: a runner that swallowed failures would
    pass every module)."""
    (tmp_path / "wrong_example.py").write_text('def f():\n    """\n    >>> 1 + 1\n    3\n    """\n',
                                               encoding="utf-8")
    monkeypatch.syspath_prepend(os.fspath(tmp_path))
    module = importlib.import_module("wrong_example")
    failed, report = _run(doctest.DocTestFinder().find(module))
    assert failed == 1 and "Expected:\n    3\nGot:\n    2" in report
