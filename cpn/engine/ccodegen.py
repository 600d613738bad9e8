"""C from a net's inscriptions: each transition's enabled bindings and their effects, for the native search.

The compiled Python engine (`cpn.engine.compiled`, `cpn.engine.codegen`) stays the reference; this module
generates C that does what it does, step for step, for transitions whose inscriptions map to machine
values: unit, bool, int ranges, enumerations (and unions without data), index colour sets and products
and records of these, as 64-bit integers (a product as its components); a token is its colour id (its
position in `CS.all()`; for an unbounded int, a union with data, or a product or record with one, an id
interned in the order its values are first met, the same on both sides: `ctables.Interned`), a place marking a list of (colour id, count) pairs in the order its Python dict has them. Guards and arc
inscriptions over these (arithmetic, `div`, `mod`, comparisons, `andalso`, `orelse`, `not`, `if`,
tuples, `#i`, index constructors, constants), lists (held by reference, `ctables.ListDom`: literals,
`::`, `@`, list patterns and the library's list functions, docs/internals.md) and the model's functions
over them (clauses with constant, variable, tuple, record and list patterns, `if`, `case`, `let val`;
one returning a product or record expanded in place) are compiled; anything else leaves its transition
to the Python engine, with the reason.

The generated group function of transition t (`grp_t`) follows the binding plan of `cpn.engine.plan`
exactly as `TransitionCodegen` does: the same loops over the same tokens in the same order, the same
tests, so it finds the same bindings in the same order; then, as `CompiledEngine._miss` does, it numbers
each binding element and interns the markings and deltas its occurrence makes, in the same order, into
tables (`_cnet.c`) that the Python engine's tables mirror (`NativeCode.to_python`, `NativeCode.to_c`):
the ids agree on both sides. What C cannot evaluate at run time (a division by zero, a result that does
not fit 64 bits (Python's integers are unbounded), a value outside its colour set, a pattern that does not
match, deep recursion) is left to the Python engine for that key,
which computes it or reports the error with its position.

Examples
--------
>>> import cpn
>>> model = cpn.loads("colset N = int with 0..3; var x : N; place P : N = 1`0;"
...                   " trans t [x < 3]; arc P -> t : x; arc t -> P : x + 1;")
>>> code = native_code(model.engine())
>>> sorted(code.native), code.left
([0], {})
"""

from __future__ import annotations

from dataclasses import fields, is_dataclass, replace

from cpn.engine import plan
from cpn.engine.ctables import (
    Interned,
    Layout,
    ListDom,
    NativeCode,
    NotNative,
    RangedList,
    S,
    StrDom,
    Tp,
    U,
    UnionDom,
    base_colset,
    interned,
    layout,
    list_key,
    value_parts,
)
from cpn.expr import binding as B
from cpn.expr import nodes as A
from cpn.values.colours import EnumCS, ListCS, StringCS

#: a transition whose variables have more bindings than this is left to Python (one slot each)
MAX_BINDINGS: int = 1 << 22
#: calls of model functions nested deeper than this are left to the Python engine (which computes them or
#: reports its own recursion limit, reached at 120 to 150 levels of a simple recursion)
MAX_DEPTH: int = 64
#: model functions returning products or records are expanded in place, nested at most this deep
MAX_INLINE: int = 6
_I64 = 1 << 62
_CHECKED = {"+": "g_add", "-": "g_sub", "*": "g_mul"}


# ---------------------------------------------------------------------------- values in C
def leaves(cv) -> list[str]:
    if isinstance(cv, S):
        return [cv.code]
    out: list[str] = []
    for x in cv.items:
        out.extend(leaves(x))
    return out


def shape(cv):
    if isinstance(cv, U):
        return cv.lay.shape
    return None if isinstance(cv, S) else tuple(shape(x) for x in cv.items)


def py_cv(v):
    """A Python value of a constant as a C value (NotNative for strings, reals, lists, unions)."""
    if isinstance(v, bool):
        return S("1" if v else "0")
    if isinstance(v, int):
        if abs(v) >= _I64:
            raise NotNative(f"the integer {v} does not fit 64 bits")
        return S(f"INT64_C({v})" if abs(v) > 1 << 30 else str(v))
    if v == ():
        return S("0")
    if isinstance(v, tuple):
        return Tp([py_cv(x) for x in v])
    raise NotNative(f"the value {v!r} has no C form")


