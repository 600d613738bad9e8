"""What a state space reduced by symmetry (the quotient graph, one state per orbit) decides.

The quotient graph of a symmetry G of the net is bisimilar to the full graph for every proposition that G
leaves unchanged (Emerson and Sistla, "Symmetry and model checking", 1996; Jensen, "Coloured Petri Nets",
vol. 2, ch. 3): an orbit is dead exactly when its markings are, the number of tokens on a place is the same
in every marking of an orbit, and a transition instance is enabled in a marking exactly when it is enabled
in every marking of the orbit (with renamed bindings). So the quotient gives the dead markings up to
symmetry (and, from the orbit sizes, their number in the full graph), the integer bounds and token maxima,
the dead and live transition instances and the fairness of transition instances. The multi-set bounds (a
colour's bound is that of its whole orbit, not of the representative) and the home markings (two
symmetric terminal components of the full graph are one in the quotient) are not preserved.

A property is decided on the quotient when its text does not tell the values of the symmetric colour sets
apart (the same rules as for the net, `cpn.net.symmetry`): then its atoms have the same value on every
marking of an orbit, and every kind of property (invariants, reachability, deadlocks, CTL) is preserved.
Otherwise its verdict is `unknown` with the reason.
"""

from __future__ import annotations

NOT_PRESERVED: str = "not preserved by symmetry reduction"
#: sections of the standard report that the quotient graph gives for the full graph
PRESERVED: tuple = ("dead_markings (up to symmetry, with their count in the full graph)", "bounds", "tokens",
                    "dead_transitions", "live_transitions", "fairness")
#: sections it does not give (null in the JSON result, "not preserved" in the text)
NOT_PRESERVED_SECTIONS: tuple = ("multiset_bounds", "home_markings")
#: and those it does not give either when the group moves module instances
INSTANCE_NOT_PRESERVED: tuple = ("live_transitions", "fairness")


def symmetry_plan(checks: list, net, scalars) -> dict:
    """check -> why its verdict is not preserved: a home-marking property, a multi-set bound, and a
    property whose text tells apart the values of a symmetric colour set; when the group moves module
    instances, a property that names one instance's place or transition (`Slave'Idle 2`: `sum`, `forall`
    and `exists` over all of them are allowed), a bound of such a place, and live transitions among
    them; the others are decided on the quotient graph."""
    from cpn.net.symmetry import expression_problems
    from cpn.properties.kinds import Bound, Home

    refused = {}
    instances = _Instances(net, scalars)
    for c in checks:
        why = instances.refusal(c)
        if why is not None:
            refused[c] = f"{NOT_PRESERVED}: {why}"
            continue
        if isinstance(c, Home):
            refused[c] = (f"{NOT_PRESERVED}: two symmetric terminal components of the full graph are one in the "
                          "quotient, so its home markings are not those of the full graph")
            continue
        if isinstance(c, Bound) and c.multiset_limits:
            refused[c] = (f"{NOT_PRESERVED}: a multi-set bound of the full graph is that of a colour's whole "
                          "orbit, not the representative's")
            continue
        texts = [p for p in _compiled(c)]
        from cpn.net.translate import Translator

        tr = Translator()
        exprs = []
        for p in texts:
            try:
                exprs.append(tr.expr(p.expr))
            except Exception:  # noqa: BLE001 - a text the translator cannot read is not judged symmetric
                refused[c] = f"{NOT_PRESERVED}: its text could not be checked for symmetry"
                break
        if c in refused:
            continue
        problems = expression_problems(net, scalars, exprs)
        if problems:
            d = problems[0]
            where = f" at {d.span}" if d.span else ""
            refused[c] = f"{NOT_PRESERVED}: {d.message.split(', so ')[0]}{where}"
    return refused


