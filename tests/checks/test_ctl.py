"""CTL labelling against a brute-force fixpoint evaluator on random hand-made graphs.

The brute force evaluates every operator by the fixpoint characterisations (Emerson-Lei for the fair
EG), iterating to stability with no SCC decomposition: a different algorithm from `cpn.checks.ctl`.
"""

import random
from array import array

from hypothesis import given, settings
from hypothesis import strategies as st

from cpn.checks.ctl import And, Atom, Kripke, Not, Or, Temporal


def graph(rng, n, p_arc=0.25, n_labels=3):
    succ = [[(rng.randrange(n_labels), v) for v in range(n) if rng.random() < p_arc] for _ in range(n)]
    offsets, dst, labels = array("q", [0]), array("i"), array("i")
    for arcs in succ:
        for lab, v in arcs:
            dst.append(v)
            labels.append(lab)
        offsets.append(len(dst))
    return succ, offsets, dst, labels


class Brute:
    def __init__(self, succ, fairness):
        self.succ = succ
        self.n = len(succ)
        self.fairness = fairness
        self.fair = self.eg(set(range(self.n))) if fairness else set(range(self.n))

    def ex(self, s):
        s = s & self.fair
        return {u for u in range(self.n) if any(v in s for _, v in self.succ[u])}

    def eu(self, a, b):
        z = b & self.fair
        while True:
            nz = z | {u for u in a if any(v in z for _, v in self.succ[u])}
            if nz == z:
                return z
            z = nz

    def eu_plain(self, a, b):
        z = set(b)
        while True:
            nz = z | {u for u in a if any(v in z for _, v in self.succ[u])}
            if nz == z:
                return z
            z = nz

    def eg(self, phi):
        dead = {u for u in range(self.n) if not self.succ[u]}
        finite = self.eu_plain(phi, phi & dead)
        z = set(phi)
        while True:
            if self.fairness:
                nz = set(phi)
                for f in self.fairness:
                    into = {u for u in range(self.n) if any(lab in f and v in z for lab, v in self.succ[u])}
                    nz &= self.eu_plain(phi, phi & into)
            else:
                nz = {u for u in phi if any(v in z for _, v in self.succ[u])}
            if nz == z:
                break
            z = nz
        return z | finite

    def sat(self, f, atoms):
        all_ = set(range(self.n))
        if isinstance(f, Atom):
            return atoms[f.index]
        if isinstance(f, Not):
            return all_ - self.sat(f.arg, atoms)
        if isinstance(f, And):
            return self.sat(f.left, atoms) & self.sat(f.right, atoms)
        if isinstance(f, Or):
            return self.sat(f.left, atoms) | self.sat(f.right, atoms)
        a = [self.sat(x, atoms) for x in f.args]
        op = f.op
        if op in ("EXB", "AXB"):
            target = (a[0] if op == "EXB" else all_ - a[0]) & self.fair
            some = {u for u in range(self.n) if any(f.arcs(lab) and v in target for lab, v in self.succ[u])}
            return some if op == "EXB" else all_ - some
        if op == "EX":
            return self.ex(a[0])
        if op == "AX":
            return all_ - self.ex(all_ - a[0])
        if op == "EF":
            return self.eu(all_, a[0])
        if op == "AG":
            return all_ - self.eu(all_, all_ - a[0])
        if op == "EG":
            return self.eg(a[0])
        if op == "AF":
            return all_ - self.eg(all_ - a[0])
        if op == "EU":
            return self.eu(a[0], a[1])
        if op == "AU":
            nb = all_ - a[1]
            return all_ - (self.eu(nb, nb - a[0]) | self.eg(nb))
        raise AssertionError(op)


def formula(rng, depth, n_atoms):
    if depth == 0 or rng.random() < 0.2:
        return Atom(rng.randrange(n_atoms))
    k = rng.randrange(8)
    if k == 0:
        return Not(formula(rng, depth - 1, n_atoms))
    if k == 1:
        return And(formula(rng, depth - 1, n_atoms), formula(rng, depth - 1, n_atoms))
    if k == 2:
        return Or(formula(rng, depth - 1, n_atoms), formula(rng, depth - 1, n_atoms))
    op = rng.choice(["EX", "AX", "EF", "AF", "EG", "AG", "EU", "AU", "EXB", "AXB"])
    if op in ("EXB", "AXB"):
        labels = frozenset(rng.sample(range(3), rng.randint(1, 2)))
        return Temporal(op, (formula(rng, depth - 1, n_atoms),), labels.__contains__)
    if op in ("EU", "AU"):
        return Temporal(op, (formula(rng, depth - 1, n_atoms), formula(rng, depth - 1, n_atoms)))
    return Temporal(op, (formula(rng, depth - 1, n_atoms),))


