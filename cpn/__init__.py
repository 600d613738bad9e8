"""cpn-verify: verify protocol designs with timed, hierarchical Coloured Petri Nets.

>>> import cpn
>>> m = cpn.loads("colset U = unit; place A : U = 1`(); place B : U; trans t; arc A -> t; arc t -> B;")
>>> e = m.engine()
>>> [e.format_binding_element(be) for be, _ in e.successors(e.initial_state())]
["Top't 1: {}"]
"""

from cpn.diagnostics import Diagnostic, Span
from cpn.errors import (
    ConfigurationError,
    CpnError,
    EvaluationError,
    ModelError,
    ModelSyntaxError,
)
from cpn.gate.run import check
from cpn.lang.parser import parse
from cpn.model import Model, load, loads
from cpn.net import Net

__version__ = "0.1.0"

__all__ = [
    "ConfigurationError", "CpnError", "Diagnostic", "EvaluationError", "Model", "ModelError", "ModelSyntaxError",
    "Net", "Span", "check", "load", "loads", "parse",
    "__version__",
]
