"""The engine: the successor function of a net, compiled (fast) or interpreted (the reference oracle)."""

from __future__ import annotations


def compile_net(net, time_condensation: bool = False, reference: bool = False):
    """Build the successor function of `net` (docs/internals.md gives the protocol)."""
    if reference:
        from cpn.engine.reference import ReferenceEngine

        return ReferenceEngine(net, time_condensation=time_condensation)
    from cpn.engine.compiled import CompiledEngine

    return CompiledEngine(net, time_condensation=time_condensation)


__all__ = ["compile_net"]
