"""Small helpers with no domain knowledge."""

from __future__ import annotations

import difflib


def did_you_mean(name: str, candidates, cutoff: float = 0.75) -> str | None:
    """The closest candidate to `name`, if one is close enough to be worth suggesting."""
    cands = list(candidates)
    lower = {c.lower(): c for c in cands}
    if name.lower() in lower and lower[name.lower()] != name:
        return lower[name.lower()]
    match = difflib.get_close_matches(name, cands, n=1, cutoff=cutoff)
    return match[0] if match else None
