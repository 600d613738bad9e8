"""States and binding elements in a form that every engine of the same net understands.

An engine's state is a tuple of intern ids, one per place, and a binding element is an id too: both are
numbered in the order the engine met them, so two engines of one net (two processes, two machines) give
the same marking different ids. `StateTransfer` turns them into values equal in every engine (a place's
multiset as the sorted, flattened items of `compiled.canonical_key`; a binding element as its transition
and the values of its variables) and back, and gives each state a hash that is the same in every process
(Python's `hash()` of a string is salted per process; the hash of a tuple of ints is not).

Used by the partitioned search (`cpn.statespace.parallel`) to send states between processes: there a
state travels as its tuple of ids, with the keys of the ids the receiver has not been sent yet
(`place_keys`, `import_place_keys`), so that each marking of a place crosses once per pair of processes.

Examples
--------
>>> import cpn
>>> net = cpn.loads("colset N = int with 0..3; var x : N; place P : N = 1`0;"
...                 " trans inc [x < 3]; arc P -> inc : x; arc inc -> P : x + 1;").net
>>> from cpn.engine import compile_net
>>> a, b = transfer_for(compile_net(net)), transfer_for(compile_net(net))
>>> s1 = a.engine.successors(a.engine.initial_state())[0][1]
>>> b.import_state(a.export_state(s1)) == b.engine.successors(b.engine.initial_state())[0][1]
True
>>> a.stable_hash(s1) == b.stable_hash(b.import_state(a.export_state(s1)))
True
"""

from __future__ import annotations

import hashlib
from operator import getitem

from cpn.engine.compiled import canonical_key


def transfer_for(engine) -> StateTransfer | None:
    """The transfer of a compiled engine's states, or None for an engine without interned places (the
    reference interpreter, another back end)."""
    if getattr(engine, "reference", True) is not False or not hasattr(engine, "store"):
        return None
    return StateTransfer(engine)


class StateTransfer:
    """Exports and imports the states and binding elements of one compiled engine (see the module)."""

    def __init__(self, engine):
        self.engine = engine
        self._places = engine.store
        n = len(engine.places)
        self.n_places = n
        self.timed = bool(engine.is_timed)
        self._keys: list[list] = [[] for _ in range(n)]  # place -> id -> canonical key
        self._hashes: list[list[int]] = [[] for _ in range(n)]  # place -> id -> stable 63-bit hash

    def _extend(self, p: int, upto: int) -> None:
        dicts = self._places.dicts[p]
        keys, hashes = self._keys[p], self._hashes[p]
        for i in range(len(keys), upto + 1):
            key = canonical_key(dicts[i])
            keys.append(key)
            text = repr(key) if type(key) is tuple else repr(sorted(map(repr, key)))
            hashes.append(int.from_bytes(hashlib.blake2b(text.encode(), digest_size=8).digest(), "little") >> 1)

    def _ensure(self, s: tuple) -> None:
        for p in range(self.n_places):
            if s[p] >= len(self._keys[p]):
                self._extend(p, s[p])

    def export_state(self, s: tuple) -> tuple:
        """The state as one canonical key per place (and the clock of a timed net)."""
        try:
            out = tuple(map(getitem, self._keys, s))  # map stops at the places: the clock is not an id
        except IndexError:
            self._ensure(s)
            out = tuple(map(getitem, self._keys, s))
        return out + (s[-1],) if self.timed else out

    def stable_hash(self, s: tuple) -> int:
        """A hash of the state equal in every process and engine of the net (not salted)."""
        try:
            hs = tuple(map(getitem, self._hashes, s))
        except IndexError:
            self._ensure(s)
            hs = tuple(map(getitem, self._hashes, s))
        return hash((hs, s[-1])) if self.timed else hash(hs)

    def import_state(self, c: tuple) -> tuple:
        """This engine's state for an exported one (its place markings interned when new)."""
        places = self._places
        index = places.index
        ids = []
        for p in range(self.n_places):
            key = c[p]
            i = index[p].get(key)
            if i is None:
                d = dict(key) if type(key) is frozenset else dict(zip(key[0::2], key[1::2]))
                i = places.intern(p, d)
            ids.append(i)
        if self.timed:
            ids.append(c[-1])
        return tuple(ids)

    def place_count(self, p: int) -> int:
        """How many markings of place p this engine has interned (their ids are 0..count-1)."""
        return len(self._places.dicts[p])

    def place_keys(self, p: int, start: int = 0, stop: int | None = None) -> list:
        """The canonical keys of place p's markings with ids start..stop-1 (stop: all of them)."""
        stop = self.place_count(p) if stop is None else stop
        if stop > len(self._keys[p]):
            self._extend(p, stop - 1)
        return self._keys[p][start:stop]

    def import_place_keys(self, p: int, keys) -> list[int]:
        """This engine's ids of place p's markings given by their canonical keys (interned when new)."""
        places = self._places
        places.index_pending(p)
        get = places.index[p].get
        out = []
        for key in keys:
            i = get(key)
            if i is None:
                i = places.intern(p, dict(key) if type(key) is frozenset else dict(zip(key[0::2], key[1::2])))
            out.append(i)
        return out

    def export_binding_elements(self, start: int = 0) -> list:
        """The binding elements from id `start` on, each as (transition, values of its variables)."""
        return list(self.engine._be[start:])

    def import_binding_element(self, key) -> int:
        """This engine's id of an exported binding element."""
        t, vals = key
        return self.engine._intern_be(t, tuple(vals))


__all__ = ["StateTransfer", "transfer_for"]
