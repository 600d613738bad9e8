"""`use "file.cpnet";`: the global declarations and modules of another model file, read as if written at
the place of the `use`, so that two models share modules without copying them (docs/language.md).

What a used file gives: its colour sets, variables, constants, functions, exceptions, `local` blocks,
symmetry declarations and modules, with their own positions (an error in them names the used file). What
it does not give: its `net` header and its top page (places, transitions, arcs and instances), which are
that model's own net. A used file may use others; a path is relative to the file that names it.
Imports `cpn.lang.ast` and layer 0.
"""

from __future__ import annotations

import os
from collections.abc import Callable

from cpn.diagnostics import Diagnostic
from cpn.errors import ModelSyntaxError
from cpn.lang import ast as A

_GIVEN = (A.ColsetDecl, A.VarDecl, A.ValDecl, A.FunDecl, A.ExceptionDecl, A.LocalDecl, A.SymmetryDecl,
          A.ModuleDecl)


def expand_uses(decls: list, filename: str, source: str, parse: Callable, using: tuple[str, ...] = ()) -> list:
    """`decls` with every top-level `use` replaced by what the used file gives (recursively).

    `parse(text, filename, using=...)` parses a used file; `using` holds the files being expanded (a cycle is an
    error). Raises `ModelSyntaxError` at the `use` for a file that cannot be read, a cycle, or a `use`
    inside a module.
    """
    out: list = []
    for d in decls:
        if isinstance(d, A.ModuleDecl):
            inner = [b for b in d.body if isinstance(b, A.UseDecl)]
            if inner:
                raise ModelSyntaxError([Diagnostic(
                    "E0101", "'use' inside a module: a used file gives global declarations and modules",
                    inner[0].span, hint="Move the 'use' to the top level of the file.")], {filename: source})
            out.append(d)
        elif isinstance(d, A.UseDecl):
            out.extend(_given(d, filename, source, parse, using))
        else:
            out.append(d)
    return out


def _given(use: A.UseDecl, filename: str, source: str, parse: Callable, using: tuple[str, ...]) -> list:
    base = os.path.dirname(filename) if filename and not filename.startswith("<") else "."
    path = os.path.normpath(os.path.join(base, use.path))
    here = os.path.normpath(filename)

    def fail(message: str, hint: str) -> ModelSyntaxError:
        return ModelSyntaxError([Diagnostic("E0501", message, use.path_span, hint=hint)], {filename: source})

    if path in using or path == here:
        chain = " -> ".join([*using, here, path]) if here not in using else " -> ".join([*using, path])
        raise fail(f"'{use.path}' uses itself ({chain})", "A file cannot use a file that uses it.")
    try:
        with open(path, encoding="utf-8-sig") as fh:
            text = fh.read()
    except FileNotFoundError:
        raise fail(f"no such model file: '{path}'",
                   "The path of a 'use' is relative to the folder of the file that names it.") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise fail(f"cannot read '{path}': {exc}", "A used file is a .cpnet model file in UTF-8.") from None
    model = parse(text, path, using=(*using, here))
    return [d for d in model.decls if isinstance(d, _GIVEN)]
