"""The standard report: JSON schema keys, text layout, partial status, determinism across hash seeds."""

import json
import os
import subprocess
import sys

from _toy import dining_philosophers
from nets import coloured_register, counter, timed_merge

from cpn.report import build_report, render_text, to_json
from cpn.statespace import ExploreOptions, Explorer

DESIGN_KEYS = {"model", "options", "statespace", "scc", "bounds", "multiset_bounds", "dead_markings",
               "dead_transitions", "live_transitions", "home_markings", "fairness", "tokens"}


def _report(engine, **opts):
    return build_report(Explorer(engine, ExploreOptions(**opts)).run(), model="toy")


def test_json_has_the_design_keys():
    d = to_json(_report(dining_philosophers(4)))
    assert DESIGN_KEYS <= set(d)
    assert {"states", "arcs", "complete", "stop_reason", "unexpanded", "seconds", "peak_memory_mb"} <= set(
        d["statespace"])
    assert {"nodes", "arcs", "terminal"} <= set(d["scc"])
    assert {"count", "examples"} <= set(d["dead_markings"])
    assert {"max_per_marking", "max_in_place", "max_of_one_colour_in_place"} <= set(d["tokens"])
    assert d["bounds"]["Top'Eat 1"] == {"upper": 2, "lower": 0}
    assert d["statespace"]["complete"] is True and d["statespace"]["stop_reason"] == "complete"
    json.dumps(d)


def test_text_sections_in_cpn_tools_order():
    text = render_text(_report(dining_philosophers(4)))
    heads = ["Statistics", "Boundedness Properties", "Home Properties", "Liveness Properties",
             "Fairness Properties"]
    pos = [text.index(f" {h}\n" + "-" * 72) for h in heads]
    assert pos == sorted(pos)
    for line in ("     Nodes:  ", "     Status: Full", "  Best Integer Bounds", "  Best Upper Multi-set Bounds",
                 "  Best Lower Multi-set Bounds", "  Home Markings", "  Dead Markings",
                 "  Dead Transition Instances", "  Live Transition Instances"):
        assert line in text
    assert "     Top'Eat 1               2          0" in text
    assert "Shortest trace to dead marking" in text


def test_text_partial_status_and_unexpanded():
    r = _report(counter(), max_states=7)
    text = render_text(r)
    assert "Status: Partial (stopped because max_states=7 was reached; 1 unexpanded node)" in text
    assert "  Dead Markings\n     None\n     (plus 1 unexpanded node, which is not a dead marking)" in text
    assert "Unknown (the state space is partial)" in text
    d = to_json(r)
    assert d["statespace"]["complete"] is False and d["statespace"]["unexpanded"] == 1
    assert d["dead_markings"]["count"] == 0 and d["fairness"] is None


def test_text_timed_home_and_untimed_dead():
    text = render_text(_report(timed_merge()))
    assert "Initial Marking is not a home marking" in text
    assert "     [2,3]\n     1 after removing time stamps" in text
    assert "No infinite occurrence sequences." in text
    assert "time condensation: off" in text


def test_multiset_bounds_text():
    d = to_json(_report(coloured_register()))
    got = d["multiset_bounds"]["Top'R 1"]
    assert (got["upper"], got["lower"]) == ("1`a++1`b++1`c", "1`c")


_SCRIPT = """
import json, sys
sys.path.insert(0, {path!r})
from nets import coloured_register
from _toy import dining_philosophers
from cpn.report import build_report, to_json, render_text
from cpn.statespace import Explorer
out = []
for e in (coloured_register(), dining_philosophers(5)):
    d = to_json(build_report(Explorer(e).run(), model="toy"))
    for k in ("seconds", "peak_memory_mb"):
        d["statespace"].pop(k)
    d["scc"].pop("seconds"); d.pop("report_seconds"); d.pop("report_part_seconds")
    out.append(d)
print(json.dumps(out, sort_keys=False))
"""


def test_results_do_not_depend_on_hash_seed():
    here = os.path.join(os.path.dirname(__file__), "..", "statespace")
    outs = []
    for seed in ("1", "2"):
        env = dict(os.environ, PYTHONHASHSEED=seed)
        p = subprocess.run([sys.executable, "-c", _SCRIPT.format(path=os.path.abspath(here))], env=env,
                           capture_output=True, text=True, check=True)
        outs.append(p.stdout)
    assert outs[0] == outs[1]
