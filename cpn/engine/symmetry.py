"""Symmetry reduction: a group of colour permutations acting on states, and canonical representatives.

A symmetry specification names *scalar* colour sets (enumerations and index colour sets) and, for each,
its group: all permutations of its values, or the rotations of its values in their declared order (for
cyclic colour sets, whose successor wraps around). The group G is the product of these groups; g in G acts
on a value of any colour set by renaming the scalar values inside it (products, records, lists and unions
included), on a marking token by token, and on a state place by place (the clock is unchanged). That G
really is a symmetry of the net, so that g maps the enabled binding elements of a marking onto those of its
image, is checked before it is used (`cpn.net.symmetry`).

`Canonicaliser.canonical(state) -> (representative, stabiliser size)` gives an exact canonical form: the
smallest state of the orbit under a fixed total order. That order compares first the *signatures* of the
values of the permuted colour sets (what the tokens holding a value look like when that value and every
other scalar value are blanked out: a property invariant under G), value by value, then the place markings
(their sorted tokens). The minimum is therefore reached only by relabellings that sort the values by
signature, so only those are enumerated (with every rotation of the rotated colour sets); values that a
transposition leaves the state unchanged under (*twins*) are never permuted among themselves, their
orders giving the same state. The number of relabellings reaching the minimum, times the twins'
permutations, is the size of the state's stabiliser, so the orbit has |G| / |stabiliser| states (the
full state space's count is the sum over the representatives; Jensen, "Coloured Petri Nets", vol. 2,
ch. 3 on symmetry specifications and the occurrence graph with symmetries; Ip and Dill's scalarsets in
Murphi for the canonical form by sorting).

Examples
--------
>>> import cpn
>>> m = cpn.loads("colset P = with a | b | c; var x : P; place Idle : P = P.all(); place Busy : P;"
...               " trans go; arc Idle -> go : x; arc go -> Busy : x;")
>>> e = m.engine()
>>> c = Canonicaliser(e, [Scalar("P", "permutations")])
>>> reps = {c.canonical(t)[0] for _, t in e.successors(e.initial_state())}
>>> len(reps), c.group_order, c.canonical(next(iter(reps)))[1]
(1, 6, 2)
"""

from __future__ import annotations

import math
from itertools import permutations

from cpn.net.scalars import (
    KINDS,
    PERMUTATIONS,
    ROTATIONS,
    Scalar,
    generators,
    root,
    scalar_values,
    value_mapper,
)


def _total(v):
    """A sort key ordering values of mixed types (a union's constants and values with data)."""
    if isinstance(v, tuple):
        return (3, tuple(_total(x) for x in v))
    if isinstance(v, bool):
        return (0, int(v))
    if isinstance(v, (int, float)):
        return (1, v)
    return (2, str(v))


def sorted_items(d: dict) -> tuple:
    """A multiset's (token, count) pairs in a fixed order: its key in the order of states."""
    try:
        return tuple(sorted(d.items()))
    except TypeError:
        return tuple(sorted(d.items(), key=_total))


