"""Build C source into a shared library with the system C compiler, load it through cffi, cache the build.

The package's libraries are named in the build manifest (`cpn._native.manifest`): `build` compiles one of
them (its units in order, their headers written beside them, the net's generated C after them where the
library takes it) and declares to cffi what its headers declare between their cffi markers.

Nothing is compiled at install time: a library is built the first time it is needed, in the user's
cache directory (``$CPN_CACHE_DIR``, else ``$XDG_CACHE_HOME/cpn-verify``, else ``~/.cache/cpn-verify``),
named by a hash of the source, the headers, the declarations and the compiler's version, and reused from
there. The cache is bounded (`CACHE_MAX_MB`, 1,024 MiB, or CPN_CACHE_MAX_MB; 0: none): a build removes
the libraries used longest ago past it (`trim_cache`). Where a build cannot happen (CPN_NO_NATIVE is set,
cffi or a compiler is missing, the compiler fails, a C file of the package is missing, the cache cannot be
written), `build` and `load_library` return None and `why_unavailable` says why, so that callers fall back
to pure Python and say so.

Examples
--------
>>> lib = load_library("int twice(int x) { return 2 * x; }", "int twice(int x);")
>>> lib is None or lib.lib.twice(21) == 42
True
"""

from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import tempfile
from dataclasses import dataclass
from functools import lru_cache

from cpn._native import manifest
from cpn._util.resources import ResourceMissing, read_text

#: the flags every library is built with (after the optimisation level)
CFLAGS = ["-shared", "-fPIC", "-std=c99"]
_OPT_LEVELS = ("-O0", "-O1", "-O2", "-O3", "-Os")


def cflags() -> list[str]:
    """The compiler flags: CFLAGS after the optimisation level, `-O2` unless CPN_CC_OPT names another
    (the test suite builds with `-O0`, whose compilations take less time: tests/conftest.py)."""
    opt = os.environ.get("CPN_CC_OPT", "-O2")
    return [opt if opt in _OPT_LEVELS else "-O2", *CFLAGS]

_reason: list[str] = []


@dataclass(frozen=True)
class Library:
    """A loaded library: `ffi` (its cffi interface) and `lib` (its functions)."""

    ffi: object
    lib: object
    path: str


def cache_dir() -> str:
    """Where built libraries are kept."""
    env = os.environ.get("CPN_CACHE_DIR")
    if env:
        return env
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "cpn-verify")


@lru_cache(maxsize=1)
def compiler() -> tuple[str, str] | None:
    """(the C compiler's command, its version line), or None where there is none."""
    cc = os.environ.get("CC") or shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
    if not cc or not shutil.which(cc):
        return None
    try:
        out = subprocess.run([cc, "--version"], capture_output=True, text=True, timeout=30)
    except (OSError, subprocess.SubprocessError):
        return None
    if out.returncode != 0:
        return None
    return cc, (out.stdout.splitlines() or [""])[0]


def switched_off() -> str | None:
    """Why native code is not to be used at all (CPN_NO_NATIVE is set), or None."""
    if os.environ.get("CPN_NO_NATIVE"):
        return "native code is switched off (CPN_NO_NATIVE is set)"
    return None


@dataclass(frozen=True)
class Recipe:
    """What `load_library` builds a library of the manifest from: the one source (the defines, the units,
    the generated C), its headers (file name -> text), the cffi declarations and the extra flags."""

    source: str
    headers: dict[str, str]
    cdef: str
    flags: tuple[str, ...]


def recipe(name: str, generated: str = "") -> Recipe:
    """The recipe of library `name` of the manifest (`generated`: the net's C, for a library that takes
    it); `ResourceMissing` where a file of the package cannot be read."""
    lib = manifest.LIBRARIES[name]
    if lib.generated != bool(generated):
        raise ValueError(f"library '{name}' {'needs' if lib.generated else 'takes no'} generated C")
    units = manifest.units(name)
    parts = [f"#define {d}" for d in lib.defines] + [read_text(u.source) for u in units]
    if generated:
        parts.append(generated)
    headers = {h.rsplit("/", 1)[-1]: read_text(h) for h in manifest.headers(name)}
    cdef = "".join(manifest.declarations(read_text(u.header), f"cpn/{u.header}") for u in units)
    return Recipe("\n".join(parts), headers, cdef, lib.flags)


