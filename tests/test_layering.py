"""Layers import only what their allow-list names (STYLE.md 2.2, docs/internals.md): checked by walking
the imports of every module."""

import ast
import pathlib

ROOT = pathlib.Path(__file__).resolve().parent.parent / "cpn"

# the order of the layers, as docs/internals.md draws it: text -> lang -> net -> engine -> statespace ->
# checks -> report -> cli; an allow-list may only name earlier layers
ORDER = ["diagnostics", "_util", "arcs", "errors", "values", "expr", "lang", "net", "io", "engine", "model", "statespace",
         "checks", "report", "__init__", "cli", "__main__"]

FOUNDATION = {"diagnostics", "_util", "errors", "arcs"}

# what each top-level part of the package may import (besides itself)
ALLOWED: dict[str, set[str]] = {
    "diagnostics": set(),
    "_util": set(),
    "arcs": set(),
    "errors": {"diagnostics"},
    "values": FOUNDATION,
    # the one expression tree (nodes, evaluator, binding analysis, printer): under the language and the engine
    "expr": FOUNDATION | {"values"},
    "lang": FOUNDATION | {"values", "expr"},
    "net": FOUNDATION | {"values", "expr", "lang"},  # lowering and translation read the checked model
    "io": FOUNDATION | {"values", "expr", "lang", "net"},  # foreign formats to and from .cpnet text
    "engine": FOUNDATION | {"values", "expr", "net"},  # the Net is the engine's only input: never the language
    "model": FOUNDATION | {"values", "expr", "lang", "net", "io", "engine"},  # the loader: file to net and engines
    "statespace": FOUNDATION | {"values", "engine"},  # through the engine protocol only
    # property texts are CPN ML, typed by the language's checker against the model's declarations; the
    # gate loads the models its scenarios name
    "checks": FOUNDATION | {"values", "expr", "lang", "net", "model", "engine", "statespace"},
    # drawings of the net print its inscriptions (cpn.expr.pretty)
    "report": FOUNDATION | {"values", "expr", "net", "engine", "statespace", "checks"},
    "__init__": FOUNDATION | {"values", "expr", "lang", "net", "engine", "model", "statespace", "checks", "report"},
    "cli": FOUNDATION | {"values", "io", "engine", "model", "statespace", "checks", "report", "__init__"},
    "__main__": {"cli"},
}


def _part(modname: str) -> str | None:
    parts = modname.split(".")
    if parts[0] != "cpn":
        return None
    if len(parts) == 1:
        return "__init__"
    return parts[1].removesuffix(".py")


def _imports(source: str) -> list[str]:
    names = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            names += [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names.append(node.module)
    return names


def _problems(mod: str, own: str, source: str, allowed: dict[str, set[str]]) -> list[str]:
    """What module `mod` of part `own` imports beyond its allow-list."""
    if own not in allowed:
        return [f"{mod}: not assigned to a layer (add it to ALLOWED)"]
    out = []
    for name in _imports(source):
        other = _part(name)
        if other is not None and other != own and other not in allowed[own]:
            out.append(f"{mod} imports {name}: {own} may import only "
                       f"{', '.join(sorted(allowed[own])) or 'nothing of cpn'}")
    return out


def test_every_module_imports_only_what_its_layer_allows():
    problems = []
    for path in sorted(ROOT.rglob("*.py")):
        rel = path.relative_to(ROOT.parent).with_suffix("")
        problems += _problems(".".join(rel.parts), rel.parts[1], path.read_text(encoding="utf-8"), ALLOWED)
    assert not problems, "\n".join(problems)


def test_allow_lists_point_only_downward():
    for part, allowed in ALLOWED.items():
        later = {a for a in allowed if ORDER.index(a) >= ORDER.index(part)}
        assert not later, f"{part} may import the later layers {sorted(later)}"


def test_an_engine_importing_the_language_fails():
    assert _problems("cpn.engine.x", "engine", "from cpn.lang import ast as A\n", ALLOWED)
    assert _problems("cpn.engine.x", "engine", "import cpn.lang.evaluate\n", ALLOWED)
    assert not _problems("cpn.engine.x", "engine", "from cpn.expr import nodes\n", ALLOWED)
    assert _problems("cpn.expr.x", "expr", "from cpn.lang import ast\n", ALLOWED)
    assert _problems("cpn.expr.x", "expr", "from cpn.engine import codegen\n", ALLOWED)
    assert _problems("cpn.statespace.x", "statespace", "from cpn.net import Net\n", ALLOWED)