# ---------------------------------------------------------------------------- the module
class Module:
    """The C text of one net: encoders, user functions, then one group function per transition."""

    def __init__(self, net, evaluator):
        self.net = net
        self.ev = evaluator
        self.encoders: dict[tuple, str] = {}
        self.functions: dict[tuple, str] = {}  # (uid, argument shape) -> C name
        self.returns: dict[tuple, object] = {}  # (uid, argument shape) -> the layout of the union values it returns
        self.fun_decls: dict[int, A.FunDecl] = {d.ref.uid: d for d in net.globals.decls if isinstance(d, A.FunDecl)}
        self.parts: list[str] = []  # function definitions, in order
        self.protos: list[str] = []
        self._n = 0
        self.doms: list[Interned] = []  # the interned colour sets, by domain, then the bindings' domains
        self.by_colset: dict[str, Interned] = {}
        self.bind_doms: dict[int, int] = {}  # transition -> the domain of its binding keys
        self.ndoms = 0
        self.list_doms: dict[tuple, ListDom] = {}  # the lists' domains, by the structure of their elements
        self._strings: StrDom | None = None  # the strings' domain
        self._globals: dict[tuple, object] = {}  # (uid, type, items) -> the C value of a global constant

    def layout(self, cs):
        """The colour ids of colour set cs: its finite layout, or else its values interned (one domain per
        colour set; for a list colour set, one per structure of its elements)."""
        base = base_colset(cs)
        if isinstance(base, StringCS):
            if base.chars is None and base.lengths is None:
                return self.string_dom()
            got = self.by_colset.get(base.name)  # the strings' domain, its tokens checked (a ranged list)
            if got is None:
                chars = base.chars
                if chars is not None and not all(isinstance(ch, str) and len(ch) == 1 for ch in chars):
                    raise NotNative(f"colour set {base.name} restricts its characters by strings of other lengths")
                got = self.by_colset[base.name] = RangedList(
                    self.string_dom(), base.name, [] if chars is None else [(0, ord(chars[0]), ord(chars[1]))], [],
                    None if base.lengths is None else (base.lengths[0], base.lengths[1]))
            return got
        if isinstance(base, ListCS):
            lv, sh = value_parts(base.elem, self.layout)
            lay = self.list_dom(lv, sh)
            checks = [(j, lo, hi) for j, (lo, hi, k) in enumerate(lv) if lo is not None and k == "int"]
            nested = [(j, k) for j, (_lo, _hi, k) in enumerate(lv) if isinstance(k, RangedList)]
            if base.low is None and not checks and not nested:
                return lay
            got = self.by_colset.get(base.name)
            if got is None:
                got = self.by_colset[base.name] = RangedList(
                    lay, base.name, checks, nested, None if base.low is None else (base.low, base.high))
            return got
        try:
            return layout(cs)
        except NotNative:
            name = base_colset(cs).name  # one domain per colour set, whatever its aliases: equal is one id
            lay = self.by_colset.get(name)
            if lay is None:
                lay = interned(cs, self._new_dom, self.layout)  # (its components' domains come first)
                self.doms.append(lay)
                self.by_colset[name] = lay
            return lay

    def string_dom(self) -> StrDom:
        """The domain of the strings (one for the net)."""
        if self._strings is None:
            self._strings = StrDom(self._new_dom(), [(None, None, "int")], None)
            self.doms.append(self._strings)
        return self._strings

    def list_dom(self, leaves, sh) -> ListDom:
        """The domain of the lists whose elements have leaves `leaves` and shape `sh` (ranges dropped)."""
        key = list_key(leaves, sh)
        lay = self.list_doms.get(key)
        if lay is None:
            lay = self.list_doms[key] = ListDom(self._new_dom(), [(None, None, k) for _lo, _hi, k in leaves], sh)
            self.doms.append(lay)
        return lay

    def parts_of_type(self, ty) -> tuple[list, object]:
        """(leaves, shape) of the values of type `ty` (`cpn.net.translate.closed_type`) held as a product is."""
        k = ty[0]
        if k in ("int", "bool", "unit"):
            return [({"int": None, "bool": 0, "unit": 0}[k], {"int": None, "bool": 1, "unit": 0}[k], k)], None
        if k == "list":
            lay = self.list_of_type(ty)
            return [(None, None, lay)], lay.shape
        if k == "string":
            lay = self.string_dom()
            return [(None, None, lay)], lay.shape
        if k in ("*", "{}"):
            out, shapes = [], []
            for t in ty[1]:
                lv, sh = self.parts_of_type(t if k == "*" else t[1])
                out.extend(lv)
                shapes.append(sh)
            return out, tuple(shapes)
        cs = self.net.colsets.get(k)
        if cs is None or len(ty) > 1:
            raise NotNative(f"a value of type {k}")
        return value_parts(cs, self.layout)

    def list_of_type(self, ty) -> ListDom:
        """The domain of the lists of type `ty` (a list type)."""
        if ty is None or ty[0] != "list":
            raise NotNative("a list whose type is not known")
        return self.list_dom(*self.parts_of_type(ty[1]))

    def make_list(self, lay: ListDom, items: list) -> U:
        """The list of the C values `items`, interned."""
        for x in items:
            if shape(x) != lay.elem_shape:
                raise NotNative("a list element of another shape")
        flat = [y for x in items for y in leaves(x)]
        buf = f"(const int64_t[]){{{', '.join(flat)}}}" if flat else "NULL"
        return U(f"g_lmake(c, {lay.dom}, {len(items)}, {lay.ew}, {buf})", lay)

    def global_cv(self, uid: int, ty, items: bool = False):
        """The C value of global constant `uid` of type `ty` (with `items`, its elements'), made once."""
        key = (uid, ty, items)
        got = self._globals.get(key)
        if got is None:
            v = self.ev.globals[uid]
            got = self._globals[key] = [self.const(x, ty[1]) for x in v] if items else self.const(v, ty)
        return got

    def const(self, v, ty):
        """The C value of constant v of type `ty` (None: a scalar or a product of scalars)."""
        if ty is None:
            return py_cv(v)
        k = ty[0]
        if k == "list":
            return self.make_list(self.list_of_type(ty), [self.const(x, ty[1]) for x in v])
        if k in ("*", "{}"):
            return Tp([self.const(x, t if k == "*" else t[1]) for x, t in zip(v, ty[1])])
        if k in ("int", "bool", "unit"):
            return py_cv(v)
        if k == "string":
            return self.make_list(self.string_dom(), [py_cv(ord(ch)) for ch in v])
        cs = self.net.colsets.get(k)
        if cs is None or isinstance(v, tuple):
            raise NotNative(f"a constant of type {k}")
        return py_cv(v)  # an enumeration constant, an index or a union's constructor without data: its position

    def inline_ms(self, e, depth: int = 0):
        """Output inscription e with each call of a model function in the place of a multiset (`after (ks,
        f)` with `fun after (rest, f) = if rest = [] then empty else 1`(rest, f)`) replaced by the function's
        body over the arguments, where the function has one clause binding variables: its terms are then
        the inscription's, as the engine's multiset of the call is made of them."""
        if depth > 8:
            return e
        if isinstance(e, A.BinOp) and e.op in ("++", "+++", "@+"):
            left = self.inline_ms(e.left, depth)
            right = self.inline_ms(e.right, depth) if e.op != "@+" else e.right
            return e if left is e.left and right is e.right else replace(e, left=left, right=right)
        if isinstance(e, A.If):
            a, b = self.inline_ms(e.then, depth), self.inline_ms(e.else_, depth)
            return e if a is e.then and b is e.else_ else replace(e, then=a, else_=b)
        if isinstance(e, A.Case):
            got = _case_as_if(e, self.enum_constants)
            return e if got is None else self.inline_ms(got, depth)
        if isinstance(e, A.App) and isinstance(e.fn, A.Name) and e.fn.ref.kind == "fun":
            fd = self.fun_decls.get(e.fn.ref.uid)
            if fd is not None and len(fd.clauses) == 1 and len(fd.clauses[0].params) == 1:
                names = _param_names(fd.clauses[0].params[0], e.arg)
                if names is not None:
                    return self.inline_ms(_substitute(fd.clauses[0].body, names), depth + 1)
        return e

    def enum_constants(self, name: str) -> int:
        """How many constants enumeration colour set `name` has (0 where it is no enumeration)."""
        cs = self.net.colsets.get(name)
        return len(cs.constants) if isinstance(cs, EnumCS) else 0

    def input_terms(self, t, read: list[int]) -> list:
        """`plan.input_terms`, with an input inscription's `case` over constants as conditional terms
        (`_case_as_if`) where each of them has a condition: such terms bind no variable (`plan` loops over
        no conditional term), so the binding plan is the engine's, for which the `case` is one multiset
        that the transition's tokens must hold."""
        out = []
        for it in plan.input_terms(t, read):
            e = it.term.opaque
            if isinstance(e, A.Case) and it.term.coef is None:
                got = _case_as_if(e, self.enum_constants)
                if got is not None:
                    split = plan.terms(got, it.term.cond)
                    if all(tm.opaque is None and tm.cond for tm in split):
                        out.extend(plan.InputTerm(it.place, tm, it.arc) for tm in split)
                        continue
            out.append(it)
        return out

    def _new_dom(self) -> int:
        self.ndoms += 1
        return self.ndoms - 1

    def bind_dom(self, t: int) -> int:
        """The domain of transition t's interned binding keys."""
        d = self.bind_doms.get(t)
        if d is None:
            d = self.bind_doms[t] = self.ndoms
            self.ndoms += 1
        return d

    def gen_new(self, P: int, T: int, sizes: str) -> list[str]:
        lines = ["void *gen_new(void) {",
                 f"    static const int64_t sizes[] = {{{sizes or '0'}}};"]
        if not self.ndoms:
            return lines + [f"    return g_new({P}, {T}, sizes);", "}"]
        return lines + [f"    return g_new_interned({P}, {T}, sizes, {self.ndoms});", "}"]

    def doms_by_id(self) -> dict:
        return {lay.dom: lay for lay in self.doms}

    def union_of(self, con):
        """The layout of the union of constructor `con` if its values are interned (it has data), else None."""
        if con.kind != "union":
            return None
        lay = self.layout(self.net.colsets[con.colset])
        return lay if isinstance(lay, UnionDom) else None

    def fresh(self, hint: str) -> str:
        self._n += 1
        return f"{hint}{self._n}"

    def encoder(self, lay: Layout) -> str:
        key = tuple(lay.leaves)
        name = self.encoders.get(key)
        if name is None:
            name = self.encoders[key] = f"enc{len(self.encoders)}"
            args = ", ".join(f"int64_t x{i}" for i in range(len(lay.leaves)))
            body = []
            expr = "0"
            for i, (lo, n) in enumerate(lay.leaves):
                body.append(f"    if (x{i} < {lo} || x{i} > {lo + n - 1}) return -1;")
                expr = f"(x{i} - {lo})" if i == 0 else f"({expr} * {n} + (x{i} - {lo}))"
            body.append(f"    return {expr};")
            self.protos.append(f"static int64_t {name}({args});")
            self.parts.append(f"static int64_t {name}({args}) {{\n" + "\n".join(body) + "\n}")
        return name

    def list_check(self, lay: RangedList) -> str:
        """`lck<d>_<k>(c, id)`: list `id` if it is a value of ranged list colour set `lay`, else -1."""
        key = ("ranged", lay.name)
        name = self.encoders.get(key)
        if name is None:
            name = self.encoders[key] = f"lck{lay.dom}_{len(self.encoders)}"
            d, w = lay.dom, lay.ew
            body = ["    if (c->err) return -1;", f"    const int64_t n = g_llen(c, {d}, id);",
                    "    if (c->err) return -1;"]
            if lay.length is not None:
                body.append(f"    if (n < {lay.length[0]} || n > {lay.length[1]}) return -1;")
            body.append("    for (int64_t i = 0; i < n; i++) {")
            for j, lo, hi in lay.checks:
                body.append(f"        {{ const int64_t x = g_lraw(c, {d}, id, 1 + i * {w} + {j});"
                            f" if (x < {_c_int(lo)} || x > {_c_int(hi)}) return -1; }}")
            for j, inner in lay.nested:
                body.append(f"        if ({self.list_check(inner)}(c, g_lraw(c, {d}, id, 1 + i * {w} + {j})) < 0)"
                            " return -1;")
            body += ["    }", "    return id;"]
            self.protos.append(f"static int64_t {name}(gctx *c, int64_t id);")
            self.parts.append(f"static int64_t {name}(gctx *c, int64_t id) {{\n" + "\n".join(body) + "\n}")
        return name

    def ranged_refs(self, leaves_: list, fail: str) -> list[str]:
        """Lines checking the leaves `x<i>` that are ranged lists (`fail` where one is not a value)."""
        return [f"    if ({self.list_check(k)}(c, x{i}) < 0) {fail}"
                for i, (_lo, _hi, k) in enumerate(leaves_) if isinstance(k, RangedList)]

    def interner(self, lay: Interned) -> str:
        key = ("interned", lay.dom)
        name = self.encoders.get(key)
        if name is None:
            name = self.encoders[key] = f"inn{lay.dom}"
            args = "".join(f", int64_t x{i}" for i in range(len(lay.leaves)))
            body = [f"    if (x{i} < {_c_int(lo)} || x{i} > {_c_int(hi)}) return -1;"
                    for i, (lo, hi, _kind) in enumerate(lay.leaves) if lo is not None]
            body += self.ranged_refs(lay.leaves, "return -1;")
            xs = ", ".join(f"x{i}" for i in range(len(lay.leaves)))
            body.append("    if (c->err) return -1;  /* a leaf C could not compute: not a value to intern */")
            body.append(f"    const int64_t x[] = {{{xs}}};")
            body.append(f"    return g_node(c, {lay.dom}, x, {len(lay.leaves)});")
            self.protos.append(f"static int64_t {name}(gctx *c{args});")
            self.parts.append(f"static int64_t {name}(gctx *c{args}) {{\n" + "\n".join(body) + "\n}")
        return name

    def constructor(self, lay: UnionDom, tag: int) -> str:
        """`un<d>_<tag>(c, data's leaves)`: the id of the union value (c->err if the data is outside its
        colour set: the engine evaluates it)."""
        key = ("union", lay.dom, tag)
        name = self.encoders.get(key)
        if name is None:
            name = self.encoders[key] = f"un{lay.dom}_{tag}"
            leaves_ = lay.cons[tag][0] if lay.cons[tag] is not None else []
            args = "".join(f", int64_t x{i}" for i in range(len(leaves_)))
            body = ["    if (c->err) return 0;"]
            body += [f"    if (x{i} < {_c_int(lo)} || x{i} > {_c_int(hi)}) {{ c->err = 1; return 0; }}"
                     for i, (lo, hi, _kind) in enumerate(leaves_) if lo is not None]
            body += self.ranged_refs(leaves_, "{ c->err = 1; return 0; }")
            xs = ", ".join([str(tag)] + [f"x{i}" for i in range(len(leaves_))])
            body.append(f"    const int64_t x[] = {{{xs}}};")
            body.append(f"    const int64_t id = g_node(c, {lay.dom}, x, {len(leaves_) + 1});")
            body.append("    return id < 0 ? 0 : id;")
            self.protos.append(f"static int64_t {name}(gctx *c{args});")
            self.parts.append(f"static int64_t {name}(gctx *c{args}) {{\n" + "\n".join(body) + "\n}")
        return name

    def encode(self, lay: Layout, cv) -> str:
        """C code of the colour id of value cv in the layout, or -1 if it is not a value of it."""
        if shape(cv) != lay.shape:
            raise NotNative("a value's shape differs from its colour set's")
        if isinstance(lay, (UnionDom, ListDom)):
            return cv.code
        if isinstance(lay, RangedList):
            return f"{self.list_check(lay)}(c, {cv.code})"
        if lay.interned:
            return f"{self.interner(lay)}(c, {', '.join(leaves(cv))})"
        return f"{self.encoder(lay)}({', '.join(leaves(cv))})"

    # -- user functions, one C function per argument shape
    def function(self, uid: int, arg) -> str:
        key = (uid, shape(arg))
        name = self.functions.get(key)
        if name is not None:
            return name
        fd = self.fun_decls.get(uid)
        if fd is None or len(fd.clauses[0].params) != 1:
            raise NotNative("a function of several curried arguments")
        # a name that does not depend on the process (uids are numbered per process): the same net gives the
        # same C, one library in the compile cache
        name = self.functions[key] = self.fresh("uf")
        nargs = len(leaves(arg))
        params = "".join(f", int64_t a{i}" for i in range(nargs))
        self.protos.append(f"static int64_t {name}(gctx *c{params});")
        it = iter(range(nargs))

        def build(sh):
            if sh is not None and sh[0] == "u":
                return U(f"a{next(it)}", self.doms_by_id()[sh[1]])
            return S(f"a{next(it)}") if sh is None else Tp([build(s) for s in sh])
        argv = build(shape(arg))
        fx = FunctionC(self, fd.name)
        lines = []
        try:
            for clause in fd.clauses:
                tests: list[str] = []
                binds: dict[int, object] = {}
                fx.match(clause.params[0], argv, tests, binds)
                lines.append(f"    if ({' && '.join(tests) or '1'}) {{")
                fx.stmt(clause.body, fx.bind_locals(binds, 2, lines), 2, lines)
                lines.append("    }")
        except NotNative:
            del self.functions[key]
            raise
        if fx.ret is not None:
            self.returns[key] = fx.ret
        args = "".join(f", a{i}" for i in range(nargs))
        self.parts.append(
            f"static int64_t {name}_body(gctx *c{params}) {{\n" + "\n".join(lines)
            + "\n    return g_fail(c);\n}\n"
            f"static int64_t {name}(gctx *c{params}) {{\n"
            f"    if (c->depth >= {MAX_DEPTH}) return g_fail(c);\n"
            f"    c->depth++;\n    int64_t r = {name}_body(c{args});\n    c->depth--;\n    return r;\n}}")
        self.protos.append(f"static int64_t {name}_body(gctx *c{params});")
        return name


