"""The importers: chosen by suffix in one registry (PNML, CPN Tools), each a subpackage of cpn.io keeping its
import path, both answering the origin of a generated line; a suffix no importer reads is refused."""

import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_importers_are_chosen_by_suffix_in_one_registry():
    from cpn.io import IMPORTERS, importer_for

    assert [imp.name for imp in IMPORTERS] == ["PNML", "CPN Tools"]
    assert importer_for("a/B.PNML").module == "cpn.io.pnml" and importer_for("x.cpn").name == "CPN Tools"
    assert importer_for("m.cpnet") is None and importer_for("m.xml") is None


PT = ('<?xml version="1.0"?><pnml xmlns="http://www.pnml.org/version-2009/grammar/pnml">'
      '<net id="n" type="http://www.pnml.org/version-2009/grammar/ptnet"><page id="pg">\n'
      '<place id="p"/>\n<transition id="t"/>\n<arc id="a" source="p" target="t"/>\n'
      '</page></net></pnml>')


def test_both_translations_answer_origin_and_keep_the_generated_span_on_request(tmp_path):
    from cpn.diagnostics import Diagnostic, Span
    from cpn.errors import ModelError
    from cpn.io import importer_for

    path = tmp_path / "m.pnml"
    path.write_text(PT)
    importer = importer_for(path)
    tr = importer.translate(path)
    arc_line = tr.text.splitlines().index("arc p -> t;") + 1
    assert tr.origin(arc_line).line == 4 and tr.notes == []
    err = ModelError([Diagnostic("E0301", "type mismatch", Span("m.cpnet", arc_line, 5))])
    moved = importer.remap_error(err, tr, "m.cpnet").diagnostics[0]
    kept = importer.remap_error(err, tr, "m.cpnet", keep_generated_span=True).diagnostics[0]
    assert (moved.span.file, moved.span.line) == (str(path), 4)
    assert (kept.span.file, kept.span.line) == ("m.cpnet", arc_line) and f"{path}:4" in kept.notes[-1]


def test_convert_refuses_a_suffix_no_importer_reads(tmp_path):
    from cpn.cli.main import main

    path = tmp_path / "net.xml"
    path.write_text(PT)
    assert main(["convert", str(path)]) == 64


def test_each_importer_is_a_subpackage_and_keeps_its_import_path():
    import cpn.io.cpntools
    import cpn.io.pnml

    for module in (cpn.io.pnml, cpn.io.cpntools):
        assert module.__file__.endswith("__init__.py")
        assert callable(module.translate_file) and callable(module.remap_error) and callable(module.translate)
    from cpn.io.pnml import write_text  # noqa: F401 - the writer is still there
    assert not list((ROOT / "cpn" / "io").glob("_pnml_*.py")) and not list((ROOT / "cpn" / "io").glob("_cpntools_*.py"))
