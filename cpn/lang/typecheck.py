"""Name resolution and type inference of a parsed model (Hindley-Milner for CPN ML); builds the colour sets
and evaluates constants. Net structure is checked by `cpn.lang.pages`.

Every error of a file is collected (one `Diagnostic` each) before `ModelError` is raised.
Imports `cpn.lang.*`, `cpn.values` and layer 0.
"""

from __future__ import annotations

from cpn._util import did_you_mean
from cpn.diagnostics import Diagnostic, Severity, Span
from cpn.errors import ModelError
from cpn.lang import ast as A
from cpn.lang import types as T
from cpn.lang.builtins import BUILTINS, MLError, parse_type
from cpn.lang.checked import Abort, ArcInfo, CheckedModel, Env, PageInfo, TransInfo
from cpn.lang.evaluate import Evaluator
from cpn.lang.multisets import MultisetInference
from cpn.lang.overrides import OverrideChecks, parse_overrides
from cpn.lang.pages import PageChecks
from cpn.lang.resolve import NameResolution
from cpn.lang.symbols import ConInfo, Symbol
from cpn.values import colours as C


class Checker(NameResolution, PageChecks, MultisetInference, OverrideChecks):
    def __init__(self, model: A.Model, overrides: dict | None = None):
        self.model = model
        self.file = model.file
        self.diags: list[Diagnostic] = []
        self.colsets: dict[str, C.ColourSet] = {}
        self.cstypes: dict[str, T.Type] = {}
        self.cs_spans: dict[str, Span] = {}
        self.globals: dict[str, Symbol] = {}
        self.variables: dict[str, Symbol] = {}
        self.ev = Evaluator(self.colsets, {})
        self.overrides = parse_overrides(overrides)
        self.init_resolution()
        self.override_problems: list = []
        self.used_overrides: set[str] = set()
        self.pending: list[tuple] = []
        self.net_name = "Top"
        self.builtin_syms: dict[str, Symbol] = {}
        for name, (tytext, _) in BUILTINS.items():
            self.builtin_syms[name] = Symbol(name, "builtin", parse_type(tytext))
        self.genv = Env(self.globals)
        self.ran_counter = 0
        self.ran_sink: list | None = None
        # CPN Tools' standard declarations; a model may redeclare them
        self.predefined = {"UNIT", "BOOL", "INT", "STRING", "REAL", "TIME", "INTINF"}
        for name, cs, ty in (("UNIT", C.UnitCS("UNIT"), T.UNIT), ("BOOL", C.BoolCS("BOOL"), T.BOOL),
                             ("INT", C.IntCS("INT"), T.INT), ("STRING", C.StringCS("STRING"), T.STRING),
                             ("REAL", C.RealCS("REAL"), T.REAL), ("TIME", C.IntCS("TIME"), T.INT),
                             ("INTINF", C.IntCS("INTINF"), T.INT)):
            self.colsets[name] = cs
            self.cstypes[name] = ty
            self.cs_spans[name] = Span("<standard declarations>", 0, 0)

    # ------------------------------------------------------------------ diagnostics
    def error(self, code, message, span, hint=None, notes=(), **params):
        self.diags.append(Diagnostic(code, message, span, hint=hint, notes=list(notes), params=params))

    def warn(self, code, message, span, hint=None, **params):
        self.diags.append(Diagnostic(code, message, span, hint=hint, params=params, severity=Severity.WARNING))

    def _where(self, span: Span | None) -> str:
        return f"{span.line}:{span.col}" if span else "?"

    # ------------------------------------------------------------------ entry point
    def check(self) -> CheckedModel:
        top_decls = []
        modules: dict[str, A.ModuleDecl] = {}
        for d in self.model.decls:
            if isinstance(d, A.NetHeader):
                self.net_name = d.name
            elif isinstance(d, A.ColsetDecl):
                self.colset_decl(d)
                if d.name not in self.colsets:
                    self.failed_names.add(d.name)
            elif isinstance(d, A.VarDecl):
                self.var_decl(d)
                self.failed_names.update(n for n, _ in d.names if n not in self.variables)
            elif isinstance(d, A.ValDecl):
                self.val_decl(d)
                if d.pat.ref is None:
                    self.failed_names.add(d.name)
            elif isinstance(d, A.FunDecl):
                if self.fun_decl(d) is None and isinstance(d.name, str):
                    self.failed_names.add(d.name)
            elif isinstance(d, A.ModuleDecl):
                if d.name in modules:
                    first = modules[d.name].span
                    self.error("E0202", f"module '{d.name}' is declared twice", d.span,
                               notes=[f"first declared at {self._where(first)}"],
                               hint="Rename one of them; module names must be unique.", name=d.name)
                else:
                    modules[d.name] = d
            else:
                top_decls.append(d)
        self.unused_overrides()
        self.raise_override_problems()
        self.module_decls = modules
        top = self.page(self.net_name, None, top_decls)
        pages = {name: self.page(name, m, m.body) for name, m in modules.items()}
        self.check_instances(top, pages)
        for p in pages.values():
            self.check_instances(p, pages)
        errors = [d for d in self.diags if d.severity is Severity.ERROR]
        if errors:
            self.note_overrides(errors)
            raise ModelError(self.diags, {self.file: self.model.source})
        return CheckedModel(self.model, self.net_name, self.colsets, self.cstypes, self.variables, self.globals,
                            self.ev, top, pages, [d for d in self.diags if d.severity is Severity.WARNING])

    # ------------------------------------------------------------------ declarations
    def _declare_global(self, sym: Symbol) -> bool:
        old = self.globals.get(sym.name)
        if old is not None and old.kind in ("var", "con") and sym.kind in ("var", "con"):
            self.error("E0202", f"'{sym.name}' is declared twice", sym.span,
                       notes=[f"first declared at {self._where(old.span)}"],
                       hint="Rename one of them.", name=sym.name)
            return False
        self.globals[sym.name] = sym  # a later val or fun shadows an earlier one, as in SML
        return True

    def const_int(self, e: A.Expr | None, what: str) -> int | None:
        if e is None:
            return None
        t = self.infer_top(e)
        if t is None:
            return None
        if not self.unify(t, T.INT, e.span, f"{what} must be an integer"):
            return None
        try:
            return self.ev.eval(e, {})
        except (MLError, ArithmeticError, TypeError, IndexError, KeyError) as exc:
            self.error("E0401", f"evaluating {what} failed: {exc}", e.span)
            return None

    def colset_decl(self, d: A.ColsetDecl) -> None:
        b = d.body
        name = d.name
        if name in self.colsets and name in self.predefined:
            self.predefined.discard(name)
            del self.colsets[name]
        if name in self.colsets:
            self.error("E0202", f"colour set '{name}' is declared twice", d.span,
                       notes=[f"first declared at {self._where(self.cs_spans[name])}"],
                       hint="Rename one of them; colour-set names must be unique.", name=name)
            return
        timed = d.timed
        cs: C.ColourSet | None = None
        ty: T.Type | None = None
        k = b.kind
        if k == "unit":
            cs, ty = C.UnitCS(name, timed), T.UNIT
        elif k == "bool":
            cs, ty = C.BoolCS(name, timed), T.BOOL
        elif k in ("int",):
            lo, hi = self.const_int(b.low, "the lower bound"), self.const_int(b.high, "the upper bound")
            if b.low is not None and (lo is None or hi is None):
                return
            if lo is not None and hi < lo:
                self.error("E0304", f"colour set '{name}' has an empty range {lo}..{hi}", b.span,
                           hint="The lower bound must not exceed the upper bound.")
                return
            cs, ty = C.IntCS(name, lo, hi, timed), T.INT
        elif k == "time":
            cs, ty = C.IntCS(name, None, None, timed), T.INT
        elif k == "string":
            cs, ty = C.StringCS(name, timed), T.STRING
        elif k == "real":
            cs, ty = C.RealCS(name, timed), T.REAL
        elif k == "enum":
            if len(set(b.names)) != len(b.names):
                self.error("E0304", f"enumeration '{name}' lists a constant twice", b.span)
                return
            cs, ty = C.EnumCS(name, b.names, timed), T.TCon(name)
            for i, c in enumerate(b.names):
                self._declare_global(Symbol(c, "con", ty, b.span, ConInfo(name, i, "enum", False)))
        elif k == "index":
            lo, hi = self.const_int(b.low, "the lower bound"), self.const_int(b.high, "the upper bound")
            if lo is None or hi is None:
                return
            if hi < lo:
                self.error("E0304", f"index colour set '{name}' has an empty range {lo}..{hi}", b.span)
                return
            cs, ty = C.IndexCS(name, b.names[0], lo, hi, timed), T.TCon(name)
            self._declare_global(Symbol(b.names[0], "con", T.TFun(T.INT, ty), b.span,
                                        ConInfo(name, 0, "index", True)))
        elif k == "product":
            comps = [self.lookup_colset(n, b.span) for n in b.names]
            if None in comps:
                return
            cs = C.ProductCS(name, comps, timed)
            ty = T.TTuple([self.cstypes[n] for n in b.names])
        elif k == "record":
            labels = [f for f, _ in b.fields]
            if len(set(labels)) != len(labels):
                self.error("E0304", f"record '{name}' has a field twice", b.span)
                return
            comps = [(f, self.lookup_colset(n, b.span)) for f, n in b.fields]
            if any(c is None for _, c in comps):
                return
            cs = C.RecordCS(name, comps, timed)
            ty = T.TRecord([(f, self.cstypes[n]) for f, n in b.fields])
        elif k == "list":
            elem = self.lookup_colset(b.names[0], b.span)
            if elem is None:
                return
            lo, hi = self.const_int(b.low, "the lower bound"), self.const_int(b.high, "the upper bound")
            cs = C.ListCS(name, elem, lo, hi, timed)
            ty = T.lst(self.cstypes[b.names[0]])
        elif k == "union":
            ty = T.TCon(name)
            cons = []
            for i, (cname, csname) in enumerate(b.fields):
                arg = self.lookup_colset(csname, b.span) if csname else None
                if csname and arg is None:
                    return
                cons.append((cname, arg))
                cty = T.TFun(self.cstypes[csname], ty) if csname else ty
                self._declare_global(Symbol(cname, "con", cty, b.span, ConInfo(name, i, "union", bool(csname))))
            cs = C.UnionCS(name, cons, timed)
        elif k in ("subset_by", "subset_with"):
            base = self.lookup_colset(b.names[0], b.span)
            if base is None:
                return
            bty = self.cstypes[b.names[0]]
            t = self.infer_top(b.pred)
            if t is None:
                return
            if k == "subset_by":
                if not self.unify(t, T.TFun(bty, T.BOOL), b.pred.span, "the predicate of a subset colour set"):
                    return
                try:
                    pred = self.ev.eval(b.pred, {})
                except MLError as exc:
                    self.error("E0401", f"evaluating the predicate failed: {exc}", b.pred.span)
                    return
                cs = C.SubsetCS(name, base, predicate=pred, timed=timed)
            else:
                if not self.unify(t, T.lst(bty), b.pred.span, "the members of a subset colour set"):
                    return
                cs = C.SubsetCS(name, base, members=self.ev.eval(b.pred, {}), timed=timed)
            ty = bty
        elif k == "alias":
            base = self.lookup_colset(b.names[0], b.span)
            if base is None:
                return
            cs, ty = C.AliasCS(name, base, timed or base.timed), self.cstypes[b.names[0]]
        if cs is None:
            self.error("E0206", f"unsupported colour set kind '{k}'", b.span)
            return
        self.colsets[name] = cs
        self.cstypes[name] = ty
        self.cs_spans[name] = d.span

    def var_decl(self, d: A.VarDecl) -> None:
        cs = self.lookup_colset(d.colset, d.colset_span)
        if cs is None:
            return
        for name, span in d.names:
            sym = Symbol(name, "var", self.cstypes[d.colset], span, d.colset)
            if self._declare_global(sym):
                self.variables[name] = sym

    def val_decl(self, d: A.ValDecl) -> None:
        name = d.name
        given = None
        if name in self.overrides:
            self.used_overrides.add(name)
            given = self.override_value(d, self.overrides[name])
        if given is not None:
            t, value = given
        else:
            expr = d.expr
            t = self.infer_top(expr)
            if t is None:
                return
            if d.type_expr is not None:
                at = self.type_of_annotation(d.type_expr)
                if at is not None and not self.unify(t, at, expr.span, f"the value of '{name}'"):
                    return
            try:
                value = self.ev.eval(expr, {})
            except (MLError, RecursionError) as exc:
                self.error("E0401", f"evaluating 'val {name}' failed: {exc}", expr.span)
                return
        sym = Symbol(name, "val", T.Scheme(T.free_vars(t), t), d.pat.span)
        self._declare_global(sym)
        d.pat.ref = sym
        self.ev.globals[sym.uid] = value

    def fun_decl(self, d: A.FunDecl, env: Env | None = None) -> Symbol | None:
        outer = env or self.genv
        if isinstance(d.ref, tuple):
            self.error("E0101", f"the clauses of function '{d.name}' have different names: "
                       + ", ".join(d.ref[1]), d.span, hint="All clauses of a 'fun' use the same name.")
            return None
        arity = len(d.clauses[0].params)
        for c in d.clauses:
            if len(c.params) != arity:
                self.error("E0301", f"the clauses of function '{d.name}' have different numbers of arguments",
                           c.span)
                return None
        sym = Symbol(d.name, "fun" if env is None else "local", None, d.span)
        ftype = T.TVar()
        sym.type = ftype
        d.ref = sym
        inner = outer.child({d.name: sym})
        try:
            for c in d.clauses:
                binds: dict[str, Symbol] = {}
                ptys = [self.infer_pat(p, binds) for p in c.params]
                body_env = inner.child(binds)
                bt = self.infer(c.body, body_env)
                if c.result_type is not None:
                    rt = self.type_of_annotation(c.result_type)
                    if rt is not None:
                        self.unify(bt, rt, c.body.span, f"the result of '{d.name}'")
                ct = bt
                for pt in reversed(ptys):
                    ct = T.TFun(pt, ct)
                self.unify(ftype, ct, c.span, f"the clauses of '{d.name}'")
            self.resolve_pending()
        except Abort:
            return None
        env_free = set()
        for lt in outer.local_types():
            env_free |= T.free_vars(lt if not isinstance(lt, T.Scheme) else lt.type)
        sym.type = T.Scheme([v for v in T.free_vars(ftype) if v not in env_free], ftype)
        if env is None:
            self._declare_global(sym)
            self.ev.make_function(d, self.ev.globals)
        return sym

    # ------------------------------------------------------------------ types
    def type_of_annotation(self, te: A.TypeExpr) -> T.Type | None:
        if isinstance(te, A.TName):
            if te.name in self.cstypes:
                return self.cstypes[te.name]
            simple = {"int": T.INT, "bool": T.BOOL, "string": T.STRING, "unit": T.UNIT, "real": T.REAL,
                      "INT": T.INT, "BOOL": T.BOOL, "STRING": T.STRING, "UNIT": T.UNIT}
            if te.name in simple:
                return simple[te.name]
            self.lookup_colset(te.name, te.span)
            return None
        if isinstance(te, A.TPost):
            inner = self.type_of_annotation(te.arg)
            if inner is None:
                return None
            if te.name in ("list", "ms"):
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

    def infer_top(self, e: A.Expr, env: Env | None = None) -> T.Type | None:
        try:
            t = self.infer(e, env or self.genv)
            self.resolve_pending()
            return t
        except Abort:
            self.pending.clear()
            return None

    def resolve_pending(self) -> None:
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
        t = getattr(self, "_i_" + type(e).__name__)(e, env)
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
        if sym.kind == "csop":
            cs, op = sym.data
            cst = self.cstypes[cs]
            if op == "mult":
                comps = T.prune(cst)
                if not isinstance(comps, T.TTuple):
                    self.error("E0301", f"'{e.name}': mult is defined on product colour sets only", e.span)
                    raise Abort()
                return T.TFun(T.TTuple([T.ms(c) for c in comps.items]), T.ms(cst))
            return {"all": T.TFun(T.UNIT, T.ms(cst)), "size": T.TFun(T.UNIT, T.INT), "ran": T.TFun(T.UNIT, cst),
                    "ord": T.TFun(cst, T.INT), "col": T.TFun(T.INT, cst), "legal": T.TFun(cst, T.BOOL),
                    "mkstr": T.TFun(cst, T.STRING)}[op]
        t = sym.type
        return t.instantiate() if isinstance(t, T.Scheme) else t

    def _i_Select(self, e, env):
        a, r = T.TVar(), T.TVar()
        self.pending.append((e, a, r, "sel"))
        return T.TFun(a, r)

    def _i_TupleE(self, e, env):
        return T.TTuple([self.infer(x, env) for x in e.items])

    def _i_RecordE(self, e, env):
        labels = [label for label, _ in e.fields]
        if len(set(labels)) != len(labels):
            self.error("E0301", "a record expression names a field twice", e.span)
            raise Abort()
        return T.TRecord([(label, self.infer(x, env)) for label, x in e.fields])

    def _i_ListE(self, e, env):
        elem = T.TVar()
        for x in e.items:
            self.must(self.infer(x, env), elem, x.span, "the elements of a list")
        return T.lst(elem)

    def _i_App(self, e, env):
        if isinstance(e.fn, A.Select):
            at = self.infer(e.arg, env)
            ft = self.infer(e.fn, env)
            self.must(ft, T.TFun(at, T.TVar()), e.span, "a field selection")
            if self.pending and self.pending[-1][0] is e.fn and self._try_select(*self.pending[-1]):
                self.pending.pop()
            return T.prune(ft).res
        if isinstance(e.fn, A.Name) and e.fn.name.endswith(".ran") and self.ran_sink is not None:
            sym = self.resolve_name(e.fn.name, env, e.fn.span)
            if sym is not None and sym.kind == "csop":
                # CS.ran() in a transition: a fresh free variable over CS (every value is one binding)
                cs = sym.data[0]
                self.ran_counter += 1
                vname = f"{cs}.ran#{self.ran_counter}"
                vsym = Symbol(vname, "var", self.cstypes[cs], e.span, cs)
                self.ran_sink.append((vname, cs, vsym))
                self.infer(e.arg, env)
                e.fn = A.Name(e.fn.span, "ignore")
                e.fn.ref = self.builtin_syms["ignore"]
                # rewrite in place: App(ignore, ()) is replaced by the variable through the parent
                e.ran_var = vsym
                return self.cstypes[cs]
        ft = self.infer(e.fn, env)
        at = self.infer(e.arg, env)
        r = T.TVar()
        pf = T.prune(ft)
        if isinstance(pf, T.TFun):
            self.must(at, pf.arg, e.arg.span, f"the argument of {self._fn_name(e.fn)}")
            self.must(pf.res, r, e.span, "an application")
        else:
            self.must(ft, T.TFun(at, r), e.fn.span, "an application (the left side is not a function)")
        return r

    @staticmethod
    def _fn_name(f):
        return f"'{f.name}'" if isinstance(f, A.Name) else "the function"

    def _i_Neg(self, e, env):
        t = self.infer(e.operand, env)
        self.must(t, T.TVar(overload=("int", "real")), e.span, "'~'")
        return t

    def _i_If(self, e, env):
        self.must(self.infer(e.cond, env), T.BOOL, e.cond.span, "the condition of 'if'")
        tt = self.infer(e.then, env)
        et = self.infer(e.else_, env)
        return self._join_branches(e, "then", "else_", tt, et)

    def _join_branches(self, e, a, b, ta, tb):
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

    def _i_Case(self, e, env):
        st = self.infer(e.subject, env)
        rt = None
        for _i, (pat, body) in enumerate(e.rules):
            binds: dict[str, Symbol] = {}
            self.must(self.infer_pat(pat, binds), st, pat.span, "a case pattern")
            bt = self.infer(body, env.child(binds))
            if rt is None:
                rt = bt
            else:
                self.must(bt, rt, body.span, "the rules of 'case' (all must have the same type)")
        return rt

    def _i_Fn(self, e, env):
        at, rt = T.TVar(), T.TVar()
        for pat, body in e.rules:
            binds: dict[str, Symbol] = {}
            self.must(self.infer_pat(pat, binds), at, pat.span, "the argument pattern of 'fn'")
            self.must(self.infer(body, env.child(binds)), rt, body.span, "the rules of 'fn'")
        return T.TFun(at, rt)

    def _i_Let(self, e, env):
        inner = env.child()
        for d in e.decls:
            if isinstance(d, A.ValDecl):
                t = self.infer(d.expr, inner)
                binds: dict[str, Symbol] = {}
                self.must(self.infer_pat(d.pat, binds), t, d.pat.span, "the pattern of 'val'")
                inner = inner.child(binds)
            elif isinstance(d, A.FunDecl):
                sym = self.fun_decl(d, inner)
                if sym is None:
                    raise Abort()
                inner = inner.child({d.name: sym})
        return self.infer(e.body, inner)

    def _i_Seq(self, e, env):
        t = None
        for x in e.items:
            t = self.infer(x, env)
        return t

    def _i_Annot(self, e, env):
        t = self.infer(e.expr, env)
        at = self.type_of_annotation(e.type_expr)
        if at is None:
            raise Abort()
        self.must(t, at, e.span, "a type annotation")
        return t

    def _i_ToMs(self, e, env):
        return T.ms(self.infer(e.expr, env))

    def _i_OpFun(self, e, env):
        a, b, r = self._op_types(e.op, e)
        return T.TFun(T.TTuple([a, b]), r)

    def _op_types(self, op, node):
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
        if op in ("++", "--", "+++"):
            elem = T.TVar()
            e.left = self.infer_ms(e.left, elem, env, f"the left operand of '{op}'")
            e.right = self.infer_ms(e.right, elem, env, f"the right operand of '{op}'")
            return T.ms(elem)
        if op == "@+":
            elem = T.TVar()
            e.left = self.infer_ms(e.left, elem, env, "the tokens of '@+'")
            self.infer_delay(e, env)
            return T.ms(elem)
        if op == "@@":
            self.error("E0206", "absolute timestamps '@@' are not supported; use '@+' delays", e.span)
            raise Abort()
        a, b, r = self._op_types(op, e)
        self.must(self.infer(e.left, env), a, e.left.span, f"the left operand of '{op}'")
        self.must(self.infer(e.right, env), b, e.right.span, f"the right operand of '{op}'")
        return r

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
                return g.type
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
            ft = g.type
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

    # ------------------------------------------------------------------ pages


def check(model: A.Model, overrides: dict | None = None) -> CheckedModel:
    """Resolve names and check types of a parsed model; raises ModelError with every error found, or
    ConfigurationError when a value in `overrides` (name -> CPN ML text or parsed `Override`) does not fit."""
    return Checker(model, overrides).check()


__all__ = ["check", "CheckedModel", "PageInfo", "TransInfo", "ArcInfo"]

