"""CPN Tools models that draw random values: they load (lint), simulate reproducibly, and explore refuses
them with one error per call of a distribution, at its place in the `.cpn` file or in a `use`d `.sml` file."""

from __future__ import annotations

import os

import pytest

import cpn
from cpn.cli.main import main
from cpn.errors import ModelError
from tests._shared import SHARED, needs_shared
from tests.io.test_cpntools import DECLS, arc, cpn_xml, page, place, trans

CORPUS = os.path.join(SHARED, "cpntools-corpus", "models")


def test_a_draw_in_a_used_sml_file_is_refused_at_its_line_in_that_file(tmp_path, capsys):
    (tmp_path / "lib.sml").write_text("fun delay () =\n  floor (exponential (0.5));\n")
    decls = DECLS + '<use id="U1"><ml>"lib.sml"</ml></use>'
    body = (place("P1", "A", "S", "1`0") + place("P2", "B", "INT") + trans("T1", "t")
            + arc("A1", "PtoT", "T1", "P1", "x") + arc("A2", "TtoP", "T1", "P2", "delay ()"))
    path = tmp_path / "m.cpn"
    path.write_text(cpn_xml(decls, page("PG1", "Top", body)))
    model = cpn.load(path)
    with pytest.raises(ModelError) as info:
        model.engine()
    [d] = info.value.diagnostics
    assert (d.code, d.span.file, d.span.line, d.span.col) == ("E0206", str(tmp_path / "lib.sml"), 2, 10)
    assert main(["simulate", str(path), "--steps", "1"]) == 0
    assert "Top't 1" in capsys.readouterr().out


@needs_shared
def test_a_corpus_model_refused_only_for_its_distributions_now_loads(capsys):
    # HCPN traffic control: 14 refusals at d2e5f54, all "'expTime' calls 'exponential'"
    path = os.path.join(CORPUS, "Danilo0liveira__HCPN_TRAFFIC_CONTROL__src__cpn_project.cpn")
    assert main(["lint", path]) == 0
    assert "simulate only" in capsys.readouterr().out
    assert main(["explore", path]) == 65
    err = capsys.readouterr().err
    assert err.count("error[E0206]: 'exponential' draws a random value") == 1  # one call, in expTime
    assert main(["simulate", path, "--steps", "5", "--seed", "3"]) == 0