class _Instances:
    """The place and transition instances that the group moves (module instances permuted with the
    values), and the properties that name one of them."""

    def __init__(self, net, scalars):
        from cpn.net.instance_symmetry import moved_places
        from cpn.net.symmetry import families_of

        self.families = families_of(net, scalars)[0] if scalars else []
        moved = moved_places(self.families)
        self.places = moved
        self.transitions = {t for f in self.families for ts in f.transitions.values() for t in ts}
        self.pages = {p for f in self.families for p in f.pages}
        self.accessors = {f"{net.places[p].page}'{net.places[p].place}" for p in moved}
        self.net = net

    def refusal(self, check) -> str | None:
        if not self.families:
            return None
        from cpn.properties.kinds import Bound, LiveTransitions

        t_names = [t.name for t in self.net.transitions]
        if isinstance(check, LiveTransitions):
            wanted = check.transitions if check.transitions is not None else range(len(t_names))
            bad = [t_names[t] for t in wanted if t in self.transitions]
            if bad:
                return (f"whether {bad[0]} is live (a transition of one of the module instances the symmetry "
                        "permutes)")
        if isinstance(check, Bound) and check.places is not None:
            bad = [self.net.places[p].name for p in check.places if p in self.places]
            if bad:
                return f"the bound of {bad[0]}, a place of one of the module instances the symmetry permutes"
        for name in check.spec.fields.get("fairness", []) or []:
            if self._names_moved_transition(str(name)):
                return f"the fairness set \"{name}\" names a transition of one module instance"
        for text in _compiled(check):
            why = self._text(text.expr)
            if why is not None:
                return why
        return None

    def _names_moved_transition(self, s: str) -> bool:
        return any(s.startswith(f"{page}'") for page in self.pages)

    def _text(self, expr) -> str | None:
        """What in a property text names one module instance: a place accessor applied to an instance
        number (not the argument of `sum`, `forall` or `exists`), or a string naming a transition."""
        import dataclasses

        from cpn.lang import ast as A

        allowed = set()
        stack = [expr]
        while stack:
            e = stack.pop()
            if isinstance(e, A.App) and isinstance(e.fn, A.Name) and e.fn.name in ("sum", "forall", "exists"):
                allowed.add(id(e.arg))
            if isinstance(e, A.Name):
                name = e.name[5:] if e.name.startswith("Mark.") else e.name
                if name in self.accessors and id(e) not in allowed:
                    return (f"'{e.name}' names the place of one module instance the symmetry permutes (use sum, "
                            "forall or exists over all of them)")
            if isinstance(e, A.Const) and e.kind == "string" and self._names_moved_transition(str(e.value)):
                return f"\"{e.value}\" names a transition of one module instance the symmetry permutes"
            if dataclasses.is_dataclass(e):
                for f in dataclasses.fields(e):
                    if f.name in ("span", "ref", "ty"):
                        continue
                    v = getattr(e, f.name)
                    if isinstance(v, (list, tuple)):
                        stack.extend(x for x in v if dataclasses.is_dataclass(x) or isinstance(x, (list, tuple)))
                        for x in v:
                            if isinstance(x, (list, tuple)):
                                stack.extend(y for y in x if dataclasses.is_dataclass(y))
                    elif dataclasses.is_dataclass(v):
                        stack.append(v)
        return None


def _compiled(check) -> list:
    """The compiled property texts of a check (`cpn.properties.predicates.Compiled`)."""
    out = []
    for name in ("pred", "fn", "atoms"):
        v = getattr(check, name, None)
        for p in v if isinstance(v, (list, tuple)) else [v]:
            if p is not None and hasattr(p, "expr"):
                out.append(p)
    return out


def decide_over_orbits(check, view):
    """The verdict of an `invariant` or `reachable` property that the quotient cannot decide through its
    representatives alone (its text names one module instance, or tells the symmetric values apart),
    decided through every marking of every orbit; None for the other kinds.

    The full graph's reachable markings are exactly the images of the quotient's representatives under
    the group (an orbit is reachable as a whole), so an invariant holds iff it holds in every image of
    every representative, and a marking is reachable iff it is an image of one. The images are generated
    from each representative by the group's generators (`cpn.engine.symmetry.Canonicaliser`), as many as
    the full graph has markings, and each is tested; no arc of the full graph is built. A violation (or a
    witness) is reported at its representative, whose trace reaches the orbit: the marking found is an
    image of the trace's last marking."""
    from cpn.checks.verdict import Verdict, evidence_to
    from cpn.properties.kinds import Invariant, Reachable, _state_name

    sym = getattr(view.g, "symmetry", None)
    if sym is None or not isinstance(check, (Invariant, Reachable)):
        return None
    g = view.g
    canon = sym.canon
    gens = canon.generators()
    fn = check.pred.fn
    view.lang.ctx.graph = None  # an image is no state of the graph: its enabled bindings come from the engine
    looking_for = isinstance(check, Reachable)  # a marking where the text is true; for an invariant, false
    images = 0
    for i, r in enumerate(g.states):
        if not g.is_expanded(i):
            continue
        seen = {r}
        stack = [r]
        while stack:
            s = stack.pop()
            images += 1
            if bool(fn(None, s)) == looking_for:
                where = (f"a marking of the orbit of {_state_name(view, i)} (an image of it under the symmetry: "
                         "the trace reaches the orbit)")
                if looking_for:
                    return Verdict.holds(f"witness: {where}", evidence_to(g, i))
                return Verdict.violated(f"false in {where}", evidence_to(g, i))
            for gen in gens:
                t = canon.apply(s, gen)
                if t not in seen:
                    seen.add(t)
                    stack.append(t)
    how = f"every image of the {g.n_states:,} representatives of the symmetry quotient, {images:,} markings"
    if not view.complete:
        return Verdict.unknown(f"{'not found' if looking_for else 'true'} in {how}; {view.reason}")
    if looking_for:
        return Verdict.violated(f"no reachable marking satisfies it ({how})")
    return Verdict.holds(f"true in {how}")


__all__ = ["INSTANCE_NOT_PRESERVED", "NOT_PRESERVED", "NOT_PRESERVED_SECTIONS", "PRESERVED", "decide_over_orbits",
           "symmetry_plan"]
