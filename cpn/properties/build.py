"""The checks of a scenario's properties, built from their kinds and texts (`build_checks`): each kind's
fields are read, its texts compiled by the property language, the names of places and transitions looked
up; every error of every property is reported at once, at its place in the scenario file.

A new kind is its fields in `cpn.properties.spec.KINDS`, its `Check` (`cpn.properties.kinds`, or a
module of its own such as `cpn.properties.ltl`) and its line in `_build` (docs/internals.md, "Where to
make a change").
"""

from __future__ import annotations

from cpn.checks.ctl import And, Atom, Not, Or, Temporal
from cpn.diagnostics import Diagnostic, Span
from cpn.errors import ModelError
from cpn.lang import ast as A
from cpn.lang import types as T
from cpn.properties.kinds import (
    INTEGER_LIMITS,
    MULTISET_LIMITS,
    Bound,
    Check,
    Ctl,
    DeadlockFree,
    DeadMarkings,
    DeadTransitions,
    Home,
    Invariant,
    LiveTransitions,
    NoLivelock,
    Reachable,
    _ctl_error,
    _slice,
)
from cpn.properties.ltl import build_ltl
from cpn.properties.predicates import CTL_ARC, CTL_BINARY, CTL_UNARY, PropertyLanguage, walk
from cpn.properties.spec import PropertySpec


def build_checks(specs: list[PropertySpec], lang: PropertyLanguage, source: str) -> list[Check]:
    """A check per property; raises ModelError with every property text error of the scenario."""
    diags: list[Diagnostic] = []
    out = []
    for spec in specs:
        try:
            out.append(_build(spec, lang))
        except ModelError as exc:
            diags.extend(exc.diagnostics)
    if diags:
        file = specs[0].span.file
        raise ModelError(diags, {file: source})
    return out


def _text(spec: PropertySpec, key: str):
    return spec.fields[key], spec.texts.get(key), spec.spans.get(key, spec.span)


def _pred(spec, lang, key, want, what):
    text, origin, span = _text(spec, key)
    return lang.compile(text, origin, span, want, what)


def _names(spec: PropertySpec, lang: PropertyLanguage, key: str) -> list[int]:
    out: list[int] = []
    diags = []
    for name in spec.fields[key]:
        ts = lang.resolve_transitions(name)
        if ts is None:
            from cpn._util import did_you_mean

            cand = did_you_mean(name, list(lang.transition_names))
            diags.append(Diagnostic("E0703", f"no transition instance '{name}' in the net",
                                    _element_span(spec, key, name),
                                    hint=f"Did you mean '{cand}'?" if cand else
                                    "Name it as the report prints it: \"Page'trans 1\", or \"Page'trans\" for "
                                    "every instance."))
        else:
            out.extend(ts)
    if diags:
        raise ModelError(diags)
    return out


def _element_span(spec: PropertySpec, key: str, name: str) -> Span:
    span = spec.spans.get(key, spec.span)
    if not spec.source:
        return span
    lines = spec.source.splitlines()
    for ln in range(span.line, min(len(lines), span.line + 50) + 1):
        col = lines[ln - 1].find(f'"{name}"')
        if col >= 0:
            return Span(span.file, ln, col + 2, ln, col + 1 + len(name))
    return span


def _build(spec: PropertySpec, lang: PropertyLanguage) -> Check:
    k = spec.kind
    f = spec.fields
    if k == "invariant":
        return Invariant(spec, _pred(spec, lang, "expr", T.BOOL, "an invariant"))
    if k == "reachable":
        return Reachable(spec, _pred(spec, lang, "expr", T.BOOL, "a reachability predicate"))
    if k == "deadlock_free":
        return DeadlockFree(spec)
    if k == "dead_markings":
        pred = _pred(spec, lang, "expr", T.BOOL, "a dead-marking predicate") if "expr" in f else None
        return DeadMarkings(spec, pred)
    if k == "bound":
        return _bound(spec, lang)
    if k == "dead_transitions":
        ts = _names(spec, lang, "expected")
        return DeadTransitions(spec, set(ts))
    if k == "live_transitions":
        return LiveTransitions(spec, _names(spec, lang, "transitions") if "transitions" in f else None)
    if k == "home":
        pred = _pred(spec, lang, "expr", T.BOOL, "a home predicate") if "expr" in f else None
        return Home(spec, pred)
    if k == "no_livelock":
        return NoLivelock(spec, _patterns(spec, lang, "progress") if f.get("progress") else None)
    if k == "ctl":
        return _ctl(spec, lang)
    if k == "ltl":
        return build_ltl(spec, lang)
    raise AssertionError(k)


