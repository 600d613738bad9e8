"""The static check that a declared symmetry really is a symmetry of the net (`check_symmetry`).

A renaming g of the values of scalar colour sets (enumerations, index colour sets) maps the behaviour of
the net onto itself when no guard, inscription, delay or priority can tell the values apart, and the
initial marking is unchanged by g. Enumeration and index values have their own type in CPN ML, so the only
ways an expression can tell them apart are: a constant of the colour set (`a`, `ph(1)`, in an expression or
a pattern), a global constant or a module parameter whose type holds the colour set, and the colour-set
functions that expose the order (`S.ord`, `S.col`, `S.mkstr`) or a subset of it. Equality, `S.all()`,
`S.size()`, `S.ran()` and the variables themselves are allowed. For rotations, the successor and the
predecessor written as `S.col ((S.ord x + k) mod n)` with n = |S| (as PNML's cyclic enumerations are
translated) are allowed as well: rotations commute with them, other permutations do not.

Every use that breaks the symmetry is reported (`file:line:col: error[E0602]`), in the guards and
inscriptions and in the bodies of the global functions they call. The initial marking is checked by value
(`cpn.engine.symmetry`). Imports `cpn.net`, `cpn.lang.types` (the types of global constants), `cpn.values`
and layer 0.
"""

from __future__ import annotations

import dataclasses

from cpn.diagnostics import Diagnostic
from cpn.expr import nodes as E
from cpn.net.instance_symmetry import instance_families, moved_initial_problems, parameter_problems
from cpn.net.scalars import (
    CODE,
    generators,
    root,
    scalar_values,
    value_mapper,
)
from cpn.values import colours as C

_root = root


#: the colour-set functions that do not tell the values of the colour set apart
SYMMETRIC_CSOPS: frozenset = frozenset({"all", "size", "ran", "legal", "mult"})
#: library functions whose result depends on the order of the values (a multi-set's values listed in order;
#: without the types, every use is refused: the multi-set may hold values of the symmetric colour set)
ORDERED_BUILTINS: frozenset = frozenset({"ms_to_list"})


def _builtin(e, *names) -> bool:
    return isinstance(e, E.Name) and e.ref is not None and e.ref.kind == "builtin" and e.name in names


def _listed_and_gathered(e):
    """(F, M) when `e` is `list_to_ms (List.map F (ms_to_list M))`, whose value does not depend on the
    order `ms_to_list` lists M in; else None."""
    if not (isinstance(e, E.App) and _builtin(e.fn, "list_to_ms")):
        return None
    m = e.arg
    if not (isinstance(m, E.App) and isinstance(m.fn, E.App) and _builtin(m.fn.fn, "List.map", "map")):
        return None
    inner = m.arg
    if isinstance(inner, E.App) and _builtin(inner.fn, "ms_to_list"):
        return m.fn.arg, inner.arg
    return None


