"""Module instances permuted with a symmetric colour set: the instance families of a symmetry and their check.

A module whose parameter has a colour set declared symmetric (`module Slave(me : SL)` with `symmetry SL =
permutations;`) is a *family* when it has exactly one instance per value of the colour set, all declared on
the same page with the same socket bindings: a renaming g of the values then maps instance `me = v`, its
place and transition instances and those of the modules it instantiates, onto instance `me = g(v)`, as
process symmetry indexes processes by a scalar set (Ip and Dill's scalarsets in Murphi; Jensen, "Coloured
Petri Nets", vol. 2, ch. 3: a symmetry specification is a group acting on the colours, and the page
instance of a process is named by a colour). The group of the colour set acts on a state by moving place
markings between the instances and renaming the values inside the tokens.

`instance_families` finds the families and refuses (E0602, at the instance declaration) what breaks the
action: a module with instances for some values only, or twice for one, instances declared on different
pages, bound to different sockets, sharing a fusion place, or whose other parameters are not the renamed
ones. What the inscriptions do with the parameter is checked by `cpn.net.symmetry` (the parameter is
then allowed like a variable of the colour set); the initial markings by value (`moved_initial_problems`).
Imports `cpn.net` and layer 0.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from cpn.diagnostics import Diagnostic
from cpn.net.scalars import CODE, root, value_mapper


@dataclass
class Family:
    """The instances of one module, one per value of symmetric scalar number `scalar`.

    `places[v]` and `transitions[v]` are the place and transition instances of the instance with parameter
    v and of the instances below it, aligned (position i of every value is the same place of the same page);
    only places that belong to the instance are listed (a port bound to a shared socket is not moved).
    """

    scalar: int
    module: str
    param: str
    roots: dict  # value -> page instance index
    places: dict = field(default_factory=dict)  # value -> tuple of place indices
    transitions: dict = field(default_factory=dict)  # value -> tuple of transition indices
    pages: frozenset = frozenset()  # the pages of the instances (the module and those below it)


def _identity_param(net, page: str, ids: dict):
    """(scalar number, param symbol) of the first parameter of `page` whose colour set is a symmetric scalar."""
    info = net.checked.modules.get(page) if net.checked is not None else None
    if info is None:
        return None
    for p in info.params:
        cs = net.colsets.get(p.data) if isinstance(p.data, str) else None
        if cs is not None and id(root(cs)) in ids:
            return ids[id(root(cs))], p
    return None


def _subtree(net, i: int) -> list[int]:
    out, stack = [], [i]
    while stack:
        j = stack.pop()
        out.append(j)
        stack.extend(reversed(net.instances[j].children))
    return out


def instance_families(net, scalars, values) -> tuple[list[Family], list[Diagnostic]]:
    """The families of the symmetric scalars `scalars` (their values `values`), and what stops a module
    with a parameter of one of them from being a family."""
    if not getattr(net, "instances", None) or net.checked is None:
        return [], []
    ids = {id(root(net.colsets[s.name])): k for k, s in enumerate(scalars)}
    problems: list[Diagnostic] = []
    inside: set[int] = set()  # page instances below a family's root
    groups: dict[tuple, list[tuple]] = {}  # (scalar, module) -> [(value, page instance, param name)]
    for pi in net.instances:
        if pi.parent is None or pi.index in inside:
            continue
        ident = _identity_param(net, pi.page, ids)
        if ident is None:
            continue
        k, psym = ident
        groups.setdefault((k, pi.page), []).append((pi.params.get(psym.uid), pi.index, psym.name))
        inside.update(_subtree(net, pi.index)[1:])
    creator = {(pi.page, pi.number): pi.index for pi in net.instances}
    families = []
    for (k, module), members in groups.items():
        s = scalars[k]
        fam, why = _family(net, k, module, members, values[k], creator, _formatter(net.colsets[s.name]))
        if why is not None:
            decl = net.instances[why[0]].decl
            problems.append(Diagnostic(
                CODE, f"{why[1]}, so {'rotating' if s.kind == 'rotations' else 'permuting'} the values of colour "
                f"set '{s.name}' does not map the instances of module '{module}' onto each other",
                None if decl is None else decl.span, hint=why[2],
                params={"colour_set": s.name, "kind": s.kind, "module": module}))
            continue
        families.append(fam)
    return families, problems


def _formatter(cs):
    def fmt(v):
        try:
            return cs.format(v)
        except Exception:  # noqa: BLE001 - a value outside the colour set may not format
            return repr(v)
    return fmt


def _family(net, k, module, members, vals, creator, fmt):
    """(the Family, None) or (None, (page instance to blame, what, hint))."""
    by_value: dict = {}
    for v, i, pname in members:
        if v in by_value:
            return None, (i, f"two instances of module '{module}' have {pname} = {fmt(v)}",
                          "Give every instance its own value of the parameter.")
        by_value[v] = i
    missing = [v for v in vals if v not in by_value]
    if missing:
        return None, (members[0][1], f"module '{module}' has no instance with {members[0][2]} = "
                      f"{', '.join(map(fmt, missing[:4]))}{' ...' if len(missing) > 4 else ''}",
                      f"Declare one instance of '{module}' per value of the parameter's colour set, or leave "
                      "the colour set out of the symmetry.")
    parents = {net.instances[i].parent for i in by_value.values()}
    if len(parents) > 1:
        return None, (members[-1][1], f"the instances of module '{module}' are declared on different pages",
                      "Declare all of them on one page.")
    trees = {v: _subtree(net, i) for v, i in by_value.items()}
    v0 = vals[0]
    shape = [net.instances[j].page for j in trees[v0]]
    fam = Family(k, module, members[0][2], dict(by_value), pages=frozenset(shape))
    for v in vals:
        tree = trees[v]
        if [net.instances[j].page for j in tree] != shape:
            return None, (by_value[v], "its instances do not instantiate the same modules", "")
        own, own0 = set(tree), set(trees[v0])
        places, trans = [], []
        for j, j0 in zip(tree, trees[v0]):
            pi, pi0 = net.instances[j], net.instances[j0]
            for name, p in pi.places.items():
                place = net.places[p]
                owned = creator.get((place.page, place.instance)) in own
                p0 = pi0.places[name]
                owned0 = creator.get((net.places[p0].page, net.places[p0].instance)) in own0
                if owned != owned0 or (not owned and p != p0):
                    what = (f"place '{name}' of instance '{net.instances[by_value[v]].decl.name}' is "
                            f"{'its own' if owned else place.name}, that of instance "
                            f"'{net.instances[by_value[v0]].decl.name}' is "
                            f"{'its own' if owned0 else net.places[p0].name}")
                    return None, (by_value[v], what, "Bind the ports of every instance to the same sockets, and "
                                  "use no fusion set across the instances.")
                if owned:
                    places.append(p)
            trans.extend(pi.transitions.values())
        fam.places[v] = tuple(places)
        fam.transitions[v] = tuple(trans)
    return fam, None


def place_images(families, images, n: int) -> list[int] | None:
    """σ: place index -> the index of its image under the renaming `images` (None: no place moves)."""
    sigma = None
    for f in families:
        g = images[f.scalar]
        if g is None:
            continue
        for v, ps in f.places.items():
            w = g[v]
            if w == v:
                continue
            if sigma is None:
                sigma = list(range(n))
            for p, q in zip(ps, f.places[w]):
                sigma[p] = q
    return sigma


def transition_images(families, images, n: int) -> list[int]:
    """The transition instances' images under the renaming `images`."""
    tau = list(range(n))
    for f in families:
        g = images[f.scalar]
        for v, ts in f.transitions.items():
            for t, u in zip(ts, f.transitions[g[v]]):
                tau[t] = u
    return tau