def build(name: str, generated: str = "") -> Library | None:
    """Library `name` of the manifest (`cpn._native.manifest.LIBRARIES`), with the net's C `generated`
    for a library that takes it; None where it cannot be built (`why_unavailable` says why)."""
    off = switched_off()
    if off is not None:
        return _unavailable(off)
    try:
        r = recipe(name, generated)
    except ResourceMissing as exc:
        return _unavailable(str(exc))
    return load_library(r.source, r.cdef, r.flags, r.headers)


def built(name: str, generated: str = "") -> bool:
    """Whether library `name` with the net's C `generated` is already built: loaded in this process or in
    the compile cache (then `build` only loads it)."""
    if switched_off() is not None:
        return False
    try:
        r = recipe(name, generated)
    except ResourceMissing:
        return False
    found = _cached(r.source, r.cdef, r.flags, r.headers)
    return not isinstance(found, str) and (found[0] in _loaded or os.path.exists(found[1]))


def note_built(hint: str, library: Library) -> None:
    """Record in the compile cache that `library` was built for what `hint` names (a caller's name for what
    it built, not the library's key): a file `built_<hint>` holding the library's file name, removed with
    the library (`trim_cache`); nothing where the cache cannot be written."""
    try:
        os.makedirs(cache_dir(), exist_ok=True)
        with open(os.path.join(cache_dir(), f"built_{hint}"), "w", encoding="ascii") as fh:
            fh.write(os.path.basename(library.path))
    except OSError:
        pass


def noted_built(hint: str) -> bool:
    """Whether `note_built(hint)` was called, in this process or an earlier one sharing the compile cache."""
    return os.path.exists(os.path.join(cache_dir(), f"built_{hint}"))


#: the compile cache's bound in MiB, unless CPN_CACHE_MAX_MB gives another (0: none): past it, a build
#: removes the libraries used longest ago (a net's C is a library per net and constants: a cache grows)
CACHE_MAX_MB: int = 1024


def cache_max_mb() -> float:
    """The compile cache's bound in MiB (0: none): CPN_CACHE_MAX_MB, else CACHE_MAX_MB."""
    try:
        return max(0.0, float(os.environ.get("CPN_CACHE_MAX_MB", CACHE_MAX_MB)))
    except ValueError:
        return float(CACHE_MAX_MB)


def trim_cache(directory: str, keep: str = "") -> int:
    """Remove the libraries of `directory` used longest ago (by their modification time, which a load
    refreshes) until it holds at most `cache_max_mb()`, never `keep`, and the records of `note_built` whose
    library is gone; the number of libraries removed. A library removed while a process has it loaded stays
    loaded there (its file is only unlinked)."""
    limit = cache_max_mb() * 1048576
    if not limit:
        return 0
    entries = []
    try:
        names = os.listdir(directory)
    except OSError:
        return 0
    for name in names:
        if name.startswith("cpn_") and name.endswith(".so"):
            path = os.path.join(directory, name)
            try:
                st = os.stat(path)
            except OSError:
                continue
            entries.append((st.st_mtime, path, st.st_size))
    total = sum(size for _t, _p, size in entries)
    removed = 0
    for _mtime, path, size in sorted(entries):
        if total <= limit:
            break
        if path == keep:
            continue
        try:
            os.remove(path)
        except OSError:
            continue
        total -= size
        removed += 1
    if removed:
        _forget_removed(directory, names)
    return removed


def _forget_removed(directory: str, names: list[str]) -> None:
    """Remove the records of `note_built` in `directory` (among `names`) that name a library no longer there
    (a record that names none, written before records named their library, is left)."""
    for name in names:
        if not name.startswith("built_"):
            continue
        path = os.path.join(directory, name)
        try:
            with open(path, encoding="ascii") as fh:
                library = fh.read().strip()
            if library and not os.path.exists(os.path.join(directory, library)):
                os.remove(path)
        except (OSError, ValueError):
            continue


def why_unavailable() -> str | None:
    """Why the last `load_library` returned None (None if it did not)."""
    return _reason[-1] if _reason else None


