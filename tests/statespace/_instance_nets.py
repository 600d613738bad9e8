"""Random small hierarchical nets with one module instantiated once per value of an index colour set `S`
(`module M(me : S)`, instances `M(me = s(k))` on the same sockets): the instances are interchangeable
under every permutation of `S` (or, with `rotations`, under its rotations: a transition may also use the
next instance's value, `S.col ((S.ord me + 1) mod N)`, as a ring does). The module uses its parameter
only through equality and by putting it into tokens; the top page may add a transition over variables."""

from __future__ import annotations

import random

HEADER = """colset S = index s with 1..{n};
colset U = unit;
colset SS = product S * S;
colset INT = int;
var x, y : S;
"""


def random_instance_net(seed: int, rotations: bool = False) -> str:
    rng = random.Random(seed)
    n = rng.choice([2, 3, 3] if not rotations else [3, 3, 4])
    lines = [HEADER.format(n=n)]
    nxt = f"S.col ((S.ord me + 1) mod {n})"
    shared = []
    for i in range(rng.randint(1, 3)):
        k = rng.choice(["S", "S", "U", "SS"])
        init = {"S": rng.choice(["", "", "S.all()"]), "U": rng.choice(["", "1`()"]),
                "SS": rng.choice(["", ""])}[k]
        shared.append((f"g{i}", k))
        lines.append(f"place g{i} : {k}" + (f" = {init}" if init else "") + ";")
    local = []
    body = []
    for i in range(rng.randint(1, 3)):
        k = rng.choice(["U", "U", "S"])
        init = {"U": rng.choice(["1`()", "1`()", ""]), "S": rng.choice(["1`me", "", "S.all()"])}[k]
        local.append((f"l{i}", k))
        body.append(f"  place l{i} : {k}" + (f" = {init}" if init else "") + ";")
    places = [(name, k, True) for name, k in shared] + [(name, k, False) for name, k in local]

    def pattern(k):
        return {"S": rng.choice(["x", "y", "me"]), "U": "()", "SS": rng.choice(["(x, y)", "(me, x)", "(x, me)"])}[k]

    def value(k):
        s = ["x", "me", "me"] + ([nxt] if rotations else [])
        return {"S": rng.choice(s), "U": "()", "SS": f"({rng.choice(s)}, {rng.choice(s)})"}[k]

    for t in range(rng.randint(1, 4)):
        guard = rng.choice(["", "", "[x = me]", "[x <> me]", "[x = y]"])
        body.append(f"  trans t{t} {guard};")
        consumed = 0
        for name, k, _ in rng.sample(places, k=rng.randint(1, min(3, len(places)))):
            kind = rng.choice(["->", "->", "<->"])
            pat = pattern(k)
            if kind == "->":
                consumed += 1
                body.append(f"  arc {name.upper() if name.startswith('g') else name} -> t{t} : {pat};")
            else:
                body.append(f"  arc {name.upper() if name.startswith('g') else name} <-> t{t} : {pat};")
        for name, k, _ in rng.sample(places, k=min(consumed, rng.randint(1, min(2, len(places))))):
            body.append(f"  arc t{t} -> {name.upper() if name.startswith('g') else name} : {value(k)};")
    extra = rng.choice(["", ", w : INT"])
    lines.append(f"module M(me : S{extra}) {{")
    lines += [f"  port io {name.upper()} : {k};" for name, k in shared]
    lines += body
    lines.append("}")
    binds = ", ".join(f"{name.upper()} = {name}" for name, _ in shared)
    for v in range(1, n + 1):
        args = f"me = s({v})" + (", w = 7" if extra else "")
        lines.append(f"instance M{v} = M({args}) {{ {binds} }};")
    if rng.random() < 0.4:  # a top-level transition over variables only
        name, k = shared[0]
        if k == "S":
            lines.append(f"trans top [x <> y]; arc {name} -> top : x; arc top -> {name} : x;")
    return "\n".join(lines) + "\n"
