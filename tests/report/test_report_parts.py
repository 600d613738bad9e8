"""build_report times each part of the analysis and tells its progress callback as each starts and ends."""

import cpn
from cpn.report import build_report
from cpn.report.model import REPORT_PARTS
from cpn.statespace import Explorer

CYCLE = ("colset N = int with 0..2; var x : N; place P : N = 1`0;"
         " trans inc; arc P -> inc : x; arc inc -> P : (x + 1) mod 3;")


def test_each_part_starts_then_ends_in_order_and_is_timed():
    events = []
    r = build_report(Explorer(cpn.loads(CYCLE).engine()).run(), progress=lambda *a: events.append(a))
    assert list(r.part_seconds) == list(REPORT_PARTS)
    assert all(sec >= 0 for sec in r.part_seconds.values())
    assert list(dict.fromkeys(e[0] for e in events if e[1] == e[2])) == list(REPORT_PARTS)
    assert events[-1] == ("trace", 1, 1)
    for part in REPORT_PARTS:  # each part starts (done 0) before it ends, and before the next starts
        mine = [i for i, e in enumerate(events) if e[0] == part]
        assert events[mine[0]][1] == 0 and mine == list(range(mine[0], mine[-1] + 1))
    fair = [e for e in events if e[0] == "fairness"]
    assert len(fair) >= 2 and fair[-1][1] == fair[-1][2]


def test_a_failing_part_is_not_reported_as_done(monkeypatch):
    import cpn.report.model as model

    def boom(*_a, **_k):
        raise RuntimeError("bounds failed")

    monkeypatch.setattr(model, "boundedness", boom)
    events = []
    x = Explorer(cpn.loads(CYCLE).engine()).run()
    try:
        build_report(x, progress=lambda *a: events.append(a))
    except RuntimeError:
        pass
    assert events[-1] == ("bounds", 0, 1)
