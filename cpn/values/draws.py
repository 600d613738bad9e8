"""CPN Tools' random distribution functions, for simulation: one seeded generator draws every value.

A net that calls them has no state space (`explore` and `check` refuse it, docs/semantics.md); `simulate`
runs it with the generator seeded by `--seed`, so that one seed gives one run. The names, argument types
and domains are those of CPN Tools' library; a value outside its domain is a run-time error, as CPN Tools
raises an exception there.

>>> use(__import__("random").Random(1)); a = FUNCTIONS["exponential"](0.5)
>>> use(__import__("random").Random(1)); a == FUNCTIONS["exponential"](0.5)
True
>>> 0 <= FUNCTIONS["discrete"]((0, 3)) <= 3
True
"""

from __future__ import annotations

import math
import random

from cpn.values.builtins import MLError

_state = {"rng": random.Random(0)}


def use(rng: random.Random) -> None:
    """Draw every value from now on with `rng` (a `random.Random` seeded by the caller)."""
    _state["rng"] = rng


def _rng() -> random.Random:
    return _state["rng"]


def _domain(ok: bool, name: str, why: str) -> None:
    if not ok:
        raise MLError(f"{name}: {why} (CPN Tools raises the exception {name.capitalize()})")


def _bernoulli(p):
    _domain(0.0 <= p <= 1.0, "bernoulli", f"p = {p} is not a probability from 0.0 to 1.0")
    return 1 if _rng().random() < p else 0


def _binomial(arg):
    n, p = arg
    _domain(n >= 1 and 0.0 <= p <= 1.0, "binomial", f"binomial({n}, {p}) needs n >= 1 and 0.0 <= p <= 1.0")
    r = _rng()
    return sum(1 for _ in range(n) if r.random() < p)


def _discrete(arg):
    a, b = arg
    _domain(a <= b, "discrete", f"discrete({a}, {b}) has no value: a > b")
    return _rng().randint(a, b)


def _poisson(m):
    _domain(m > 0.0, "poisson", f"the intensity {m} is not positive")
    r = _rng()
    total = 0
    while m > 0.0:  # the sum of Poisson draws is a Poisson draw: parts small enough for exp(-part)
        part = min(m, 500.0)
        m -= part
        limit, k, prod = math.exp(-part), 0, r.random()
        while prod > limit:
            k += 1
            prod *= r.random()
        total += k
    return total


def _uniform(arg):
    a, b = arg
    _domain(a <= b, "uniform", f"uniform({a}, {b}) needs a <= b")
    return a + (b - a) * _rng().random()


def _exponential(r):
    _domain(r > 0.0, "exponential", f"the intensity {r} is not positive")
    return _rng().expovariate(r)


def _normal(arg):
    mean, variance = arg
    _domain(variance >= 0.0, "normal", f"the variance {variance} is negative")
    return _rng().gauss(mean, math.sqrt(variance))


def _erlang(arg):
    n, r = arg
    _domain(n >= 1 and r > 0.0, "erlang", f"erlang({n}, {r}) needs n >= 1 and r > 0.0")
    return _rng().gammavariate(float(n), 1.0 / r)


def _gamma(arg):
    lam, k = arg
    _domain(lam > 0.0 and k > 0.0, "gamma", f"gamma({lam}, {k}) needs l > 0.0 and k > 0.0")
    return _rng().gammavariate(k, 1.0 / lam)  # shape k, rate l


def _beta(arg):
    a, b = arg
    _domain(a > 0.0 and b > 0.0, "beta", f"beta({a}, {b}) needs a > 0.0 and b > 0.0")
    return _rng().betavariate(a, b)


def _chisq(n):
    _domain(n >= 1, "chisq", f"{n} degrees of freedom: at least 1")
    return _rng().gammavariate(n / 2.0, 2.0)


def _student(n):
    _domain(n >= 1, "student", f"{n} degrees of freedom: at least 1")
    r = _rng()
    return r.gauss(0.0, 1.0) / math.sqrt(r.gammavariate(n / 2.0, 2.0) / n)


def _weibull(arg):
    lam, k = arg
    _domain(lam > 0.0 and k > 0.0, "weibull", f"weibull({lam}, {k}) needs lambda > 0.0 and k > 0.0")
    return _rng().weibullvariate(lam, k)


def _rayleigh(s):
    _domain(s > 0.0, "rayleigh", f"the parameter {s} is not positive")
    return s * math.sqrt(-2.0 * math.log(1.0 - _rng().random()))


# SML/NJ's structure Random, which CPN ML includes: `Random.rand (i, j)` makes a generator from two seeds (the
# same seeds, the same sequence, as in SML/NJ; the numbers are not SML/NJ's), the others draw from one and
# advance it. A generator is a value of type `rand`.
def _sml_rand(arg):
    a, b = arg
    return random.Random(f"Random.rand({a},{b})")


def _sml_rand_range(arg):
    lo, hi = arg
    _domain(lo <= hi, "randRange", f"Random.randRange ({lo}, {hi}): lo > hi")
    return lambda gen: gen.randint(lo, hi)


# name -> (CPN Tools' type, implementation)
DISTRIBUTIONS: dict[str, tuple[str, object]] = {
    "bernoulli": ("real -> int", _bernoulli),
    "binomial": ("int * real -> int", _binomial),
    "discrete": ("int * int -> int", _discrete),
    "poisson": ("real -> int", _poisson),
    "uniform": ("real * real -> real", _uniform),
    "exponential": ("real -> real", _exponential),
    "normal": ("real * real -> real", _normal),
    "erlang": ("int * real -> real", _erlang),
    "gamma": ("real * real -> real", _gamma),
    "beta": ("real * real -> real", _beta),
    "chisq": ("int -> real", _chisq),
    "student": ("int -> real", _student),
    "weibull": ("real * real -> real", _weibull),
    "rayleigh": ("real -> real", _rayleigh),
    "Random.rand": ("int * int -> rand", _sml_rand),
    "Random.randRange": ("int * int -> rand -> int", _sml_rand_range),
    "Random.randInt": ("rand -> int", lambda gen: gen.randint(-(2 ** 30), 2 ** 30 - 1)),
    "Random.randNat": ("rand -> int", lambda gen: gen.randint(0, 2 ** 30 - 1)),
    "Random.randReal": ("rand -> real", lambda gen: gen.random()),
}

FUNCTIONS: dict[str, object] = {name: fn for name, (_, fn) in DISTRIBUTIONS.items()}


def ran(values: list):
    """One value of a finite colour set's values, drawn (CS.ran() where it is no choice)."""
    return values[_rng().randrange(len(values))]


__all__ = ["DISTRIBUTIONS", "FUNCTIONS", "ran", "use"]
