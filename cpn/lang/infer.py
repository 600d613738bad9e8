"""Type inference of CPN ML expressions and patterns (Hindley-Milner with CPN ML's overloaded operators)
and types of annotations.

A mixin of `cpn.lang.typecheck.Checker`, which provides the scopes, name resolution and diagnostics.
Imports `cpn.lang.*` and layer 0.
"""

from __future__ import annotations

from typing import NoReturn

from cpn._util import did_you_mean
from cpn._util.deep import left_spine
from cpn.diagnostics import Span
from cpn.expr.binding import children
from cpn.expr.forms import FORMS
from cpn.lang import ast as A
from cpn.lang import types as T
from cpn.lang.builtins import (
    FINITE_DRAWS,
    LIBRARY_TYPES,
    RANDOM_BUILTINS,
    SIMULATION_ONLY_BUILTINS,
    STOPS_SIMULATE,
)
from cpn.lang.checked import Abort, Env
from cpn.lang.function_draws import FunctionDraws
from cpn.lang.symbols import Symbol

# operators with a typing rule of their own (multisets, time), which end a chain of plain operators
_MS_OPS: frozenset[str] = frozenset({"++", "--", "+++", "@+", "@++", "@@"})


def _ms_form(e: A.Expr) -> bool:
    """An operand that `infer_ms` reads in a multiset context of its own (not a plain expression)."""
    return (isinstance(e, A.BinOp) and e.op in _MS_OPS and e.op != "++") or isinstance(e, A.If)


def _is_list_con(t: T.Type) -> bool:
    t = T.prune(t)
    return isinstance(t, T.TCon) and t.name == "list"


def _may_hold_lists(t: T.Type) -> bool:
    """Whether t, an element type, may be a list type (so that a multiset of lists read as a list fits)."""
    t = T.prune(t)
    return isinstance(t, T.TVar) or _is_list_con(t)


def _wants_list_of_lists(t: T.Type) -> bool:
    """Whether t, the other operand of '@', may be a list of lists or a multiset (read as a list)."""
    t = T.prune(t)
    if isinstance(t, T.TVar) or (isinstance(t, T.TCon) and t.name == "ms"):
        return True
    return _is_list_con(t) and _may_hold_lists(t.args[0])


def _not_plain(node: A.BinOp) -> bool:
    return node.op in _MS_OPS


# CPN Tools' random draws over finitely many integers, explored as a choice of every value where CS.ran() is one

# The library functions on multisets that CPN Tools models also give a list (a multiset is a list there)
LIST_AS_MS_FUNCTIONS: frozenset[str] = frozenset({"ms_to_list", "ms_to_col", "size"})


def random_hint(name: str) -> str:
    """What to change so that a state space can hold the draw of random distribution function `name`."""
    where = ("in an output arc inscription or a transition delay, directly or in a function that is not "
             "recursive and is called there with all its arguments (not in a guard, an input arc, a 'val' or a "
             "function given to another), where it is explored as a choice of every value")
    if name.endswith(".ran"):
        return f"For a state space, call {name}() {where}."
    if name in FINITE_DRAWS:
        return f"For a state space, call {name} with constant arguments {where}."
    return (f"For a state space, replace {name}(...) by a finite choice: a small colour set "
            "'colset D = int with 1..5;' and 'D.ran()' in an output arc or a delay (every value is explored), "
            "or a bounded 'discrete(a, b)' there.")


