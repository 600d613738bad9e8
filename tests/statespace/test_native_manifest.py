"""The C as a component (cpn/_native): each unit has a header and includes the headers of what it uses, so
that it compiles on its own; the cffi declarations are read from the headers (none are Python strings);
one build manifest names the libraries, and the compiled library's cache key follows its headers."""

from __future__ import annotations

import ast
import os
import pathlib
import re
import subprocess

import pytest

from cpn._native import manifest
from cpn._util import cbuild, resources
from tests._shared import ROOT

PACKAGE = os.path.join(ROOT, "cpn")


def _text(path: str) -> str:
    with open(os.path.join(PACKAGE, path), encoding="utf-8") as f:
        return f.read()


def _includes(path: str) -> set[str]:
    """The package's headers that file `path` (under cpn/) includes, as unit names."""
    return {name for name in re.findall(r'^#include "(\w+)\.h"', _text(path), re.M)}


# ---------------------------------------------------------------------------- the reader
def test_the_declarations_are_the_text_between_the_markers_without_comments():
    header = ("#ifndef X\n#define X\nstatic int hidden(void);\n/* cffi: begin */\n"
              "typedef struct s s;  /* opaque */\n/* what Python calls */\nint f(s *p,\n      int n);\n"
              "/* cffi: end */\nstruct s { int a; };\n#endif\n")
    assert manifest.declarations(header) == "typedef struct s s;\nint f(s *p,\n      int n);\n"


@pytest.mark.parametrize("header, says", [
    ("int f(void);\n", "expected one '/* cffi: begin */'"),
    ("/* cffi: end */\nint f(void);\n/* cffi: begin */\n", "expected one"),
    ("/* cffi: begin */\nint f(void);\n/* cffi: end */\n/* cffi: begin */\n/* cffi: end */\n", "expected one"),
    ("/* cffi: begin */\nint f(void);\n#ifdef ND_THREADS\nint g(void);\n#endif\n/* cffi: end */\n",
     "x.h:3: a preprocessor line between the cffi markers (#ifdef ND_THREADS)"),
])
def test_a_header_whose_declarations_cannot_be_read_says_why(header, says):
    with pytest.raises(manifest.HeaderError, match=re.escape(says)):
        manifest.declarations(header, "x.h")


# ---------------------------------------------------------------------------- the units and their headers
def test_the_c_files_on_disk_are_the_manifests():
    on_disk = {f"{manifest.FOLDER}/{f}" for f in os.listdir(os.path.join(PACKAGE, manifest.FOLDER))
               if f.endswith((".c", ".h"))}
    assert on_disk == set(manifest.DATA_FILES)
    assert set(manifest.DATA_FILES) <= set(resources.DATA_FILES)
    used = {name for lib in manifest.LIBRARIES.values() for name in lib.units}
    assert used == set(manifest.UNITS), "a unit no library compiles"


@pytest.mark.parametrize("name", sorted(manifest.UNITS))
def test_a_unit_includes_its_header_and_those_of_the_units_it_uses(name):
    unit = manifest.UNITS[name]
    own = _includes(unit.source) | _includes(unit.header)
    assert name in _includes(unit.source), f"{unit.source} does not include its header"
    assert own - {name} == set(unit.uses), f"{unit.source} includes {sorted(own - {name})}, the manifest says {unit.uses}"


def test_a_library_compiles_what_its_units_use_before_them():
    for lib in manifest.LIBRARIES.values():
        for k, name in enumerate(lib.units):
            missing = set(manifest.UNITS[name].uses) - set(lib.units)
            assert not missing, f"{name} uses {missing}, which its library does not compile"
            # what a unit uses comes first, but for the net's run-time, which the threads call (a header suffices)
            later = [u for u in manifest.UNITS[name].uses if lib.units.index(u) > k]
            assert later in ([], ["_cnet"]), (name, later)


