"""Layers import only downward (STYLE.md 2.2): checked by walking the imports of every module."""

import ast
import pathlib

ROOT = pathlib.Path(__file__).resolve().parent.parent / "cpn"

# layer of each top-level part of the package
LAYER = {
    "diagnostics": 0, "errors": 0, "_util": 0,
    "values": 1,
    "lang": 2,
    "net": 3, "io": 3,
    "engine": 4,
    "model": 4,
    "statespace": 5,
    "checks": 6,
    "report": 7,
    "cli": 8,
    "__init__": 7, "__main__": 9,
}


def _part(modname: str) -> str | None:
    parts = modname.split(".")
    if parts[0] != "cpn":
        return None
    if len(parts) == 1:
        return "__init__"
    return parts[1].removesuffix(".py")


def test_no_module_imports_a_later_layer():
    problems = []
    for path in ROOT.rglob("*.py"):
        rel = path.relative_to(ROOT.parent).with_suffix("")
        mod = ".".join(rel.parts)
        own = _part(mod) if rel.name != "__init__" or len(rel.parts) > 2 else "__init__"
        if rel.parts[-1] == "__init__" and len(rel.parts) > 2:
            own = rel.parts[1]
        if own not in LAYER:
            problems.append(f"{mod}: not assigned to a layer")
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            names = []
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                names = [node.module]
            for name in names:
                other = _part(name)
                if other is None or other == own:
                    continue
                if other not in LAYER:
                    problems.append(f"{mod} imports unknown part {name}")
                elif LAYER[other] > LAYER[own]:
                    problems.append(f"{mod} (layer {LAYER[own]}) imports {name} (layer {LAYER[other]})")
    assert not problems, "\n".join(problems)