class _Checker:
    def __init__(self, net, name: str, kind: str):
        self.net = net
        self.name = name
        self.kind = kind
        self.cs = _root(net.colsets[name])
        # every colour set name that denotes this one (aliases) or a subset of it
        self.names = {n for n, c in net.colsets.items() if _root(c) is self.cs}
        self.subsets = {n for n, c in net.colsets.items()
                        if isinstance(_root(c), C.SubsetCS) and _root(_root(c).base) is self.cs}
        self.size = len(self.cs.values())
        # colour sets whose values hold values of this one (products, records, lists, unions of it)
        self.holding = set()
        for n, c in net.colsets.items():
            try:
                if value_mapper(c, {id(self.cs): 0}) is not None:
                    self.holding.add(n)
            except ValueError:
                self.holding.add(n)
        self.problems: list[Diagnostic] = []
        self.funs = {d.ref.uid: d for d in net.globals.decls if isinstance(d, E.FunDecl)}
        self.seen_funs: set[int] = set()
        self.where = ""
        self.val_types: dict = {}
        self.allowed_params: set = set()  # parameters of the instance families (`cpn.net.instance_symmetry`)
        checked = getattr(net, "checked", None)
        if checked is not None:
            self.val_types = {s.uid: s.type for s in checked.globals.values() if s.kind == "val"}
            for page in [checked.top, *checked.modules.values()]:
                self.val_types.update({s.uid: s.type for s in page.params})

    # ---------------------------------------------------------------- reporting
    def refuse(self, node, what: str, hint: str) -> None:
        self.problems.append(Diagnostic(
            CODE, f"{what} tells the values of colour set '{self.name}' apart, so {self._group()} is not a "
            f"symmetry of the net{self.where}", getattr(node, "span", None), hint=hint,
            params={"colour_set": self.name, "kind": self.kind}))

    def _group(self) -> str:
        return (f"rotating the values of '{self.name}'" if self.kind == "rotations"
                else f"permuting the values of '{self.name}'")

    # ---------------------------------------------------------------- walking
    def expr(self, e) -> None:
        if e is None:
            return
        if isinstance(e, E.App) and self.kind == "rotations" and self._is_rotation(e):
            self.expr(e.arg.left.left.arg)  # the rotated value
            return
        if isinstance(e, E.Name):
            self.name_ref(e)
            return
        inner = _listed_and_gathered(e)
        if inner is not None:  # list_to_ms (List.map F (ms_to_list M)): the order is forgotten again
            fn, ms = inner
            self.expr(fn)
            self.expr(ms)
            return
        for f in dataclasses.fields(e):
            if f.name == "span":
                continue
            self.child(getattr(e, f.name))

    def child(self, v) -> None:
        if isinstance(v, E.Expr):
            self.expr(v)
        elif isinstance(v, E.Pat):
            self.pat(v)
        elif isinstance(v, (list, tuple)):
            for x in v:
                self.child(x)
        elif isinstance(v, E.ValDecl):
            self.pat(v.pat)
            self.expr(v.expr)
        elif isinstance(v, E.FunDecl):
            for c in v.clauses:
                self.child(c.params)
                self.expr(c.body)

    def pat(self, p) -> None:
        if isinstance(p, (E.PVar, E.PCon)) and p.ref.kind == "con" and self._own_con(p.ref):
            self.refuse(p, f"the pattern constant '{p.name}'",
                        "Match with a variable and compare with '=' to another variable instead of naming a "
                        f"value of '{self.name}'.")
        for f in dataclasses.fields(p):
            if f.name in ("span", "ref"):
                continue
            self.child(getattr(p, f.name))

    def _own_con(self, ref) -> bool:
        return isinstance(ref.data, E.Constructor) and ref.data.colset in self.names

    def name_ref(self, e: E.Name) -> None:
        ref = e.ref
        if ref.kind == "con" and self._own_con(ref):
            self.refuse(e, f"the constant '{e.name}'",
                        f"Replace the constant by a variable of '{self.name}' (bound by an arc or "
                        f"'{self.name}.all()'), or leave '{self.name}' out of the symmetry.")
        elif ref.kind == "csop":
            cs, op = ref.data
            if cs in self.subsets:
                self.refuse(e, f"'{e.name}' (a subset of '{self.name}')",
                            f"A subset picks out some values of '{self.name}'; leave '{self.name}' out of the "
                            "symmetry.")
            elif cs in self.names and op not in SYMMETRIC_CSOPS:
                extra = (" Rotations allow the successor and predecessor written as "
                         f"'{cs}.col (({cs}.ord x + k) mod {self.size})'." if self.kind == "rotations" else
                         " If the net only uses successors and predecessors, declare rotations instead.")
                self.refuse(e, f"'{e.name}' (the order of the values)",
                            f"Compare values with '=' and '<>' only.{extra}")
            elif cs in self.holding and op not in SYMMETRIC_CSOPS:
                self.refuse(e, f"'{e.name}' (the order of the values of '{cs}', which hold values of "
                            f"'{self.name}')", "Compare values with '=' and '<>' only.")
        elif ref.kind == "var" and ref.data in self.subsets:
            self.refuse(e, f"the variable '{e.name}' of a subset of '{self.name}'",
                        f"A subset picks out some values of '{self.name}'; leave '{self.name}' out of the "
                        "symmetry.")
        elif ref.kind == "val" and self._type_holds(self.val_types.get(ref.uid)):
            self.refuse(e, f"the constant '{e.name}'",
                        f"A global constant holding values of '{self.name}' names particular values; use "
                        f"'{self.name}.all()' or a variable instead.")
        elif (ref.kind == "param" and ref.uid not in self.allowed_params
              and self._type_holds(self.val_types.get(ref.uid))):
            self.refuse(e, f"the module parameter '{e.name}'",
                        "Module instances given different values of the colour set are told apart; leave "
                        f"'{self.name}' out of the symmetry.")
        elif ref.kind == "builtin" and e.name in ORDERED_BUILTINS:
            self.refuse(e, f"'{e.name}' (it lists a multi-set in the order of its values)",
                        "Keep the multi-set (use 'cf', 'size' or the arc itself), or leave "
                        f"'{self.name}' out of the symmetry.")
        elif ref.kind == "fun" and ref.uid in self.funs and ref.uid not in self.seen_funs:
            self.seen_funs.add(ref.uid)
            outer = self.where
            self.where = f" (in function '{e.name}', called at {e.span})" if e.span else f" (in function '{e.name}')"
            self.child(self.funs[ref.uid])
            self.where = outer

    def _type_holds(self, t) -> bool:
        if t is None:
            return False
        from cpn.lang import types as T

        if isinstance(t, T.Scheme):
            t = t.type
        t = T.prune(t)
        own = {n for n in self.names}
        if isinstance(t, T.TCon):
            return t.name in own or any(self._type_holds(a) for a in t.args)
        if isinstance(t, T.TTuple):
            return any(self._type_holds(a) for a in t.items)
        if isinstance(t, T.TRecord):
            return any(self._type_holds(a) for _, a in t.fields)
        if isinstance(t, T.TFun):
            return self._type_holds(t.arg) or self._type_holds(t.res)
        return False

    def _is_rotation(self, e: E.App) -> bool:
        """`S.col ((S.ord x + k) mod n)` with n = |S| and k an integer constant."""
        fn, arg = e.fn, e.arg
        if not (isinstance(fn, E.Name) and fn.ref.kind == "csop" and fn.ref.data[0] in self.names
                and fn.ref.data[1] == "col"):
            return False
        if not (isinstance(arg, E.BinOp) and arg.op == "mod" and self._int(arg.right) == self.size):
            return False
        s = arg.left
        if not (isinstance(s, E.BinOp) and s.op == "+" and self._int(s.right) is not None):
            return False
        o = s.left
        return (isinstance(o, E.App) and isinstance(o.fn, E.Name) and o.fn.ref.kind == "csop"
                and o.fn.ref.data[0] in self.names and o.fn.ref.data[1] == "ord")

    def _int(self, e):
        if isinstance(e, E.Const) and type(e.value) is int:
            return e.value
        if isinstance(e, E.Name) and e.ref.kind == "val":
            v = self.net.globals.constants.get(e.ref.uid)
            return v if type(v) is int else None
        return None


