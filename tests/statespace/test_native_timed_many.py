"""Many random timed nets, the native timed search against the Python search: the graphs must be the same
(states under the same ids, arcs in the same order, binding elements, dead markings), with and without
time condensation, with and without priorities. The native timed search leaves a net that reads the clock
(`intTime()`) to Python, so its reads are the constant 0 here. Each net compiles its own C (about 0.7 s),
so the suite runs a few beyond those of test_native_timed_c; `CPN_DIFFERENTIAL_NETS=300 pytest
tests/statespace/test_native_timed_many.py` runs 300: at 02c8714 the 600 searches of each kind (300 nets, with
and without condensation) gave the same graphs, in 5 min 26 s wall, 103 s user, at load 5 to 6."""

import os

import cpn
from tests.engine.randomnets import random_timed_net
from tests.statespace.test_native_timed_c import _both, _with_priorities, _without_clock, needs_native

NETS = int(os.environ.get("CPN_DIFFERENTIAL_NETS", "6"))
FIRST = 1000  # seeds apart from those of test_native_timed_c


@needs_native
def test_many_random_timed_nets_the_native_search_is_the_python_search():
    compared = wholly = 0
    for seed in range(FIRST, FIRST + NETS):
        text = _without_clock(random_timed_net(seed))
        if seed % 3 == 0:
            text = _with_priorities(text, seed)
        model = cpn.loads(text, f"timed{seed}.cpnet")
        code, why = model.engine().timed_groups().native_code()
        assert why is None, (seed, why)
        for condensation in (False, True):
            try:
                _both(model, condensation, limit=300)
            except AssertionError as exc:
                raise AssertionError(f"C and Python differ on random timed net {seed} (condensation "
                                     f"{condensation}):\n{text}\n{exc}") from None
        compared += 1
        wholly += not code.left
    assert compared == NETS and wholly == NETS  # every net of the generator is wholly in C
