"""Scenario files (`specs/*.toml`, docs/specs.md): reading, validating and expanding parameter tables.

`tomllib` gives values without positions, so the raw text is scanned once more to find where each key's
value starts (`_Locator`), and the characters of a string value are mapped back to the file
(`cpn.properties.spec.TextOrigin`): an error in a property text points at its line and column in the TOML
file. Imports the standard library, layer 0, the property kinds (`cpn.properties.spec`) and the state
space's `Backend` (the words of `backend`) only.
"""

from __future__ import annotations

import itertools
import os
import re
import tomllib
from dataclasses import dataclass, field

from cpn.diagnostics import Diagnostic, Span, other_command_hint
from cpn.errors import ModelError
from cpn.properties.spec import (
    BOUND_INTEGER,
    BOUND_MULTISET,
    BOUND_OLD_SPELLINGS,
    KINDS,
    PropertySpec,
    TextOrigin,
    line_col,
)
from cpn.statespace.options import Backend

TOP_KEYS = {"name", "model", "description", "set", "explore", "parameters", "property"}
EXPLORE_KEYS = {"max_states": int, "max_arcs": int, "max_seconds": (int, float), "max_memory_mb": (int, float),
                "time_condensation": bool, "stop_at_first_violation": bool, "detect_time_growth": bool,
                "until_time": int, "workers": int, "backend": Backend,
                "reduction": str, "sweep_line": bool, "progress": str, "symmetry": list}
# the reductions `reduction` may name (docs/specs.md)
REDUCTIONS: tuple = ("stubborn", "symmetry")


@dataclass
class Run:
    """One configuration of a scenario: its name and the `val` values it sets."""

    name: str
    params: dict
    values: dict


@dataclass
class Scenario:
    path: str
    source: str
    name: str
    model: str  # resolved path
    description: str
    values: dict
    explore: dict
    runs: list[Run]
    properties: list[PropertySpec]
    value_spans: dict = field(default_factory=dict)  # constant name -> Span of its value in [set] or a row
    explore_texts: dict = field(default_factory=dict)  # [explore] key -> (TextOrigin, Span) of a text value

    def __repr__(self) -> str:
        return (f"Scenario({self.name!r}, {self.path!r}, {len(self.runs)} run{'s' if len(self.runs) != 1 else ''}, "
                f"{len(self.properties)} propert{'ies' if len(self.properties) != 1 else 'y'})")


_HEADER = re.compile(r"^[ \t]*(\[\[?)[ \t]*([A-Za-z0-9_.\-\" ]+?)[ \t]*\]\]?[ \t]*(#.*)?$")
_KEY = re.compile(r"^[ \t]*([A-Za-z0-9_\-]+|\"[^\"]*\")[ \t]*=[ \t]*")


class _Locator:
    """Positions of keys and values: (table path, key) -> (offset of the key, offset of the value)."""

    def __init__(self, text: str):
        self.text = text
        self.keys: dict[tuple, tuple[int, int]] = {}
        self.headers: dict[tuple, int] = {}
        counts: dict[str, int] = {}
        table: tuple = ()
        pos = 0
        depth = 0
        in_ml: str | None = None
        for line in text.splitlines(keepends=True):
            start = pos
            pos += len(line)
            if in_ml is not None:
                if in_ml in line:
                    in_ml = None if line.count(in_ml) % 2 == 1 else in_ml
                continue
            if depth == 0:
                m = _HEADER.match(line.rstrip("\r\n"))
                if m:
                    name = m.group(2).strip().strip('"')
                    if m.group(1) == "[[":
                        counts[name] = counts.get(name, 0) + 1
                        table = (name, counts[name])
                    else:
                        table = (name,)
                    self.headers[table] = start + m.start(2)
                    continue
                m = _KEY.match(line)
                if m:
                    key = m.group(1).strip('"')
                    self.keys[(table, key)] = (start + m.start(1), start + m.end())
                    rest = line[m.end():]
                    for q in ('"""', "'''"):
                        if rest.startswith(q) and rest.count(q) == 1:
                            in_ml = q
                    depth += _bracket_balance(rest)
                    continue
            depth = max(0, depth + _bracket_balance(line))

    def value_offset(self, table: tuple, key: str) -> int | None:
        got = self.keys.get((table, key))
        return got[1] if got else None

    def key_offset(self, table: tuple, key: str) -> int | None:
        got = self.keys.get((table, key))
        return got[0] if got else None