def check_symmetry(net, scalars) -> list[Diagnostic]:
    """Every use in the net's guards, inscriptions, delays and priorities (and the global functions they
    call) that tells apart the values of a declared symmetric colour set; [] when none does.

    `scalars` are `(name, kind)` pairs (`cpn.engine.symmetry.Scalar`); a name that is not an enumeration or
    an index colour set is reported too.
    """
    out: list[Diagnostic] = []
    bad = False
    for s in scalars:
        name, kind = s.name, s.kind
        cs = net.colsets.get(name)
        if cs is None or not isinstance(_root(cs), (C.EnumCS, C.IndexCS)) or _root(cs).values() is None:
            known = sorted(n for n, c in net.colsets.items() if isinstance(_root(c), (C.EnumCS, C.IndexCS)))
            what = "no colour set of the net" if cs is None else f"a colour set of kind '{_root(cs).kind}'"
            out.append(Diagnostic(
                CODE, f"'{name}' is {what}: only enumerations and index colour sets can be declared symmetric",
                None, hint=("Its enumeration and index colour sets are " + ", ".join(f"'{n}'" for n in known) + "."
                            if known else "The net has no enumeration or index colour set."),
                params={"colour_set": name, "kind": kind}))
            bad = True
    if bad:
        return out
    families, out = families_of(net, scalars)
    if out:
        return out  # instances that cannot be permuted: their parameter's uses would only repeat it
    allowed = _family_params(net, families)
    for s in scalars:
        name, kind = s.name, s.kind
        c = _Checker(net, name, kind)
        c.allowed_params = allowed
        for t in net.transitions:
            c.seen_funs = set()
            c.where = ""
            for g in t.guards:
                c.expr(g)
            c.expr(t.delay)
            c.expr(t.priority)
            for a in t.arcs:
                c.expr(a.expr)
        out.extend(c.problems)
    # one message per position and text: a function called by many transitions is reported once
    seen = set()
    unique = []
    for d in out:
        key = (str(d.span), d.message.split(" (in function")[0])
        if key not in seen:
            seen.add(key)
            unique.append(d)
    return unique


