"""Every TOML example of docs/specs.md and docs/ci-guide.md is a valid scenario."""

import pathlib
import re

import pytest

from cpn.gate.scenario import loads_scenario

ROOT = pathlib.Path(__file__).resolve().parents[2]
BLOCKS = [(doc, m.group(1)) for doc in ("docs/specs.md", "docs/ci-guide.md")
          for m in re.finditer(r"```toml\n(.*?)```", (ROOT / doc).read_text(encoding="utf-8"), re.S)]


@pytest.mark.parametrize("doc, block", BLOCKS)
def test_documented_examples_are_valid_scenarios(doc, block):
    text = block if "model =" in block else 'model = "bench/nets/ms.cpnet"\n' + block
    text = re.sub(r'model = "[^"]*"', 'model = "bench/nets/ms.cpnet"', text)
    s = loads_scenario(text, str(ROOT / "example.toml"))
    assert s.runs


def test_the_documented_ms_properties_hold_on_ms(tmp_path):
    from cpn.gate.run import run_scenario

    props = [b for d, b in BLOCKS if "MS'" in b and "[[property]]" in b and "StopAndWait" not in b
             and "Slave'" not in b and "[set]" not in b]
    text = 'model = "bench/nets/ms.cpnet"\n[set]\nN = 2\n' + "\n".join(props)
    s = loads_scenario(text, str(ROOT / "example.toml"))
    r = run_scenario(s, s.runs[0])
    assert {p.spec.name: p.verdict.status.value for p in r.results if p.verdict.status.value != "holds"} == {}


def test_the_documented_stop_and_wait_properties(tmp_path):
    from cpn.gate.run import run_scenario

    props = [b for d, b in BLOCKS if d == "docs/specs.md" and "StopAndWait" in b and "[explore]" not in b]
    text = ('model = "models/examples/stop_and_wait.cpnet"\n[explore]\ntime_condensation = true\n'
            + "\n".join(props))
    s = loads_scenario(text, str(ROOT / "example.toml"))
    r = run_scenario(s, s.runs[0])
    got = {p.spec.name: p.verdict.status.value for p in r.results}
    assert got.pop("no cycle without an acknowledgement") == "violated"
    assert set(got.values()) == {"holds"}, got
