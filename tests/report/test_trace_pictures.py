"""Charts of counterexamples: lost frames and frames still on their way are drawn, the marking a
counterexample leads to is shown after it (check's output, the text report, the HTML page), and a
standalone chart is as wide as its title.

The net tests/report/nets/twice.cpnet: the line loses the first copy of a request, passes the
retransmission, and the slave answers it twice; the shortest counterexample of "at most one answer on
the line" has a lost frame, delivered frames, and three frames still in their places at its end.
"""

import os
import pathlib
import re
import xml.etree.ElementTree as ET

import pytest

import cpn
from cpn.cli.main import main
from cpn.report import build_report
from cpn.report import svg as S
from cpn.report.html import Verdict, evidence_trace, render_html
from cpn.report.msc import build_chart, draw_msc

ROOT = pathlib.Path(__file__).resolve().parents[2]
NETS = pathlib.Path(__file__).resolve().parent / "nets"
SVG = "{http://www.w3.org/2000/svg}"


@pytest.fixture(scope="module")
def twice():
    run = cpn.check(str(NETS / "twice.toml"))[0]
    result = run.results[0]
    assert result.verdict.status.value == "violated"
    trace, _ = evidence_trace(result.verdict.evidence, run.engine)
    return run, result, trace


def test_a_lost_frame_ends_in_a_cross_and_frames_in_flight_stay_open(twice):
    run, _result, trace = twice
    chart = build_chart(trace, run.exploration)
    lines = [a for a, _ in chart.lifelines]
    assert lines == ["Master1", "Line1", "Slave1"]
    steps = {e.step: e.label for e in chart.events}
    got = sorted((m.label, m.fate, lines[m.src_line], lines[m.dst_line], steps[m.src],
                  steps.get(m.dst)) for m in chart.messages)
    assert got == [
        ("Answers: 2", "pending", "Slave1", "Master1", "Reply", None),  # the first answer ...
        ("Answers: 2", "pending", "Slave1", "Master1", "Reply", None),  # ... and the second, the violation
        ("Delivered: 2", "pending", "Line1", "Slave1", "Forward", None),  # kept by the slave's double arc
        ("Sent: 1", "lost", "Master1", "Line1", "Send", "Lose"),
        ("Sent: 2", "delivered", "Master1", "Line1", "Retry", "Forward"),
    ]
    # the last step produced a frame: the chart shows it (before, no message started at the last step)
    assert any(m.src == len(trace) for m in chart.messages)


def test_the_chart_draws_the_cross_and_the_open_arrows(twice):
    run, _result, trace = twice
    svg = draw_msc(trace, run.exploration, marked_step=len(trace), standalone=True)
    root = ET.fromstring(svg)
    groups = [g for g in root.iter(f"{SVG}g") if (g.get("class") or "").startswith("message")]
    fates = [g.get("class").split()[1] for g in groups]
    assert sorted(fates) == ["delivered", "lost", "pending", "pending", "pending"]
    lost = groups[fates.index("lost")]
    assert lost.find(f"{SVG}path[@class='lost']") is not None  # the cross
    assert lost.find(f"{SVG}line").get("marker-end") is None  # no arrowhead: it never arrives
    last_y = max(float(g.find(f"{SVG}rect").get("y")) + 12 for g in root.iter(f"{SVG}g")
                 if (g.get("class") or "").startswith("event"))
    height = float(root.get("height"))
    for g, fate in zip(groups, fates):
        line = g.find(f"{SVG}line")
        if fate == "pending":
            assert line.get("stroke-dasharray") and "-open)" in line.get("marker-end")
            assert last_y < float(line.get("y2")) < height  # open below the last step, inside the drawing
            assert "still there at the end of the trace" in g.find(f"{SVG}title").text


def test_check_prints_the_violating_marking_after_the_counterexample(tmp_path, capsys):
    code = main(["check", str(NETS / "twice.toml"), "--reports", str(tmp_path)])
    out = capsys.readouterr().out
    assert code == 1
    for text in (out, (tmp_path / "twice.txt").read_text(encoding="utf-8"),
                 (tmp_path / "twice.md").read_text(encoding="utf-8")):
        after = text[text.index("6. @7  Slave'Reply 1"):]
        head = re.search(r"violating marking (\d+) at time 7, the property reads Twice'Answers 1:", after)
        assert head, after
        lines = after[head.end():].splitlines()[1:4]
        assert re.match(r"\s+Twice'Answers 1\s+2`2@8$", lines[0])  # the place the property reads, first
        assert {line.split()[0] for line in lines[1:]} == {"Twice'Delivered", "Master'Timer"}
    doc = __import__("json").loads((tmp_path / "twice.json").read_text(encoding="utf-8"))
    marking = doc["properties"][0]["trace"]["marking"]
    assert marking["reads"] == ["Twice'Answers 1"] and marking["places"]["Twice'Answers 1"] == "2`2@8"
    assert marking["violating"] is True and marking["state"] == doc["properties"][0]["trace"]["target"]


