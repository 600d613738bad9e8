"""States and binding elements in a form that every engine of the same net understands.

An engine's state is a tuple of intern ids, one per place, and a binding element is an id too: both are
numbered in the order the engine met them, so two engines of one net (two processes, two machines) give
the same marking different ids. `StateTransfer` turns them into values equal in every engine (a place's
multiset as the sorted, flattened items of `compiled.canonical_key`; a binding element as its transition
and the values of its variables) and back, and gives each state a hash that is the same in every process
(Python's `hash()` of a string is salted per process; the hash of a tuple of ints is not).

Used by the partitioned search (`cpn.statespace.parallel`) to send states between processes.

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

    def export_state(self, s: tuple) -> tuple:
        """The state as one canonical key per place (and the clock of a timed net)."""
        out = []
        for p in range(self.n_places):
            keys = self._keys[p]
            i = s[p]
            if i >= len(keys):
                self._extend(p, i)
            out.append(keys[i])
        if self.timed:
            out.append(s[-1])
        return tuple(out)

    def stable_hash(self, s: tuple) -> int:
        """A hash of the state equal in every process and engine of the net (not salted)."""
        hs = []
        for p in range(self.n_places):
            h = self._hashes[p]
            i = s[p]
            if i >= len(h):
                self._extend(p, i)
            hs.append(h[i])
        if self.timed:
            hs.append(s[-1])
        return hash(tuple(hs))

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

    def export_binding_elements(self, start: int = 0) -> list:
        """The binding elements from id `start` on, each as (transition, values of its variables)."""
        return list(self.engine._be[start:])

    def import_binding_element(self, key) -> int:
        """This engine's id of an exported binding element."""
        t, vals = key
        return self.engine._intern_be(t, tuple(vals))


__all__ = ["StateTransfer", "transfer_for"]
