"""A warning about a `.cpn` file points into that file, as an error does: `file.cpn:line:col` of the
element's text (what an editor or a CI annotation can open), with the line of the translated text in a
note; `lint` shows the `.cpn` line under it."""

import cpn
from cpn.cli.main import main
from cpn.errors import ModelError
from tests.io.test_cpntools import DECLS, arc, cpn_xml, page, place, trans


def _model(tmp_path):
    decls = DECLS + '<ml id="M2">fun Delay() = discrete(1,3);</ml>'
    body = (place("P1", "A", "S", "1`0") + trans("T1", "t", cond="Delay() > 1")
            + arc("A1", "PtoT", "T1", "P1", "x"))
    path = tmp_path / "t.cpn"
    path.write_text(cpn_xml(decls, page("PG1", "Top", body)))
    return path


def test_a_warning_points_at_the_cpn_file_where_explore_refuses_the_same_construct(tmp_path):
    path = _model(tmp_path)
    model = cpn.load(path)
    [w] = [w for w in model.warnings if w.code == "W0105"]
    assert w.span.file == str(path) and w.span.line > 1
    assert any("line" in n and "translated text" in n for n in w.notes)
    line = path.read_text().splitlines()[w.span.line - 1]
    assert "discrete" in line[w.span.col - 1:]  # the column is the draw's, in the .cpn file's line
    try:
        model.engine()
    except ModelError as exc:
        [d] = exc.diagnostics
    assert (d.span.file, d.span.line) == (w.span.file, w.span.line)


def test_lint_shows_the_cpn_line_under_a_warning(tmp_path, capsys):
    path = _model(tmp_path)
    assert main(["lint", str(path)]) == 0
    err = capsys.readouterr().err
    head = next(line for line in err.splitlines() if "warning[W0105]" in line)
    assert head.startswith(f"{path}:") and "(as .cpnet)" not in head
    shown = err.splitlines()[err.splitlines().index(head) + 2]
    assert "discrete(1,3)" in shown  # the declaration that draws, as the .cpn file has it
