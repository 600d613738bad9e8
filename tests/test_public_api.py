"""The public door (`cpn/__init__.py`): every name the README and docs/*.md use from Python is in
`cpn.__all__` and importable from `cpn`."""

import pathlib
import re

import pytest

import cpn

ROOT = pathlib.Path(__file__).resolve().parent.parent
DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
SUBPACKAGES = {p.stem for p in (ROOT / "cpn").iterdir() if not p.name.startswith("__")}

# names the documents import from a module of the package, not from `cpn`, on purpose: the HTML page's
# own rows and entries (`cpn.report.html.Verdict` is a row of the page, not `cpn.Verdict`)
NOT_PUBLIC = {("cpn.report.html", "Verdict"), ("cpn.report.html", "IndexEntry"), ("cpn.report.html", "render_html"),
              ("cpn.report.html", "render_index")}


def _code(text: str) -> str:
    """The Python code blocks of a Markdown text, and its inline code."""
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    inline = re.findall(r"`([^`\n]+)`", re.sub(r"```.*?```", "", text, flags=re.S))
    return "\n".join(blocks + inline)


def _imports(code: str) -> set[tuple[str, str]]:
    out = set()
    for module, names in re.findall(r"\bfrom (cpn(?:\.[a-z_.]+)?) import ([A-Za-z_, ]+)", code):
        out |= {(module, n.split(" as ")[0].strip()) for n in names.split(",") if n.strip()}
    return out


def documented_names(docs=DOCS) -> dict[str, set[str]]:
    """name -> the documents that use it from Python as `cpn.name`, `from cpn import name`, or from one of
    the package's modules in a code example (`from cpn.statespace import Explorer`)."""
    found: dict[str, set[str]] = {}
    for doc in docs:
        code = _code(doc.read_text(encoding="utf-8"))
        names = {n for n in re.findall(r"\bcpn\.([A-Za-z_]\w*)", code) if n not in SUBPACKAGES}
        names |= {n for m, n in _imports(code) if (m, n) not in NOT_PUBLIC}
        for n in names:
            found.setdefault(n, set()).add(doc.name)
    return found


def test_the_documents_use_the_public_door():
    names = documented_names()
    # what the README and the docs show today, so that the reading of them is not empty
    assert {"load", "check", "Explorer", "build_report", "RunResult", "Verdict"} <= set(names)
    missing = {n: sorted(d) for n, d in names.items() if n not in cpn.__all__}
    assert not missing, f"used in the docs but not in cpn.__all__: {missing}"


@pytest.mark.parametrize("name", sorted(cpn.__all__))
def test_every_public_name_is_importable(name):
    assert getattr(cpn, name) is not None
    exec(f"from cpn import {name}", {})  # noqa: S102 - the name comes from __all__


def test_a_name_the_docs_use_that_the_door_lacks_fails(tmp_path):
    doc = tmp_path / "new.md"
    doc.write_text("Run `cpn.verify(path)`, or:\n\n```python\nfrom cpn import load, simulate\n"
                   "from cpn.statespace import Explorer\nfrom cpn.report.html import Verdict\n```\n")
    names = documented_names([doc])
    assert set(names) == {"verify", "load", "simulate", "Explorer"}
    assert {"verify", "simulate"} == {n for n in names if n not in cpn.__all__}
    with pytest.raises(AttributeError, match="no attribute 'verify'"):
        cpn.verify  # noqa: B018
