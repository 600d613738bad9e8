"""The HTML pages of the bundled models rendered in headless Chromium.

Fails on any JavaScript error or console error, on a request for anything but the page itself, on a
drawing that renders blank, on a page wider than the window (laptop 1366 px, phone 390 px) and on
text smaller than 12 px. A full-page screenshot of every page at both widths is kept in pytest's
temporary directory (printed with -s). Skipped only when no Chromium is installed (`.ci/run` installs
Debian's `chromium`).
"""

import json
import os
import pathlib

import pytest
from _cdp import Browser, find_chromium

import cpn
from cpn.cli.main import main
from cpn.report import build_report
from cpn.report.html import IndexEntry, Verdict, render_html, render_index
from cpn.statespace import ExploreOptions, Explorer, shortest_trace

ROOT = pathlib.Path(__file__).resolve().parents[2]
WIDTHS = {"laptop": 1366, "phone": 390}

PAGES = {
    "stations": ["models/examples/stations.cpnet"],
    "stop_and_wait": ["--time-condensation", "models/examples/stop_and_wait.cpnet"],
    "ms2": ["bench/nets/ms.cpnet", "--set", "N=2"],
    "minibus": ["tests/report/nets/minibus.cpnet"],  # a master, a bus and two slaves as module instances
    # MODBUS scenario A.2 (reports/README.md): a master, a bus and 16 slave instances, a 131-step trace
    "modbus_A2": ["models/modbus/modbus.cpnet", "--time-condensation", "--set", 'CONFIG="A"', "--set",
                  "ADRS=[0,3,5,6]", "--set", "FCS=[1,7,20]", "--set", "PO=2"],
}

CHECK = r"""
(async () => {
  const W = window.innerWidth;
  const out = {scrollWidth: document.documentElement.scrollWidth, innerWidth: W, drawings: [], overflow: [],
               minFont: 99, minSvgFont: 99};
  async function ink(svg) {
    const text = new XMLSerializer().serializeToString(svg);
    const img = new Image();
    await new Promise((ok, bad) => { img.onload = ok; img.onerror = bad;
      img.src = 'data:image/svg+xml;charset=utf-8,' + encodeURIComponent(text); });
    const c = document.createElement('canvas');
    c.width = Math.max(1, Math.min(img.width, 3000)); c.height = Math.max(1, Math.min(img.height, 3000));
    const g = c.getContext('2d');
    g.fillStyle = '#fff'; g.fillRect(0, 0, c.width, c.height); g.drawImage(img, 0, 0);
    const d = g.getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) if (d[i] < 200 || d[i + 1] < 200 || d[i + 2] < 200) n++;
    return n;
  }
  for (const svg of document.querySelectorAll('.cpnv .scroll > svg')) {
    const bb = svg.getBBox(), r = svg.getBoundingClientRect();
    out.drawings.push({cls: svg.getAttribute('class'), w: bb.width, h: bb.height, rw: r.width, rh: r.height,
                       shapes: svg.querySelectorAll('circle,ellipse,rect,path,line,text').length,
                       inked: await ink(svg)});
  }
  for (const el of document.querySelectorAll('.cpnv header, .cpnv nav, .cpnv section, .cpnv figure, .cpnv table')) {
    const r = el.getBoundingClientRect();
    const scroller = el.closest('.tablewrap, .scroll');
    if (r.right > W + 1 && !scroller) out.overflow.push(el.tagName + '#' + el.id + ' right=' + r.right);
  }
  for (const el of document.querySelectorAll('.cpnv p, .cpnv td, .cpnv th, .cpnv a, .cpnv li, .cpnv summary')) {
    out.minFont = Math.min(out.minFont, parseFloat(getComputedStyle(el).fontSize));
  }
  for (const t of document.querySelectorAll('.cpnv .scroll > svg text')) {
    out.minSvgFont = Math.min(out.minSvgFont, parseFloat(t.getAttribute('font-size')));
  }
  out.height = document.documentElement.scrollHeight;
  return out;
})()
"""

FIT = r"""
(() => {
  for (const b of document.querySelectorAll('.cpnv button.fit')) b.click();
  return [...document.querySelectorAll('.cpnv figure.fitted .scroll > svg')].map(
    s => s.getBoundingClientRect().right <= window.innerWidth + 1);
})()
"""


@pytest.fixture(scope="module")
def browser():
    exe = find_chromium()
    if exe is None:
        pytest.skip("Chromium is not installed (Debian: apt-get install -y chromium; .ci/run installs it)")
    b = Browser(exe)
    try:
        b.call("Runtime.enable")
        b.call("Log.enable")
        b.call("Network.enable")
        b.call("Page.enable")
        yield b
    finally:
        b.close()


