"""The standard report's graph algorithms in C (`_graph.c`): SCCs, the SCC graph's arcs, arc labels, dead
states, live transition instances, fairness classes and the place columns of packed states.

Built with the system C compiler through cffi on first use and cached (`cpn._util.cbuild`). Every
function here takes the graph's own arrays (no copy: `ffi.from_buffer`) and returns None when native
code is unavailable or an array is not of the expected type; the callers then run their pure-Python
reference (`cpn.statespace.scc`, `cpn.checks`), which gives the same results (tests/statespace and
tests/checks compare both on random graphs).

Setting the module's `enabled` to False (or the environment variable CPN_NO_NATIVE) makes every
function return None, and so does a graph of fewer than MIN_ITEMS arcs (about 5,000 steps of Tarjan in
Python, 5 ms of CPU, the time of loading the library; where the Python code runs at C speed, such as
the place columns, MIN_ITEMS x CHEAP items): there the Python code is faster.
"""

from __future__ import annotations

import gc
from array import array
from itertools import compress

from cpn._util.cbuild import build

#: False: every function returns None (the pure-Python path runs); tests switch it to compare both
enabled: bool = True
#: graphs with fewer arcs (stores with fewer states) are left to the Python code; tests set it to 0
MIN_ITEMS: int = 5000
#: where the Python code runs at C speed (`set`, `map`, `itemgetter`) it handles about this many items
#: in the time of one of Tarjan's arcs, so it is left more of them
CHEAP: int = 20
_ID_CODES = {"B": 1, "H": 2, "i": 4}


def library(items: int | None = None):
    """The loaded library, or None (no compiler, no cffi, CPN_NO_NATIVE, `enabled` is False, or a graph
    of `items` arcs or states below MIN_ITEMS)."""
    if not enabled or (items is not None and items < MIN_ITEMS):
        return None
    if not _loaded:
        # cffi parses the declarations with pycparser, whose many small objects make the cyclic garbage
        # collector walk the search's heap again: 16 ms of CPU after CSRepetitions-COL-02's search
        # (7,424 states), 4 ms with the collector off
        collecting = gc.isenabled()
        gc.disable()
        try:
            lib = build("graph")
        finally:
            if collecting:
                gc.enable()
        if lib is None:
            return None
        _loaded.append(lib)
    return _loaded[0]


_loaded: list = []  # the library once loaded (a build would read and hash the source again on every call)


def _csr_ok(offsets, dst) -> bool:
    return (isinstance(offsets, array) and offsets.typecode == "q" and isinstance(dst, array)
            and dst.typecode == "i")


def _ids_ok(ids) -> bool:
    return isinstance(ids, array) and ids.typecode in _ID_CODES


def _buf(ffi, ctype: str, data):
    """A C view of an array (its first item when empty, never read)."""
    return ffi.from_buffer(ctype, data if len(data) else array(data.typecode, [0]))


def scc(n: int, offsets: array, dst: array):
    """Tarjan's SCCs as (comp, members, start, terminal, nontrivial), as `scc.strongly_connected_components`
    numbers them; None where native code is unavailable. `offsets` may cover only the first states."""
    lib = library(len(dst))
    if lib is None or not _csr_ok(offsets, dst):
        return None
    ffi, c = lib.ffi, lib.lib
    nexp = len(offsets) - 1
    comp = array("i", bytes(4 * n))
    members = array("i", bytes(4 * n))
    start = array("i", bytes(4 * (n + 1)))
    terminal = bytearray(n)
    nontrivial = bytearray(n)
    count = c.gr_scc(n, nexp, _buf(ffi, "int64_t[]", offsets), _buf(ffi, "int32_t[]", dst),
                     _buf(ffi, "int32_t[]", comp), _buf(ffi, "int32_t[]", members), _buf(ffi, "int32_t[]", start),
                     ffi.from_buffer("uint8_t[]", terminal or bytearray(1)),
                     ffi.from_buffer("uint8_t[]", nontrivial or bytearray(1)))
    if count == -2:
        return None  # 2^30 states or more: the Python code
    if count < 0:
        raise MemoryError("no memory for the SCC decomposition")
    del start[count + 1:]
    del terminal[count:]
    del nontrivial[count:]
    return comp, members, start, terminal, nontrivial


