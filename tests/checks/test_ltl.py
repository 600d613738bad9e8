"""LTL on the fly (`cpn.checks.ltl`): random formulas on random small systems against the paths of the
system read directly, the lasso counterexamples, the stuttering of dead states, and a net."""

from __future__ import annotations

import itertools
import random

import pytest

import cpn
from cpn.checks.ltl import Cache, check_ltl
from tests.checks.test_ltl_buchi import holds_on_lasso, random_formula


class Kripke:
    """A small system: successors by state number, the propositions true in each state."""

    def __init__(self, succ: dict, labels: dict) -> None:
        self.succ, self.labels = succ, labels

    def initial_state(self):
        return 0

    def successors(self, s):
        return [(f"{s}->{t}", t) for t in self.succ[s]]

    def props(self, n: int):
        return [lambda s, i=i: i in self.labels[s] for i in range(n)]


def random_kripke(rng: random.Random, n_states: int, n_aps: int) -> Kripke:
    succ = {s: sorted(rng.sample(range(n_states), rng.randrange(0, min(3, n_states + 1)))) for s in range(n_states)}
    labels = {s: {i for i in range(n_aps) if rng.random() < 0.5} for s in range(n_states)}
    return Kripke(succ, labels)


def lassos(k: Kripke, max_len: int):
    """Every path from 0 of at most max_len states that closes a cycle (a dead end stutters)."""
    stack = [[0]]
    while stack:
        path = stack.pop()
        last = path[-1]
        nxt = k.succ[last] or [last]
        for t in nxt:
            if t in path:
                i = path.index(t)
                yield path[:i], path[i:]
            if len(path) < max_len:
                stack.append(path + [t])


def word(k: Kripke, states: list) -> list:
    return [k.labels[s] for s in states]


def lasso_path(k: Kripke, res) -> tuple[list, list]:
    """The states of a counterexample's prefix and cycle, checked to be a path of the system from 0 whose
    cycle returns to the end of the prefix (a dead end stutters)."""
    states = [s for _label, s in res.prefix]
    cycle = [s for _label, s in res.cycle]
    assert states[0] == 0 and cycle and cycle[-1] == states[-1]
    for a, b in itertools.pairwise(states + cycle):
        assert b in (k.succ[a] or [a])
    return states, cycle


@pytest.mark.parametrize("seed", range(6))
def test_random_formulas_on_random_systems_agree_with_their_paths(seed):
    rng = random.Random(100 + seed)
    violated = held = 0
    for _ in range(80):
        k = random_kripke(rng, rng.randrange(1, 5), 2)
        f = random_formula(rng, 3, 2)
        res = check_ltl(k, f, k.props(2))
        bad = [(p, c) for p, c in lassos(k, 6) if not holds_on_lasso(f, word(k, p), word(k, c))]
        if res.holds:
            held += 1
            assert not bad, (f, k.succ, k.labels, bad[0])
            continue
        violated += 1
        # the counterexample is a path of the system, closing a cycle, on which the formula is false
        states, cycle = lasso_path(k, res)
        assert not holds_on_lasso(f, word(k, states[:-1]), word(k, [states[-1]] + cycle[:-1])), (f, res)
    assert violated and held  # both outcomes were exercised


def test_a_dead_state_repeats_forever():
    k = Kripke({0: [1], 1: []}, {0: set(), 1: {0}})
    assert check_ltl(k, ("F", ("G", ("ap", 0))), k.props(1)).holds
    res = check_ltl(k, ("G", ("not", ("ap", 0))), k.props(1))
    assert res.holds is False
    assert [s for _l, s in res.prefix] == [0, 1] and res.cycle == [(None, 1)]


def test_the_search_stops_at_the_first_accepting_cycle():
    # a ring 0 -> 1 -> ... -> 999 -> 0 where every state may also stay, p holding at 0 only: "G p" fails
    # on the cycle 1 -> 1, found before the rest of the ring is generated
    k = Kripke({s: [s, (s + 1) % 1000] for s in range(1000)}, {s: ({0, 1} if s == 0 else {1}) for s in range(1000)})
    res = check_ltl(k, ("G", ("ap", 0)), k.props(2))
    assert res.holds is False and res.system_states <= 3
    full = check_ltl(k, ("G", ("ap", 1)), k.props(2))
    assert full.holds and full.system_states == 1000


