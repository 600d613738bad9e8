"""Resolving names of colour sets and values, and the errors for unknown ones: each unknown name is
reported once (later uses become notes), names whose declaration failed are not reported again (their
error is the cause), and "did you mean" is offered only for a strong candidate.

`NameResolution` is a mixin of `cpn.lang.typecheck.Checker`, which provides scopes and diagnostics.
Imports `cpn.lang.*`, `cpn.values` and layer 0.
"""

from __future__ import annotations

from cpn._util import did_you_mean
from cpn.diagnostics import Diagnostic, Span
from cpn.lang import ast as A
from cpn.lang.builtins import COLSET_OPS, record_setter
from cpn.lang.checked import Env
from cpn.lang.symbols import Symbol
from cpn.values import colours as C

MAX_LATER_USES: int = 3  # later uses of an unknown name listed in its note

_KIND_WORDS = {"var": "the variable", "val": "the constant", "fun": "the function", "con": "the constructor",
               "builtin": "the library function", "local": "", "param": "the module parameter"}


def suggestion(name: str, candidates: dict[str, str]) -> str | None:
    """'Did you mean X?' for the candidate closest to `name`, if it is a strong one; `candidates` maps each
    name to its description ("the variable 'x' (declared at 3:5)")."""
    cand = did_you_mean(name, candidates)
    return f"Did you mean {candidates[cand]}?" if cand is not None else None


def _other_case(a: str, b: str) -> bool:
    """Whether the letters of two names differ in case somewhere they could be compared ('INT', 'intt')."""
    return a.lower() == b.lower() or a.isupper() != b.isupper() or a[:1].isupper() != b[:1].isupper()


class NameResolution:
    """Lookups with one error per cause (mixed into the Checker)."""

    def init_resolution(self) -> None:
        self.failed_names: set[str] = set()  # colour sets, values, variables and functions whose declaration failed
        self.unknown_reported: dict[tuple[str, str], Diagnostic] = {}  # (namespace, name) -> its error

    def describe(self, sym: Symbol) -> str:
        word = sym.what or _KIND_WORDS.get(sym.kind, "")
        where = f" (declared at {self._where(sym.span)})" if sym.span is not None and sym.span.line > 0 else ""
        return f"{word} '{sym.name}'{where}".strip()

    def _unknown(self, namespace: str, name: str, span: Span, message: str, hint: str | None) -> None:
        """Report an unknown name once; a later use becomes a note of the first report."""
        first = self.unknown_reported.get((namespace, name))
        if first is not None:
            uses = first.params.setdefault("later_uses", [])
            uses.append(self._where(span))
            shown = ", ".join(uses[:MAX_LATER_USES]) + (f" and {len(uses) - MAX_LATER_USES} more"
                                                        if len(uses) > MAX_LATER_USES else "")
            first.notes = [f"also used at {shown}"]
            return
        self.error("E0201", message, span, hint=hint, name=name)
        self.unknown_reported[(namespace, name)] = self.diags[-1]

    def lookup_colset(self, name: str, span: Span) -> C.ColourSet | None:
        cs = self.colsets.get(name)
        if cs is None and name not in self.failed_names:
            cands = {n: f"'{n}' (declared at {self._where(self.cs_spans[n])})" if self.cs_spans[n].line > 0
                     else f"'{n}'" for n in self.colsets}
            cand = did_you_mean(name, cands)
            if cand is None:
                hint = "Declare it with 'colset NAME = ...;' before its first use."
            else:
                hint = f"Did you mean {cands[cand]}?" + (" Colour-set names are case-sensitive."
                                                          if _other_case(cand, name) else "")
            self._unknown("colset", name, span, f"unknown colour set '{name}'", hint)
        return cs

    def resolve_name(self, name: str, env: Env, span: Span) -> Symbol | None:
        sym = env.lookup(name)
        if sym is not None:
            return sym
        if name in self.builtin_syms:
            return self.builtin_syms[name]
        if "." in name:
            cs, _, op = name.rpartition(".")
            if cs in self.colsets and (op in COLSET_OPS or record_setter(self.colsets[cs], op)):
                return Symbol(name, "csop", None, span, (cs, op))
        return None

    def unknown_name(self, name: str, env: Env, span: Span) -> None:
        if name in self.failed_names:
            return  # its declaration failed and was reported
        if "." in name:
            cs, _, op = name.rpartition(".")
            if cs in self.failed_names or ("colset", cs) in self.unknown_reported:
                return
            if cs in self.colsets:
                ops = list(COLSET_OPS) + [f"set_{label}" for label in getattr(self.colsets[cs], "labels", [])]
                hint = suggestion(op, {o: f"'{cs}.{o}'" for o in ops}) or \
                    f"Colour sets have the functions {', '.join(sorted(COLSET_OPS))}" + \
                    (", and record colour sets set_<field>." if op.startswith("set_") else ".")
            else:
                struct = name.split(".")[0]
                known = {n.split(".")[0] for n in self.builtin_syms if "." in n}
                hint = suggestion(name, {n: f"the library function '{n}'" for n in self.builtin_syms}) or (
                    "This library function is not supported (docs/cpnml.md)." if struct in known else
                    f"'{struct}' is neither a structure of the CPN ML library nor declared by the model: it comes "
                    "from an extension or a file the model does not load.")
            self._unknown("name", name, span, f"unknown name '{name}'", hint)
            return
        cands: dict[str, str] = {n: f"the library function '{n}'" for n in self.builtin_syms}
        cands.update({n: self.describe(s) for n, s in self.globals.items()})
        e = env
        scopes = []
        while e is not None:
            scopes.append(e.names)
            e = e.parent
        for names in reversed(scopes):  # inner scopes shadow outer ones
            cands.update({n: self.describe(s) for n, s in names.items()})
        hint = suggestion(name, cands) or "Declare it with 'val', 'var' or 'fun' before its first use."
        if self._declared_below(name, span):
            hint = (f"'{name}' is declared further down: a declaration sees only the declarations above it, as in "
                    "SML. Move that declaration above this one.")
        self._unknown("name", name, span, f"unknown name '{name}'", hint)

    def _declared_below(self, name: str, span: Span) -> bool:
        """Whether a top-level val, fun or var after `span` declares `name` (a use before the declaration)."""
        model = getattr(self, "model", None)
        for d in getattr(model, "decls", ()):
            at = getattr(d, "span", None)
            if at is None or at.file != span.file or (at.line, at.col) <= (span.line, span.col):
                continue
            names = [n for n, _ in getattr(d, "names", ())] if isinstance(d, A.VarDecl) else [getattr(d, "name", None)]
            if name in names:
                return True
        return False
