"""Writing nets as PNML (placeholder until the writer lands)."""

from __future__ import annotations


def write_text(net) -> str:
    raise NotImplementedError


def write(net, path) -> None:
    raise NotImplementedError
