"""The examples in the docstrings of the public API run and give what they show."""

import doctest
import importlib

import pytest

PUBLIC = [
    "cpn", "cpn.model", "cpn.arcs", "cpn.io", "cpn.expr.pretty", "cpn.values.colours", "cpn.values.multiset", "cpn.net.model", "cpn.expr.nodes", "cpn.expr.binding", "cpn.values.builtins",
    "cpn.engine", "cpn.engine.protocol", "cpn.engine.plan", "cpn.expr.evaluate", "cpn.statespace.explore",
    "cpn.statespace.scc", "cpn.checks.mcc", "cpn.report.model", "cpn.report.json", "cpn.report.text",
]


@pytest.mark.parametrize("name", PUBLIC)
def test_docstring_examples(name):
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.failed == 0
    assert result.attempted > 0, f"{name} has no example"