def parameter_problems(net, scalars, families, generators) -> list[Diagnostic]:
    """A diagnostic per family whose instances' parameters are not the renamed ones (`Sub(next = ...)` not
    following the renaming, another parameter that differs between instances)."""
    ids = {id(root(net.colsets[s.name])): k for k, s in enumerate(scalars)}
    out = []
    checked = net.checked
    for f in families:
        done = False
        for images in generators:
            image = lambda k, x, images=images: images[k][x]  # noqa: E731
            for v, r in f.roots.items():
                w = images[f.scalar][v]
                for j, jw in zip(_subtree(net, r), _subtree(net, f.roots[w])):
                    a, b = net.instances[j], net.instances[jw]
                    info = checked.modules.get(a.page)
                    for psym in info.params if info is not None else ():
                        cs = net.colsets.get(psym.data) if isinstance(psym.data, str) else None
                        m = None if cs is None else value_mapper(cs, ids)
                        x = a.params.get(psym.uid)
                        if (x if m is None else m(x, image)) != b.params.get(psym.uid):
                            decl = b.decl if b.decl is not None else net.instances[f.roots[w]].decl
                            out.append(Diagnostic(
                                CODE, f"parameter '{psym.name}' of instance '{b.decl.name if b.decl else b.page}' "
                                f"is {b.params.get(psym.uid)!r}, not the image of {x!r} (instance "
                                f"'{a.decl.name if a.decl else a.page}'), so the instances of module '{f.module}' "
                                "are not interchangeable", None if decl is None else decl.span,
                                hint="Give the instances the same values for their other parameters (or values "
                                "that follow the renaming of the symmetric colour set).",
                                params={"colour_set": scalars[f.scalar].name, "module": f.module}))
                            done = True
                            break
                    if done:
                        break
                if done:
                    break
            if done:
                break
    return out


