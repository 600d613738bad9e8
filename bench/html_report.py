"""How long the HTML report takes beside the exploration it shows.

Usage:
  python bench/html_report.py [--repeat 3]

For each model: states, arcs, which state-space drawing the page uses, the page's size, the seconds of
`Explorer.run` and of `render_html` (medians over --repeat), and their ratio.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, ROOT)

MODELS = [
    ("models/examples/stations.cpnet", {}, False),
    ("models/examples/stop_and_wait.cpnet", {}, True),
    ("tests/report/nets/minibus.cpnet", {}, False),
    ("bench/nets/ms.cpnet", {"N": "2"}, False),
    ("bench/nets/ms.cpnet", {"N": "3"}, False),
    ("bench/nets/ms.cpnet", {"N": "5"}, False),
    ("bench/nets/dp.cpnet", {"N": "8"}, False),
    ("models/modbus/modbus.cpnet", {"CONFIG": '"A"', "ADRS": "[0,3,5,6]", "FCS": "[1,7,20]", "PO": "2"}, True),
]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)

    import cpn
    from cpn.report import build_report
    from cpn.report.graphdraw import choose
    from cpn.report.html import render_html
    from cpn.statespace import ExploreOptions, Explorer

    print(f"{'model':<44} {'states':>8} {'arcs':>9} {'drawn':>6} {'page kB':>8} {'explore s':>10} "
          f"{'html s':>8} {'html/explore':>12}")
    for path, sets, tc in MODELS:
        explore_s, html_s = [], []
        for _ in range(args.repeat):
            engine = cpn.load(os.path.join(ROOT, path), set=sets).engine(time_condensation=tc)
            x = Explorer(engine, ExploreOptions()).run()
            explore_s.append(x.seconds)
            r = build_report(x, model=path)
            t0 = time.perf_counter()
            page = render_html(r)
            html_s.append(time.perf_counter() - t0)
        e, h = statistics.median(explore_s), statistics.median(html_s)
        name = path + ("".join(f" {k}={v}" for k, v in sets.items()) if len(sets) < 3 else " A.2") \
            + (" (tc)" if tc else "")
        kind = choose(x) if r.scc.nodes <= 300 or choose(x) == "full" else "none"
        print(f"{name:<44} {x.n_states:>8,} {x.n_arcs:>9,} {kind:>6} {len(page.encode()) // 1024:>8,} "
              f"{e:>10.3f} {h:>8.3f} {h / e if e else float('inf'):>12.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
