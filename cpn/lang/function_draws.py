"""Finite draws inside the model's functions, explored as choices (docs/semantics.md, "Bindings").

A call `f a1 .. an` of a top-level function that draws (`discrete`, `bernoulli` with constant arguments,
`CS.ran()`, directly or through the functions it calls), with all its arguments, in an output arc inscription
or a transition delay, is written out there, so that each of its draws becomes a free variable of the
transition (the mechanism of `CS.ran()`). The draws of a function that the net uses otherwise are random
draws (simulate only). A mixin of the checker (`cpn.lang.typecheck.Checker`), through `TypeInference`.
"""

from __future__ import annotations

import copy

from cpn.expr.binding import children
from cpn.lang import ast as A
from cpn.lang import types as T
from cpn.lang.builtins import FINITE_DRAWS, RANDOM_BUILTINS
from cpn.lang.checked import Env
from cpn.lang.symbols import Symbol


class FunctionDraws:
    """Which functions draw, which call which, and which calls are written out."""

    def init_draws(self) -> None:
        self.ran_counter = 0
        self.ran_marked = False  # an App node was marked to be replaced (`ran_var`): see pages._replace_ran
        self.ran_sink: list | None = None
        self.random_draws: list = []  # (name, span): calls of random distribution functions (simulate only)
        self.choice_draws: list = []  # (call, span): discrete, bernoulli explored as a choice (our extension)
        # the free variables that stand for a draw (CS.ran(), discrete, bernoulli, @+[a,b]) -> the weight of
        # each value in simulate (bernoulli: p and 1 - p), or None where every value is equally likely
        self.draw_variables: dict[str, dict | None] = {}
        # a transition's span -> the variables that a guard conjunct binds to its draws (`output_binder`)
        self.draw_outputs: dict = {}
        # real-valued delays, reference variables, side effects: (what, span, hint, name), simulate only
        self.simulation_only_uses: list = []
        self.current_fun: str | None = None  # the top-level function being checked
        self.fun_draws: dict[str, list[A.Name]] = {}  # its draws
        self.fun_effects: dict[str, list[A.Name]] = {}  # its uses of the clock or text output (simulate only)
        self.fun_refs: dict[str, set[str]] = {}  # the top-level functions it names
        self.fun_used_outside: set[str] = set()  # named by the net other than in a call written out
        self.fun_asts: dict[str, A.FunDecl] = {}  # the text of those that may draw, as written

    def record_draws(self, checked) -> None:
        checked.random_draws = list(self.random_draws)
        checked.choice_draws = list(self.choice_draws)
        checked.draw_variables = dict(self.draw_variables)
        checked.draw_outputs = {span: frozenset(names) for span, names in self.draw_outputs.items()}
        checked.simulation_only = list(self.simulation_only_uses)

    def top_fun_decl(self, d: A.FunDecl):
        """`fun_decl` of a top-level function, keeping its text if it may draw and noting its draws."""
        if isinstance(d.name, str) and not isinstance(d.ref, tuple) and self.may_draw(d):
            try:
                self.fun_asts[d.name] = copy.deepcopy(d)  # its text as written, for calls written out
            except RecursionError:
                pass  # nested too deeply to be copied: its draws stay draws
        outer, self.current_fun = self.current_fun, d.name if isinstance(d.name, str) else None
        try:
            return self.fun_decl(d)
        finally:
            self.current_fun = outer

    def may_draw(self, d: A.FunDecl) -> bool:
        """Whether a function declaration, not checked yet, names a random draw or a function declared
        before it that may draw (a cheap look, so that only such functions are kept for `drawing_call`)."""
        stack = [c.body for c in d.clauses]
        while stack:
            x = stack.pop()
            if isinstance(x, A.Name) and (x.name in RANDOM_BUILTINS or x.name.endswith(".ran")
                                          or x.name in self.fun_asts):
                return True
            stack.extend(c for c in children(x) if c is not None)
        return False

    def drawing_call(self, e: A.App, env: Env) -> T.Type | None:
        """A call `f a1 .. an` of a top-level function that draws (discrete, bernoulli, CS.ran(), directly or
        through other functions), in an output arc inscription or a delay, with all its arguments: the call
        is written out (`case (a1, .., an) of clause patterns => bodies`, each body in the global scope), so
        that each draw in it is a choice of every value, as if it were written there (docs/semantics.md).
        A recursive function, a partial application, or a draw whose arguments depend on the function's
        arguments stay random draws. Returns the call's type, or None if the call is not written out."""
        args, fn = [], e
        while isinstance(fn, A.App):
            args.append(fn.arg)
            fn = fn.fn
        d = self.fun_asts.get(fn.name) if isinstance(fn, A.Name) else None
        if d is None or len(d.clauses[0].params) != len(args) or self.resolve_name(fn.name, env, fn.span) \
                is not self.genv.lookup(fn.name) or not self._draws_without_recursion(fn.name):
            return None
        args.reverse()
        subject = args[0] if len(args) == 1 else A.TupleE(e.span, args)
        st = self.infer(subject, env)
        rules, rt = [], T.TVar()
        for c in copy.deepcopy(d.clauses):
            pat = c.params[0] if len(args) == 1 else A.PTuple(c.span, list(c.params))
            binds: dict[str, Symbol] = {}
            self.must(self.infer_pat(pat, binds), st, pat.span, f"the arguments of '{fn.name}'")
            self.must(self.infer(c.body, self.genv.child(binds)), rt, c.body.span, f"the result of '{fn.name}'")
            rules.append((pat, c.body))
        e.ran_var = A.Case(e.span, subject, rules, ty=rt)  # put in place of the call by `_replace_ran`
        self.ran_marked = True
        return rt

    def _draws_without_recursion(self, name: str) -> bool:
        """Whether top-level function `name` draws (itself or through the functions it calls), only draws
        that can be a choice, and is not recursive (a recursive function may draw any number of times)."""
        seen, stack = set(), list(self.fun_refs.get(name, ()))
        while stack:
            f = stack.pop()
            if f == name:
                return False
            if f not in seen:
                seen.add(f)
                stack.extend(self.fun_refs.get(f, ()))
        draws = [e for f in seen | {name} for e in self.fun_draws.get(f, ())]
        return bool(draws) and all(self._finite(e.name) for e in draws)

    def _finite(self, name: str) -> bool:
        """Whether a draw can be a choice: discrete, bernoulli, or CS.ran() of a colour set small enough to try
        every value (a function that draws from anything else keeps its draws: simulate only)."""

        if name in FINITE_DRAWS:
            return True
        cs = self.colsets.get(name.rsplit(".", 1)[0]) if name.endswith(".ran") else None
        return cs is not None and cs.values() is not None

    def take_choices(self, info, sink: list) -> None:
        """The free variables made for the choices of one inscription (`sink`) become the transition's."""
        for v, cs, sym in sink:
            info.ran.append((v, cs))
            self.variables[v] = sym

    def output_binder(self, g: A.Expr, info) -> bool:
        """Whether guard `g` is `p = e` with p a variable or a tuple of variables that occur nowhere but in
        the output arcs and the delay of the transition (a CPN Tools code segment's output variables, bound
        once per binding element): the draws of e are then choices, as in those inscriptions, and every
        inscription that reads p reads the same choice (docs/semantics.md, "Bindings")."""
        if not (isinstance(g, A.BinOp) and g.op == "="):
            return False
        items = g.left.items if isinstance(g.left, A.TupleE) else [g.left]
        if not all(isinstance(x, A.Name) for x in items):
            return False
        names = {x.name for x in items}
        if len(names) != len(items) or any(getattr(self.genv.lookup(n), "kind", None) != "var" for n in names):
            return False
        d = info.decl
        elsewhere = [a.expr for a in info.arcs if not a.kind.produces or a.kind.consumes]
        elsewhere += [x for x in d.guards if x is not g] + [d.priority]
        return not any(names & _names(x) for x in elsewhere)

    def settle_function_draws(self) -> None:
        """The draws inside top-level functions: those of a function the net uses other than by a call that
        is written out (`drawing_call`): in a guard, an input arc, a `val`, an initial marking, a recursive
        or partial call, directly or through other functions, are random draws (W0105, simulate only)."""
        used, stack = set(), list(self.fun_used_outside)
        while stack:
            f = stack.pop()
            if f not in used:
                used.add(f)
                stack.extend(self.fun_refs.get(f, ()))
        for f in sorted(used):
            for e in self.fun_draws.get(f, ()):
                self.random_draw(e)
            for e in self.fun_effects.get(f, ()):
                self.effect_builtin(e)


def _names(e) -> set[str]:
    """The names an expression (checked or not) mentions."""
    out, stack = set(), [e]
    while stack:
        x = stack.pop()
        if isinstance(x, A.Name):
            out.add(x.name)
        elif x is not None:
            stack.extend(children(x))
    return out
