"""The engine: the successor function of a net, compiled (fast) or interpreted (the reference oracle).

Reads only `cpn.net` and `cpn.values`; the `Engine` protocol is what the layers above use.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from cpn.engine.protocol import Engine

if TYPE_CHECKING:
    from cpn.net import Net


def compile_net(net: Net, time_condensation: bool = False, reference: bool = False) -> Engine:
    """Build the successor function of `net`.

    Parameters
    ----------
    net : Net
        A flattened net (`cpn.load(path).net`).
    time_condensation : bool
        For timed nets: shift every timestamp so that the clock of each state is 0 (docs/semantics.md).
    reference : bool
        The reference interpreter (slow, the tests' oracle) instead of the compiled engine.

    Returns
    -------
    Engine
        The successor function, with the protocol of `cpn.engine.protocol.Engine`.

    Examples
    --------
    >>> import cpn
    >>> net = cpn.loads("colset U = unit; place A : U = 2`(); trans t; arc A -> t;").net
    >>> engine = compile_net(net)
    >>> [engine.token_counts(s) for _, s in engine.successors(engine.initial_state())]
    [(1,)]
    """
    if reference:
        from cpn.engine.reference import ReferenceEngine

        return ReferenceEngine(net, time_condensation=time_condensation)
    from cpn.engine.compiled import CompiledEngine

    return CompiledEngine(net, time_condensation=time_condensation)


__all__ = ["Engine", "compile_net"]
