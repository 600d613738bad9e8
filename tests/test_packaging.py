"""What a user installs has every file the package reads at run time (cpn/_util/resources.py: the grammar
and the build manifest's C, cpn/_native/manifest.py), and a native build that cannot happen falls back to
the Python search with one note (cpn/_util/cbuild.py).

The whole path (the README's main command after `pip install .`, the wheel built from the sdist in a fresh
virtual environment, run from another folder) is `.ci/install-check`, which `.ci/run` runs before the tests.
"""

from __future__ import annotations

import ast
import os
import subprocess
import sys
import tarfile
import zipfile

import pytest

from cpn._native import manifest
from cpn._util import cbuild, resources
from tests._shared import ROOT

PACKAGE = os.path.join(ROOT, "cpn")


def test_every_data_file_of_the_package_is_on_the_list():
    on_disk = {os.path.relpath(os.path.join(folder, f), PACKAGE).replace(os.sep, "/")
               for folder, _, files in os.walk(PACKAGE) for f in files if not f.endswith((".py", ".pyc"))
               and "__pycache__" not in folder}
    assert on_disk == set(resources.DATA_FILES)


def test_no_module_reads_a_file_beside_it_but_through_the_list():
    """`open(... __file__ ...)` would read a file that pyproject.toml may not ship: every data file is read
    through cpn._util.resources.read_text."""
    offenders = []
    for folder, _, files in os.walk(PACKAGE):
        for f in files:
            if f.endswith(".py"):
                path = os.path.join(folder, f)
                with open(path, encoding="utf-8") as fh:
                    tree = ast.parse(fh.read())
                for node in ast.walk(tree):
                    if isinstance(node, ast.Call) and getattr(node.func, "id", None) == "open" and any(
                            isinstance(n, ast.Name) and n.id == "__file__" for n in ast.walk(node)):
                        offenders.append(f"{os.path.relpath(path, ROOT)}:{node.lineno}")
    assert not offenders


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """The sdist and the wheel, built from a copy of the tracked files (as CI's fresh clone has them)."""
    tmp = tmp_path_factory.mktemp("build")
    src, dist = tmp / "src", tmp / "dist"
    files = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True).stdout
    src.mkdir()
    for name in filter(None, files.decode().split("\0")):
        if name.startswith(("cpn/", "pyproject.toml", "README.md")) and os.path.isfile(os.path.join(ROOT, name)):
            target = src / name
            target.parent.mkdir(parents=True, exist_ok=True)
            with open(os.path.join(ROOT, name), "rb") as a, open(target, "wb") as b:
                b.write(a.read())
    # the sdist, then the wheel built from the sdist (PyPA's `build`, in isolated environments)
    out = subprocess.run([sys.executable, "-m", "build", "--outdir", str(dist), str(src)], capture_output=True,
                         text=True, timeout=600)
    assert out.returncode == 0, (out.stdout + out.stderr)[-3000:]
    (sdist,), (wheel,) = dist.glob("*.tar.gz"), dist.glob("*.whl")
    return sdist, wheel


def _data_files(names: list[str]) -> set[str]:
    """The files under cpn/ among `names` (paths in an archive) that are not Python modules."""
    return {n for n in names if n.startswith("cpn/") and not n.endswith("/") and not n.endswith((".py", ".pyc"))}


def test_the_wheel_and_the_sdist_ship_exactly_the_data_files(built):
    sdist, wheel = built
    in_wheel = _data_files(zipfile.ZipFile(wheel).namelist())
    in_sdist = _data_files([m.name.split("/", 1)[1] for m in tarfile.open(sdist).getmembers()
                            if m.isfile() and "/" in m.name])
    listed = {f"cpn/{name}" for name in resources.DATA_FILES}
    assert in_wheel == listed, f"the wheel differs from DATA_FILES: {sorted(in_wheel ^ listed)}"
    assert in_sdist == listed, f"the sdist differs from DATA_FILES: {sorted(in_sdist ^ listed)}"
    # the C of the build manifest, headers too
    assert {f"cpn/{name}" for name in manifest.DATA_FILES} <= in_wheel
    assert any(name.endswith(".h") for name in manifest.DATA_FILES)


def test_a_data_file_missing_from_the_installation_is_a_clear_error(monkeypatch):
    monkeypatch.setattr(resources.resources, "files", lambda _: _Missing())
    with pytest.raises(resources.ResourceMissing, match="_native/_cnet.c cannot be read.*reinstall"):
        resources.read_text("_native/_cnet.c")
    assert cbuild.build("store") is None
    assert "cpn/_native/_packed.c cannot be read" in cbuild.why_unavailable()


