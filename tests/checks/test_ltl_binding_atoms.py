"""`kind = "ltl"`: binding-element atoms, written as in `ctl` (`EXB ("T", p)`, `AXB ("T", p)`) and read on
the path: its next step is an occurrence of T and p holds after it, or, if the next step is one, p holds
after it."""

from __future__ import annotations

import pytest

from cpn.checks.verdict import Status
from cpn.errors import ModelError
from cpn.gate.run import run_scenario
from cpn.gate.scenario import loads_scenario
from tests.checks.test_traces import _replays

# send with ok=false loses the token (it stays in A), with ok=true delivers it to D, where the net is dead
LOSSY = ("colset U = unit; colset B = bool; var ok : B; place A : U = 1`(); place D : U; trans send;"
         " arc A -> send : (); arc send -> A : (if ok then empty else 1`()); arc send -> D : (if ok then 1`() else empty);")
IN_D = "size (Top'D 1) = 1"


def _verdicts(tmp_path, formulas: dict):
    (tmp_path / "m.cpnet").write_text(LOSSY, encoding="utf-8")
    body = "".join(f"[[property]]\nname = \"{n}\"\nkind = \"ltl\"\nformula = '''{f}'''\n" for n, f in formulas.items())
    s = loads_scenario('model = "m.cpnet"\n' + body, str(tmp_path / "s.toml"))
    r = run_scenario(s, s.runs[0], {})
    return r, {p.spec.name: p.verdict for p in r.results}


def test_binding_element_atoms_on_the_paths_of_a_lossy_send(tmp_path):
    r, v = _verdicts(tmp_path, {
        "delivered": 'F (EXB ("Top\'send 1: {ok=true}", true))',
        "delivery ends in D": f'G (AXB ("Top\'send: {{ok=true}}", {IN_D}))',
        "every send ends in D": f'G (AXB ("Top\'send", {IN_D}))',
        "always a send": 'G (EXB ("Top\'send", true))',
        "delivered or lost for ever": f'F (G ({IN_D})) orelse G (EXB ("Top\'send 1: {{ok=false}}", true))',
        "lost then sent again": 'G (AXB ("Top\'send: {ok=false}", EXB ("Top\'send", true)))',
    })
    H, V = Status.HOLDS, Status.VIOLATED
    assert {n: x.status for n, x in v.items()} == {
        "delivered": V, "delivery ends in D": H, "every send ends in D": V, "always a send": V,
        "delivered or lost for ever": H, "lost then sent again": H}
    lost = v["delivered"].evidence  # the send that loses the token, forever
    assert lost.cycle and _replays(r.engine, r.exploration.graph, lost)
    assert "dead" in v["always a send"].message  # a dead marking's stutter step is no occurrence


def test_a_binding_element_atom_not_in_the_net_is_refused_at_its_place(tmp_path):
    with pytest.raises(ModelError) as err:
        _verdicts(tmp_path, {"x": 'F (EXB ("Top\'sned", true))'})
    d = err.value.diagnostics[0]
    assert d.code == "E0703" and "EXB" in d.message and d.span.line == 5 and d.span.col > 20
