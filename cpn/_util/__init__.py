"""Small helpers with no domain knowledge."""

from __future__ import annotations

import difflib


def did_you_mean(name: str, candidates, cutoff: float = 0.75) -> str | None:
    """The closest candidate to `name`, if one is close enough to be worth suggesting: the same name in
    another case, else the closest by spelling, in the same case or, failing that, in any case
    ('intt' -> 'INT').

    >>> did_you_mean("intt", ["INT", "BOOL"]), did_you_mean("Idel", ["Idle", "Busy"]), did_you_mean("x", ["INT"])
    ('INT', 'Idle', None)
    """
    cands = list(candidates)
    lower: dict[str, str] = {}
    for c in cands:
        lower.setdefault(c.lower(), c)
    if name.lower() in lower and lower[name.lower()] != name:
        return lower[name.lower()]
    match = difflib.get_close_matches(name, cands, n=1, cutoff=cutoff)
    if match:
        return match[0]
    match = difflib.get_close_matches(name.lower(), list(lower), n=1, cutoff=cutoff)
    return lower[match[0]] if match else None
