"""State stores: the states of a search numbered 0.. in discovery order, found again by value.

`PackedStore` keeps every state as a fixed-width record of bytes (field f of the state tuple in the
fewest bytes its largest value so far needs: 1, 2, 4 or 8) in one contiguous arena with an
open-addressing hash table over it, both in native memory (`_packed.c`, built with the system C compiler
through cffi on first use). `TupleStore` keeps the engine's tuples in a list and a dict; it is used where
the packed store cannot be built (no compiler, no cffi) or the states are not tuples of non-negative
integers, and a `PackedStore` turns itself into one the moment a state cannot be packed.

Both give the same ids for the same sequence of insertions, and `states` is a sequence of the engine's
tuples either way (the packed store decodes a record when it is read).

Examples
--------
>>> st = new_store((0, 0), packed=False)
>>> st.add_successors([(0, (0, 1)), (1, (0, 0)), (2, (0, 1))], dst := [])
[0]
>>> dst, st.states[1], st.find((0, 1)), st.kind
([1, 0, 1], (0, 1), 1, 'tuples')
"""

from __future__ import annotations

import struct
from array import array
from collections.abc import Sequence
from itertools import chain

from cpn._util.cbuild import build, why_unavailable

_CODES = {1: "B", 2: "H", 4: "I", 8: "Q"}
_CHUNK = 4096  # records decoded per copy when the states are iterated


def _library():
    return build("store")


def packed_unavailable() -> str | None:
    """Why the packed store cannot be used here (None if it can)."""
    return None if _library() is not None else why_unavailable()


def new_store(s0, packed: bool = True):
    """A store holding the initial state `s0` as state 0: packed where possible, else tuples."""
    if packed and PackedStore.fits(s0):
        lib = _library()
        if lib is not None:
            return PackedStore(lib, s0)
    return TupleStore(s0)


def pack(store):
    """`store` as a packed store with the same ids where that can be built (else `store` itself)."""
    if store.kind != "tuples" or not len(store) or not PackedStore.fits(store.states[0]):
        return store
    lib = _library()
    if lib is None:
        return store
    packed = PackedStore(lib, store.states[0])
    packed.add_successors([(0, s) for s in store.states[1:]], array("i"))
    return packed if packed.kind == "packed" else store


class TupleStore:
    """The engine's states as they are: a list (id -> state) and a dict (state -> id)."""

    kind = "tuples"

    def __init__(self, s0=None, states: list | None = None):
        self.states: list = states if states is not None else ([] if s0 is None else [s0])
        self.index: dict = {s: i for i, s in enumerate(self.states)}

    def __len__(self) -> int:
        return len(self.states)

    def find(self, state) -> int | None:
        """The id of a state, or None."""
        return self.index.get(state)

    def add_successors(self, succ: list, dst) -> list[int]:
        """Number the states of the (binding element, state) pairs `succ`, append their ids to `dst`
        and return the positions in `succ` of the states that were new, in order."""
        states, index = self.states, self.index
        get = index.get
        fresh = []
        k = 0
        for _be, t in succ:
            j = get(t)
            if j is None:
                j = index[t] = len(states)
                states.append(t)
                fresh.append(k)
            dst.append(j)
            k += 1
        return fresh

    def nbytes(self) -> int | None:
        return None

    def finish(self) -> None:
        pass


class _PackedStates(Sequence):
    """The states of a packed store as the engine's tuples (decoded when read)."""

    def __init__(self, store: PackedStore):
        self._store = store

    def __len__(self) -> int:
        return len(self._store)

    def __getitem__(self, i):
        n = len(self)
        if isinstance(i, slice):
            start, stop, step = i.indices(n)
            if step != 1:
                return [self[j] for j in range(start, stop, step)]
            if stop <= start:
                return []
            st = self._store  # a run of records: copied once, decoded at C speed
            size = st.struct.size
            return list(st.struct.iter_unpack(bytes(st.ffi.buffer(st.lib.cs_arena(st.handle) + start * size,
                                                                  (stop - start) * size))))
        if i < 0:
            i += n
        if not 0 <= i < n:
            raise IndexError("state id out of range")
        st = self._store
        size = st.struct.size
        return st.struct.unpack(st.ffi.buffer(st.lib.cs_arena(st.handle) + i * size, size))

    def __iter__(self):
        # a few thousand records copied at a time, decoded one by one (chain yields at C speed)
        st = self._store
        size = st.struct.size
        iter_unpack = st.struct.iter_unpack
        buffer, arena = st.ffi.buffer, st.lib.cs_arena
        n = len(self)
        return chain.from_iterable(
            iter_unpack(bytes(buffer(arena(st.handle) + start * size, min(_CHUNK, n - start) * size)))
            for start in range(0, n, _CHUNK))


