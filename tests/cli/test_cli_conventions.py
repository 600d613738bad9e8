"""The conventions of the command line and its reports: a default memory limit, output paths checked before
any work, capped listings, lint over every file, '-' for every output, wide integer columns, one
command-line convention (exit statuses, --quiet), every dead marking with its marking and trace, and docs
whose examples run (the README's test command is .ci/run's last line)."""

import json
import os
import re
import shutil
import subprocess
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tests", "statespace"))

from _toy import dining_philosophers, pt_net  # noqa: E402

import cpn  # noqa: E402
import cpn.cli.explore as explore  # noqa: E402
from cpn.cli.main import build_parser, main  # noqa: E402
from cpn.report import build_report, render_text, to_json  # noqa: E402
from cpn.statespace import ExploreOptions, Explorer, replay  # noqa: E402
from tests._shared import SHARED, needs_shared  # noqa: E402

EXAMPLES = os.path.join(ROOT, "models", "examples")
SAMPLES = os.path.join(SHARED, "cpntools-samples")

COUNTER = """net Counter;
colset INT = int;
var n : INT;
place P : INT = 1`0;
trans Inc;
arc P -> Inc : n;
arc Inc -> P : n + 1;
"""

ONE_PLACE = """net One;
colset U = unit;
place P : U = 1`();
trans T;
arc P -> T : ();
"""


@pytest.fixture
def toy(monkeypatch, tmp_path):
    """`explore` on a toy engine: the model file exists, loading is replaced and recorded."""
    model = tmp_path / "toy.cpnet"
    model.write_text("(* replaced by a toy engine *)\n")
    state = {"engine": dining_philosophers(3), "loaded": 0}

    def load(path, sets, time_condensation):
        state["loaded"] += 1
        return state["engine"]

    monkeypatch.setattr(explore, "load_engine", load)
    return str(model), state


def _write(tmp_path, name, text):
    p = tmp_path / name
    p.write_text(text)
    return str(p)


def _report(engine, **limits):
    return build_report(Explorer(engine, ExploreOptions(**limits)).run(), model="toy")


# ---------------------------------------------------------------------- a default memory limit


def test_help_states_the_default_memory_limit(capsys):
    from cpn.statespace.options import default_max_memory_mb

    assert main(["explore", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert f"(default {default_max_memory_mb():,.0f}: 50% of the memory of this machine" in text


def test_the_default_follows_a_lower_limit_of_the_process():
    code = ("import resource; resource.setrlimit(resource.RLIMIT_AS, (1 << 30, 1 << 30)); "
            "from cpn.statespace.options import default_max_memory_mb; print(default_max_memory_mb())")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 0, p.stderr
    assert float(p.stdout) == 512.0


def test_an_unbounded_model_ends_with_a_partial_report_instead_of_dying(tmp_path):
    """Under `ulimit -v` 700 MB and without --max-memory, the search used to die with MemoryError."""
    model = _write(tmp_path, "counter.cpnet", COUNTER)
    limit = 700_000_000

    def ulimit():
        import resource

        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))

    p = subprocess.run([sys.executable, "-m", "cpn", "explore", model, "--json", "-", "--max-seconds", "300"],
                       capture_output=True, text=True, cwd=ROOT, preexec_fn=ulimit, timeout=600)
    assert p.returncode == 2, p.stderr[-2000:]
    d = json.loads(p.stdout)
    assert d["statespace"]["stop_reason"] == "max_memory" and d["statespace"]["unexpanded"] >= 1
    assert d["options"]["max_memory_is_default"] is True
    assert d["options"]["max_memory_mb"] == pytest.approx(limit / 1048576 / 2, abs=1)
    assert "the default limit: raise it with --max-memory" in p.stderr and "Traceback" not in p.stderr


