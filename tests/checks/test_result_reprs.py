"""The results of `cpn.check` print briefly: a property's result names the property and its verdict, and
never repeats the scenario file's text."""

import os

import cpn
from tests.checks._nets import COUNTER, scenario

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def test_a_property_result_has_a_short_repr():
    runs = cpn.check(os.path.join(ROOT, "specs", "examples", "dp.toml"))
    source = runs[0].scenario.source
    for r in runs[0].results:
        text = repr(r)
        assert r.spec.name in text and r.spec.kind in text and r.verdict.status.value in text.lower()
        assert f"dp.toml:{r.spec.span.line}:{r.spec.span.col}" in text  # where the property is written
        assert source[:40] not in text and "model =" not in text
        assert len(text) < 400, text
    assert source[:40] not in repr(runs[0].scenario) and "dp.toml" in repr(runs[0].scenario)


def test_evidence_prints_its_length_not_its_states(tmp_path):
    path = scenario(tmp_path, COUNTER, '[[property]]\nname = "below three"\nkind = "invariant"\n'
                                       'expr = "ms_to_col (C\'P 1) < 3"\n')
    (result,) = cpn.check(path)[0].results
    assert result.verdict.status.value == "violated"
    assert "Evidence(3 steps to state 3)" in repr(result)
