"""Random small coloured nets that are symmetric in an enumeration `S` (all permutations, or rotations when
`rotations`): only variables, equality tests, `S.all()` and (for rotations) the successor of a value.
Some nets also use a second scalar colour set `R`, all of whose permutations are symmetries."""

from __future__ import annotations

import random

HEADER = """colset S = with a | b | c{extra};
colset R = with r1 | r2;
colset U = unit;
colset SS = product S * S;
colset SR = product S * R;
var x, y : S;
var r : R;
"""


def random_symmetric_net(seed: int, rotations: bool = False) -> str:
    rng = random.Random(seed)
    n = rng.choice([3, 3, 4])
    extra = " | d" if n == 4 else ""
    lines = [HEADER.format(extra=extra)]
    kinds = ["S", "S", "U", "SS", "SR"]
    places = []
    for i in range(rng.randint(2, 5)):
        k = rng.choice(kinds)
        places.append((f"p{i}", k))
        init = {"S": lambda: rng.choice(["", "S.all()", "S.all()", "S.all() ++ S.all()"]),
                "U": lambda: rng.choice(["", "1`()", "2`()"]),
                "SS": lambda: rng.choice(["", "", "SS.all()"]),
                "SR": lambda: rng.choice(["", "SR.all()", "SR.all()"])}[k]()
        lines.append(f"place p{i} : {k}" + (f" = {init}" if init else "") + ";")
    succ = "S.col ((S.ord {v} + 1) mod %d)" % n

    def pattern(k):
        return {"S": rng.choice(["x", "y"]), "U": "()", "SS": rng.choice(["(x, y)", "(y, x)", "(x, x)"]),
                "SR": rng.choice(["(x, r)", "(y, r)"])}[k]

    def value(k):
        s = ["x", "y"] + ([succ.format(v="x")] if rotations else [])
        return {"S": rng.choice(s), "U": "()", "SS": f"({rng.choice(s)}, {rng.choice(s)})",
                "SR": f"({rng.choice(s)}, r)"}[k]

    for t in range(rng.randint(1, 4)):
        guard = rng.choice(["", "", "[x <> y]", "[x = y]"])
        lines.append(f"trans t{t} {guard};")
        consumed = 0  # tokens taken by the transition: it puts back at most as many (a finite state space)
        for name, k in rng.sample(places, k=rng.randint(1, min(3, len(places)))):
            kind = rng.choice(["->", "->", "->", "<->", "inhibitor"])
            pat = pattern(k)
            if kind == "->":
                coef = rng.choice(["", "", "2`"])
                consumed += 2 if coef else 1
                lines.append(f"arc {name} -> t{t} : {coef}{pat};")
            elif kind == "<->":
                lines.append(f"arc {name} <-> t{t} : {pat};")
            else:
                lines.append(f"inhibitor {name} -> t{t}" + (f" : {pat}" if rng.random() < 0.5 else "") + ";")
        for name, k in rng.sample(places, k=min(consumed, rng.randint(1, min(2, len(places))))):
            lines.append(f"arc t{t} -> {name} : {value(k)};")
    return "\n".join(lines) + "\n"
