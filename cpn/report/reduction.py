"""What a reduced state space (stubborn sets, symmetry) does and does not preserve, as the reports say it."""

from __future__ import annotations

from cpn.statespace import Exploration

# What a reduced state space (stubborn sets) does and does not preserve, as the report says it.
NOT_PRESERVED: str = "not preserved by stubborn sets"
SYM_NOT_PRESERVED: str = "not preserved by symmetry reduction"
REDUCED_SECTIONS: tuple = ("scc", "bounds", "home_markings", "dead_transitions", "live_transitions", "fairness")


def reduction_text(x: Exploration) -> str | None:
    """One sentence naming the reduction that ran and what it preserves (None: the full graph)."""
    if x.reduction is None:
        return None
    if x.reduction == "symmetry":
        return symmetry_text(x)
    visible = (x.reduction_stats or {}).get("visible_places")
    kept = "the dead markings (their existence and their set)"
    if visible is not None:
        names = ", ".join(x.engine.places[p].name for p in visible) or "none"
        kept += f" and the invariants over the visible places ({names})"
    return (f"reduction: stubborn sets (partial-order reduction); the node and arc counts are those of the "
            f"reduced graph; it preserves {kept}; the SCC graph, bounds, home markings, dead and live "
            f"transition instances and fairness are {NOT_PRESERVED} and not reported")


def symmetry_text(x: Exploration) -> str:
    """The sentence of `reduction_text` for symmetry reduction."""
    st = x.reduction_stats or {}
    full = ("" if st.get("full_states") is None else
            f" (the full state space: {st['full_states']:,} nodes and {st['full_arcs']:,} arcs, the sums of the "
            "orbit sizes)")
    families = st.get("instances") or []
    if families:
        return (f"reduction: symmetry ({', '.join(st.get('symmetry') or [])}, moving the instances of "
                f"{', '.join(families)}; a group of {st.get('group_order', 0):,} renamings); the node and arc counts "
                f"are those of the quotient graph, one node per orbit{full}; it preserves the dead markings up to "
                "symmetry, the integer bounds (of every instance, from the same place of each) and token maxima "
                "and the dead transition instances; the SCC graph is the quotient's; the multi-set bounds, home "
                f"markings, live transition instances and fairness are {SYM_NOT_PRESERVED} and not reported; "
                "traces are paths of the full graph")
    return (f"reduction: symmetry ({', '.join(st.get('symmetry') or [])}; a group of {st.get('group_order', 0):,} "
            f"renamings); the node and arc counts are those of the quotient graph, one node per orbit{full}; it "
            "preserves the dead markings up to symmetry, the integer bounds and token maxima, the dead and live "
            "transition instances and fairness; the SCC graph is the quotient's; the multi-set bounds and home "
            f"markings are {SYM_NOT_PRESERVED} and not reported; traces are paths of the full graph")


__all__ = ["NOT_PRESERVED", "REDUCED_SECTIONS", "SYM_NOT_PRESERVED", "reduction_text", "symmetry_text"]
