"""`check` over a folder loads each model once per set of constant values: one parse per text (with the
bytes of the files it uses), one type check and one flattening per set of values, the generated code of
each transition compiled once; every run still gets an engine of its own, and the verdicts and reports
are byte for byte those of loading the model afresh for every run."""

import contextlib
import pathlib

import pytest

import cpn
import cpn.engine.compiled as compiled
import cpn.model
from cpn.cli.main import main

LIB = """
colset N = int with 0..9;
colset U = unit timed;
var n : N;
"""

MODEL = """
net Retry;
use "lib.cpnet";
val Max = 2;
place Tries : N = 1`0;
place Timer : U = 1`();
trans retry [n < Max] @+ 3;
arc Tries -> retry : n;
arc retry -> Tries : n + 1;
arc Timer -> retry : ();
arc retry -> Timer : ();
"""

SCENARIO = """
name = "{name}"
model = "retry.cpnet"

[set]
Max = {max}

[explore]
time_condensation = {condensed}

[[property]]
name = "the count stays below Max + 1"
kind = "invariant"
expr = "ms_to_col (Retry'Tries 1) <= Max"

[[property]]
name = "it stops at Max"
kind = "dead_markings"
count = 1
expr = "Retry'Tries 1 = (1`Max)"
"""

# two sets of values, each checked by two scenarios (one with time condensation, one without)
RUNS = [("two", 2, "false"), ("two_condensed", 2, "true"), ("four", 4, "false"), ("four_condensed", 4, "true")]


def _gate(folder: pathlib.Path) -> pathlib.Path:
    folder.mkdir(exist_ok=True)
    (folder / "lib.cpnet").write_text(LIB, encoding="utf-8")
    (folder / "retry.cpnet").write_text(MODEL, encoding="utf-8")
    for name, top, condensed in RUNS:
        (folder / f"{name}.toml").write_text(SCENARIO.format(name=name, max=top, condensed=condensed),
                                             encoding="utf-8")
    return folder


def _count(monkeypatch) -> dict:
    """Counts the parses, type checks and flattenings of `cpn.model`, the compilations of generated code
    and the engines built."""
    counts = {"parse": [], "check": [], "lower": [], "compile": [], "engine": []}

    def counting(what, real):
        def call(*args, **kw):
            counts[what].append(args[0] if what != "compile" else args[1])
            return real(*args, **kw)
        return call

    for what, module, name in [("parse", cpn.model, "_parse"), ("check", cpn.model, "_check"),
                               ("lower", cpn.model, "_lower")]:
        monkeypatch.setattr(module, name, counting(what, getattr(module, name)))
    monkeypatch.setattr(compiled, "compile", counting("compile", compile), raising=False)
    real_init = compiled.CompiledEngine.__init__

    def init(self, *args, **kw):
        counts["engine"].append(self)
        real_init(self, *args, **kw)

    monkeypatch.setattr(compiled.CompiledEngine, "__init__", init)
    compiled.compiled_code.cache_clear()  # an earlier test may have compiled the same text
    return counts


def test_a_folder_parses_its_model_once_and_checks_it_once_per_set_of_values(tmp_path, monkeypatch, capsys):
    folder = _gate(tmp_path / "gate")
    counts = _count(monkeypatch)
    # one process (with --jobs, each process of the check keeps a cache of its own)
    assert main(["check", str(folder), "--no-timings", "-q", "--no-reports", "--jobs", "1"]) == 0
    out = capsys.readouterr().out
    assert out.count("holds") >= 8  # two properties in each of the four runs
    assert len(counts["parse"]) == 1  # not one per run
    assert len(counts["check"]) == 2 and len(counts["lower"]) == 2  # one per set of values
    assert len(counts["engine"]) == 4 and len(set(map(id, counts["engine"]))) == 4  # an engine of its own per run
    transitions = [f for f in counts["compile"] if f.startswith("<cpn transition")]
    assert transitions == ["<cpn transition Retry'retry 1>"]  # the same text for both sets of values
    assert {e.time_condensation for e in counts["engine"]} == {False, True}


