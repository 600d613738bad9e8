"""LTL atoms over the step that leaves a position (`check_ltl(..., step_propositions=...)`, the binding
elements that occur): random formulas on random small systems against the lassos of the system."""

from __future__ import annotations

import random

import pytest

from cpn.checks.ltl import check_ltl
from tests.checks.test_ltl import Kripke, lasso_path, random_kripke
from tests.checks.test_ltl_buchi import holds_on_lasso, random_formula
from tests.checks.test_ltl_strong import all_lassos


def step_word(k: Kripke, states: list, nxt: list, tests: list) -> list:
    """The letters of the positions `states`, each followed by the state in `nxt`: the state's propositions
    (0, 1) and the step's (2 + j when tests[j] accepts its label, None for a dead state's stutter)."""
    out = []
    for s, t in zip(states, nxt):
        label = f"{s}->{t}" if t in k.succ[s] else None
        out.append(k.labels[s] | {2 + j for j, test in enumerate(tests) if label is not None and test(label)})
    return out


@pytest.mark.parametrize("seed", range(5))
def test_step_atoms_against_the_lassos_of_the_system(seed):
    rng = random.Random(1300 + seed)
    violated = held = 0
    for _ in range(60):
        k = random_kripke(rng, rng.randrange(1, 5), 2)
        f = random_formula(rng, 3, 3)  # atom 2 is the step atom
        t = rng.randrange(len(k.succ))
        tests = [lambda label, t=t: label.endswith(f"->{t}")]
        res = check_ltl(k, f, k.props(2), step_propositions=tests)
        if res.holds:
            held += 1
            for p, c in all_lassos(k, 6):
                ring = p + c + c[:1]
                word = step_word(k, ring[:-1], ring[1:], tests)
                assert holds_on_lasso(f, word[:len(p)], word[len(p):]), (f, k.succ, k.labels, t, p, c)
            continue
        violated += 1
        states, cycle = lasso_path(k, res)
        ring = states + cycle
        word = step_word(k, ring[:-1], ring[1:], tests)
        assert not holds_on_lasso(f, word[:len(states) - 1], word[len(states) - 1:]), (f, k.succ, t, res)
    assert violated and held


def test_a_step_atom_reads_the_step_that_leaves_the_position():
    # 0 -> 1 -> 1 ...: the first step moves to 1, then 1 -> 1 forever
    k = Kripke({0: [1], 1: [1]}, {0: set(), 1: set()})
    to_1 = [lambda label: label.endswith("->1")]
    assert check_ltl(k, ("G", ("ap", 0)), [], step_propositions=to_1).holds
    leave_0 = [lambda label: label.startswith("0->")]
    assert check_ltl(k, ("ap", 0), [], step_propositions=leave_0).holds
    assert check_ltl(k, ("X", ("ap", 0)), [], step_propositions=leave_0).holds is False
    # a dead state's stutter step satisfies no step atom
    dead = Kripke({0: [1], 1: []}, {0: set(), 1: set()})
    assert check_ltl(dead, ("F", ("G", ("not", ("ap", 0)))), [], step_propositions=to_1).holds