def test_a_limit_gives_no_verdict():
    k = Kripke({s: [(s + 1) % 1000] for s in range(1000)}, {s: {0} for s in range(1000)})
    res = check_ltl(k, ("G", ("ap", 0)), k.props(1), max_states=50)
    assert res.holds is None and "50 markings" in res.reason and res.system_states <= 52


def test_on_a_net_through_the_engine_protocol():
    engine = cpn.loads("colset U = unit; place A : U = 1`(); place B : U;"
                       " trans go; trans back; arc A -> go; arc go -> B; arc B -> back; arc back -> A;").engine()
    system = Cache(engine)
    in_a = [lambda s: engine.token_counts(s)[0] > 0]
    assert check_ltl(system, ("G", ("F", ("ap", 0))), in_a).holds
    res = check_ltl(system, ("F", ("G", ("ap", 0))), in_a)
    assert res.holds is False
    steps = [engine.format_binding_element(label) for label, _s in res.prefix[1:] + res.cycle]
    assert any(s.startswith("Top'go") for s in steps)
    assert system.expanded == 2


def _fair_lasso(k: Kripke, cycle_states: list, closing: int, targets: list) -> bool:
    """Whether the cycle (states, then back to `closing`) is weakly fair to 'moving to t' for each t."""
    ring = cycle_states + [closing]
    steps = list(itertools.pairwise(ring))
    for t in targets:
        occurs = any(b == t and b in k.succ[a] for a, b in steps)
        disabled = any(t not in k.succ[s] for s in cycle_states)
        if not (occurs or disabled):
            return False
    return True


@pytest.mark.parametrize("seed", range(4))
def test_weak_fairness_against_the_fair_lassos_of_the_system(seed):
    rng = random.Random(500 + seed)
    fair_violations = 0
    for _ in range(60):
        k = random_kripke(rng, rng.randrange(2, 5), 2)
        f = random_formula(rng, 3, 2)
        targets = [0]
        weak = [(lambda s, t=t, k=k: t in k.succ[s], lambda label, t=t: label is not None and label.endswith(f"->{t}"))
                for t in targets]
        res = check_ltl(k, f, k.props(2), weak_fairness=weak)
        bad = []
        for p, c in lassos(k, 6):
            if not holds_on_lasso(f, word(k, p), word(k, c)) and _fair_lasso(k, c, c[0], targets):
                bad.append((p, c))
        if res.holds:
            assert not bad, (f, k.succ, k.labels, bad[0])
            continue
        fair_violations += 1
        states = [s for _label, s in res.prefix]
        cycle = [s for _label, s in res.cycle]
        assert cycle and cycle[-1] == states[-1]
        loop = [states[-1]] + cycle[:-1]
        assert not holds_on_lasso(f, word(k, states[:-1]), word(k, loop))
        labels = [label for label, _s in res.cycle]
        for t in targets:  # the lasso's cycle is fair: the move to t occurs, or t is not enabled somewhere
            assert any(lab is not None and lab.endswith(f"->{t}") for lab in labels) or \
                any(t not in k.succ[s] for s in loop)
    assert fair_violations


def test_weak_fairness_rules_out_a_transition_that_is_ignored_forever():
    # 0 loops on itself or moves to 1, where p holds forever: F p fails only by ignoring the move to 1
    k = Kripke({0: [0, 1], 1: [1]}, {0: set(), 1: {0}})
    assert check_ltl(k, ("F", ("ap", 0)), k.props(1)).holds is False
    weak = [(lambda s: 1 in k.succ[s] and s != 1, lambda label: label == "0->1")]
    assert check_ltl(k, ("F", ("ap", 0)), k.props(1), weak_fairness=weak).holds
