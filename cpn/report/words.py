"""Wording helpers of the reports, public so that the command line words its messages the same way
(`noun`). Standard library only."""

from __future__ import annotations


def noun(n: int, singular: str, plural: str | None = None) -> str:
    """`singular` for one, `plural` (default: singular + 's') otherwise: "1 step", "2 steps".

    >>> f"{3} {noun(3, 'step')}", f"{1} {noun(1, 'step')}"
    ('3 steps', '1 step')
    """
    return singular if n == 1 else (plural or singular + "s")
