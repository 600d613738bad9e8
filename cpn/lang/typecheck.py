"""Checking a parsed model: the declarations in order (colour sets, variables, constants, functions),
then the pages. The jobs are mixins: colour-set construction (`cpn.lang.colsets`), type inference
(`cpn.lang.infer`), name resolution (`cpn.lang.resolve`), multiset contexts (`cpn.lang.multisets`),
`--set` values (`cpn.lang.overrides`) and net structure (`cpn.lang.pages`).

Every error of a file is collected (one `Diagnostic` each) before `ModelError` is raised.
Imports `cpn.lang.*`, `cpn.values` and layer 0.
"""

from __future__ import annotations

from cpn.diagnostics import Diagnostic, Severity, Span
from cpn.errors import ModelError
from cpn.expr.evaluate import Evaluator, run_deep
from cpn.lang import ast as A
from cpn.lang import types as T
from cpn.lang.builtins import BUILTINS, LIBRARY_CONSTRUCTOR_TYPES, MLError, library_constructors, parse_type
from cpn.lang.checked import Abort, ArcInfo, CheckedModel, Env, PageInfo, TransInfo
from cpn.lang.colsets import ColourSetConstruction
from cpn.lang.infer import TypeInference
from cpn.lang.multisets import MultisetInference
from cpn.lang.overrides import OverrideChecks, parse_overrides
from cpn.lang.pages import PageChecks
from cpn.lang.resolve import NameResolution
from cpn.lang.symbols import ConInfo, Symbol
from cpn.values import colours as C


