"""The scalar colour sets a symmetry reduction permutes, and how a renaming of their values acts on values.

A `Scalar` names an enumeration or index colour set and the group acting on it (all permutations, or the
rotations); `generators` lists the renamings that generate that group; `value_mapper` lifts a renaming of
the scalars' values to the values of any colour set built from them (products, records, unions, lists).
Whether the net's behaviour is invariant under them is `cpn.net.symmetry`'s check.
"""

from __future__ import annotations

from dataclasses import dataclass

from cpn.values import colours as C

PERMUTATIONS: str = "permutations"
ROTATIONS: str = "rotations"
KINDS: tuple = (PERMUTATIONS, ROTATIONS)


@dataclass(frozen=True)
class Scalar:
    """One symmetric colour set: its name and its group ('permutations' or 'rotations')."""

    name: str
    kind: str = PERMUTATIONS

    def __str__(self) -> str:
        return self.name if self.kind == PERMUTATIONS else f"{self.name}:{self.kind}"



def parse_scalars(text: str) -> list[Scalar]:
    """`PH,Ring:rotations` -> [Scalar('PH'), Scalar('Ring', 'rotations')]; ValueError on a bad kind."""
    out = []
    for part in text.split(","):
        part = part.strip()
        if not part:
            continue
        name, _, kind = part.partition(":")
        kind = kind.strip() or PERMUTATIONS
        if kind not in KINDS:
            raise ValueError(f"'{kind}' is not a kind of symmetry (known: {', '.join(KINDS)})")
        out.append(Scalar(name.strip(), kind))
    return out


def generators(scalars, values) -> list[list[dict]]:
    """Renamings generating the group: per scalar (its values in `values`), a full cycle and, for all
    permutations, a transposition (together they generate the symmetric group); the others fixed."""
    ident = [{v: v for v in vals} for vals in values]
    out = []
    for k, (s, vals) in enumerate(zip(scalars, values)):
        if len(vals) < 2:
            continue
        cyc = {v: vals[(i + 1) % len(vals)] for i, v in enumerate(vals)}
        gens = [cyc]
        if s.kind == PERMUTATIONS and len(vals) > 2:
            sw = dict(ident[k])
            sw[vals[0]], sw[vals[1]] = vals[1], vals[0]
            gens.append(sw)
        for g in gens:
            images = list(ident)
            images[k] = g
            out.append(images)
    return out


def _tuple_mapper(maps: list, direct: list):
    """The mapper of a tuple whose component i has mapper maps[i] (None: unchanged); `direct[i]` is the
    scalar's number when the component is a scalar itself (its value is renamed in place, one call less:
    this is the explorer's innermost loop under symmetry reduction)."""
    moved = [i for i, m in enumerate(maps) if m is not None]
    if len(maps) == 2 and moved == [0] and direct[0] is not None:
        k = direct[0]
        return lambda v, image: (image(k, v[0]), v[1])
    if len(maps) == 2 and moved == [1] and direct[1] is not None:
        k = direct[1]
        return lambda v, image: (v[0], image(k, v[1]))
    if len(maps) == 3 and moved == [0] and direct[0] is not None:
        k = direct[0]
        return lambda v, image: (image(k, v[0]), v[1], v[2])
    pairs = [(i, maps[i]) for i in moved]

    def f(v, image):
        out = list(v)
        for i, m in pairs:
            out[i] = m(out[i], image)
        return tuple(out)
    return f


CODE: str = "E0602"


def root(cs):
    """The colour set an alias names (`colset B = A;` is A)."""
    while isinstance(cs, C.AliasCS):
        cs = cs.base
    return cs


def scalar_values(cs) -> list | None:
    """The values of a scalar colour set in their declared order, None if it is not one."""
    cs = root(cs)
    if isinstance(cs, (C.EnumCS, C.IndexCS)):
        return cs.values()
    return None


def value_mapper(cs, scalars: dict):
    """`f(v, image) -> v'` renaming the scalar values inside a value of colour set `cs`, where
    `image(k, x)` is the new name of value x of scalar k; `scalars` maps each scalar colour set object (its
    root) to k. None when `cs` holds no scalar value. A subset of a scalar colour set raises ValueError
    (a renaming can leave it)."""
    cs0 = root(cs)
    k = scalars.get(id(cs0))
    if k is not None:
        return lambda v, image: image(k, v)
    if isinstance(cs0, C.SubsetCS):
        if value_mapper(cs0.base, scalars) is not None:
            raise ValueError(cs0.name)
        return None
    if isinstance(cs0, (C.ProductCS, C.RecordCS)):
        comps = cs0.components if isinstance(cs0, C.ProductCS) else [c for _, c in cs0.fields]
        maps = [value_mapper(c, scalars) for c in comps]
        if all(m is None for m in maps):
            return None
        return _tuple_mapper(maps, [scalars.get(id(root(c))) for c in comps])
    if isinstance(cs0, C.ListCS):
        m = value_mapper(cs0.elem, scalars)
        if m is None:
            return None
        return lambda v, image: tuple(m(x, image) for x in v)
    if isinstance(cs0, C.UnionCS):
        maps = [None if c is None else value_mapper(c, scalars) for _, c in cs0.constructors]
        if all(m is None for m in maps):
            return None
        return lambda v, image: v if type(v) is int or maps[v[0]] is None else (v[0], maps[v[0]](v[1], image))
    return None


__all__ = ["CODE", "KINDS", "PERMUTATIONS", "ROTATIONS", "Scalar", "generators", "parse_scalars", "root", "scalar_values",
           "value_mapper"]