class ExprC:
    """One expression to a C value; `vars` maps transition variables, `locals` function locals to values."""

    def __init__(self, mod: Module, vars_: dict, params: dict):
        self.mod = mod
        self.vars = vars_
        self.params = params
        self.locals: dict[int, object] = {}
        self.inlined = 0  # model functions inlined around this expression (`inline`)

    def with_locals(self, locals_: dict) -> ExprC:
        e = ExprC(self.mod, self.vars, self.params)
        e.locals = locals_
        e.inlined = self.inlined
        return e

    def scalar(self, e) -> str:
        cv = self.cx(e)
        if not isinstance(cv, S):
            raise NotNative("a tuple where a scalar is expected")
        return cv.code

    def cx(self, e):
        fn = getattr(self, "_c_" + type(e).__name__, None)
        if fn is None:
            raise NotNative(f"{type(e).__name__} expressions")
        return fn(e)

    def _c_Const(self, e):
        if e.kind in ("int", "bool", "unit"):
            return py_cv(e.value)
        if e.kind == "string":
            return self.mod.const(e.value, ("string",))
        raise NotNative(f"{e.kind} constants")

    def _c_Name(self, e):
        sym = e.ref
        k = sym.kind
        if k == "var":
            return self.vars[sym.name]
        if k == "local":
            if sym.uid not in self.locals:
                raise NotNative("a local that is not a value")
            return self.locals[sym.uid]
        if k == "val":
            return self.mod.global_cv(sym.uid, e.ty)
        if k == "param" and sym.uid in self.params:
            return self.mod.const(self.params[sym.uid], e.ty)
        if k == "con" and self.mod.union_of(sym.data) is not None and not sym.data.has_arg:
            lay = self.mod.union_of(sym.data)
            return U(f"{self.mod.constructor(lay, sym.data.tag)}(c)", lay)
        if k == "con" and _tag(sym.data) is not None:
            return S(str(sym.data.tag))
        raise NotNative(f"the name {sym.name} ({k})")

    def _c_TupleE(self, e):
        return Tp([self.cx(x) for x in e.items])

    def _c_ListE(self, e):
        return self.mod.make_list(self.mod.list_of_type(e.ty), [self.cx(x) for x in e.items])

    def pair(self, a, b) -> tuple:
        """The C values of a and b, where one may be `[]` of a type the checker left open (in a polymorphic
        function): the empty list of the other's domain."""
        if _open_nil(a) and not _open_nil(b):
            y = self.cx(b)
            return self.mod.make_list(self.as_list(y).lay, []), y
        if _open_nil(b) and not _open_nil(a):
            x = self.cx(a)
            return x, self.mod.make_list(self.as_list(x).lay, [])
        return self.cx(a), self.cx(b)

    def string(self, e) -> U:
        """The C value of string expression e."""
        cv = self.cx(e)
        if not isinstance(cv, U) or not isinstance(cv.lay, StrDom):
            raise NotNative("a string operation on a value that is not a string")
        return cv

    def lst(self, e) -> U:
        """The C value of list expression e."""
        return self.as_list(self.cx(e))

    @staticmethod
    def as_list(cv) -> U:
        if not isinstance(cv, U) or not isinstance(cv.lay, ListDom):
            raise NotNative("a list operation on a value that is not a list")
        return cv

    def items_of(self, e) -> list | None:
        """The elements of list expression e as C values where they are known when the C is generated (a
        list literal, a constant), else None: a function of them then needs no list built."""
        if isinstance(e, A.ListE):
            return [self.cx(x) for x in e.items]
        if isinstance(e, A.Name) and e.ref.kind == "val" and e.ty is not None and e.ty[0] == "list":
            return self.mod.global_cv(e.ref.uid, e.ty, items=True)
        return None

    def list_builtin(self, name: str, arg):
        """A library function over lists applied to `arg`, or None if it is not one C knows."""
        if name in ("hd", "List.hd", "List.last"):
            items = self.items_of(arg)
            if items:
                return items[0 if name != "List.last" else -1]
            lst = self.lst(arg)
            at = "0" if name != "List.last" else f"g_llen(c, {lst.lay.dom}, {lst.code}) - 1"
            return lst.lay.element(lst.code, at)
        if name in ("size", "String.size"):
            x = self.string(arg)
            return S(f"g_llen(c, {x.lay.dom}, {x.code})")
        if name in ("length", "List.length", "null", "List.null"):
            items = self.items_of(arg)
            n = str(len(items)) if items is not None else None
            if n is None:
                lst = self.lst(arg)
                n = f"g_llen(c, {lst.lay.dom}, {lst.code})"
            return S(n if "null" not in name else f"({n} == 0)")
        if name in ("tl", "List.tl", "rev", "List.rev"):
            lst = self.lst(arg)
            fn = "g_ltl" if "tl" in name else "g_lrev"
            return U(f"{fn}(c, {lst.lay.dom}, {lst.lay.ew}, {lst.code})", lst.lay)
        if name in ("List.nth", "List.take", "List.drop") and isinstance(arg, A.TupleE) and len(arg.items) == 2:
            items = self.items_of(arg.items[0]) if name == "List.nth" else None
            i = self.scalar(arg.items[1])
            if items is not None:  # a chain of conditionals over the known elements
                return _select(items, i)
            lst = self.lst(arg.items[0])
            if name == "List.nth":
                return lst.lay.element(lst.code, i)
            fn = "g_ltake" if name == "List.take" else "g_ldrop"
            return U(f"{fn}(c, {lst.lay.dom}, {lst.lay.ew}, {lst.code}, {i})", lst.lay)
        return None

    def higher(self, kind: str, f, over, ty):
        """`List.filter f l`, `List.map f l`, `List.exists f l`, `List.all f l` (over: l's C value) and
        `List.tabulate (n, f)` (over: n) with f a `fn`: a loop in a GNU statement expression, f's body
        evaluated in place for each element (c->err ends it: the engine evaluates the whole)."""
        lv, iv, nv, bv, kv, rv = (self.mod.fresh(h) for h in ("hl", "hi", "hn", "hb", "hk", "hr"))
        if kind == "tabulate":
            x = S(iv)
            head = f"int64_t {nv} = {over}; if ({nv} < 0) c->err = 1;"
        else:
            x = over.lay.element(lv, iv)
            head = f"const int64_t {lv} = {over.code}; int64_t {nv} = g_llen(c, {over.lay.dom}, {lv});"
        v = self.case_of(x, f.rules)
        if kind in ("exists", "all"):
            test = self.scalar_of(v)
            stop = f"if ({'' if kind == 'exists' else '!'}({test})) {{ {rv} = {int(kind == 'exists')}; break; }}"
            return S(f"__extension__ ({{ {head} int64_t {rv} = {int(kind == 'all')}; "
                     f"for (int64_t {iv} = 0; !c->err && {iv} < {nv}; {iv}++) {{ {stop} }} c->err ? 0 : {rv}; }})")
        if kind == "filter":
            out, put, cond = over.lay, leaves(x), self.scalar_of(v)
        else:
            out = self.mod.list_of_type(ty)
            if shape(v) != out.elem_shape:
                raise NotNative("a list element of another shape")
            put, cond = leaves(v), "1"
        w = out.ew
        fill = " ".join(f"{bv}[{kv} * {w} + {j}] = {code};" for j, code in enumerate(put))
        return U(f"__extension__ ({{ {head} int64_t {kv} = 0; "
                 f"int64_t *{bv} = (int64_t *)malloc(((size_t)({nv} > 0 ? {nv} : 0) * {w} + 1) * sizeof(int64_t)); "
                 f"if (!{bv}) c->err = 2; "
                 f"for (int64_t {iv} = 0; !c->err && {iv} < {nv}; {iv}++) {{ if ({cond}) {{ {fill} {kv}++; }} }} "
                 f"int64_t {rv} = g_lmake(c, {out.dom}, {kv}, {w}, {bv}); free({bv}); {rv}; }})", out)

    @staticmethod
    def scalar_of(cv) -> str:
        if not isinstance(cv, S) or isinstance(cv, U):
            raise NotNative("a tuple where a scalar is expected")
        return cv.code

    def mem(self, lst_e, x_e) -> S:
        """`mem lst x`."""
        x = self.cx(x_e)
        items = self.items_of(lst_e)
        if items is not None:
            return S("(" + " || ".join(equal(x, y) for y in items) + ")" if items else "0")
        lst = self.lst(lst_e)
        if shape(x) != lst.lay.elem_shape:
            raise NotNative("mem of a value of another shape than the list's elements")
        return S(f"g_lmem(c, {lst.lay.dom}, {lst.lay.ew}, {lst.code}, (const int64_t[]){{{', '.join(leaves(x))}}})")

    def _c_RecordE(self, e):
        return Tp([self.cx(x) for _, x in sorted(e.fields, key=lambda f: f[0])])

    def _c_App(self, e):
        fn = e.fn
        if isinstance(fn, A.Select):
            v = self.cx(e.arg)
            if not isinstance(v, Tp) or not 0 <= fn.index < len(v.items):
                raise NotNative("#i of a value that is not a product")
            return v.items[fn.index]
        if isinstance(fn, A.Name):
            sym = fn.ref
            if sym.kind == "con" and self.mod.union_of(sym.data) is not None and sym.data.has_arg:
                lay = self.mod.union_of(sym.data)
                arg = self.cx(e.arg)
                if shape(arg) != lay.cons[sym.data.tag][1]:
                    raise NotNative("a constructor's data of another shape")
                return U(f"{self.mod.constructor(lay, sym.data.tag)}(c{''.join(', ' + x for x in leaves(arg))})", lay)
            if sym.kind == "con" and sym.data.kind == "index":
                cs = self.mod.net.colsets[sym.data.colset]
                return S(f"g_rng(c, {self.scalar(e.arg)}, {cs.low}, {cs.high})")
            if sym.kind == "builtin" and sym.name == "not":
                return S(f"(!{self.scalar(e.arg)})")
            if sym.kind == "builtin":
                got = self.list_builtin(sym.name, e.arg)
                if got is not None:
                    return got
            if sym.kind == "fun":
                arg = self.cx(e.arg)
                try:
                    name = self.mod.function(sym.uid, arg)
                except NotNative:
                    got = self.inline(sym.uid, arg)
                    if got is None:
                        raise
                    return got
                call = f"{name}(c{''.join(', ' + x for x in leaves(arg))})"
                lay = self.mod.returns.get((sym.uid, shape(arg)))
                return S(call) if lay is None else U(call, lay)
        if isinstance(fn, A.App) and isinstance(fn.fn, A.Name) and fn.fn.ref.kind == "builtin" \
                and fn.fn.ref.name in ("mem", "List.mem"):
            return self.mem(fn.arg, e.arg)
        if isinstance(fn, A.App) and isinstance(fn.fn, A.Name) and fn.fn.ref.kind == "builtin" \
                and fn.fn.ref.name in _HIGHER and isinstance(fn.arg, A.Fn):
            return self.higher(_HIGHER[fn.fn.ref.name], fn.arg, self.lst(e.arg), e.ty)
        if isinstance(fn, A.Name) and fn.ref.kind == "builtin" and fn.ref.name == "List.tabulate" \
                and isinstance(e.arg, A.TupleE) and len(e.arg.items) == 2 and isinstance(e.arg.items[1], A.Fn):
            return self.higher("tabulate", e.arg.items[1], self.scalar(e.arg.items[0]), e.ty)
        name = fn.ref.name if isinstance(fn, A.Name) else fn.fn.ref.name if isinstance(fn, A.App) \
            and isinstance(fn.fn, A.Name) else None
        raise NotNative(f"the library function {name}" if name else
                        "an application of something other than a function of the model or the library")

    def constant(self, e):
        """(value,) of a string constant or a `val` bound to one, else None."""
        if isinstance(e, A.Const) and e.kind == "string":
            return (e.value,)
        if isinstance(e, A.Name) and e.ref.kind == "val":
            v = self.mod.ev.globals[e.ref.uid]
            return (v,) if isinstance(v, str) else None
        return None

    def _c_Neg(self, e):
        return S(f"g_neg(c, {self.scalar(e.operand)})")

    def _c_If(self, e):
        cond = self.scalar(e.cond)
        a, b = self.pair(e.then, e.else_)
        if shape(a) != shape(b):
            raise NotNative("if branches of different shapes")

        def join(x, y):
            if isinstance(x, U):
                return U(f"({cond} ? {x.code} : {y.code})", x.lay)
            if isinstance(x, S):
                return S(f"({cond} ? {x.code} : {y.code})")
            return Tp([join(p, q) for p, q in zip(x.items, y.items)])
        return join(a, b)

    def inline(self, uid: int, arg):
        """A model function's value on C value `arg` as an expression of its clauses (a `case` over the
        argument), where it has no C function of its own (it returns a product or record): None for a
        function of several curried arguments, or nested deeper than `MAX_INLINE`."""
        fd = self.mod.fun_decls.get(uid)
        if fd is None or len(fd.clauses[0].params) != 1 or self.inlined >= MAX_INLINE:
            return None
        ex = self.with_locals(self.locals)
        ex.inlined = self.inlined + 1
        return ex.case_of(arg, [(cl.params[0], cl.body) for cl in fd.clauses])

    def _c_Case(self, e):
        """`case` as a chain of conditionals (each rule's data read only once its tests pass)."""
        return self.case_of(self.cx(e.subject), e.rules)

    def case_of(self, subj, rules):
        fx = FunctionC(self.mod, "")
        arms = []
        for pat, body in rules:
            tests: list[str] = []
            binds: dict = {}
            fx.match(pat, subj, tests, binds)
            arms.append((" && ".join(tests) or "1", self.with_locals({**self.locals, **binds}).cx(body)))
        shapes = {repr(shape(v)) for _, v in arms}
        if len(shapes) != 1:
            raise NotNative("case rules of different shapes")

        def chain(i, sh_of):
            if i == len(arms):
                return None
            cond, v = arms[i]
            rest = chain(i + 1, sh_of)
            return v if rest is None and cond == "1" else (cond, v, rest)

        def build(node, pick):
            if node is None:
                return "g_fail(c)"
            if not isinstance(node, tuple):
                return pick(node)
            cond, v, rest = node
            return f"(({cond}) ? {pick(v)} : {build(rest, pick)})"

        tree = chain(0, None)
        first = arms[0][1]

        def over(x, path):
            if isinstance(x, Tp):
                return Tp([over(y, path + [i]) for i, y in enumerate(x.items)])

            def pick(v):
                for i in path:
                    v = v.items[i]
                return v.code
            code = build(tree, pick)
            return U(code, x.lay) if isinstance(x, U) else S(code)
        return over(first, [])

    def _c_BinOp(self, e):
        op = e.op
        if op == "::":
            h, t = self.cx(e.left), self.lst(e.right)
            if shape(h) != t.lay.elem_shape:
                raise NotNative("a list element of another shape")
            return U(f"g_lcons(c, {t.lay.dom}, {t.lay.ew}, (const int64_t[]){{{', '.join(leaves(h))}}}, {t.code})",
                     t.lay)
        if op in ("@", "^^"):
            a, b = self.lst(e.left), self.lst(e.right)
            if a.lay is not b.lay:
                raise NotNative("an append of lists of different shapes")
            return U(f"g_lapp(c, {a.lay.dom}, {a.lay.ew}, {a.code}, {b.code})", a.lay)
        if op == "^":
            a, b = self.string(e.left), self.string(e.right)
            return U(f"g_lapp(c, {a.lay.dom}, 1, {a.code}, {b.code})", a.lay)
        if op in ("=", "<>"):
            consts = self.constant(e.left), self.constant(e.right)
            if None not in consts:  # two constants the C cannot hold (strings: a model's switches)
                return S("1" if (consts[0][0] == consts[1][0]) == (op == "=") else "0")
            eq = equal(*self.pair(e.left, e.right))
            return S(eq if op == "=" else f"(!{eq})")
        if op in ("andalso", "orelse", "+", "-", "*", "<", "<=", ">", ">=", "div", "mod"):
            a, b = self.scalar(e.left), self.scalar(e.right)
            if op == "div":
                return S(f"g_div(c, {a}, {b})")
            if op == "mod":
                return S(f"g_mod(c, {a}, {b})")
            if op in _CHECKED:  # overflow is handed back to Python, whose integers are unbounded
                return S(f"{_CHECKED[op]}(c, {a}, {b})")
            cop = {"andalso": "&&", "orelse": "||"}.get(op, op)
            return S(f"({a} {cop} {b})")
        raise NotNative(f"the operator {op}")


