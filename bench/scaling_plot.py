"""A scaling table of a Markdown file (states and seconds against a parameter) as an SVG image.

Usage:
  python bench/scaling_plot.py FILE.md --after HEADING --param N [--states COL ...] [--seconds COL ...] -o OUT.svg

The table is the first one after the line containing HEADING; --states and --seconds name its columns
(default "states" and "s"); a repeated heading is prefixed like the first one of its group ("with a
broadcast: states"). For example, the Modbus-A table of reports/README.md:
  python bench/scaling_plot.py reports/README.md --after "## Modbus-A" --param N -o modbus_a.svg
"""

from __future__ import annotations

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def main(argv=None) -> int:
    from cpn.report.plot import markdown_table, scaling_chart

    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("file")
    ap.add_argument("--after", default="", help="the table follows the line that contains this text")
    ap.add_argument("--param", default="N", help="the column of the parameter (x axis)")
    ap.add_argument("--states", nargs="+", default=["states"], help="columns of states (log scale)")
    ap.add_argument("--seconds", nargs="+", default=["s"], help="columns of seconds")
    ap.add_argument("-o", "--output", required=True)
    args = ap.parse_args(argv)
    with open(args.file, encoding="utf-8") as fh:
        rows = markdown_table(fh.read(), args.after)
    missing = [c for c in [args.param, *args.states, *args.seconds] if not rows or c not in rows[0]]
    if missing:
        have = ", ".join(rows[0]) if rows else "no table"
        print(f"error: no column {', '.join(repr(c) for c in missing)} in the table ({have})", file=sys.stderr)
        return 64
    svg = scaling_chart(rows, args.param, standalone=True, states=tuple(args.states), seconds=tuple(args.seconds))
    with open(args.output, "w", encoding="utf-8") as fh:
        fh.write(svg + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