def _compile_alone(unit: manifest.Unit, defines: tuple[str, ...], tmp_path) -> subprocess.CompletedProcess:
    cc = cbuild.compiler()
    for h in manifest.headers(next(n for n, lib in manifest.LIBRARIES.items() if unit.name in lib.units)):
        (tmp_path / h.rsplit("/", 1)[-1]).write_text(_text(h))
    src = tmp_path / "unit.c"
    src.write_text("".join(f"#define {d}\n" for d in defines) + _text(unit.source))
    return subprocess.run([cc[0], "-fsyntax-only", "-std=c99", "-Werror=implicit-function-declaration",
                           "-I", str(tmp_path), str(src)], capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize("name", sorted(manifest.UNITS))
def test_every_unit_compiles_on_its_own_with_each_of_its_libraries_defines(name, tmp_path):
    """Nothing comes from the order in which a library puts the units together: each unit alone, with its
    headers, is a complete translation unit."""
    if cbuild.compiler() is None:
        pytest.skip("no C compiler")
    unit = manifest.UNITS[name]
    for lib in {lib.defines for lib in manifest.LIBRARIES.values() if name in lib.units}:
        out = _compile_alone(unit, lib, tmp_path)
        assert out.returncode == 0, f"{unit.source} with {lib}:\n{out.stderr[-2000:]}"


def test_a_unit_that_relies_on_another_being_compiled_first_fails_to_compile_alone(tmp_path):
    """The check above can fail: _search.c without its include is what it was before its header."""
    if cbuild.compiler() is None:
        pytest.skip("no C compiler")
    unit = manifest.UNITS["_search"]
    (tmp_path / "unit.c").write_text(_text(unit.source).replace('#include "_search.h"', ""))
    out = subprocess.run([cbuild.compiler()[0], "-fsyntax-only", "-std=c99", str(tmp_path / "unit.c")],
                         capture_output=True, text=True, timeout=120)
    assert out.returncode != 0 and "cs_store" in out.stderr


# ---------------------------------------------------------------------------- the declarations
_PROTOTYPE = re.compile(r"\b(cs|nd|nt|th|gr|gen)_\w+\s*\([^)]*\)\s*;")


def test_no_module_declares_c_functions_in_a_python_string():
    offenders = [f"{path.relative_to(ROOT)}:{node.lineno}"
                 for path in sorted(pathlib.Path(PACKAGE).rglob("*.py"))
                 for node in ast.walk(ast.parse(path.read_text(encoding="utf-8")))
                 if isinstance(node, ast.Constant) and isinstance(node.value, str) and _PROTOTYPE.search(node.value)]
    assert not offenders


def test_only_the_build_compiles_c_and_declares_it_to_cffi():
    """Every library is built by name from the manifest (cbuild.build): no module builds C of its own."""
    offenders = [f"{path.relative_to(ROOT)}:{node.lineno}"
                 for path in sorted(pathlib.Path(PACKAGE).rglob("*.py")) if path.name != "cbuild.py"
                 for node in ast.walk(ast.parse(path.read_text(encoding="utf-8")))
                 if isinstance(node, ast.Call) and (getattr(node.func, "id", None) == "load_library"
                                                    or getattr(node.func, "attr", None) in ("load_library", "cdef"))]
    assert not offenders


@pytest.mark.parametrize("name", sorted(manifest.LIBRARIES))
def test_every_librarys_declarations_are_read_by_cffi_and_defined_by_its_units(name):
    cffi = pytest.importorskip("cffi")
    r = cbuild.recipe(name, "/* the net's C */" if manifest.LIBRARIES[name].generated else "")
    cffi.FFI().cdef(r.cdef)
    declared = set(re.findall(r"\b(\w+)\s*\(", r.cdef))
    assert declared, name
    for fn in declared:
        if fn == "gen_new":  # the generated code's own
            continue
        assert re.search(rf"^[\w \*]*\b{fn}\(", r.source, re.M), f"{name}: {fn} is declared, not defined"


def test_the_search_library_declares_what_the_python_side_calls():
    cdef = cbuild.recipe("search-net-threads", "x").cdef
    for fn in ("cs_add_many", "nd_run", "nd_set_gen", "th_assemble", "gen_ms_table", "gen_new"):
        assert f" {fn}(" in cdef or f"*{fn}(" in cdef


# ---------------------------------------------------------------------------- the build
def _key(r: cbuild.Recipe) -> str:
    return cbuild.cache_key(r.source, r.cdef, "cc 1.0", cbuild.cflags() + list(r.flags), r.headers, "1.0")


@pytest.mark.parametrize("header", ["_native/_packed.h", "_native/_search.h"])
def test_the_cache_key_changes_when_a_header_changes(monkeypatch, header):
    before = _key(cbuild.recipe("search"))
    real = cbuild.read_text
    monkeypatch.setattr(cbuild, "read_text", lambda name: real(name) + ("\n/* changed */\n" if name == header else ""))
    changed = cbuild.recipe("search")
    assert changed.headers[header.rsplit("/", 1)[-1]].endswith("/* changed */\n")
    assert _key(changed) != before


def test_a_library_is_built_from_its_units_in_the_manifests_order_and_with_its_headers(tmp_path, monkeypatch):
    if cbuild.compiler() is None or cbuild.switched_off():
        pytest.skip("no native build here")
    pytest.importorskip("cffi")
    monkeypatch.setenv("CPN_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(cbuild, "_loaded", {})  # not the library an earlier test of this process loaded
    r = cbuild.recipe("search-timed")
    starts = [r.source.index(_text(u.source)) for u in manifest.units("search-timed")]
    assert starts == sorted(starts)
    assert set(r.headers) == {"_packed.h", "_search.h", "_timed.h"}
    lib = cbuild.build("search-timed")
    assert lib is not None, cbuild.why_unavailable()
    assert os.path.dirname(lib.path) == str(tmp_path)
    assert hasattr(lib.lib, "nt_run") and hasattr(lib.lib, "cs_new")


def test_the_net_library_takes_the_generated_code_and_the_others_do_not():
    with pytest.raises(ValueError, match="needs generated C"):
        cbuild.recipe("search-net-threads")
    with pytest.raises(ValueError, match="takes no generated C"):
        cbuild.recipe("search", "int x;")