class PackedStore:
    """States as fixed-width records in native memory (see the module's docstring)."""

    kind = "packed"

    @staticmethod
    def fits(s0) -> bool:
        """Whether states shaped like `s0` can be packed (a non-empty tuple of non-negative ints)."""
        return (isinstance(s0, tuple) and len(s0) > 0
                and all(type(v) is int and v >= 0 for v in s0))

    def __init__(self, library, s0: tuple, widths: list[int] | None = None):
        self.ffi, self.lib = library.ffi, library.lib
        self.widths = widths or [_width(v) for v in s0]
        self.handle = self.ffi.gc(self.lib.cs_new(len(s0), bytes(self.widths)), self.lib.cs_free)
        if self.handle == self.ffi.NULL:
            raise MemoryError("cannot allocate the state store")
        self.struct = struct.Struct(_format(self.widths))
        self._cap = 0
        self._grow(64)
        self._fallback: TupleStore | None = None
        self.states: Sequence = _PackedStates(self)
        self.add_successors([(0, s0)], [])

    def __len__(self) -> int:
        if self._fallback is not None:
            return len(self._fallback)
        return self.lib.cs_count(self.handle)

    def _grow(self, n: int) -> None:
        cap = max(n, 2 * self._cap)
        self._ids = self.ffi.new("int32_t[]", cap)
        self._fresh = self.ffi.new("int32_t[]", cap)
        self._cap = cap

    def find(self, state) -> int | None:
        """The id of a state, or None."""
        if self._fallback is not None:
            return self._fallback.find(state)
        try:
            rec = self.struct.pack(*state)
        except (struct.error, TypeError):
            return None
        i = self.lib.cs_find(self.handle, rec)
        if i == -2:
            raise MemoryError("the state store cannot build its table (no memory)")
        return None if i < 0 else i

    def add_successors(self, succ: list, dst) -> list[int]:
        """As `TupleStore.add_successors`; `dst` is an array("i") (its ids are appended as bytes)."""
        if self._fallback is not None:
            return self._fallback.add_successors(succ, dst)
        n = len(succ)
        pack = self.struct.pack
        try:
            buf = b"".join([pack(*t) for _be, t in succ])
        except (struct.error, TypeError):
            if not self._widen(succ):
                self._to_tuples()
                return self._fallback.add_successors(succ, dst)
            pack = self.struct.pack
            buf = b"".join([pack(*t) for _be, t in succ])
        if n > self._cap:
            self._grow(n)
        nfresh = self.lib.cs_add_many(self.handle, buf, n, self._ids, self._fresh)
        if nfresh < 0:
            raise MemoryError("the state store cannot grow any more")
        if type(dst) is list:
            dst.extend(self.ffi.unpack(self._ids, n))
        else:
            dst.frombytes(self.ffi.buffer(self._ids, 4 * n))
        return self.ffi.unpack(self._fresh, nfresh) if nfresh else []

    def sync(self) -> None:
        """Take over the fields' widths from native code that widened them (the native search does)."""
        if self._fallback is None:
            widths = list(self.ffi.unpack(self.lib.cs_widths(self.handle), len(self.widths)))
            if widths != self.widths:
                self.widths = widths
                self.struct = struct.Struct(_format(widths))

    def _widen(self, succ) -> bool:
        """Make every field wide enough for the states of `succ`; False if one cannot be packed."""
        widths = list(self.widths)
        for _be, t in succ:
            if len(t) != len(widths):
                return False
            for f, v in enumerate(t):
                if type(v) is not int or v < 0 or v >= 1 << 64:
                    return False
                w = _width(v)
                if w > widths[f]:
                    widths[f] = w
        if widths != self.widths:
            if self.lib.cs_widen(self.handle, bytes(widths)) != 0:
                raise MemoryError("the state store cannot grow any more")
            self.widths = widths
            self.struct = struct.Struct(_format(widths))
        return True

    def _to_tuples(self) -> None:
        """From now on, keep the states as tuples (a state that cannot be packed was met)."""
        fallback = TupleStore(states=list(self.states))
        self._fallback = fallback
        self.states = fallback.states
        self.kind = fallback.kind
        self.handle = None

    def nbytes(self) -> int | None:
        """Native bytes held (arena and hash table), or None once the states are tuples."""
        if self._fallback is not None:
            return None
        return self.lib.cs_nbytes(self.handle)

    def finish(self) -> None:
        """The search is over: give back the arena's unused room."""
        if self._fallback is None:
            self.lib.cs_trim(self.handle)


def _width(v: int) -> int:
    for w in (1, 2, 4, 8):
        if v < 1 << (8 * w):
            return w
    raise OverflowError(v)


def _format(widths) -> str:
    return "<" + "".join(_CODES[w] for w in widths)


__all__ = ["PackedStore", "TupleStore", "new_store", "pack", "packed_unavailable"]
