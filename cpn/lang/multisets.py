"""Type inference where a multiset is expected (arc inscriptions, initial markings, operands of '++' and
'@+'): a single value means ``1`value``, and a list of values means the multiset of its elements, as in
CPN Tools, whose multisets are lists.

A mixin of `cpn.lang.typecheck.Checker`, which provides inference and diagnostics.
Imports `cpn.lang.*` and layer 0.
"""

from __future__ import annotations

from cpn.expr.binding import all_vars
from cpn.expr.evaluate import run_deep
from cpn.lang import ast as A
from cpn.lang import types as T
from cpn.lang.builtins import MLError
from cpn.lang.checked import Abort, Env
from cpn.lang.symbols import Symbol
from cpn.values import colours as C


def _is_ms(t) -> bool:
    return isinstance(t, T.TCon) and t.name == "ms"


def _is_list(t) -> bool:
    return isinstance(t, T.TCon) and t.name == "list"


class MultisetInference:
    """Inference of expressions in a multiset context (mixed into the Checker)."""

    def infer_ms(self, e: A.Expr, elem: T.Type, env: Env, what: str) -> A.Expr:
        """Infer e where a multiset over `elem` is expected and return the expression to use: a single value
        is wrapped in ToMs, a list of values becomes the multiset of its elements.

        The expected element type is passed down through '++', '--', '+++', '@+' and the branches of 'if',
        so that ``1`x ++ f y`` with `f y` a list of colours is read as CPN Tools reads it.
        """
        if isinstance(e, A.BinOp) and e.op in ("++", "--", "+++"):
            e.left = self.infer_ms(e.left, elem, env, f"the left operand of '{e.op}'")
            e.right = self.infer_ms(e.right, elem, env, f"the right operand of '{e.op}'")
            e.ty = T.ms(elem)
            return e
        if isinstance(e, A.BinOp) and e.op in ("@+", "@++"):
            self.refuse_second_delay(e)
            e.left = self.infer_ms(e.left, elem, env, f"the tokens of '{e.op}'")
            if e.op == "@++":
                self.real_delay(e, env)
            else:
                self.infer_delay(e, env)
            e.ty = T.ms(elem)
            return e
        if isinstance(e, A.If):
            self.must(self.infer(e.cond, env), T.BOOL, e.cond.span, "the condition of 'if'")
            e.then = self.infer_ms(e.then, elem, env, what)
            e.else_ = self.infer_ms(e.else_, elem, env, what)
            if isinstance(e.then, A.ToMs) and isinstance(e.else_, A.ToMs):
                # two single values: ``1`(if c then a else b)``, the form the engines bind tokens with
                e.then, e.else_, e.ty = e.then.expr, e.else_.expr, elem
                return A.ToMs(e.span, e, ty=T.ms(elem))
            e.ty = T.ms(elem)
            return e
        return self.ms_of_typed(e, self.infer(e, env), elem, what)

    def ms_of_typed(self, e: A.Expr, t: T.Type, elem: T.Type, what: str) -> A.Expr:
        """`infer_ms` for a plain expression e already inferred to type t."""
        self.force_ms(t)
        pt = T.prune(t)
        if _is_ms(pt):
            self.must(pt.args[0], elem, e.span, what)
            return e
        if isinstance(pt, T.TVar):
            # not known yet (e.g. a recursive call): a multiset, as CPN ML's ++ requires
            self.must(pt, T.ms(elem), e.span, what)
            return e
        pe = T.prune(elem)
        if _is_list(pt) and not _is_list(pe) and not isinstance(pe, T.TVar):
            # a list where a multiset of non-lists is expected: its elements are the tokens (CPN Tools)
            self.must(pt.args[0], elem, e.span, what)
            return self.list_as_multiset(e, elem)
        self.must(t, elem, e.span, what)
        return A.ToMs(e.span, e, ty=T.ms(elem))

    @property
    def appends(self) -> list[tuple]:
        """The open readings of `l1 ++ l2` (`infer_plus`), decided by `resolve_appends`."""
        return self.__dict__.setdefault("_open_appends", [])

    def infer_plus(self, e: A.BinOp, env: Env) -> T.Type:
        """`a ++ b` outside a multiset context. CPN Tools' multisets are lists and its `++` is list append
        (`type 'a ms = 'a list`, `ms1 ++ ms2 = ms1 @ ms2`): when both operands are lists of the same type,
        the reading is left open (a variable with `append` set) and decided by the context, a list where a
        list is expected (`a @ b`, left operand first), otherwise the multiset of the two lists as before."""
        lt, rt = self.infer(e.left, env), self.infer(e.right, env)
        pl, pr = T.prune(lt), T.prune(rt)
        el = pl.append if isinstance(pl, T.TVar) and pl.append is not None else pl if _is_list(pl) else None
        er = pr.append if isinstance(pr, T.TVar) and pr.append is not None else pr if _is_list(pr) else None
        if el is None or er is None:
            elem = T.TVar()
            e.left = self.ms_of_typed(e.left, lt, elem, "the left operand of '++'")
            e.right = self.ms_of_typed(e.right, rt, elem, "the right operand of '++'")
            return T.ms(elem)
        self.must(er, el, e.right.span, "the right operand of '++' (a list like its left operand)")
        r = T.TVar()
        r.append = el
        self.appends.append((e, r, el, (pl, pr)))
        return r

    def force_ms(self, t: T.Type) -> None:
        """Decide an open `l1 ++ l2` (see `infer_plus`) as the multiset of the two lists."""
        p = T.prune(t)
        if isinstance(p, T.TVar) and p.append is not None:
            T.unify(p, T.ms(p.append))

    def resolve_appends(self) -> None:
        """Decide every open `l1 ++ l2`, outermost first: a multiset unless the context made it a list."""
        while self.appends:
            e, r, el, operands = self.appends.pop()
            self.force_ms(r)
            decided = T.prune(r)
            inner = [isinstance(x, T.TVar) for x in operands]  # an operand that is itself an open `++`
            for x, is_inner in zip(operands, inner):
                if is_inner:
                    T.unify(x, decided)
            if _is_ms(decided):
                mst = T.ms(el)
                if not inner[0]:
                    e.left = A.ToMs(e.left.span, e.left, ty=mst)
                if not inner[1]:
                    e.right = A.ToMs(e.right.span, e.right, ty=mst)
                e.ty = mst
            else:
                e.op = "@"
                e.ty = decided

    def list_as_multiset(self, e: A.Expr, elem: T.Type) -> A.Expr:
        """The multiset of the elements of list expression e: a list literal becomes ``1`a ++ 1`b`` (so that
        its variables can be bound by tokens on an input arc), any other list ``list_to_ms e``."""
        mst = T.ms(elem)
        if isinstance(e, A.ListE):
            if not e.items:
                empty = A.Name(e.span, "empty", ty=mst)
                empty.ref = self.builtin_syms["empty"]
                return empty
            out: A.Expr = A.ToMs(e.items[0].span, e.items[0], ty=mst)
            for x in e.items[1:]:
                out = A.BinOp(e.span, "++", out, A.ToMs(x.span, x, ty=mst), ty=mst)
            return out
        fn = A.Name(e.span, "list_to_ms", ty=T.TFun(T.lst(elem), mst))
        fn.ref = self.builtin_syms["list_to_ms"]
        return A.App(e.span, fn, e, ty=mst)

    def ms_as_list(self, e: A.Expr, mst: T.Type) -> A.Expr:
        """The list of the elements of multiset expression e, in the order of its colour set: ``ms_to_list e``."""
        lt = T.lst(mst.args[0])
        fn = A.Name(e.span, "ms_to_list", ty=T.TFun(mst, lt))
        fn.ref = self.builtin_syms["ms_to_list"]
        return A.App(e.span, fn, e, ty=lt)

    def time_interval(self, e: A.ListE, env: Env) -> A.Expr:
        """CPN Tools 4's time interval `@+[a,b]` (a transition delay or an output arc's): the delay is chosen
        in the binding, one binding element per integer of a..b, as a free variable over a..b (`CS.ran()`'s
        mechanism). The bounds are constants."""
        what = f"the time interval '@+[...]' at {e.span.line}:{e.span.col}"
        if self.ran_sink is None:
            self.error("E0206", f"{what} is allowed only as a transition delay or on an output arc", e.span)
            raise Abort()
        bounds = []
        for b in e.items:
            self.must(self.infer(b, env), T.INT, b.span, "a bound of a time interval (an integer)")
            if all_vars(b):
                self.error("E0206", f"the bounds of {what} are constants; this one depends on the binding",
                           b.span, hint="Write the bounds with numbers and 'val' constants.")
                raise Abort()
            try:
                bounds.append(run_deep(self.ev.eval, b, {}))
            except (MLError, RecursionError) as exc:
                self.error("E0401", f"evaluating a bound of {what} failed: {exc}", b.span)
                raise Abort() from None
        lo, hi = bounds
        if not 0 <= lo <= hi:
            self.error("E0301", f"{what} is [{lo},{hi}]: the bounds must satisfy 0 <= a <= b", e.span)
            raise Abort()
        fn = A.Name(e.span, "ignore", ty=T.TFun(T.UNIT, T.UNIT))
        node = A.App(e.span, fn, A.Const(e.span, (), "unit", ty=T.UNIT), ty=T.INT)
        self.choice_variable(node, f"@+[{lo},{hi}]", lo, hi)  # no colour-set name can be written so
        return node

    def choice_variable(self, node: A.App, name: str, lo: int, hi: int, weights: dict | None = None) -> None:
        """Make App `node` stand for a free variable over the integers lo..hi (colour set `name`, made here):
        every value is one binding element (CS.ran()'s mechanism; `_replace_ran` puts the variable in).
        `weights` gives the probability of each value in simulate (None: all equally likely)."""
        if name not in self.colsets:
            self.colsets[name] = C.IntCS(name, lo, hi)
            self.cstypes[name] = T.INT
        self.ran_counter += 1
        vsym = Symbol(f"{name}#{self.ran_counter}", "var", T.INT, node.span, name)
        self.ran_sink.append((vsym.name, name, vsym))
        self.draw_variables[vsym.name] = weights
        node.fn = A.Name(node.span, "ignore", ty=T.TFun(T.UNIT, T.UNIT))
        node.fn.ref = self.builtin_syms["ignore"]
        node.arg = A.Const(node.span, (), "unit", ty=T.UNIT)
        node.ran_var = vsym
        self.ran_marked = True

    def finite_draw(self, e: A.App, env: Env) -> T.Type:
        """`discrete(a, b)` and `bernoulli(p)`, CPN Tools' random draws over finitely many integers, where
        `CS.ran()` would be a choice (an output arc inscription, a transition delay): a choice of every value,
        our extension (CPN Tools' state space tool cannot analyse random distribution functions)."""
        fname = e.fn.name
        if self.ran_sink is None:
            self.error("E0206", f"'{fname}' draws a random value here: it is a choice of every value only where it "
                       "is called in an output arc inscription or a transition delay", e.span,
                       hint=f"Call {fname} in the output arc inscription or the delay, and pass the value to the "
                            "function as an argument.", name=fname)
            raise Abort()
        args = e.arg.items if isinstance(e.arg, A.TupleE) else [e.arg]
        want = (T.INT, T.INT) if fname == "discrete" else (T.REAL,)
        if len(args) != len(want):
            self.error("E0301", f"'{fname}' takes {'(a, b), two integers' if fname == 'discrete' else 'a real p'}",
                       e.arg.span)
            raise Abort()
        values = []
        for a, t in zip(args, want):
            self.must(self.infer(a, env), t, a.span, f"the argument of '{fname}'")
            if all_vars(a):
                self.error("E0206", f"the arguments of '{fname}' explored as a choice are constants; this one "
                           "depends on the binding", a.span, hint="Write them with numbers and 'val' constants.")
                raise Abort()
            try:
                values.append(run_deep(self.ev.eval, a, {}))
            except (MLError, RecursionError) as exc:
                self.error("E0401", f"evaluating the argument of '{fname}' failed: {exc}", a.span)
                raise Abort() from None
        if fname == "discrete":
            lo, hi = values
            if lo > hi:
                self.error("E0301", f"discrete({lo}, {hi}) has no value: a > b", e.span)
                raise Abort()
        else:
            p = values[0]
            if not 0.0 <= p <= 1.0:
                self.error("E0301", f"bernoulli({p}): p is a probability, from 0.0 to 1.0", e.span)
                raise Abort()
            lo, hi = (0 if p < 1.0 else 1), (1 if p > 0.0 else 0)  # 1 with probability p, else 0
        weights = {0: 1.0 - values[0], 1: values[0]} if fname == "bernoulli" else None
        self.choice_variable(e, f"{fname}({lo},{hi})", lo, hi, weights)
        if any(d.code == "W0104" and d.span == e.span for d in self.diags):
            return T.INT  # a draw in a function written out at several calls: one warning
        self.choice_draws.append((f"{fname}({', '.join(map(str, values))})", e.span))
        self.warn("W0104", f"{fname}{'(' + ', '.join(map(str, values)) + ')'} is explored as a choice of every value "
                  f"({lo}..{hi}), one binding element each; simulate draws one", e.span,
                  hint="CPN Tools' state space tool cannot analyse random distribution functions: this reading is "
                       "cpn-verify's (docs/semantics.md).", name=fname)
        return T.INT

    def infer_delay(self, e: A.BinOp, env: Env) -> None:
        """The delay d of `tokens @+ d`: an integer, or a time interval `[a, b]`."""
        if isinstance(e.right, A.ListE) and len(e.right.items) == 2:
            e.right = self.time_interval(e.right, env)
            return
        dt = self.infer(e.right, env)
        if not self.unify(dt, T.INT, e.right.span, "a time delay (it must be an integer)"):
            raise Abort()

    def refuse_second_delay(self, e: A.BinOp) -> None:
        """`e @+ d1 @+ d2`: CPN Tools' '@+' delays an untimed multiset, so a delayed one is a type error there."""
        if isinstance(e.left, A.BinOp) and e.left.op in ("@+", "@++"):
            self.error("E0301", f"'{e.op}' delays a multiset that '{e.left.op}' has delayed already", e.span,
                       hint="CPN ML's '@+' takes an untimed multiset (CPN Tools: 'ms @+ int' is a timed multiset). "
                            "Write one delay, 'e @+ (d1 + d2)', or add delayed terms with '+++'.")
            raise Abort()

    def hint_delay_operand(self, node: A.BinOp) -> None:
        """The hint for a type error at an operator one of whose operands is a delay written without
        parentheses: `x @+ d + 1` is `(x @+ d) + 1`, as '@+' is CPN Tools' `infix 7`, tighter than '+'."""
        for side in (node.left, node.right):
            if isinstance(side, A.BinOp) and side.op in ("@+", "@++") and self.diags:
                self.diags[-1].hint = (f"'{side.op}' is an operator of CPN ML as tight as '*' (CPN Tools' infix 7), "
                                       f"so it takes one operand on each side of '{node.op}': put the delay or the "
                                       f"delayed multiset in parentheses, e.g. 'e @+ (d + 1)'.")
                return