def expression_problems(net, scalars, exprs) -> list[Diagnostic]:
    """What tells the values of `scalars` apart in other expressions over the net (property texts, in the
    net's expression form): the rules of `check_symmetry`, and a string naming binding values (an
    `enabled "T: {x=a}"` pattern)."""
    out: list[Diagnostic] = []
    for s in scalars:
        c = _Checker(net, s.name, s.kind)
        for e in exprs:
            c.expr(e)
            for node in _strings(e):
                if "{" in node.value:
                    c.refuse(node, f"the binding pattern \"{node.value}\"",
                             "Name the transition only, or leave the colour set out of the symmetry.")
        out.extend(c.problems)
    return out


def _strings(e):
    stack = [e]
    while stack:
        x = stack.pop()
        if isinstance(x, E.Const) and x.kind == "string":
            yield x
        elif isinstance(x, (E.Expr, E.Pat)):
            stack.extend(getattr(x, f.name) for f in dataclasses.fields(x) if f.name != "span")
        elif isinstance(x, (list, tuple)):
            stack.extend(x)


def families_of(net, scalars) -> tuple[list, list[Diagnostic]]:
    """The module instances that the scalars permute (`cpn.net.instance_symmetry.instance_families`)."""
    values = [scalar_values(net.colsets[s.name]) for s in scalars]
    return instance_families(net, scalars, values)


def _family_params(net, families) -> set:
    """The uids of the parameters of the families' pages: allowed in their inscriptions like variables."""
    checked = getattr(net, "checked", None)
    out = set()
    for f in families:
        for page in f.pages:
            info = checked.modules.get(page) if checked is not None else None
            out.update(p.uid for p in (info.params if info is not None else ()))
    return out


def symmetry_problems(net, scalars) -> list[Diagnostic]:
    """Everything that stops `scalars` from being a symmetry of the net: `check_symmetry` (with the module
    instances the scalars permute), then (when the inscriptions are fine) the instances' parameters and
    the initial marking."""
    out = check_symmetry(net, scalars)
    if not out:
        values = [scalar_values(net.colsets[s.name]) for s in scalars]
        gens = generators(scalars, values)
        families, _ = families_of(net, scalars)
        if families:
            out = parameter_problems(net, scalars, families, gens) or moved_initial_problems(net, scalars, families,
                                                                                             gens)
        else:
            out = initial_marking_problems(net, scalars, gens)
    return out


def initial_marking_problems(net, scalars, generators) -> list[Diagnostic]:
    """A diagnostic per place whose initial marking some renaming of `generators` (per scalar: value ->
    value, in the order of `scalars`) changes: such an initial marking tells the values apart."""
    ids = {id(root(net.colsets[s.name])): k for k, s in enumerate(scalars)}
    out = []
    for p in net.places:
        m = value_mapper(p.colour_set, ids)
        if m is None or not p.initial:
            continue
        for images in generators:
            image = lambda k, x, images=images: images[k][x]  # noqa: E731
            moved: dict = {}
            for key, c in p.initial.items():
                nk = (m(key[0], image), key[1]) if p.timed else m(key, image)
                moved[nk] = moved.get(nk, 0) + c
            if moved != p.initial:
                k = next(k for k, g in enumerate(images) if any(a != b for a, b in g.items()))
                s = scalars[k]
                out.append(Diagnostic(
                    CODE, f"the initial marking of place '{p.name}' tells the values of colour set '{s.name}' "
                    f"apart, so {'rotating' if s.kind == 'rotations' else 'permuting'} them is not a symmetry "
                    "of the net", p.span, hint=f"Give every value of '{s.name}' the same tokens (e.g. with "
                    f"'{s.name}.all()'), or leave '{s.name}' out of the symmetry.",
                    params={"colour_set": s.name, "kind": s.kind, "place": p.name}))
                break
    return out


__all__ = ["SYMMETRIC_CSOPS", "check_symmetry", "expression_problems", "families_of", "initial_marking_problems",
           "symmetry_problems"]