class Canonicaliser:
    """Canonical representatives of an engine's states under the group of a symmetry specification.

    Parameters
    ----------
    engine : a compiled or reference engine (`cpn.engine.compile_net`).
    scalars : the symmetric colour sets (`Scalar`), checked beforehand by `cpn.net.symmetry`.
    """

    def __init__(self, engine, scalars: list[Scalar]):
        self.engine = engine
        self.scalars = list(scalars)
        net = engine.net
        self.values: list[list] = []
        ids: dict = {}
        for k, s in enumerate(self.scalars):
            cs = net.colsets[s.name]
            vals = scalar_values(cs)
            if vals is None:
                raise ValueError(f"colour set '{s.name}' is not an enumeration or an index colour set")
            self.values.append(vals)
            ids[id(root(cs))] = k
        self.position = [{v: i for i, v in enumerate(vals)} for vals in self.values]
        self.group_order = 1
        for s, vals in zip(self.scalars, self.values):
            self.group_order *= math.factorial(len(vals)) if s.kind == PERMUTATIONS else len(vals)
        n = len(engine.places)
        self.n_places = n
        self.mappers: list = []
        for p in engine.places:
            m = value_mapper(net.places[len(self.mappers)].colour_set, ids)
            if m is not None and p.timed:
                m = (lambda mm: lambda key, image: (mm(key[0], image), key[1]))(m)
            self.mappers.append(m)
        # module instances permuted with the values (`cpn.net.instance_symmetry`): a place of instance v is
        # moved to the same place of instance g(v)
        from cpn.net.symmetry import families_of

        self.families = families_of(net, self.scalars)[0]
        self.owner: dict[int, tuple] = {}  # moved place -> (scalar, the value naming its instance, position)
        self._owned: dict[tuple, list] = {}  # (scalar, value) -> the places of its instances, aligned
        for f in self.families:
            for v, ps in f.places.items():
                self._owned.setdefault((f.scalar, v), []).extend(ps)
                for j, p in enumerate(ps):
                    self.owner[p] = (f.scalar, v, (f.module, j))
        self._held: dict[tuple, set] = {}  # (scalar, value) -> places holding it, in the last signed state
        self.sym_places = [p for p in range(n) if self.mappers[p] is not None or p in self.owner]
        self.permuted = [k for k, s in enumerate(self.scalars) if s.kind == PERMUTATIONS]
        self.rotated = [k for k, s in enumerate(self.scalars) if s.kind == ROTATIONS]
        self.reference = bool(getattr(engine, "reference", False))
        if not self.reference:
            self._dicts = engine.store.dicts
            self._intern = engine.store.intern
        self.canonicalised = 0
        self.relabellings = 0
        self._keys: list[dict] = [{} for _ in range(n)]  # place -> marking -> its sorted tokens
        self._images: list[dict] = [{} for _ in range(n)]  # place -> (rotation, marking) -> image
        self._rotations_of = []
        for k in self.rotated:
            vals = self.values[k]
            self._rotations_of.append([{v: vals[(i + r) % len(vals)] for i, v in enumerate(vals)}
                                       for r in range(len(vals))])
        ident = [{v: v for v in vals} for vals in self.values]
        self._rotations = [ident]
        for j, k in enumerate(self.rotated):
            self._rotations = [c[:k] + [g] + c[k + 1:] for c in self._rotations for g in self._rotations_of[j]]
        self._sigmas = [self.sigma(c) for c in self._rotations]

    # ------------------------------------------------------------------ places
    def _dict(self, state, p: int) -> dict:
        return dict(state[p]) if self.reference else self._dicts[p][state[p]]

    def _make(self, p: int, d: dict):
        return frozenset(d.items()) if self.reference else self._intern(p, d)

    # ------------------------------------------------------------------ the action of G
    def sigma(self, images: list[dict]) -> list[int] | None:
        """The places' images under the renaming `images` (None when no module instance moves)."""
        if not self.families:
            return None
        from cpn.net.instance_symmetry import place_images

        return place_images(self.families, images, self.n_places)

    def apply(self, state, images: list[dict]):
        """The image of `state` under the renaming `images` (one dict value -> value per scalar): the
        values renamed in every token, the markings of the module instances moved to their images."""
        image = lambda k, x: images[k][x]  # noqa: E731
        sigma = self.sigma(images)
        out = list(state)
        for p in self.sym_places:
            q = p if sigma is None else sigma[p]
            m = self.mappers[p]
            if m is None:
                if q != p:
                    out[q] = state[p] if self.reference else self._make(q, self._dict(state, p))
                continue
            d = self._dict(state, p)
            if d:
                nd: dict = {}
                for key, c in d.items():
                    nk = m(key, image)
                    nd[nk] = nd.get(nk, 0) + c
                out[q] = self._make(q, nd)
            elif q != p:
                out[q] = state[p] if self.reference else self._make(q, d)
        return tuple(out)

    def generators(self) -> list[list[dict]]:
        """Renamings generating G (`cpn.net.symmetry.generators`)."""
        return generators(self.scalars, self.values)

    def group(self):
        """Every renaming of G (|G| of them: for tests and small groups)."""
        per = []
        for s, vals in zip(self.scalars, self.values):
            if s.kind == PERMUTATIONS:
                per.append([dict(zip(vals, perm)) for perm in permutations(vals)])
            else:
                n = len(vals)
                per.append([{v: vals[(i + r) % n] for i, v in enumerate(vals)} for r in range(n)])

        def rec(k):
            if k == len(per):
                yield []
                return
            for g in per[k]:
                for rest in rec(k + 1):
                    yield [g] + rest
        return rec(0)

    # ------------------------------------------------------------------ canonical form
    def signatures(self, state) -> list[dict]:
        """Per permuted scalar k: value -> its signature, the sorted (place, blanked token, count) of the
        tokens holding it, every scalar value blanked (-1 for this one, -2 for the others)."""
        sig = [dict() if k in self.permuted else None for k in range(len(self.scalars))]
        for k in self.permuted:
            for v in self.values[k]:
                sig[k][v] = []
        owner = self.owner
        held_at = self._held = {} if self.families else None  # only `_swaps_moved` reads it
        for p in self.sym_places:
            d = self._dict(state, p)
            if not d:
                continue
            m = self.mappers[p]
            own = owner.get(p)
            for key, c in d.items():
                held: list = []
                if m is not None:
                    m(key, lambda k, x, held=held: held.append((k, x)) or x)
                if own is not None:
                    held.append(own[:2])
                seen = set()
                for k, x in held:
                    if sig[k] is None or (k, x) in seen:
                        continue
                    seen.add((k, x))
                    if held_at is not None:
                        held_at.setdefault((k, x), set()).add(p)
                    blank = key if m is None else m(key, lambda k2, y, k=k, x=x: -1 if (k2 == k and y == x) else -2)
                    # a moved place is named by its position in the module and whether its instance is x's
                    where = (0, p) if own is None else (1, own[2], -1 if own[:2] == (k, x) else -2)
                    sig[k][x].append((where, blank, c))
        for k in self.permuted:
            for v, items in sig[k].items():
                try:
                    items.sort()
                except TypeError:
                    items.sort(key=_total)
                sig[k][v] = tuple(items)
        return sig

    def _key(self, state) -> tuple:
        return tuple(self._place_key(p, state[p]) for p in self.sym_places)

    def _relabellings(self, state):
        """(per permuted scalar: the renamings to try, the product of its twin classes' factorials)."""
        sig = self.signatures(state)
        options = {}
        twins_factor = 1
        for k in self.permuted:
            vals = self.values[k]
            s = sig[k]
            try:
                order = sorted(vals, key=lambda v: s[v])
            except TypeError:
                order = sorted(vals, key=lambda v: _total(s[v]))
            # classes of equal signature, in signature order; inside, classes of twins
            classes: list[list[list]] = []
            prev = object()
            for v in order:
                if not classes or s[v] != prev:
                    classes.append([])
                    prev = s[v]
                cls = classes[-1]
                for twins in cls:
                    if self._swaps_to_itself(state, k, twins[0], v, s[v]):
                        twins.append(v)
                        break
                else:
                    cls.append([v])
            for cls in classes:
                for twins in cls:
                    twins_factor *= math.factorial(len(twins))
            options[k] = self._label_choices(classes, vals)
        return options, twins_factor

    def _swaps_to_itself(self, state, k: int, a, b, signature) -> bool:
        """Whether exchanging values a and b of scalar k leaves the state unchanged. Only the places
        holding b (its signature names them; a's is the same) can change; their multisets are compared
        without interning the exchanged ones."""
        sw: list = [_Identity()] * len(self.scalars)
        sw[k] = _Swap(a, b)
        if self.families:
            return self._swaps_moved(state, k, a, b, sw)
        image = lambda j, x: sw[j][x]  # noqa: E731
        for p in {where[1] for where, _blank, _c in signature}:
            d = self._dict(state, p)
            m = self.mappers[p]
            nd: dict = {}
            for key, c in d.items():
                nk = m(key, image)
                nd[nk] = nd.get(nk, 0) + c
            if nd != d:
                return False
        return True

    def _swaps_moved(self, state, k: int, a, b, sw) -> bool:
        """`_swaps_to_itself` when module instances move: only the places holding a or b (recorded by
        `signatures` for this state) and those of their instances can change; each one's image under the
        exchange is compared with the marking of the place it moves to."""
        oa, ob = self._owned.get((k, a), ()), self._owned.get((k, b), ())
        target = dict(zip(oa, ob))
        target.update(zip(ob, oa))
        image = lambda j, x: sw[j][x]  # noqa: E731
        held = self._held
        for p in held.get((k, a), set()) | held.get((k, b), set()) | set(target):
            q = target.get(p, p)
            m = self.mappers[p]
            d = self._dict(state, p)
            if m is None:
                nd = d
            else:
                nd = {}
                for key, c in d.items():
                    nk = m(key, image)
                    nd[nk] = nd.get(nk, 0) + c
            if nd != (d if q == p else self._dict(state, q)):
                return False
        return True

    @staticmethod
    def _label_choices(classes, vals) -> list[dict]:
        """Every renaming that gives the values of each signature class the class's labels, twins in a
        fixed order (one per arrangement of the twin classes)."""
        per_class = []
        start = 0
        for cls in classes:
            size = sum(len(t) for t in cls)
            labels = vals[start:start + size]
            start += size
            arrangements = []
            for arrangement in _distinct_arrangements([i for i, t in enumerate(cls) for _ in t]):
                counters = [0] * len(cls)
                m = {}
                for label, i in zip(labels, arrangement):
                    m[cls[i][counters[i]]] = label
                    counters[i] += 1
                arrangements.append(m)
            per_class.append(arrangements)
        out = [{}]
        for arrangements in per_class:
            out = [{**a, **b} for a in out for b in arrangements]
        return out

    def canonical(self, state):
        """(the orbit's representative, the size of its stabiliser in G)."""
        self.canonicalised += 1
        if not self.permuted:
            return self._canonical_rotations(state)
        perm_options, factor = self._relabellings(state)
        combos = [list(self._rotations[0])] if self.rotated else [[None] * len(self.scalars)]
        for j, k in enumerate(self.rotated):
            combos = [c[:k] + [g] + c[k + 1:] for c in combos for g in self._rotations_of[j]]
        for k in self.permuted:
            combos = [c[:k] + [g] + c[k + 1:] for c in combos for g in perm_options[k]]
        best = best_key = None
        ties = 0
        for images in combos:
            self.relabellings += 1
            t = self.apply(state, images)
            key = self._key(t)
            if best_key is None or key < best_key:
                best, best_key, ties = t, key, 1
            elif key == best_key:
                ties += 1
        return best, ties * factor

    def _canonical_rotations(self, state):
        """`canonical` for a group of rotations only: the renamings are fixed, so the image of each place
        marking under each of them is remembered (a place marking recurs in many states)."""
        places = self.sym_places
        images = self._images
        place_key = self._place_key
        best = best_key = None
        ties = 0
        for ci, combo in enumerate(self._rotations):
            self.relabellings += 1
            sigma = self._sigmas[ci]
            if sigma is None:
                row = []
                for p in places:
                    x = state[p]
                    memo = images[p]
                    y = memo.get((ci, x))
                    if y is None:
                        y = memo[(ci, x)] = self._image(p, x, combo)
                    row.append(y)
            else:
                moved = {}
                for p in places:
                    x = state[p]
                    memo = images[p]
                    y = memo.get((ci, x))
                    if y is None:
                        y = memo[(ci, x)] = self._image(p, x, combo, sigma[p])
                    moved[sigma[p]] = y
                row = [moved[p] for p in places]
            key = tuple(place_key(p, y) for p, y in zip(places, row))
            if best_key is None or key < best_key:
                best, best_key, ties = row, key, 1
            elif key == best_key:
                ties += 1
        out = list(state)
        for p, y in zip(places, best):
            out[p] = y
        return tuple(out), ties

    def _image(self, p: int, x, images, q: int | None = None):
        """The image of place p's marking `x` (an id, or a frozenset for the reference engine), as a
        marking of place q (p unless a module instance moves it)."""
        d = dict(x) if self.reference else self._dicts[p][x]
        q = p if q is None else q
        m = self.mappers[p]
        if m is None or not d:
            return x if q == p or self.reference else self._make(q, d)
        image = lambda k, v: images[k][v]  # noqa: E731
        nd: dict = {}
        for key, c in d.items():
            nk = m(key, image)
            nd[nk] = nd.get(nk, 0) + c
        return self._make(q, nd)

    def _place_key(self, p: int, x) -> tuple:
        memo = self._keys[p]
        k = memo.get(x)
        if k is None:
            k = memo[x] = sorted_items(dict(x) if self.reference else self._dicts[p][x])
        return k


class _Identity:
    def __getitem__(self, x):
        return x


class _Swap:
    def __init__(self, a, b):
        self.a, self.b = a, b

    def __getitem__(self, x):
        return self.b if x == self.a else self.a if x == self.b else x


def _distinct_arrangements(items: list):
    """The distinct orderings of a list with repeated items (lexicographic, without duplicates)."""
    items = sorted(items)
    n = len(items)
    yield tuple(items)
    while True:
        i = n - 2
        while i >= 0 and items[i] >= items[i + 1]:
            i -= 1
        if i < 0:
            return
        j = n - 1
        while items[j] <= items[i]:
            j -= 1
        items[i], items[j] = items[j], items[i]
        items[i + 1:] = reversed(items[i + 1:])
        yield tuple(items)


__all__ = ["KINDS", "PERMUTATIONS", "ROTATIONS", "Canonicaliser", "Scalar", "root", "scalar_values",
           "sorted_items", "value_mapper"]