#: the library's functions over lists that C runs as loops (`ExprC.higher`)
_HIGHER = {"List.filter": "filter", "filter": "filter", "List.map": "map", "map": "map", "List.exists": "exists",
           "List.all": "all"}


def _param_names(p, arg) -> dict | None:
    """{uid of a parameter: its argument} where pattern p binds variables only and `arg` has its shape."""
    if isinstance(p, A.PVar) and p.ref.kind != "con":
        return {p.ref.uid: arg}
    if isinstance(p, A.PWild):
        return {}
    if isinstance(p, A.PTuple) and isinstance(arg, A.TupleE) and len(p.items) == len(arg.items):
        out: dict = {}
        for q, x in zip(p.items, arg.items):
            got = _param_names(q, x)
            if got is None:
                return None
            out.update(got)
        return out
    return None


def _case_as_if(e, constants=None):
    """`case` e as `if`s where each rule but a last catch-all tests a constant, `[]` or a constant of an
    enumeration colour set (its subject is then evaluated once per test), else None. Without a catch-all,
    rules that name every constant of an enumeration (`constants(colour set)`: how many it has) need no
    test in the last rule: no value escapes them, as no value escapes the `case`."""
    rest = None
    rules = list(e.rules)
    if rules and constants is not None and not any(isinstance(p, (A.PWild, A.PConst)) or
                                                   (isinstance(p, A.PVar) and p.ref.kind != "con")
                                                   for p, _b in rules):
        seen = {(p.ref.data.colset, p.ref.data.tag) for p, _b in rules if _enum_constant(p)}
        sets = {cs for cs, _tag in seen}
        if len(seen) == len(rules) and len(sets) == 1 and len(seen) == constants(next(iter(sets))):
            rest = rules.pop()[1]  # the last rule matches every value the others leave
    for pat, body in reversed(rules):
        if isinstance(pat, A.PWild):
            rest = body
            continue
        if isinstance(pat, A.PVar) and pat.ref.kind != "con":
            rest = _substitute(body, {pat.ref.uid: e.subject})
            continue
        if rest is None:  # no rule matches every value
            return None
        if isinstance(pat, A.PList) and not pat.items:
            other = A.ListE(pat.span, [], None)
        elif isinstance(pat, A.PConst) and pat.kind in ("int", "bool", "unit"):
            other = A.Const(pat.span, pat.value, pat.kind)
        elif _enum_constant(pat):
            other = A.Name(pat.span, pat.name, None, pat.ref)
        else:
            return None
        rest = A.If(e.span, A.BinOp(pat.span, "=", e.subject, other), body, rest)
    return rest


def _enum_constant(p) -> bool:
    """Whether pattern p is a constant of an enumeration colour set."""
    return isinstance(p, A.PVar) and p.ref is not None and p.ref.kind == "con" \
        and getattr(p.ref.data, "kind", None) == "enum"


def _substitute(x, names: dict):
    """Expression x with each local name of `names` replaced by its expression (names are unique per binder,
    so nothing is captured)."""
    if isinstance(x, A.Name):
        return names.get(x.ref.uid, x) if x.ref is not None and x.ref.kind == "local" else x
    if isinstance(x, (list, tuple)):
        got = [_substitute(y, names) for y in x]
        return x if all(a is b for a, b in zip(got, x)) else type(x)(got)
    if not is_dataclass(x) or isinstance(x, (A.Ref, A.Constructor)) or isinstance(x, type):
        return x
    changes = {}
    for f in fields(x):
        v = getattr(x, f.name)
        nv = _substitute(v, names)
        if nv is not v:
            changes[f.name] = nv
    return replace(x, **changes) if changes else x


def _open_nil(e) -> bool:
    """Whether e is `[]` of a type not fixed."""
    return isinstance(e, A.ListE) and not e.items and not _fixed(e.ty)


def _fixed(ty) -> bool:
    """Whether type `ty` (`closed_type`) has no part left open."""
    if ty is None or ty[0] == "'":
        return False
    if ty[0] == "*":
        return all(_fixed(x) for x in ty[1])
    if ty[0] == "{}":
        return all(_fixed(x) for _label, x in ty[1])
    return all(_fixed(x) for x in ty[1:])


def _select(items: list, i: str):
    """Element i (C code) of the C values `items`: a chain of conditionals (g_fail past the last)."""
    if not items:
        return S("g_fail(c)")
    first = items[0]
    if isinstance(first, Tp):
        return Tp([_select([x.items[j] for x in items], i) for j in range(len(first.items))])
    code = "g_fail(c)"
    for k in range(len(items) - 1, -1, -1):
        code = f"(({i}) == {k} ? {items[k].code} : {code})"
    return U(code, first.lay) if isinstance(first, U) else S(code)


def _c_int(x: int) -> str:
    return f"INT64_C({x})" if abs(x) > 1 << 30 else str(x)


def _tag(con):
    """The value of a constructor that is a value of its own (an enumeration constant, a union constructor
    without data: its position), or None."""
    if con.kind == "enum" or (con.kind == "union" and not con.has_arg and isinstance(con.tag, int)):
        return con.tag
    return None


def union_tag(cv: U) -> str:
    """C code of the tag of union value cv."""
    return f"g_leaf(c, {cv.lay.dom}, {cv.lay.width}, {cv.code}, 0)"


def equal(a, b) -> str:
    la, lb = leaves(a), leaves(b)
    if shape(a) != shape(b):
        raise NotNative("a comparison of values of different shapes")
    return "(" + " && ".join(f"({x}) == ({y})" for x, y in zip(la, lb)) + ")" if la else "1"


class FunctionC:
    """The body of a model function as C statements (clauses, `if`, `case`, `let val`)."""

    def __init__(self, mod: Module, name: str):
        self.mod = mod
        self.name = name
        self.ret = None  # the layout of the union values it returns, if it returns some

    def match(self, p, cv, tests: list, binds: dict) -> None:
        if isinstance(p, A.PWild):
            return
        if isinstance(p, A.PVar):
            if p.ref.kind == "con" and isinstance(cv, U):
                tests.append(f"({union_tag(cv)}) == {p.ref.data.tag}")
                return
            if p.ref.kind == "con":
                if _tag(p.ref.data) is None or not isinstance(cv, S):
                    raise NotNative("a constructor pattern")
                tests.append(f"({cv.code}) == {p.ref.data.tag}")
            else:
                binds[p.ref.uid] = cv
            return
        if isinstance(p, A.PConst):
            if p.kind not in ("int", "bool", "unit") or not isinstance(cv, S):
                raise NotNative(f"a {p.kind} pattern")
            tests.append(f"({cv.code}) == {py_cv(p.value).code}")
            return
        if isinstance(p, A.PTuple):
            if not isinstance(cv, Tp) or len(cv.items) != len(p.items):
                raise NotNative("a tuple pattern against a value of another shape")
            for q, x in zip(p.items, cv.items):
                self.match(q, x, tests, binds)
            return
        if isinstance(p, A.PRecord):
            if not isinstance(cv, Tp) or len(cv.items) != len(p.ty_labels):
                raise NotNative("a record pattern against a value of another shape")
            for label, q in p.fields:
                self.match(q, cv.items[p.ty_labels.index(label)], tests, binds)
            return
        if isinstance(p, A.PCon) and isinstance(cv, U) and p.ref.data.kind == "union":
            tests.append(f"({union_tag(cv)}) == {p.ref.data.tag}")  # (before the data's leaves are read)
            self.match(p.arg, cv.lay.payload(cv.code, p.ref.data.tag), tests, binds)
            return
        if isinstance(p, A.PCon) and p.ref.data.kind == "index":
            self.match(p.arg, cv, tests, binds)
            return
        if isinstance(p, A.PAs):
            binds[p.ref.uid] = cv
            self.match(p.pat, cv, tests, binds)
            return
        if isinstance(p, (A.PList, A.PCons)):
            lst = ExprC.as_list(cv)
            n = f"g_llen(c, {lst.lay.dom}, {lst.code})"
            if isinstance(p, A.PList):  # (the length first: the elements are read only where they are)
                tests.append(f"{n} == {len(p.items)}")
                for i, q in enumerate(p.items):
                    self.match(q, lst.lay.element(lst.code, str(i)), tests, binds)
                return
            tests.append(f"{n} >= 1")
            self.match(p.head, lst.lay.element(lst.code, "0"), tests, binds)
            self.match(p.tail, U(f"g_ltl(c, {lst.lay.dom}, {lst.lay.ew}, {lst.code})", lst.lay), tests, binds)
            return
        raise NotNative(f"a {type(p).__name__} pattern")

    def bind_locals(self, binds: dict, depth: int, out: list, locals_: dict | None = None) -> dict:
        """Declare C locals for the values bound by a pattern (each evaluated once)."""
        locals_ = dict(locals_ or {})
        pad = "    " * depth
        for uid, cv in binds.items():
            def put(x):
                if isinstance(x, U):
                    name = self.mod.fresh("l")
                    out.append(f"{pad}int64_t {name} = {x.code};")
                    return U(name, x.lay)
                if isinstance(x, S):
                    name = self.mod.fresh("l")
                    out.append(f"{pad}int64_t {name} = {x.code};")
                    return S(name)
                return Tp([put(y) for y in x.items])
            locals_[uid] = put(cv)
        return locals_

    def stmt(self, e, locals_: dict, depth: int, out: list) -> None:
        if depth > 40:
            raise NotNative("functions nested too deeply")
        pad = "    " * depth
        ex = ExprC(self.mod, {}, {}).with_locals(locals_)
        if isinstance(e, A.If):
            out.append(f"{pad}if ({ex.scalar(e.cond)}) {{")
            self.stmt(e.then, locals_, depth + 1, out)
            out.append(f"{pad}}} else {{")
            self.stmt(e.else_, locals_, depth + 1, out)
            out.append(f"{pad}}}")
            return
        if isinstance(e, A.Case):
            subj = self.bind_locals({-1: ex.cx(e.subject)}, depth, out)[-1]
            for pat, body in e.rules:
                tests: list[str] = []
                binds: dict = {}
                self.match(pat, subj, tests, binds)
                out.append(f"{pad}if ({' && '.join(tests) or '1'}) {{")
                self.stmt(body, self.bind_locals(binds, depth + 1, out, locals_), depth + 1, out)
                out.append(f"{pad}}}")
            out.append(f"{pad}return g_fail(c);")
            return
        if isinstance(e, A.Let) and all(isinstance(d, A.ValDecl) for d in e.decls):
            inner = dict(locals_)
            out.append(f"{pad}{{")
            for d in e.decls:
                v = ExprC(self.mod, {}, {}).with_locals(inner).cx(d.expr)
                tests: list[str] = []
                binds: dict = {}
                self.match(d.pat, v, tests, binds)
                if tests:
                    out.append(f"{pad}    if (!({' && '.join(tests)})) return g_fail(c);")
                inner = self.bind_locals(binds, depth + 1, out, inner)
            self.stmt(e.body, inner, depth + 1, out)
            out.append(f"{pad}}}")
            return
        cv = ex.cx(e)
        if isinstance(cv, U):  # a union value: the call's value is one too (`Module.returns`)
            self.ret = cv.lay
        elif not isinstance(cv, S):
            raise NotNative("a tuple where a scalar is expected")
        out.append(f"{pad}return {cv.code};")


