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
                "TC": lambda: " ++ ".join(f"(1`{rng.randint(0, 2)}@+{rng.randint(0, 3)})" for _ in range(rng.randint(0, 2)))}[k]()
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
        at = len(lines)
        lines.append("")
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
                v = f"if b then 1`({value(k)}) else empty"
            lines.append(f"arc t{t} -> {name} : {v};")
        if not any(k == "TC" for _, k in outs):
            delay = ""  # a transition delay without a timed output place is an error (E0301)
        lines[at] = f"trans t{t} {guard}{delay}{prio};"
    return "\n".join(lines) + "\n"


TIMED_HEADER = """colset C = int with 0..2;
colset U = unit;
colset TC = int with 0..2 timed;
colset TU = unit timed;
colset TP = product C * C timed;
colset B = bool;
var x, y : C;
var b : B;
fun nx(v) = (v + 1) mod 3;
fun tm(u) = intTime() mod 3;
"""

TIMED_KINDS = ("TC", "TU", "TP")


def random_timed_net(seed: int, preempt: bool = False) -> str:
    """A random timed net using every timed construct of the language: timed colour sets (int, unit,
    product), initial-marking delays, transition delays and output-arc delays (constant or reading the
    clock), `intTime()` in guards, input and output inscriptions, delays and priorities (directly and
    through a function), double, inhibitor and reset arcs on timed places, delayed conditional and summed
    outputs, and priorities. About half of the nets read the clock. With `preempt`, about half of the input
    arcs of timed places have a delay `e @+ k` (CPN Tools' preemption; a number or a `val`); without it the
    nets are those of the seeds before input delays existed."""
    rng = random.Random(seed)
    clock = rng.random() < 0.5  # whether intTime() may appear at all
    lines = [TIMED_HEADER + ("val K = 2;\n" if preempt else "")]
    places = []

    def d():
        return rng.choice(["", "", f"@+{rng.randint(1, 4)}"])

    for i in range(rng.randint(2, 4)):
        k = rng.choice(["C", "U"] + list(TIMED_KINDS) * 2) if i else rng.choice(TIMED_KINDS)
        places.append((f"p{i}", k))
        init = {"C": lambda: " ++ ".join(f"{rng.randint(1, 2)}`{rng.randint(0, 2)}" for _ in range(rng.randint(0, 2))),
                "U": lambda: f"{rng.randint(0, 2)}`()",
                "TC": lambda: " ++ ".join(f"(1`{rng.randint(0, 2)}{d()})" for _ in range(rng.randint(0, 3))),
                "TU": lambda: " ++ ".join(f"({rng.randint(1, 2)}`(){d()})" for _ in range(rng.randint(0, 2))),
                "TP": lambda: " ++ ".join(f"(1`({rng.randint(0, 2)},{rng.randint(0, 2)}){d()})"
                                          for _ in range(rng.randint(0, 2)))}[k]()
        lines.append(f"place p{i} : {k}" + (f" = {init}" if init else "") + ";")

    def now(mod=3):
        return rng.choice(["(intTime() mod 3)", "tm()"]) if mod == 3 else "(intTime() mod 2)"

    def pattern(k):
        if k in ("U", "TU"):
            return "()"
        if k in ("C", "TC"):
            choices = ["x", "y", "x", str(rng.randint(0, 2))]
            return rng.choice(choices + ([now()] if clock else []))
        choices = ["(x, y)", "(x, x)", f"(x, {rng.randint(0, 2)})", "(y, x)"]
        return rng.choice(choices + (["(x, intTime() mod 3)"] if clock else []))

    def value(k):
        if k in ("U", "TU"):
            return "()"
        if k in ("C", "TC"):
            return rng.choice(["x", "y", "nx(x)", "(x + y) mod 3", "0"] + ([now()] if clock else []))
        return rng.choice(["(x, y)", "(nx(x), y)", "(y, x)"] + (["(x, intTime() mod 3)"] if clock else []))

    def delay():
        return rng.choice([str(rng.randint(0, 3))] * 3 + ([now(), now(2)] if clock else []))

    guards = ["", "", "[x <> y]", "[x = nx(y)]", "[b]", "[x <= y]"]
    if clock:
        k = rng.randint(1, 6)
        guards += [f"[intTime() < {k}]", f"[intTime() >= {k}]", "[x <= intTime()]", "[(intTime() mod 2) = 0]",
                   "[tm() <> x]", f"[b orelse intTime() > {k}]"]
    for t in range(rng.randint(1, 4)):
        outs = rng.sample(places, k=rng.randint(1, min(2, len(places))))
        guard = rng.choice(guards)
        # a transition delay only where every output place is timed (a delay into an untimed place is an error)
        tdelay = f" @+ {delay()}" if all(k in TIMED_KINDS for _, k in outs) and rng.random() < 0.4 else ""
        prio = ""
        if rng.random() < 0.3:
            prio = " priority " + rng.choice(["500", "1000", "2000"] + (["(intTime() mod 2) * 1000"] if clock else []))
        lines.append(f"trans t{t} {guard}{tdelay}{prio};")
        for name, k in rng.sample(places, k=rng.randint(1, min(3, len(places)))):
            kind = rng.choice(["->", "->", "->", "<->", "<->", "inhibitor", "reset"])
            pat = pattern(k)
            if kind == "->":
                early = ""
                if preempt and k in TIMED_KINDS and rng.random() < 0.5:
                    early = f" @+ {rng.choice(['0', '1', '2', '3', '5', 'K', '(K + 1)'])}"
                lines.append(f"arc {name} -> t{t} : {rng.choice(['', '', '2`'])}{pat}{early};")
            elif kind == "<->":
                lines.append(f"arc {name} <-> t{t} : {pat};")
            elif kind == "inhibitor":
                lines.append(f"inhibitor {name} -> t{t}" + (f" : {pat}" if rng.random() < 0.5 else "") + ";")
            else:
                lines.append(f"reset {name} -> t{t};")
        for name, k in outs:
            v = value(k)
            timed = k in TIMED_KINDS
            r = rng.random()
            if r < 0.15:
                v = f"if b then 1`({value(k)}) else empty"
            elif r < 0.25 and timed:
                v = f"1`({value(k)}) ++ 1`({value(k)})"
            if timed and rng.random() < 0.6:
                v = f"({v}) @+ {delay()}"
            lines.append(f"arc t{t} -> {name} : {v};")
    return "\n".join(lines) + "\n"
