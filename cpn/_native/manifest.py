"""The build manifest of the package's C: which units (a `.c` file and its `.h`) make which library, in which
order, with which defines and flags, and the cffi declarations of a library, read from its headers.

Every place that compiles C asks for a library by its name here (`cpn._util.cbuild.build`); the package data
(`cpn._util.resources.DATA_FILES`, what pyproject.toml ships) is `DATA_FILES` below, and
tests/test_packaging.py checks the built wheel and sdist against it.

A library is one translation unit: its units' sources in order (each includes the headers of the units it
uses, written beside it at build time), then, for the libraries of a net, the C generated from the net's
inscriptions (`cpn.engine.ccodegen`), which calls `_cnet.c`'s helpers and `_search.c`'s `nd_put_group`.
What Python calls of a unit is declared in its header between the markers ``/* cffi: begin */`` and
``/* cffi: end */``: plain C declarations, no preprocessor line, which `declarations` takes out of the text
as they are (no preprocessor is run).

Examples
--------
>>> [unit.source for unit in units("search-timed")]
['_native/_packed.c', '_native/_search.c', '_native/_timed.c']
>>> declarations("int f(void);\\n/* cffi: begin */\\nint g(int x);\\n/* cffi: end */\\n")
'int g(int x);\\n'
"""

from __future__ import annotations

import re
from dataclasses import dataclass

#: the folder of the C, as a path under the `cpn` package
FOLDER = "_native"


@dataclass(frozen=True)
class Unit:
    """A C unit: `name` is its `.c` file and its `.h` file under FOLDER; `uses`, the units whose headers its
    files include (tests/statespace/test_native_manifest.py checks them against the `#include` lines)."""

    name: str
    uses: tuple[str, ...] = ()

    @property
    def source(self) -> str:
        return f"{FOLDER}/{self.name}.c"

    @property
    def header(self) -> str:
        return f"{FOLDER}/{self.name}.h"


@dataclass(frozen=True)
class Library:
    """A compiled library: its units in the order they are compiled, the macros defined before them, more
    compiler flags, and whether the C generated from a net follows them."""

    units: tuple[str, ...]
    defines: tuple[str, ...] = ()
    flags: tuple[str, ...] = ()
    generated: bool = False


UNITS: dict[str, Unit] = {u.name: u for u in (
    Unit("_packed"),                           # the packed state store
    Unit("_search", ("_packed",)),             # the native breadth-first search over transition groups
    Unit("_timed", ("_search",)),              # its driver for timed nets and nets with priorities
    Unit("_cnet", ("_search",)),               # the run-time of the C generated from a net
    Unit("_threads", ("_search", "_cnet")),    # the multi-threaded search
    Unit("_graph"),                            # the standard report's graph algorithms
)}

#: ND_THREADS: _cnet.c's tables are shared between threads; POSIX for the threads' barriers and clock
#: (-std=c99 alone declares neither)
_THREADED = ("_POSIX_C_SOURCE 200809L", "ND_THREADS", "ND_GENERATED")

LIBRARIES: dict[str, Library] = {
    "store": Library(("_packed",)),                                     # cpn.statespace.store
    "graph": Library(("_graph",)),                                      # cpn.statespace.graphnative
    "search": Library(("_packed", "_search")),                          # cpn.statespace.native
    "search-timed": Library(("_packed", "_search", "_timed")),          # cpn.statespace.nativetimed
    "search-timed-net": Library(("_packed", "_search", "_timed", "_cnet"), ("ND_GENERATED",),
                                generated=True),                        # cpn.statespace.nativetimed
    "search-net-threads": Library(("_packed", "_search", "_threads", "_cnet"), _THREADED, ("-pthread",),
                                  generated=True),                      # cpn.statespace.threads
}


def units(library: str) -> list[Unit]:
    """The units of `library`, in the order they are compiled."""
    return [UNITS[name] for name in LIBRARIES[library].units]


def headers(library: str) -> list[str]:
    """The headers `library`'s units include (theirs and those of the units they use), as paths under `cpn/`."""
    seen: list[str] = []

    def visit(name: str) -> None:
        for used in UNITS[name].uses:
            visit(used)
        if name not in seen:
            seen.append(name)

    for unit in LIBRARIES[library].units:
        visit(unit)
    return [UNITS[name].header for name in seen]


#: every C file of the package, as paths under `cpn/`
DATA_FILES: tuple[str, ...] = tuple(path for unit in UNITS.values() for path in (unit.source, unit.header))

_BEGIN, _END = "/* cffi: begin */", "/* cffi: end */"
_COMMENT = re.compile(r"/\*.*?\*/", re.S)


class HeaderError(ValueError):
    """A header's cffi declarations cannot be taken out of it (the reason, with the line)."""


def declarations(text: str, name: str = "<header>") -> str:
    """The declarations between the cffi markers of header `text` (one pair), comments taken out; a
    preprocessor line there is an error, since cffi reads the declarations without a preprocessor."""
    begin, end = text.find(_BEGIN), text.find(_END)
    if begin < 0 or end < begin or text.count(_BEGIN) != 1 or text.count(_END) != 1:
        raise HeaderError(f"{name}: expected one '{_BEGIN}' followed by one '{_END}'")
    start = begin + len(_BEGIN)
    body = text[start:end]
    first = text.count("\n", 0, start) + 1
    for k, line in enumerate(body.split("\n")):
        if line.lstrip().startswith("#"):
            raise HeaderError(f"{name}:{first + k}: a preprocessor line between the cffi markers "
                              f"({line.strip()}): cffi reads them without a preprocessor")
    lines = [line.rstrip() for line in _COMMENT.sub("", body).split("\n")]
    return "".join(line + "\n" for line in lines if line.strip())