def moved_initial_problems(net, scalars, families, generators) -> list[Diagnostic]:
    """A diagnostic per place whose initial marking, renamed by a generator, is not the initial marking
    of its image place (a place of a family's instance is compared with the same place of the instance
    it is mapped to)."""
    ids = {id(root(net.colsets[s.name])): k for k, s in enumerate(scalars)}
    out = []
    reported = set()
    for images in generators:
        sigma = place_images(families, images, len(net.places)) or list(range(len(net.places)))
        image = lambda k, x, images=images: images[k][x]  # noqa: E731
        for p in net.places:
            m = value_mapper(p.colour_set, ids)
            q = net.places[sigma[p.index]]
            if (m is None and q is p) or p.index in reported:
                continue
            moved: dict = {}
            for key, c in p.initial.items():
                nk = key if m is None else (m(key[0], image), key[1]) if p.timed else m(key, image)
                moved[nk] = moved.get(nk, 0) + c
            if moved != q.initial:
                k = next((k for k, g in enumerate(images) if any(a != b for a, b in g.items())), 0)
                s = scalars[k]
                reported.add(p.index)
                what = (f"the initial marking of place '{p.name}' tells the values of colour set '{s.name}' apart"
                        if q is p else f"the initial marking of place '{q.name}' is not that of '{p.name}' renamed")
                out.append(Diagnostic(
                    CODE, f"{what}, so {'rotating' if s.kind == 'rotations' else 'permuting'} them is not a "
                    "symmetry of the net", p.span, hint=f"Give every value of '{s.name}' (and every instance "
                    "named by one) the same tokens, renamed, or leave the colour set out of the symmetry.",
                    params={"colour_set": s.name, "kind": s.kind, "place": p.name}))
    return out


def moved_places(families) -> set[int]:
    """The place instances that the families move."""
    return {p for f in families for ps in f.places.values() for p in ps}


__all__ = ["Family", "instance_families", "moved_initial_problems", "moved_places", "parameter_problems",
           "place_images", "transition_images"]
