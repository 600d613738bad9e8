"""cpn-verify: verify protocol designs with timed, hierarchical Coloured Petri Nets.

The public door: every name the README and docs/*.md use from Python is here, in `__all__`
(tests/test_public_api.py reads the documents and checks it). The reports' names (`build_report`,
`render_text`, `to_json`, `Report`) are imported when first used, so that `import cpn` does not load the
renderers.

>>> import cpn
>>> m = cpn.loads("colset U = unit; place A : U = 1`(); place B : U; trans t; arc A -> t; arc t -> B;")
>>> e = m.engine()
>>> [e.format_binding_element(be) for be, _ in e.successors(e.initial_state())]
["Top't 1: {}"]
>>> x = cpn.Explorer(e, cpn.ExploreOptions()).run()
>>> x.n_states, x.complete, cpn.render_text(cpn.build_report(x)).splitlines()[0]
(2, True, 'CPN Tools state space report for:')
"""

from cpn.checks import Evidence, Status, Verdict
from cpn.diagnostics import Diagnostic, Span
from cpn.engine import Engine, compile_net
from cpn.errors import (
    ConfigurationError,
    CpnError,
    EvaluationError,
    ModelError,
    ModelSyntaxError,
)
from cpn.gate import PropertyResult, RunResult, Scenario, check, load_scenario, loads_scenario, run_scenario
from cpn.lang.parser import parse
from cpn.model import Model, load, loads
from cpn.net import Net
from cpn.statespace import Exploration, ExploreOptions, Explorer, StopReason, Trace, replay, shortest_trace

__version__ = "0.1.0"

# name -> the module that defines it, imported on first use (PEP 562)
_LATER = {"Report": "cpn.report", "build_report": "cpn.report", "render_text": "cpn.report", "to_json": "cpn.report"}


def __getattr__(name: str):
    module = _LATER.get(name)
    if module is None:
        raise AttributeError(f"module 'cpn' has no attribute '{name}'")
    import importlib

    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LATER))


__all__ = [
    # models: load, parse, the net and its engine
    "Engine", "Model", "Net", "compile_net", "load", "loads", "parse",
    # exploring a state space, and its report
    "Exploration", "Explorer", "ExploreOptions", "Report", "StopReason", "Trace", "build_report", "render_text",
    "replay", "shortest_trace", "to_json",
    # scenario files and their verdicts
    "Evidence", "PropertyResult", "RunResult", "Scenario", "Status", "Verdict", "check", "load_scenario",
    "loads_scenario", "run_scenario",
    # errors and diagnostics
    "ConfigurationError", "CpnError", "Diagnostic", "EvaluationError", "ModelError", "ModelSyntaxError", "Span",
    "__version__",
]
