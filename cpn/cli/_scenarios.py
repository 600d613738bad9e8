"""The scenario files of `check` and `mutate`: found under the paths given, loaded, `--set` applied, and
(for `check`, whose runs each write their own report files) every run given a name no other run has."""

from __future__ import annotations

import os
import sys

from cpn.cli._common import UsageError


def scenario_paths(paths: list, hint: str = "") -> list:
    """The scenario files under `paths`, refused with a usage error when a path does not exist (with `hint`
    after it) or when there are none."""
    from cpn.gate.scenario import scenario_files

    for p in paths:
        if not os.path.exists(p):
            raise UsageError(f"no such scenario file or folder: '{p}'{hint}")
    files = scenario_files(paths)
    if not files:
        raise UsageError(f"no scenario (*.toml) in {', '.join(paths)}")
    return files


def load_scenarios(files: list, sets: dict, unique: bool = True) -> tuple[list, int]:
    """The scenarios that load, with the --set values applied (and, with `unique`, unique run names), and
    the number of files refused (each refusal printed)."""
    from cpn.diagnostics import render
    from cpn.errors import ModelError
    from cpn.gate.scenario import load_scenario

    bad_files = 0
    scenarios = []
    for path in files:
        try:
            scenario = load_scenario(path)
        except ModelError as err:
            print(err.render(), file=sys.stderr)
            bad_files += 1
            continue
        if sets:
            apply_sets(scenario, sets)
        scenarios.append(scenario)
    for scenario, diag in (unique_names(scenarios) if unique else ()):  # two runs never share their report files
        print(render(diag, scenario.source), file=sys.stderr)
        scenarios.remove(scenario)
        bad_files += 1
    return scenarios, bad_files


def apply_sets(scenario, sets: dict[str, str]) -> None:
    """`check --set NAME=VALUE`: every run of the scenario takes the value (over [set] and over a parameter
    table's), and its name says so, as a parameter row's does: 'MS[N=5]' (rows made equal are run once)."""
    from cpn.gate.scenario import Run

    def show(v) -> str:
        return ("true" if v else "false") if isinstance(v, bool) else str(v)

    runs, seen = [], set()
    for r in scenario.runs:
        params = {k: sets.get(k, v) for k, v in r.params.items()}
        label = {**params, **{k: v for k, v in sets.items() if k not in params}}
        name = f"{scenario.name}[{','.join(f'{k}={show(v)}' for k, v in label.items())}]"
        if name not in seen:
            seen.add(name)
            runs.append(Run(name, params, {**r.values, **sets}))
    scenario.runs = runs


def _stem(path: str) -> str:
    return os.path.splitext(os.path.basename(path))[0]


def unique_names(scenarios: list) -> list:
    """Make every run's report name unique; returns the scenarios refused, each with its error.

    Two scenarios named by their files alone (`a/basic.toml`, `b/basic.toml`) take the paths from the
    folder they share: runs `a/basic` and `b/basic`, reports `a-basic.*` and `b-basic.*`. Names that
    still meet (a `name = ...` given twice, or names that become the same file name) are refused at the
    later scenario's `name` line: its reports would overwrite the other's.
    """
    from cpn.diagnostics import Diagnostic
    from cpn.report.verdicts import report_name

    groups: dict[str, list] = {}
    for s in scenarios:
        groups.setdefault(report_name(s.name).casefold(), []).append(s)
    for group in groups.values():
        named_by_file = [s for s in group if s.name == _stem(s.path)]
        if len(group) < 2 or not named_by_file:
            continue
        root = os.path.commonpath([os.path.dirname(os.path.abspath(s.path)) for s in group])
        for s in named_by_file:
            qualified = os.path.splitext(os.path.relpath(os.path.abspath(s.path), root))[0].replace(os.sep, "/")
            for r in s.runs:
                r.name = qualified + r.name[len(s.name):]
            s.name = qualified
    taken: dict[str, tuple] = {}  # a report name (case folded: some file systems ignore case) -> its run
    refused = []
    for s in scenarios:
        stems = {report_name(r.name).casefold(): r for r in s.runs}
        clash = next((key for key in stems if key in taken), None)
        if clash is None:
            taken.update({key: (s, r) for key, r in stems.items()})
            continue
        other, other_run = taken[clash]
        stem = report_name(stems[clash].name)
        refused.append((s, Diagnostic(
            "E0702", f"the run '{stems[clash].name}' would write the reports of the run '{other_run.name}' of "
            f"{other.path} ({stem}.json, .txt, .md): two runs need two names", _name_span(s),
            hint="Give each scenario its own name = \"...\" (the default is the file name).")))
    return refused


def _name_span(scenario):
    """The span of the scenario's top-level `name` value, else the start of the file."""
    import re

    from cpn.diagnostics import Span

    for n, line in enumerate(scenario.source.splitlines(), 1):
        if line.lstrip().startswith("["):
            break
        m = re.match(r"""(\s*name\s*=\s*)("[^"]*"|'[^']*')""", line)
        if m:
            start = len(m.group(1)) + 1
            return Span(scenario.path, n, start, n, start + len(m.group(2)) - 1)
    return Span(scenario.path, 1, 1)
