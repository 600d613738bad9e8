"""The compiler of property texts (the engine capability `predicate_compiler`, `cpn.engine.protocol`).

A property text, typed by the language and closed into the net's expression form, is compiled with the
engine's expression compiler (`cpn.engine.codegen.ExprCompiler`) and the model's compiled functions, plus
things of its own: a place read with a constant instance (`Page'place 1`) becomes `MK(S, index)`, a
one-clause `fn` becomes a Python lambda, so that `forall P (fn m => ...)` does not run in the
tree-walking evaluator (20x faster on DP(10)), and so do the values and functions a `let` declares. The
property layer (`cpn.properties.predicates`) reaches it through the engine's protocol only. Imports the
engine's code generator and run-time library, and `cpn.expr`.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

from cpn.engine.codegen import ExprCompiler, Namespace, Unsupported
from cpn.engine.runtime import RUNTIME
from cpn.expr import nodes as E


class PredicateCompiler:
    """Compiles closed expressions into functions `f(I, S)` of a state id and a state.

    `places` maps the uid of a name that reads a place (the property language's `Page'place`) to its
    instances (instance number -> place index). The generated code calls `MK(S, place)` for a marking and
    `EVAL(node, locals)` for what it leaves to `evaluator`; the caller gives `MK` and any other name its
    prologue uses in `env`.
    """

    def __init__(self, evaluator, places: dict[int, dict[int, int]], functions: dict):
        self.evaluator = evaluator
        self.ns = Namespace()
        self.compiler = _PredicateExprCompiler(self.ns, evaluator, places, functions)

    def function(self, expr: E.Expr, env: dict, prologue: str = "", label: str = "<property>") -> Callable:
        """`def f(I, S): <prologue> return <expr>` compiled, with the run-time library, `EVAL` and `env`
        as its globals; `prologue` is Python lines indented by four spaces."""
        body = self.compiler.expr(expr)
        glob = dict(RUNTIME)
        glob.update(self.ns.objects)
        glob["EVAL"] = self.evaluator.eval
        glob.update(env)
        src = f"def _property(I, S):\n{prologue}    return {body}\n"
        exec(compile(src, label, "exec"), glob)  # noqa: S102 - generated from the typed tree
        return glob["_property"]


class _PredicateExprCompiler(ExprCompiler):
    """The engine's expression compiler, plus place access and one-clause `fn`."""

    def __init__(self, ns, ev, places: dict[int, dict[int, int]], functions: dict):
        super().__init__(ns, ev, {}, {}, {})
        self.places = places
        self.functions = functions
        self.locals: dict[int, str] = {}

    def _c_Name(self, e):
        sym = e.ref
        if sym is not None and sym.kind == "local":
            py = self.locals.get(sym.uid)
            if py is None:
                raise Unsupported()
            return py
        return super()._c_Name(e)

    def fallback(self, e):
        node = self.ns.ref(e, "X")
        used = _local_uids(e)
        items = ", ".join(f"{uid}: {py}" for uid, py in self.locals.items() if uid in used)
        return f"EVAL({node}, {{{items}}})"

    def _c_Fn(self, e):
        if len(e.rules) != 1:
            raise Unsupported()
        pat, body = e.rules[0]
        return self._lambda(pat, body)

    def _lambda(self, pat, body) -> str:
        """A Python lambda of one argument matched by `pat`, a pattern of plain variables (or a tuple of
        them), returning `body`."""
        names = _pattern_names(pat)
        if names is None:
            raise Unsupported()
        saved = dict(self.locals)
        params = self._params(names)
        try:
            code = self.expr(body)
        finally:
            self.locals = saved
        return _function(params, _is_tuple(pat), code)

    def _params(self, names: list) -> list[str]:
        """Python parameter names for the symbols `names` (None: '_'), now known as locals."""
        params = []
        for i, uid in enumerate(names):
            py = f"_L{uid}" if uid is not None else f"_W{i}"  # one name per '_': Python refuses a repeated one
            params.append(py)
            if uid is not None:
                self.locals[uid] = py
        return params

    def _c_Let(self, e):
        """`let val p = v ... fun f p = b ... in body end`, where each pattern is plain variables and each
        function has one clause of one argument and does not call itself: each declaration binds the
        parameter of a Python lambda applied at once, so values are computed in order, before the body,
        as SML does. Other declarations leave the whole `let` to the evaluator."""
        saved = dict(self.locals)
        frames: list[tuple[list[str], str, bool]] = []  # (parameters, value, value is a tuple to spread)
        try:
            for d in e.decls:
                if isinstance(d, E.ValDecl):
                    names = _pattern_names(d.pat)
                    if names is None:
                        raise Unsupported()
                    value = self.expr(d.expr)
                    frames.append((self._params(names), value, _is_tuple(d.pat)))
                elif isinstance(d, E.FunDecl):
                    clause = d.clauses[0]
                    if len(d.clauses) != 1 or len(clause.params) != 1 or d.ref.uid in _local_uids(clause.body):
                        raise Unsupported()
                    value = self._lambda(clause.params[0], clause.body)
                    frames.append((self._params([d.ref.uid]), value, False))
                else:
                    raise Unsupported()
            code = self.expr(e.body)
        finally:
            self.locals = saved
        for params, value, spread in reversed(frames):
            code = f"{_function(params, spread, code)}({value})"
        return code

    def _c_App(self, e):
        if isinstance(e.fn, E.Name) and isinstance(e.arg, E.Const):
            instances = self.places.get(e.fn.ref.uid)
            if instances is not None and e.arg.value in instances:
                return f"MK(S, {instances[e.arg.value]})"
        return super()._c_App(e)


def _local_uids(e) -> set[int]:
    """The uids of the local names read anywhere under `e` (also in a `let`'s declarations and in rules)."""
    out: set[int] = set()
    stack = [e]
    while stack:
        n = stack.pop()
        if isinstance(n, E.Name) and n.ref.kind == "local":
            out.add(n.ref.uid)
        if dataclasses.is_dataclass(n) and not isinstance(n, type):
            stack.extend(getattr(n, f.name) for f in dataclasses.fields(n) if f.name not in ("span", "ty", "ref"))
        elif isinstance(n, (list, tuple)):
            stack.extend(n)
    return out


def _function(params: list[str], spread: bool, code: str) -> str:
    """A Python lambda of one argument returning `code`: the argument is `params[0]`, or, with `spread`, a
    tuple whose items are `params`."""
    if spread:
        return f"(lambda _t: (lambda {', '.join(params)}: {code})(*_t))"
    return f"(lambda {params[0]}: {code})"


def _bare(pat):
    """The pattern under its type annotations (`f : FRAME` binds what `f` binds)."""
    while isinstance(pat, E.PAnnot):
        pat = pat.pat
    return pat


def _pattern_names(pat) -> list | None:
    """Symbol uids bound by a pattern of plain variables (None for '_'), or None for other patterns; a type
    annotation (`f : FRAME`) binds what its pattern binds."""
    pat = _bare(pat)
    if isinstance(pat, E.PWild):
        return [None]
    if isinstance(pat, E.PVar) and pat.ref.kind == "local":
        return [pat.ref.uid]
    if isinstance(pat, E.PTuple):
        out = []
        for p in pat.items:
            got = _pattern_names(p)
            if got is None or len(got) != 1 or _is_tuple(p):
                return None
            out.extend(got)
        return out
    return None


def _is_tuple(pat) -> bool:
    return isinstance(_bare(pat), E.PTuple)


__all__ = ["PredicateCompiler"]