def scc_arcs(offsets: array, dst: array, comp: array, members: array, start: array) -> tuple[int, int] | None:
    """(arcs between different SCCs, distinct ordered pairs of SCCs joined by an arc), or None."""
    lib = library(len(dst))
    if lib is None or not _csr_ok(offsets, dst):
        return None
    ffi = lib.ffi
    out = ffi.new("int64_t[2]")
    if lib.lib.gr_scc_arcs(len(offsets) - 1, _buf(ffi, "int64_t[]", offsets), _buf(ffi, "int32_t[]", dst),
                           _buf(ffi, "int32_t[]", comp), _buf(ffi, "int32_t[]", members),
                           _buf(ffi, "int32_t[]", start), len(start) - 1, out) != 0:
        raise MemoryError("no memory for the SCC graph")
    return out[0], out[1]


def distinct_ids(ids: array) -> list[int] | None:
    """The distinct values of an array of non-negative ids (e.g. the arcs' binding elements), increasing."""
    lib = library(len(ids) // CHEAP)
    if lib is None or not _ids_ok(ids):
        return None
    ffi = lib.ffi
    bw = _ID_CODES[ids.typecode]
    top = lib.lib.gr_max_id(_buf(ffi, "uint8_t[]", ids), bw, len(ids))
    if top < 0:
        return []
    seen = bytearray(top + 1)
    lib.lib.gr_mark_ids(_buf(ffi, "uint8_t[]", ids), bw, len(ids), ffi.from_buffer("uint8_t[]", seen))
    return list(compress(range(top + 1), seen))


def map_ids(ids: array, table: list[int], code: str) -> array | None:
    """array(code, [table[i] for i in ids]) (code "B", "H" or "i"; every id < len(table)), or None."""
    lib = library(len(ids) // CHEAP)
    if lib is None or not _ids_ok(ids) or code not in _ID_CODES:
        return None
    ffi = lib.ffi
    out = array(code, bytes(array(code).itemsize * len(ids)))
    lib.lib.gr_map_ids(_buf(ffi, "uint8_t[]", ids), _ID_CODES[ids.typecode], len(ids),
                       _buf(ffi, "int32_t[]", array("i", table or [0])), _buf(ffi, "uint8_t[]", out),
                       _ID_CODES[code])
    return out


def dead_states(offsets: array) -> list[int] | None:
    """The expanded states without an arc, increasing, or None."""
    lib = library((len(offsets) - 1) // CHEAP)
    if lib is None or not isinstance(offsets, array) or offsets.typecode != "q":
        return None
    ffi = lib.ffi
    out = array("i", bytes(4 * max(1, len(offsets) - 1)))
    k = lib.lib.gr_dead(len(offsets) - 1, _buf(ffi, "int64_t[]", offsets), _buf(ffi, "int32_t[]", out))
    return out[:k].tolist()


def reverse(n: int, offsets: array, dst: array) -> tuple[array, array] | None:
    """Predecessors in CSR form (pred_off, pred) as `cpn.checks.ctl.reverse_csr` gives them, or None."""
    lib = library(len(dst))
    if lib is None or not _csr_ok(offsets, dst):
        return None
    ffi = lib.ffi
    nexp = len(offsets) - 1
    pred_off = array("q", bytes(8 * (n + 1)))
    pred = array("i", bytes(4 * offsets[nexp]))
    if lib.lib.gr_reverse(n, nexp, _buf(ffi, "int64_t[]", offsets), _buf(ffi, "int32_t[]", dst),
                          _buf(ffi, "int64_t[]", pred_off), _buf(ffi, "int32_t[]", pred)) != 0:
        raise MemoryError("no memory for the predecessors")
    return pred_off, pred


def live(offsets: array, labels: array, ntrans: int, comp: array, members: array, start: array,
         terminal: bytearray):
    """Per transition instance, 1 if it labels an arc in every terminal SCC (a bytearray), or None."""
    lib = library(len(labels) // 10)
    if lib is None or not isinstance(offsets, array) or offsets.typecode != "q" or not _ids_ok(labels):
        return None
    ffi = lib.ffi
    out = bytearray(max(1, ntrans))
    if lib.lib.gr_live(len(comp), len(offsets) - 1, _buf(ffi, "int64_t[]", offsets),
                       _buf(ffi, "uint8_t[]", labels), _ID_CODES[labels.typecode], ntrans,
                       _buf(ffi, "int32_t[]", comp), _buf(ffi, "int32_t[]", members),
                       _buf(ffi, "int32_t[]", start), ffi.from_buffer("uint8_t[]", bytes(terminal) or b"\0"),
                       len(start) - 1, ffi.from_buffer("uint8_t[]", out)) != 0:
        raise MemoryError("no memory for the live transitions")
    return out[:ntrans]


FAIRNESS_CLASSES = ("Impartial", "Fair", "Just", "No Fairness")


def fairness(n: int, offsets: array, dst: array, labels: array, ntrans: int, comp: array, members: array,
             start: array, nontrivial: bytearray) -> list[str] | None:
    """The fairness class (a name of FAIRNESS_CLASSES) of every transition instance, or None where native
    code is unavailable. The graph must have a nontrivial SCC and be complete. The Python code costs
    about a tenth of the graph per transition instance (SimpleLoadBal-PT-02, 2,650 arcs and 45
    transition instances: 15-20 ms of CPU against 1 ms here plus 4.5 ms for loading the library), so
    arcs x transition instances / 10 is held against MIN_ITEMS."""
    lib = library(len(dst) * max(1, ntrans) // 10)
    if lib is None or not _csr_ok(offsets, dst) or not _ids_ok(labels):
        return None
    ffi = lib.ffi
    out = bytearray(max(1, ntrans))
    if lib.lib.gr_fairness(n, len(offsets) - 1, _buf(ffi, "int64_t[]", offsets), _buf(ffi, "int32_t[]", dst),
                           _buf(ffi, "uint8_t[]", labels), _ID_CODES[labels.typecode], ntrans,
                           _buf(ffi, "int32_t[]", comp), _buf(ffi, "int32_t[]", members),
                           _buf(ffi, "int32_t[]", start), ffi.from_buffer("uint8_t[]", bytes(nontrivial) or b"\0"),
                           len(start) - 1, ffi.from_buffer("uint8_t[]", out)) != 0:
        raise MemoryError("no memory for the fairness searches")
    return [FAIRNESS_CLASSES[k] for k in out[:ntrans]]


def _records(store):
    """(arena buffer, number of records, record size, byte offset and width of each field) of a packed
    store (`cpn.statespace.store.PackedStore`), or None for any other store."""
    if getattr(store, "kind", None) != "packed":
        return None
    size = store.struct.size
    n = len(store)
    arena = store.ffi.buffer(store.lib.cs_arena(store.handle), n * size) if n else b"\0"
    offsets, o = [], 0
    for w in store.widths:
        offsets.append(o)
        o += w
    return arena, n, size, offsets, list(store.widths)


def place_columns(store, caps: list[int]) -> list[list[int]] | None:
    """Per field f < len(caps) of a packed store's states, its distinct values, increasing; None when the
    store is not packed, native code is unavailable, or a value of field f is not below caps[f]."""
    rec = _records(store)
    lib = library(rec[1] * len(caps) // CHEAP) if rec is not None else None
    if lib is None:
        return None
    arena, n, size, fo, fw = rec
    nf = len(caps)
    if nf > len(fo):
        return None
    ffi = lib.ffi
    so = array("q", [0])
    for c in caps:
        so.append(so[-1] + c)
    seen = bytearray(max(1, so[-1]))
    if lib.lib.gr_columns(ffi.from_buffer("uint8_t[]", arena), n, size, nf, ffi.new("int32_t[]", fo[:nf] or [0]),
                          ffi.new("int32_t[]", fw[:nf] or [0]), _buf(ffi, "int64_t[]", so),
                          _buf(ffi, "int64_t[]", array("q", caps)), ffi.from_buffer("uint8_t[]", seen)) != 0:
        return None
    return [list(compress(range(caps[f]), seen[so[f]:so[f + 1]])) for f in range(nf)]


def max_sum(store, fields: list[int], tables: list[list[int]]) -> int | None:
    """The largest sum over `fields` of tables[k][value of field fields[k]] over the packed store's states
    (every value must index its table, as `place_columns` checked); None when not available."""
    rec = _records(store)
    lib = library(rec[1] * len(fields) // CHEAP) if rec is not None else None
    if lib is None:
        return None
    arena, n, size, fo, fw = rec
    ffi = lib.ffi
    to = array("q", [0])
    flat = array("q")
    for table in tables:
        flat.extend(table)
        to.append(len(flat))
    return lib.lib.gr_max_sum(ffi.from_buffer("uint8_t[]", arena), n, size, len(fields),
                              ffi.new("int32_t[]", [fo[f] for f in fields] or [0]),
                              ffi.new("int32_t[]", [fw[f] for f in fields] or [0]), _buf(ffi, "int64_t[]", to),
                              _buf(ffi, "int64_t[]", flat))


# ----------------------------------------------------------------------------- CTL fixpoints
def _pred_ok(pred_off, pred) -> bool:
    return _csr_ok(pred_off, pred)


def eu(n: int, pred_off: array, pred: array, phi: bytearray, psi: bytearray) -> bytearray | None:
    """E[phi U psi] over the predecessors (`reverse`): the psi-states and the phi-states with a path
    through phi-states to one; None where native code is unavailable."""
    lib = library(len(pred))
    if lib is None or not _pred_ok(pred_off, pred) or n == 0 or len(phi) < n or len(psi) < n:
        return None
    ffi = lib.ffi
    out = bytearray(psi)
    if lib.lib.gr_eu(n, _buf(ffi, "int64_t[]", pred_off), _buf(ffi, "int32_t[]", pred),
                     ffi.from_buffer("uint8_t[]", phi), ffi.from_buffer("uint8_t[]", out)) != 0:
        raise MemoryError("no memory for E[phi U psi]")
    return out


def ex(n: int, pred_off: array, pred: array, target: bytearray) -> bytearray | None:
    """The states with an arc into a target state, or None."""
    lib = library(len(pred))
    if lib is None or not _pred_ok(pred_off, pred) or n == 0 or len(target) < n:
        return None
    ffi = lib.ffi
    out = bytearray(n)
    lib.lib.gr_ex(n, _buf(ffi, "int64_t[]", pred_off), _buf(ffi, "int32_t[]", pred),
                  ffi.from_buffer("uint8_t[]", target), ffi.from_buffer("uint8_t[]", out))
    return out


def eg(n: int, offsets: array, dst: array, pred_off: array, pred: array, dead: bytearray,
       phi: bytearray) -> bytearray | None:
    """EG phi without fairness: the phi-states with a path that stays in phi forever or ends in a dead
    phi-state; None where native code is unavailable."""
    lib = library(len(dst))
    if lib is None or not _csr_ok(offsets, dst) or not _pred_ok(pred_off, pred) or n == 0 \
            or len(dead) < n or len(phi) < n:
        return None
    ffi = lib.ffi
    out = bytearray(n)
    if lib.lib.gr_eg(n, len(offsets) - 1, _buf(ffi, "int64_t[]", offsets), _buf(ffi, "int32_t[]", dst),
                     _buf(ffi, "int64_t[]", pred_off), _buf(ffi, "int32_t[]", pred),
                     ffi.from_buffer("uint8_t[]", dead), ffi.from_buffer("uint8_t[]", phi),
                     ffi.from_buffer("uint8_t[]", out)) != 0:
        raise MemoryError("no memory for EG phi")
    return out


def label_rows(n: int, offsets: array, labels: array, nlabels: int) -> list[bytearray] | None:
    """Per label t < nlabels, the states (a bytearray of n) with an arc labelled t; None where native
    code is unavailable."""
    lib = library(len(labels))
    if lib is None or not isinstance(offsets, array) or offsets.typecode != "q" or not _ids_ok(labels) \
            or n == 0 or nlabels == 0:
        return None
    ffi = lib.ffi
    out = bytearray(n * nlabels)
    lib.lib.gr_label_rows(n, len(offsets) - 1, _buf(ffi, "int64_t[]", offsets), _buf(ffi, "uint8_t[]", labels),
                          _ID_CODES[labels.typecode], nlabels, ffi.from_buffer("uint8_t[]", out))
    return [out[t * n:(t + 1) * n] for t in range(nlabels)]


# ----------------------------------------------------------------------------- LTL
def ltl_accepting_cycle(n: int, offsets: array, dst: array, props: list[bytearray], moves,
                        initial: int, nq: int, n_acc: int) -> tuple[bool, int] | None:
    """Whether the product of the complete graph (state 0 initial, a state without arcs repeating
    forever) with a generalised Büchi automaton has an accepting cycle, and the product states the
    search generated; None where native code is unavailable or the product is too large.

    `props[b]` is proposition b's value in every state; `moves(q, mask)` lists the automaton's moves
    (acceptance sets, next state) from state q reading a state whose true propositions are `mask`, as
    `cpn.checks.buchi.Automaton.moves` gives them; it is asked once per automaton state and distinct
    mask."""
    lib = library(len(dst))
    if lib is None or not _csr_ok(offsets, dst) or n == 0 or len(props) > 30 or n_acc > 31 \
            or any(len(p) < n for p in props):
        return None
    ffi = lib.ffi
    flat = bytearray().join(bytes(p[:n]) for p in props) or bytearray(1)
    mask = array("i", bytes(4 * n))
    lib.lib.gr_masks(n, len(props), ffi.from_buffer("uint8_t[]", flat), _buf(ffi, "int32_t[]", mask))
    distinct = distinct_ids(mask)
    if distinct is None:
        distinct = sorted(set(mask))
    mtable = array("i", bytes(4 * (distinct[-1] + 1)))
    for k, m in enumerate(distinct):
        mtable[m] = k
    moff, macc, mdst = array("q", [0]), array("I"), array("i")
    for q in range(nq):
        for m in distinct:
            merged: dict = {}
            for acc, r in moves(q, m):
                merged[r] = merged.get(r, 0) | acc  # one edge per target, with every set some edge to it meets
            for r, acc in merged.items():
                mdst.append(r)
                macc.append(acc)
            moff.append(len(mdst))
    count = ffi.new("int64_t *")
    got = lib.lib.gr_ltl(n, len(offsets) - 1, _buf(ffi, "int64_t[]", offsets), _buf(ffi, "int32_t[]", dst),
                         _buf(ffi, "int32_t[]", mask), _buf(ffi, "int32_t[]", mtable), len(distinct), nq,
                         _buf(ffi, "int64_t[]", moff), _buf(ffi, "uint32_t[]", macc), _buf(ffi, "int32_t[]", mdst),
                         initial, (1 << n_acc) - 1, count)
    if got == -1:
        raise MemoryError("no memory for the product with the automaton")
    if got < 0:
        return None
    return bool(got), count[0]


# ----------------------------------------------------------------------------- integer columns
def _i64(a) -> bool:
    return isinstance(a, array) and a.typecode == "q"


def add_columns(columns: list[array]) -> array | None:
    """The sum of integer columns (arrays "q" of one length), item by item; None where native code is
    unavailable."""
    lib = library(len(columns[0]) // CHEAP) if columns else None
    if lib is None or not all(_i64(c) and len(c) == len(columns[0]) for c in columns):
        return None
    ffi = lib.ffi
    acc = array("q", columns[0])
    for c in columns[1:]:
        lib.lib.gr_add_i64(len(acc), _buf(ffi, "int64_t[]", c), _buf(ffi, "int64_t[]", acc))
    return acc


def less_equal(left, right) -> bytearray | None:
    """Item by item, left <= right (a bytearray of 0/1) for integer columns (arrays "q") or one column and
    an int; None where native code is unavailable or neither side is a column."""
    n = len(left) if _i64(left) else len(right) if _i64(right) else 0
    lib = library(n // CHEAP) if n else None
    if lib is None:
        return None
    ffi = lib.ffi
    out = bytearray(n)
    if _i64(left) and _i64(right):
        if len(right) != n:
            return None
        lib.lib.gr_le_i64(n, _buf(ffi, "int64_t[]", left), _buf(ffi, "int64_t[]", right),
                          ffi.from_buffer("uint8_t[]", out))
    elif _i64(left) and isinstance(right, int) and -(1 << 63) <= right < (1 << 63):
        lib.lib.gr_le_const(n, _buf(ffi, "int64_t[]", left), right, 0, ffi.from_buffer("uint8_t[]", out))
    elif _i64(right) and isinstance(left, int) and -(1 << 63) <= left < (1 << 63):
        lib.lib.gr_le_const(n, _buf(ffi, "int64_t[]", right), left, 1, ffi.from_buffer("uint8_t[]", out))
    else:
        return None
    return out
