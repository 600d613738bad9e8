"""`use "file.cpnet";` gives the declarations and modules of another model file (not its top page), so two
models share modules; a family of instances over an index colour set names its members by number
(Client1 for cl(1)), so that a symmetric family of module instances can follow a constant."""

import pytest

import cpn
from cpn.errors import ModelError
from cpn.statespace import ExploreOptions, Explorer

LIB = """
net Lib;
colset U = unit;
val N = 2;
module M { port io P : U; trans t; arc P -> t; }
place Top : U = 1`();                  (* the library's own top page: not given by 'use' *)
instance M1 = M { P = Top };
"""

MAIN = """
use "lib.cpnet";
place A : U = N`();
instance X = M { P = A };
"""


def _write(tmp_path, **files):
    for name, text in files.items():
        (tmp_path / name).write_text(text)


def test_use_gives_declarations_and_modules_but_not_the_top_page(tmp_path):
    _write(tmp_path, **{"lib.cpnet": LIB, "main.cpnet": MAIN})
    m = cpn.load(tmp_path / "main.cpnet", set={"N": 3})
    assert sorted(p.name for p in m.net.places) == ["Top'A 1"]
    assert sorted(t.name for t in m.net.transitions) == ["M't 1"]
    assert m.net.places[0].initial == {(): 3}   # the used file's N, set from outside


def test_use_in_a_used_file_is_relative_to_that_file(tmp_path):
    (tmp_path / "sub").mkdir()
    _write(tmp_path, **{"sub/lib.cpnet": LIB, "sub/mid.cpnet": 'use "lib.cpnet";\nval K = N + 1;\n',
                        "main.cpnet": 'use "sub/mid.cpnet";\nplace A : U = K`();\ninstance X = M { P = A };\n'})
    m = cpn.load(tmp_path / "main.cpnet")
    assert m.net.places[0].initial == {(): 3}


def test_errors_in_a_used_file_name_that_file(tmp_path):
    _write(tmp_path, **{"lib.cpnet": "colset U = unit;\nval N : U = 3;\n", "main.cpnet": 'use "lib.cpnet";\n'})
    with pytest.raises(ModelError) as exc:
        cpn.load(tmp_path / "main.cpnet")
    spans = [d.span for d in exc.value.diagnostics]
    assert spans and all(s.file.endswith("lib.cpnet") and s.line == 2 for s in spans)


@pytest.mark.parametrize("files, message, line, col", [
    ({"main.cpnet": 'colset U = unit;\nuse "none.cpnet";\n'}, "no such model file", 2, 5),
    ({"main.cpnet": 'use "main.cpnet";\n'}, "uses itself", 1, 5),
    ({"main.cpnet": 'use "b.cpnet";\n', "b.cpnet": 'use "main.cpnet";\n'}, "uses itself", 1, 5),
    ({"main.cpnet": 'colset U = unit;\nmodule M {\n  use "b.cpnet";\n}\n', "b.cpnet": ""}, "inside a module", 3, 3),
])
def test_use_errors_have_a_position_and_a_hint(tmp_path, files, message, line, col):
    _write(tmp_path, **files)
    with pytest.raises(ModelError) as exc:
        cpn.load(tmp_path / "main.cpnet")
    d = exc.value.diagnostics[0]
    assert message in d.message and d.hint
    assert (d.span.line, d.span.col) == (line, col)


def test_use_is_not_a_keyword_inside_expressions():
    m = cpn.loads("colset U = unit; fun use x = x + 1; val N = use 1; place A : U = N`();")
    assert m.net.places[0].initial == {(): 2}


SYM = """
val NC = 2;
colset CLI = index cl with 1..NC;
symmetry CLI = permutations;
colset U = unit;
module C(me : CLI) { port io P : CLI; place Id : U = 1`(); trans go; arc Id -> go; arc go -> P : me; }
place Pool : CLI;
instance Client[k : CLI] = C(me = k) { P = Pool };
"""


def test_a_family_over_an_index_colour_set_is_named_by_number_and_permuted_by_symmetry():
    m = cpn.loads(SYM, set={"NC": 3})
    assert sorted(t.name for t in m.net.transitions) == ["C'go 1", "C'go 2", "C'go 3"]
    engine = m.engine()
    full = Explorer(engine, ExploreOptions()).run()
    reduced = Explorer(engine, ExploreOptions(reduction="symmetry", symmetry=m.symmetry("CLI"))).run()
    assert full.n_states == 8 and reduced.n_states == 4