def _bracket_balance(s: str) -> int:
    s = re.sub(r'"(?:\\.|[^"\\])*"|\'[^\']*\'|#.*', "", s)
    return s.count("[") + s.count("{") - s.count("]") - s.count("}")


def _string_offsets(text: str, start: int) -> tuple | None:
    """File offsets of the characters of the TOML string value starting at `start` (plus one past the end)."""
    found = next(((q, b) for q, b in (('"""', True), ("'''", False), ('"', True), ("'", False))
                  if text.startswith(q, start)), None)
    if found is None:
        return None
    q, basic = found
    i = start + len(q)
    if len(q) == 3 and text.startswith("\n", i):
        i += 1
    elif len(q) == 3 and text.startswith("\r\n", i):
        i += 2
    out = []
    while i < len(text):
        if text.startswith(q, i) and not (len(q) == 3 and text.startswith(q[0], i + 3)):
            out.append(i)
            return tuple(out)
        c = text[i]
        if basic and c == "\\":
            nxt = text[i + 1:i + 2]
            if nxt == "u":
                out.append(i)
                i += 6
                continue
            if nxt == "U":
                out.append(i)
                i += 10
                continue
            if len(q) == 3 and nxt in ("\n", "\r", " ", "\t"):
                j = i + 1
                while j < len(text) and text[j] in " \t\r\n":
                    j += 1
                i = j
                continue
            out.append(i)
            i += 2
            continue
        out.append(i)
        i += 1
    return None


class _Reader:
    """Validates the decoded TOML against the format, collecting every error with its position."""

    def __init__(self, path: str, text: str):
        self.path = path
        self.text = text
        self.loc = _Locator(text)
        self.diags: list[Diagnostic] = []

    def span_at(self, offset: int | None, length: int = 1) -> Span:
        if offset is None:
            return Span(self.path, 1, 1)
        line, col = line_col(self.text, offset)
        return Span(self.path, line, col, line, col + max(length, 1) - 1)

    def key_span(self, table: tuple, key: str) -> Span:
        off = self.loc.key_offset(table, key)
        if off is None:
            return self.table_span(table)
        return self.span_at(off, len(key))

    def value_span(self, table: tuple, key: str) -> Span:
        off = self.loc.value_offset(table, key)
        if off is None:
            return self.table_span(table)
        end = self.text.find("\n", off)
        raw = self.text[off:end if end >= 0 else len(self.text)].rstrip()
        return self.span_at(off, len(raw))

    def table_span(self, table: tuple) -> Span:
        off = self.loc.headers.get(table)
        return self.span_at(off, len(table[0]) if table else 1) if off is not None else Span(self.path, 1, 1)

    def error(self, code: str, message: str, span: Span, hint: str | None = None) -> None:
        self.diags.append(Diagnostic(code, message, span, hint=hint))

    def origin(self, table: tuple, key: str) -> TextOrigin | None:
        off = self.loc.value_offset(table, key)
        if off is None:
            return None
        offs = _string_offsets(self.text, off)
        return TextOrigin(self.path, self.text, offs) if offs is not None else None


def load_scenario(path: str | os.PathLike) -> Scenario:
    """Read and validate a scenario file; raises ModelError (exit status 65) with every error positioned."""
    path = os.fspath(path)
    try:
        with open(path, encoding="utf-8") as fh:
            text = fh.read()
    except UnicodeDecodeError as exc:
        raise ModelError([Diagnostic("E0701", f"the file is not UTF-8 text ({exc.reason})", Span(path, 1, 1))]) from None
    return loads_scenario(text, path)


