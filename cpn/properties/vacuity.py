"""Vacuity: a property that holds, but holds for a reason that says nothing about the protocol.

- an invariant that is an implication (`not P orelse Q`, `if P then Q else true`, or a conjunction of
  them) whose premise P is true in no reachable marking;
- a `dead_markings` predicate when there is no dead marking to test it on;
- a CTL formula that still holds when one of its atoms is replaced by false (where the atom counts
  positively) or by true (where it counts negatively), the vacuity of Beer, Ben-David, Eisner and
  Rodeh (1997), and a CTL implication `not P or ...` whose premise P holds in no reachable marking.

Imports `cpn.checks` only.
"""

from __future__ import annotations

from cpn.checks.ctl import And, Atom, Not, Or, Temporal
from cpn.checks.verdict import Status
from cpn.lang import ast as A
from cpn.properties.kinds import Ctl, DeadMarkings, Invariant, _slice

# the diagnostic codes of the two kinds of warning a property that holds can get (cpn.diagnostics.CODES)
VACUOUS = "W0702"  # it holds vacuously (this module)
STRUCTURAL = "W0703"  # it follows from the net's structure (cpn.properties.structure)
# every warning of cpn.properties.structure starts with these words, every warning of this module with others
STRUCTURAL_WORDS = "follows from the net's structure"


def warning_code(text: str) -> str:
    """The code of a warning that `vacuity` or `cpn.properties.structure.structural` wrote.

    >>> warning_code("holds vacuously: there is no dead marking, so its predicate is never tested")
    'W0702'
    """
    return STRUCTURAL if text.startswith(STRUCTURAL_WORDS) else VACUOUS


def vacuity(check, view, verdict) -> list[str]:
    """Why a property that holds on a complete state space holds vacuously (one sentence each); empty
    when it does not, or when the verdict is not 'holds'."""
    if verdict.status is not Status.HOLDS or not view.complete or view.g is None:
        return []
    if isinstance(check, DeadMarkings) and check.pred is not None and not view.g.dead_states():
        return ["holds vacuously: there is no dead marking, so its predicate is never tested"]
    if isinstance(check, Invariant):
        return _invariant(check, view)
    if isinstance(check, Ctl):
        return _ctl(check, view)
    return []


def _invariant(check, view) -> list[str]:
    out = []
    pred = check.pred
    for premise in _premises(pred.expr):
        text = _slice(pred.text, None, premise)
        compiled = view.lang.compile_checked(text, premise, pred.span)
        if not any(view.truth(compiled)):
            out.append(f"holds vacuously: the premise '{text}' of its implication is true in no reachable marking")
    return out


def _premises(e) -> list:
    """The premises of the implications an invariant's text is made of (its top-level conjuncts)."""
    if isinstance(e, A.Annot):
        return _premises(e.expr)
    if isinstance(e, A.BinOp) and e.op == "andalso":
        return _premises(e.left) + _premises(e.right)
    if isinstance(e, A.BinOp) and e.op == "orelse":
        for side in (e.left, e.right):
            if _is_not(side):
                return [side.arg]
        return []
    if isinstance(e, A.If) and isinstance(e.else_, A.Const) and e.else_.value is True:
        return [e.cond]
    return []


def _ctl(check, view) -> list[str]:
    k = view.kripke(check.fairness)
    atoms = [view.truth(a) for a in check.atoms]
    out = []
    formula_text = check.spec.fields.get("formula", "")
    for premise in _ctl_premises(check.formula, check):
        if isinstance(premise, _NotInAtom):  # `not P` inside one atom: P is never true where it always is
            if all(atoms[premise.index]):
                text = _slice(formula_text, None, check.atoms[premise.index].expr.arg)
                out.append(f"holds vacuously: the premise '{text}' of its implication is true in no reachable "
                           "marking")
        elif not any(k.label(premise, atoms, {})):
            out.append(f"holds vacuously: the premise '{_text(premise, check)}' of its implication is true in no "
                       "reachable marking")
    polarity: dict[int, set] = {}
    _polarities(check.formula, True, polarity)
    n = len(atoms[0]) if atoms else 0
    for index, signs in sorted(polarity.items()):
        if len(signs) != 1 or not n:
            continue
        positive = signs == {True}
        replaced = list(atoms)
        replaced[index] = bytearray(n) if positive else bytearray([1]) * n
        if k.label(check.formula, replaced, {})[0]:
            text = check.atoms[index].text
            out.append(f"holds vacuously in '{text}': the formula holds just as well with it replaced by "
                       f"{'false' if positive else 'true'}")
    return out


class _NotInAtom:
    """A premise `not P` that is one atom of the formula (P has no temporal operator)."""

    def __init__(self, index: int):
        self.index = index


def _is_not(e) -> bool:
    return isinstance(e, A.App) and isinstance(e.fn, A.Name) and e.fn.name == "not"


def _ctl_premises(f, atoms_of) -> list:
    """The sub-formulas P of the implications `not P orelse Q` (and `Q orelse not P`) of a formula."""
    out = []
    stack = [f]
    while stack:
        g = stack.pop()
        if isinstance(g, Or):
            for side in (g.left, g.right):
                if isinstance(side, Not):
                    out.append(side.arg)
                elif isinstance(side, Atom) and _is_not(atoms_of.atoms[side.index].expr):
                    out.append(_NotInAtom(side.index))
            stack += [g.left, g.right]
        elif isinstance(g, And):
            stack += [g.left, g.right]
        elif isinstance(g, Not):
            stack.append(g.arg)
        elif isinstance(g, Temporal):
            stack += list(g.args)
    return out


def _polarities(f, positive: bool, out: dict) -> None:
    """Where each atom occurs: positively (under an even number of negations) or negatively. Every
    temporal operator is monotone in its arguments."""
    if isinstance(f, Atom):
        out.setdefault(f.index, set()).add(positive)
    elif isinstance(f, Not):
        _polarities(f.arg, not positive, out)
    elif isinstance(f, (And, Or)):
        _polarities(f.left, positive, out)
        _polarities(f.right, positive, out)
    elif isinstance(f, Temporal):
        for a in f.args:
            _polarities(a, positive, out)


def _text(f, check) -> str:
    if isinstance(f, Atom):
        return check.atoms[f.index].text
    if isinstance(f, Not):
        return f"not ({_text(f.arg, check)})"
    if isinstance(f, (And, Or)):
        op = "andalso" if isinstance(f, And) else "orelse"
        return f"({_text(f.left, check)}) {op} ({_text(f.right, check)})"
    return f"{f.op} ({', '.join(_text(a, check) for a in f.args)})"
