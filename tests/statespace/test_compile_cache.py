"""The compile cache is bounded (`cbuild.CACHE_MAX_MB`, CPN_CACHE_MAX_MB): a build removes the libraries
used longest ago past the bound, never the one it built, and a load marks a library used."""

from __future__ import annotations

import os

from cpn._util import cbuild


def _library(directory, name: str, size: int, mtime: float) -> str:
    path = os.path.join(directory, f"cpn_{name}.so")
    with open(path, "wb") as fh:
        fh.write(b"\0" * size)
    os.utime(path, (mtime, mtime))
    return path


def test_the_libraries_used_longest_ago_go_first_down_to_the_bound(tmp_path, monkeypatch):
    monkeypatch.setenv("CPN_CACHE_MAX_MB", "2")
    mib = 1048576
    old, older, kept, new = (_library(tmp_path, n, mib, t) for n, t in
                             (("old", 300), ("older", 200), ("kept", 100), ("new", 400)))
    other = tmp_path / "built_hint"  # what is not a library stays
    other.write_text("")
    assert cbuild.trim_cache(str(tmp_path), keep=kept) == 2
    assert sorted(os.listdir(tmp_path)) == ["built_hint", "cpn_kept.so", "cpn_new.so"]
    assert not os.path.exists(old) and not os.path.exists(older) and os.path.exists(new)



def test_the_records_of_what_was_built_go_with_their_libraries(tmp_path, monkeypatch):
    monkeypatch.setenv("CPN_CACHE_DIR", str(tmp_path))
    monkeypatch.setenv("CPN_CACHE_MAX_MB", "1")
    mib = 1048576
    old, new = _library(tmp_path, "old", mib, 100), _library(tmp_path, "new", mib, 200)
    cbuild.note_built("a", cbuild.Library(None, None, old))
    cbuild.note_built("b", cbuild.Library(None, None, new))
    assert cbuild.noted_built("a") and cbuild.noted_built("b") and not cbuild.noted_built("c")
    assert cbuild.trim_cache(str(tmp_path), keep=new) == 1
    assert not cbuild.noted_built("a") and cbuild.noted_built("b")  # the record of the removed library too
    assert sorted(os.listdir(tmp_path)) == ["built_b", "cpn_new.so"]

def test_no_bound_and_a_bad_bound(tmp_path, monkeypatch):
    _library(tmp_path, "a", 2 * 1048576, 100)
    monkeypatch.setenv("CPN_CACHE_MAX_MB", "0")
    assert cbuild.trim_cache(str(tmp_path)) == 0
    monkeypatch.setenv("CPN_CACHE_MAX_MB", "many")  # the default bound
    assert cbuild.cache_max_mb() == cbuild.CACHE_MAX_MB and cbuild.trim_cache(str(tmp_path)) == 0


def test_a_build_trims_and_a_load_marks_its_library_used(tmp_path, monkeypatch):
    monkeypatch.setenv("CPN_CACHE_DIR", str(tmp_path))
    monkeypatch.setenv("CPN_CACHE_MAX_MB", "0.001")  # about 1 KB: any library is past it
    stale = _library(tmp_path, "stale", 10, 100)
    source = "int thrice_for_the_cache_test(int x) { return 3 * x; }"
    lib = cbuild.load_library(source, "int thrice_for_the_cache_test(int x);")
    if lib is None:  # no compiler here: nothing to build, nothing trimmed
        assert cbuild.why_unavailable()
        return
    assert lib.lib.thrice_for_the_cache_test(2) == 6
    built = [n for n in os.listdir(tmp_path) if n.endswith(".so")]
    assert not os.path.exists(stale) and len(built) == 1  # the stale one removed, the new one kept
    path = os.path.join(tmp_path, built[0])
    os.utime(path, (100, 100))
    monkeypatch.setattr(cbuild, "_loaded", {})  # as a new process would
    assert cbuild.load_library(source, "int thrice_for_the_cache_test(int x);") is not None
    assert os.stat(path).st_mtime > 100


def test_a_library_another_process_removes_before_it_is_loaded_is_built_again(tmp_path, monkeypatch):
    monkeypatch.setenv("CPN_CACHE_DIR", str(tmp_path))
    source = "int twice_for_the_race_test(int x) { return 2 * x; }"
    cdef = "int twice_for_the_race_test(int x);"
    found = cbuild._cached(source, cdef, (), {})
    if isinstance(found, str):  # no compiler here: nothing to race for
        return
    _key, path = found
    assert cbuild._build(source, {}, (), path, str(tmp_path)) is None  # built by a run before, never loaded here
    builds = []
    real_build, real_utime = cbuild._build, os.utime

    def removed_once_seen(where, *args, **kw):  # another process's bound on the cache, right after the look
        real_utime(where, *args, **kw)
        if where == path and not builds:
            os.remove(where)

    monkeypatch.setattr(cbuild, "_build", lambda *a: builds.append(a) or real_build(*a))
    monkeypatch.setattr(cbuild.os, "utime", removed_once_seen)
    lib = cbuild.load_library(source, cdef)
    assert lib is not None and lib.lib.twice_for_the_race_test(21) == 42
    assert len(builds) == 1 and os.path.exists(path)
