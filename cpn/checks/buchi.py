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


def simplify(f: tuple) -> tuple:
    """A formula in negation normal form rewritten by laws that keep its meaning and shrink its
    automaton: constants folded, ``a U F b = F b``, ``a R G b = G b``, ``F G F b = G F b``,
    ``G F G b = F G b``, ``a U a = a`` and ``a R a = a``."""
    op = f[0]
    if op in ("true", "false", "ap", "not"):
        return f
    args = [simplify(x) for x in f[1:]]
    if op == "X":
        a = args[0]
        return a if a in (TRUE, FALSE) else ("X", a)
    a, b = args
    if op == "and":
        if FALSE in (a, b):
            return FALSE
        return b if a == TRUE or a == b else a if b == TRUE else ("and", a, b)
    if op == "or":
        if TRUE in (a, b):
            return TRUE
        return b if a == FALSE or a == b else a if b == FALSE else ("or", a, b)
    if a == b or b in (TRUE, FALSE):
        return b
    if op == "U":
        if a == FALSE:
            return b
        if b[0] == "U" and b[1] == TRUE:  # a U F c = F c
            return b
        if a == TRUE and b[0] == "R" and b[1] == FALSE and b[2][0] == "U" and b[2][1] == TRUE:
            return b  # F G F c = G F c
        return ("U", a, b)
    if a == TRUE:
        return b
    if b[0] == "R" and b[1] == FALSE:  # a R G c = G c
        return b
    if a == FALSE and b[0] == "U" and b[1] == TRUE and b[2][0] == "R" and b[2][1] == FALSE:
        return b  # G F G c = F G c
    return ("R", a, b)


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
    """A generalised Büchi automaton with labels and acceptance sets on its edges.

    A state is what the run still promises about the present and the future (the tableau's obligations).
    `edges[q]` lists (pos, neg, acc, r): from state q, a system state whose true propositions (a bitmask)
    contain all of `pos` and none of `neg` may be read, moving to state r; `acc` is the bitmask of the
    acceptance sets the edge belongs to, of `n_acc` sets (a run is accepting if it takes an edge of every
    set infinitely often). Runs start in `initial`.
    """

    edges: list[list[tuple[int, int, int, int]]]
    initial: int
    n_acc: int

    @property
    def full(self) -> int:
        return (1 << self.n_acc) - 1

    def __len__(self) -> int:
        return len(self.edges)

    def moves(self, q: int, mask: int) -> list[tuple[int, int]]:
        """(acceptance sets, next state) of the edges from q that read a state with propositions `mask`."""
        return [(acc, r) for pos, neg, acc, r in self.edges[q] if mask & pos == pos and not mask & neg]


@dataclass
class _Node:
    incoming: set
    new: set
    old: set
    nxt: set


_INIT = -1


def translate(f: tuple) -> Automaton:
    """The generalised Büchi automaton of the formula f (any form: it is put in negation normal form and
    simplified)."""
    g = simplify(nnf(f))
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
    # a state per distinct obligation set: a node expands the obligations its predecessors left
    states: dict = {frozenset({g}): 0}
    for d in done:
        states.setdefault(frozenset(d.nxt), len(states))
    edges: list[set] = [set() for _ in states]
    for d in done:
        pos = neg = acc = 0
        for h in d.old:
            if h[0] == "ap":
                pos |= 1 << h[1]
            elif h[0] == "not":
                neg |= 1 << h[1][1]
        for k, u in enumerate(untils):
            if u not in d.old or u[2] in d.old:
                acc |= 1 << k
        if not untils:
            acc = 1
        target = states[frozenset(d.nxt)]
        for src in d.incoming:
            q = 0 if src == _INIT else states[frozenset(done[src].nxt)]
            edges[q].add((pos, neg, acc, target))
    return _prune(Automaton([sorted(e) for e in edges], 0, max(1, len(untils))))


def _prune(a: Automaton) -> Automaton:
    """The automaton without the states from which no accepting cycle can be reached (no accepting run
    goes through them), nor the edges into them."""
    n = len(a)
    succ = [{e[3] for e in a.edges[q]} for q in range(n)]
    reach = [{q} for q in range(n)]
    changed = True
    while changed:  # transitive closure: automata are small
        changed = False
        for q in range(n):
            more = set().union(*(reach[r] for r in succ[q])) if succ[q] else set()
            if not more <= reach[q]:
                reach[q] |= more
                changed = True
    good: set = set()
    for q in range(n):
        comp = {r for r in reach[q] if q in reach[r]}
        mask = 0
        for u in comp:
            for _p, _n, acc, r in a.edges[u]:
                if r in comp:
                    mask |= acc
        if mask == a.full:
            good |= comp
    useful = [bool(reach[q] & good) for q in range(n)]
    return Automaton([[e for e in a.edges[q] if useful[e[3]]] if useful[q] else [] for q in range(n)], a.initial,
                     a.n_acc)


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

    start = (0, a.initial)
    succ: dict = {}
    seen, stack = {start}, [start]
    while stack:
        k, q = stack.pop()
        out = [(acc, (nxt(k), r)) for acc, r in a.moves(q, word[k])]
        succ[(k, q)] = out
        for _acc, v in out:
            if v not in seen:
                seen.add(v)
                stack.append(v)
    plain = {v: [w for _acc, w in out] for v, out in succ.items()}
    for v in seen:
        comp = {w for w in _reach(plain, v) if v in _reach(plain, w)}
        mask = 0
        for u in comp:
            for acc, w in succ[u]:
                if w in comp:
                    mask |= acc
        if mask == a.full and any(w in comp for u in comp for w in plain[u]):
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
