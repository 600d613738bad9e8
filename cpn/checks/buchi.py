"""LTL formulas and their translation into generalised Büchi automata.

A formula is a tree of tuples: ``("ap", i)`` (atomic proposition i, a state predicate), ``("true",)``,
``("false",)``, ``("not", f)``, ``("and", f, g)``, ``("or", f, g)``, ``("X", f)``, ``("F", f)``,
``("G", f)``, ``("U", f, g)`` and ``("R", f, g)``. `translate` puts the formula in negation normal form
and builds the automaton with the tableau of Gerth, Peled, Vardi and Wolper ("Simple on-the-fly automatic
verification of linear temporal logic", PSTV 1995): every node of the tableau is a state of the
automaton, labelled by the literals a state of the system must satisfy to enter it; there is one
acceptance set per `U` subformula (the nodes that do not promise it, or fulfil it). An automaton without
`U` has one acceptance set holding every state. Imports the standard library only.

Examples
--------
>>> a = translate(("F", ("ap", 0)))
>>> accepts(a, [set(), set()], [{0}]), accepts(a, [{0}], [set()]), accepts(a, [], [set()])
(True, True, False)
"""

from __future__ import annotations

from dataclasses import dataclass

TRUE = ("true",)
FALSE = ("false",)


# ----------------------------------------------------------------------------- formulas
def nnf(f: tuple, negate: bool = False) -> tuple:
    """f (or not f) in negation normal form over true, false, literals, and, or, X, U and R."""
    op = f[0]
    if op == "true":
        return FALSE if negate else TRUE
    if op == "false":
        return TRUE if negate else FALSE
    if op == "ap":
        return ("not", f) if negate else f
    if op == "not":
        return nnf(f[1], not negate)
    if op in ("and", "or"):
        dual = {"and": "or", "or": "and"}[op] if negate else op
        return (dual, nnf(f[1], negate), nnf(f[2], negate))
    if op == "X":
        return ("X", nnf(f[1], negate))
    if op == "F":  # F g = true U g
        return nnf(("U", TRUE, f[1]), negate)
    if op == "G":  # G g = false R g
        return nnf(("R", FALSE, f[1]), negate)
    if op in ("U", "R"):
        dual = {"U": "R", "R": "U"}[op] if negate else op
        return (dual, nnf(f[1], negate), nnf(f[2], negate))
    raise ValueError(f"unknown LTL operator {op!r}")


def atoms(f: tuple) -> set[int]:
    """The atomic propositions of f."""
    if f[0] == "ap":
        return {f[1]}
    out: set[int] = set()
    for x in f[1:]:
        out |= atoms(x)
    return out


def text(f: tuple, names=None) -> str:
    """The formula as text (`names[i]` for atomic proposition i, else ``p<i>``)."""
    op = f[0]
    if op == "ap":
        return names[f[1]] if names else f"p{f[1]}"
    if op in ("true", "false"):
        return op
    if op == "not":
        return f"!{text(f[1], names)}"
    if op in ("X", "F", "G"):
        return f"{op} {text(f[1], names)}"
    sym = {"and": "&&", "or": "||", "U": "U", "R": "R"}[op]
    return f"({text(f[1], names)} {sym} {text(f[2], names)})"


# ----------------------------------------------------------------------------- automata
@dataclass
class Automaton:
    """A generalised Büchi automaton with labels on states.

    State q may be entered on a system state whose true propositions (a bitmask) contain all of
    `pos[q]` and none of `neg[q]`; `initial` are the states a run may start in (reading the first system
    state), `succ[q]` the states after q; `acc[q]` is the bitmask of the acceptance sets q belongs to, of
    `n_acc` sets (a run is accepting if it visits every set infinitely often).
    """

    pos: list[int]
    neg: list[int]
    initial: list[int]
    succ: list[list[int]]
    acc: list[int]
    n_acc: int

    @property
    def full(self) -> int:
        return (1 << self.n_acc) - 1

    def __len__(self) -> int:
        return len(self.pos)

    def enters(self, q: int, mask: int) -> bool:
        """Whether q may be entered on a system state whose true propositions are `mask`."""
        return mask & self.pos[q] == self.pos[q] and not mask & self.neg[q]


@dataclass
class _Node:
    incoming: set
    new: set
    old: set
    nxt: set


_INIT = -1


