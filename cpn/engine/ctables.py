"""The tables the generated C and the Python engine share: colour ids of colour sets (`layout`), and the
copying of interned markings, deltas and binding elements between the C tables (`_cnet.c`) and the
compiled engine's (`NativeCode.to_c`, `NativeCode.to_python`), with the same ids on both sides.

Examples
--------
>>> from cpn.values.colours import IntCS, ProductCS, BoolCS
>>> lay = layout(ProductCS("P", [IntCS("A", 2, 4), BoolCS("B")]))
>>> lay.leaves, lay.size, lay.index[(3, True)]
([(2, 3), (0, 2)], 6, 3)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from itertools import product as _cartesian

from cpn.values.colours import (
    AliasCS,
    BoolCS,
    EnumCS,
    IndexCS,
    IntCS,
    ListCS,
    ProductCS,
    RecordCS,
    StringCS,
    UnionCS,
    UnitCS,
)

#: colour sets with more values than this are not laid out as colour ids
MAX_COLOURS: int = 1 << 20
_I64 = 1 << 62


class NotNative(Exception):
    """An inscription, colour set or net outside what the C code generator handles (the reason)."""


# ---------------------------------------------------------------------------- values in C
@dataclass
class S:
    """A scalar: a C expression of type int64_t (bool 0/1, unit 0, an enumeration's position, an int)."""

    code: str


@dataclass
class U(S):
    """A value held in C as its interned id in the domain of `lay` (a union with data)."""

    lay: object = None


@dataclass
class Tp:
    """A product or record: its components (records in the order of their labels)."""

    items: list


@dataclass
class Layout:
    """How the values of a colour set are colour ids: leaves (low, count) in mixed radix, the first most
    significant (the order of `itertools.product`, hence of `CS.all()`)."""

    leaves: list[tuple[int, int]]
    shape: object
    values: list
    index: dict = field(default_factory=dict)
    interned = False

    @property
    def size(self) -> int:
        return len(self.values)

    def strides(self) -> list[int]:
        out, s = [], 1
        for _lo, n in reversed(self.leaves):
            out.append(s)
            s *= n
        return list(reversed(out))

    def decode(self, code: str):
        """The value (as a C value) of colour id `code`."""
        strides = self.strides()
        it = iter(range(len(self.leaves)))

        def build(sh):
            if sh is None:
                i = next(it)
                lo, n = self.leaves[i]
                x = code if strides[i] == 1 else f"({code} / {strides[i]})"
                if i > 0:
                    x = f"({x} % {n})"
                return S(x if lo == 0 else f"({lo} + {x})")
            return Tp([build(s) for s in sh])
        return build(self.shape)


class _Nodes:
    """What the two kinds of interned colour ids share: the leaves C interns for a value."""

    def c_flat(self, v, cid: int, child=None) -> list[int]:
        """The leaves C interns for value v of colour id `cid`: its own (`flat`), or for a value C cannot hold
        (an integer beyond 64 bits) leaves of the placeholder's width, the last naming the id: a value of its
        own whose leaves C never reads (`g_leaf`: the engine evaluates what reads them)."""
        try:
            return self.flat(v, child)
        except OverflowError:
            return [0] * (self.width - 1) + [cid]


@dataclass
class Interned(_Nodes):
    """The colour ids of a colour set without a finite layout (an unbounded int, a product or record with
    one): ids given in the order the values are first met, in the C table of domain `dom` (`g_node`, a
    value as its int64 leaves) and in `values`/`index` here, the same on both sides (`NativeCode.to_c`
    and `to_python` copy what one side interned to the other before the other reads it). `leaves`: per
    leaf, (low, high) of a finite range or (None, None), and how Python holds it ("int", "bool", "unit")."""

    dom: int
    leaves: list[tuple]
    shape: object
    values: list = field(default_factory=list)
    index: dict = field(default_factory=dict)
    interned = True
    size = None

    @property
    def width(self) -> int:
        """The leaves of a placeholder (`c_flat`): one more than any value's."""
        return len(self.leaves) + 1

    def decode(self, code: str):
        """The value (as a C value) of colour id `code`: its leaves read from the table."""
        return _decode(self.leaves, self.shape, self.dom, self.width, code, 0)

    def flat(self, v, cid=None) -> list[int]:
        """The leaves of Python value v (OverflowError if one does not fit 64 bits; `cid(lay, x)`: the id of
        value x of a component held by reference)."""
        return _flat(self.leaves, self.shape, v, cid)

    def value(self, flat) -> object:
        """The Python value of leaves `flat`."""
        return _value(self.leaves, self.shape, flat)


class _ByReference(_Nodes):
    """What the domains of values held in C by their id share (unions with data, lists): their shape in a
    product is ("u", domain), and a value in C is its id (`U`)."""

    interned = True
    size = None

    @property
    def shape(self):
        return ("u", self.dom)

    def decode(self, code: str):
        return U(code, self)


@dataclass
class UnionDom(_ByReference):
    """The interned colour ids of a union with data: a value is the node [tag, its data's leaves] of domain
    `dom` (a constructor without data: [tag]); `cons` per tag: None, or its data's (leaves, shape)."""

    dom: int
    cons: list
    values: list = field(default_factory=list)
    index: dict = field(default_factory=dict)

    @property
    def width(self) -> int:
        return 2 + max((len(c[0]) for c in self.cons if c is not None), default=0)

    def payload(self, code: str, tag: int):
        """The data (as a C value) of node `code`, whose tag is `tag`."""
        leaves, sh = self.cons[tag]
        return _decode(leaves, sh, self.dom, self.width, code, 1)

    def flat(self, v, cid=None) -> list[int]:
        if not isinstance(v, tuple):
            return [v]
        tag, x = v
        leaves, sh = self.cons[tag]
        return [tag, *_flat(leaves, sh, x, cid)]

    def value(self, flat) -> object:
        tag = int(flat[0])
        if self.cons[tag] is None:
            return tag
        leaves, sh = self.cons[tag]
        return (tag, _value(leaves, sh, flat[1:]))


@dataclass
class ListDom(_ByReference):
    """The interned ids of the lists whose elements have leaves `leaves` and shape `shape` (their ranges
    dropped: one domain per element structure, so that `[]` of one type is one id): a list is the node
    [n, its n elements' leaves] of domain `dom`, an element being held as a product is (its scalars, and
    the ids of the unions and lists in it); a list the engine made that C cannot hold (an integer beyond 64
    bits) is [-1, its id]. Held in C by reference, as a union with data is (`U`)."""

    dom: int
    leaves: list[tuple]
    elem_shape: object
    values: list = field(default_factory=list)
    index: dict = field(default_factory=dict)

    @property
    def ew(self) -> int:
        """The leaves of one element."""
        return len(self.leaves)

    def element(self, code: str, i: str):
        """Element i (C code, from 0) of list `code`, as a C value (c->err if there is none)."""
        return _decode_leaves(self.leaves, self.elem_shape,
                              lambda j: f"g_lelem(c, {self.dom}, {self.ew}, {code}, {i}, {j})")

    def flat(self, v, cid=None) -> list[int]:
        out = [len(v)]
        for x in v:
            out += _flat(self.leaves, self.elem_shape, x, cid)
        return out

    def c_flat(self, v, cid: int, child=None) -> list[int]:
        try:
            return self.flat(v, child)
        except OverflowError:
            return [-1, cid]

    def value(self, flat) -> object:
        n, w = int(flat[0]), self.ew
        return tuple(_value(self.leaves, self.elem_shape, flat[1 + k * w:1 + (k + 1) * w]) for k in range(n))


class StrDom(ListDom):
    """The interned ids of strings: a string is the list of its characters' code points (the node [n, its
    n codes] of its own domain), so that `^` is the lists' append and `size` their length, and two strings
    are equal where their ids are. One domain holds the strings of every string colour set (a restricted one,
    `string with "a".."z" and 1..8`, checks its tokens: a `RangedList` over this domain)."""

    def flat(self, v, cid=None) -> list[int]:
        return [len(v), *map(ord, v)]

    def c_flat(self, v, cid: int, child=None) -> list[int]:
        return self.flat(v)

    def value(self, flat) -> object:
        return "".join(chr(int(x)) for x in flat[1:1 + int(flat[0])])


class RangedList:
    """A list colour set with a length range or ranges in its elements (`list INT with 0..3`, `list N` for
    `N = int with 0..3`): its values are those of the lists' domain `base` (one id for one list, whatever
    colour set holds it), and a value becomes one of its tokens only once `checks` pass: per element, the
    leaves (index, low, high) in range, and the ranged lists in it (index, their RangedList); `length`,
    (low, high) or None."""

    def __init__(self, base: ListDom, name: str, checks: list, nested: list, length):
        self.base, self.name, self.checks, self.nested, self.length = base, name, checks, nested, length

    def __getattr__(self, attr):
        return getattr(self.base, attr)

    def decode(self, code: str):
        return U(code, self.base)


def list_key(leaves, shape) -> tuple:
    """The domain of lists with elements of leaves `leaves` and shape `shape`: their structure, ranges
    dropped."""
    return tuple(k if isinstance(k, str) else ("d", k.dom) for _lo, _hi, k in leaves), shape


def _decode(leaves, shape, dom: int, width: int, code: str, at: int):
    return _decode_leaves(leaves, shape, lambda j: f"g_leaf(c, {dom}, {width}, {code}, {at + j})")


def _decode_leaves(leaves, shape, leaf):
    """The C value of shape `shape` whose leaf j is the C code `leaf(j)` (a value held by reference: its
    domain's `decode`)."""
    it = iter(range(len(leaves)))
    kinds = iter(leaves)

    def build(sh):
        if sh is None or sh[0] == "u":
            x = leaf(next(it))
            kind = next(kinds)[2]
            return kind.decode(x) if sh is not None else S(x)
        return Tp([build(s) for s in sh])
    return build(shape)


def _flat(leaves, shape, v, cid) -> list[int]:
    out: list[int] = []
    kinds = iter(leaves)

    def walk(sh, x):
        if sh is None or sh[0] == "u":
            kind = next(kinds)[2]
            if not isinstance(kind, str):
                if cid is None:
                    raise KeyError("a value held by reference")
                out.append(cid(kind, x))
                return
            x = 0 if kind == "unit" else int(x)
            if not -(1 << 63) <= x < 1 << 63:
                raise OverflowError(f"the integer {x} does not fit 64 bits")
            out.append(x)
            return
        for s, y in zip(sh, x):
            walk(s, y)
    walk(shape, v)
    return out


def _value(leaves, shape, flat):
    it = iter(zip(flat, leaves))

    def build(sh):
        if sh is None or sh[0] == "u":
            x, (_lo, _hi, kind) = next(it)
            if not isinstance(kind, str):
                return kind.values[x]
            return bool(x) if kind == "bool" else () if kind == "unit" else int(x)
        return tuple(build(s) for s in sh)
    return build(shape)


def value_parts(cs, ref=None):
    """(leaves, shape) of the values of colour set cs held as a product is in C (`_interned_parts`)."""
    return _interned_parts(cs, ref)


def _interned_parts(cs, ref=None):
    """(leaves, shape) of a colour set whose values are scalars, values held by reference (`ref(cs)`: the
    layout of a union with data) or products and records of them."""
    cs = _base(cs)
    if ref is not None and (isinstance(cs, (ListCS, StringCS)) or (isinstance(cs, UnionCS)
                                                        and any(c is not None for _, c in cs.constructors))):
        lay = ref(cs)
        return [(None, None, lay)], lay.shape
    if isinstance(cs, UnitCS):
        return [(0, 0, "unit")], None
    if isinstance(cs, BoolCS):
        return [(0, 1, "bool")], None
    if isinstance(cs, IntCS):
        if cs.low is None:
            return [(None, None, "int")], None
        if abs(cs.low) >= _I64 or abs(cs.high) >= _I64:
            raise NotNative(f"colour set {cs.name} has values too large for C")
        return [(cs.low, cs.high, "int")], None
    if isinstance(cs, EnumCS):
        return [(0, len(cs.constants) - 1, "int")], None
    if isinstance(cs, UnionCS) and all(c is None for _, c in cs.constructors):
        return [(0, len(cs.constructors) - 1, "int")], None
    if isinstance(cs, IndexCS):
        return [(cs.low, cs.high, "int")], None
    if isinstance(cs, (ProductCS, RecordCS)):
        comps = cs.components if isinstance(cs, ProductCS) else [c for _, c in cs.fields]
        out, shapes = [], []
        for c in comps:
            lv, sh = _interned_parts(c, ref)
            out.extend(lv)
            shapes.append(sh)
        return out, tuple(shapes)
    raise NotNative(f"colour set {cs.name} ({cs.kind}) has no C layout")


def interned(cs, dom, ref=None):
    """The interned colour ids of colour set cs (NotNative if its values are not scalars, unions with data
    (with `ref`), products or records of them); `dom()` numbers its domain once its components have
    theirs."""
    base = _base(cs)
    if ref is not None and isinstance(base, UnionCS):
        cons = [None if c is None else _interned_parts(c, ref) for _, c in base.constructors]
        return UnionDom(dom(), cons)
    lv, sh = _interned_parts(cs, ref)
    return Interned(dom(), lv, sh)


def base_colset(cs):
    """The colour set an alias names."""
    return _base(cs)


def _base(cs):
    while isinstance(cs, AliasCS):
        cs = cs.base
    return cs


def _layout_parts(cs):
    cs = _base(cs)
    if isinstance(cs, UnitCS):
        return [(0, 1)], None
    if isinstance(cs, BoolCS):
        return [(0, 2)], None
    if isinstance(cs, IntCS):
        if cs.low is None or cs.high < cs.low:
            raise NotNative(f"colour set {cs.name} is not a finite int range")
        return [(cs.low, cs.high - cs.low + 1)], None
    if isinstance(cs, EnumCS):
        return [(0, len(cs.constants))], None
    if isinstance(cs, UnionCS) and all(c is None for _, c in cs.constructors):  # an enumeration: its tags
        return [(0, len(cs.constructors))], None
    if isinstance(cs, IndexCS):
        return [(cs.low, cs.high - cs.low + 1)], None
    if isinstance(cs, (ProductCS, RecordCS)):
        comps = cs.components if isinstance(cs, ProductCS) else [c for _, c in cs.fields]
        out, shapes = [], []
        for c in comps:
            lv, sh = _layout_parts(c)
            out.extend(lv)
            shapes.append(sh)
        return out, tuple(shapes)
    raise NotNative(f"colour set {cs.name} ({cs.kind}) has no C layout")


def layout(cs) -> Layout:
    """The layout of a colour set, checked against its values (NotNative if it has none)."""
    lv, sh = _layout_parts(cs)
    total = 1
    for lo, n in lv:
        if abs(lo) + n >= _I64 >> 20:
            raise NotNative(f"colour set {cs.name} has values too large for C")
        total *= n
        if total > MAX_COLOURS:
            raise NotNative(f"colour set {cs.name} has more than {MAX_COLOURS:,} values")
    vals = cs.values()
    if vals is None or len(vals) != total:
        raise NotNative(f"colour set {cs.name} is not enumerable")
    lay = Layout(lv, sh, vals)
    # the colour ids must be the positions in CS.all(): check the mixed radix against the values
    ranges = [range(lo, lo + n) for lo, n in lv]
    for cid, flat in enumerate(_cartesian(*ranges)):
        if _flatten(vals[cid]) != list(flat):
            raise NotNative(f"colour set {cs.name}: its values are not in mixed-radix order")
    lay.index = {v: i for i, v in enumerate(vals)}
    return lay


def _flatten(v) -> list:
    if v == ():
        return [0]
    if isinstance(v, tuple):
        out = []
        for x in v:
            out.extend(_flatten(x))
        return out
    return [int(v)]


# ---------------------------------------------------------------------------- the net
@dataclass
class NativeCode:
    """The C of a net's transitions (`source`, compiled after the run-time `_cnet.c` in the build manifest's
    libraries that take a net's C: `cpn._native.manifest`) and the exchange of tables with the Python
    engine."""

    source: str
    native: list[int]  # transitions compiled to C
    left: dict[int, str]  # transitions left to the Python engine: why
    layouts: list[Layout | None]  # per place (None: a place whose markings C does not hold, timed nets)
    var_layouts: dict[int, list[Layout]]  # per native transition
    # per place, whether it is timed (the search of timed nets): its tokens' keys are (value, timestamp),
    # in C a timed colour id (`gen_tid_put`)
    timed: list[bool] | None = None
    _tids: list[dict] | None = None  # per timed place: (value, timestamp) -> its timed colour in C
    _tid_keys: tuple | None = None  # (the context, per timed place its timed colours' keys read from C)
    # the interned colour sets, by domain; per transition whose binding keys are interned, its domain
    doms: list[Interned] = field(default_factory=list)
    bind_doms: dict[int, int] = field(default_factory=dict)

    def _cid(self, ffi, lib, ctx, lay, v) -> int:
        """The colour id of value v in layout lay (for an interned one, interned on both sides if new)."""
        cid = lay.index.get(v)
        if cid is None:
            if not lay.interned:
                raise KeyError(v)
            flat = lay.c_flat(v, len(lay.values), lambda child, x: self._cid(ffi, lib, ctx, child, x))
            cid = lib.gen_node_put(ctx, lay.dom, ffi.new("int64_t[]", flat), len(flat))
            if cid != len(lay.values):
                raise MemoryError("the native tables cannot grow any more") if cid < 0 else \
                    RuntimeError(f"native values out of step with the engine (domain {lay.dom})")
            lay.values.append(v)
            lay.index[v] = cid
        return cid

    def _pairs_to_c(self, ffi, lib, ctx, p: int, d: dict) -> list[int]:
        """A Python multiset of place p as C pairs (colour id or timed colour id, count)."""
        lay = self.layouts[p]
        index = lay.index
        flat: list[int] = []
        if self.timed is None or not self.timed[p]:
            if lay.interned:
                for v, n in d.items():
                    flat += (self._cid(ffi, lib, ctx, lay, v), n)
                return flat
            for v, n in d.items():
                flat += (index[v], n)
            return flat
        if self._tids is None:
            self._tids = [{} for _ in self.layouts]
        tids = self._tids[p]
        for k, n in d.items():
            tid = tids.get(k)
            if tid is None:
                v, ts = k
                if not -(1 << 63) <= ts < 1 << 63:
                    raise OverflowError(f"the timestamp {ts} does not fit 64 bits")
                tid = lib.gen_tid_put(ctx, p, self._cid(ffi, lib, ctx, lay, v), ts)
                if tid < 0:
                    raise MemoryError("the native tables cannot grow any more")
                tids[k] = tid
            flat += (tid, n)
        return flat

    def _timed_values(self, ffi, lib, ctx, p: int) -> list:
        """Place p's timed colours in C as (value, timestamp) keys, by timed colour id: those read before
        (per context: C only appends to the table) and the new ones, so that a search returning to Python
        at each level does not read the whole table each time."""
        colp, tsp = ffi.new("int32_t **"), ffi.new("int64_t **")
        n = lib.gen_tid_table(ctx, p, colp, tsp)
        key = int(ffi.cast("uintptr_t", ctx))
        if self._tid_keys is None or self._tid_keys[0] != key:
            self._tid_keys = (key, [[] for _ in self.layouts])
        got = self._tid_keys[1][p]
        if n < len(got):  # (another table: read it anew)
            got = self._tid_keys[1][p] = []
        if n > len(got):
            vals = self.layouts[p].values
            h = len(got)
            got += zip(map(vals.__getitem__, ffi.unpack(colp[0] + h, n - h)), ffi.unpack(tsp[0] + h, n - h))
        return got

    def to_c(self, engine, lib, ctx) -> None:
        """Copy the engine's markings, deltas and binding elements that the C tables do not have yet."""
        ffi, lib = lib.ffi, lib.lib
        P = len(engine.places)
        for lay in self.doms:  # a new context's tables: the values interned so far, in their order
            for i in range(lib.gen_node_count(ctx, lay.dom), len(lay.values)):
                flat = lay.c_flat(lay.values[i], i, lambda child, x: child.index[x])
                if lib.gen_node_put(ctx, lay.dom, ffi.new("int64_t[]", flat), len(flat)) != i:
                    raise RuntimeError(f"native values out of step with the engine (domain {lay.dom})")
        for what, tables in ((0, engine.store.dicts), (1, engine._deltas)):
            for p in range(P):
                if self.layouts[p] is None:  # a place whose markings C does not hold
                    continue
                have = lib.gen_count(ctx, what, p)
                for i in range(have, len(tables[p])):
                    d = tables[p][i]
                    flat = self._pairs_to_c(ffi, lib, ctx, p, d)
                    got = lib.gen_ms_put(ctx, what, p, ffi.new("int32_t[]", flat or [0]), len(d))
                    if got != i:
                        raise RuntimeError(f"native tables out of step with the engine (place {p}, {got} != {i})")
        have = lib.gen_count(ctx, 2, 0)
        for i in range(have, len(engine._be)):
            t, vals = engine._be[i]
            got = lib.gen_be_put(ctx, t, self._be_key(ffi, lib, ctx, t, vals))
            if got != i:
                raise RuntimeError(f"native binding elements out of step with the engine ({got} != {i})")

    def _be_key(self, ffi, lib, ctx, t: int, vals: tuple) -> int:
        lays = self.var_layouts.get(t)
        if lays is None:
            return -1
        dom = self.bind_doms.get(t)
        if dom is not None:  # the interned tuple of the variables' slots (`TransitionC.slot`)
            slots = []
            for lay, v in zip(lays, vals):
                if not lay.interned:  # a scalar's slot is its value (its colour id plus its low), else its id
                    cid = lay.index.get(v)
                    if cid is None:
                        return -1
                    slots.append(cid + lay.leaves[0][0] if lay.shape is None else cid)
                elif lay.shape is None:
                    if not lay.leaves[0][2] == "int" or not isinstance(v, int) or not -(1 << 63) <= v < 1 << 63:
                        return -1
                    slots.append(v)
                else:
                    try:
                        slots.append(self._cid(ffi, lib, ctx, lay, v))
                    except OverflowError:
                        return -1
            key = lib.gen_node_put(ctx, dom, ffi.new("int64_t[]", slots or [0]), len(slots))
            if key < 0:
                raise MemoryError("the native tables cannot grow any more")
            return key
        key = 0
        for lay, v in zip(lays, vals):
            cid = lay.index.get(v)
            if cid is None:
                return -1
            key = key * lay.size + cid
        return key

    def to_python(self, engine, lib, ctx) -> None:
        """Copy the markings, deltas and binding elements C made into the engine's tables (same ids)."""
        ffi, lib = lib.ffi, lib.lib
        P = len(engine.places)
        store = engine.store
        for lay in self.doms:  # first the values C interned (components first): the markings' ids name them
            n = lib.gen_node_count(ctx, lay.dom)
            if n > len(lay.values):
                lists = isinstance(lay, ListDom)  # (a list's leaves are as many as its elements make)
                w = 1 if lists else lay.width
                buf = ffi.new("int64_t[]", w)
                for i in range(len(lay.values), n):
                    if lists and lib.gen_node_len(ctx, lay.dom, i) > w:
                        w = lib.gen_node_len(ctx, lay.dom, i)
                        buf = ffi.new("int64_t[]", w)
                    k = lib.gen_node_get(ctx, lay.dom, i, buf, w)
                    v = lay.value(ffi.unpack(buf, k))
                    lay.values.append(v)
                    lay.index[v] = i
        offp, lenp, pairp = ffi.new("int64_t **"), ffi.new("int32_t **"), ffi.new("int32_t **")
        for what in (0, 1):
            for p in range(P):
                if self.layouts[p] is None:
                    continue
                vals = self.layouts[p].values
                have = len(store.dicts[p]) if what == 0 else len(engine._deltas[p])
                total = lib.gen_ms_table(ctx, what, p, offp, lenp, pairp)
                if total <= have:  # (fewer: the engine went on alone, past a hand-over to Python)
                    continue
                if self.timed is not None and self.timed[p]:
                    vals = self._timed_values(ffi, lib, ctx, p)
                offs = ffi.unpack(offp[0] + have, total - have)
                lens = ffi.unpack(lenp[0] + have, total - have)
                start = offs[0]
                pairs = ffi.unpack(pairp[0] + start, offs[-1] + 2 * lens[-1] - start)
                # the colours' values and counts of all the pairs at once, then each multiset's slice of them
                get = vals.__getitem__
                cols, counts = list(map(get, pairs[0::2])), pairs[1::2]
                made = [dict(zip(cols[h:h + n], counts[h:h + n]))
                        for h, n in zip([(o - start) >> 1 for o in offs], lens)]
                if what == 0:  # C interned them: new and distinct, indexed when the engine next needs it
                    store.append_new(p, made)
                    continue
                for i, d in enumerate(made, have):
                    if engine._delta(p, d) != i:
                        raise RuntimeError(f"native tables out of step with the engine (place {p}, id {i})")
        total = lib.gen_count(ctx, 2, 0)
        tp = ffi.new("int32_t *")
        for i in range(len(engine._be), total):
            key = lib.gen_be_key(ctx, i, tp)
            t = tp[0]
            dom = self.bind_doms.get(t)
            if dom is not None:
                lays = self.var_layouts[t]
                buf = ffi.new("int64_t[]", max(len(lays), 1))
                lib.gen_node_get(ctx, dom, key, buf, len(lays))
                vals = tuple(lay.values[x - lay.leaves[0][0] if lay.shape is None else x] if not lay.interned
                             else lay.value([x]) if lay.shape is None else lay.values[x] for lay, x in zip(lays, buf))
                if engine._intern_be(t, vals) != i:
                    raise RuntimeError("native binding elements out of step with the engine")
                continue
            vals = []
            for lay in reversed(self.var_layouts[t]):
                key, cid = divmod(key, lay.size)
                vals.append(lay.values[cid])
            if engine._intern_be(t, tuple(reversed(vals))) != i:
                raise RuntimeError("native binding elements out of step with the engine")