_BARE_RANGE = re.compile(r"^([ \t]*[A-Za-z_][A-Za-z0-9_']*[ \t]*=[ \t]*)(-?\d+[ \t]*\.\.[ \t]*-?\d+)([ \t]*(#.*)?)$",
                         re.MULTILINE)


def loads_scenario(text: str, path: str = "<scenario>") -> Scenario:
    """Read a scenario from TOML text (`path` names it in errors and anchors the model path).

    A parameter range may be written bare, `N = 1..8`, as well as quoted, `N = "1..8"` (TOML itself
    only allows the quoted form).
    """
    text = _BARE_RANGE.sub(lambda m: f'{m.group(1)}"{m.group(2)}"{m.group(3)}', text)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        msg = str(exc)
        m = re.search(r"\(at line (\d+), column (\d+)\)", msg)
        line, col = (int(m.group(1)), int(m.group(2))) if m else (1, 1)
        msg = re.sub(r"\s*\(at line \d+, column \d+\)", "", msg).rstrip(".")
        raise ModelError([Diagnostic("E0701", f"not valid TOML: {msg[:1].lower() + msg[1:]}",
                                     Span(path, line, col, line, col),
                                     hint=other_command_hint(path, text, "scenario")
                                     or "Check quotes and brackets; TOML is described at https://toml.io.")],
                         {path: text}) from None
    r = _Reader(path, text)
    for key in data:
        if key not in TOP_KEYS:
            r.error("E0702", f"unknown key '{key}' in a scenario", r.key_span((), key),
                    hint=f"A scenario has the keys {', '.join(sorted(TOP_KEYS))} (docs/specs.md).")
    model = data.get("model")
    if not isinstance(model, str) or not model:
        r.error("E0702", "a scenario must name its model: model = \"path/to/model.cpnet\"",
                r.value_span((), "model") if "model" in data else Span(path, 1, 1),
                hint="Give the model file relative to the scenario file.")
        model = ""
    name = data.get("name", os.path.splitext(os.path.basename(path))[0])
    if not isinstance(name, str):
        r.error("E0702", "'name' must be a string", r.value_span((), "name"))
        name = str(name)
    values = _values(r, data.get("set", {}), ("set",))
    explore = _explore(r, data.get("explore", {}))
    rows = _parameters(r, data.get("parameters"))
    props = _properties(r, data.get("property", []))
    base = os.path.dirname(os.path.abspath(path))
    model_path = model if os.path.isabs(model) else os.path.normpath(os.path.join(base, model))
    if model and not os.path.isfile(model_path):
        r.error("E0702", f"no model file '{model}' (looked for {model_path})", r.value_span((), "model"),
                hint="The model path is relative to the scenario file.")
    if r.diags:
        raise ModelError(r.diags, {path: text})
    runs = []
    for row in rows:
        label = ",".join(f"{k}={_show(v)}" for k, v in row.items())
        runs.append(Run(f"{name}[{label}]" if row else name, dict(row), {**values, **row}))
    spans = {k: r.value_span(("set",), k) for k in values}
    if isinstance(data.get("parameters"), dict):
        spans.update({k: r.value_span(("parameters",), k) for k in data["parameters"]})
    elif isinstance(data.get("parameters"), list):
        for i, row in enumerate(data["parameters"], 1):
            spans.update({k: r.value_span(("parameters", i), k) for k in row if k not in spans})
    texts = {k: (r.origin(("explore",), k), r.value_span(("explore",), k)) for k in ("progress",) if k in explore}
    return Scenario(path, text, name, model_path, str(data.get("description", "")), values, explore, runs, props,
                    spans, texts)


