"""`use` files as CPN Tools models name them: relative to the model, with Windows separators
(`"lib\\\\util.sml"`), a folder of the author's machine (`"C:\\\\work\\\\Util.sml"`: the file name is looked for
beside the model, in any case), and one clear error naming the paths tried when the file is not there."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import ModelError
from tests.io.test_cpntools import DECLS, cpn_xml, page, place


def _model(tmp_path, use: str):
    decls = DECLS + f'<use id="U1"><ml>{use}</ml></use>'
    model = tmp_path / "m.cpn"
    model.write_text(cpn_xml(decls, page("PG1", "Top", place("P1", "A", "INT", "1`(twice 21)"))))
    return model


def test_a_path_with_backslashes_is_read_relative_to_the_model(tmp_path):
    (tmp_path / "lib").mkdir()
    (tmp_path / "lib" / "util.sml").write_text("fun twice n = 2 * n;\n")
    model = _model(tmp_path, '"lib\\\\util.sml"')
    assert cpn.load(str(model)).net.places[0].initial == {42: 1}


def test_a_folder_of_the_authors_machine_finds_the_file_beside_the_model_in_any_case(tmp_path):
    (tmp_path / "util.SML").write_text("fun twice n = 2 * n;\n")
    model = _model(tmp_path, '"C:\\\\work\\\\models\\\\Util.sml"')
    assert cpn.load(str(model)).net.places[0].initial == {42: 1}


def test_a_missing_file_is_one_error_naming_the_paths_tried(tmp_path):
    model = _model(tmp_path, '"C:\\\\work\\\\models\\\\Util.sml"')
    with pytest.raises(ModelError) as exc:
        cpn.load(str(model))
    errors = [d for d in exc.value.diagnostics if d.code.startswith("E")]
    assert len(errors) == 1, [d.message for d in errors]
    message = errors[0].message
    assert "cannot read the ML file" in message and "'Util.sml'" in message
    assert "Put 'Util.sml' next to the model" in (errors[0].hint or "")
