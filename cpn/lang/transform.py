"""The lark `Transformer` from parse trees to `cpn.lang.ast`; the only module that knows rule names, with the
expression forms that declare their own (`cpn.expr.forms`)."""

from __future__ import annotations

from lark import Token, Transformer_NonRecursive, Tree, v_args
from lark.tree import Meta

from cpn.diagnostics import Span
from cpn.expr.binding import has_delay
from cpn.expr.forms import BY_RULE
from cpn.lang import ast as A


def _unescape(text: str) -> str:
    out = []
    i = 0
    while i < len(text):
        c = text[i]
        if c == "\\" and i + 1 < len(text):
            n = text[i + 1]
            out.append({"n": "\n", "t": "\t", "\\": "\\", '"': '"'}.get(n, n))
            i += 2
        else:
            out.append(c)
            i += 1
    return "".join(out)


def _end_col(node) -> int:
    """The column of the last character (lark's end column is one past it); on the start line a span
    never ends before it starts, on a later line its end column is its own."""
    end = node.end_column - 1
    return max(end, node.column) if node.end_line == node.line else max(end, 1)


# Operators whose chains may be regrouped without changing the value, the order in which the operands are
# evaluated, or the type: multiset sums, list and string concatenation.
ASSOCIATIVE_OPS: frozenset[str] = frozenset({"++", "+++", "^^", "@", "^"})


# A chain `a1 :: a2 :: ... :: t` of at least this many '::' is read as `[a1, a2, ...] @ t` (the same value,
# the operands evaluated in the same order); shorter chains keep their '::' and its messages.
LONG_CONS_CHAIN: int = 32


# The operators looser than CPN Tools' `infix 7 @+` that an inscription's delay reaches over (delay_whole).
_DELAY_REACHES_OVER: frozenset[str] = frozenset({"+", "-", "^", "::", "@", "^^", "++", "--"})


def _ends_with(outer: Span, inner: Span) -> bool:
    """inner ends where outer does: inner is the last operand of outer, not in parentheses of its own."""
    return (outer.end_line, outer.end_col) == (inner.end_line, inner.end_col)




def delay_whole(e):
    """An arc inscription or initial marking `e @+ d` as CPN Tools reads it: the delay of all of e.

    In CPN ML '@+' is `infix 7`, tighter than `+ - ^ :: @ ++ --`, so `i+1 @+ d` alone would be `i + (1 @+ d)`.
    CPN Tools' help writes an output inscription as `exp @+ arc-delay` and an initial marking as
    `init-mark-exp @+ time-delay` (the delay appended "using @+ as a separator"), and models made with it
    write `i+1@++exponential(1.0/4.0)` and ``1`0 ++ 1`1 @+ 2``: a delay that ends an inscription whose other
    operators are looser delays everything before it, unless it is in parentheses or another delay comes
    earlier. The same holds for each branch of an `if` and each rule of a `case` at the top, and for each term
    of a '+++' sum. Anywhere else '@+' is the operator of its level: `f (x :: y @+ 2)` is `x :: (y @+ 2)`.
    """
    if isinstance(e, A.If):
        e.then, e.else_ = delay_whole(e.then), delay_whole(e.else_)
        return e
    if isinstance(e, A.Case):
        e.rules = [(p, delay_whole(b)) for p, b in e.rules]
        return e
    if not isinstance(e, A.BinOp):
        return e
    if e.op == "+++":
        e.left, e.right = delay_whole(e.left), delay_whole(e.right)
        return e
    spine = []
    node = e
    while isinstance(node, A.BinOp) and node.op in _DELAY_REACHES_OVER and _ends_with(node.span, node.right.span):
        spine.append(node)
        node = node.right
    delay = node
    if not spine or not (isinstance(delay, A.BinOp) and delay.op in ("@+", "@++")) \
            or any(has_delay(n.left) for n in spine):
        return e
    spine[-1].right = delay.left
    end = delay.left.span
    for n in spine:
        n.span = Span(n.span.file, n.span.line, n.span.col, end.end_line, end.end_col)
    s = e.span
    return A.BinOp(Span(s.file, s.line, s.col, delay.span.end_line, delay.span.end_col), delay.op, e, delay.right)