# ---------------------------------------------------------------------------- transitions
class TransitionC:
    """The group function of one transition: its bindings on the markings of the places it reads (in the
    order of `TransitionCodegen`), then each binding element's effect (as `CompiledEngine._miss`)."""

    def __init__(self, mod: Module, t, k: int, read: list[int], writes: list[int], place_layouts: list):
        self.mod, self.t, self.k, self.read, self.writes = mod, t, k, read, writes
        self.pl = place_layouts
        net = mod.net
        self.var_lay = []
        self.vars: dict[str, object] = {}
        for i, v in enumerate(t.variables):
            cs = net.colsets[net.variables[v].data]
            lay = mod.layout(cs)
            self.var_lay.append(lay)
            # a variable's slot: its colour id, or its value if it is a scalar (`slot`)
            self.vars[v] = S(f"v{i}") if lay.shape is None else lay.decode(f"v{i}")
        self.ex = ExprC(mod, self.vars, t.params)
        # its consuming arcs' terms (a `case` over constants split, `Module.input_terms`), made once
        self.in_terms = mod.input_terms(t, read)
        self.views: set[int] = set()  # timed places read: bound on their untimed views
        self.lines: list[str] = []
        self.depth = 1
        self.size = 1
        # a binding's key: its variables' colour ids in mixed radix, or (a variable of an interned colour
        # set) the interned tuple of their slots
        self.open_keys = any(lay.interned for lay in self.var_lay)
        for lay in self.var_lay:
            if not lay.interned:
                self.size *= lay.size
        if self.size > MAX_BINDINGS and not self.open_keys:
            raise NotNative(f"its variables have more than {MAX_BINDINGS:,} bindings")
        self.bind_dom = mod.bind_dom(t.index) if self.open_keys else None

    def emit(self, line: str) -> None:
        self.lines.append("    " * self.depth + line)

    def open(self, line: str) -> None:
        self.emit(line)
        self.depth += 1

    # -- binding
    def assign(self, var: str, cv, from_token: bool) -> None:
        """Bind variable `var` to value cv (from a token: a value outside its colour set is Python's)."""
        i = self.t.variables.index(var)
        lay = self.var_lay[i]
        if lay.shape is None:
            if not isinstance(cv, S):
                raise NotNative("a tuple bound to a scalar variable")
            self.emit(f"v{i} = {cv.code};")
            if lay.interned and lay.leaves[0][0] is not None:
                lo, hi, _kind = lay.leaves[0]
                self.emit(f"if (v{i} < {_c_int(lo)} || v{i} > {_c_int(hi)}) {'FAIL' if from_token else 'continue'};")
        else:
            self.emit(f"v{i} = {self.mod.encode(lay, cv)};")
            self.emit(f"if (v{i} < 0) {'FAIL' if from_token else 'continue'};")

    def match(self, e, src, bound: set) -> None:
        if B.is_var(e):
            if e.name in bound:
                self.emit(f"if (!{equal(self.vars[e.name], src)}) continue;")
            else:
                self.assign(e.name, src, True)
                bound.add(e.name)
            return
        if isinstance(e, (A.TupleE, A.RecordE)):
            items = e.items if isinstance(e, A.TupleE) else [x for _, x in sorted(e.fields, key=lambda f: f[0])]
            if not isinstance(src, Tp) or len(src.items) != len(items):
                raise NotNative("a tuple pattern against a value of another shape")
            for x, s in zip(items, src.items):
                self.match(x, s, bound)
            return
        if isinstance(e, A.App) and B.is_constructor_fn(e.fn) and isinstance(src, U) \
                and e.fn.ref.data.kind == "union":
            tag = e.fn.ref.data.tag
            self.emit(f"if (({union_tag(src)}) != {tag}) continue;")
            self.match(e.arg, src.lay.payload(src.code, tag), bound)
            return
        if isinstance(e, A.App) and B.is_constructor_fn(e.fn):
            if e.fn.ref.data.kind != "index":
                raise NotNative("a union constructor pattern")
            self.match(e.arg, src, bound)
            return
        if isinstance(e, A.ListE) or (isinstance(e, A.BinOp) and e.op == "::"):
            lst = ExprC.as_list(src)  # as the engine matches a list: its length, then its elements
            n = f"g_llen(c, {lst.lay.dom}, {lst.code})"
            if isinstance(e, A.ListE):
                self.emit(f"if ({n} != {len(e.items)}) continue;")
                for i, x in enumerate(e.items):
                    self.match(x, lst.lay.element(lst.code, str(i)), bound)
                return
            self.emit(f"if ({n} < 1) continue;")
            self.match(e.left, lst.lay.element(lst.code, "0"), bound)
            self.match(e.right, U(f"g_ltl(c, {lst.lay.dom}, {lst.lay.ew}, {lst.code})", lst.lay), bound)
            return
        self.emit(f"if (!{equal(src, self.ex.cx(e))}) continue;")

    def token(self, pi: int, code: str):
        return self.pl[self.read[pi]].decode(code)

    def generate(self) -> str:
        return self.bind_source() + "\n" + self.recipe() + "\n" + self.group()

    def bind_source(self) -> str:
        """`bind<k>(c, key)`: the enabled bindings on the read places' markings `key` into `c->bind`."""
        t = self.t
        for it in self.in_terms:
            if it.term.opaque is not None:
                raise NotNative("an input arc's inscription is a multiset expression")
        steps = plan.binding_plan(self.in_terms, t.guards, t.variables, t.free)
        conj = B.guard_conjuncts(t.guards)
        nv = len(t.variables)
        head = [f"static int bind{self.k}(gctx *c, const uint32_t *key) {{"]
        for i, p in enumerate(self.read):
            if p in self.views:  # a timed place: bound on its untimed view, as the engine binds
                head.append(f"    int32_t N{i} = 0;")
                head.append(f"    const int32_t *M{i} = g_view(c, {p}, key[{i}], &N{i});")
            else:
                head.append(f"    const int32_t *M{i} = ms_pairs(&c->mk[{p}], key[{i}]);")
                head.append(f"    const int32_t N{i} = ms_len(&c->mk[{p}], key[{i}]);")
            head.append(f"    (void)M{i}; (void)N{i};")
        if self.views:
            head.append("    if (c->err) return -1;")
        for i in range(nv):
            head.append(f"    int64_t v{i} = 0;")
        head.append("    c->nb = 0;")
        self.open("do {")
        bound: set[str] = set()
        self.loop_token: dict[int, str] = {}
        for step in steps:
            if isinstance(step, plan.Test):
                self.emit(f"if (!({self.ex.scalar(conj[step.guard])})) continue;")
            elif isinstance(step, plan.Loop):
                it = self.in_terms[step.term]
                j = self.mod.fresh("j")
                tok = self.mod.fresh("t")
                self.open(f"for (int32_t {j} = 0; {j} < N{it.place}; {j}++) {{")
                self.emit(f"const int64_t {tok} = M{it.place}[2 * {j}];")
                self.loop_token[step.term] = tok
                e = it.term.value
                lay = self.pl[self.read[it.place]]
                if B.is_var(e) and e.name not in bound and lay.interned and lay.shape is not None \
                        and self.var_lay[t.variables.index(e.name)] is lay:  # the token's id is the value's
                    self.emit(f"v{t.variables.index(e.name)} = {tok};")
                    bound.add(e.name)
                else:
                    self.match(e, self.token(it.place, tok), bound)
            elif isinstance(step, plan.Bind):
                tok = self.ex.cx(step.expr)
                self.match_bind(step.pattern, tok, bound)
                for v in sorted(step.new):
                    self.check_member(v)
            else:
                i = t.variables.index(step.var)
                lay = self.var_lay[i]
                if lay.interned:
                    raise NotNative(f"variable {step.var} of a colour set without a finite layout is bound by no arc")
                j = self.mod.fresh("e")
                self.open(f"for (int64_t {j} = 0; {j} < {lay.size}; {j}++) {{")
                self.emit(f"v{i} = {j}{'' if lay.shape is not None or lay.leaves[0][0] == 0 else f' + {lay.leaves[0][0]}'};")
                bound.add(step.var)
        self.consumption_tests()
        self.inhibitor_tests()
        self.emit(f"if (g_grow((void **)&c->bind, &c->bind_cap, c->nb + {max(nv, 1)}, 8)) {{ c->err = 2; goto done; }}")
        for i in range(nv):
            self.emit(f"c->bind[c->nb + {i}] = v{i};")
        self.emit(f"c->nb += {max(nv, 1)};")
        while self.depth > 2:
            self.depth -= 1
            self.emit("}")
        self.depth = 1
        self.emit("} while (0);")
        self.lines.append("done:")
        self.lines.append("    return c->err ? -1 : 0;")
        self.lines.append("}")
        body = "\n".join(head + self.lines)
        self.lines = []
        return body

    def key_lines(self, pad: str, fail: str, fail_node: str) -> list[str]:
        """The binding key `bk` of the variables' slots `v` (`fail` if one is outside its colour set)."""
        lines = []
        for i, lay in enumerate(self.var_lay):
            if lay.interned:
                continue
            lo = lay.leaves[0][0] if lay.shape is None else 0
            lines.append(f"{pad}x = v[{i}] - {lo}; if (x < 0 || x >= {lay.size}) {fail};")
            if not self.open_keys:
                lines.append(f"{pad}bk = bk * {lay.size} + x;")
        if self.open_keys:
            lines.append(f"{pad}bk = g_node(c, {self.bind_dom}, v, {len(self.var_lay)}); if (bk < 0) {fail_node};")
        return lines

    def match_bind(self, e, src, bound: set) -> None:
        """A guard binder `pattern = e`: as `match`, but a value outside a variable's colour set only
        skips the binding (`check_member`)."""
        if B.is_var(e) and e.name not in bound:
            self.assign(e.name, src, False)
            bound.add(e.name)
            return
        if isinstance(e, (A.TupleE, A.RecordE)) and isinstance(src, Tp):
            items = e.items if isinstance(e, A.TupleE) else [x for _, x in sorted(e.fields, key=lambda f: f[0])]
            if len(items) != len(src.items):
                raise NotNative("a tuple pattern against a value of another shape")
            for x, s in zip(items, src.items):
                self.match_bind(x, s, bound)
            return
        self.match(e, src, bound)

    def check_member(self, var: str) -> None:
        i = self.t.variables.index(var)
        lay = self.var_lay[i]
        if isinstance(lay, RangedList):  # a restricted string or list: its length and elements
            self.emit(f"if ({self.mod.list_check(lay)}(c, v{i}) < 0) continue;")
        elif lay.interned:
            if lay.shape is None and lay.leaves[0][0] is not None:
                lo, hi, _kind = lay.leaves[0]
                self.emit(f"if (v{i} < {_c_int(lo)} || v{i} > {_c_int(hi)}) continue;")
        elif lay.shape is None:
            lo, n = lay.leaves[0]
            self.emit(f"if (v{i} < {lo} || v{i} > {lo + n - 1}) continue;")

    def value_code(self, term, k):
        """The value of an input term (the token itself for a looped pattern), as (C value, colour id)."""
        return self.ex.cx(term.value)

    def consumption_tests(self) -> None:
        per_place: dict[int, list] = {}
        for k, it in enumerate(self.in_terms):
            per_place.setdefault(it.place, []).append((k, it.term))
        for pi in range(len(self.read)):
            entries = per_place.get(pi)
            if not entries:
                continue
            lay = self.pl[self.read[pi]]
            k, term = entries[0]
            if len(entries) == 1 and k in self.loop_token and term.coef is None and not term.cond \
                    and B.is_pattern(term.value):
                continue
            if len(entries) == 1 and not term.cond:
                col = self.mod.fresh("col")
                if term.coef is None:
                    self.emit(f"{{ const int64_t {col} = {self.mod.encode(lay, self.ex.cx(term.value))};")
                    self.emit(f"  if ({col} < 0 || ms_count(M{pi}, N{pi}, {col}) == 0) continue; }}")
                else:
                    n = self.mod.fresh("n")
                    self.emit(f"{{ const int64_t {n} = {self.ex.scalar(term.coef)};")
                    self.emit(f"  if ({n} < 0) FAIL;")
                    self.emit(f"  const int64_t {col} = {self.mod.encode(lay, self.ex.cx(term.value))};")
                    self.emit(f"  if ({n} && ({col} < 0 || ms_count(M{pi}, N{pi}, {col}) < {n})) continue; }}")
                continue
            buf = self.mod.fresh("cb")
            cnt = self.mod.fresh("cn")
            self.emit(f"int32_t {buf}[{2 * len(entries)}]; int32_t {cnt} = 0; (void){buf};")
            for _k, term in entries:
                self.accumulate(term, lay, buf, cnt, "continue")
            self.emit(f"if (!g_enough(M{pi}, N{pi}, {buf}, {cnt})) continue;")

    def accumulate(self, term, lay, buf: str, cnt: str, outside: str, check_all: bool = False) -> None:
        """`c[v] = c.get(v, 0) + n` for one term; a value outside the colour set with n > 0 (with any n if
        `check_all`, as the engine checks every produced token): `outside`."""
        opened = 0
        for ce, pol in term.cond:
            self.open(f"if ({'' if pol else '!'}({self.ex.scalar(ce)})) {{")
            opened += 1
        n = self.mod.fresh("n")
        col = self.mod.fresh("col")
        self.emit(f"{{ const int64_t {n} = {'1' if term.coef is None else self.ex.scalar(term.coef)};")
        self.emit(f"  if ({n} < 0) FAIL;")
        if check_all:
            self.emit(f"  {{ const int64_t {col} = {self.mod.encode(lay, self.ex.cx(term.value))};")
            self.emit(f"    if ({col} < 0) {outside}; else if ({n}) {cnt} = g_acc({buf}, {cnt}, {col}, {n}); }} }}")
        else:
            self.emit(f"  if ({n}) {{ const int64_t {col} = {self.mod.encode(lay, self.ex.cx(term.value))};")
            self.emit(f"    if ({col} < 0) {outside}; else {cnt} = g_acc({buf}, {cnt}, {col}, {n}); }} }}")
        for _ in range(opened):
            self.depth -= 1
            self.emit("}")

    def inhibitor_tests(self) -> None:
        for a in self.t.arcs:
            if not a.kind.blocks:
                continue
            pi = self.read.index(a.place)
            if a.expr is None:
                self.emit(f"if (N{pi}) continue;")
                continue
            terms = plan.terms(a.expr)
            if any(tm.opaque is not None for tm in terms):
                raise NotNative("an inhibitor arc's inscription is a multiset expression")
            lay = self.pl[a.place]
            buf, cnt, miss = self.mod.fresh("ib"), self.mod.fresh("in"), self.mod.fresh("im")
            self.emit(f"{{ int32_t {buf}[{2 * len(terms) + 2}]; int32_t {cnt} = 0; int {miss} = 0; (void){buf};")
            self.depth += 1
            for tm in terms:
                self.accumulate(tm, lay, buf, cnt, f"{miss} = 1")
            self.emit(f"int any = {miss}; for (int32_t q = 0; q < {cnt}; q++) any |= {buf}[2 * q + 1] != 0;")
            self.emit(f"if (!any) {{ if (N{pi}) continue; }}")
            self.emit(f"else if (!{miss} && g_enough(M{pi}, N{pi}, {buf}, {cnt})) continue;")
            self.depth -= 1
            self.emit("}")

    # -- a binding element's effect: its deltas, in the order `_recipe` and `_flat_recipe` intern them
    def recipe(self) -> str:
        t = self.t
        self.depth = 1
        self.lines = [f"static int rcp{self.k}(gctx *c, const int64_t *v, int64_t be) {{"]
        for i in range(len(t.variables)):
            self.emit(f"const int64_t v{i} = v[{i}]; (void)v{i};")
        # produced tokens, per place, in arc and term order (all checked before any delta is interned)
        produced: dict[int, tuple[str, str]] = {}
        out_terms: dict[int, list] = {}
        for a in t.arcs:
            if a.kind.produces and a.expr is not None:
                out_terms.setdefault(a.place, []).extend(plan.terms(self.mod.inline_ms(a.expr)))
        for p, terms in out_terms.items():
            if any(tm.opaque is not None for tm in terms):
                raise NotNative("an output arc's inscription is a multiset expression")
            buf, cnt = self.mod.fresh("pb"), self.mod.fresh("pn")
            self.emit(f"int32_t {buf}[{2 * len(terms) + 2}]; int32_t {cnt} = 0; (void){buf};")
            produced[p] = (buf, cnt)
            for tm in terms:
                self.accumulate(tm, self.pl[p], buf, cnt, "FAIL", check_all=True)
        consumed: dict[int, list] = {}
        for it in self.in_terms:
            consumed.setdefault(it.place, []).append(it.term)
        width = 3 * len(self.read) + len(self.writes)
        self.emit(f"if (g_pool(c, {max(width, 1)})) {{ c->err = 2; goto done; }}")
        self.emit("int32_t *r = c->tb->pool + c->tb->npool;")
        resets = {a.place for a in t.arcs if a.kind.empties}
        for i, p in enumerate(self.read):
            terms = consumed.get(i, [])
            if terms:
                buf, cnt = self.mod.fresh("cb"), self.mod.fresh("cn")
                self.emit(f"int32_t {buf}[{2 * len(terms) + 2}]; int32_t {cnt} = 0; (void){buf};")
                for tm in terms:
                    self.accumulate(tm, self.pl[p], buf, cnt, "FAIL")
                self.emit(f"r[{3 * i}] = {cnt} ? (int32_t)g_delta(c, {p}, {buf}, {cnt}) : -1;")
            else:
                self.emit(f"r[{3 * i}] = -1;")
            if p in produced:
                buf, cnt = produced[p]
                self.emit(f"r[{3 * i + 1}] = {cnt} ? (int32_t)g_delta(c, {p}, {buf}, {cnt}) : -1;")
            else:
                self.emit(f"r[{3 * i + 1}] = -1;")
            self.emit(f"r[{3 * i + 2}] = {1 if p in resets else 0};")
        base = 3 * len(self.read)
        for w, p in enumerate(self.writes):
            buf, cnt = produced.get(p, ("NULL", "0"))
            self.emit(f"r[{base + w}] = {cnt} ? (int32_t)g_delta(c, {p}, {buf}, {cnt}) : -2;")
        for w, p in enumerate(self.writes):  # the empty delta of a written place this binding leaves alone
            self.emit(f"if (r[{base + w}] == -2) r[{base + w}] = (int32_t)g_delta(c, {p}, NULL, 0);")
        self.emit("if (c->err) goto done;")
        self.emit(f"g_recipe_done(c, be, {max(width, 1)});")
        self.lines.append("done:")
        self.lines.append("    return c->err ? -1 : 0;")
        self.lines.append("}")
        return "\n".join(self.lines)

    def group(self) -> str:
        nv, nr, nw = len(self.t.variables), len(self.read), len(self.writes)
        width = 1 + nr + nw
        lines = [f"static int grp{self.k}(gctx *c, nd_search *d, const uint32_t *key) {{",
                 "    c->err = 0;",
                 f"    if (bind{self.k}(c, key)) return c->err == 2 ? -2 : -1;",
                 f"    const int64_t nb = c->nb / {max(nv, 1)};",
                 f"    if (g_grow((void **)&c->out, &c->out_cap, nb * {width} + 1, 4)) return -2;",
                 "    for (int64_t b = 0; b < nb; b++) {",
                 f"        const int64_t *v = c->bind + b * {max(nv, 1)};",
                 "        int64_t bk = 0, x;",
                 "        (void)v; (void)x;"]
        lines += self.key_lines("        ", "return -1", "return c->err == 2 ? -2 : -1")
        lines += [
            "        int64_t be;",
            f"        const int32_t *R = g_recipe(c, {self.t.index}, bk, v, rcp{self.k}, &be);",
            "        if (!R) return c->err == 2 ? -2 : -1;",
            f"        int32_t *e = c->out + b * {width};",
            "        e[0] = (int32_t)be;",
        ]
        for i, p in enumerate(self.read):
            lines += [
                "        {",
                f"            const int32_t *r = R + {3 * i};",
                f"            int64_t nid = r[2] ? 0 : key[{i}];",
                f"            if (r[0] >= 0 && !r[2]) nid = g_apply(c, {p}, nid, r[0], -1);",
                f"            if (!c->err && r[1] >= 0) nid = g_apply(c, {p}, nid, r[1], 1);",
                "            if (c->err) return c->err == 2 ? -2 : -1;",
                f"            e[{1 + i}] = (int32_t)nid;",
                "        }"]
        for w in range(nw):
            lines.append(f"        e[{1 + nr + w}] = R[{3 * nr + w}];")
        lines += ["    }",
                  f"    return nd_put_group(d, {self.k}, key, nb, c->out) ? -2 : 0;",
                  "}"]
        return "\n".join(lines)


