"""A `use`d .sml file's declarations are read with the net's: the globbox declarations that only the file
names (`val FILE = "logs/log"`, used by the file's logging functions) are kept, not left out as unused."""

from __future__ import annotations

import cpn
from tests.io.test_cpntools import DECLS, cpn_xml, page, place


def test_a_declaration_only_a_used_file_names_is_kept(tmp_path):
    (tmp_path / "lib.sml").write_text('fun path n = PREFIX ^ Int.toString n;\n')
    decls = DECLS + '<ml id="M2">val PREFIX = "logs/log";</ml><use id="U1"><ml>"lib.sml"</ml></use>'
    model = tmp_path / "m.cpn"
    model.write_text(cpn_xml(decls, page("PG1", "Top", place("P1", "A", "INT", "1`(String.size (path 12))"))))
    assert cpn.load(str(model)).net.places[0].initial == {len("logs/log12"): 1}
