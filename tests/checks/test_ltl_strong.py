"""LTL under strong fairness (`check_ltl(..., strong_fairness=...)`): random formulas on random small
systems against every lasso of the system up to a length, cycles that repeat states included, and a system
where weak fairness is not enough."""

from __future__ import annotations

import itertools
import random

import pytest

from cpn.checks.ltl import check_ltl
from tests.checks.test_ltl import Kripke, lasso_path, random_kripke, word
from tests.checks.test_ltl_buchi import holds_on_lasso, random_formula


def all_lassos(k: Kripke, max_len: int):
    """(prefix, cycle) for every path from 0 of at most max_len steps that returns to one of its states
    (a cycle may pass a state more than once; a dead end stutters)."""
    stack = [[0]]
    while stack:
        path = stack.pop()
        for t in k.succ[path[-1]] or [path[-1]]:
            for i, s in enumerate(path):
                if s == t:
                    yield path[:i], path[i:]
            if len(path) < max_len:
                stack.append(path + [t])


def moves_to(t: int):
    return lambda label: label is not None and label.endswith(f"->{t}")


def strongly_fair(k: Kripke, loop: list, labels: list, targets: list) -> bool:
    """Whether a cycle (its states, and the labels of its steps) lets each 'move to t' occur when some
    state of it enables the move."""
    return all(any(map(moves_to(t), labels)) or not any(t in k.succ[s] for s in loop) for t in targets)


@pytest.mark.parametrize("seed", range(5))
def test_strong_fairness_against_the_fair_lassos_of_the_system(seed):
    rng = random.Random(900 + seed)
    violated = held = 0
    for _ in range(50):
        k = random_kripke(rng, rng.randrange(2, 5), 2)
        f = random_formula(rng, 3, 2)
        targets = sorted(rng.sample(range(len(k.succ)), rng.randrange(1, 3)))
        strong = [(lambda s, t=t, k=k: t in k.succ[s], moves_to(t)) for t in targets]
        res = check_ltl(k, f, k.props(2), strong_fairness=strong)
        if res.holds:
            held += 1
            for p, c in all_lassos(k, 7):
                labels = [f"{a}->{b}" if b in k.succ[a] else None for a, b in itertools.pairwise(c + c[:1])]
                assert holds_on_lasso(f, word(k, p), word(k, c)) or not strongly_fair(k, c, labels, targets), \
                    (f, k.succ, k.labels, targets, p, c)
            continue
        violated += 1
        states, cycle = lasso_path(k, res)
        loop = [states[-1]] + cycle[:-1]
        assert not holds_on_lasso(f, word(k, states[:-1]), word(k, loop)), (f, res)
        assert strongly_fair(k, loop, [label for label, _s in res.cycle], targets), (f, k.succ, targets, res)
    assert violated and held


def test_strong_fairness_where_weak_fairness_is_not_enough():
    # 0 <-> 1 forever, or 0 -> 2 where p holds for ever: the move to 2 is enabled in 0 only, so the cycle
    # 0 1 0 1 ... is weakly fair to it (it is not enabled in 1) but not strongly fair
    k = Kripke({0: [1, 2], 1: [0], 2: [2]}, {0: set(), 1: set(), 2: {0}})
    to_2 = [(lambda s: 2 in k.succ[s] and s != 2, moves_to(2))]
    assert check_ltl(k, ("F", ("ap", 0)), k.props(1)).holds is False
    weak = check_ltl(k, ("F", ("ap", 0)), k.props(1), weak_fairness=to_2)
    assert weak.holds is False and [s for _l, s in weak.cycle] in ([1, 0], [0, 1])
    assert check_ltl(k, ("F", ("ap", 0)), k.props(1), strong_fairness=to_2).holds


def test_the_refinement_finds_a_fair_cycle_inside_an_unfair_scc():
    # 0 <-> 1, 1 -> 1, and 0 -> 2 where p holds for ever: the SCC {0, 1} ignores the move to 2, enabled
    # in 0, so it is not strongly fair; without 0 the cycle 1 -> 1 is, and "F p" fails on 0 1 1 1 ...
    k = Kripke({0: [1, 2], 1: [0, 1], 2: [2]}, {0: set(), 1: set(), 2: {0}})
    to_2 = [(lambda s: 2 in k.succ[s] and s != 2, moves_to(2))]
    res = check_ltl(k, ("F", ("ap", 0)), k.props(1), strong_fairness=to_2)
    assert res.holds is False
    assert [s for _l, s in res.prefix] == [0, 1] and [s for _l, s in res.cycle] == [1]
    # with the move to 0 strongly fair as well (enabled in 1), no fair cycle avoids 2
    to_0 = [(lambda s: 0 in k.succ[s], moves_to(0))]
    assert check_ltl(k, ("F", ("ap", 0)), k.props(1), strong_fairness=to_2 + to_0).holds
