"""`load`: a model file of any supported format to a checked, flattened net and its engines.

The public door's main entry; imports every front-end layer (lang, net, io) and the engine.
"""

from __future__ import annotations

import os

from cpn.diagnostics import Diagnostic, Span
from cpn.errors import ConfigurationError, ModelError
from cpn.lang.overrides import parse_overrides, usage_error
from cpn.lang.parser import parse as _parse
from cpn.lang.typecheck import check as _check
from cpn.net.lower import lower as _lower


class Model:
    """A loaded model: its source, the checked declarations and the flattened net."""

    def __init__(self, path: str, source: str, net, warnings: list[Diagnostic]):
        self.path = path
        self.source = source
        self.net = net
        self.warnings = warnings
        self.translation = None  # for .pnml and .cpn files: the translation to .cpnet and its origins

    def engine(self, time_condensation: bool = False, reference: bool = False):
        from cpn.engine import compile_net

        return compile_net(self.net, time_condensation=time_condensation, reference=reference)

    @property
    def name(self) -> str:
        return self.net.name


def _normalise_overrides(values) -> dict[str, str]:
    out = {}
    for k, v in (values or {}).items():
        out[str(k)] = v if isinstance(v, str) else _ml_literal(v)
    return out


def _ml_literal(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return f"~{-v}" if v < 0 else str(v)
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    raise ConfigurationError(f"cannot use {v!r} as a CPN ML value; give it as CPN ML text")


def source_of(path: str) -> str:
    """The `.cpnet` source text of a model file (translated for PNML and CPN Tools files)."""
    lower = path.lower()
    if lower.endswith(".pnml"):
        from cpn.io import pnml

        return pnml.translate(path)
    if lower.endswith(".cpn"):
        from cpn.io import cpntools

        return cpntools.translate(path)
    try:
        with open(path, encoding="utf-8-sig") as fh:
            return fh.read()
    except UnicodeDecodeError as exc:
        raise ModelError([Diagnostic("E0501", f"the file is not UTF-8 text ({exc.reason})", Span(path, 1, 1))]) from None


def loads(text: str, filename: str = "<string>", set: dict | None = None) -> Model:  # noqa: A002
    """Load a model from `.cpnet` source text."""
    overrides = parse_overrides(_normalise_overrides(set))  # once, before checking: a bad value is a usage error
    try:
        model = _parse(text, filename)
        checked = _check(model, overrides)
        net = _lower(checked)
    except RecursionError:
        raise ModelError([Diagnostic("E0206", "the model is nested too deeply to be read (expressions or "
                                     "declarations inside thousands of parentheses)", Span(filename, 1, 1),
                                     hint="Split the expression with 'let' or auxiliary functions.")],
                         {filename: text}) from None
    return Model(filename, text, net, checked.warnings)


def _original_position(span: Span, translation) -> str:
    """Where a position of the translation of a .cpn or .pnml file comes from, in that file."""
    if span.file.lower().endswith(".pnml (as .cpnet)"):
        found = translation.locate(span.line)
    else:
        located = translation.locate(span.line, span.col)
        found = located[0] if located is not None else None
    return str(found if found is not None else span)


def load(path: str | os.PathLike, set: dict | None = None) -> Model:  # noqa: A002
    """Load a model file (`.cpnet`, `.pnml`, `.cpn`), check it and flatten it.

    Parameters
    ----------
    path : the model file.
    set : values for `val` constants, as CPN ML text or Python int/bool/str (`{"N": 8}`).

    Raises
    ------
    ModelError : with every diagnostic of the file.
    ConfigurationError : the file does not exist.
    """
    path = os.fspath(path)
    if not os.path.exists(path):
        raise ConfigurationError(f"no such model file: {path}")
    if os.path.isdir(path):
        raise ConfigurationError(f"{path} is a directory, not a model file")
    lower = path.lower()
    if lower.endswith((".pnml", ".cpn")):
        # foreign formats are translated to .cpnet text; errors in the translation point back at the file
        if lower.endswith(".pnml"):
            from cpn.io import pnml as fmt

            translation = fmt.translate_with_origins(path)
        else:
            from cpn.io import cpntools as fmt

            translation = fmt.translate_file(path)
        generated = f"{path} (as .cpnet)"
        try:
            model = loads(translation.text, generated, set)
        except ModelError as exc:
            raise fmt.remap_error(exc, translation, generated) from None
        except ConfigurationError as exc:
            problems = getattr(exc, "problems", None)
            if not problems:
                raise
            # a --set value that does not fit names the constant's declaration in the file the user has
            raise usage_error(problems, lambda span: _original_position(span, translation)) from None
        model.path = path
        model.translation = translation
        return model
    return loads(source_of(path), path, set)
