"""The one tree-walking evaluator of CPN ML expressions (`cpn.expr.nodes`).

The language evaluates declarations with it while checking (`val`, colour-set bounds and predicates) and
initial markings and module parameters while lowering, on the typed tree whose names are Symbols; the
reference interpreter evaluates the net's inscriptions with it, and the compiled engine the expressions
its compiler leaves (`let`, `case`, `fn`), on the net's tree whose names are Refs. Slow and plain on
purpose: it is the oracle the compiled engine is tested against. The operators and the library have the
meaning of `cpn.values.builtins`.

Examples
--------
>>> from cpn.expr import nodes as E
>>> ev = Evaluator({})
>>> ev.eval(E.BinOp(None, "+", E.Const(None, 1, "int"), E.Const(None, 2, "int")), {})
3
"""

from __future__ import annotations

import copy
from typing import Any

from cpn._util.deep import left_spine
from cpn._util.deep import run_deep as _run_deep
from cpn._util.deep import run_deep_again as _run_deep_again
from cpn.expr import nodes as A
from cpn.expr.forms import FORMS
from cpn.values import draws
from cpn.values.builtins import FUNCTIONS, TIME_BUILTINS, MLError, binop
from cpn.values.effects import Cell, cannot_run
from cpn.values.multiset import Multiset, TimedMultiset


class Closure:
    """A CPN ML function value: clauses evaluated in the environment where the function was defined."""

    __slots__ = ("clauses", "env", "ev", "arity", "name", "args")

    def __init__(self, clauses, env, ev, name="fn", arity=1, args=()):
        self.clauses = clauses  # list of (params: list[Pat], body)
        self.env = env
        self.ev = ev
        self.arity = arity
        self.name = name
        self.args = args

    def call(self, arg):
        args = self.args + (arg,)
        if len(args) < self.arity:
            return Closure(self.clauses, self.env, self.ev, self.name, self.arity, args)
        for params, body in self.clauses:
            env = dict(self.env)
            if all(self.ev.match(p, a, env) for p, a in zip(params, args)):
                return self.ev.eval(body, env)
        raise MLError(f"no clause of '{self.name}' matches its argument (SML exception Match)")

    __call__ = call


def ml_function_of(frame) -> str | None:
    """The name of the model's function a Python frame runs, or None (for `deepest_recursion`)."""
    code = frame.f_code
    if code is _CALL_CODE:
        return frame.f_locals["self"].name
    if code.co_filename.startswith(FUNCTION_FILE):
        return code.co_filename[len(FUNCTION_FILE):-1]
    return None


_CALL_CODE = Closure.call.__code__
#: the file name of a compiled function of the model: FUNCTION_FILE + name + ">"
FUNCTION_FILE: str = "<cpn function "


def run_deep(fn, *args):
    """`fn(*args)`, on a deep stack if a function of the model recurses beyond Python's recursion limit
    (`cpn._util.deep.run_deep`); deeper than that stack allows, an MLError naming the function."""
    return _run_deep(fn, args, MLError, ml_function_of)


def run_deep_again(fn, *args):
    """`run_deep` after `fn(*args)` ran out of Python's recursion limit on the ordinary stack (so that the
    ordinary case costs no call)."""
    return _run_deep_again(fn, args, MLError, ml_function_of)


