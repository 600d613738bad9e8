"""The verdicts agree with CPN Tools' published state-space report of the CPN book's LimitProtocol
(Jensen & Kristensen 2009, ch. 7; shared/validation/expected.json)."""

import os

from cpn.gate.run import run_scenario
from cpn.gate.scenario import loads_scenario
from tests._shared import SHARED, needs_shared

MODEL = os.path.join(SHARED, "validation", "CPNBook-LimitProtocol", "7-2LimitProtocol.cpn")

BOUNDS = {"Packets_To_Send": (6, 6), "Data_Received": (1, 1), "NextSend": (1, 1), "NextRec": (1, 1),
          "A": (3, 0), "B": (3, 0), "C": (3, 0), "D": (3, 0), "Limit": (3, 0)}


@needs_shared
def test_limit_protocol_published_properties(tmp_path):
    props = ['[[property]]\nname = "one dead marking"\nkind = "dead_markings"\ncount = 1\n',
             '[[property]]\nname = "deadlock"\nkind = "deadlock_free"\n',
             '[[property]]\nname = "home"\nkind = "home"\n',
             '[[property]]\nname = "no dead transition"\nkind = "dead_transitions"\nexpected = []\n',
             '[[property]]\nname = "live"\nkind = "live_transitions"\n',
             '[[property]]\nname = "the dead marking is home"\nkind = "ctl"\n'
             'formula = "AG (EF (not (EX true)))"\n']
    for place, (hi, lo) in BOUNDS.items():
        props.append(f'[[property]]\nname = "{place}"\nkind = "bound"\nplace = "Protocol\'{place} 1"\n'
                     f"upper = {hi}\nlower = {lo}\n")
    s = loads_scenario(f'model = "{MODEL}"\n' + "".join(props), str(tmp_path / "limit.toml"))
    r = run_scenario(s, s.runs[0])
    assert (r.exploration.n_states, r.exploration.n_arcs) == (13215, 52784)
    got = {p.spec.name: p.verdict.status.value for p in r.results}
    assert got.pop("deadlock") == "violated"
    assert got.pop("live") == "violated"  # CPN Tools: no live transition instance
    assert set(got.values()) == {"holds"}, got
