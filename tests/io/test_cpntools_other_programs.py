"""CPN Tools models whose code segments talk to another program (Comms/CPN's `ConnManagementLayer`) or read
a file (`TextIO.openIn`): they load with a warning (W0106) at each library call, `explore` refuses them with
one error (E0206) per call, and `simulate` runs them up to the occurrence that makes such a call, where it
stops with a run-time error (E0401) naming the function. A dangling arc is refused as CPN Tools refuses it."""

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
DECLS = ('<color id="C1"><id>UNIT</id><unit/></color><color id="C2"><id>STRING</id><string/></color>'
         '<var id="V1"><type><id>STRING</id></type><id>msg</id></var>'
         '<ml id="M1">fun recvstr (c) = ConnManagementLayer.receive (c, stringDecode)</ml>'
         '<ml id="M2">fun conn (c, p) = ConnManagementLayer.openConnection (c, "127.0.0.1", p)</ml>')


def comms_net(tmp_path, guard: str = ""):
    """`tick` puts a token back on its place; `talk` opens a connection and receives a message, in its
    code segment, when the place 'Go' holds a token (`guard` may keep it from ever occurring)."""
    body = (place("P1", "Idle", "UNIT", "1`()") + place("P2", "Go", "UNIT", "1`()") + place("P3", "Got", "STRING")
            + trans("T1", "tick") + arc("A1", "PtoT", "T1", "P1", "()") + arc("A2", "TtoP", "T1", "P1", "()")
            + trans("T2", "talk", cond=guard, code='input (); output (msg); action (conn ("c1", 9000); recvstr "c1");')
            + arc("A3", "PtoT", "T2", "P2", "()") + arc("A4", "TtoP", "T2", "P3", "msg"))
    path = tmp_path / "comms.cpn"
    path.write_text(cpn_xml(DECLS, page("PG1", "Top", body)))
    return path


def test_a_model_that_talks_to_another_program_loads_with_a_warning_at_each_call(tmp_path, capsys):
    assert main(["lint", str(comms_net(tmp_path))]) == 0
    out = capsys.readouterr()
    assert "simulate only" in out.out
    assert "warning[W0106]: 'ConnManagementLayer.openConnection' talks to another program" in out.err
    assert "warning[W0106]: 'ConnManagementLayer.receive' talks to another program" in out.err


def test_explore_refuses_it_with_one_error_per_call(tmp_path):
    path = comms_net(tmp_path)
    with pytest.raises(ModelError) as info:
        cpn.load(path).engine()
    found = sorted((d.code, d.params["name"], d.span.file) for d in info.value.diagnostics)
    assert found == [("E0206", "ConnManagementLayer.openConnection", str(path)),
                     ("E0206", "ConnManagementLayer.receive", str(path))]


def test_simulate_stops_at_the_occurrence_that_calls_it(tmp_path, capsys):
    path = comms_net(tmp_path)
    # seed 1: 'tick' occurs before 'talk' (the outputs of a binding element that does not occur are not
    # evaluated, so the run goes on until 'talk' occurs)
    assert main(["simulate", str(path), "--steps", "50", "--seed", "1"]) == 65
    out = capsys.readouterr()
    steps = [line for line in out.out.splitlines()[1:] if line.strip()]
    assert steps and all("Top'tick 1" in line for line in steps)
    assert "error[E0401]" in out.err and "transition 'Top'talk 1'" in out.err
    assert "'ConnManagementLayer.openConnection' talks to another program over a socket" in out.err
    assert "Traceback" not in out.err


def test_simulate_runs_a_model_whose_calls_never_occur(tmp_path, capsys):
    path = comms_net(tmp_path, guard="[1 = 2]")
    out = tmp_path / "run.json"
    assert main(["simulate", str(path), "--steps", "20", "--seed", "1", "--json", str(out)]) == 0
    assert len(json.loads(out.read_text())["steps"]) == 20


def test_reading_a_file_stops_simulate_at_the_occurrence(tmp_path, capsys):
    body = (place("P1", "Go", "UNIT", "1`()") + place("P2", "Lines", "STRING")
            + trans("T1", "read", code='input (); output (msg); action '
                    '(let val f = TextIO.openIn "signal.txt" in valOf (TextIO.inputLine f) end);')
            + arc("A1", "PtoT", "T1", "P1", "()") + arc("A2", "TtoP", "T1", "P2", "msg"))
    path = tmp_path / "reads.cpn"
    path.write_text(cpn_xml(DECLS, page("PG1", "Top", body)))
    assert main(["lint", str(path)]) == 0
    assert "warning[W0106]: 'TextIO.openIn' reads a file" in capsys.readouterr().err
    assert main(["simulate", str(path), "--steps", "5"]) == 65
    err = capsys.readouterr().err
    assert "error[E0401]" in err and "'TextIO.openIn' reads a file: simulate cannot run it" in err
    assert "'signal.txt'" in err


def test_an_arc_to_a_transition_the_file_does_not_hold_is_refused_with_the_element_to_delete(tmp_path):
    # CPN Tools' loader leaves an arc end whose id it does not find unset: the arc joins no transition there
    body = (place("P1", "A", "UNIT", "1`()") + trans("T1", "t") + arc("A1", "PtoT", "T1", "P1", "()")
            + arc("A2", "PtoT", "T9", "P1", "()"))
    path = tmp_path / "dangling.cpn"
    path.write_text(cpn_xml(DECLS, page("PG1", "Top", body)))
    with pytest.raises(ModelError) as info:
        cpn.load(path)
    [d] = info.value.diagnostics
    assert d.code == "E0502" and "its transition end 'T9' is no transition of the file" in d.message
    assert "would join no transition" in d.hint and 'Delete the <arc id="A2">' in d.hint


@needs_shared
def test_the_corpus_model_that_talks_to_a_controller_loads_and_simulate_stops_at_the_socket(capsys):
    # refused at 6290ca2: code segments that bind output variables with socket I/O
    path = os.path.join(CORPUS, "chrismachado__sdn-coloredpetrinet-model__cpn__model__finalwork.cpn")
    assert main(["lint", path]) == 0
    assert main(["explore", path]) == 65
    assert capsys.readouterr().err.count("error[E0206]") == 3
    assert main(["simulate", path, "--steps", "5"]) == 65
    assert "'ConnManagementLayer.openConnection' talks to another program" in capsys.readouterr().err