class TypeInference(FunctionDraws):
    """Inference of expressions, patterns and annotations (mixed into the Checker)."""

    types = T  # the types, for the type rules of the forms that declare their own (cpn.expr.forms)

    def type_of_annotation(self, te: A.TypeExpr) -> T.Type | None:
        if isinstance(te, A.TName):
            if te.name in self.cstypes:
                return self.cstypes[te.name]
            simple = {"int": T.INT, "bool": T.BOOL, "string": T.STRING, "unit": T.UNIT, "real": T.REAL,
                      "INT": T.INT, "BOOL": T.BOOL, "STRING": T.STRING, "UNIT": T.UNIT,
                      "order": T.TCon("order"), "time": T.INT}  # time: the model time, an integer
            if te.name in simple:
                return simple[te.name]
            if te.name in LIBRARY_TYPES:  # `: Date.month`, `NONE : TextIO.outstream option`
                return T.TCon(te.name)
            self.lookup_colset(te.name, te.span)
            return None
        if isinstance(te, A.TPost):
            inner = self.type_of_annotation(te.arg)
            if inner is None:
                return None
            if te.name in ("list", "ms", "option", "ref"):
                return T.TCon(te.name, (inner,))
            self.error("E0201", f"unknown type constructor '{te.name}'", te.span)
            return None
        if isinstance(te, A.TTuple):
            items = [self.type_of_annotation(x) for x in te.items]
            return None if None in items else T.TTuple(items)
        return None

    def unify(self, a, b, span, what: str) -> bool:
        try:
            T.unify(a, b)
            return True
        except T.UnifyError as exc:
            names: dict = {}
            detail = f" ({exc})" if str(exc) else ""
            self.error("E0301", f"type mismatch in {what}: found {T.show(a, names)}, expected {T.show(b, names)}"
                       + detail, span, found=T.show(a), expected=T.show(b))
            return False

    def must(self, a, b, span, what):
        if not self.unify(a, b, span, what):
            raise Abort()

    def abort(self) -> NoReturn:
        """Give up the expression being typed (after its error was reported)."""
        raise Abort()

    def infer_top(self, e: A.Expr, env: Env | None = None) -> T.Type | None:
        try:
            t = self.infer(e, env or self.genv)
            self.resolve_pending()
            return t
        except Abort:
            self.pending.clear()
            self.appends.clear()
            return None

    def resolve_pending(self) -> None:
        self.resolve_appends()
        progress = True
        while self.pending and progress:
            progress = False
            for item in list(self.pending):
                if self._try_select(*item):
                    self.pending.remove(item)
                    progress = True
        for node, _argt, _rest, kind in self.pending:
            self.error("E0301", f"cannot tell which record or tuple '#{node.label}' selects from" if kind == "sel"
                       else "cannot tell the type of this flexible record pattern", node.span,
                       hint="Add a type annotation, e.g. (x : MyRecord).")
        if self.pending:
            self.pending.clear()
            raise Abort()

    def _try_select(self, node, argt, rest, kind) -> bool:
        t = T.prune(argt)
        if isinstance(t, T.TVar):
            return False
        if kind == "pat":
            if not isinstance(t, T.TRecord):
                self.error("E0301", "a record pattern matches a value that is not a record", node.span)
                return True
            node.ty_labels = t.labels()
            for label, ft in rest:
                fields = dict(t.fields)
                if label not in fields:
                    self.error("E0301", f"the record has no field '{label}'", node.span)
                    return True
                self.unify(ft, fields[label], node.span, f"field '{label}'")
            return True
        if isinstance(t, T.TRecord):
            labels = t.labels()
            if node.label not in labels:
                self.error("E0301", f"the record {T.show(t)} has no field '{node.label}'", node.span,
                           hint=f"Its fields are {', '.join(labels)}.")
                return True
            node.index = labels.index(node.label)
            self.unify(rest, t.fields[node.index][1], node.span, f"'#{node.label}'")
            return True
        if isinstance(t, T.TTuple) and node.label.isdigit():
            i = int(node.label)
            if not 1 <= i <= len(t.items):
                self.error("E0301", f"'#{i}' selects from a tuple of {len(t.items)} components", node.span)
                return True
            node.index = i - 1
            self.unify(rest, t.items[i - 1], node.span, f"'#{i}'")
            return True
        self.error("E0301", f"'#{node.label}' is applied to a value of type {T.show(t)}", node.span)
        return True

    # ------------------------------------------------------------------ expressions
    def infer(self, e: A.Expr, env: Env) -> T.Type:
        m = getattr(self, "_i_" + type(e).__name__, None)
        # a form that declares its own rules (cpn.expr.forms)
        t = FORMS[e.__class__].infer(self, e, env) if m is None else m(e, env)
        e.ty = t
        return t

    def _i_Const(self, e, env):
        return {"int": T.INT, "string": T.STRING, "bool": T.BOOL, "unit": T.UNIT, "real": T.REAL}[e.kind]

    def _i_Name(self, e, env):
        sym = self.resolve_name(e.name, env, e.span)
        if sym is None:
            self.unknown_name(e.name, env, e.span)
            raise Abort()
        e.ref = sym
        if sym.kind == "fun":  # which functions call which, and which the net uses (settle_function_draws)
            if self.current_fun is not None:
                self.fun_refs.setdefault(self.current_fun, set()).add(sym.name)
            else:
                self.fun_used_outside.add(sym.name)
        if sym.kind == "csop":
            cs, op = sym.data
            cst = self.cstypes[cs]
            if op == "ran":
                # an application CS.ran() in an output arc inscription or a delay never gets here (_i_App):
                # anywhere else it is one random draw, which simulate makes and no state space holds
                self.random_draw(e)
            if op.startswith("set_"):  # CS.set_<field> r v: r with the field set to v, as in CPN Tools
                rt = T.prune(cst)
                return T.TFun(cst, T.TFun(dict(rt.fields)[op[4:]], cst))
            if op == "mult":
                comps = T.prune(cst)
                if not isinstance(comps, T.TTuple):
                    self.error("E0301", f"'{e.name}': mult is defined on product colour sets only", e.span)
                    raise Abort()
                return T.TFun(T.TTuple([T.ms(c) for c in comps.items]), T.ms(cst))
            return {"all": T.TFun(T.UNIT, T.ms(cst)), "size": T.TFun(T.UNIT, T.INT), "ran": T.TFun(T.UNIT, cst),
                    "ord": T.TFun(cst, T.INT), "col": T.TFun(T.INT, cst), "legal": T.TFun(cst, T.BOOL),
                    "mkstr": T.TFun(cst, T.STRING), "lt": T.TFun(T.TTuple([cst, cst]), T.BOOL),
                    "input_ms": T.TFun(T.TCon("TextIO.instream"), T.ms(cst)),
                    "output": T.TFun(T.TTuple([T.TCon("TextIO.outstream"), cst]), T.UNIT),
                    "output_col": T.TFun(T.TTuple([T.TCon("TextIO.outstream"), cst]), T.UNIT),
                    "output_ms": T.TFun(T.TTuple([T.TCon("TextIO.outstream"), T.ms(cst)]), T.UNIT)}[op]
        if sym.kind == "builtin" and sym.name in RANDOM_BUILTINS:
            self.random_draw(e)
        if sym.kind == "builtin" and sym.name in SIMULATION_ONLY_BUILTINS:
            self.effect_builtin(e)
        t = sym.type
        return t.instantiate() if isinstance(t, T.Scheme) else t

    def _depends_on_binding(self, e: A.Expr, env: Env) -> bool:
        """Whether a name in `e` (not yet inferred) is a variable of the transition or a local name."""
        stack = [e]
        while stack:
            x = stack.pop()
            if isinstance(x, A.Name):
                sym = self.resolve_name(x.name, env, x.span)
                if sym is not None and sym.kind in ("var", "local", "param"):
                    return True
                continue
            stack.extend(c for c in children(x) if c is not None)
        return False

    def random_draw(self, e: A.Name) -> None:
        """A call of one of CPN Tools' random distribution functions: simulate draws it (seeded), explore and
        check refuse the model with one error per such call (`random_draws`); lint warns."""
        if any(span == e.span and name == e.name for name, span in self.random_draws):
            return
        if self.current_fun is not None:  # settled once the net's uses of the function are known
            self.fun_draws.setdefault(self.current_fun, []).append(e)
            return
        self.random_draws.append((e.name, e.span))
        self.warn("W0105", f"'{e.name}' draws a random value: simulate runs the model (one run per --seed), "
                  "explore and check cannot analyse it", e.span,
                  hint=random_hint(e.name), name=e.name)

    def simulation_only(self, what: str, span: Span, hint: str, name: str,
                        runs: str = "simulate runs the model") -> None:
        """A construct that simulate runs and no state space can hold (a real-valued delay, a reference
        variable, a code segment's side effect): lint warns (W0106), explore and check refuse the model with
        one error per construct (`simulation_only`), `what` saying what it is and `hint` what to change."""
        if any(span == s and what == w for w, s, _, _ in self.simulation_only_uses):
            return
        self.simulation_only_uses.append((what, span, hint, name))
        self.warn("W0106", f"{what}: {runs}, explore and check cannot analyse it", span,
                  hint=hint, name=name)

    def effect_builtin(self, e: A.Name) -> None:
        """A use of a library function with no state-space meaning (the machine's clock, text output): simulate
        runs it, explore and check refuse the net with one error per use (W0106 in lint), at the built-in
        itself. Inside a top-level function it counts where the net uses the function (`settle_function_draws`)."""
        if self.current_fun is not None:
            self.fun_effects.setdefault(self.current_fun, []).append(e)
            return
        what, hint = SIMULATION_ONLY_BUILTINS[e.name]
        runs = ("simulate runs the model up to the first occurrence that calls it, and stops there"
                if e.name in STOPS_SIMULATE else "simulate runs the model")
        self.simulation_only(f"'{e.name}' {what}", e.span, hint, e.name, runs)

    def real_delay(self, e: A.BinOp, env: Env) -> None:
        """The delay of `e @++ d` (CPN Tools' real-valued delay): a real; simulation only."""
        self.must(self.infer(e.right, env), T.REAL, e.right.span, "a real-valued delay '@++' (a real)")
        self.simulation_only("'@++' is a real-valued delay", e.span,
                             "For a state space, write an integer delay with '@+' (e.g. '@+ round(d)' or a "
                             "bounded choice '@+[a,b]'): model time is an integer there.", "@++")

    def _i_App(self, e, env):
        if isinstance(e.fn, A.Select):
            at = self.infer(e.arg, env)
            ft = self.infer(e.fn, env)
            self.must(ft, T.TFun(at, T.TVar()), e.span, "a field selection")
            if self.pending and self.pending[-1][0] is e.fn and self._try_select(*self.pending[-1]):
                self.pending.pop()
            return T.prune(ft).res
        if self.ran_sink is not None and self.fun_draws:
            t = self.drawing_call(e, env)
            if t is not None:
                return t
        if (isinstance(e.fn, A.Name) and e.fn.name in FINITE_DRAWS and self.ran_sink is not None
                and getattr(self.resolve_name(e.fn.name, env, e.fn.span), "kind", "builtin") == "builtin"
                and not self._depends_on_binding(e.arg, env)):
            # discrete(a, b), bernoulli(p) with constant arguments in an output arc or a delay: a choice, as
            # CS.ran(); anywhere else a draw that only simulation makes (random_draw)
            return self.finite_draw(e, env)
        if isinstance(e.fn, A.Name) and e.fn.name.endswith(".ran") and self.ran_sink is not None:
            sym = self.resolve_name(e.fn.name, env, e.fn.span)
            if sym is not None and sym.kind == "csop":
                # CS.ran() in a transition: a fresh free variable over CS (every value is one binding)
                cs = sym.data[0]
                self.ran_counter += 1
                vname = f"{cs}.ran#{self.ran_counter}"
                vsym = Symbol(vname, "var", self.cstypes[cs], e.span, cs)
                self.ran_sink.append((vname, cs, vsym))
                self.draw_variables[vname] = None  # simulate: every value of CS equally likely
                self.infer(e.arg, env)
                e.fn = A.Name(e.fn.span, "ignore")
                e.fn.ref = self.builtin_syms["ignore"]
                # rewrite in place: App(ignore, ()) is replaced by the variable through the parent
                e.ran_var = vsym
                self.ran_marked = True
                return self.cstypes[cs]
        ft = self.infer(e.fn, env)
        at = self.infer(e.arg, env)
        pf0 = T.prune(ft)
        if isinstance(pf0, T.TFun) and _is_list_con(pf0.arg) and _may_hold_lists(T.prune(pf0.arg).args[0]):
            self.force_ms(at)  # `length (l1 ++ l2)` still reads the multiset of the two lists as a list
        r = T.TVar()
        pf = T.prune(ft)
        if isinstance(pf, T.TFun):
            pa, pt = T.prune(pf.arg), T.prune(at)
            if isinstance(pa, T.TCon) and pa.name == "list" and isinstance(pt, T.TCon) and pt.name == "ms":
                # a multiset where a list is expected: CPN Tools' multisets are lists (`List.map f (CS.all())`)
                e.arg = self.ms_as_list(e.arg, pt)
                at = T.lst(pt.args[0])
            elif (isinstance(pa, T.TCon) and pa.name == "ms" and isinstance(pt, T.TCon) and pt.name == "list"
                    and isinstance(e.fn, A.Name) and e.fn.name in LIST_AS_MS_FUNCTIONS):
                # a list given to a multiset function: CPN Tools' multisets are lists (`size [a, b]`)
                el = pt.args[0]
                if e.fn.name == "ms_to_list":
                    # the list itself, in its order, as in CPN Tools: List.concat [l]
                    self.must(pa, T.ms(el), e.arg.span, f"the argument of {self._fn_name(e.fn)}")
                    self.must(pf.res, r, e.span, "an application")
                    fn = A.Name(e.fn.span, "List.concat", ty=T.TFun(T.lst(T.lst(el)), T.lst(el)))
                    fn.ref = self.builtin_syms["List.concat"]
                    e.fn, e.arg = fn, A.ListE(e.arg.span, [e.arg], ty=T.lst(T.lst(el)))
                    return r
                e.arg = self.list_as_multiset(e.arg, el)
                at = T.ms(el)
            self.must(at, pf.arg, e.arg.span, f"the argument of {self._fn_name(e.fn)}")
            self.must(pf.res, r, e.span, "an application")
        else:
            self.must(ft, T.TFun(at, r), e.fn.span, "an application (the left side is not a function)")
        return r

    @staticmethod
    def _fn_name(f):
        return f"'{f.name}'" if isinstance(f, A.Name) else "the function"

    def is_empty_ms(self, x, env) -> bool:
        return isinstance(x, A.Name) and x.name == "empty" and env.lookup("empty") is None

    def empty_as_list(self, x, other, env=None):
        """`empty` beside a list (the other branch of an `if`, a rule of a `case`) is `[]`: CPN Tools'
        multisets are lists, so `if l = [] then empty else hd l :: f (tl l)` is a list there."""
        if env is not None and not self.is_empty_ms(x, env):
            return x
        po = T.prune(other)
        if isinstance(po, T.TCon) and po.name == "list":
            return A.ListE(x.span, [])
        return x

    def join_branches(self, e, a, b, ta, tb):
        self.force_ms(ta)
        self.force_ms(tb)
        pa, pb = T.prune(ta), T.prune(tb)
        is_ms = lambda t: isinstance(t, T.TCon) and t.name == "ms"  # noqa: E731
        if is_ms(pa) and not is_ms(pb) and not isinstance(pb, T.TVar):
            setattr(e, b, A.ToMs(getattr(e, b).span, getattr(e, b), ty=T.ms(tb)))
            tb = T.ms(tb)
        elif is_ms(pb) and not is_ms(pa) and not isinstance(pa, T.TVar):
            setattr(e, a, A.ToMs(getattr(e, a).span, getattr(e, a), ty=T.ms(ta)))
            ta = T.ms(ta)
        self.must(tb, ta, getattr(e, b).span, "the branches (both must have the same type)")
        return ta

    def op_types(self, op, node):
        if op in ("+", "-", "*"):
            v = T.TVar(overload=("int", "real"))
            node.op_ty = v
            return v, v, v
        if op == "/":
            return T.REAL, T.REAL, T.REAL
        if op in ("div", "mod"):
            return T.INT, T.INT, T.INT
        if op == "^":
            return T.STRING, T.STRING, T.STRING
        if op in ("<", "<=", ">", ">="):
            v = T.TVar(overload=("int", "real", "string"))
            node.op_ty = v
            return v, v, T.BOOL
        if op in ("=", "<>"):
            v = T.TVar(eq=True)
            return v, v, T.BOOL
        if op == "::":
            v = T.TVar()
            return v, T.lst(v), T.lst(v)
        if op in ("^^", "@"):
            v = T.lst(T.TVar())
            return v, v, v
        if op in ("andalso", "orelse"):
            return T.BOOL, T.BOOL, T.BOOL
        if op == "`":
            v = T.TVar()
            return T.INT, v, T.ms(v)
        raise Abort()

    def _i_BinOp(self, e, env):
        op = e.op
        if op == "++" and not any(_ms_form(x) for x in (e.left, e.right)):
            return self.infer_plus(e, env)
        if op in ("++", "--", "+++"):
            elem = T.TVar()
            e.left = self.infer_ms(e.left, elem, env, f"the left operand of '{op}'")
            e.right = self.infer_ms(e.right, elem, env, f"the right operand of '{op}'")
            return T.ms(elem)
        if op == "@+":
            self.refuse_second_delay(e)
            elem = T.TVar()
            e.left = self.infer_ms(e.left, elem, env, "the tokens of '@+'")
            self.infer_delay(e, env)
            return T.ms(elem)
        if op == "@++":
            self.refuse_second_delay(e)
            elem = T.TVar()
            e.left = self.infer_ms(e.left, elem, env, "the tokens of '@++'")
            self.real_delay(e, env)
            return T.ms(elem)
        if op == "@@":
            self.error("E0206", "absolute timestamps '@@' are not supported; use '@+' delays", e.span)
            raise Abort()
        # `a + b - c * d ...`: the left spine in a loop, so that a chain of any length is one frame deep
        first, spine = left_spine(e, A.BinOp, _not_plain)
        t = self.infer(first, env)
        for node in spine:
            op = node.op
            a, b, r = self.op_types(op, node)
            rt = self.infer(node.right, env)
            if op in ("::", "@", "^^"):
                # a multiset where a list is expected: CPN Tools' multisets are lists (``x :: 1`y``)
                # an open `l1 ++ l2` (MultisetInference.infer_plus) is such a multiset where that reading fits
                if op == "::":
                    if _may_hold_lists(t):
                        self.force_ms(rt)
                else:
                    if _wants_list_of_lists(rt):
                        self.force_ms(t)
                    if _wants_list_of_lists(t):
                        self.force_ms(rt)
                pl, pr = T.prune(t), T.prune(rt)
                if op != "::" and isinstance(pl, T.TCon) and pl.name == "ms":
                    node.left = self.ms_as_list(node.left, pl)
                    t = T.lst(pl.args[0])
                if isinstance(pr, T.TCon) and pr.name == "ms":
                    node.right = self.ms_as_list(node.right, pr)
                    rt = T.lst(pr.args[0])
            if not (self.unify(t, a, node.left.span, f"the left operand of '{op}'")
                    and self.unify(rt, b, node.right.span, f"the right operand of '{op}'")):
                self.hint_delay_operand(node)
                raise Abort()
            node.ty = t = r
        return t

    # ------------------------------------------------------------------ patterns
    def infer_pat(self, p: A.Pat, binds: dict[str, Symbol]) -> T.Type:
        t = self._infer_pat(p, binds)
        p.ty = t
        return t

    def _bind_local(self, name, span, binds, t):
        if name in binds:
            self.error("E0202", f"variable '{name}' occurs twice in one pattern", span)
            raise Abort()
        sym = Symbol(name, "local", t, span)
        binds[name] = sym
        return sym

    def _infer_pat(self, p, binds):
        if isinstance(p, A.PWild):
            return T.TVar()
        if isinstance(p, A.PVar):
            g = self.globals.get(p.name)
            if g is not None and g.kind == "con" and not g.data.has_arg:
                p.ref = g
                return g.type.instantiate() if isinstance(g.type, T.Scheme) else g.type  # NONE
            t = T.TVar()
            p.ref = self._bind_local(p.name, p.span, binds, t)
            return t
        if isinstance(p, A.PConst):
            return {"int": T.INT, "string": T.STRING, "bool": T.BOOL, "unit": T.UNIT}[p.kind]
        if isinstance(p, A.PTuple):
            return T.TTuple([self.infer_pat(x, binds) for x in p.items])
        if isinstance(p, A.PList):
            v = T.TVar()
            for x in p.items:
                self.must(self.infer_pat(x, binds), v, x.span, "the elements of a list pattern")
            return T.lst(v)
        if isinstance(p, A.PCons):
            h = self.infer_pat(p.head, binds)
            tl = self.infer_pat(p.tail, binds)
            self.must(tl, T.lst(h), p.span, "a '::' pattern")
            return tl
        if isinstance(p, A.PCon):
            g = self.globals.get(p.name)
            if g is None or g.kind != "con" or not g.data.has_arg:
                cand = did_you_mean(p.name, [n for n, s in self.globals.items() if s.kind == "con"])
                self.error("E0201", f"'{p.name}' is not a constructor with an argument", p.span,
                           hint=f"Did you mean '{cand}'?" if cand else None, name=p.name)
                raise Abort()
            p.ref = g
            ft = g.type.instantiate() if isinstance(g.type, T.Scheme) else g.type  # SOME x
            self.must(self.infer_pat(p.arg, binds), ft.arg, p.arg.span, f"the argument of '{p.name}'")
            return ft.res
        if isinstance(p, A.PRecord):
            fields = [(label, self.infer_pat(q, binds)) for label, q in p.fields]
            if p.flexible:
                v = T.TVar()
                self.pending.append((p, v, fields, "pat"))
                return v
            p.ty_labels = sorted(label for label, _ in fields)
            return T.TRecord(fields)
        if isinstance(p, A.PAs):
            t = self.infer_pat(p.pat, binds)
            p.ref = self._bind_local(p.name, p.span, binds, t)
            return t
        if isinstance(p, A.PAnnot):
            t = self.infer_pat(p.pat, binds)
            at = self.type_of_annotation(p.type_expr)
            if at is None:
                raise Abort()
            self.must(t, at, p.span, "a type annotation")
            return t
        raise Abort()