@pytest.fixture(scope="module")
def pages(tmp_path_factory):
    out = tmp_path_factory.mktemp("html")
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        for name, args in PAGES.items():
            assert main(["explore", *args, "--quiet", "--html", str(out / f"{name}.html")]) == 0
    finally:
        os.chdir(cwd)
    model = cpn.load(str(ROOT / "models/examples/stations.cpnet"))
    x = Explorer(model.engine(), ExploreOptions()).run()
    r = build_report(x, model="stations.cpnet")
    dead = r.dead.states[0]
    verdicts = [Verdict("no dead marking", "violated", "1 dead marking", shortest_trace(x.graph, dead, x.engine)),
                Verdict("Requests bounded by 3", "holds"),
                Verdict("every request answered", "unknown", "not evaluated")]
    (out / "verdicts.html").write_text(render_html(r, verdicts), encoding="utf-8")
    # a property check's pages: the broken stop-and-wait variant (4 violated properties) and its index
    assert main(["check", str(ROOT / "docs/ci/broken/stop_and_wait.toml"), "--no-reports", "--quiet",
                 "--html", str(out / "check")]) == 1
    (out / "check_broken.html").write_bytes((out / "check" / "stop-and-wait-broken.html").read_bytes())
    (out / "check_index.html").write_bytes((out / "check" / "index.html").read_bytes())
    (out / "index.html").write_text(render_index([IndexEntry("stations", "verdicts.html", "violated", 28, 0.1),
                                                  IndexEntry("ms2", "ms2.html", "holds", 189, 0.2)]),
                                    encoding="utf-8")
    return out


def _load(b: Browser, path: pathlib.Path, width: int) -> dict:
    b.events.clear()
    b.call("Emulation.setDeviceMetricsOverride", width=width, height=900, deviceScaleFactor=1,
           mobile=width < 600)
    b.call("Page.navigate", url=path.as_uri())
    b.wait_for("Page.loadEventFired")
    result = b.evaluate(CHECK)
    b.call("Runtime.evaluate", expression="0")  # let pending console events arrive
    return result


def _errors(b: Browser) -> list[str]:
    out = []
    for e in b.events:
        m, p = e["method"], e.get("params", {})
        if m == "Runtime.exceptionThrown":
            out.append(json.dumps(p.get("exceptionDetails"))[:500])
        elif m == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
            out.append(json.dumps(p.get("args"))[:500])
        elif m == "Log.entryAdded" and p.get("entry", {}).get("level") == "error":
            out.append(p["entry"].get("text", ""))
        elif m == "Network.requestWillBeSent":
            url = p.get("request", {}).get("url", "")
            if not url.startswith(("file:", "data:", "about:")):
                out.append(f"the page requested {url}")
    return out


def _screenshot(b: Browser, path: pathlib.Path, width: int, height: int) -> None:
    import base64

    shot = b.call("Page.captureScreenshot", format="png", captureBeyondViewport=True,
                  clip={"x": 0, "y": 0, "width": width, "height": min(height, 16000), "scale": 1})
    path.write_bytes(base64.b64decode(shot["data"]))


@pytest.mark.parametrize("width", list(WIDTHS))
@pytest.mark.parametrize("page", [*PAGES, "verdicts", "index", "check_broken", "check_index"])
def test_page_renders_in_chromium(browser, pages, page, width):
    w = WIDTHS[width]
    path = pages / f"{page}.html"
    res = _load(browser, path, w)
    shot = pages / f"{page}-{width}.png"
    _screenshot(browser, shot, w, res["height"])
    print(f"screenshot: {shot}")
    assert _errors(browser) == []
    assert res["scrollWidth"] <= res["innerWidth"], "the page is wider than the window"
    assert res["overflow"] == []
    assert res["minFont"] >= 12
    if page in ("index", "check_index"):
        assert res["drawings"] == []
        return
    kinds = {d["cls"] for d in res["drawings"]}
    assert "drawing net" in kinds and "drawing chart" in kinds
    assert kinds & {"drawing statespace", "drawing sccgraph"}
    if page != "ms2":  # MS(2) has no dead marking, so no trace to chart
        assert "drawing msc" in kinds
    for d in res["drawings"]:
        # (a chain of states is one narrow column: the drawing must be large in one direction at least)
        assert max(d["w"], d["h"]) > 40 and min(d["w"], d["h"]) > 10 and d["rw"] > 40 and d["rh"] > 40, d
        assert d["shapes"] >= 4 and d["inked"] > 500, f"blank drawing: {d}"
    assert res["minSvgFont"] >= 11
    fitted = browser.evaluate(FIT)
    assert fitted and all(fitted), "a drawing fitted to the width is still wider than the window"
    assert _errors(browser) == []
    assert shot.stat().st_size > 20_000
