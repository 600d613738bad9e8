"""The Python code generated for every model of the repository, in one text: a change to the expression
tree or its compiler that is meant to keep the behaviour leaves it byte-identical.

    python3 bench/codegen_dump.py > before.txt    # ... change ...
    python3 bench/codegen_dump.py | diff before.txt -

Covers models/, bench/nets/ and tests/models/: for each model that loads, the source of its compiled
global functions, of each transition's binding function and of the flat successor function.
"""

from __future__ import annotations

import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
FOLDERS = ("models", "bench/nets", "tests/models")


def model_files() -> list[pathlib.Path]:
    return sorted(p for d in FOLDERS for p in (ROOT / d).rglob("*.cpnet"))


def generated(path: pathlib.Path) -> str:
    """The generated code of one model, or the reason it has none."""
    import cpn
    from cpn.engine import codegen
    from cpn.engine.compiled import CompiledEngine
    from cpn.expr import nodes as E

    try:
        net = cpn.load(path).net
        engine = CompiledEngine(net)
    except Exception as exc:  # noqa: BLE001 - a model that does not load or compile is listed with why
        return f"not compiled: {type(exc).__name__}\n"
    fc = codegen.FunctionCodegen(codegen.Namespace(), engine.ev, {}, {n: s.uid for n, s in net.variables.items()})
    out = []
    for d in net.globals.decls:
        if isinstance(d, E.FunDecl):
            fc.functions[d.ref.uid] = None  # as the engine compiles them: visible to later ones if compiled
            src = fc.compile(d)
            if src is None:
                del fc.functions[d.ref.uid]
            out.append(f"# function {d.name}\n{src}")
    for t in net.transitions:
        out.append(f"# transition {t.name}\n{engine.sources[t.index]}")
    out.append(f"# successors\n{getattr(engine, 'successors_source', None)}")
    return "\n".join(out) + "\n"


def main() -> int:
    for path in model_files():
        sys.stdout.write(f"=== {path.relative_to(ROOT)}\n{generated(path)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
