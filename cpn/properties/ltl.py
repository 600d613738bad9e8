"""`kind = "ltl"` in scenario files: an LTL formula over the property language's atoms.

The formula is a CPN ML boolean text in which the temporal operators are functions: ``G p``, ``F p``,
``X p`` (or ``ALWAYS``, ``EVENTUALLY``, ``NEXT``), ``U (p, q)`` and ``R (p, q)`` (``UNTIL``,
``RELEASE``), combined with ``not``, ``andalso``, ``orelse`` and ``if``; its largest parts without a
temporal operator are the atoms, marking predicates as anywhere else (``enabled "Page'T 1"`` included).
``EXB ("Page'T 1: {x=1}", p)`` and ``AXB (...)`` are `ctl`'s binding-element operators read on the path:
the step that leaves the position is such an occurrence and ``X p`` holds, or it is not or ``X p`` holds.
It holds when every infinite path from the initial marking satisfies it; a dead marking repeats forever
(docs/specs.md). `weak_fairness = ["Page'T", ...]` keeps only the paths on which each listed transition,
if it is enabled in every marking from some point on, occurs infinitely often; `strong_fairness = [...]`
the paths on which each, if it is enabled infinitely often, occurs infinitely often.

The check runs `cpn.checks.ltl` on the fly, before the state space is explored (`search_on_the_fly`,
called by `cpn.gate.run`): the product of the automaton with the markings generated as the search goes,
stopping at the first accepting cycle, so a violation is found without the whole state space. A
violation is a lasso: the shortest path in the product to the cycle found, then that cycle (or a path
that ends in a dead marking). Under a reduction, or when the search on the fly stopped at a limit, it runs
on the explored graph instead.
"""

from __future__ import annotations

from cpn._util import did_you_mean
from cpn.checks.ltl import LtlResult, check_ltl
from cpn.checks.verdict import Evidence, Verdict, path_evidence
from cpn.diagnostics import Diagnostic
from cpn.errors import ModelError
from cpn.lang import ast as A
from cpn.lang import types as T
from cpn.properties.kinds import Check, _slice, _state_name
from cpn.properties.predicates import CTL_ARC, LTL_BINARY, LTL_UNARY, walk


class Ltl(Check):
    def __init__(self, spec, formula: tuple, atoms: list, weak: list[set] | None = None,
                 strong: list[set] | None = None, steps: list | None = None):
        super().__init__(spec)
        self.formula = formula
        self.atoms = atoms
        self.steps = steps or []  # binding-element tests of EXB and AXB: atoms len(atoms) + j
        self.weak = weak or []  # per weak fairness entry, its transition instances
        self.strong = strong or []  # the same for strong fairness
        self.fly: LtlResult | None = None  # the search on the fly, when it ran

    def search_on_the_fly(self, system, lang, max_states: int | None = None,
                          deadline: float | None = None) -> LtlResult:
        """Decide the formula on the fly on `system` (the engine, or a `cpn.checks.ltl.Cache` around it
        shared by several formulas): the markings are generated as the search needs them. The result is
        kept for `decide`."""
        ctx = lang.ctx
        ctx.graph = None  # no graph yet: `enabled` asks the engine
        transition_of = lang.transition_index

        def pair(ts: set) -> tuple:
            return (lambda s: any(transition_of(be) in ts for be, _t in system.successors(s)),
                    lambda be: be is not None and transition_of(be) in ts)

        self.fly = check_ltl(system, self.formula, [lambda s, fn=a.fn: bool(fn(None, s)) for a in self.atoms],
                             max_states=max_states, deadline=deadline,
                             weak_fairness=[pair(ts) for ts in self.weak],
                             strong_fairness=[pair(ts) for ts in self.strong],
                             step_propositions=list(self.steps))
        return self.fly

    def decide(self, view) -> Verdict:
        if self.fly is not None and self.fly.holds is not None:
            return self._decided_on_the_fly(view, self.fly)
        if not view.complete:
            return Verdict.unknown(view.reason if self.fly is None else
                                   f"{self.fly.reason} (the search on the fly); {view.reason}")
        truths = [view.truth(a) for a in self.atoms]
        res = check_ltl(_Graph(view.g), self.formula, [t.__getitem__ for t in truths],
                        weak_fairness=[_weak(view, ts) for ts in self.weak],
                        strong_fairness=[_weak(view, ts) for ts in self.strong],
                        step_propositions=[_occurs(view, test) for test in self.steps])
        if res.holds:
            return Verdict.holds(f"every path satisfies it ({res.product_states:,} states of the product with "
                                 f"the {res.automaton_states}-state automaton of its negation)")
        path = [s for _label, s in res.prefix]
        hints = {(u, v): a for (_l, u), (a, v) in zip(res.prefix, res.prefix[1:])}
        stutter = res.cycle and res.cycle[0][0] is None
        cycle = [] if stutter else [s for _label, s in res.cycle]
        arcs = None if stutter else [a for a, _s in res.cycle]
        ev = path_evidence(view.g, path, cycle or None, arcs, hints)
        end = path[-1]
        if stutter:
            msg = f"a path that ends in dead {_state_name(view, end)} does not satisfy it"
        else:
            msg = f"a path that cycles through {_state_name(view, end)} does not satisfy it"
        return Verdict.violated(msg, ev)


    def _decided_on_the_fly(self, view, res: LtlResult) -> Verdict:
        size = (f"{res.system_states:,} markings generated, {res.product_states:,} states of the product with "
                f"the {res.automaton_states}-state automaton of its negation")
        if res.holds:
            return Verdict.holds(f"every path satisfies it (decided on the fly: {size})")
        stutter = bool(res.cycle) and res.cycle[0][0] is None
        ids = [view.g.state_id(s) for _label, s in res.prefix]
        cids = [] if stutter else [view.g.state_id(s) for _label, s in res.cycle]
        ev = None
        if None not in ids and None not in cids:
            ev = Evidence(tuple(ids), tuple(label for label, _s in res.prefix[1:]), tuple(cids),
                          tuple(() if stutter else (label for label, _s in res.cycle)))
        end = ids[-1]
        where = _state_name(view, end) if end is not None else f"a marking {len(ids) - 1} steps from the initial one"
        if stutter:
            msg = f"a path that ends in dead {where} does not satisfy it"
        else:
            msg = f"a path that cycles through {where} does not satisfy it"
        return Verdict.violated(f"{msg} (found on the fly: {size})", ev)


