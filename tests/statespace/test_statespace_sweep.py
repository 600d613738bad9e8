"""The sweep-line method gives the full search's counts, dead markings and bounds on
random timed nets and the repository's timed models; regress arcs are detected and handled."""

import os

import pytest

import cpn
from cpn.checks.columns import place_markings
from cpn.errors import ConfigurationError
from cpn.statespace import ExploreOptions, Explorer, StopReason
from cpn.statespace.sweep import SweepLine
from tests.engine.randomnets import random_timed_net

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# the random timed nets with a finite state space have at most 256 states (seeds 0..59): a search that
# passes LIMIT finds one without end, and costs LIMIT states (3,000 took 14 s of the test's 15)
LIMIT = 500


def _full_figures(engine, x):
    """(states, arcs, dead markings, integer bounds, multiset bounds) of a full exploration."""
    states = x.graph.states
    dead = {states[i] for i in x.graph.dead_states()}
    bounds, upper, lower = [], [], []
    for marks in place_markings(engine, list(states)):
        counts = [n for _k, _ms, n in marks]
        bounds.append([max(counts), min(counts)])
        up: dict = {}
        lo = dict(marks[0][1])
        for _k, ms, _n in marks:
            for v, k in ms.items():
                up[v] = max(up.get(v, 0), k)
            lo = {v: min(k, ms.get(v, 0)) for v, k in lo.items() if ms.get(v, 0)}
        upper.append(up)
        lower.append(lo)
    return x.n_states, x.n_arcs, dead, bounds, upper, lower


def _sweep_figures(y):
    return y.states, y.arcs, set(y.dead), y.bounds, y.multiset_upper, y.multiset_lower


def test_random_timed_nets_sweep_equals_full_search():
    compared = 0
    for seed in range(60):
        model = cpn.loads(random_timed_net(seed), f"timed{seed}.cpnet")
        engine = model.engine()
        x = Explorer(engine, ExploreOptions(max_states=LIMIT, backend="python")).run()
        if not x.complete:
            continue  # time or the markings grow without end: nothing to compare with
        y = SweepLine(engine, ExploreOptions(max_states=LIMIT)).run()
        assert y.complete and y.exact and y.regress_arcs == 0, seed
        assert _sweep_figures(y) == _full_figures(engine, x), f"random timed net {seed} differs"
        assert y.peak_states <= y.states
        compared += 1
    assert compared >= 20  # the generator gives finite timed state spaces about half the time


@pytest.mark.parametrize("path", ["models/examples/timer_cancel.cpnet", "tests/statespace/models/timed_merge.cpnet"])
def test_repository_timed_models_sweep_equals_full_search(path):
    model = cpn.load(os.path.join(ROOT, path))
    engine = model.engine()
    x = Explorer(engine, ExploreOptions(max_states=200_000)).run()
    assert x.complete
    y = SweepLine(engine).run()
    assert y.complete and y.exact
    assert _sweep_figures(y) == _full_figures(engine, x)


def test_modbus_timed_scenario_held_states_are_a_fraction():
    values = {"CONFIG": '"A"', "ADRS": "[3,5]", "FCS": "[4,5,7]", "PO": "2"}
    engine = cpn.load(os.path.join(ROOT, "models/modbus/modbus.cpnet"), set=values).engine()
    x = Explorer(engine).run()
    y = SweepLine(engine).run()
    assert (y.states, y.arcs, set(y.dead)) == _full_figures(engine, x)[:3] == (492, 525, set(y.dead))
    assert len(y.dead) == 13 and y.peak_states < y.states // 5


@pytest.mark.parametrize("name", ["B_6", pytest.param("D_2", marks=pytest.mark.slow)])
def test_modbus_timed_scenarios_with_quiet_spells_are_not_cut_short(name):
    # B.6 without condensation has a quiet spell of 34 clock values (no new marking modulo time) before
    # its last states: the time-growth watch must not stop the sweep there
    from cpn.gate.scenario import load_scenario

    scenario = load_scenario(os.path.join(ROOT, "specs", "modbus", f"{name}.toml"))
    engine = cpn.load(scenario.model, set=scenario.runs[0].values).engine()
    x = Explorer(engine).run()
    y = SweepLine(engine).run()
    assert x.complete and y.complete and (y.states, y.arcs, set(y.dead)) == _full_figures(engine, x)[:3]


