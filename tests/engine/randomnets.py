"""Random small coloured nets, as `.cpnet` text, for differential tests of the two engines."""

from __future__ import annotations

import random

HEADER = """colset C = int with 0..2;
colset U = unit;
colset P = product C * C;
colset TC = int with 0..2 timed;
colset B = bool;
var x, y : C;
var b : B;
fun nx(v) = (v + 1) mod 3;
"""


def random_net(seed: int) -> str:
    rng = random.Random(seed)
    kinds = ["C", "U", "P", "TC"]
    nplaces = rng.randint(2, 5)
    places = []
    lines = [HEADER]
    timed = rng.random() < 0.3
    for i in range(nplaces):
        k = rng.choice(kinds if timed else kinds[:3])
        places.append((f"p{i}", k))
        init = {"C": lambda: " ++ ".join(f"{rng.randint(1, 2)}`{rng.randint(0, 2)}" for _ in range(rng.randint(0, 2))),
                "U": lambda: f"{rng.randint(0, 2)}`()",
                "P": lambda: " ++ ".join(f"1`({rng.randint(0, 2)},{rng.randint(0, 2)})" for _ in range(rng.randint(0, 2))),
                "TC": lambda: " ++ ".join(f"1`{rng.randint(0, 2)}@+{rng.randint(0, 3)}" for _ in range(rng.randint(0, 2)))}[k]()
        lines.append(f"place p{i} : {k}" + (f" = {init}" if init else "") + ";")
    ntrans = rng.randint(1, 4)

    def pattern(k, bound):
        if k == "U":
            return "()"
        if k in ("C", "TC"):
            return rng.choice(["x", "y", "x", str(rng.randint(0, 2))])
        return rng.choice(["(x, y)", "(x, x)", f"(x, {rng.randint(0, 2)})", "(y, x)"])

    def value(k):
        if k == "U":
            return "()"
        if k in ("C", "TC"):
            return rng.choice(["x", "y", "nx(x)", "nx(y)", "(x + y) mod 3", "0"])
        return rng.choice(["(x, y)", "(nx(x), y)", "(y, x)", "(x, 0)"])

    for t in range(ntrans):
        guard = rng.choice(["", "", "[x <> y]", "[x = nx(y)]", "[b]", "[x <= y]"])
        delay = f" @+ {rng.randint(0, 2)}" if timed and rng.random() < 0.3 else ""
        prio = ""
        lines.append(f"trans t{t} {guard}{delay}{prio};")
        used = rng.sample(places, k=rng.randint(1, min(3, len(places))))
        for name, k in used:
            kind = rng.choice(["->", "->", "->", "<->", "inhibitor", "reset"])
            pat = pattern(k, set())
            if kind == "->":
                coef = rng.choice(["", "", "2`"])
                lines.append(f"arc {name} -> t{t} : {coef}{pat};")
            elif kind == "<->":
                lines.append(f"arc {name} <-> t{t} : {pat};")
            elif kind == "inhibitor":
                lines.append(f"inhibitor {name} -> t{t}" + (f" : {pat}" if rng.random() < 0.5 else "") + ";")
            else:
                lines.append(f"reset {name} -> t{t};")
        outs = rng.sample(places, k=rng.randint(1, min(2, len(places))))
        for name, k in outs:
            v = value(k)
            if k == "TC" and rng.random() < 0.5:
                v = f"{v} @+ {rng.randint(0, 3)}"
            if rng.random() < 0.2:
                v = f"if b then 1`{value(k)} else empty"
            lines.append(f"arc t{t} -> {name} : {v};")
    return "\n".join(lines) + "\n"
