"""The mutants of a model: operators applied at the positions of the syntax tree, numbered in source order,
drawn by a seed."""

import pathlib

from cpn.gate.mutants import OPERATORS, mutants, select
from cpn.lang.parser import parse

HERE = pathlib.Path(__file__).parent
SOURCE = (HERE / "counter.cpnet").read_text(encoding="utf-8")


def found(source=SOURCE, **kw):
    return mutants(parse(source, "counter.cpnet"), **kw)


def line_of(m, source=SOURCE) -> str:
    """The mutant's text of the line the mutant starts at ('' where the edit deleted the last line)."""
    lines = m.apply(source).splitlines()
    return lines[m.span.line - 1] if m.span.line <= len(lines) else ""


def by_change(ms):
    return {(m.operator, str(m.span), line_of(m).strip()) for m in ms}


def test_each_operator_edits_the_text_at_its_node():
    ms = found()
    assert [m.number for m in ms] == list(range(1, len(ms) + 1))
    assert [(m.span.line, m.span.col) for m in ms] == sorted((m.span.line, m.span.col) for m in ms)
    changes = by_change(ms)
    for expected in [
        ("comparison-changed", "counter.cpnet:14:14", "trans inc [n <= Max];"),
        ("guard-negated", "counter.cpnet:14:12", "trans inc [not (n < Max)];"),
        ("guard-dropped", "counter.cpnet:14:12", "trans inc [true];"),
        ("priority-changed", "counter.cpnet:14:20", "trans inc [n < Max] priority 100;"),
        ("arithmetic-changed", "counter.cpnet:16:22", "arc inc -> Count : n - 1;"),
        ("constant-changed", "counter.cpnet:16:24", "arc inc -> Count : n + 2;"),
        ("constant-changed", "counter.cpnet:4:11", "val Max = 2;"),
        ("token-duplicated", "counter.cpnet:16:20", "arc inc -> Count : (n + 1) ++ (n + 1);"),
        ("arc-one-way", "counter.cpnet:17:11", "arc Token -> inc : ();"),
        ("arc-one-way", "counter.cpnet:17:5", "arc inc -> Token : ();"),
        ("token-dropped", "counter.cpnet:12:16", "place Token : U;"),
        ("constant-changed", "counter.cpnet:11:21", "place Count : N = 1`~1;"),
    ]:
        assert expected in changes, expected
    removed = [m for m in ms if m.operator == "arc-removed"]
    assert [m.span.line for m in removed] == [15, 16, 17]
    assert "arc Count -> inc" not in removed[0].apply(SOURCE)
    assert len(removed[0].apply(SOURCE).splitlines()) == len(SOURCE.splitlines()) - 1  # the whole line
    assert {m.operator for m in ms} <= set(OPERATORS)


def test_a_diff_shows_the_changed_line_with_its_file():
    m = next(m for m in found() if m.operator == "comparison-changed")
    diff = m.diff(SOURCE)
    assert diff.splitlines()[:2] == ["--- counter.cpnet", f"+++ counter.cpnet ({m.ident})"]
    assert "-trans inc [n < Max];" in diff.splitlines() and "+trans inc [n <= Max];" in diff.splitlines()


def test_if_branches_conditions_and_delays():
    src = """colset U = unit timed; colset B = bool; var b : B;
place P : U = 1`(); place Q : U;
trans t [b andalso (b orelse false)] @+ 2;
arc P -> t : ();
arc t -> Q : (if b then 1`() else empty) @+ 3;
"""
    ms = mutants(parse(src, "m.cpnet"))
    texts = {(m.operator, line_of(m, src)) for m in ms}
    assert ("if-swapped", "arc t -> Q : ((if b then empty else 1`())) @+ 3;") in texts
    assert ("conjunct-dropped", "trans t [(b)] @+ 2;") in texts
    assert ("disjunct-dropped", "trans t [b andalso ((false))] @+ 2;") in texts
    assert ("boolean-flipped", "trans t [b andalso (b orelse true)] @+ 2;") in texts
    assert ("delay-changed", "trans t [b andalso (b orelse false)];") in texts
    assert ("delay-changed", "trans t [b andalso (b orelse false)] @+ (2) + 1;") in texts
    assert ("delay-changed", "arc t -> Q : (if b then 1`() else empty);") in texts


def test_values_every_run_sets_are_not_mutated():
    assert any("'Max'" in m.description for m in found())
    assert not any("'Max'" in m.description for m in found(skip_values=frozenset({"Max"})))


def test_the_same_seed_draws_the_same_mutants():
    ms = found()
    a, b = select(ms, 5, seed=7), select(ms, 5, seed=7)
    assert [m.number for m in a] == [m.number for m in b]
    assert len(a) == 5 and [m.number for m in a] == sorted(m.number for m in a)
    draws = {tuple(m.number for m in select(ms, 5, seed=s)) for s in range(6)}
    assert len(draws) > 1  # the seed matters
    assert select(ms, None, seed=3) == ms and select(ms, len(ms) + 4, seed=3) == ms
