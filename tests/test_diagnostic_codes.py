"""The registry of diagnostic codes (cpn/diagnostics.py) lists exactly the codes the package emits."""

import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[1]


def test_the_code_registry_lists_exactly_the_codes_emitted():
    import re

    from cpn.diagnostics import CODES

    used = set()
    for path in (ROOT / "cpn").rglob("*.py"):
        if path.name != "diagnostics.py":
            used |= set(re.findall(r'"([EW]\d{4})"', path.read_text(encoding="utf-8")))
    assert used == set(CODES), (sorted(used - set(CODES)), sorted(set(CODES) - used))
