"""Figures of the code itself, for the design notes: the functions over 60 lines of a package (the lines
from `def` to the last line of the body, nested functions counted on their own), longest first.

    python3 bench/code_metrics.py            # cpn/
    python3 bench/code_metrics.py cpn --limit 60

The pairs of places that share six or more lines, the other figure docs/internals.md gives, come from a
separate duplicate finder run in `cpn/`; import circles and upward imports are tests
(tests/test_layering.py).
"""

from __future__ import annotations

import argparse
import ast
import pathlib


def long_functions(root: pathlib.Path, limit: int) -> list[tuple[int, str]]:
    """(lines, "path:line name") of every function of the package longer than `limit` lines."""
    rows = []
    for path in sorted(root.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                n = node.end_lineno - node.lineno + 1
                if n > limit:
                    rows.append((n, f"{path}:{node.lineno} {node.name}"))
    return sorted(rows, key=lambda r: (-r[0], r[1]))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("package", nargs="?", default="cpn")
    ap.add_argument("--limit", type=int, default=60)
    args = ap.parse_args()
    rows = long_functions(pathlib.Path(args.package), args.limit)
    for n, where in rows:
        print(f"{n:5} {where}")
    print(f"{len(rows)} functions over {args.limit} lines in {args.package}/")


if __name__ == "__main__":
    main()