def test_the_key_holds_the_used_files_and_the_values(tmp_path, monkeypatch):
    folder = _gate(tmp_path)
    counts = _count(monkeypatch)
    path = folder / "retry.cpnet"
    with cpn.model.caching():
        first = cpn.load(path, set={"Max": 2})
        assert cpn.load(path, set={"Max": "2"}).net is first.net  # the same value, written otherwise
        assert cpn.load(path, set={"Max": 3}).net is not first.net
        (folder / "lib.cpnet").write_text(LIB.replace("0..9", "0..7"), encoding="utf-8")
        changed = cpn.load(path, set={"Max": 2})
    assert changed.net is not first.net and len(counts["parse"]) == 2  # the used file changed: parsed again
    assert (first.net.colsets["N"].high, changed.net.colsets["N"].high) == (9, 7)
    assert len(counts["check"]) == 3
    with cpn.model.caching():
        cpn.load(path, set={"Max": 2})
    assert len(counts["parse"]) == 3  # a cache lasts for one block (one check or mutate run)


def test_models_from_the_cache_do_not_share_their_mutable_parts(tmp_path):
    path = _gate(tmp_path) / "retry.cpnet"
    with cpn.model.caching():
        a, b = cpn.load(path), cpn.load(path)
        a.warnings.append("x")
        a.path = "elsewhere"
        assert b.warnings == [] and b.path == str(path)
        ea, eb = a.engine(), b.engine()
    assert ea is not eb and ea.store is not eb.store
    s = ea.initial_state()
    assert [eb.token_counts(t) for _, t in eb.successors(eb.initial_state())] == \
           [ea.token_counts(t) for _, t in ea.successors(s)]


@contextlib.contextmanager
def _no_cache():
    yield None


def _reports(folder, out, monkeypatch, cached: bool, capsys) -> tuple:
    with monkeypatch.context() as m:
        if not cached:
            m.setattr(cpn.model, "caching", _no_cache)
            m.setattr(compiled, "compiled_code", compiled.compiled_code.__wrapped__)
        code = main(["check", str(folder), "--no-timings", "-q", "--reports", str(out)])
    printed = capsys.readouterr().out
    return code, printed, {p.relative_to(out).as_posix(): p.read_bytes() for p in sorted(out.rglob("*")) if p.is_file()}


@pytest.mark.parametrize("extra", [[], ["specs/examples/ms.toml"]])
def test_the_reports_are_those_of_loading_afresh_for_every_run(tmp_path, monkeypatch, capsys, extra):
    folder = _gate(tmp_path / "gate")
    for f in extra:
        (folder / pathlib.Path(f).name).write_text(
            pathlib.Path(f).read_text(encoding="utf-8").replace('model = "../../', f'model = "{pathlib.Path.cwd().as_posix()}/'),
            encoding="utf-8")
    fresh = _reports(folder, tmp_path / "fresh", monkeypatch, False, capsys)
    once = _reports(folder, tmp_path / "once", monkeypatch, True, capsys)
    assert fresh[0] == once[0] == 0
    assert fresh[1] == once[1]
    assert len(fresh[2]) >= 3 * len(RUNS) and fresh[2] == once[2]


def test_mutate_loads_the_original_once_for_the_runs_of_its_gate(monkeypatch):
    from cpn.gate.mutation import mutate
    from cpn.gate.scenario import load_scenario

    here = pathlib.Path(__file__).parent.parent / "mutate"
    source = (here / "counter.cpnet").read_text(encoding="utf-8")
    counts = _count(monkeypatch)
    report = mutate([load_scenario(here / "weak.toml"), load_scenario(here / "strong.toml")], max_mutants=1, seed=1)
    assert report.models[0].runs == 2 and len(report.models[0].outcomes) == 1
    assert counts["parse"].count(source) == 1 and len(counts["check"]) == 1  # not once per run


def _flat(tree) -> bytes:
    """The tree's pickle without the pickler's memo: the values of its nodes, whatever shares what."""
    import io
    import pickle

    out = io.BytesIO()
    pickler = pickle.Pickler(out)
    pickler.fast = True
    pickler.dump(tree)
    return out.getvalue()


def test_a_kept_parse_is_copied_with_nodes_of_its_own_and_the_same_spans(tmp_path):
    path = _gate(tmp_path) / "retry.cpnet"
    text, name = path.read_text(encoding="utf-8"), str(path)
    cache = cpn.model.LoadCache()
    used = cpn.model._used_files(text, name)
    first, a, b = (cache.parse(text, name, used) for _ in range(3))
    assert len(cache.trees) == 1
    assert _flat(a) == _flat(b) == _flat(first)  # the same tree
    for x, y in zip(a.decls, b.decls):
        assert x is not y and x.span is y.span  # (the checker writes into the nodes; spans are immutable)
    arc = next(d for d in a.decls if type(d).__name__ == "ArcDecl")
    twin = b.decls[a.decls.index(arc)]
    assert arc.expr is not twin.expr and arc.expr.span is twin.expr.span
