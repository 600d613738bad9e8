"""`no_livelock`'s `progress` takes binding elements as `fairness` does: "every cycle contains a successful
transmission" is `progress = ["StopAndWait'TransmitPacket 1: {ok=true}"]`."""

from pathlib import Path

import pytest

from cpn.errors import ModelError
from cpn.gate.run import run_scenario
from cpn.gate.scenario import load_scenario

MODEL = "models/examples/stop_and_wait.cpnet"


def _run(tmp_path, progress: str):
    path = tmp_path / "s.toml"
    path.write_text(f'model = "{Path(MODEL).resolve()}"\n[explore]\ntime_condensation = true\n'
                    f'[[property]]\nname = "p"\nkind = "no_livelock"\nprogress = [{progress}]\n', encoding="utf-8")
    s = load_scenario(str(path))
    r = run_scenario(s, s.runs[0])
    (result,) = r.results
    return r, result.verdict


def _verdict(tmp_path, progress: str):
    return _run(tmp_path, progress)[1]


def test_a_transition_holds_but_its_successful_binding_does_not(tmp_path):
    # every cycle transmits a packet, but a cycle may lose it every time
    assert _verdict(tmp_path, '"StopAndWait\'TransmitPacket 1"').status.value == "holds"
    r, v = _run(tmp_path, '"StopAndWait\'TransmitPacket 1: {ok=true}"')
    assert v.status.value == "violated"
    cycle = [r.engine.format_binding_element(be) for be in v.evidence.cycle_arcs]
    assert any("TransmitPacket" in t for t in cycle)  # the cycle transmits ...
    assert not any("TransmitPacket" in t and "ok=true" in t for t in cycle)  # ... and never successfully


def test_the_failing_binding_alone_is_violated_too(tmp_path):
    # a cycle in which every packet goes through (ok=true) transmits none with ok=false
    assert _verdict(tmp_path, '"StopAndWait\'TransmitPacket 1: {ok=false}"').status.value == "violated"


def test_an_unknown_binding_is_refused_at_its_position(tmp_path):
    with pytest.raises(ModelError) as info:
        _verdict(tmp_path, '"StopAndWait\'TransmitPacket 1: {okk=true}"')
    (d,) = info.value.diagnostics
    assert d.code == "E0703" and "binding element" in d.message and (d.span.line, d.span.col) == (7, 14)


def test_a_misspelt_transition_gets_a_did_you_mean(tmp_path):
    with pytest.raises(ModelError) as info:
        _verdict(tmp_path, '"StopAndWait\'TransmitPackt 1: {ok=true}"')
    (d,) = info.value.diagnostics
    assert "Did you mean 'StopAndWait'TransmitPacket 1'?" in d.hint
