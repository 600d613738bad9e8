"""The files the package reads at run time besides its Python modules: one list, `DATA_FILES`, read
through one function, `read_text`.

The C files on the list are the build manifest's (`cpn._native.manifest.DATA_FILES`: every unit's `.c` and
`.h`). `pyproject.toml` ships them as package data; `tests/test_packaging.py` builds the wheel and the sdist
and checks that they hold exactly the files of the list besides the modules, and that every data file under
`cpn/` is on it. A file that an installation lacks raises `ResourceMissing` (an `OSError`), which the native
back end turns into a fallback to Python with a note.
"""

from __future__ import annotations

from importlib import resources

from cpn._native import manifest

#: every data file the package reads, as a path under the `cpn` package
DATA_FILES: tuple[str, ...] = ("lang/grammar.lark", *manifest.DATA_FILES)


class ResourceMissing(OSError):
    """A data file of the package cannot be read: the installation is incomplete."""


def read_text(name: str) -> str:
    """The text of data file `name` (a path under `cpn/` listed in DATA_FILES)."""
    if name not in DATA_FILES:
        raise ValueError(f"'{name}' is not one of the package's data files (cpn._util.resources.DATA_FILES)")
    try:
        return resources.files("cpn").joinpath(name).read_text(encoding="utf-8")
    except OSError as exc:
        raise ResourceMissing(f"cpn/{name} cannot be read ({exc.strerror or exc}): the installation is "
                              "incomplete; reinstall cpn-verify") from None