def _chain_op(node) -> str | None:
    if isinstance(node, Tree) and node.data == "binop" and len(node.children) == 3:
        op = str(node.children[1])
        if op in ASSOCIATIVE_OPS:
            return op
    return None


def balance_chains(tree: Tree) -> Tree:
    """Regroup every long chain of one associative operator (`a ++ b ++ ... ++ z`) into a balanced tree.

    A 600-term `++` initial marking is one flat list of operands, not 600 levels of nesting: regrouped, it
    is about ten levels deep, so only real nesting (parentheses, `let`, `if` inside each other) can make a
    model too deep to read. Iterative, so a chain of any length is handled.
    """
    stack = [tree]
    while stack:
        node = stack.pop()
        if not isinstance(node, Tree):
            continue
        for i, child in enumerate(node.children):
            cons = _cons_chain(child)
            if cons is not None:
                node.children[i] = child = cons
            op = _chain_op(child)
            if op is not None:
                operands = _flatten(child, op)
                if len(operands) > 2:
                    node.children[i] = _balanced(operands, op, child.children[1])
                    stack.extend(operands)
                    continue
            stack.append(child)
    return tree


def _is_cons(node) -> bool:
    return isinstance(node, Tree) and node.data == "binop" and len(node.children) == 3 \
        and str(node.children[1]) == "::"


def _cons_chain(node) -> Tree | None:
    """`[a1, ..., an] @ t` for a chain of at least LONG_CONS_CHAIN '::', else None."""
    if not _is_cons(node):
        return None
    heads = []
    tail = node
    while _is_cons(tail):
        heads.append(tail.children[0])
        tail = tail.children[2]
    if len(heads) < LONG_CONS_CHAIN:
        return None
    if isinstance(tail, Tree) and tail.data == "list_":
        return Tree("list_", heads + [c for c in tail.children if c is not None], _span_meta(heads[0], tail))
    lst = Tree("list_", heads, _span_meta(heads[0], heads[-1]))
    token = Token("CONSOP", "@")
    return _join(lst, token, tail)


def _span_meta(first_node, last_node) -> Meta:
    meta = Meta()
    first, last = getattr(first_node, "meta", None), getattr(last_node, "meta", None)
    if first is not None and last is not None and not first.empty and not last.empty:
        meta.line, meta.column = first.line, first.column
        meta.end_line, meta.end_column = last.end_line, last.end_column
        meta.start_pos, meta.end_pos = first.start_pos, last.end_pos
        meta.empty = False
    return meta


def _flatten(node: Tree, op: str) -> list:
    """The operands of a chain of `op`, left to right, whichever way the chain is grouped."""
    out = []
    todo = [node]
    while todo:
        n = todo.pop()
        if _chain_op(n) == op:
            todo.append(n.children[2])
            todo.append(n.children[0])
        else:
            out.append(n)
    return out


def _balanced(operands: list, op: str, token) -> Tree:
    level = list(operands)
    while len(level) > 1:
        nxt = [_join(level[k], token, level[k + 1]) for k in range(0, len(level) - 1, 2)]
        if len(level) % 2:
            nxt.append(level[-1])
        level = nxt
    return level[0]


def _join(left, token, right) -> Tree:
    return Tree("binop", [left, token, right], _span_meta(left, right))


# SML's base types, written in a datatype's constructor arguments, as CPN Tools' standard colour sets
_BASE_TYPES: dict[str, str] = {"int": "INT", "string": "STRING", "bool": "BOOL", "unit": "UNIT", "real": "REAL",
                               "intinf": "INTINF"}


