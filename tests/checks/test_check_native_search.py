"""`cpn-verify check` searches natively where its properties only observe the states (an
invariant, a reachability, a deadlock check without `stop_at_first_violation`): the monitor is shown every
new state in id order after each batch of the native search, and the first dead state is read off the
graph. Verdicts, messages and counterexamples are those of the Python search."""

import json
import os

import pytest

from cpn.statespace import chooser
from cpn.statespace.store import packed_unavailable
from tests._checkrun import check_reports, record_backends

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(__file__)))
DP = os.path.join(ROOT, "bench", "nets", "dp.cpnet").replace("\\", "/")
NATIVE = packed_unavailable()

SPEC = f'''name = "dp"
model = "{DP}"

[set]
N = 7

[[property]]
name = "at most one eats"
kind = "invariant"
expr = "size (DP'Eat 1) <= 1"

[[property]]
name = "forks are conserved"
kind = "invariant"
expr = "size (DP'Forks 1) + size (DP'HasLeft 1) + 2 * size (DP'Eat 1) = N"

[[property]]
name = "three eat at once"
kind = "reachable"
expr = "size (DP'Eat 1) = 3"

[[property]]
name = "no deadlock"
kind = "deadlock_free"
'''


def _check(tmp_path, name, capsys):
    spec = tmp_path / f"{name}.toml"
    spec.write_text(SPEC, encoding="utf-8")
    code, docs = check_reports(tmp_path, name, capsys, str(spec))
    (doc,) = docs.values()
    return code, doc


@pytest.mark.skipif(NATIVE is not None, reason=f"no native code: {NATIVE}")
def test_check_searches_natively_with_the_python_verdicts(tmp_path, capsys, monkeypatch):
    backends = record_backends(monkeypatch)
    code_c, doc_c = _check(tmp_path, "c", capsys)
    assert backends == [None]  # the native search ran, the monitor on its states
    monkeypatch.setattr(chooser, "why_not_native", lambda *_: "the Python search, for comparison")
    code_py, doc_py = _check(tmp_path, "py", capsys)
    assert code_c == code_py == 1
    assert doc_c["properties"] == doc_py["properties"] and doc_c["statespace"] == doc_py["statespace"]
    verdicts = {p["name"]: p["verdict"] for p in doc_c["properties"]}
    assert verdicts == {"at most one eats": "violated", "forks are conserved": "holds",
                        "three eat at once": "holds", "no deadlock": "violated"}
    assert "deadlock" in json.dumps(doc_c["properties"][3]).lower()