def test_max_memory_0_is_no_limit_and_an_explicit_limit_is_recorded(toy, capsys):
    model, _ = toy
    assert main(["explore", model, "--max-memory", "0", "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["options"]["max_memory_mb"] is None and d["options"]["max_memory_is_default"] is False
    assert main(["explore", model, "--max-memory", "5000", "--json", "-"]) == 0
    assert json.loads(capsys.readouterr().out)["options"]["max_memory_mb"] == 5000


# ---------------------------------------------------------------------- outputs checked first


@pytest.mark.parametrize("option,where", [("--json", "missing/o.json"), ("--json", "."),
                                          ("--dot", "missing/g.dot"), ("--graphml", "file/g.graphml")])
def test_an_unwritable_output_is_refused_before_loading(toy, tmp_path, capsys, option, where):
    model, state = toy
    (tmp_path / "file").write_text("a file, not a folder")
    path = str(tmp_path / where) if where != "." else str(tmp_path)
    assert main(["explore", model, option, path]) == 73
    err = capsys.readouterr().err
    assert err.startswith(f"error: cannot write {option} {path}: ") and "Traceback" not in err
    assert state["loaded"] == 0


@needs_shared
def test_every_subcommand_checks_its_outputs_first(tmp_path, capsys):
    bad = str(tmp_path / "missing" / "out")
    model = os.path.join(EXAMPLES, "stations.cpnet")
    assert main(["lint", model, "--json", bad]) == 73
    assert main(["simulate", model, "--json", bad]) == 73
    assert main(["convert", os.path.join(SAMPLES, "DiningPhilosophers.cpn"), "-o", bad]) == 73
    assert main(["validate", os.path.join(SHARED, "validation"), "--json", bad]) == 73
    captured = capsys.readouterr()
    assert captured.err.count("error: cannot write") == 4 and "Traceback" not in captured.err
    assert captured.out == ""


def test_two_outputs_to_stdout_are_a_usage_error(toy, capsys):
    model, state = toy
    assert main(["explore", model, "--json", "-", "--dot", "-"]) == 64
    assert "only one output can go to standard output" in capsys.readouterr().err
    assert state["loaded"] == 0


# ---------------------------------------------------------------------- long listings are cut


def test_a_long_multiset_bound_is_cut_and_the_json_keeps_it(tmp_path):
    engine = cpn.load(_write(tmp_path, "counter.cpnet", COUNTER)).engine()
    r = _report(engine, max_states=500)
    text = render_text(r)
    assert "1`19++" in text and "1`20++" not in text
    assert "... 480 more colours not shown (the JSON result lists all" in text
    assert len(text.splitlines()) < 150
    upper = to_json(r)["multiset_bounds"]["Counter'P 1"]["upper"]
    assert upper.count("++") == 499 and upper.endswith("1`499")
    assert "1`499" in render_text(r, max_listed=None)


def test_max_listed_sets_every_cap(tmp_path, capsys):
    model = _write(tmp_path, "counter.cpnet", COUNTER)
    assert main(["explore", model, "--max-states", "60", "--max-listed", "5", "--quiet"]) == 2
    out = capsys.readouterr().out
    assert "1`4++" in out and "1`5++" not in out and "55 more colours" in out
    assert main(["explore", model, "--max-states", "60", "--max-listed", "0", "--quiet"]) == 2
    out = capsys.readouterr().out
    assert "1`59" in out and "more colours" not in out


def test_a_long_trace_is_cut_in_the_text_only():
    chain = 130  # a chain of transitions: one dead marking 130 steps away
    pre = [[1 if p == t else 0 for p in range(chain + 1)] for t in range(chain)]
    post = [[1 if p == t + 1 else 0 for p in range(chain + 1)] for t in range(chain)]
    r = _report(pt_net(pre, post, [1] + [0] * chain))
    text = render_text(r)
    assert "     100. Top'T99 1" in text and "     101. " not in text
    assert "... 30 more steps not shown (the JSON result has the whole trace" in text
    assert len(to_json(r)["dead_markings"]["listed"][0]["trace"]) == 130


# ---------------------------------------------------------------------- lint checks every file


def test_lint_checks_every_file_and_exits_with_the_worst_status(tmp_path, capsys):
    good = os.path.join(EXAMPLES, "stations.cpnet")
    bad = _write(tmp_path, "bad.cpnet", "colset C = int;\nplace P : D;\n")
    assert main(["lint", good, str(tmp_path / "missing.cpnet"), bad, good]) == 64
    captured = capsys.readouterr()
    assert captured.out.count(f"{good}: ok") == 2
    assert "no such model file" in captured.err and "bad.cpnet:2:" in captured.err
    assert main(["lint", good, bad]) == 65
    assert f"{good}: ok" in capsys.readouterr().out


@pytest.mark.parametrize("text", ["", "\n\n", "(* only a comment *)\nnet Nothing;\ncolset U = unit;\n"])
def test_lint_warns_about_an_empty_model(tmp_path, capsys, text):
    path = _write(tmp_path, "empty.cpnet", text)
    assert main(["lint", path]) == 0
    err = capsys.readouterr().err
    assert f"{path}:1:1: warning[W0103]: the model declares no place and no transition" in err
    assert main(["lint", path, "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert [x["code"] for x in d["models"][0]["diagnostics"]] == ["W0103"]


# ---------------------------------------------------------------------- '-' for every output


@needs_shared
def test_dash_is_stdout_for_every_output(toy, tmp_path, monkeypatch, capsys):
    model, _ = toy
    monkeypatch.chdir(tmp_path)
    assert main(["explore", model, "--dot", "-"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("digraph statespace {") and "CPN Tools state space report" not in out
    assert main(["explore", model, "--graphml", "-"]) == 0
    assert capsys.readouterr().out.startswith("<graphml")
    stations = os.path.join(EXAMPLES, "stations.cpnet")
    assert main(["simulate", stations, "--steps", "3", "--json", "-"]) == 0
    assert len(json.loads(capsys.readouterr().out)["steps"]) == 3
    assert main(["lint", stations, "--json", "-"]) == 0
    assert json.loads(capsys.readouterr().out)["models"][0]["status"] == "ok"
    assert main(["convert", os.path.join(SAMPLES, "DiningPhilosophers.cpn"), "-o", "-"]) == 0
    assert "place Unused_Chopsticks" in capsys.readouterr().out
    assert os.listdir(tmp_path) == ["toy.cpnet"]  # no file named '-'


# ---------------------------------------------------------------------- wide integer columns


def test_integer_bound_columns_never_run_together():
    big = 123_456_789_012_345
    r = _report(pt_net([[big + 1, 0]], [[0, 1]], [big, 7]))  # nothing is enabled: one state
    lines = render_text(r).splitlines()
    row = next(line for line in lines if line.startswith("     Top'P0 1 "))
    assert row.split() == ["Top'P0", "1", str(big), str(big)]
    header = lines[lines.index("  Best Integer Bounds") + 1]
    assert header.index("Lower") == row.rindex(str(big)) and header.index("Upper") == row.index(str(big))


def test_docs_say_that_int_is_unbounded_unlike_cpn_tools():
    with open(os.path.join(ROOT, "docs", "statespace.md"), encoding="utf-8") as fh:
        doc = " ".join(fh.read().split())
    assert "CPN ML's `int` is unbounded here" in doc and "1,073,741,823" in doc and "`intinf`" in doc


# ---------------------------------------------------------------------- one convention


def test_exit_statuses_are_one_enum():
    from cpn.cli._common import ExitStatus

    assert {s.name: int(s) for s in ExitStatus} == {
        "OK": 0, "VIOLATED": 1, "UNKNOWN": 2, "USAGE": 64, "DATAERR": 65, "SOFTWARE": 70, "CANTCREAT": 73,
        "INTERRUPTED": 130}
    assert ExitStatus.worst([0, 65, 2]) is ExitStatus.DATAERR and ExitStatus.worst([]) is ExitStatus.OK


def test_quiet_means_the_same_in_every_subcommand():
    from cpn.cli._common import QUIET_HELP

    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")
    for name in ("lint", "simulate", "explore", "convert", "validate"):
        helps = [a.help for a in sub.choices[name]._actions if a.dest == "quiet"]
        assert helps == [QUIET_HELP], name


@needs_shared
def test_quiet_drops_confirmations_and_notes(tmp_path, capsys):
    stations = os.path.join(EXAMPLES, "stations.cpnet")
    assert main(["lint", "--quiet", stations]) == 0
    assert capsys.readouterr().out == ""
    assert main(["simulate", "--quiet", stations, "--steps", "2"]) == 0
    assert "stopped after" not in capsys.readouterr().out
    out = tmp_path / "dp.cpnet"
    assert main(["convert", "--quiet", os.path.join(SAMPLES, "DiningPhilosophers.cpn"), "-o", str(out)]) == 0
    assert capsys.readouterr().err == "" and out.exists()


def test_an_unknown_flag_prints_the_subcommands_usage(capsys):
    assert main(["lint", "--bogus", os.path.join(EXAMPLES, "stations.cpnet")]) == 64
    err = capsys.readouterr().err
    assert err.startswith("usage: cpn-verify lint ") and "unrecognized arguments: --bogus" in err


def test_the_progress_line_fits_the_terminal():
    from cpn.cli._search_args import progress_text
    from cpn.statespace import Progress

    p = Progress(states=1_234_567_890, arcs=98_765_432_100, queue=123_456_789, seconds=86_400.5,
                 memory_mb=123_456.0)
    for width in (20, 40, 60, 80, 100):
        assert len(progress_text(p, width)) < width
    wide = progress_text(p, 200)
    assert "states 1,234,567,890" in wide and "states/s" in wide and "MiB" in wide
    assert progress_text(p, 80).startswith("exploring  states 1,234,567,890  arcs 98,765,432,100")


def test_one_is_singular(tmp_path, capsys):
    one = _write(tmp_path, "one.cpnet", ONE_PLACE)
    assert main(["lint", one]) == 0
    assert "ok (1 place instance, 1 transition instance)" in capsys.readouterr().out
    assert main(["simulate", os.path.join(EXAMPLES, "stations.cpnet"), "--steps", "1"]) == 0
    assert "stopped after 1 step (--steps 1)" in capsys.readouterr().out
    assert main(["simulate", one, "--steps", "5"]) == 0
    assert "dead marking after 1 step:" in capsys.readouterr().out
    assert main(["explore", _write(tmp_path, "c.cpnet", COUNTER), "--max-states", "3"]) == 2
    captured = capsys.readouterr()
    assert "1 unexpanded node)" in captured.out and "1 unexpanded node, which is not a dead marking" in captured.out
    assert "1 state was not expanded" in captured.err
    assert "(1 step)" in render_text(_report(pt_net([[1]], [[0]], [1])))


@needs_shared
def test_convert_without_o_writes_to_stdout_not_beside_its_input(tmp_path, capsys):
    net = tmp_path / "DiningPhilosophers.cpn"
    shutil.copy(os.path.join(SAMPLES, "DiningPhilosophers.cpn"), net)
    assert main(["convert", str(net)]) == 0
    assert "place Unused_Chopsticks : CS = CS.all();" in capsys.readouterr().out
    assert os.listdir(tmp_path) == ["DiningPhilosophers.cpn"]


# ---------------------------------------------------------------------- every dead marking


def _choice(n: int):
    """One token and n transitions, each moving it to its own place: n dead markings, one step away."""
    pre = [[1] + [0] * n for _ in range(n)]
    post = [[0] + [1 if p == t else 0 for p in range(n)] for t in range(n)]
    return pt_net(pre, post, [1] + [0] * n)


def test_each_dead_marking_is_listed_with_its_marking_and_a_shortest_trace():
    engine = _choice(3)
    x = Explorer(engine).run()
    r = build_report(x, model="toy")
    d = to_json(r)["dead_markings"]
    assert d["count"] == 3 and d["listed_cap"] == 10
    assert [e["node"] for e in d["listed"]] == [2, 3, 4]
    assert [e["marking"] for e in d["listed"]] == [{"Top'P1 1": "1`()"}, {"Top'P2 1": "1`()"},
                                                    {"Top'P3 1": "1`()"}]
    assert d["trace"] == d["listed"][0]["trace"]  # the existing key keeps its meaning
    for listed in r.dead_listed:
        assert replay(engine, x.graph, listed.trace) and listed.trace.target == listed.state
    text = render_text(r)
    for node, t in ((2, 0), (3, 1), (4, 2)):
        assert f"  Dead marking {node}\n          Top'P{t + 1} 1: 1`()\n" in text
        assert f"  Shortest trace to dead marking {node} (1 step)\n     1. Top'T{t} 1" in text


def test_the_listing_of_dead_markings_is_capped_and_says_so():
    r = _report(_choice(12))
    assert len(r.dead_listed) == 10 and len(to_json(r)["dead_markings"]["listed"]) == 10
    text = render_text(r)
    assert text.count("  Shortest trace to dead marking") == 10
    assert "(10 of 12 dead markings listed with a trace" in text


def test_trace_to_dead_shows_the_changes_of_every_listed_trace(toy, capsys):
    model, state = toy
    state["engine"] = _choice(2)
    assert main(["explore", model]) == 0
    assert "-> 1`()" not in capsys.readouterr().out
    assert main(["explore", model, "--trace-to-dead"]) == 0
    assert capsys.readouterr().out.count("          Top'P0 1: 1`() -> empty") == 2


# ---------------------------------------------------------------------- docs that run


def test_the_python_example_of_docs_statespace_runs(monkeypatch):
    with open(os.path.join(ROOT, "docs", "statespace.md"), encoding="utf-8") as fh:
        doc = fh.read()
    code = re.search(r"```python\n(.*?)```", doc, re.S).group(1)
    monkeypatch.chdir(ROOT)
    exec(compile(code, "docs/statespace.md", "exec"), {})  # noqa: S102 - the doc's own example


def _doc(name):
    with open(os.path.join(ROOT, "docs", name), encoding="utf-8") as fh:
        return " ".join(fh.read().split())


def test_cancelling_a_timer_token_that_is_not_ready(capsys):
    path = os.path.join(EXAMPLES, "timer_cancel.cpnet")
    engine = cpn.load(path).engine()
    x = Explorer(engine).run()
    dead = x.graph.dead_states()
    assert (x.n_states, x.n_arcs, [i + 1 for i in dead]) == (12, 11, [6, 11, 12])
    assert "It has 12 states, 11 arcs and 3 dead markings (nodes 6, 11 and 12)" in _doc("patterns.md")
    place = {p.name: p.index for p in engine.places}
    names = [t.name for t in engine.transitions]
    for i in dead:  # no stale timer is left behind
        assert engine.format_marking(x.graph.states[i], place["TimerCancel'Timer 1"]) == "empty"
    g = x.graph
    for i in range(g.expanded):  # a cancelled timer never expires
        done = engine.format_marking(g.states[i], place["TimerCancel'Done 1"]) != "empty"
        for be, _j in g.out_arcs(i):
            if done:
                assert not engine.format_binding_element(be).startswith("TimerCancel'Expire")
    assert "TimerCancel'Discard 1" in names
    assert main(["explore", path]) == 0
    out = capsys.readouterr().out
    assert "  Dead marking 6 (model time 5)\n          TimerCancel'Sends 1: 1`1" in out
    assert "     3. TimerCancel'Discard 1: {g=1, k=0}" in out


def test_one_frame_to_several_listeners(capsys):
    path = os.path.join(EXAMPLES, "broadcast.cpnet")
    assert main(["explore", path, "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert (d["statespace"]["states"], d["statespace"]["arcs"], d["dead_markings"]["count"]) == (81, 234, 1)
    assert d["dead_markings"]["listed"][0]["marking"] == {
        f"Listener'Received {i}": "1`1++1`2" for i in (1, 2, 3)}
    assert "three listener instances: 81 states, 234 arcs, one dead marking" in _doc("patterns.md")
    assert main(["explore", path, "--set", "N=5", "--json", "-"]) == 0
    left = json.loads(capsys.readouterr().out)["dead_markings"]["listed"][0]["marking"]["Broadcast'Bus 1"]
    assert left == "1`(4,1)++1`(4,2)++1`(5,1)++1`(5,2)"


def test_exit_1_is_promised_only_for_check():
    from cpn.cli._common import EPILOG

    with open(os.path.join(ROOT, "README.md"), encoding="utf-8") as fh:
        readme = fh.read()
    flat = " ".join(readme.split())
    assert "1 a property is violated (only `cpn-verify check` verifies properties, so only it exits 1)" in flat
    assert "1   a property is violated (only 'cpn-verify check' verifies properties)" in EPILOG
    assert "explore` verifies no property, so it never exits 1" in _doc("statespace.md")
    blocks = re.findall(r"```sh\n(.*?)```", readme, re.S)
    assert blocks[:2] == [
        "python3 -m pip install . && cpn-verify check specs/modbus specs/examples && cpn-verify explore "
        "--time-condensation models/examples/stop_and_wait.cpnet\n",
        "python3 -m pip install -e '.[test]' && ruff check cpn tests bench && pytest -n auto --dist loadfile\n",
    ]
    # .ci/run runs exactly the README's test command, as its last line
    with open(os.path.join(ROOT, ".ci", "run"), encoding="utf-8") as fh:
        assert fh.read().splitlines()[-1] + "\n" == blocks[1]


def test_a_large_dead_marking_is_cut_in_the_text(tmp_path):
    model = _write(tmp_path, "fill.cpnet", """net Fill;
colset N = int with 0..29;
place Todo : N = N.all();
place Done : N;
trans MoveAll;
arc Todo -> MoveAll : N.all();
arc MoveAll -> Done : N.all();
""")
    r = _report(cpn.load(model).engine())
    text = render_text(r)
    assert "          Fill'Done 1: 1`0++1`1++" in text and "++1`19++... (10 more colours)" in text
    assert to_json(r)["dead_markings"]["listed"][0]["marking"]["Fill'Done 1"].endswith("1`29")


def test_max_listed_also_sets_how_many_dead_markings_are_listed(toy, capsys):
    model, state = toy
    state["engine"] = _choice(12)
    assert main(["explore", model, "--max-listed", "0", "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)["dead_markings"]
    assert len(d["listed"]) == 12 and d["listed_cap"] is None
    assert main(["explore", model, "--max-listed", "3"]) == 0
    assert "(3 of 12 dead markings listed with a trace" in capsys.readouterr().out


WIDE = """colset C = int with 0..1999;
colset U = unit;
var x : C;
var n : INT;
place P : C = C.all();
place Q : INT = 1`0;
trans T;
arc P <-> T : x;
arc Q -> T : n;
arc T -> Q : n * 2000 + x;
"""


def test_limits_are_looked_at_between_expansions_of_states_with_many_successors(monkeypatch):
    """Memory used to be read every 512 expansions only: with 2,000 successors per state that is a
    million stored states between two readings, far past the limit."""
    from cpn.statespace import ExploreOptions, Explorer, StopReason

    looked_at = []

    def check_limits(self, n_states, n_arcs, queue):
        looked_at.append(n_states)
        return StopReason.MAX_MEMORY  # as if the limit were reached at the first reading

    monkeypatch.setattr(Explorer, "_check_limits", check_limits)
    engine = cpn.loads(WIDE, "wide.cpnet").engine()
    x = Explorer(engine, ExploreOptions()).run()
    assert x.stop_reason is StopReason.MAX_MEMORY
    # the first reading comes after about 65,536 arcs (33 expansions), not after 512 expansions
    assert looked_at and looked_at[0] < 100_000 and x.n_states < 100_000


def test_a_run_time_error_after_one_step_says_one_step():
    from cpn.errors import EvaluationError

    model = cpn.loads("colset C = int with 0..2;\nvar x : C;\nplace P : C = 1`1;\nplace Q : C;\n"
                      "trans A;\narc P -> A : x;\narc A -> Q : x - 1;\ntrans B;\narc Q -> B : x;\n"
                      "arc B -> P : 1 div x;\n", "one.cpnet")
    from cpn.statespace import ExploreOptions, Explorer

    with pytest.raises(EvaluationError) as info:
        Explorer(model.engine(), ExploreOptions()).run()
    text = info.value.render()
    assert "reached after 1 step from the initial marking" in text, text
