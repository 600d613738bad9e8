"""CPN Tools models that only simulation can run: real-valued delays (`@++`), reference variables that are
constants (a `globref` with a literal, real ones included, never assigned) and CPN Tools' `ModelTime`. They
load, `simulate` runs them, and `explore` refuses them with one error per construct at its place in the file."""

from __future__ import annotations

import json
import os

import pytest

import cpn
from cpn.cli.main import main
from cpn.errors import ModelError
from tests._shared import SHARED, needs_shared
from tests.io.test_cpntools import arc, cpn_xml, page, place, trans

CORPUS = os.path.join(SHARED, "cpntools-corpus", "models")
DECLS = ('<color id="C1"><id>UT</id><unit/><timed/></color>'
         '<color id="C2"><id>ST</id><string/><timed/></color>'
         '<globref id="G1"><id>mean</id><ml>4.5</ml></globref>')


def real_time_net(tmp_path):
    body = (place("P1", "A", "UT", "1`()") + place("P2", "B", "ST")
            + trans("T1", "t", time="@++exponential(1.0/(!mean))")
            + arc("A1", "PtoT", "T1", "P1", "()") + arc("A2", "TtoP", "T1", "P2", "ModelTime.toString(time())@++0.5")
            + arc("A3", "TtoP", "T1", "P1", "()"))
    path = tmp_path / "m.cpn"
    path.write_text(cpn_xml(DECLS, page("PG1", "Top", body)))
    return path


def test_a_real_delay_and_a_real_globref_load_and_simulate(tmp_path, capsys):
    path = real_time_net(tmp_path)
    assert main(["lint", str(path)]) == 0
    assert "simulate only" in capsys.readouterr().out
    out = tmp_path / "run.json"
    assert main(["simulate", str(path), "--steps", "3", "--seed", "1", "--json", str(out)]) == 0
    run = json.loads(out.read_text())
    second = run["steps"][1]["time"]
    assert [s["binding_element"] for s in run["steps"]] == ["Top't 1: {}"] * 3 and 0 < second < 100
    # the second occurrence at a real time: ModelTime.toString gives it, and the token's time stamp is real
    assert f'1`"{second:g}"@' in run["final_marking"]["Top'B 1"]

def test_explore_refuses_each_real_delay_at_its_place_in_the_file(tmp_path):
    path = real_time_net(tmp_path)
    with pytest.raises(ModelError) as info:
        cpn.load(path).engine()
    lines = path.read_text().splitlines()

    def at(text):  # (line, col) of text in the file
        [(n, line)] = [(n, line) for n, line in enumerate(lines, 1) if text in line]
        return n, line.index(text) + 1

    found = sorted((d.code, d.span.file, d.span.line, d.span.col, d.params["name"]) for d in info.value.diagnostics)
    delay, draw, arc_delay = at("@++exponential"), at("exponential("), at("ModelTime.toString(time())@++")
    assert found == sorted([("E0206", str(path), *delay, "@++"), ("E0206", str(path), *draw, "exponential"),
                            ("E0206", str(path), *arc_delay, "@++")])


@needs_shared
@pytest.mark.parametrize("name", ["cpn-io__cpn-js__sample-cpn-models__TUE__discretemodel_task2",
                                  "selabhvl__cpnmcdctesting__CPNmodels__NatCPN__OriginalModel__VM"])
def test_corpus_models_with_real_delays_or_model_time_now_simulate(name, capsys):
    # refused at a4f029f: '@++' and globrefs with real values (the first), ModelTime.toString (the second)
    path = os.path.join(CORPUS, name + ".cpn")
    assert main(["lint", path]) == 0
    assert "simulate only" in capsys.readouterr().out
    assert main(["simulate", path, "--steps", "10", "--seed", "2"]) == 0
    assert main(["explore", path]) == 65
    assert "error[E0206]" in capsys.readouterr().err