def native_code(engine) -> NativeCode:
    """The C of an untimed net's transitions (NotNative if no place marking can be held in C)."""
    net = engine.net
    if net.is_timed:
        raise NotNative("the net is timed")
    mod = Module(net, engine.ev)
    layouts = []
    for p in net.places:
        try:
            layouts.append(mod.layout(p.colour_set))
        except NotNative as exc:
            raise NotNative(f"place '{p.name}': {exc}") from None
    bodies: dict[int, str] = {}
    left: dict[int, str] = {}
    var_layouts: dict[int, list[Layout]] = {}
    for k, info in enumerate(engine._plan):
        t = info.t
        saved = (len(mod.parts), len(mod.protos), dict(mod.functions), dict(mod.encoders))
        try:
            tc = TransitionC(mod, t, k, list(info.read), list(info.writes), layouts)
            bodies[k] = tc.generate()
            var_layouts[t.index] = tc.var_lay
        except (NotNative, plan.Unbindable, RecursionError) as exc:
            left[t.index] = _why(exc)
            del mod.parts[saved[0]:]
            del mod.protos[saved[1]:]
            mod.functions, mod.encoders = saved[2], saved[3]
    sizes = ", ".join(str(1 if k not in bodies else _size(var_layouts[engine._plan[k].t.index]))
                      for k in range(len(engine._plan)))
    dispatch = "\n".join(f"    case {k}: return grp{k}(c, d, key);" for k in bodies)
    src = "\n".join([
        "#define FAIL do { c->err = 1; goto done; } while (0)",
        "static int64_t g_rng(gctx *c, int64_t x, int64_t lo, int64_t hi) { if (x < lo || x > hi) c->err = 1; return x; }",
        *mod.protos,
        *mod.parts,
        *bodies.values(),
        "static int gen_group(void *g, nd_search *d, int k, const uint32_t *key) {",
        "    gctx *c = (gctx *)g;",
        "    (void)c; (void)d; (void)key;",
        "    switch (k) {",
        dispatch,
        "    default: return -1;",
        "    }",
        "}",
        "static int64_t gen_add(void *g, uint32_t p, uint32_t did, uint32_t old) {",
        "    gctx *c = (gctx *)g;",
        "    c->err = 0;",
        "    int64_t r = g_apply(c, (int)p, old, did, 1);",
        "    return c->err ? -1 : r;",
        "}",
        *mod.gen_new(len(net.places), len(engine._plan), sizes),
    ])
    return NativeCode(src, sorted(engine._plan[k].t.index for k in bodies), left, layouts, var_layouts,
                      doms=mod.doms, bind_doms=_bind_doms(mod, var_layouts))