class Checker(ColourSetConstruction, TypeInference, NameResolution, PageChecks, MultisetInference,
              OverrideChecks):
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
        self.symmetries: list[tuple[str, str]] = []  # `symmetry` declarations: (colour set, kind)
        self.used_overrides: set[str] = set()
        self.pending: list[tuple] = []
        self.net_name = "Top"
        self.builtin_syms: dict[str, Symbol] = {}
        for name, (tytext, _) in BUILTINS.items():
            self.builtin_syms[name] = Symbol(name, "builtin", parse_type(tytext))
        self.genv = Env(self.globals)
        self.init_draws()  # random draws, simulation-only constructs, draws in functions (cpn.lang.function_draws)
        # CPN Tools' standard declarations; a model may redeclare them
        self.predefined = {"UNIT", "BOOL", "INT", "STRING", "REAL", "TIME", "INTINF"}
        for name, cs, ty in (("UNIT", C.UnitCS("UNIT"), T.UNIT), ("BOOL", C.BoolCS("BOOL"), T.BOOL),
                             ("INT", C.IntCS("INT"), T.INT), ("STRING", C.StringCS("STRING"), T.STRING),
                             ("REAL", C.RealCS("REAL"), T.REAL), ("TIME", C.IntCS("TIME"), T.INT),
                             ("INTINF", C.IntCS("INTINF"), T.INT)):
            self.colsets[name] = cs
            self.cstypes[name] = ty
            self.cs_spans[name] = Span("<standard declarations>", 0, 0)
        for sym in library_constructors():  # NONE, SOME, LESS, EQUAL, GREATER, Date.Jan, ...
            self.globals[sym.name] = sym
        # SML's exception Fail of string, which a model may raise and handle like its own
        fail = Symbol("Fail", "con", T.TFun(T.STRING, T.EXN), Span("<standard declarations>", 0, 0))
        fail.data = ConInfo("exn", "Fail#0", "union", True)
        self.globals["Fail"] = fail

    # ------------------------------------------------------------------ diagnostics
    def error(self, code, message, span, hint=None, notes=(), **params):
        self.diags.append(Diagnostic(code, message, span, hint=hint, notes=list(notes), params=params))

    def warn(self, code, message, span, hint=None, **params):
        self.diags.append(Diagnostic(code, message, span, hint=hint, params=params, severity=Severity.WARNING))

    def _where(self, span: Span | None) -> str:
        return f"{span.line}:{span.col}" if span else "?"

    # ------------------------------------------------------------------ entry point
    def check(self) -> CheckedModel:
        top_decls: list = []
        modules: dict[str, A.ModuleDecl] = {}
        for d in self.model.decls:
            self.top_decl(d, top_decls, modules)
        self.unused_overrides()
        self.raise_override_problems()
        self.module_decls = modules
        top = self.page(self.net_name, None, top_decls)
        pages = {name: self.page(name, m, m.body) for name, m in modules.items()}
        self.check_instances(top, pages)
        for p in pages.values():
            self.check_instances(p, pages)
        self.settle_function_draws()
        errors = [d for d in self.diags if d.severity is Severity.ERROR]
        if errors:
            self.note_overrides(errors)
            raise ModelError(self.diags, {self.file: self.model.source})
        checked = CheckedModel(self.model, self.net_name, self.colsets, self.cstypes, self.variables,
                               self.globals, self.ev, top, pages,
                               [d for d in self.diags if d.severity is Severity.WARNING])
        checked.symmetries = list(self.symmetries)
        self.record_draws(checked)
        return checked

    def top_decl(self, d: A.Decl, top_decls: list, modules: dict) -> None:
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
            if isinstance(d.pat, A.PWild):  # `val _ = e`: checked and evaluated, naming nothing (SML)
                self.val_decl(d)
                return
            if d.name is None:
                self.error("E0206", "a 'val' with a pattern is only supported inside 'let'", d.span,
                           hint="Declare each name with its own 'val NAME = ...', or use #1, #2.")
                return
            self.val_decl(d)
            if d.pat.ref is None:
                self.failed_names.add(d.name)
        elif isinstance(d, A.ExceptionDecl):
            self.exception_decl(d)
        elif isinstance(d, A.SymmetryDecl):
            self.symmetry_decl(d)
        elif isinstance(d, A.LocalDecl):
            self.local_decl(d, top_decls, modules)
        elif isinstance(d, A.FunDecl):
            if self.top_fun_decl(d) is None and isinstance(d.name, str):
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

    def local_decl(self, d: A.LocalDecl, top_decls: list, modules: dict) -> None:
        """`local D1 in D2 end`: the names D1 declares are seen by D2, then hidden again (an earlier
        declaration of the same name is visible after the block)."""
        before = dict(self.globals)
        for x in d.private:
            self.top_decl(x, top_decls, modules)
        private = {n: s for n, s in self.globals.items() if before.get(n) is not s}
        for x in d.public:
            self.top_decl(x, top_decls, modules)
        for name, sym in private.items():
            if self.globals.get(name) is sym:
                if name in before:
                    self.globals[name] = before[name]
                else:
                    del self.globals[name]

    def symmetry_decl(self, d: A.SymmetryDecl) -> None:
        """Record `symmetry CS = permutations | rotations;` (checked against the net when a symmetry
        reduction uses it: `cpn.net.symmetry`)."""
        if d.kind not in ("permutations", "rotations"):
            self.error("E0304", f"unknown kind of symmetry '{d.kind}'", d.kind_span,
                       hint="Write 'permutations' (every renaming of the values) or 'rotations' (for a cyclic "
                            "colour set, whose successor wraps around).")
            return
        for name, span in d.names:
            cs = self.lookup_colset(name, span)
            if cs is None:
                continue
            base = cs
            while isinstance(base, C.AliasCS):
                base = base.base
            if not isinstance(base, (C.EnumCS, C.IndexCS)):
                self.error("E0304", f"colour set '{name}' cannot be declared symmetric: it is of kind '{base.kind}'",
                           span, hint="Only enumerations ('with a | b | c') and index colour sets ('index i with "
                           "1..n') are sets of interchangeable values.")
                continue
            if any(n == name for n, _ in self.symmetries):
                self.error("E0202", f"colour set '{name}' is declared symmetric twice", span)
                continue
            self.symmetries.append((name, d.kind))

    def exception_decl(self, d: A.ExceptionDecl) -> None:
        arg = None
        if d.type_expr is not None:
            arg = self.type_of_annotation(d.type_expr)
            if arg is None:
                return
        sym = Symbol(d.name, "con", T.TFun(arg, T.EXN) if arg is not None else T.EXN, d.span)
        sym.data = ConInfo("exn", f"{d.name}#{sym.uid}", "union", arg is not None)
        d.ref = sym
        self._declare_global(sym)

    # ------------------------------------------------------------------ declarations
    def _declare_global(self, sym: Symbol) -> bool:
        old = self.globals.get(sym.name)
        if old is not None and old.kind in ("var", "con") and sym.kind in ("var", "con") \
                and not (old.data is not None and getattr(old.data, "colset", None) in LIBRARY_CONSTRUCTOR_TYPES):
            self.error("E0202", f"'{sym.name}' is declared twice", sym.span,
                       notes=[f"first declared at {self._where(old.span)}"],
                       hint="Rename one of them.", name=sym.name)
            return False
        self.globals[sym.name] = sym  # a later val or fun shadows an earlier one, as in SML
        return True

    def var_decl(self, d: A.VarDecl) -> None:
        cs = self.lookup_colset(d.colset, d.colset_span)
        if cs is None:
            return
        for name, span in d.names:
            sym = Symbol(name, "var", self.cstypes[d.colset], span, d.colset)
            if self._declare_global(sym):
                self.variables[name] = sym

    def val_decl(self, d: A.ValDecl) -> None:
        name = d.name if d.name is not None else "_"
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
                value = run_deep(self.ev.eval, expr, {})
            except (MLError, RecursionError) as exc:
                self.error("E0401", f"evaluating 'val {name}' failed: {exc}", expr.span)
                return
        if d.name is None:
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


def check(model: A.Model, overrides: dict | None = None) -> CheckedModel:
    """Resolve names and check types of a parsed model; raises ModelError with every error found, or
    ConfigurationError when a value in `overrides` (name -> CPN ML text or parsed `Override`) does not fit."""
    return Checker(model, overrides).check()


__all__ = ["check", "CheckedModel", "PageInfo", "TransInfo", "ArcInfo"]

