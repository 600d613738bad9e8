"""The scenario gate: scenario files (`scenario`), running a scenario's runs and deciding its properties
(`run`; under the sweep-line method, `sweep`), and mutation testing of a gate (`mutants`, `mutation`).

May import the property language (cpn.properties), cpn.checks, the state space and the model loader;
never report or cli.
"""

from cpn.gate.run import PropertyResult, RunResult, check, run_scenario
from cpn.gate.scenario import Run, Scenario, load_scenario, loads_scenario

__all__ = ["PropertyResult", "Run", "RunResult", "Scenario", "check", "load_scenario", "loads_scenario",
           "run_scenario"]
