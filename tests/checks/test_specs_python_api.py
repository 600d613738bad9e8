"""docs/specs.md, "From Python": the documented snippet runs and prints what the page says, and every
attribute its table lists exists on the objects `cpn.check` returns."""

import contextlib
import io
import os
import pathlib
import re

import cpn

ROOT = pathlib.Path(__file__).resolve().parents[2]
DOC = (ROOT / "docs" / "specs.md").read_text(encoding="utf-8")
SECTION = DOC[DOC.index("### From Python"):DOC.index("## 5.")]


def test_the_documented_snippet_prints_what_the_page_shows(monkeypatch):
    code = re.search(r"```python\n(.*?)```", SECTION, re.S).group(1)
    shown = re.search(r"```text\n(.*?)```", SECTION, re.S).group(1)
    monkeypatch.chdir(ROOT)  # "from the repository's root"
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, "docs/specs.md", "exec"), {})  # noqa: S102 - the documentation's own example
    assert out.getvalue() == shown


def _top_level(cell: str) -> list[str]:
    """The backticked names of a table cell outside parentheses (those inside describe a sub-object)."""
    depth, kept = 0, []
    for c in cell:
        depth += c == "("
        if depth == 0:
            kept.append(c)
        depth -= c == ")" and depth > 0
    return re.findall(r"`(\w+)`", "".join(kept))


def test_every_documented_attribute_exists():
    rows = dict(re.findall(r"^\| `(\w+)` \| (.*) \|$", SECTION, re.M))
    assert set(rows) == {"RunResult", "PropertyResult", "Verdict", "Evidence"}
    runs = cpn.check(os.path.join(ROOT, "specs", "examples", "stations.toml"))
    run = runs[0]
    result = next(r for r in run.results if r.verdict.evidence is not None)
    objects = {"RunResult": run, "PropertyResult": result, "Verdict": result.verdict,
               "Evidence": result.verdict.evidence}
    for name, obj in objects.items():
        assert type(obj).__name__ == name
        names = _top_level(rows[name])
        assert names, name
        missing = [a for a in names if not hasattr(obj, a)]
        assert not missing, (name, missing)
    for a in ("name", "values"):
        assert hasattr(run.run, a)
    for a in ("n_states", "n_arcs", "complete", "stop_reason"):
        assert hasattr(run.exploration, a)
    for a in ("name", "kind", "fields", "expect", "span"):
        assert hasattr(result.spec, a)