class Evaluator:
    """Evaluates expressions; `globals` maps symbol uids of vals and functions to values."""

    def __init__(self, colsets: dict, globals_: A.Globals | dict[int, Any] | None = None):
        """`globals_`: a net's `Globals` (its functions are declared here), or the language's own table of
        values by uid, which the evaluator then shares (the checker fills it as it goes)."""
        self.colsets = colsets  # name -> ColourSet
        self.time = 0
        if globals_ is None or isinstance(globals_, dict):
            self.globals: dict[int, Any] = {} if globals_ is None else globals_
            return
        self.globals = _own_cells(globals_.constants)  # uid -> value of a global constant or function
        for d in globals_.decls:
            if not (isinstance(d, A.ValDecl) and d.pat.ref.uid in globals_.constants):
                self.declare(d, self.globals)

    # ------------------------------------------------------------------ expressions
    def eval(self, e: A.Expr, env: dict) -> Any:
        rule = _RULES.get(e.__class__)
        if rule is None:
            rule = _rule_of(e.__class__)
        return rule(self, e, env)

    def _e_Const(self, e, env):
        return e.value

    def _e_Name(self, e, env):
        sym = e.ref
        kind = sym.kind
        if kind in ("local", "var", "param"):
            try:
                return env[sym.uid]
            except KeyError:
                raise MLError(f"variable '{sym.name}' is not bound") from None
        if kind in ("val", "fun"):
            return self.globals[sym.uid]
        if kind == "con":
            info = sym.data
            if info.kind == "enum":
                return info.tag
            if info.kind == "index":
                cs = self.colsets[info.colset]

                def mk(i, cs=cs):
                    if not cs.contains(i):
                        raise MLError(f"{cs.constructor}({i}) is outside colour set {cs.name}")
                    return i
                return mk
            if info.has_arg:
                return lambda v, tag=info.tag: (tag, v)
            return info.tag
        if kind == "builtin":
            if sym.name in TIME_BUILTINS:
                if sym.name == "intTime":  # the clock rounded down where '@++' made it a real (simulate)
                    return lambda _u: self.time if self.time.__class__ is int else int(self.time // 1)
                return lambda _u: self.time
            return FUNCTIONS[sym.name]
        if kind == "csop":
            return self._csop(*sym.data)
        raise MLError(f"cannot evaluate '{sym.name}'")

    def _csop(self, csname, op):
        cs = self.colsets[csname]
        if op.startswith("set_") and cs.kind == "record" and op[4:] in cs.labels:  # CS.set_<field> r v
            i = cs.labels.index(op[4:])
            return lambda r: lambda v: r[:i] + (v,) + r[i + 1:]
        if op == "all":
            def all_(_u):
                vals = cs.values()
                if vals is None:
                    raise MLError(f"{csname}.all(): colour set {csname} is infinite or too large")
                return Multiset(vals)
            return all_
        if op == "size":
            return lambda _u: cs.size()
        if op == "ord":
            return cs.ord
        if op == "col" and cs.kind in ("enum", "index", "int") and cs.values() is not None:
            low = getattr(cs, "low", 0) or 0
            size = cs.size()

            def col_range(i):
                if not 0 <= i < size:
                    raise MLError(f"{csname}.col({i}) is outside the colour set")
                return low + i
            return col_range
        if op == "col":
            def col(i):
                vals = cs.values()
                if vals is None or not 0 <= i < len(vals):
                    raise MLError(f"{csname}.col({i}) is outside the colour set")
                return vals[i]
            return col
        if op == "legal":
            return cs.contains
        if op == "lt":  # CS.lt (a, b): a before b in the colour set's order
            return lambda ab: cs.sort_key(ab[0]) < cs.sort_key(ab[1])
        if op == "mkstr":
            return cs.format
        if op == "mult":
            def mult(ms_tuple):
                items = [((), 1)]
                for m in ms_tuple:
                    if isinstance(m, TimedMultiset):
                        m = m.untimed()
                    items = [(acc + (v,), n * k) for acc, n in items for v, k in m.items()]
                return Multiset({v: n for v, n in items})
            return mult
        if op == "input_ms":  # its stream comes from TextIO.openIn, which stops simulate first
            return cannot_run(f"{csname}.input_ms", "reads a file")
        if op in ("output", "output_col", "output_ms"):  # to a stream of TextIO.openOut: dropped, as its text
            return lambda _stream_and_value: ()
        if op == "ran":
            def ran(_u):  # a draw where it is no choice (inside a function): simulation only
                vals = cs.values()
                if not vals:
                    raise MLError(f"{csname}.ran(): colour set {csname} is infinite or too large to draw from")
                return draws.ran(vals)
            return ran
        raise MLError(f"unknown colour set function {csname}.{op}")

    def _e_App(self, e, env):
        f = self.eval(e.fn, env)
        a = self.eval(e.arg, env)
        if f.__class__ is Closure:
            return f.call(a)  # a Python call, not through __call__: no C stack per level of recursion
        return f(a)

    def _e_BinOp(self, e, env):
        if e.left.__class__ is not A.BinOp:  # one operator: as it always was
            op = e.op
            if op == "andalso":
                return bool(self.eval(e.left, env)) and bool(self.eval(e.right, env))
            if op == "orelse":
                return bool(self.eval(e.left, env)) or bool(self.eval(e.right, env))
            return binop(op, self.eval(e.left, env), self.eval(e.right, env))
        # the left spine (`a + b + ... + z`, `a andalso b andalso ...`) in a loop: one frame for a chain
        first, spine = left_spine(e, A.BinOp)
        v = self.eval(first, env)
        for node in spine:
            op = node.op
            if op == "andalso":
                v = bool(v) and bool(self.eval(node.right, env))
            elif op == "orelse":
                v = bool(v) or bool(self.eval(node.right, env))
            else:
                v = binop(op, v, self.eval(node.right, env))
        return v

    # ------------------------------------------------------------------ declarations (global, in let)
    def declare(self, d: A.Decl, env: dict) -> None:
        if isinstance(d, A.ValDecl):
            v = self.eval(d.expr, env)
            if not self.match(d.pat, v, env):
                raise MLError("the value does not match the pattern of 'val' (SML exception Bind)")
        elif isinstance(d, A.FunDecl):
            clo = self.make_function(d, env)
            env[d.ref.uid] = clo
        else:
            raise MLError("unsupported declaration inside let")

    def closure(self, clauses: list, env: dict, name: str = "fn") -> Closure:
        """A function value of one argument: `clauses` are (params, body) tried in order (a form's rule)."""
        return Closure(clauses, env, self, name)

    def make_function(self, d: A.FunDecl, env: dict) -> Closure:
        clo = Closure([(c.params, c.body) for c in d.clauses], env, self, d.name, arity=len(d.clauses[0].params))
        env[d.ref.uid] = clo  # recursion: the closure sees itself
        return clo

    # ------------------------------------------------------------------ patterns
    def match(self, p: A.Pat, v: Any, env: dict) -> bool:
        if isinstance(p, A.PWild):
            return True
        if isinstance(p, A.PVar):
            sym = p.ref
            if sym is not None and sym.kind == "con":
                return v == self._e_Name(A.Name(p.span, p.name, ref=sym), env)
            env[sym.uid] = v
            return True
        if isinstance(p, A.PConst):
            return v == p.value and type(v) is type(p.value) or (p.kind == "unit" and v == ())
        if isinstance(p, A.PTuple):
            return len(v) == len(p.items) and all(self.match(q, x, env) for q, x in zip(p.items, v))
        if isinstance(p, A.PList):
            return len(v) == len(p.items) and all(self.match(q, x, env) for q, x in zip(p.items, v))
        if isinstance(p, A.PCons):
            return len(v) >= 1 and self.match(p.head, v[0], env) and self.match(p.tail, v[1:], env)
        if isinstance(p, A.PCon):
            info = p.ref.data
            if info.kind == "index":
                return self.match(p.arg, v, env)
            return isinstance(v, tuple) and v[0] == info.tag and self.match(p.arg, v[1], env)
        if isinstance(p, A.PRecord):
            labels = p.ty_labels
            return all(self.match(q, v[labels.index(label)], env) for label, q in p.fields)
        if isinstance(p, A.PAs):
            env[p.ref.uid] = v
            return self.match(p.pat, v, env)
        if isinstance(p, A.PAnnot):
            return self.match(p.pat, v, env)
        raise MLError(f"unsupported pattern {type(p).__name__}")


def _own_cells(constants: dict[int, Any]) -> dict[int, Any]:
    """The net's constants, with copies of the reference cells they hold (`val x = ref 0`): an engine's run
    starts from the values the declarations gave them, whatever the runs of other engines of the net
    assigned. One copy per cell, so that two constants naming the same cell still share it."""
    if not any(_holds_cell(v) for v in constants.values()):
        return dict(constants)
    memo: dict = {}
    return {uid: copy.deepcopy(v, memo) if _holds_cell(v) else v for uid, v in constants.items()}


def global_cells(values: dict[int, Any]) -> list[Cell]:
    """The reference cells that global values hold (inside tuples too), each once."""
    out: dict[int, Cell] = {}
    stack = list(values.values())
    while stack:
        x = stack.pop()
        if x.__class__ is Cell:
            out.setdefault(id(x), x)
        elif x.__class__ is tuple:
            stack.extend(x)
    return list(out.values())


def _holds_cell(v) -> bool:
    stack = [v]
    while stack:
        x = stack.pop()
        if x.__class__ is Cell:
            return True
        if x.__class__ is tuple:
            stack.extend(x)
    return False


#: node class -> the rule evaluating it: a method `_e_<class>` of the evaluator, or its form's `evaluate`
_RULES: dict[type, Any] = {}


def _rule_of(cls: type):
    rule = getattr(Evaluator, "_e_" + cls.__name__, None)
    if rule is None:
        rule = FORMS[cls].evaluate  # a form that declares its own rules (cpn.expr.forms)
    _RULES[cls] = rule
    return rule