@settings(max_examples=150, deadline=None)
@given(st.integers(0, 10**9), st.integers(1, 9), st.sampled_from([0.1, 0.25, 0.5]), st.integers(0, 2))
def test_labelling_matches_brute_force(seed, n, p_arc, n_fair):
    rng = random.Random(seed)
    succ, offsets, dst, labels = graph(rng, n, p_arc)
    fairness = [set(rng.sample(range(3), rng.randint(1, 2))) for _ in range(n_fair)]
    k = Kripke(n, offsets, dst, labels, fairness)
    brute = Brute(succ, fairness)
    atom_sets = [{u for u in range(n) if rng.random() < 0.5} for _ in range(3)]
    atoms = [bytearray(1 if u in s else 0 for u in range(n)) for s in atom_sets]
    for _ in range(6):
        f = formula(rng, 3, 3)
        memo = {}
        got = {u for u in range(n) if k.label(f, atoms, memo)[u]}
        assert got == brute.sat(f, atom_sets), f
        # a counterexample or witness is a real path of the graph; a lasso ends where its cycle starts
        for start in range(n):
            value = start in got
            path, cycle = k.explain(f, atoms, start, value, memo)
            assert path[0] == start
            for u, v in zip(path, path[1:]):
                assert any(w == v for _, w in succ[u])
            prev = path[-1]
            for v in cycle:
                assert any(w == v for _, w in succ[prev])
                prev = v
            if cycle:
                assert cycle[-1] == path[-1]
                arcs = k.last_cycle_arcs
                assert len(arcs) == len(cycle)
                states = [path[-1], *cycle]
                for fset in fairness:  # the cycle takes an arc of every fairness set
                    assert any(
                        (labels[a] in fset) if a >= 0 else any(lab in fset and w == v for lab, w in succ[u])
                        for a, u, v in zip(arcs, states, states[1:]))


def test_lasso_is_a_fair_cycle():
    # 0 -a-> 1, 1 -b-> 0, 1 -c-> 1: with fairness {a} the self-loop c alone is not a fair cycle
    offsets, dst, labels = array("q", [0, 1, 3]), array("i", [1, 0, 1]), array("i", [0, 1, 2])
    k = Kripke(2, offsets, dst, labels, [{0}])
    stem, cycle = k.lasso(0, bytearray([1, 1]))
    assert cycle and cycle[-1] == stem[-1]
    states = [stem[-1], *cycle]
    assert any(u == 0 and v == 1 for u, v in zip(states, states[1:]))  # the only arc labelled a
    # without the arc a inside the sub-graph, no fair path stays in {1} forever
    assert k.lasso(1, bytearray([0, 1])) is None


def test_dead_states_end_maximal_paths():
    # 0 -> 1, 1 dead: EG p holds at 0 when p holds at 0 and 1 (a finite maximal path); AX false holds at 1
    k = Kripke(2, array("q", [0, 1, 1]), array("i", [1]), array("i", [0]))
    assert list(k.label(Temporal("EG", (Atom(0),)), [bytearray([1, 1])])) == [1, 1]
    assert list(k.label(Temporal("AX", (Atom(0),)), [bytearray([0, 0])])) == [0, 1]
    assert list(k.label(Temporal("EX", (Atom(0),)), [bytearray([1, 1])])) == [1, 0]


def test_labelling_stops_at_its_deadline_before_a_temporal_operator():
    import time

    from cpn.checks.ctl import OutOfTime

    k = Kripke(2, array("q", [0, 1, 1]), array("i", [1]), array("i", [0]))
    atoms = [bytearray([0, 1])]
    k.deadline = time.monotonic() - 1
    assert k.label(Not(Atom(0, "p")), atoms) == bytearray([1, 0])  # no operator over the graph: answered
    try:
        k.label(Temporal("EF", (Atom(0, "p"),)), atoms)
    except OutOfTime as exc:
        assert "EF" in str(exc)
    else:
        raise AssertionError("a passed deadline did not stop the labelling")
    k.deadline = time.monotonic() + 60
    assert k.label(Temporal("EF", (Atom(0, "p"),)), atoms) == bytearray([1, 1])