class ToAst(Transformer_NonRecursive):
    """Parse tree to AST; non-recursive, so that a 5,000-term chain is no 5,000 Python frames deep."""

    def __init__(self, filename: str):
        super().__init__(visit_tokens=False)
        self.file = filename

    # -- positions
    def span(self, meta) -> Span:
        if getattr(meta, "empty", False) or not hasattr(meta, "line"):
            return Span(self.file, 0, 0)
        return Span(self.file, meta.line, meta.column, meta.end_line, _end_col(meta))

    def tspan(self, tok: Token) -> Span:
        return Span(self.file, tok.line, tok.column, tok.end_line, _end_col(tok))

    def __default__(self, data, children, meta):
        """A rule without a method here: an expression form that declares its own (cpn.expr.forms)."""
        form = BY_RULE.get(data)
        if form is None:
            return super().__default__(data, children, meta)
        return form.parse(self.span(meta), list(children))

    # -- statements
    def start(self, items):
        return list(items)

    @v_args(meta=True)
    def net_header(self, meta, items):
        return A.NetHeader(self.span(meta), items[0][0])

    @v_args(meta=True)
    def use_decl(self, meta, items):
        tok = items[0]
        return A.UseDecl(self.span(meta), _unescape(tok[1:-1]), self.tspan(tok))

    def name(self, items):
        tok = items[0]
        text = _unescape(tok[1:-1]) if tok.type == "STRING" else str(tok)
        return (text, self.tspan(tok))

    @v_args(meta=True)
    def colset_decl(self, meta, items):
        name, body, timed = items
        return A.ColsetDecl(self.span(meta), str(name), body, timed is not None)

    @v_args(meta=True)
    def datatype_decl(self, meta, items):
        """`datatype M = Ping | Data of INT`: the union colour set `union Ping + Data : INT`; an argument
        that is no colour set name (`of INT * STRING`) is kept for the checker to refuse (`pred`)."""
        fields, bad = [], None
        for con, te in items[1:]:
            if te is None or isinstance(te, A.TName):
                fields.append((con, None if te is None else _BASE_TYPES.get(te.name, te.name)))
            else:
                bad = bad or te
        return A.ColsetDecl(self.span(meta), str(items[0]),
                            A.ColsetBody(self.span(meta), "datatype", fields=fields, pred=bad), False)

    def dtcon(self, items):
        return (str(items[0]), items[1])

    def _cs(self, meta, kind, **kw):
        return A.ColsetBody(self.span(meta), kind, **kw)

    @v_args(meta=True)
    def cs_unit(self, meta, items):
        return self._cs(meta, "unit")

    @v_args(meta=True)
    def cs_bool(self, meta, items):
        """`bool with (no, yes)`: the two booleans, written `no` (false) and `yes` (true)."""
        return self._cs(meta, "bool", names=[str(n) for n in items if n is not None])

    @v_args(meta=True)
    def cs_int(self, meta, items):
        lo, hi = (items + [None, None])[:2]
        return self._cs(meta, "int", low=lo, high=hi)

    @v_args(meta=True)
    def cs_string(self, meta, items):
        """`string with "a".."z" and 3..9`: the strings of those characters, of those lengths."""
        lo, hi, lmin, lmax = (items + [None] * 4)[:4]
        chars = [_unescape(str(c)[1:-1]) for c in (lo, hi) if c is not None]
        return self._cs(meta, "string", names=chars, low=lmin, high=lmax)

    @v_args(meta=True)
    def cs_real(self, meta, items):
        return self._cs(meta, "real")

    @v_args(meta=True)
    def cs_time(self, meta, items):
        return self._cs(meta, "time")

    @v_args(meta=True)
    def cs_enum(self, meta, items):
        return self._cs(meta, "enum", names=[str(t) for t in items])

    @v_args(meta=True)
    def cs_index(self, meta, items):
        con, lo, hi = items
        return self._cs(meta, "index", names=[str(con)], low=lo, high=hi)

    @v_args(meta=True)
    def cs_product(self, meta, items):
        return self._cs(meta, "product", names=[str(t) for t in items])

    @v_args(meta=True)
    def cs_record(self, meta, items):
        return self._cs(meta, "record", fields=list(items))

    def rfield(self, items):
        return (str(items[0]), str(items[1]))

    @v_args(meta=True)
    def cs_list(self, meta, items):
        elem, lo, hi = (items + [None, None])[:3]
        return self._cs(meta, "list", names=[str(elem)], low=lo, high=hi)

    @v_args(meta=True)
    def cs_union(self, meta, items):
        return self._cs(meta, "union", fields=list(items))

    def ufield(self, items):
        return (str(items[0]), str(items[1]) if items[1] is not None else None)

    @v_args(meta=True)
    def cs_subset_by(self, meta, items):
        return self._cs(meta, "subset_by", names=[str(items[0])], pred=items[1])

    @v_args(meta=True)
    def cs_subset_with(self, meta, items):
        return self._cs(meta, "subset_with", names=[str(items[0])], pred=items[1])

    @v_args(meta=True)
    def cs_alias(self, meta, items):
        return self._cs(meta, "alias", names=[str(items[0])])

    @v_args(meta=True)
    def var_decl(self, meta, items):
        names = [(str(t), self.tspan(t)) for t in items[:-1]]
        cs = items[-1]
        return A.VarDecl(self.span(meta), names, str(cs), self.tspan(cs))

    @v_args(meta=True)
    def symmetry_decl(self, meta, items):
        names = [(str(t), self.tspan(t)) for t in items[:-1]]
        return A.SymmetryDecl(self.span(meta), names, str(items[-1]), self.tspan(items[-1]))

    @v_args(meta=True)
    def val_wild(self, meta, items):
        """`val _ = e`: e is checked and evaluated, and names nothing."""
        ty, expr = items
        return A.ValDecl(self.span(meta), A.PWild(self.span(meta)), expr, ty)

    @v_args(meta=True)
    def val_rec(self, meta, items):
        """`val rec f = fn p1 => e1 | p2 => e2`: the function `fun f p1 = e1 | f p2 = e2`."""
        name, rules = items
        return A.FunDecl(self.span(meta), str(name),
                         [A.Clause(pat.span if pat.span else self.span(meta), [pat], body) for pat, body in rules])

    lval_rec = val_rec

    @v_args(meta=True)
    def val_decl(self, meta, items):
        name, ty, expr = items
        return A.ValDecl(self.span(meta), A.PVar(self.tspan(name), str(name)), expr, ty)

    @v_args(meta=True)
    def fun_decl(self, meta, items):
        return self._fun(meta, items)

    def _fun(self, meta, clauses):
        names = {c[0] for c in clauses}
        clause_list = [c[1] for c in clauses]
        fd = A.FunDecl(self.span(meta), clauses[0][0], clause_list)
        if len(names) > 1:
            fd.clauses = clause_list
            fd.ref = ("mismatched-names", sorted(names))
        return fd

    @v_args(meta=True)
    def clause(self, meta, items):
        name = str(items[0])
        params = [p for p in items[1:-2]]
        rty, body = items[-2], items[-1]
        return (name, A.Clause(self.span(meta), params, body, rty))

    @v_args(meta=True)
    def place_decl(self, meta, items):
        (name, nspan), cs, init, fus_kw, fus = items
        return A.PlaceDecl(self.span(meta), name, nspan, str(cs), self.tspan(cs),
                           None if init is None else delay_whole(init), fusion=fus[0] if fus else None)

    @v_args(meta=True)
    def port_decl(self, meta, items):
        kind, (name, nspan), cs, init = items
        return A.PlaceDecl(self.span(meta), name, nspan, str(cs), self.tspan(cs),
                           None if init is None else delay_whole(init), port=str(kind))

    @v_args(meta=True)
    def trans_decl(self, meta, items):
        (name, nspan), guard, delay, prio, action = items
        d = A.TransDecl(self.span(meta), name, nspan, guard or [], delay, prio)
        if action is not None:
            d.outputs, d.action_span, d.action = action
        return d

    def action(self, items):
        """(output variable names, span of the keyword 'action', the action)."""
        names, keyword, expr = items
        return names or [], self.tspan(keyword), expr

    def outputs(self, items):
        return [str(n) for n in items]

    def guard(self, items):
        return [g for g in items if g is not None]

    @v_args(meta=True)
    def delay(self, meta, items):
        if str(items[0]) == "@++":  # a real-valued delay: `() @++ d`, which the checker takes apart
            return A.BinOp(self.span(meta), "@++", A.Const(self.span(meta), (), "unit"), items[1])
        return items[1]

    def priority(self, items):
        return items[0]

    def arc_end(self, items):
        """(name, span, 'place' / 'trans' / None) of one end of an arc."""
        if len(items) == 1 and isinstance(items[0], tuple):
            return (*items[0], None)
        kind = items[0]
        if len(items) == 1:  # a bare `place` or `trans`: the element of that name
            return (str(kind), self.tspan(kind), None)
        return (*items[1], str(kind))

    @v_args(meta=True)
    def arc_decl(self, meta, items):
        (src, sspan, skind), arrow, (dst, dspan, dkind), expr = items
        return A.ArcDecl(self.span(meta), str(arrow), src, sspan, dst, dspan,
                         None if expr is None else delay_whole(expr), skind, dkind)

    @v_args(meta=True)
    def inhibitor_decl(self, meta, items):
        (src, sspan, skind), arrow, (dst, dspan, dkind), expr = items
        return A.ArcDecl(self.span(meta), "inhibitor" if str(arrow) == "->" else "inhibitor?", src, sspan, dst,
                         dspan, expr, skind, dkind)

    @v_args(meta=True)
    def reset_decl(self, meta, items):
        (src, sspan, skind), arrow, (dst, dspan, dkind) = items
        return A.ArcDecl(self.span(meta), "reset" if str(arrow) == "->" else "reset?", src, sspan, dst, dspan, None,
                         skind, dkind)

    @v_args(meta=True)
    def module_decl(self, meta, items):
        name = str(items[0])
        params = []
        body = []
        for it in items[1:]:
            if isinstance(it, tuple) and len(it) == 3 and isinstance(it[0], str):
                params.append(it)
            elif it is not None:
                body.append(it)
        return A.ModuleDecl(self.span(meta), name, params, body)

    def param(self, items):
        return (str(items[0]), str(items[1]), self.tspan(items[0]))

    @v_args(meta=True)
    def instance_decl(self, meta, items):
        (name, nspan), mod = items[0], items[1]
        args, binds = [], []
        for it in items[2:]:
            if it is None:
                continue
            if it[0] == "arg":
                args.append(it[1:])
            else:
                binds.append(it[1:])
        return A.InstanceDecl(self.span(meta), name, nspan, str(mod), self.tspan(mod), args, binds)

    @v_args(meta=True)
    def instance_family(self, meta, items):
        name, var, (low, high, cs, cspan), mod = items[:4]
        args = [it[1:] for it in items[4:] if it is not None and it[0] == "arg"]
        binds = [it[1:] for it in items[4:] if it is not None and it[0] == "bind"]
        return A.InstanceFamilyDecl(self.span(meta), str(name), self.tspan(name), str(mod), self.tspan(mod), args,
                                    binds, str(var), self.tspan(var), low, high, cs, cspan)

    def family_range(self, items):
        return (items[0], items[1], None, None)

    def family_colset(self, items):
        return (None, None, str(items[0]), self.tspan(items[0]))

    def arg(self, items):
        return ("arg", str(items[0]), items[1], self.tspan(items[0]))

    def bind(self, items):
        (port, pspan), (sock, sspan) = items
        return ("bind", port, pspan, sock, sspan)

    # -- types
    @v_args(meta=True)
    def ty_name(self, meta, items):
        return A.TName(self.span(meta), str(items[0]))

    @v_args(meta=True)
    def ty_post(self, meta, items):
        return A.TPost(self.span(meta), items[0], str(items[1]))

    @v_args(meta=True)
    def ty_tuple(self, meta, items):
        return items[0] if len(items) == 1 else A.TTuple(self.span(meta), list(items))

    # -- expressions
    def match(self, items):
        return list(items)

    def mrule(self, items):
        return (items[0], items[1])

    @v_args(meta=True)
    def orelse(self, meta, items):
        return A.BinOp(self.span(meta), "orelse", items[0], items[1])

    @v_args(meta=True)
    def andalso(self, meta, items):
        return A.BinOp(self.span(meta), "andalso", items[0], items[1])

    @v_args(meta=True)
    def binop(self, meta, items):
        left, op, right = items
        return A.BinOp(self.span(meta), str(op), left, right)

    @v_args(meta=True)
    def app(self, meta, items):
        return A.App(self.span(meta), items[0], items[1])

    @v_args(meta=True)
    def int_(self, meta, items):
        return A.Const(self.span(meta), int(str(items[0]).replace("~", "-")), "int")

    @v_args(meta=True)
    def real_(self, meta, items):
        return A.Const(self.span(meta), float(str(items[0]).replace("~", "-")), "real")

    @v_args(meta=True)
    def string_(self, meta, items):
        text = str(items[0])
        if text.startswith("#"):
            text = text[1:]
        return A.Const(self.span(meta), _unescape(text[1:-1]), "string")

    @v_args(meta=True)
    def ident(self, meta, items):
        name = str(items[0])
        if name in ("true", "false"):
            return A.Const(self.span(meta), name == "true", "bool")
        if name == "nil":  # SML's name of the empty list
            return A.ListE(self.span(meta), [])
        return A.Name(self.span(meta), name)

    @v_args(meta=True)
    def qident(self, meta, items):
        return A.Name(self.span(meta), str(items[0]))

    @v_args(meta=True)
    def unit_(self, meta, items):
        return A.Const(self.span(meta), (), "unit")

    def efield(self, items):
        return (str(items[0]), items[1])

    @v_args(meta=True)
    def pfield_annot(self, meta, items):
        tok, ty = items
        return (str(tok), A.PAnnot(self.span(meta), A.PVar(self.tspan(tok), str(tok)), ty))

    @v_args(meta=True)
    def lval(self, meta, items):
        return A.ValDecl(self.span(meta), items[0], items[1])

    @v_args(meta=True)
    def lfun(self, meta, items):
        return self._fun(meta, [i for i in items if i is not None])

    @v_args(meta=True)
    def lexception(self, meta, items):
        return A.ExceptionDecl(self.span(meta), str(items[0]), items[1])

    @v_args(meta=True)
    def exception_decl(self, meta, items):
        return A.ExceptionDecl(self.span(meta), str(items[0]), items[1])

    @v_args(meta=True)
    def local_decl(self, meta, items):
        return A.LocalDecl(self.span(meta), items[0], items[1])

    def local_part(self, items):
        return list(items)

    # -- patterns
    @v_args(meta=True)
    def pannot(self, meta, items):
        return A.PAnnot(self.span(meta), items[0], items[1])

    @v_args(meta=True)
    def pas(self, meta, items):
        return A.PAs(self.span(meta), str(items[0]), items[1])

    @v_args(meta=True)
    def pconsop(self, meta, items):
        return A.PCons(self.span(meta), items[0], items[1])

    @v_args(meta=True)
    def pcon(self, meta, items):
        return A.PCon(self.span(meta), str(items[0]), items[1])

    @v_args(meta=True)
    def pwild(self, meta, items):
        return A.PWild(self.span(meta))

    @v_args(meta=True)
    def pname(self, meta, items):
        name = str(items[0])
        if name in ("true", "false"):
            return A.PConst(self.span(meta), name == "true", "bool")
        if name == "nil":  # SML's name of the empty list
            return A.PList(self.span(meta), [])
        return A.PVar(self.span(meta), name)

    @v_args(meta=True)
    def pint(self, meta, items):
        return A.PConst(self.span(meta), int(items[0]), "int")

    @v_args(meta=True)
    def pnegint(self, meta, items):
        return A.PConst(self.span(meta), -int(items[0]), "int")

    @v_args(meta=True)
    def pstring(self, meta, items):
        text = str(items[0])
        if text.startswith("#"):
            text = text[1:]
        return A.PConst(self.span(meta), _unescape(text[1:-1]), "string")

    @v_args(meta=True)
    def punit(self, meta, items):
        return A.PConst(self.span(meta), (), "unit")

    @v_args(meta=True)
    def ptuple(self, meta, items):
        return A.PTuple(self.span(meta), list(items))

    @v_args(meta=True)
    def plist(self, meta, items):
        return A.PList(self.span(meta), [i for i in items if i is not None])

    @v_args(meta=True)
    def precord(self, meta, items):
        flexible = bool(items) and isinstance(items[-1], Token)
        fields = [i for i in items if i is not None and not isinstance(i, Token)]
        return A.PRecord(self.span(meta), fields, flexible)

    def pfield(self, items):
        if len(items) == 1:
            tok = items[0]
            return (str(tok), A.PVar(self.tspan(tok), str(tok)))
        return (str(items[0]), items[1])