CYCLE = """colset N = int with 0..3; var x : N; place P : N = 1`0; place Q : N = 1`0;
trans step [x < 3]; arc P -> step : x; arc step -> P : x + 1;
trans back [x = 3]; arc P -> back : x; arc back -> P : 0;
trans out [x = 2]; arc P -> out : x; arc out -> Q : x;"""


def test_regress_arc_is_detected_and_every_state_explored():
    model = cpn.loads(CYCLE)
    engine = model.engine()
    x = Explorer(engine).run()

    def measure(s):  # the value on P: the arc of 'back' (3 -> 0) decreases it
        return max(engine.marking(s)[0] or {-1: 1})

    y = SweepLine(engine, measure=measure, measure_text="P").run()
    assert y.complete and y.regress_arcs >= 1 and not y.exact and y.regress_example[0] > y.regress_example[1]
    assert y.sweeps >= 2 and y.persistent >= 1
    # every state explored at least once: the counts are upper bounds, the dead markings and bounds exact
    assert y.states >= x.n_states and y.arcs >= x.n_arcs
    assert _sweep_figures(y)[2:] == _full_figures(engine, x)[2:]
    assert any("upper bounds" in n for n in y.notes)


def test_a_regress_arc_into_a_deleted_state_is_swept_again():
    # 0 -> 1 -> 2 -> 1: the arc 2 -> 1 regresses to a state deleted behind the sweep-line; a second sweep
    # from it explores 1 and 2 again (both states and their arcs counted twice), nothing is left out
    model = cpn.loads("colset N = int with 0..2; var x : N; place P : N = 1`0;"
                      " trans up [x < 2]; arc P -> up : x; arc up -> P : x + 1;"
                      " trans down [x = 2]; arc P -> down : x; arc down -> P : 1;")
    engine = model.engine()
    y = SweepLine(engine, measure=lambda s: max(engine.marking(s)[0])).run()
    assert (y.states, y.arcs, y.exact, y.sweeps, y.persistent) == (5, 5, False, 2, 1)  # full: 3 states, 3 arcs
    assert Explorer(engine).run().n_states == 3


def test_no_measure_for_untimed_or_condensed_nets():
    with pytest.raises(ConfigurationError, match="untimed"):
        SweepLine(cpn.loads(CYCLE).engine())
    ticker = cpn.load(os.path.join(ROOT, "tests/statespace/models/ticker.cpnet"))
    with pytest.raises(ConfigurationError, match="time condensation"):
        SweepLine(ticker.engine(time_condensation=True), ExploreOptions(time_condensation=True))


@pytest.mark.parametrize("path", ["tests/statespace/models/ticker.cpnet", "models/examples/stop_and_wait.cpnet"])
def test_time_that_grows_for_ever_stops_the_sweep(path):
    # without time condensation these state spaces are infinite: the full search and the sweep-line stop
    # for the same reason (the markings modulo time no longer change), the sweep holding few states
    engine = cpn.load(os.path.join(ROOT, path)).engine()
    assert Explorer(engine, ExploreOptions(max_states=100_000)).run().stop_reason is StopReason.TIME_GROWS
    y = SweepLine(engine, ExploreOptions(max_states=100_000)).run()
    assert y.stop_reason is StopReason.TIME_GROWS and y.peak_states < 50 and y.time_growth


def test_limits_stop_the_sweep_honestly():
    model = cpn.load(os.path.join(ROOT, "models/examples/stop_and_wait.cpnet"))
    y = SweepLine(model.engine(), ExploreOptions(max_states=10)).run()
    assert y.stop_reason is StopReason.MAX_STATES and not y.complete and y.unexpanded > 0