def _show(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    return str(v)


def _values(r: _Reader, table, where: tuple) -> dict:
    if not isinstance(table, dict):
        r.error("E0702", f"'{where[0]}' must be a table of constant values", r.table_span(where))
        return {}
    out = {}
    for k, v in table.items():
        if isinstance(v, (bool, int, str)):
            out[k] = v
        else:
            r.error("E0702", f"the value of '{k}' must be an integer, a boolean or a string (CPN ML text)",
                    r.value_span(where, k))
    return out


def _explore(r: _Reader, table) -> dict:
    if not isinstance(table, dict):
        r.error("E0702", "'explore' must be a table", r.table_span(("explore",)))
        return {}
    out = {}
    for k, v in table.items():
        want = EXPLORE_KEYS.get(k)
        if want is None:
            r.error("E0702", f"unknown exploration option '{k}'", r.key_span(("explore",), k),
                    hint=f"The options are {', '.join(sorted(EXPLORE_KEYS))}.")
            continue
        if k == "progress":  # a progress measure for the sweep-line method, checked with the model
            if not isinstance(v, str) or not v.strip():
                r.error("E0702", "'progress' must be an integer expression over the marking, as a string",
                        r.value_span(("explore",), k), hint="For example: progress = \"ms_to_col (Master'NextId 1)\".")
                continue
            out[k] = v
            continue
        if want is list:  # symmetry: true (the model's declarations), "auto", or colour sets
            if v is True:
                out[k] = ""
            elif isinstance(v, str) and v.strip():
                out[k] = v.strip()
            elif isinstance(v, list) and v and all(isinstance(x, str) and x.strip() for x in v):
                out[k] = ",".join(x.strip() for x in v)
            else:
                r.error("E0702", "'symmetry' must be true, \"auto\" or a list of colour sets",
                        r.value_span(("explore",), k), hint='Write symmetry = ["PH", "Ring:rotations"] (all '
                        "permutations of PH, rotations of Ring), symmetry = \"auto\", or symmetry = true for the "
                        "model's own declarations.")
            continue
        if want is Backend:  # the search: the words of `--backend`
            if not isinstance(v, str) or v not in Backend.option_words():
                r.error("E0702", f"'backend' must be one of {', '.join(repr(w) for w in Backend.option_words())}",
                        r.value_span(("explore",), k), hint="'auto': the native search where it can run, else "
                        "Python; 'c': the native search (why not, as a warning); 'python': the Python search. "
                        "The state space is the same with each (as explore --backend).")
                continue
            out[k] = v
            continue
        if want is str:
            if v not in REDUCTIONS:
                r.error("E0702", f"'{k}' must be one of {', '.join(repr(x) for x in REDUCTIONS)}",
                        r.value_span(("explore",), k), hint="'stubborn': stubborn sets (partial-order "
                        "reduction); 'symmetry': symmetry reduction (with the 'symmetry' option or the model's "
                        "declarations).")
                continue
            out[k] = v
            continue
        ok = isinstance(v, want) and (want is bool or not isinstance(v, bool))
        if k == "until_time" and ok and v < 0:  # a model-time bound: 0 is a bound
            r.error("E0702", "'until_time' must be a model time, 0 or more", r.value_span(("explore",), k))
            continue
        if not ok or (want is not bool and k != "until_time" and v <= 0):
            r.error("E0702", f"'{k}' must be {'true or false' if want is bool else 'a positive number'}",
                    r.value_span(("explore",), k))
            continue
        out[k] = v
    if out.get("sweep_line") and (out.get("reduction") or "until_time" in out):
        key = "reduction" if out.get("reduction") else "until_time"
        r.error("E0702", f"'sweep_line' cannot be combined with '{key}'", r.key_span(("explore",), key),
                hint="The sweep-line method explores the whole state space in the order of its progress measure; "
                     "drop one of the two options.")
    if "progress" in out and not out.get("sweep_line"):
        r.error("E0702", "'progress' is the sweep-line method's progress measure, but 'sweep_line' is not set",
                r.key_span(("explore",), "progress"), hint="Add sweep_line = true, or drop 'progress'.")
    return out


_RANGE = re.compile(r"^\s*(-?\d+)\s*\.\.\s*(-?\d+)\s*$")


def _parameters(r: _Reader, params) -> list[dict]:
    if params is None:
        return [{}]
    if isinstance(params, dict):
        axes = []
        for k, v in params.items():
            if isinstance(v, str):
                m = _RANGE.match(v)
                if not m or int(m.group(1)) > int(m.group(2)):
                    r.error("E0704", f"'{k}' must be an inclusive range \"a..b\" with a <= b, or a list of values",
                            r.value_span(("parameters",), k), hint=f'Write {k} = "1..8" or {k} = [1, 2, 4].')
                    continue
                axes.append((k, list(range(int(m.group(1)), int(m.group(2)) + 1))))
            elif isinstance(v, list) and v and all(isinstance(x, (int, bool, str)) for x in v):
                axes.append((k, v))
            else:
                r.error("E0704", f"'{k}' must be a range \"a..b\" or a non-empty list of values",
                        r.value_span(("parameters",), k))
        return [dict(zip([k for k, _ in axes], combo)) for combo in itertools.product(*[v for _, v in axes])]
    if isinstance(params, list) and params and all(isinstance(row, dict) for row in params):
        keys = list(params[0])
        rows = []
        for i, row in enumerate(params, 1):
            if list(row) != keys and set(row) != set(keys):
                r.error("E0704", f"parameter row {i} sets {', '.join(sorted(row))}, the first row sets "
                        f"{', '.join(sorted(keys))}", r.table_span(("parameters", i)),
                        hint="Every row gives a value to the same constants.")
            rows.append(_values(r, row, ("parameters", i)))
        return rows
    r.error("E0704", "'parameters' must be a table of ranges or lists, or an array of rows [[parameters]]",
            r.table_span(("parameters",)))
    return [{}]


def _properties(r: _Reader, props) -> list[PropertySpec]:
    if not isinstance(props, list) or not all(isinstance(p, dict) for p in props):
        r.error("E0702", "properties are written as [[property]] tables", r.key_span((), "property"))
        return []
    out = []
    names: dict[str, int] = {}
    for i, p in enumerate(props, 1):
        table = ("property", i)
        kind = p.get("kind")
        if kind not in KINDS:
            close = [k for k in KINDS if isinstance(kind, str) and (k.startswith(kind[:4]) or kind in k)]
            span = r.value_span(table, "kind") if "kind" in p else r.table_span(table)
            r.error("E0702", f"unknown property kind {kind!r}" if kind is not None else "a property needs a 'kind'",
                    span, hint=(f"Did you mean '{close[0]}'? " if close else "")
                    + f"The kinds are {', '.join(KINDS)} (docs/specs.md).")
            continue
        required, optional = KINDS[kind]
        allowed = required | optional | {"kind", "name", "description", "expect"}
        bad = False
        for k in p:
            if k not in allowed:
                r.error("E0702", f"a '{kind}' property has no field '{k}'", r.key_span(table, k),
                        hint=f"Its fields are {', '.join(sorted(allowed - {'kind'}))}.")
                bad = True
        for k in sorted(required - set(p)):
            r.error("E0702", f"a '{kind}' property needs the field '{k}'", r.value_span(table, "kind"))
            bad = True
        name = p.get("name", f"{kind}#{i}")
        if not isinstance(name, str) or not name:
            r.error("E0702", "'name' must be a non-empty string", r.value_span(table, "name"))
            name = f"{kind}#{i}"
        if name in names:
            r.error("E0702", f"two properties are named '{name}'", r.value_span(table, "name"),
                    hint=f"Property {names[name]} has the same name; names identify properties in reports.")
        names[name] = i
        expect = p.get("expect", "holds")
        if expect not in ("holds", "violated"):
            r.error("E0702", f"'expect' must be \"holds\" or \"violated\", not {expect!r}", r.value_span(table, "expect"),
                    hint="A mutant scenario writes expect = \"violated\" on the property its bug must break.")
            bad = True
        fields = {k: v for k, v in p.items() if k not in ("kind", "name", "description", "expect")}
        bad |= not _check_fields(r, table, kind, fields)
        spans = {k: r.value_span(table, k) for k in p}
        texts = {k: r.origin(table, k) for k, v in fields.items() if isinstance(v, str)}
        if not bad:
            out.append(PropertySpec(i, name, kind, fields, r.value_span(table, "kind"), spans, texts,
                                    str(p.get("description", "")), r.text, expect))
    return out


def _check_fields(r: _Reader, table: tuple, kind: str, f: dict) -> bool:
    ok = True

    def bad(key, what, hint=None):
        nonlocal ok
        ok = False
        r.error("E0702", f"'{key}' of a '{kind}' property must be {what}", r.value_span(table, key), hint=hint)

    multisets = (*BOUND_MULTISET, "upper_multiset", "lower_multiset")
    integers = (*BOUND_INTEGER, "upper", "lower")
    for k in ("expr", "formula", "place", *multisets):
        if k in f and (not isinstance(f[k], str) or not f[k].strip()):
            bad(k, "a non-empty string")
    for k in ("count", "count_modulo_time"):
        if k in f and (not isinstance(f[k], int) or isinstance(f[k], bool) or f[k] < 0):
            bad(k, "a non-negative integer")
    for k in integers:
        if k in f and (isinstance(f[k], bool) or not isinstance(f[k], (int, str))):
            bad(k, "an integer or a CPN ML integer expression")
    for k in ("expected", "transitions", "progress", "fairness", "weak_fairness", "strong_fairness"):
        if k in f and (not isinstance(f[k], list) or not all(isinstance(x, str) for x in f[k])):
            bad(k, "a list of transition names", hint=f'Write {k} = ["Page\'Trans 1", "Module\'Trans"].')
    if "initial" in f and not isinstance(f["initial"], bool):
        bad("initial", "true or false")
    if kind == "dead_markings" and not f:
        ok = False
        r.error("E0702", "a 'dead_markings' property needs 'count', 'count_modulo_time' or 'expr'",
                r.value_span(table, "kind"), hint="Use kind = \"deadlock_free\" to require no dead marking.")
    if kind == "bound":
        if ("place" in f) == ("expr" in f):
            ok = False
            r.error("E0702", "a 'bound' property needs exactly one of 'place' and 'expr'", r.value_span(table, "kind"))
        if not (set(integers) | set(multisets)) & set(f):
            ok = False
            r.error("E0702", f"a 'bound' property needs a limit: one of {', '.join(BOUND_INTEGER + BOUND_MULTISET)}",
                    r.value_span(table, "kind"), hint="For example: at_most = 1 (every reachable marking has at "
                    "most 1), or upper_equals = 1 (the best upper bound is exactly 1).")
        for old, new in BOUND_OLD_SPELLINGS.items():
            if old in f and new in f:
                ok = False
                r.error("E0702", f"'{old}' and '{new}' are two spellings of the same bound", r.key_span(table, old),
                        hint=f"Keep '{new}' (the older spelling '{old}' means the same: the best bound equals the "
                        "value).")
        if "expr" in f and set(multisets) & set(f):
            ok = False
            r.error("E0702", "multiset bounds are given for a 'place', not for an 'expr'", r.value_span(table, "kind"))
    return ok


def scenario_files(paths: list[str]) -> list[str]:
    """The scenario files named by `paths` (files, or folders searched recursively for *.toml), sorted."""
    out = []
    for p in paths:
        if os.path.isdir(p):
            for root, dirs, files in os.walk(p):
                dirs.sort()
                out.extend(os.path.join(root, f) for f in sorted(files) if f.endswith(".toml"))
        else:
            out.append(p)
    return out