def lasso_states(res: LtlResult) -> set:
    """The markings of a violation's lasso (for an exploration that stops once it has them all)."""
    return {s for _label, s in res.prefix} | {s for _label, s in res.cycle}


def _weak(view, transitions: set) -> tuple:
    """(enabled(state), occurs(arc)) of a set of transition instances, over the explored graph."""
    labels, offsets = view.labels(), view.g.offsets
    enabled = bytearray(view.g.n_states)
    for u in range(view.g.n_states):
        for a in range(offsets[u], offsets[u + 1]):
            if labels[a] in transitions:
                enabled[u] = 1
                break
    return enabled.__getitem__, lambda a: a is not None and labels[a] in transitions


def _occurs(view, test) -> tuple:
    """The test of an arc (a label of `_Graph`): whether its binding element passes `test`."""
    bes = view.g.bes
    return lambda a: test(bes[a])


class _Graph:
    """An explored graph as the LTL search sees a system: state ids, arcs labelled by their index."""

    def __init__(self, g) -> None:
        self.offsets, self.dst = g.offsets, g.dst

    def initial_state(self) -> int:
        return 0

    def successors(self, u: int) -> list:
        dst = self.dst
        return [(a, dst[a]) for a in range(self.offsets[u], self.offsets[u + 1])]


def build_ltl(spec, lang) -> Ltl:
    text, origin, span = spec.fields["formula"], spec.texts.get("formula"), spec.spans.get("formula", spec.span)
    expr = lang.check(text, origin, span, T.BOOL, "an LTL formula", ltl=True)
    syms = {id(s): n for n, s in lang.ltl_symbols.items()}
    atoms: list = []
    steps: list = []  # binding-element tests; ("step", j) until the atoms are counted

    def op_of(e) -> str | None:
        if isinstance(e, A.App) and isinstance(e.fn, A.Name) and e.fn.ref is not None and id(e.fn.ref) in syms:
            return syms[id(e.fn.ref)]
        return None

    def temporal(e) -> bool:
        return any(isinstance(n, A.Name) and n.ref is not None and id(n.ref) in syms for n in walk(e))

    def conv(e) -> tuple:
        if not temporal(e):
            atoms.append(lang.compile_checked(_slice(text, origin, e), e, span))
            return ("ap", len(atoms) - 1)
        op = op_of(e)
        if op in CTL_ARC:  # on a path: its next step is (EXB) or, if it is, leads to (AXB) ...
            pat, phi = e.arg.items
            steps.append(lang.arc_pattern(op, pat, text, origin, span))
            occurs, after = ("step", len(steps) - 1), ("X", conv(phi))
            return ("and", occurs, after) if op == "EXB" else ("or", ("not", occurs), after)
        if op in LTL_BINARY:
            a, b = e.arg.items
            return (LTL_BINARY[op], conv(a), conv(b))
        if op in LTL_UNARY:
            return (LTL_UNARY[op], conv(e.arg))
        if isinstance(e, A.App) and isinstance(e.fn, A.Name) and e.fn.name == "not":
            return ("not", conv(e.arg))
        if isinstance(e, A.BinOp) and e.op in ("andalso", "orelse"):
            return ("and" if e.op == "andalso" else "or", conv(e.left), conv(e.right))
        if isinstance(e, A.If):
            c = conv(e.cond)
            return ("or", ("and", c, conv(e.then)), ("and", ("not", c), conv(e.else_)))
        if isinstance(e, A.Annot):
            return conv(e.expr)
        from cpn.properties.predicates import _remap

        raise _remap(ModelError([Diagnostic(
            "E0702", "a temporal operator can only be combined with not, andalso, orelse and if-then-else",
            e.span, hint="Move the temporal operator out of the function, let or case expression.")]),
            text, origin, span)

    formula = _numbered(conv(expr), len(atoms))
    fairness: dict[str, list[set]] = {"weak_fairness": [], "strong_fairness": []}
    diags = []
    for key, sets in fairness.items():
        for name in spec.fields.get(key, []):
            ts = lang.resolve_transitions(name)
            if ts is None:
                near = did_you_mean(name, list(lang.transition_names))
                diags.append(Diagnostic("E0703", f"no transition instance '{name}' in the net",
                                        spec.spans.get(key, spec.span),
                                        hint=f"Did you mean '{near}'?" if near else
                                        "Name it as the report prints it: \"Page'trans 1\", or \"Page'trans\" "
                                        "for every instance."))
            else:
                sets.append(set(ts))
    if diags:
        raise ModelError(diags)
    return Ltl(spec, formula, atoms, fairness["weak_fairness"], fairness["strong_fairness"], steps)


def _numbered(f: tuple, n_atoms: int) -> tuple:
    """The formula with its step atoms ("step", j) numbered after the marking atoms: ("ap", n_atoms + j)."""
    if f[0] == "step":
        return ("ap", n_atoms + f[1])
    if f[0] == "ap":
        return f
    return (f[0], *(_numbered(a, n_atoms) for a in f[1:]))


__all__ = ["Ltl", "build_ltl", "lasso_states"]
