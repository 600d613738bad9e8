"""The property language: the kinds of property a scenario states (`spec`, `kinds`), property texts and
their compilation against one net and engine (`predicates`), the warnings on properties that hold
vacuously or by the net's structure (`vacuity`, `structure`), and which properties a reduced state space
decides (`reduction`, `symmetry`).

May import cpn.checks (the algorithms the kinds decide with), cpn.statespace, the language and the net;
never the gate (cpn.gate), report or cli.
"""

from cpn.properties.build import build_checks
from cpn.properties.kinds import Check, GraphView
from cpn.properties.predicates import Compiled, PredicateError, PropertyLanguage
from cpn.properties.spec import KINDS, PropertySpec, TextOrigin

__all__ = ["KINDS", "Check", "Compiled", "GraphView", "PredicateError", "PropertyLanguage", "PropertySpec",
           "TextOrigin", "build_checks"]
