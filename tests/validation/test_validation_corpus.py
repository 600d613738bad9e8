"""End to end: every corpus instance of up to 100,000 states, loaded with `cpn.load`, explored, and
compared with every figure expected.json publishes (shared/validation/README.md)."""

from __future__ import annotations

import json
import os

import pytest

from cpn.cli.validate import select, validate_instance
from tests._shared import SHARED, needs_shared

VALIDATION = os.environ.get("CPN_VALIDATION_DIR", SHARED + "/validation")
LIMIT = 100_000


def _instances():
    try:
        with open(os.path.join(VALIDATION, "expected.json"), encoding="utf-8") as fh:
            corpus = json.load(fh)
    except OSError:
        return []
    return [inst for inst in corpus["instances"] if inst["states"] <= LIMIT]


INSTANCES = _instances()


@needs_shared
@pytest.mark.parametrize("inst", INSTANCES, ids=[i["name"] for i in INSTANCES])
def test_instance_matches_published_figures(inst):
    [(inst, skip)] = select([inst], None, None)
    if skip:
        pytest.skip(skip)
    res = validate_instance(VALIDATION, inst, max_states=2 * LIMIT)
    assert res.status == "match", "\n".join(res.differences) or res.reason
