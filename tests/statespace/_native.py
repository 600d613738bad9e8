"""What the tests of the generated C's colour sets share: both searches of one net, and one error both ways."""

import pytest

from cpn.errors import EvaluationError
from cpn.statespace import ExploreOptions, Explorer
from tests.engine._explore import same_exploration


def both_searches(engine_c, engine_py, limit: int = 3000):
    """The C search of `engine_c`, after checking it found the Python search's graph of `engine_py`."""
    c = Explorer(engine_c, ExploreOptions(backend="c", max_states=limit)).run()
    py = Explorer(engine_py, ExploreOptions(backend="python", max_states=limit, packed_states=False)).run()
    assert c.backend == "c" and py.backend == "python"
    same_exploration(c, py)
    return c


def net_code(model):
    """(the net's generated C, why there is none), as the native search makes it: a timed net's from its
    transition groups."""
    engine = model.engine()
    return engine.timed_groups().native_code() if engine.is_timed else engine.native_code()


def wholly_in_c(model) -> None:
    """Check that the generated C of `model` leaves no transition to the engine."""
    code, why = net_code(model)
    assert why is None and code.left == {}, (why, code and code.left)


def same_error(model, max_states: int = 1000) -> str:
    """The error of `model`'s C search, the same as the Python search's."""
    errors = []
    for backend in ("c", "python"):
        with pytest.raises(EvaluationError) as got:
            Explorer(model.engine(), ExploreOptions(backend=backend, max_states=max_states)).run()
        errors.append(str(got.value))
    assert errors[0] == errors[1], errors
    return errors[0]