def translate(f: tuple) -> Automaton:
    """The generalised Büchi automaton of the formula f (any form: it is put in negation normal form)."""
    g = nnf(f)
    done: list[_Node] = []  # finished tableau nodes; their index is their name

    def expand(node: _Node) -> None:
        while True:
            if not node.new:
                for d in done:
                    if d.old == node.old and d.nxt == node.nxt:
                        d.incoming |= node.incoming
                        return
                done.append(node)
                node = _Node({len(done) - 1}, set(node.nxt), set(), set())
                continue
            h = min(node.new, key=repr)  # a fixed order: the automaton does not depend on the hash seed
            node.new.remove(h)
            if h in node.old:
                continue
            op = h[0]
            if op in ("true", "false", "ap", "not"):
                if h == FALSE or _negation(h) in node.old:
                    return  # contradiction: the node is dropped
                node.old.add(h)
                continue
            if op == "and":
                node.old.add(h)
                node.new |= {h[1], h[2]} - node.old
                continue
            if op == "X":
                node.old.add(h)
                node.nxt.add(h[1])
                continue
            # or, U, R split the node in two
            if op == "or":
                first, first_next, second = {h[1]}, set(), {h[2]}
            elif op == "U":
                first, first_next, second = {h[1]}, {h}, {h[2]}
            else:  # R
                first, first_next, second = {h[2]}, {h}, {h[1], h[2]}
            old = node.old | {h}
            expand(_Node(set(node.incoming), node.new | (first - old), set(old), node.nxt | first_next))
            node = _Node(set(node.incoming), node.new | (second - old), set(old), set(node.nxt))

    expand(_Node({_INIT}, {g}, set(), set()))
    untils = sorted({h for d in done for h in d.old if h[0] == "U"}, key=repr)
    n = len(done)
    pos, neg, acc = [0] * n, [0] * n, [0] * n
    succ: list[list[int]] = [[] for _ in range(n)]
    initial = []
    for q, d in enumerate(done):
        for h in d.old:
            if h[0] == "ap":
                pos[q] |= 1 << h[1]
            elif h[0] == "not":
                neg[q] |= 1 << h[1][1]
        for src in sorted(d.incoming):
            if src == _INIT:
                initial.append(q)
            else:
                succ[src].append(q)
        for k, u in enumerate(untils):
            if u not in d.old or u[2] in d.old:
                acc[q] |= 1 << k
    if not untils:
        return Automaton(pos, neg, initial, succ, [1] * n, 1)
    return Automaton(pos, neg, initial, succ, acc, len(untils))


def _negation(h: tuple) -> tuple:
    if h == TRUE:
        return FALSE
    if h[0] == "not":
        return h[1]
    return ("not", h)


# ----------------------------------------------------------------------------- words
def accepts(a: Automaton, prefix: list, cycle: list) -> bool:
    """Whether the automaton accepts the infinite word prefix cycle cycle ... (each letter the set of
    true propositions; `cycle` not empty): a cycle through every acceptance set in the product of the
    automaton with the lasso, found by brute force (a reference for tests, not for large inputs)."""
    word = [sum(1 << i for i in letter) for letter in list(prefix) + list(cycle)]
    n, loop = len(word), len(prefix)

    def nxt(k: int) -> int:
        return k + 1 if k + 1 < n else loop

    start = [(0, q) for q in a.initial if a.enters(q, word[0])]
    succ = {}
    seen, stack = set(start), list(start)
    while stack:
        k, q = stack.pop()
        out = [(nxt(k), r) for r in a.succ[q] if a.enters(r, word[nxt(k)])]
        succ[(k, q)] = out
        for v in out:
            if v not in seen:
                seen.add(v)
                stack.append(v)
    # an accepting cycle: an SCC (of the reachable product) that is nontrivial and meets every set
    for v in seen:
        comp = {w for w in _reach(succ, v) if v in _reach(succ, w)}
        if any(w in comp for u in comp for w in succ[u]):
            mask = 0
            for _k, q in comp:
                mask |= a.acc[q]
            if mask == a.full:
                return True
    return False


def _reach(succ: dict, v) -> set:
    seen, stack = {v}, [v]
    while stack:
        for w in succ[stack.pop()]:
            if w not in seen:
                seen.add(w)
                stack.append(w)
    return seen


__all__ = ["FALSE", "TRUE", "Automaton", "accepts", "atoms", "nnf", "text", "translate"]
