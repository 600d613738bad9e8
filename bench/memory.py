"""Where the memory of a native search goes: the graph's arrays, the store, the caches, the process.

Usage:
  python bench/memory.py [--net ms|dp] [--n 8]

It loads bench/nets/NET.cpnet with N, builds the net's C (before measuring), generates the state space with
`--backend c`, then prints the bytes of each array of the graph (arc destinations and binding elements,
CSR offsets, BFS parents), the packed store (records and hash table), the native caches of the
transitions' results, and the resident memory before, after and at the peak of generation.
"""

from __future__ import annotations

import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

MIB = 1 << 20


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--net", default="ms")
    ap.add_argument("--n", type=int, default=8)
    args = ap.parse_args(argv)
    import cpn
    from cpn.statespace import ExploreOptions, Explorer, native
    from cpn.statespace._memory import current_rss_mb, peak_rss_mb

    model = cpn.load(os.path.join(HERE, "nets", f"{args.net}.cpnet"), set={"N": str(args.n)})
    engine = model.engine(time_condensation=False)
    native.library()
    code, _why = engine.native_code()
    if code is not None:
        native.library(code)
    searches = []
    flush = native.NativeSearch.flush

    def keep(self):  # the search object, for its caches' size
        if not searches:
            searches.append(self)
        return flush(self)

    native.NativeSearch.flush = keep
    rss0 = current_rss_mb()
    x = Explorer(engine, ExploreOptions(backend="c")).run()
    rss1 = current_rss_mb()
    peak = max(peak_rss_mb(), rss1)
    g = x.graph
    n = x.n_states
    print(f"{args.net}({args.n}): {n:,} states, {x.n_arcs:,} arcs, back end {x.backend}, "
          f"field widths {getattr(g.store, 'widths', None)}")
    rows = [(name, len(getattr(g, name)) * getattr(g, name).itemsize) for name in
            ("dst", "bes", "offsets", "parent", "parent_be")]
    rows.append(("store (records and table)", g.store.nbytes() or 0))
    if searches:
        rows.append(("caches of the transitions' results", searches[0].cache_bytes()))
    for name, b in rows:
        print(f"  {name:<36}{b / MIB:>10.1f} MiB{b / n:>8.1f} B/state")
    print(f"  resident memory: {rss0:.1f} MiB before, {rss1:.1f} MiB after, peak {peak:.1f} MiB; "
          f"growth at the peak {(peak - rss0):.1f} MiB ({(peak - rss0) * MIB / n:.1f} B/state)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