def _why(exc: Exception) -> str:
    """Why a transition is left to the engine."""
    if isinstance(exc, RecursionError):  # (a chain of thousands of operators: the engine evaluates it flat)
        return "an inscription nested too deeply for the C generator"
    return str(exc) or type(exc).__name__


def _bind_doms(mod: Module, var_layouts: dict) -> dict[int, int]:
    """The domains of the native transitions' interned binding keys."""
    return {t: d for t, d in mod.bind_doms.items() if t in var_layouts}


def _size(lays) -> int:
    """The number of binding keys of a transition whose variables have layouts `lays` (-1: interned)."""
    n = 1
    for lay in lays:
        if lay.interned:
            return -1
        n *= lay.size
    return n


# ---------------------------------------------------------------------------- timed nets
def timed_out_terms(e, delays: tuple = (), cond=None) -> list[tuple]:
    """An output inscription's terms with their `@+` delays (outermost first), as `codegen.out_terms`
    flattens it: (Term, delay expressions)."""
    cond = cond or []
    if isinstance(e, A.BinOp) and e.op in ("++", "+++"):
        return timed_out_terms(e.left, delays, cond) + timed_out_terms(e.right, delays, cond)
    if isinstance(e, A.BinOp) and e.op == "@+":
        return timed_out_terms(e.left, (*delays, e.right), cond)
    if isinstance(e, A.If):
        return timed_out_terms(e.then, delays, cond + [(e.cond, True)]) \
            + timed_out_terms(e.else_, delays, cond + [(e.cond, False)])
    got = plan.terms(e, cond)
    if any(tm.opaque is not None for tm in got):
        raise NotNative("an output arc's inscription is a multiset expression")
    return [(tm, delays) for tm in got]


class TimedTransitionC(TransitionC):
    """The functions of one transition of a timed net (or of a net with priorities) for the native timed
    search (`_timed.c`), as `CompiledEngine._timed_miss` and `_writes` compute them: `rdy<k>` its binding
    elements' ready times and priorities for the read ids (interning the binding elements; for a
    transition that touches no timed place, its effects too), `eff<k>` the effects of those ready at time
    f, each followed by its successor's written and shifted markings (`nt_settle`)."""

    def __init__(self, mod, t, k, read, writes, place_layouts, timed_places: set, timed: bool, clock: bool):
        super().__init__(mod, t, k, read, writes, place_layouts)
        self.timed_places = timed_places
        self.timed = timed  # its effects depend on the occurrence time
        self.clock = bool(timed_places) or clock  # the net is timed (else: an untimed net with priorities)
        self.views = {p for p in read if p in timed_places}
        self.resets = {a.place for a in t.arcs if a.kind.empties}
        # per place: its input arcs' delay `e @+ k` (CPN Tools' preemption), as `_TInfo.early`
        self.early = {a.place: a.preemption for a in t.arcs if a.preemption}
        for p in (*read, *writes):
            if isinstance(place_layouts[p], NotNative):  # a place whose markings C cannot hold
                raise place_layouts[p]
        if any(p in self.resets for p in writes):
            raise NotNative("a reset arc on a place it does not read")

    def generate(self) -> str:
        return "\n".join([self.bind_source(), self.one(), self.ready_fn(), self.effect_fn()])

    def one(self) -> str:
        """`one<k>(c, v, key, mode, f, e, ready, prio)`: one binding's evaluation (mode 0: its values are
        checked), its ready time and priority (mode 1), and its entry at time f into e (mode 2)."""
        t = self.t
        self.depth = 1
        self.lines = [f"static int one{self.k}(gctx *c, const int64_t *v, const uint32_t *key, int mode, int64_t f, "
                      "int32_t *e, int64_t *ready, int64_t *prio) {",
                      "    (void)key; (void)f; (void)e; (void)mode;"]
        for i in range(len(t.variables)):
            self.emit(f"const int64_t v{i} = v[{i}]; (void)v{i};")
        consumed: dict[int, list] = {}
        for it in self.in_terms:
            consumed.setdefault(it.place, []).append(it.term)
        cons: dict[int, tuple[str, str]] = {}
        for i, p in enumerate(self.read):
            terms = consumed.get(i, [])
            buf, cnt = self.mod.fresh("cb"), self.mod.fresh("cn")
            self.emit(f"int32_t {buf}[{2 * len(terms) + 2}]; int32_t {cnt} = 0; (void){buf};")
            for tm in terms:
                self.accumulate(tm, self.pl[p], buf, cnt, "FAIL")
            cons[i] = (buf, cnt)
        out_terms: dict[int, list] = {}
        for a in t.arcs:
            if a.kind.produces and a.expr is not None:
                got = timed_out_terms(self.mod.inline_ms(a.expr))
                if got:
                    out_terms.setdefault(a.place, []).extend(got)
        prod: dict[int, tuple[str, str]] = {}
        for p, terms in out_terms.items():
            buf, cnt = self.mod.fresh("pb"), self.mod.fresh("pn")
            self.emit(f"int64_t {buf}[{3 * len(terms) + 3}]; int32_t {cnt} = 0; (void){buf};")
            prod[p] = (buf, cnt)
            for tm, delays in terms:
                self.produce(tm, delays, self.pl[p], buf, cnt)
        td = "0"
        if t.delay is not None:
            self.emit(f"const int64_t td = {self.ex.scalar(t.delay)};")
            td = "td"
        self.emit(f"*prio = {'1000' if t.priority is None else self.ex.scalar(t.priority)};")
        self.emit("if (c->err || mode == 0) goto done;")
        self.emit("int64_t r = INT64_MIN;")
        for i, p in enumerate(self.read):
            if p in self.timed_places and consumed.get(i):
                buf, cnt = cons[i]
                early = f" q = g_sub(c, q, {self.early[p]});" if self.early.get(p) else ""
                self.emit(f"if ({cnt}) {{ int64_t q = g_ready(c, {p}, key[{i}], {buf}, {cnt});{early} "
                          "if (q > r) r = q; }")
        self.emit("*ready = r;")
        self.emit("if (c->err || mode == 1) goto done;")
        nr = len(self.read)
        if not self.clock:
            self.recipe_writes(cons, prod, out_terms)
            self.lines.append("done:")
            self.lines.append("    return c->err ? -1 : 0;")
            self.lines.append("}")
            out = "\n".join(self.lines)
            self.lines = []
            return out
        self.emit(f"const int64_t base = g_add(c, f, {td if self.timed else '0'}); (void)base;")
        for i, p in enumerate(self.read):
            buf, cnt = cons[i]
            timed = p in self.timed_places
            if not timed and p not in self.resets:
                self.emit(f"{{ int64_t nid = key[{i}];")
                self.emit(f"  if ({cnt}) {{ int64_t sd = g_delta(c, {p}, {buf}, {cnt}); if (c->err) goto done;")
                self.emit(f"    nid = g_apply(c, {p}, nid, sd, -1); if (c->err) goto done; }}")
                if p in prod:
                    pb, pn = prod[p]
                    self.emit(f"  {{ int32_t ab[{2 * len(out_terms[p]) + 2}]; int32_t an = 0;")
                    self.emit(f"    for (int32_t j = 0; j < {pn}; j++) if ({pb}[3 * j + 1]) "
                              f"an = g_acc(ab, an, {pb}[3 * j], {pb}[3 * j + 1]);")
                    self.emit(f"    if (an) {{ int64_t ad = g_delta(c, {p}, ab, an); if (c->err) goto done;")
                    self.emit(f"      nid = g_apply(c, {p}, nid, ad, 1); if (c->err) goto done; }} }}")
                self.emit(f"  e[{1 + i}] = (int32_t)nid; }}")
                continue
            if p not in prod and p not in self.resets:
                self.emit(f"if (!{cnt}) e[{1 + i}] = (int32_t)key[{i}]; else {{")
            else:
                self.emit("{")
            pb, pn = prod.get(p, ("NULL", "0"))
            if timed and p in prod:
                self.emit(f"  for (int32_t j = 0; j < {pn}; j++) {pb}[3 * j + 2] = g_add(c, base, {pb}[3 * j + 2]);")
            latest = f"g_add(c, f, {self.early[p]})" if self.early.get(p) else "f"  # the latest stamp taken
            self.emit(f"  int64_t nid = g_rewrite(c, {p}, {1 if timed else 0}, key[{i}], {buf}, {cnt}, "
                      f"{1 if p in self.resets else 0}, {pb}, {pn}, {latest});")
            self.emit(f"  if (c->err) goto done; e[{1 + i}] = (int32_t)nid; }}")
        for w, p in enumerate(self.writes):
            if p not in prod:
                self.emit(f"e[{1 + nr + w}] = -1;")
                continue
            pb, pn = prod[p]
            timed = p in self.timed_places
            self.emit(f"{{ int32_t ab[{2 * len(out_terms[p]) + 2}]; int32_t an = 0;")
            self.emit(f"  for (int32_t j = 0; j < {pn}; j++) if ({pb}[3 * j + 1]) {{")
            if timed:
                self.emit(f"    int64_t col = g_tid(c, {p}, {pb}[3 * j], g_add(c, base, {pb}[3 * j + 2]));")
                self.emit("    if (c->err) goto done;")
            else:
                self.emit(f"    int64_t col = {pb}[3 * j];")
            self.emit(f"    an = g_acc(ab, an, col, {pb}[3 * j + 1]); }}")
            self.emit(f"  e[{1 + nr + w}] = an ? (int32_t)g_delta(c, {p}, ab, an) : -1; if (c->err) goto done; }}")
        self.lines.append("done:")
        self.lines.append("    return c->err ? -1 : 0;")
        self.lines.append("}")
        out = "\n".join(self.lines)
        self.lines = []
        return out

    def recipe_writes(self, cons: dict, prod: dict, out_terms: dict) -> None:
        """An entry of an untimed net's binding (with priorities), as `CompiledEngine._miss` and `_recipe`
        make it: every delta first (per read place the consumed then the produced, then the written
        places'), then the read places' new ids."""
        nr = len(self.read)
        agg: dict[int, str] = {}
        for p, (pb, pn) in prod.items():
            ab, an = self.mod.fresh("ab"), self.mod.fresh("an")
            self.emit(f"int32_t {ab}[{2 * len(out_terms[p]) + 2}]; int32_t {an} = 0;")
            self.emit(f"for (int32_t j = 0; j < {pn}; j++) if ({pb}[3 * j + 1]) "
                      f"{an} = g_acc({ab}, {an}, {pb}[3 * j], {pb}[3 * j + 1]);")
            agg[p] = (ab, an)
        for i, p in enumerate(self.read):
            buf, cnt = cons[i]
            self.emit(f"int64_t sd{i} = {cnt} ? g_delta(c, {p}, {buf}, {cnt}) : -1; (void)sd{i};")
            if p in agg:
                ab, an = agg[p]
                self.emit(f"int64_t ad{i} = {an} ? g_delta(c, {p}, {ab}, {an}) : -1; (void)ad{i};")
            else:
                self.emit(f"int64_t ad{i} = -1; (void)ad{i};")
        for w, p in enumerate(self.writes):
            if p in agg:
                ab, an = agg[p]
                self.emit(f"e[{1 + nr + w}] = {an} ? (int32_t)g_delta(c, {p}, {ab}, {an}) : -1;")
            else:
                self.emit(f"e[{1 + nr + w}] = -1;")
        self.emit("if (c->err) goto done;")
        for i, p in enumerate(self.read):
            reset = p in self.resets
            self.emit(f"{{ int64_t nid = {'0' if reset else f'key[{i}]'};")
            if not reset:
                self.emit(f"  if (sd{i} >= 0) {{ nid = g_apply(c, {p}, nid, sd{i}, -1); if (c->err) goto done; }}")
            self.emit(f"  if (ad{i} >= 0) {{ nid = g_apply(c, {p}, nid, ad{i}, 1); if (c->err) goto done; }}")
            self.emit(f"  e[{1 + i}] = (int32_t)nid; }}")

    def produce(self, term, delays, lay, buf: str, cnt: str) -> None:
        """One output term's (colour id, count, delay) into buf (every value checked, as `_check_tokens`)."""
        opened = 0
        for ce, pol in term.cond:
            self.open(f"if ({'' if pol else '!'}({self.ex.scalar(ce)})) {{")
            opened += 1
        self.emit(f"{{ const int64_t n = {'1' if term.coef is None else self.ex.scalar(term.coef)};")
        self.emit("  if (n < 0) FAIL;")
        self.emit(f"  const int64_t col = {self.mod.encode(lay, self.ex.cx(term.value))};")
        self.emit("  if (col < 0) FAIL;")
        dl = "0"
        for d in delays:
            dl = f"g_add(c, {dl}, {self.ex.scalar(d)})"
        self.emit(f"  {buf}[3 * {cnt}] = col; {buf}[3 * {cnt} + 1] = n; {buf}[3 * {cnt} + 2] = {dl}; {cnt}++; }}")
        for _ in range(opened):
            self.depth -= 1
            self.emit("}")

    def _key_lines(self, pad: str) -> list[str]:
        return [f"{pad}int64_t bk = 0, x; (void)x;", *self.key_lines(pad, "goto fail", "goto fail")]

    def ready_fn(self) -> str:
        nv, nr, nw = max(len(self.t.variables), 1), len(self.read), len(self.writes)
        width = 1 + nr + nw
        lines = [f"static int rdy{self.k}(gctx *c, nt_search *t, const uint32_t *key) {{",
                 "    c->err = 0;",
                 f"    if (bind{self.k}(c, key)) return c->err == 2 ? -2 : -1;",
                 f"    const int64_t nb = c->nb / {nv};",
                 "    int64_t rd, pr, be, *pairs = NULL;",
                 "    int fresh;",
                 f"    int32_t ent[{width}];",
                 "    for (int64_t b = 0; b < nb; b++)  /* every binding evaluates before one is numbered */",
                 f"        if (one{self.k}(c, c->bind + b * {nv}, key, 0, 0, ent, &rd, &pr)) goto fail;",
                 "    pairs = (int64_t *)malloc((size_t)(2 * nb + 2) * 8);",
                 "    if (!pairs) return -2;"]
        if not self.timed:
            lines.append(f"    if (g_grow((void **)&c->out, &c->out_cap, nb * {width} + 1, 4)) {{ c->err = 2; goto fail; }}")
        lines += ["    for (int64_t b = 0; b < nb; b++) {",
                  f"        const int64_t *v = c->bind + b * {nv};",
                  *self._key_lines("        "),
                  f"        be = g_be(c, {self.t.index}, bk, &fresh);",
                  "        if (c->err) goto fail;"]
        if self.timed:
            lines.append(f"        if (one{self.k}(c, v, key, 1, 0, ent, &rd, &pr)) goto fail;")
        else:
            lines += [f"        int32_t *e = c->out + b * {width};",
                      f"        if (one{self.k}(c, v, key, 2, 0, e, &rd, &pr)) goto fail;",
                      "        e[0] = (int32_t)be; rd = INT64_MIN;"]
        lines += ["        pairs[2 * b] = rd; pairs[2 * b + 1] = pr;",
                  "    }",
                  f"    int rc = nt_put_ready(t, {self.k}, key, nb, pairs);",
                  "    free(pairs); pairs = NULL;",
                  "    if (rc) return -2;"]
        if not self.timed:
            lines += [f"    uint32_t k2[{nr + 1}];",
                      f"    for (int i = 0; i < {nr}; i++) k2[i] = key[i];",
                      f"    k2[{nr}] = 0;",
                      f"    if (nt_put_effect(t, {self.k}, k2, nb, c->out)) return -2;"]
        lines += ["    return 0;",
                  "fail:",
                  "    return c->err == 2 ? -2 : -1;",
                  "}"]
        return "\n".join(lines)

    def effect_fn(self) -> str:
        nv, nr, nw = max(len(self.t.variables), 1), len(self.read), len(self.writes)
        width = 1 + nr + nw
        lines = [f"static int eff{self.k}(gctx *c, nt_search *t, const uint32_t *key, int64_t f, const uint32_t *s) {{",
                 "    c->err = 0;",
                 f"    uint32_t k2[{nr + 1}];",
                 f"    for (int i = 0; i < {nr}; i++) k2[i] = key[i];",
                 f"    k2[{nr}] = {'(uint32_t)f' if self.timed else '0'};",
                 f"    if (bind{self.k}(c, k2)) return c->err == 2 ? -2 : -1;",
                 f"    const int64_t nb = c->nb / {nv};",
                 f"    if (g_grow((void **)&c->out, &c->out_cap, nb * {width} + 1, 4)) return -2;",
                 "    int64_t rd, pr, m = 0;",
                 "    int fresh;",
                 "    for (int64_t b = 0; b < nb; b++) {",
                 f"        const int64_t *v = c->bind + b * {nv};",
                 *self._key_lines("        "),
                 f"        int64_t be = g_be(c, {self.t.index}, bk, &fresh);",
                 "        if (c->err) goto fail;",
                 f"        int32_t *e = c->out + m * {width};",
                 f"        if (one{self.k}(c, v, k2, 1, f, e, &rd, &pr)) goto fail;",
                 "        if (rd > f) continue;",
                 f"        if (one{self.k}(c, v, k2, 2, f, e, &rd, &pr)) goto fail;",
                 "        e[0] = (int32_t)be;",
                 f"        int rc = nt_settle(t, {self.k}, s, f, e);",
                 "        if (rc) return rc;",
                 "        m++;",
                 "    }",
                 f"    return nt_put_effect(t, {self.k}, k2, m, c->out) ? -2 : 0;",
                 "fail:",
                 "    return c->err == 2 ? -2 : -1;",
                 "}"]
        return "\n".join(lines)