def test_a_place_the_property_reads_is_listed_even_when_empty(tmp_path, capsys):
    src = (NETS / "twice.toml").read_text(encoding="utf-8")
    src = src.replace('model = "twice.cpnet"', f'model = "{(NETS / "twice.cpnet").as_posix()}"')
    src = src.replace('expr = "size (Twice\'Answers 1) <= 1"',
                      'expr = "size (Twice\'Answers 1) <= 1 andalso size (Master\'Done 1) = 0"')
    (tmp_path / "s.toml").write_text(src, encoding="utf-8")
    assert main(["check", str(tmp_path / "s.toml"), "--reports", str(tmp_path / "r")]) == 1
    out = capsys.readouterr().out
    assert "the property reads Twice'Answers 1, Master'Done 1:" in out  # in the order of the net's places
    assert re.search(r"\n\s+Master'Done 1\s+empty\n", out)


def test_the_page_shows_the_violating_marking_after_the_chart(twice):
    run, result, _trace = twice
    report = build_report(run.exploration, model=run.scenario.model)
    v = result.verdict
    page = render_html(report, [Verdict(result.spec.name, v.status, v.message, v.evidence,
                                        places=("Twice'Answers 1",))])
    block = page[page.index('id="trace-v0"'):]
    block = block[:block.index("</div></div>") if "</div></div>" in block else len(block)]
    chart, marking = block.index('class="drawing msc"'), block.index('class="end-marking"')
    assert chart < marking
    rows = re.findall(r"<tr( class=read)?><td>(.*?)</td><td><span class=\"mono\">(.*?)</span>", block[marking:])
    assert rows[0] == (" class=read", "Twice&#x27;Answers 1"
                       ' <span class="pill">read by the property</span>', "2`2@8")
    assert {r[1] for r in rows[1:]} == {"Twice&#x27;Delivered 1", "Master&#x27;Timer 1"}
    assert "Violating marking" in block[marking:]


def test_check_html_pages_show_the_marking_after_each_counterexample(tmp_path, capsys):
    assert main(["check", str(NETS / "twice.toml"), "--reports", str(tmp_path / "r"),
                 "--html", str(tmp_path / "h")]) == 1
    page = (tmp_path / "h" / "twice.html").read_text(encoding="utf-8")
    assert page.index('class="drawing msc"') < page.index('class="end-marking"')
    # the place the property reads comes first, marked as read
    assert ('<tr class=read><td>Twice&#x27;Answers 1 <span class="pill">read by the property</span></td>'
            '<td><span class="mono">2`2@8') in page


def test_a_standalone_chart_is_as_wide_as_its_title(tmp_path, capsys):
    net = tmp_path / "one.cpnet"
    net.write_text("net One;\ncolset U = unit;\nplace P : U = 1`();\ntrans T;\narc P -> T;\n")
    svg = tmp_path / "t.svg"
    assert main(["explore", str(net), "--quiet", "--msc", str(svg)]) == 0
    root = ET.fromstring(svg.read_text(encoding="utf-8"))
    title = next(t for t in root.iter(f"{SVG}text") if t.get("font-weight") == "600" and t.get("font-size") == "14")
    assert title.text.startswith("Shortest trace to dead marking")
    # bold text is about 8% wider than the regular text the estimate is for; 10 px of margin on the left
    assert float(title.get("x")) + 1.08 * S.text_width(title.text, 14) <= float(root.get("width"))


def test_every_chart_of_the_examples_is_well_formed(tmp_path):
    for net in ("models/examples/stations.cpnet", "models/examples/broadcast.cpnet"):
        model = cpn.load(str(ROOT / net))
        from cpn.statespace import ExploreOptions, Explorer, shortest_trace

        x = Explorer(model.engine(), ExploreOptions()).run()
        for d in x.graph.dead_states()[:2]:
            trace = shortest_trace(x.graph, d, x.engine)
            root = ET.fromstring(draw_msc(trace, x, marked_step=len(trace), standalone=True))
            assert root.tag == f"{SVG}svg"
    assert os.path.isdir(tmp_path)
