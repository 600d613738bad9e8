"""Fixtures of the state space tests."""

import pytest

from cpn.statespace import nativetimed
from tests._shared import count_calls


@pytest.fixture
def fills(monkeypatch):
    """How many states the engine expanded for the C search; the C search never hands over here."""
    monkeypatch.setattr(nativetimed, "HAND_OVER_RATE", 1e9)
    return count_calls(monkeypatch, nativetimed.TimedNativeSearch, "_fill")
