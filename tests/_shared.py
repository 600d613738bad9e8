"""Where the shared test data lives: `../shared` beside the repository (CI's layout), or CPN_SHARED_DIR; and
a counter of a method's calls."""

import os

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.environ.get("CPN_SHARED_DIR") or os.path.normpath(os.path.join(ROOT, "..", "shared"))


def count_calls(monkeypatch, cls, name: str) -> list[int]:
    """A one-element list counting the calls of method `name` of `cls` from now on (which still run)."""
    count = [0]
    method = getattr(cls, name)

    def counted(self, *args, **kwargs):
        count[0] += 1
        return method(self, *args, **kwargs)
    monkeypatch.setattr(cls, name, counted)
    return count
