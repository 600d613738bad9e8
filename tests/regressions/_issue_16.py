"""Helpers of the issue 16 regression tests: the small models beside them and their state-space figures."""

import os

import cpn
from cpn.statespace.explore import Explorer
from cpn.statespace.options import ExploreOptions

MODELS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "issue_16")


def model_path(name: str) -> str:
    return os.path.join(MODELS, name)


def figures(name: str, reference: bool = False, **options) -> tuple[int, int, int]:
    """(nodes, arcs, dead markings) of the state space of a model beside this file."""
    return engine_figures(cpn.load(model_path(name)).engine(reference=reference), **options)


def engine_figures(engine, **options) -> tuple[int, int, int]:
    """(nodes, arcs, dead markings) of the state space of an engine."""
    result = Explorer(engine, ExploreOptions(**options)).run()
    g = result.graph
    dead = sum(1 for i in range(g.expanded) if g.offsets[i] == g.offsets[i + 1])
    return result.n_states, result.n_arcs, dead
