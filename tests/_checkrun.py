"""`cpn-verify check` run from a test: its reports without the figures that vary from run to run, and
which searches ran natively."""

from __future__ import annotations

import json


def check_reports(tmp_path, name: str, capsys, spec: str) -> tuple[int, dict]:
    """`cpn-verify check SPEC --reports TMP_PATH/NAME --no-timings`: its exit code and its JSON reports by
    file name, without their seconds."""
    from cpn.cli.main import main

    rep = tmp_path / name
    code = main(["check", spec, "--reports", str(rep), "--no-timings"])
    capsys.readouterr()
    docs = {}
    for path in sorted(rep.glob("*.json")):
        doc = json.loads(path.read_text(encoding="utf-8"))
        for p in doc["properties"]:
            p.pop("seconds", None)
        for key in ("seconds", "check_seconds"):
            doc["statespace"].pop(key, None)
        docs[path.name] = doc
    return code, docs


def record_backends(monkeypatch) -> list:
    """The list to which each search from now on appends why it is not native (None: it is)."""
    from cpn.statespace import chooser

    backends: list = []
    unavailable = chooser.why_not_native

    def spy(engine, options, s0):
        why = unavailable(engine, options, s0)
        backends.append(why)
        return why

    monkeypatch.setattr(chooser, "why_not_native", spy)
    return backends
