"""Foreign model formats: PNML (`cpn.io.pnml`) and CPN Tools (`cpn.io.cpntools`), behind one registry.

Each importer translates its format into `.cpnet` source text, which then goes through the one front end
(parser, type checker, lowering, engine); its `Translation` also says where every generated line comes
from, so that errors point back into the foreign file. `importer_for(path)` chooses by file suffix: the
one place that does (`cpn.load`, `cpn-verify convert` and `validate` ask it). A new format is a
subpackage `cpn/io/<format>/` with `translate_file(path) -> Translation` and `remap_error(error,
translation, generated_name, keep_generated_span)`, and one line in `IMPORTERS`; its private modules
live inside it (`cpn/io/pnml/_terms.py`).

The PNML writer (`cpn.io.pnml.write`) prints a `.cpnet` model or a flattened net as PNML. Imports
`cpn.lang` (the writer reads the syntax tree), `cpn.net`, `cpn.values` and layer 0 (tests/test_layering.py).

Examples
--------
>>> importer_for("model.PNML").name, importer_for("net.cpn").module, importer_for("m.cpnet")
('PNML', 'cpn.io.cpntools', None)
"""

from __future__ import annotations

import importlib
import os
from dataclasses import dataclass
from typing import Protocol

from cpn.diagnostics import Span
from cpn.errors import ModelError


class Translation(Protocol):
    """The `.cpnet` text of a foreign file and the origin of its lines."""

    path: str  # the foreign file
    text: str  # the .cpnet source
    notes: list[str]  # what the translation approximated or left out

    def origin(self, line: int, col: int = 1) -> Span | None:
        """Where position (line, col) of `text` comes from in the foreign file, if known."""


@dataclass(frozen=True)
class Importer:
    """A foreign format: its name, its file suffixes and the module that translates it (imported on use)."""

    name: str
    suffixes: tuple[str, ...]
    module: str

    def translate(self, path: str | os.PathLike) -> Translation:
        """Translate the file; raises ModelError (E0501 unreadable, E0502 untranslatable)."""
        return importlib.import_module(self.module).translate_file(os.fspath(path))

    def remap_error(self, error: ModelError, translation: Translation, generated_name: str | None = None,
                    keep_generated_span: bool = False) -> ModelError:
        """Point the diagnostics of a failed load of the translation at the foreign file: their spans move
        there, or, with `keep_generated_span` (the translation is on disk), a note names the origin."""
        module = importlib.import_module(self.module)
        return module.remap_error(error, translation, generated_name, keep_generated_span=keep_generated_span)


IMPORTERS: list[Importer] = [
    Importer("PNML", (".pnml",), "cpn.io.pnml"),
    Importer("CPN Tools", (".cpn",), "cpn.io.cpntools"),
]


def importer_for(path: str | os.PathLike) -> Importer | None:
    """The importer of a file by its suffix (any case), or None for `.cpnet` and unknown suffixes."""
    lower = os.fspath(path).lower()
    return next((imp for imp in IMPORTERS if lower.endswith(imp.suffixes)), None)


__all__ = ["IMPORTERS", "Importer", "Translation", "importer_for"]
