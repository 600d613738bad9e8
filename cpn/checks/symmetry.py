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


def symmetry_plan(checks: list, net, scalars) -> dict:
    """check -> why its verdict is not preserved: a home-marking property, a multi-set bound, and a
    property whose text tells apart the values of a symmetric colour set; the others are decided on the
    quotient graph."""
    from cpn.checks.properties import Bound, Home
    from cpn.net.symmetry import expression_problems
    from cpn.net.translate import Translator

    refused = {}
    for c in checks:
        if isinstance(c, Home):
            refused[c] = (f"{NOT_PRESERVED}: two symmetric terminal components of the full graph are one in the "
                          "quotient, so its home markings are not those of the full graph")
            continue
        if isinstance(c, Bound) and (c.upper_ms is not None or c.lower_ms is not None):
            refused[c] = (f"{NOT_PRESERVED}: a multi-set bound of the full graph is that of a colour's whole "
                          "orbit, not the representative's")
            continue
        texts = [p for p in _compiled(c)]
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


def _compiled(check) -> list:
    """The compiled property texts of a check (`cpn.checks.predicates.Compiled`)."""
    out = []
    for name in ("pred", "fn", "atoms"):
        v = getattr(check, name, None)
        for p in v if isinstance(v, (list, tuple)) else [v]:
            if p is not None and hasattr(p, "expr"):
                out.append(p)
    return out


__all__ = ["NOT_PRESERVED", "NOT_PRESERVED_SECTIONS", "PRESERVED", "symmetry_plan"]
