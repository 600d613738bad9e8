"""Typed CPN ML expressions and transitions to Python source.

Each transition becomes one function that enumerates its enabled bindings on the multisets of the places
it reads: nested loops over the distinct tokens that input-arc patterns match, each guard conjunct tested
as soon as its variables are bound, then the consumed and produced tokens. Every generated line that
evaluates a model expression is recorded in a blame table (line -> model element and span), so that an
error raised inside generated code names the model element. Model text is never executed as Python: the
source is built from the net's expressions (`cpn.expr.nodes`), identifiers are mangled, constants are
`repr`s of checked values. The order of the loops and tests is the binding plan of `cpn.engine.plan`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from cpn._util.deep import left_spine
from cpn.engine import plan
from cpn.expr import binding as B
from cpn.expr import nodes as A
from cpn.expr.forms import FORMS
from cpn.values.builtins import FUNCTIONS, TIME_BUILTINS

_PY_BINOPS = {"+": "+", "-": "-", "*": "*", "^": "+", "^^": "+", "@": "+", "=": "==", "<>": "!=",
              "<": "<", "<=": "<=", ">": ">", ">=": ">="}


def _binop_code(op: str, left: str, right: str) -> str:
    if op == "andalso":
        return f"({left} and {right})"
    if op == "orelse":
        return f"({left} or {right})"
    if op == "::":
        return f"(({left},) + {right})"
    if op in _PY_BINOPS:
        return f"({left} {_PY_BINOPS[op]} {right})"
    return f"BINOP({op!r}, {left}, {right})"


def sum_code(parts: list[str], ns: Namespace) -> str:
    """Python code of the sum of `parts` (tuples or lists), in chunks of CHAIN_CHUNK (see `_c_BinOp`)."""
    if len(parts) <= CHAIN_CHUNK:
        return " + ".join(parts)
    temp = ns.temp()
    chunks = [" + ".join(parts[i:i + CHAIN_CHUNK]) for i in range(0, len(parts), CHAIN_CHUNK)]
    steps = [f"({temp} := {chunks[0]})"] + [f"({temp} := {temp} + {c})" for c in chunks[1:-1]]
    return "(" + ", ".join(steps) + f", {temp} + {chunks[-1]})[-1]"


class Unsupported(Exception):
    """An expression the compiler leaves to the evaluator."""


@dataclass
class Namespace:
    """Objects the generated module refers to by name."""

    objects: dict[str, Any] = field(default_factory=dict)
    _ids: dict[int, str] = field(default_factory=dict)
    _temps: int = 0

    def temp(self) -> str:
        """A fresh name for a temporary of generated code."""
        self._temps += 1
        return f"_W{self._temps}"

    def ref(self, obj: Any, hint: str = "K") -> str:
        key = id(obj)
        name = self._ids.get(key)
        if name is None:
            name = f"_{hint}{len(self.objects)}"
            self._ids[key] = name
            self.objects[name] = obj
        return name


# Python refuses source nested more deeply than about 200 parentheses or 100 indentation levels: an
# expression nested deeper than MAX_NESTING (a 300-term `x + x + ...`) is left to the evaluator from there
# on, and a function whose statements nest deeper than MAX_BLOCKS stays with the evaluator.
MAX_NESTING: int = 64
MAX_BLOCKS: int = 40
#: operators of one chain compiled into one Python expression before its value goes to a temporary
CHAIN_CHUNK: int = 32


class ExprCompiler:
    """Compiles one expression to a Python expression string, given the Python names of bound variables."""

    _nesting = 0

    def __init__(self, ns: Namespace, evaluator, varnames: dict[str, str], params: dict[int, Any],
                 var_uids: dict[str, int]):
        self.ns = ns
        self.ev = evaluator
        self.varnames = varnames  # transition variable name -> python local name
        self.params = params
        self.var_uids = var_uids

    def const(self, v: Any) -> str:
        if isinstance(v, (bool, int, str, float)) or v == ():
            return repr(v)
        return self.ns.ref(v, "K")

    def fallback(self, e: A.Expr) -> str:
        """Evaluate e with the tree-walking evaluator (for let, case, fn, sequences)."""
        node = self.ns.ref(e, "X")
        used = B.all_vars(e)
        items = ", ".join(f"{self.var_uids[n]}: {py}" for n, py in self.varnames.items() if n in used)
        env = self.ns.ref(self.params, "P")
        return f"EVAL({node}, {{**{env}, {items}}})" if items else f"EVAL({node}, {env})"

    def expr(self, e: A.Expr) -> str:
        if self._nesting >= MAX_NESTING:
            return self.fallback(e)
        self._nesting += 1
        try:
            m = getattr(self, "_c_" + type(e).__name__, None)
            if m is not None:
                return m(e)
            code = FORMS[e.__class__].compile(self, e)  # a form that declares its own rules (cpn.expr.forms)
            if code is None:
                raise Unsupported()
            return code
        except Unsupported:
            return self.fallback(e)
        finally:
            self._nesting -= 1

    def _c_Const(self, e):
        return self.const(e.value)

    def _c_Name(self, e):
        sym = e.ref
        k = sym.kind
        if k == "var":
            return self.varnames[sym.name]
        if k == "fun" and sym.uid in getattr(self, "functions", {}):
            return self.ns.ref(self.functions[sym.uid], "F")
        if k in ("val", "fun"):
            return self.ns.ref(self.ev.globals[sym.uid], "G")
        if k == "param":
            return self.const(self.params[sym.uid])
        if k == "con":
            info = sym.data
            if info.kind == "enum" or (info.kind == "union" and not info.has_arg):
                return repr(info.tag)
            return self.ns.ref(self.ev.eval(e, {}), "C")
        if k == "builtin":
            if sym.name in TIME_BUILTINS:
                return "TIMEFN"  # the evaluator's clock (cpn.engine.clock finds who reads it)
            return self.ns.ref(FUNCTIONS[sym.name], "B")
        if k == "csop":
            return self.ns.ref(self.ev.eval(e, {}), "S")
        raise Unsupported()

    def _c_App(self, e):
        if isinstance(e.fn, A.Select):
            return f"{self.expr(e.arg)}[{e.fn.index}]"
        if isinstance(e.fn, A.Name) and e.fn.ref.kind == "con" and e.fn.ref.data.kind == "index":
            return f"IDX({self.ns.ref(self.ev.colsets[e.fn.ref.data.colset], 'S')}, {self.expr(e.arg)})"
        if isinstance(e.fn, A.Name) and e.fn.ref.kind == "con" and e.fn.ref.data.kind == "union":
            return f"({e.fn.ref.data.tag!r}, {self.expr(e.arg)})"
        if isinstance(e.fn, A.Name) and e.fn.ref.kind == "builtin" and e.fn.name == "not":
            return f"(not {self.expr(e.arg)})"
        return f"{self.expr(e.fn)}({self.expr(e.arg)})"

    def _c_BinOp(self, e):
        # The left spine (`a + b - c ...`, `a andalso b andalso ...`) in a loop. Python's compiler recurses
        # on nested operators too (a 5,000-term sum is a RecursionError there): every CHAIN_CHUNK operators
        # the partial result goes to a temporary, `(_W := a + .. + k, _W := _W + l + .., _W + .. + z)[-1]`,
        # which evaluates the same operands in the same order, short circuits included.
        first, spine = left_spine(e, A.BinOp)
        acc = self.expr(first)
        parts = []
        temp = None
        for k, node in enumerate(spine):
            if k and k % CHAIN_CHUNK == 0:
                temp = temp or self.ns.temp()
                parts.append(f"({temp} := {acc})")
                acc = temp
            acc = _binop_code(node.op, acc, self.expr(node.right))
        if not parts:
            return acc
        return "(" + ", ".join(parts) + f", {acc})[-1]"


def out_terms(e: A.Expr, ec: ExprCompiler, delay: str = "0") -> list[str]:
    """Python expressions, each a list of (value, count, delay) triples, whose sum is the output of e."""
    if isinstance(e, A.BinOp) and e.op in ("++", "+++"):
        return out_terms(e.left, ec, delay) + out_terms(e.right, ec, delay)
    if isinstance(e, A.BinOp) and e.op == "@+":
        d = ec.expr(e.right)
        return out_terms(e.left, ec, d if delay == "0" else f"({delay}) + ({d})")
    if isinstance(e, A.ToMs):
        return [f"(({ec.expr(e.expr)}, 1, {delay}),)"]
    if isinstance(e, A.BinOp) and e.op == "`":
        return [f"(({ec.expr(e.right)}, {ec.expr(e.left)}, {delay}),)"]
    if isinstance(e, A.Name) and e.ref is not None and e.ref.kind == "builtin" and e.name == "empty":
        return []
    if isinstance(e, A.If):
        a = sum_code(out_terms(e.then, ec, delay), ec.ns) or "()"
        b = sum_code(out_terms(e.else_, ec, delay), ec.ns) or "()"
        return [f"(({a}) if {ec.expr(e.cond)} else ({b}))"]
    return [f"MSITEMS({ec.expr(e)}, {delay})"]


class TransitionCodegen:
    """Generates `bind_<t>(M0, M1, ...)`: the enabled bindings of one transition instance."""

    def __init__(self, t, net, ns: Namespace, evaluator, read: list[int]):
        self.t = t
        self.net = net
        self.ns = ns
        self.read = read  # place indices, in the order of the function's parameters
        self.varnames = {v: f"v{i}" for i, v in enumerate(t.variables)}
        var_uids = {name: sym.uid for name, sym in net.variables.items()}
        self.ec = ExprCompiler(ns, evaluator, self.varnames, t.params, var_uids)
        self.lines: list[str] = []
        self.blame: dict[int, tuple[str, Any]] = {}
        self.indent = 1
        self._tok = 0

    def emit(self, line: str, blame: tuple[str, Any] | None = None) -> None:
        self.lines.append("    " * self.indent + line)
        if blame is not None:
            self.blame[len(self.lines)] = blame

    def newtok(self) -> str:
        self._tok += 1
        return f"tok{self._tok}"

    # -- pattern matching
    def gen_match(self, e, src: str, bound: set, blame) -> None:
        if B.is_var(e):
            py = self.varnames[e.name]
            if e.name in bound:
                self.emit(f"if {src} != {py}: continue")
            else:
                self.emit(f"{py} = {src}")
                bound.add(e.name)
            return
        if isinstance(e, A.TupleE):
            for i, x in enumerate(e.items):
                self.gen_match(x, f"{src}[{i}]", bound, blame)
            return
        if isinstance(e, A.RecordE):
            for i, (_, x) in enumerate(sorted(e.fields, key=lambda f: f[0])):
                self.gen_match(x, f"{src}[{i}]", bound, blame)
            return
        if isinstance(e, A.ListE):
            self.emit(f"if len({src}) != {len(e.items)}: continue")
            for i, x in enumerate(e.items):
                self.gen_match(x, f"{src}[{i}]", bound, blame)
            return
        if isinstance(e, A.App) and B.is_constructor_fn(e.fn):
            info = e.fn.ref.data
            if info.kind == "index":
                self.gen_match(e.arg, src, bound, blame)
            else:
                self.emit(f"if type({src}) is not tuple or {src}[0] != {info.tag!r}: continue")
                self.gen_match(e.arg, f"{src}[1]", bound, blame)
            return
        if isinstance(e, A.BinOp) and e.op == "::":
            self.emit(f"if not {src}: continue")
            self.gen_match(e.left, f"{src}[0]", bound, blame)
            self.gen_match(e.right, f"{src}[1:]", bound, blame)
            return
        self.emit(f"if {src} != {self.ec.expr(e)}: continue", blame)

    def check_member(self, var: str) -> None:
        sym = self.net.variables[var]
        cs = self.net.colsets[sym.data]
        self.emit(f"if not {self.ns.ref(cs.contains, 'M')}({self.varnames[var]}): continue")

    # -- the whole function
    def generate(self) -> tuple[str, str]:
        """The name and the source of the function: binding, consumption, inhibition, production."""
        t = self.t
        fname = f"bind_{t.index}"
        self.in_terms = plan.input_terms(t, self.read)
        self.lines.append(f"def {fname}({', '.join(f'M{i}' for i in range(len(self.read)))}):")
        self.indent = 1
        self.emit("out = []")
        self.emit("for _once in ONCE:")
        self.indent += 1
        try:
            steps = plan.binding_plan(self.in_terms, t.guards, t.variables, t.free)
        except plan.Unbindable as exc:
            raise RuntimeError(f"{exc} of {t.name}") from None
        self.emit_binding(steps)
        consumed = self.emit_consumption()
        self.emit_inhibitors()
        self.emit_production(consumed)
        self.indent = 1
        self.emit("return out")
        return fname, "\n".join(self.lines)

    def emit_binding(self, steps: list) -> None:
        """The loops and tests of the binding plan; `loop_token` maps each looped term to its token."""
        conj = B.guard_conjuncts(self.t.guards)
        bound: set[str] = set()
        self.loop_token: dict[int, tuple[int, str]] = {}  # term number -> (place position, token name)
        for step in steps:
            if isinstance(step, plan.Test):
                g = conj[step.guard]
                self.emit(f"if not {self.ec.expr(g)}: continue", ("guard", g))
            elif isinstance(step, plan.Loop):
                it = self.in_terms[step.term]
                pi, term, bl = it.place, it.term, ("arc", it.arc)
                if B.is_var(term.value):
                    py = self.varnames[term.value.name]
                    self.emit(f"for {py} in M{pi}:")
                    self.indent += 1
                    bound.add(term.value.name)
                    self.loop_token[step.term] = (pi, py)
                else:
                    tok = self.newtok()
                    self.emit(f"for {tok} in M{pi}:")
                    self.indent += 1
                    self.gen_match(term.value, tok, bound, bl)
                    self.loop_token[step.term] = (pi, tok)
            elif isinstance(step, plan.Bind):
                bl = ("guard", conj[step.guard])
                tok = self.newtok()
                self.emit(f"{tok} = {self.ec.expr(step.expr)}", bl)
                self.gen_match(step.pattern, tok, bound, bl)
                for v in sorted(step.new):
                    self.check_member(v)
            else:
                v = step.var
                cs = self.net.colsets[self.net.variables[v].data]
                self.emit(f"for {self.varnames[v]} in {self.ns.ref(tuple(cs.values()), 'V')}:")
                self.indent += 1
                bound.add(v)

    def emit_consumption(self) -> list[str]:
        """Per read place, the name of the dict of consumed tokens (or "None"), checking they are there."""
        loop_token = self.loop_token
        per_place: dict[int, list] = {}
        for k, it in enumerate(self.in_terms):
            per_place.setdefault(it.place, []).append((k, it.term, ("arc", it.arc)))
        consumed = []
        for pi in range(len(self.read)):
            entries = per_place.get(pi)
            if not entries:
                consumed.append("None")
                continue
            c = f"c{pi}"
            if len(entries) == 1 and entries[0][0] in loop_token and entries[0][1].coef is None \
                    and not entries[0][1].cond and B.is_pattern(entries[0][1].value):
                k = entries[0][0]
                self.emit(f"{c} = {{{self._value_code(entries[0][1].value, loop_token[k][1])}: 1}}")
                consumed.append(c)
                continue
            if len(entries) == 1 and entries[0][1].opaque is None and not entries[0][1].cond:
                k, term, bl = entries[0]
                val = self._value_code(term.value, loop_token[k][1] if k in loop_token else None)
                if term.coef is None:
                    self.emit(f"_v = {val}", bl)
                    self.emit(f"if _v not in M{pi}: continue")
                    self.emit(f"{c} = {{_v: 1}}")
                else:
                    self.emit(f"_n = {self.ec.expr(term.coef)}", bl)
                    self.emit("if _n < 0: raise MLError(f'negative coefficient {_n}')", bl)
                    self.emit(f"_v = {val}", bl)
                    self.emit(f"if _n and M{pi}.get(_v, 0) < _n: continue")
                    self.emit(f"{c} = {{_v: _n}} if _n else {{}}")
                consumed.append(c)
                continue
            self.emit(f"{c} = {{}}")
            for k, term, bl in entries:
                lines = []
                if term.opaque is not None:
                    lines.append((f"for _v, _n, _d in MSITEMS({self.ec.expr(term.opaque)}, 0):", bl))
                    lines.append(("    " + f"{c}[_v] = {c}.get(_v, 0) + _n", None))
                else:
                    coef = "1" if term.coef is None else self.ec.expr(term.coef)
                    val = self._value_code(term.value, loop_token[k][1] if k in loop_token else None)
                    if term.coef is not None:
                        lines.append((f"_n = {coef}", bl))
                        lines.append(("if _n < 0: raise MLError(f'negative coefficient {_n}')", bl))
                        lines.append((f"if _n: _v = {val}; {c}[_v] = {c}.get(_v, 0) + _n", bl))
                    else:
                        lines.append((f"_v = {val}; {c}[_v] = {c}.get(_v, 0) + 1", bl))
                cond_prefix = 0
                for ce, pol in term.cond:
                    self.emit(f"if {'' if pol else 'not '}{self.ec.expr(ce)}:", bl)
                    self.indent += 1
                    cond_prefix += 1
                for line, lb in lines:
                    self.emit(line, lb)
                self.indent -= cond_prefix
            self.emit(f"if not ENOUGH(M{pi}, {c}): continue")
            consumed.append(c)
        return consumed

    def emit_inhibitors(self) -> None:
        """An inhibitor arc skips the binding while its place holds the inscription (any token, if none)."""
        for a in self.t.arcs:
            if a.kind.blocks:
                pi = self.read.index(a.place)
                if a.expr is None:
                    self.emit(f"if M{pi}: continue")
                else:
                    self.emit(f"if INHIBITED(M{pi}, {self.ec.expr(a.expr)}): continue", ("arc", a))

    def emit_production(self, consumed: list[str]) -> None:
        """The produced tokens, the delay and the priority; then the binding with its effect is kept."""
        t = self.t
        produced = []
        for a in t.arcs:
            # a double arc puts back its own inscription (not everything taken from its place)
            if a.kind.produces and a.expr is not None:
                parts = out_terms(a.expr, self.ec)
                if parts:
                    var = f"_o{a.place}_{len(produced)}"
                    self.emit(f"{var} = {sum_code(parts, self.ns)}", ("arc", a))
                    produced.append(f"({a.place}, {var})")
        delay = "0"
        if t.delay is not None:
            self.emit(f"_td = {self.ec.expr(t.delay)}", ("delay", t.delay))
            delay = "_td"
        prio = "None"
        if t.priority is not None:
            self.emit(f"_pr = {self.ec.expr(t.priority)}", ("priority", t.priority))
            prio = "_pr"
        binding = "(" + "".join(self.varnames[v] + ", " for v in t.variables) + ")"
        self.emit(f"out.append(({binding}, ({''.join(c + ', ' for c in consumed)}), "
                  f"({''.join(p + ', ' for p in produced)}), {delay}, {prio}))")

    def _value_code(self, e, tok: str | None) -> str:
        if tok is not None and B.is_pattern(e):
            return tok
        return self.ec.expr(e)


class FunctionCodegen:
    """Compiles a global `fun` of one argument (possibly a tuple) into a Python function.

    Clauses become pattern tests in order; bodies are compiled expressions. Functions of several curried
    arguments stay with the evaluator.
    """

    def __init__(self, ns: Namespace, evaluator, functions: dict[int, Any], var_uids: dict[str, int]):
        self.ns = ns
        self.ev = evaluator
        self.functions = functions
        self.var_uids = var_uids

    def compile(self, fd: A.FunDecl) -> str | None:
        if len(fd.clauses[0].params) != 1:
            return None
        name = f"_F{fd.ref.uid}"
        lines = [f"def {name}(arg):"]
        self._n = 0
        try:
            for clause in fd.clauses:
                locals_: dict[int, str] = {}
                body: list[str] = []
                if not self._match(clause.params[0], "arg", body, locals_):
                    return None
                lines.append("    for _once in ONCE:")
                lines.extend("        " + b for b in body)
                self._stmt(clause.body, locals_, 2, lines)
        except Unsupported:
            return None
        lines.append(f"    raise MLError({('no clause of ' + repr(fd.name) + ' matches its argument (SML exception Match)')!r})")
        return "\n".join(lines)

    def _stmt(self, e: A.Expr, locals_: dict[int, str], depth: int, out: list[str]) -> None:
        """Statements that return the value of e: case, if and let become control flow."""
        if depth > MAX_BLOCKS:
            raise Unsupported()
        pad = "    " * depth
        if isinstance(e, A.Case):
            self._n += 1
            subj = f"_c{self._n}"
            out.append(f"{pad}{subj} = {self._expr(e.subject, locals_)}")
            for pat, body in e.rules:
                inner = dict(locals_)
                tests: list[str] = []
                if not self._match(pat, subj, tests, inner):
                    raise Unsupported()
                out.append(f"{pad}for _once in ONCE:")
                out.extend(f"{pad}    {t}" for t in tests)
                self._stmt(body, inner, depth + 1, out)
            out.append(f"{pad}raise MLError('no rule of the case-expression matches (SML exception Match)')")
            return
        if isinstance(e, A.If):
            out.append(f"{pad}if {self._expr(e.cond, locals_)}:")
            self._stmt(e.then, locals_, depth + 1, out)
            out.append(f"{pad}else:")
            self._stmt(e.else_, locals_, depth + 1, out)
            return
        if isinstance(e, A.Let) and all(isinstance(d, A.ValDecl) for d in e.decls):
            inner = dict(locals_)
            for d in e.decls:
                self._n += 1
                tmp = f"_t{self._n}"
                out.append(f"{pad}{tmp} = {self._expr(d.expr, inner)}")
                tests: list[str] = []
                if not self._match(d.pat, tmp, tests, inner):
                    raise Unsupported()
                for t in tests:
                    if t.endswith(": continue"):
                        out.append(f"{pad}{t[:-len('continue')]}raise MLError('the value does not match the "
                                   "pattern of val (SML exception Bind)')")
                    else:
                        out.append(f"{pad}{t}")
            self._stmt(e.body, inner, depth, out)
            return
        out.append(f"{pad}return {self._expr(e, locals_)}")

    def _expr(self, e: A.Expr, locals_: dict[int, str]) -> str:
        return _LocalExprCompiler(self.ns, self.ev, locals_, self.functions, self.var_uids).expr(e)

    def _match(self, p: A.Pat, src: str, out: list[str], locals_: dict[int, str]) -> bool:
        if isinstance(p, A.PWild):
            return True
        if isinstance(p, A.PVar):
            sym = p.ref
            if sym.kind == "con":
                out.append(f"if {src} != {sym.data.tag!r}: continue")
                return True
            py = f"l{sym.uid}"
            locals_[sym.uid] = py
            out.append(f"{py} = {src}")
            return True
        if isinstance(p, A.PConst):
            if p.kind == "bool":
                out.append(f"if {src} is not {p.value!r}: continue")
            else:
                out.append(f"if {src} != {p.value!r}: continue")
            return True
        if isinstance(p, A.PTuple):
            return all(self._match(x, f"{src}[{i}]", out, locals_) for i, x in enumerate(p.items))
        if isinstance(p, A.PList):
            out.append(f"if len({src}) != {len(p.items)}: continue")
            return all(self._match(x, f"{src}[{i}]", out, locals_) for i, x in enumerate(p.items))
        if isinstance(p, A.PCons):
            out.append(f"if not {src}: continue")
            return self._match(p.head, f"{src}[0]", out, locals_) and self._match(p.tail, f"{src}[1:]", out, locals_)
        if isinstance(p, A.PCon):
            info = p.ref.data
            if info.kind == "index":
                return self._match(p.arg, src, out, locals_)
            out.append(f"if type({src}) is not tuple or {src}[0] != {info.tag!r}: continue")
            return self._match(p.arg, f"{src}[1]", out, locals_)
        if isinstance(p, A.PRecord):
            labels = p.ty_labels
            return all(self._match(q, f"{src}[{labels.index(label)}]", out, locals_) for label, q in p.fields)
        if isinstance(p, A.PAs):
            py = f"l{p.ref.uid}"
            locals_[p.ref.uid] = py
            out.append(f"{py} = {src}")
            return self._match(p.pat, src, out, locals_)
        return False


class _LocalExprCompiler(ExprCompiler):
    """An expression compiler that also knows the local variables of a function clause."""

    def __init__(self, ns, ev, locals_, functions, var_uids):
        super().__init__(ns, ev, {}, {}, var_uids)
        self.locals = locals_
        self.functions = functions

    def fallback(self, e):
        raise Unsupported()

    def _c_Name(self, e):
        sym = e.ref
        if sym.kind == "local":
            if sym.uid not in self.locals:
                raise Unsupported()
            return self.locals[sym.uid]
        if sym.kind == "fun" and sym.uid in self.functions:
            return f"_F{sym.uid}"
        return super()._c_Name(e)
