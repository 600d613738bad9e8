"""Where the shared test data lives: `../shared` beside the repository (CI's layout), or CPN_SHARED_DIR;
the mark of the tests that read it; and a counter of a method's calls.

A test that reads the shared data carries `needs_shared` (on the test, or as the module's `pytestmark`).
Where the data is absent, tests/conftest.py skips those tests with the reason, except under CI (CI=true),
where they fail: CI must have the data. tests/test_shared_data.py checks that every test reading the shared
data carries the mark.
"""

import os

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.environ.get("CPN_SHARED_DIR") or os.path.normpath(os.path.join(ROOT, "..", "shared"))
#: whether the shared data is there
HAVE_SHARED = os.path.isdir(SHARED)
#: the mark of a test that reads the shared data
needs_shared = pytest.mark.needs_shared


def count_calls(monkeypatch, cls, name: str) -> list[int]:
    """A one-element list counting the calls of method `name` of `cls` from now on (which still run)."""
    count = [0]
    method = getattr(cls, name)

    def counted(self, *args, **kwargs):
        count[0] += 1
        return method(self, *args, **kwargs)
    monkeypatch.setattr(cls, name, counted)
    return count