def timed_native_code(engine, probe: bool = False) -> NativeCode:
    """The C of a timed net's (or a net with priorities') transitions for the native timed search
    (`TimedTransitionC`; NotNative if no place marking can be held in C or a transition reads the clock).

    With `probe`, only the first instance of each transition of a module (the same page, parameters of the
    same kinds, places of the same colour sets) is generated: its `left` says, in a fraction of the time,
    which transitions the whole net's C would leave to the engine (`auto`'s choice; an instance that
    differs after all is left to the engine when the whole is generated, with its note). Not for a search."""
    net = engine.net
    if getattr(engine, "reads_clock", False):
        raise NotNative("a transition reads the clock")
    mod = Module(net, engine.ev)
    layouts: list = []  # a place's layout, or why it has none: the transitions touching it are the engine's
    for p in net.places:
        try:
            layouts.append(mod.layout(p.colour_set))
        except NotNative as exc:
            layouts.append(NotNative(f"place '{p.name}': {exc}"))
    timed_places = {p for p in range(len(net.places)) if engine.is_timed and engine.store.timed[p]}
    bodies: dict[int, str] = {}
    left: dict[int, str] = {}
    var_layouts: dict[int, list[Layout]] = {}
    seen: set = set()
    for k, info in enumerate(engine._plan):
        t = info.t
        if probe:
            kind = (t.page, t.transition, tuple((u, type(v).__name__) for u, v in sorted(t.params.items())),
                    tuple(net.places[a.place].colour_set.name for a in t.arcs))
            if kind in seen:
                continue
            seen.add(kind)
        saved = (len(mod.parts), len(mod.protos), dict(mod.functions), dict(mod.encoders))
        try:
            tc = TimedTransitionC(mod, t, k, list(info.read), list(info.writes), layouts, timed_places,
                                  bool(engine.is_timed and info.timed), bool(engine.is_timed))
            bodies[k] = tc.generate()
            var_layouts[t.index] = tc.var_lay
        except (NotNative, plan.Unbindable, RecursionError) as exc:
            left[t.index] = _why(exc)
            del mod.parts[saved[0]:]
            del mod.protos[saved[1]:]
            mod.functions, mod.encoders = saved[2], saved[3]
    if not bodies:  # one reason for the whole net: a place C cannot hold, else the first transition's
        raise next((lay for lay in layouts if isinstance(lay, NotNative)), None) \
            or NotNative(next(iter(left.values()), "the net has no transition"))
    sizes = ", ".join(str(1 if k not in bodies else _size(var_layouts[engine._plan[k].t.index]))
                      for k in range(len(engine._plan)))
    held = ", ".join("0" if isinstance(lay, NotNative) else "1" for lay in layouts) or "0"
    src = "\n".join([
        "#define FAIL do { c->err = 1; goto done; } while (0)",
        "static int64_t g_rng(gctx *c, int64_t x, int64_t lo, int64_t hi) { if (x < lo || x > hi) c->err = 1; return x; }",
        *mod.protos,
        *mod.parts,
        *bodies.values(),
        "static int gen_ready(void *g, nt_search *t, int k, const uint32_t *key) {",
        "    gctx *c = (gctx *)g;",
        "    (void)c; (void)t; (void)key;",
        "    switch (k) {",
        *(f"    case {k}: return rdy{k}(c, t, key);" for k in bodies),
        "    default: return -1;",
        "    }",
        "}",
        "static int gen_effect(void *g, nt_search *t, int k, const uint32_t *key, int64_t f, const uint32_t *s) {",
        "    gctx *c = (gctx *)g;",
        "    (void)c; (void)t; (void)key; (void)f; (void)s;",
        "    switch (k) {",
        *(f"    case {k}: return eff{k}(c, t, key, f, s);" for k in bodies),
        "    default: return -1;",
        "    }",
        "}",
        "static int gen_group(void *g, nd_search *d, int k, const uint32_t *key) {",
        "    (void)g; (void)d; (void)k; (void)key;",
        "    return -1;",
        "}",
        f"static const uint8_t HELD[] = {{{held}}};  /* the places whose markings C holds */",
        "static int64_t gen_add(void *g, uint32_t p, uint32_t did, uint32_t old) {",
        "    gctx *c = (gctx *)g;",
        "    if (!HELD[p]) return -1;",
        "    c->err = 0;",
        "    int64_t r = g_apply(c, (int)p, old, did, 1);",
        "    return c->err ? -1 : r;",
        "}",
        "static int64_t gen_shift(void *g, uint32_t p, uint32_t id, uint32_t f) {",
        "    gctx *c = (gctx *)g;",
        "    if (!HELD[p]) return -1;",
        "    c->err = 0;",
        "    int64_t r = g_shift(c, (int)p, id, f);",
        "    return c->err ? -1 : r;",
        "}",
        *mod.gen_new(len(net.places), len(engine._plan), sizes),
    ])
    code = NativeCode(src, sorted(engine._plan[k].t.index for k in bodies), left,
                      [None if isinstance(lay, NotNative) else lay for lay in layouts], var_layouts,
                      doms=mod.doms, bind_doms=_bind_doms(mod, var_layouts))
    code.timed = [p in timed_places for p in range(len(net.places))]
    return code