class _Missing:
    def joinpath(self, name):
        return self

    def read_text(self, encoding=None):
        raise FileNotFoundError(2, "No such file or directory")


NET = os.path.join(ROOT, "bench", "nets", "ms.cpnet")


def _explore(tmp_path, env: dict, *args: str) -> subprocess.CompletedProcess:
    full = {**os.environ, "CPN_CACHE_DIR": str(tmp_path / "cache"), **env}
    return subprocess.run([sys.executable, "-m", "cpn", "explore", NET, "--set", "N=2", *args], cwd=tmp_path,
                          env=full, capture_output=True, text=True, timeout=600)


def _unwritable(tmp_path) -> dict:
    blocker = tmp_path / "a-file"
    blocker.write_text("")
    return {"CPN_CACHE_DIR": str(blocker / "cache")}  # below a file: cannot be made, even by root


@pytest.mark.parametrize("case, env, says", [
    ("no compiler", {"CC": "/nonexistent/cc"}, "no C compiler found"),
    ("failing compiler", {"CC": "false"}, "no C compiler found"),
    ("unwritable cache", None, "compile cache"),
    ("switched off", {"CPN_NO_NATIVE": "1"}, None),
])
def test_a_native_build_that_cannot_happen_falls_back_to_python(tmp_path, case, env, says):
    env = _unwritable(tmp_path) if env is None else env
    out = _explore(tmp_path, env)
    assert out.returncode == 0, out.stderr
    assert "Status: Full" in out.stdout and "Nodes:  189" in out.stdout
    assert "Traceback" not in out.stderr and "internal error" not in out.stderr
    notes = [line for line in out.stderr.splitlines() if line.startswith("note:")]
    if says is None:  # the user's own choice asks nothing of them: no note without --verbose
        assert notes == []
    else:
        assert len(notes) == 1 and says in notes[0], out.stderr


def test_a_note_that_asks_something_is_said_once_on_a_partial_search_too(tmp_path):
    out = _explore(tmp_path, {"CC": "/nonexistent/cc"}, "--max-states", "50")
    assert out.returncode == 2, out.stderr
    assert out.stderr.count("no C compiler found") == 1, out.stderr


def test_the_compiler_failing_on_the_source_falls_back(tmp_path, monkeypatch):
    monkeypatch.setenv("CPN_CACHE_DIR", str(tmp_path))
    assert cbuild.load_library("this is not C", "int f(void);") is None
    assert cbuild.why_unavailable().startswith("the C compiler failed") or \
        cbuild.why_unavailable().startswith("no C compiler")


def test_switched_off_stops_the_threads_before_any_c_is_made(tmp_path, monkeypatch):
    import cpn
    from cpn.engine import ccodegen
    from cpn.statespace import ExploreOptions, Explorer

    made = []
    real = ccodegen.native_code
    monkeypatch.setattr(ccodegen, "native_code", lambda engine: made.append(1) or real(engine))
    monkeypatch.setenv("CPN_NO_NATIVE", "1")
    monkeypatch.setenv("CPN_CACHE_DIR", str(tmp_path))
    x = Explorer(cpn.load(NET, set={"N": 2}).engine(), ExploreOptions(workers=2, threads=True)).run()
    assert x.n_states == 189 and x.backend == "workers"
    assert made == []
    assert any("CPN_NO_NATIVE" in n for n in x.notes)


def test_a_grammar_missing_from_the_installation_is_one_line_not_a_traceback(tmp_path):
    """The grammar has no fallback: the command says what is missing and exits 70, without a traceback."""
    code = ("import sys; from cpn._util import resources\n"
            "class Missing:\n"
            "    def joinpath(self, name): return self\n"
            "    def read_text(self, encoding=None): raise FileNotFoundError(2, 'No such file or directory')\n"
            "resources.resources.files = lambda _: Missing()\n"
            "from cpn.cli.main import main\n"
            f"sys.exit(main(['lint', {os.path.join(ROOT, 'models', 'examples', 'stations.cpnet')!r}]))\n")
    out = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=300,
                         env={**os.environ, "PYTHONPATH": ROOT})
    assert out.returncode == 70, out.stderr
    assert "Traceback" not in out.stderr
    assert "cpn/lang/grammar.lark cannot be read" in out.stderr and "reinstall" in out.stderr