def _bound(spec, lang) -> Check:
    f = spec.fields

    def const(key, want, what):
        v = f.get(key)
        if v is None or isinstance(v, int):
            return v
        text, origin, span = _text(spec, key)
        return lang.constant(text, origin, span, want, what)

    places = None
    fn = None
    if "place" in f:
        name = f["place"]
        places = _place_instances(spec, lang, name)
        cst = lang.place_cstype[_base(name, lang)]
    else:
        fn = _pred(spec, lang, "expr", T.INT, "a bounded integer expression")
        cst = None
    limits = {}
    for key, old in INTEGER_LIMITS:
        given = key if key in f else old if old in f else None
        if given is not None:
            limits[key] = const(given, T.INT, f"'{given}'")
    multiset_limits = {}
    for key, old in MULTISET_LIMITS:
        given = key if key in f else old if old in f else None
        if given is not None and cst is not None:
            multiset_limits[key] = const(given, T.ms(cst), f"'{given}'")
    return Bound(spec, places, fn, limits, multiset_limits)


def _base(name: str, lang) -> str:
    if name in lang.accessors:
        return name
    return name.rsplit(" ", 1)[0]


def _place_instances(spec, lang, name: str) -> list[int]:
    acc = lang.accessors.get(name)
    if acc is not None:
        return acc.places
    base, _, num = name.rpartition(" ")
    acc = lang.accessors.get(base)
    if acc is not None and num.isdigit() and int(num) in acc.instances:
        return [acc.instances[int(num)]]
    from cpn._util import did_you_mean

    cand = did_you_mean(name, [f"{b} {i}" for b, a in lang.accessors.items() for i in a.instances] + list(lang.accessors))
    text, origin, span = _text(spec, "place")
    raise ModelError([Diagnostic("E0703", f"no place instance '{name}' in the net",
                                 origin.span(0, len(text) - 1) if origin else span,
                                 hint=f"Did you mean '{cand}'?" if cand else
                                 "Name it as the report prints it: \"Page'place 1\", or \"Page'place\" for every "
                                 "instance.")])


def _ctl(spec, lang) -> Check:
    text, origin, span = _text(spec, "formula")
    expr = lang.check(text, origin, span, T.BOOL, "a CTL formula", ctl=True)
    ctl_syms = {id(s): n for n, s in lang.ctl_symbols.items()}
    atoms = []

    def temporal(e) -> bool:
        return any(isinstance(n, A.Name) and n.ref is not None and id(n.ref) in ctl_syms for n in walk(e))

    def conv(e):
        if not temporal(e):
            atoms.append(lang.compile_checked(_slice(text, origin, e), e, span))
            return Atom(len(atoms) - 1)
        if isinstance(e, A.App) and isinstance(e.fn, A.Name) and e.fn.ref is not None and id(e.fn.ref) in ctl_syms:
            op = ctl_syms[id(e.fn.ref)]
            if op in CTL_ARC:
                pat, phi = e.arg.items
                return Temporal(op, (conv(phi),), lang.arc_pattern(op, pat, text, origin, span))
            if op in CTL_BINARY:
                a, b = e.arg.items
                return Temporal(op, (conv(a), conv(b)))
            return Temporal(CTL_UNARY[op], (conv(e.arg),))
        if isinstance(e, A.App) and isinstance(e.fn, A.Name) and e.fn.name == "not":
            return Not(conv(e.arg))
        if isinstance(e, A.BinOp) and e.op in ("andalso", "orelse"):
            return (And if e.op == "andalso" else Or)(conv(e.left), conv(e.right))
        if isinstance(e, A.If):
            c = conv(e.cond)
            return Or(And(c, conv(e.then)), And(Not(c), conv(e.else_)))
        if isinstance(e, A.Annot):
            return conv(e.expr)
        raise _ctl_error(e, text, origin, span)

    formula = conv(expr)
    return Ctl(spec, formula, atoms, _patterns(spec, lang, "fairness") if spec.fields.get("fairness") else [])


def _patterns(spec: PropertySpec, lang: PropertyLanguage, key: str) -> list:
    """The binding-element tests of a list of transitions and binding elements (`fairness`, `progress`):
    "Page'trans 1", "Page'trans" (every instance), "Page'trans 1: {var=value}" (the bindings with that value)."""
    from cpn._util import did_you_mean

    diags = []
    for name in spec.fields[key]:
        if lang.resolve_transitions(name) is None and not lang._known_be(name):
            tname = name.partition(":")[0].strip()
            cand = None if tname in lang.transition_names else did_you_mean(tname, list(lang.transition_names))
            diags.append(Diagnostic("E0703", f"no transition instance or binding element '{name}' in the net",
                                    _element_span(spec, key, name),
                                    hint=f"Did you mean '{cand}'?" if cand else
                                    "Write \"Page'trans 1\", \"Page'trans\" (every instance) or "
                                    "\"Page'trans 1: {var=value}\" (the bindings with that value)."))
    if diags:
        raise ModelError(diags)
    return [lang.binding_pattern(name) for name in spec.fields[key]]


__all__ = ["build_checks"]
