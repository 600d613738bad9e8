"""Settings of the whole test suite."""

import gc
import os

import pytest

from cpn.cli.main import GC_THRESHOLDS
from tests._shared import HAVE_SHARED, SHARED

# The suite builds many small libraries (one per net whose C it tests), and what the tests check does not
# depend on the optimisation: it builds them without (`-O0`, not the `-O2` users get from
# cpn._util.cbuild.cflags). A library of DP(6) compiled in 0.23 s at -O0 and 0.58 s at -O1 (gcc 12, two runs
# each). Whole runs of the suite from a fresh clone and an empty cache varied more than that difference on
# the same machine: 7 min 14 s and 8 min 45 s at -O0, 8 min 10 s at -O1.
os.environ.setdefault("CPN_CC_OPT", "-O0")

# The garbage collector's thresholds of the command line (cpn.cli.main.GC_THRESHOLDS), for the tests that run
# it in this process: with Python's defaults, full collections walk every model, engine and graph the
# tests of a process keep alive.
gc.set_threshold(*GC_THRESHOLDS)


def pytest_addoption(parser):
    parser.addoption("--slow", action="store_true",
                     help="run the long tests too (marked `slow`; `pytest --slow -m slow` runs only them)")


def pytest_configure(config):
    config.addinivalue_line("markers", "needs_shared: the test reads the shared data (tests/_shared.py)")
    config.addinivalue_line("markers", "slow: a long test, deselected unless --slow is given (README.md)")


def pytest_collection_modifyitems(config, items):
    """Without --slow, the tests marked `slow` are deselected: each repeats on a larger instance what a
    test of the suite checks, or runs what CI's installation check runs (.ci/install-check)."""
    if config.getoption("--slow"):
        return
    slow = [item for item in items if item.get_closest_marker("slow") is not None]
    if slow:
        config.hook.pytest_deselected(items=slow)
        items[:] = [item for item in items if item.get_closest_marker("slow") is None]


@pytest.hookimpl(tryfirst=True)  # before the skip marks, whose empty parameter sets would hide it
def pytest_runtest_setup(item):
    """A test marked `needs_shared` is skipped where the shared data is absent; under CI it fails."""
    if HAVE_SHARED or item.get_closest_marker("needs_shared") is None:
        return
    if os.environ.get("CI", "").lower() in ("1", "true", "yes"):
        pytest.fail(f"the shared test data is missing: {SHARED} does not exist, and CI must have it "
                    "(put the shared folder beside the repository or set CPN_SHARED_DIR)", pytrace=False)
    pytest.skip(f"the shared test data is absent ({SHARED}; set CPN_SHARED_DIR)")