def _unavailable(reason: str) -> None:
    _reason.append(reason)
    return None


_loaded: dict[str, Library] = {}


def cache_key(source: str, cdef: str, compiler_version: str, flags: list[str], headers: dict[str, str],
              cffi_version: str) -> str:
    """The name of a built library in the cache: a hash of everything the build reads."""
    parts = [source, cdef, compiler_version, " ".join(flags), cffi_version]
    for name in sorted(headers):
        parts += [name, headers[name]]
    return hashlib.sha256("\0".join(parts).encode()).hexdigest()[:24]


def _cached(source: str, cdef: str, flags, headers: dict[str, str]) -> tuple[str, str] | str:
    """(the cache key, the path in the compile cache) of the library built from these, or why it cannot be
    built (cffi or a compiler missing)."""
    try:
        import cffi
    except ImportError:
        return "cffi is not installed"
    cc = compiler()
    if cc is None:
        return "no C compiler found (set CC or install cc/gcc/clang)"
    key = cache_key(source, cdef, cc[1], cflags() + list(flags), headers, cffi.__version__)
    return key, os.path.join(cache_dir(), f"cpn_{key}.so")


def _build(source: str, headers: dict[str, str], flags: tuple[str, ...], path: str, directory: str) -> str | None:
    """Build the library at `path` (in a folder of its own, moved in place at once), then bound the cache;
    why it could not be built, or None."""
    try:
        os.makedirs(directory, exist_ok=True)
    except OSError as err:
        return (f"the compile cache {directory} cannot be made ({err.strerror or err}); "
                "set CPN_CACHE_DIR to a writable folder")
    try:
        with tempfile.TemporaryDirectory(dir=directory) as tmp:
            src = os.path.join(tmp, "lib.c")
            with open(src, "w") as f:
                f.write(source)
            for name, text in headers.items():
                with open(os.path.join(tmp, name), "w") as f:
                    f.write(text)
            out = os.path.join(tmp, "lib.so")
            res = subprocess.run([compiler()[0], *cflags(), *flags, "-I", tmp, "-o", out, src], capture_output=True,
                                 text=True, timeout=300)
            if res.returncode != 0:
                first = (res.stderr.strip().splitlines() or ["no message"])[0]
                return f"the C compiler failed: {first}"
            os.replace(out, path)  # atomic: a concurrent build of the same key is harmless
        trim_cache(directory, keep=path)
    except (OSError, subprocess.SubprocessError) as err:
        where = f" in the compile cache {directory}" if isinstance(err, OSError) else ""
        return (f"could not build native code{where}: {getattr(err, 'strerror', None) or err}"
                + ("; set CPN_CACHE_DIR to a writable folder" if where else ""))
    return None


def load_library(source: str, cdef: str, flags: tuple[str, ...] = (),
                 headers: dict[str, str] | None = None) -> Library | None:
    """The library built from C `source` whose functions `cdef` declares (built once, then cached);
    `flags`: more compiler flags than CFLAGS; `headers`: the files (name -> text) its `#include "..."`
    lines name, written beside the source. All are part of the cache key, as the source is."""
    headers = headers or {}
    off = switched_off()
    if off is not None:
        return _unavailable(off)
    found = _cached(source, cdef, flags, headers)
    if isinstance(found, str):
        return _unavailable(found)
    key, path = found
    if key in _loaded:
        return _loaded[key]
    import cffi

    directory = os.path.dirname(path)
    for attempt in (1, 2):
        if os.path.exists(path):
            try:
                os.utime(path)  # used now: the last the cache's bound removes (`trim_cache`)
            except OSError:
                pass
        else:
            why = _build(source, headers, flags, path, directory)
            if why is not None:
                return _unavailable(why)
        ffi = cffi.FFI()
        ffi.cdef(cdef)
        try:
            lib = ffi.dlopen(path)
            break
        except OSError as err:
            if attempt == 1 and not os.path.exists(path):
                continue  # removed meanwhile by another process's bound on the cache (`trim_cache`): built again
            return _unavailable(f"could not load native code: {err}")
    _loaded[key] = loaded = Library(ffi, lib, path)
    return loaded
