"""Writing nets as PNML: P/T nets (every place of colour set unit) and symmetric nets (colour sets
unit, bool, enumerations, int ranges and products of them; inscriptions and guards made of the
operators that `cpn.io.pnml` reads, including the helper functions it generates).

The writer works on the checked-free `.cpnet` syntax tree of a flat net (no modules), so that what
`translate` produced can be written back and read again with the same state space.
Imports the stdlib, `cpn.diagnostics`, `cpn.errors`, `cpn.lang` (parsing only) and `cpn.io.pnml._names`.
"""

from __future__ import annotations

import os
import re
from xml.sax.saxutils import escape, quoteattr

from cpn.diagnostics import Diagnostic, Span
from cpn.errors import ModelError

PNML_NS = "http://www.pnml.org/version-2009/grammar/pnml"
PT_TYPE = "http://www.pnml.org/version-2009/grammar/ptnet"
SN_TYPE = "http://www.pnml.org/version-2009/grammar/symmetricnet"

_CMP = {"=": "equality", "<>": "inequality", "<": "lessthan", "<=": "lessthanorequal",
        ">": "greaterthan", ">=": "greaterthanorequal"}


class _Unsupported(Exception):
    def __init__(self, message: str, node=None):
        super().__init__(message)
        self.node = node


def _is_flat_net(net) -> bool:
    """Whether `net` is a flattened `cpn.net.Net` (place and transition instances)."""
    return hasattr(net, "places") and hasattr(net, "transitions") and hasattr(net, "checked")


def _model_of(net):
    """The `.cpnet` syntax tree of `net`: a Model, an object holding one (a loaded model, a flattened
    net), .cpnet text or a path."""
    from cpn.lang import ast as A

    if isinstance(net, A.Model):
        return net
    for attr in ("ast", "model", "syntax", "tree"):
        inner = getattr(net, attr, None)
        if isinstance(inner, A.Model):
            return inner
    if _is_flat_net(net):
        return net.checked.model
    from cpn.lang.parser import parse

    if isinstance(net, os.PathLike) or (isinstance(net, str) and "\n" not in net and net.endswith(".cpnet")):
        path = os.fspath(net)
        with open(path, encoding="utf-8") as fh:
            return parse(fh.read(), path)
    if isinstance(net, str):
        return parse(net, "<cpnet>")
    source = getattr(net, "source", None)
    if isinstance(source, str):
        return parse(source, getattr(net, "file", None) or getattr(net, "path", None) or "<cpnet>")
    raise TypeError(f"cannot write {type(net).__name__} as PNML: give a .cpnet model, its text or its path")


def write(net, path: str | os.PathLike, net_id: str | None = None) -> None:
    """Write `net` as a PNML file at `path` (a P/T net when every place is of colour set unit).

    Raises ModelError (E0502) naming every element that PNML cannot express.
    """
    text = write_text(net, net_id=net_id or os.path.splitext(os.path.basename(os.fspath(path)))[0])
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(text)


def write_text(net, net_id: str = "net") -> str:
    """The PNML document for `net` as text.

    `net` is a `.cpnet` path, its text, its syntax tree, a loaded model (`cpn.load`) or a flattened
    `cpn.net.Net`. A net with modules is written from its flattened form, which must be a P/T net
    (place instances named as in the state space report, e.g. `Sender'Ready 2`).
    """
    from cpn.lang import ast as A

    model = _model_of(net)
    if any(isinstance(d, (A.ModuleDecl, A.InstanceDecl)) for d in model.decls):
        flat = net if _is_flat_net(net) else getattr(net, "net", None)
        if flat is None:
            first = next(d for d in model.decls if isinstance(d, (A.ModuleDecl, A.InstanceDecl)))
            raise ModelError([Diagnostic(
                "E0502", "a net with modules is written from its flattened form", first.span,
                hint="Pass the loaded model (cpn.load(path)) or its flattened net (model.net) to write().")])
        return _FlatPTWriter(flat, net_id).run()
    return _Writer(model, net_id).run()


class _Writer:
    def __init__(self, model, net_id: str) -> None:
        from cpn.lang import ast as A

        self.A = A
        self.model = model
        self.net_id = net_id
        self.diags: list[Diagnostic] = []
        self.colsets: dict[str, object] = {}  # name -> ColsetBody (aliases resolved)
        self.consts: dict[str, str] = {}  # enum constant -> colour set
        self.vars: dict[str, str] = {}
        self.funs: dict[str, tuple[str, str]] = {}  # helper name -> (op, colour set)
        self.places: list = []
        self.transitions: list = []
        self.arcs: list = []
        self.ids: set[str] = set()

    # ------------------------------------------------------------------ helpers
    def fail(self, node, message: str) -> None:
        span = getattr(node, "span", None) or Span(self.model.file, 1, 1)
        self.diags.append(Diagnostic("E0502", message, span,
                                     hint="PNML holds P/T nets and symmetric nets; docs/pnml.md lists what "
                                          "can be written."))

    def xml_id(self, name: str) -> str:
        base = re.sub(r"[^A-Za-z0-9_.-]", "_", name) or "n"
        if not (base[0].isalpha() or base[0] == "_"):
            base = "n" + base
        cand, k = base, 2
        while cand in self.ids:
            cand, k = f"{base}_{k}", k + 1
        self.ids.add(cand)
        return cand

    def resolve(self, name: str):
        seen = set()
        body = self.colsets.get(name)
        while body is not None and body.kind == "alias" and name not in seen:
            seen.add(name)
            name = body.names[0]
            body = self.colsets.get(name)
        return name, body

    # ------------------------------------------------------------------ entry
    def run(self) -> str:
        A = self.A
        for d in self.model.decls:
            if isinstance(d, A.ColsetDecl):
                if d.timed:
                    self.fail(d, f"colour set '{d.name}' is timed; PNML nets are untimed")
                self.colsets[d.name] = d.body
                if d.body.kind == "enum":
                    for c in d.body.names:
                        self.consts[c] = d.name
            elif isinstance(d, A.VarDecl):
                for n, _span in d.names:
                    self.vars[n] = d.colset
            elif isinstance(d, A.FunDecl):
                self.analyse_fun(d)
            elif isinstance(d, A.PlaceDecl):
                if d.fusion:
                    self.fail(d, f"place '{d.name}' belongs to a fusion set; PNML nets here are flat")
                self.places.append(d)
            elif isinstance(d, A.TransDecl):
                if d.delay is not None or d.priority is not None:
                    self.fail(d, f"transition '{d.name}' has a delay or priority, which PNML cannot express")
                self.transitions.append(d)
            elif isinstance(d, A.ArcDecl):
                self.arcs.append(d)
            elif isinstance(d, (A.ModuleDecl, A.InstanceDecl)):
                self.fail(d, "modules and instances cannot be written as PNML (write the flat net)")
            elif isinstance(d, A.ValDecl):
                self.fail(d, "'val' declarations cannot be written as PNML")
            elif isinstance(d, (A.LocalDecl, A.ExceptionDecl)):
                self.fail(d, "'local' and 'exception' declarations cannot be written as PNML")
            elif isinstance(d, A.NetHeader):
                pass
        pt = all(self.resolve(p.colset)[1] is not None and self.resolve(p.colset)[1].kind == "unit"
                 for p in self.places) and not any(t.guards for t in self.transitions)
        if pt:
            text = self.pt_net()
        else:
            text = self.sn_net()
        if self.diags:
            raise ModelError(self.diags)
        return text

    def document(self, net_type: str, page: list[str], declarations: list[str]) -> str:
        out = ['<?xml version="1.0" encoding="UTF-8"?>', f'<pnml xmlns="{PNML_NS}">',
               f"  <net id={quoteattr(self.net_id)} type={quoteattr(net_type)}>",
               f"    <name><text>{escape(self.net_id)}</text></name>"]
        if declarations:
            out += ["    <declaration><structure><declarations>"] + [f"      {d}" for d in declarations] + \
                   ["    </declarations></structure></declaration>"]
        out += ['    <page id="page0">'] + [f"      {x}" for x in page] + ["    </page>", "  </net>", "</pnml>"]
        return "\n".join(out) + "\n"

    def node_ids(self) -> tuple[dict[str, str], dict[str, str]]:
        """The XML ids of the places and of the transitions, apart: a place and a transition may share a
        name (CPN Tools allows it), and each still gets an id of its own."""
        places = {p.name: self.xml_id(p.name) for p in self.places}
        transitions = {t.name: self.xml_id(t.name) for t in self.transitions}
        return places, transitions

    def arc_list(self):
        """(place, transition, direction 'in'/'out', kind, expr, decl) for every arc, double arcs split."""
        pnames = {p.name for p in self.places}
        out = []
        for a in self.arcs:
            src_is_place = a.src_kind == "place" if a.src_kind else (
                a.dst_kind == "trans" if a.dst_kind else a.src in pnames)
            place, trans = (a.src, a.dst) if src_is_place else (a.dst, a.src)
            if a.kind in ("inhibitor", "reset"):
                out.append((place, trans, "in", a.kind, a.expr, a))
            elif a.kind == "<->":
                out.append((place, trans, "in", "normal", a.expr, a))
                out.append((place, trans, "out", "normal", a.expr, a))
            else:
                out.append((place, trans, "in" if src_is_place else "out", "normal", a.expr, a))
        return out

    # ------------------------------------------------------------------ P/T
    def unit_count(self, e, what) -> int:
        """The number of tokens of a closed unit multiset expression."""
        A = self.A
        if e is None:
            return 1
        if isinstance(e, A.Const) and e.kind == "unit":
            return 1
        # the type checker's 1`v, and (e : T) (a flattened net's expressions have no annotations)
        if isinstance(e, A.ToMs) or isinstance(e, getattr(A, "Annot", A.ToMs)):
            return self.unit_count(e.expr, what)
        if isinstance(e, A.Name) and e.name == "empty":
            return 0
        if isinstance(e, A.BinOp) and e.op == "`" and isinstance(e.left, A.Const) and e.left.kind == "int":
            return e.left.value * self.unit_count(e.right, what)
        if isinstance(e, A.BinOp) and e.op == "++":
            return self.unit_count(e.left, what) + self.unit_count(e.right, what)
        raise _Unsupported(f"{what} is not a constant number of tokens", e)

    def pt_net(self) -> str:
        pid, tid = self.node_ids()
        page = []
        for p in self.places:
            try:
                m = self.unit_count(p.init, f"the initial marking of place '{p.name}'") if p.init else 0
            except _Unsupported as exc:
                self.fail(exc.node or p, str(exc))
                m = 0
            mark = f"<initialMarking><text>{m}</text></initialMarking>" if m else ""
            page.append(f"<place id={quoteattr(pid[p.name])}><name><text>{escape(p.name)}</text></name>"
                        f"{mark}</place>")
        for t in self.transitions:
            page.append(f"<transition id={quoteattr(tid[t.name])}><name><text>{escape(t.name)}</text></name>"
                        f"</transition>")
        for k, (place, trans, direction, kind, expr, decl) in enumerate(self.arc_list()):
            src, dst = (pid[place], tid[trans]) if direction == "in" else (tid[trans], pid[place])
            w = 1
            if kind != "reset":
                try:
                    w = self.unit_count(expr, f"the inscription of the arc '{decl.src}' -> '{decl.dst}'")
                except _Unsupported as exc:
                    self.fail(exc.node or decl, str(exc))
            typ = f'<type value="{kind}"/>' if kind != "normal" else ""
            insc = f"<inscription><text>{w}</text></inscription>" if w != 1 and kind != "reset" else ""
            page.append(f'<arc id="a{k + 1}" source={quoteattr(src)} target={quoteattr(dst)}>{insc}{typ}</arc>')
        return self.document(PT_TYPE, page, [])

    # ------------------------------------------------------------------ symmetric nets
    def sort_xml(self, name: str, node) -> str:
        name, body = self.resolve(name)
        if body is None:
            raise _Unsupported(f"unknown colour set '{name}'", node)
        return f'<usersort declaration="{name}"/>'

    def colset_decl(self, name: str, body) -> str | None:
        A = self.A
        k = body.kind
        if k == "alias":
            return None
        if k == "unit":
            inner = "<dot/>"
        elif k == "bool":
            inner = "<bool/>"
        elif k == "enum":
            inner = "<cyclicenumeration>" + "".join(
                f'<feconstant id="{c}" name="{c}"/>' for c in body.names) + "</cyclicenumeration>"
        elif k == "int" and isinstance(body.low, A.Const) and isinstance(body.high, A.Const):
            inner = f'<finiteintrange start="{body.low.value}" end="{body.high.value}"/>'
        elif k == "product":
            inner = "<productsort>" + "".join(self.sort_xml(n, body) for n in body.names) + "</productsort>"
        else:
            raise _Unsupported(f"colour set '{name}' ({k}) has no PNML sort; PNML sorts are finite: unit, "
                               "bool, enumerations, int ranges and products", body)
        return f'<namedsort id="{name}" name="{name}">{inner}</namedsort>'

    def analyse_fun(self, d) -> None:
        """Recognise the helper functions `cpn.io.pnml` generates (successor, predecessor, order,
        partition element of), by what they compute, not by their names."""
        A = self.A
        if len(d.clauses) != 1 or len(d.clauses[0].params) != 1 or not isinstance(d.clauses[0].params[0], A.PVar):
            return
        arg = d.clauses[0].params[0].name
        body = d.clauses[0].body
        if isinstance(body, A.Case) and isinstance(body.subject, A.Name) and body.subject.name == arg:
            table = {}
            for pat, e in body.rules:
                if not isinstance(pat, A.PVar):
                    return
                if isinstance(e, A.Name):
                    table[pat.name] = e.name
                elif isinstance(e, A.Const) and e.kind == "int":
                    table[pat.name] = e.value
                else:
                    return
            cs = {self.consts.get(c) for c in table}
            if len(cs) != 1 or None in cs:
                return
            (cs,) = cs
            order = self.colsets[cs].names
            if set(table) != set(order):
                return
            n = len(order)
            if all(table[c] == i for i, c in enumerate(order)):
                self.funs[d.name] = ("ord", cs)
            elif all(table[c] == order[(i + 1) % n] for i, c in enumerate(order)):
                self.funs[d.name] = ("successor", cs)
            elif all(table[c] == order[(i - 1) % n] for i, c in enumerate(order)):
                self.funs[d.name] = ("predecessor", cs)
            return
        # int-range successor/predecessor: if c = hi then lo else c + 1 (or c = lo then hi else c - 1)
        if isinstance(body, A.If) and isinstance(body.else_, A.BinOp) and body.else_.op in ("+", "-") \
                and isinstance(body.else_.left, A.Name) and body.else_.left.name == arg \
                and isinstance(body.else_.right, A.Const) and body.else_.right.value == 1:
            self.funs[d.name] = ("successor" if body.else_.op == "+" else "predecessor", "")
        elif isinstance(body, A.Name) and body.name == arg:
            self.funs[d.name] = ("ord", "")

    def sn_net(self) -> str:
        decls = []
        for name, body in self.colsets.items():
            try:
                x = self.colset_decl(name, body)
            except _Unsupported as exc:
                self.fail(exc.node, str(exc))
                continue
            if x:
                decls.append(x)
        for v, cs in self.vars.items():
            try:
                decls.append(f'<variabledecl id="var_{v}" name="{v}">{self.sort_xml(cs, None)}</variabledecl>')
            except _Unsupported as exc:
                self.fail(exc.node, str(exc))
        pid, tid = self.node_ids()
        page = []
        sort_of_place = {}
        for p in self.places:
            try:
                cs, _body = self.resolve(p.colset)
                sort_of_place[p.name] = cs
                init = ""
                if p.init is not None:
                    init = f"<hlinitialMarking><structure>{self.ms(p.init, cs)}</structure></hlinitialMarking>"
                page.append(f"<place id={quoteattr(pid[p.name])}><name><text>{escape(p.name)}</text></name>"
                            f"<type><structure>{self.sort_xml(cs, p)}</structure></type>{init}</place>")
            except _Unsupported as exc:
                self.fail(exc.node or p, f"the initial marking of place '{p.name}': {exc}")
        for t in self.transitions:
            cond = ""
            try:
                if t.guards:
                    g = t.guards[0] if len(t.guards) == 1 else None
                    inner = self.boolean(g) if g is not None else \
                        "<and>" + "".join(f"<subterm>{self.boolean(x)}</subterm>" for x in t.guards) + "</and>"
                    cond = f"<condition><structure>{inner}</structure></condition>"
            except _Unsupported as exc:
                self.fail(exc.node or t, f"the guard of transition '{t.name}': {exc}")
            page.append(f"<transition id={quoteattr(tid[t.name])}><name><text>{escape(t.name)}</text></name>"
                        f"{cond}</transition>")
        for k, (place, trans, direction, kind, expr, decl) in enumerate(self.arc_list()):
            src, dst = (pid[place], tid[trans]) if direction == "in" else (tid[trans], pid[place])
            cs = sort_of_place.get(place)
            insc = ""
            try:
                if kind != "reset":
                    e = expr if expr is not None else self.A.Const(decl.span, (), "unit")
                    insc = f"<hlinscription><structure>{self.ms(e, cs)}</structure></hlinscription>"
            except _Unsupported as exc:
                self.fail(exc.node or decl, f"the inscription of the arc '{decl.src}' -> '{decl.dst}': {exc}")
            typ = f'<type value="{kind}"/>' if kind != "normal" else ""
            page.append(f'<arc id="a{k + 1}" source={quoteattr(src)} target={quoteattr(dst)}>{insc}{typ}</arc>')
        return self.document(SN_TYPE, page, decls)

    # ------------------------------------------------------------------ terms
    def ms(self, e, cs: str | None) -> str:
        """A multiset term of colour set `cs`."""
        A = self.A
        if isinstance(e, A.Annot):
            return self.ms(e.expr, cs)
        if isinstance(e, A.ToMs):  # the type checker's 1`v
            e = e.expr
        if isinstance(e, A.BinOp) and e.op == "++":
            parts = self.flatten(e, "++")
            return "<add>" + "".join(f"<subterm>{self.ms(p, cs)}</subterm>" for p in parts) + "</add>"
        if isinstance(e, A.BinOp) and e.op == "--":
            return f"<subtract><subterm>{self.ms(e.left, cs)}</subterm><subterm>{self.ms(e.right, cs)}</subterm></subtract>"
        if isinstance(e, A.BinOp) and e.op == "`":
            if not (isinstance(e.left, A.Const) and e.left.kind == "int"):
                raise _Unsupported("a multiplicity that is not a constant", e.left)
            inner = self.all_of(e.right) if self.all_of(e.right, check=True) else self.value(e.right, cs)
            return (f'<numberof><subterm><numberconstant value="{e.left.value}"><positive/></numberconstant>'
                    f"</subterm><subterm>{inner}</subterm></numberof>")
        if self.all_of(e, check=True):
            return self.all_of(e)
        if isinstance(e, A.Name) and e.name == "empty":
            if cs is None:
                raise _Unsupported("'empty' of an unknown colour set", e)
            return f"<empty>{self.sort_xml(cs, e)}</empty>"
        return (f'<numberof><subterm><numberconstant value="1"><positive/></numberconstant></subterm>'
                f"<subterm>{self.value(e, cs)}</subterm></numberof>")

    def all_of(self, e, check: bool = False):
        A = self.A
        ok = isinstance(e, A.App) and isinstance(e.fn, A.Name) and e.fn.name.endswith(".all") \
            and isinstance(e.arg, A.Const) and e.arg.kind == "unit"
        if check:
            return ok
        return f"<all>{self.sort_xml(e.fn.name[:-4], e)}</all>"

    def flatten(self, e, op: str) -> list:
        A = self.A
        if isinstance(e, A.BinOp) and e.op == op:
            return self.flatten(e.left, op) + self.flatten(e.right, op)
        return [e]

    def value(self, e, cs: str | None) -> str:
        """A single value of colour set `cs` (None when not known)."""
        A = self.A
        body = self.resolve(cs)[1] if cs else None
        if isinstance(e, A.Const):
            if e.kind == "unit":
                return "<dotconstant/>"
            if e.kind == "bool":
                return f'<booleanconstant value="{"true" if e.value else "false"}"/>'
            if e.kind == "int" and body is not None and body.kind == "int":
                return (f'<finiteintrangeconstant value="{e.value}"><finiteintrange start="{body.low.value}" '
                        f'end="{body.high.value}"/></finiteintrangeconstant>')
            raise _Unsupported(f"the constant {e.value!r} has no PNML form here", e)
        if isinstance(e, A.Name):
            if e.name in self.vars:
                return f'<variable refvariable="var_{e.name}"/>'
            if e.name in self.consts:
                return f'<useroperator declaration="{e.name}"/>'
            raise _Unsupported(f"'{e.name}' is neither a variable nor a constant of an enumeration", e)
        if isinstance(e, A.TupleE):
            comps = body.names if body is not None and body.kind == "product" else [None] * len(e.items)
            return "<tuple>" + "".join(f"<subterm>{self.value(x, c)}</subterm>"
                                       for x, c in zip(e.items, comps)) + "</tuple>"
        step = self.step(e)
        if step is not None:
            op, x = step
            return f"<{op}><subterm>{self.value(x, cs)}</subterm></{op}>"
        if isinstance(e, A.App) and isinstance(e.fn, A.Name) and e.fn.name in self.funs:
            op, fcs = self.funs[e.fn.name]
            if op in ("successor", "predecessor"):
                return f"<{op}><subterm>{self.value(e.arg, fcs or cs)}</subterm></{op}>"
        raise _Unsupported("an expression that PNML symmetric nets cannot express", e)

    def _csop(self, e, op: str):
        """The argument of `S.op arg` (and S) when e has that form, else None."""
        A = self.A
        if isinstance(e, A.App) and isinstance(e.fn, A.Name) and e.fn.name.endswith("." + op):
            return e.arg, e.fn.name[: -len(op) - 1]
        return None

    def step(self, e):
        """('successor' | 'predecessor', x) when e is how `cpn.io.pnml` writes successor/predecessor:
        `S.col ((S.ord x + k) mod n)` with k = 1 or n - 1, or, on an int range a..b,
        `if x = b then a else x + 1` / `if x = a then b else x - 1`."""
        A = self.A
        col = self._csop(e, "col")
        if col is not None:
            m = col[0]
            if isinstance(m, A.BinOp) and m.op == "mod" and isinstance(m.right, A.Const) \
                    and isinstance(m.left, A.BinOp) and m.left.op == "+" and isinstance(m.left.right, A.Const):
                inner = self._csop(m.left.left, "ord")
                n, k = m.right.value, m.left.right.value
                body = self.resolve(col[1])[1]
                if inner is not None and inner[1] == col[1] and body is not None and body.kind == "enum" \
                        and len(body.names) == n:
                    if n and k == 1 % n:
                        return "successor", inner[0]
                    if n and k == (n - 1) % n:
                        return "predecessor", inner[0]
            return None
        if isinstance(e, A.If) and isinstance(e.cond, A.BinOp) and e.cond.op == "=" \
                and isinstance(e.else_, A.BinOp) and e.else_.op in ("+", "-") \
                and isinstance(e.else_.right, A.Const) and e.else_.right.value == 1 \
                and isinstance(e.cond.left, A.Name) and isinstance(e.else_.left, A.Name) \
                and e.cond.left.name == e.else_.left.name:
            body = self.resolve(self.sort_of_value(e.cond.left) or "")[1]
            if body is None or body.kind != "int" or not all(
                    isinstance(x, A.Const) for x in (body.low, body.high, e.cond.right, e.then)):
                return None
            lo, hi = body.low.value, body.high.value
            if e.else_.op == "+" and (e.cond.right.value, e.then.value) == (hi, lo):
                return "successor", e.cond.left
            if e.else_.op == "-" and (e.cond.right.value, e.then.value) == (lo, hi):
                return "predecessor", e.cond.left
        return None

    def boolean(self, e) -> str:
        A = self.A
        if isinstance(e, A.BinOp) and e.op in ("andalso", "orelse"):
            tag = "and" if e.op == "andalso" else "or"
            return f"<{tag}>" + "".join(f"<subterm>{self.boolean(x)}</subterm>"
                                        for x in self.flatten(e, e.op)) + f"</{tag}>"
        if isinstance(e, A.App) and isinstance(e.fn, A.Name) and e.fn.name == "not":
            return f"<not><subterm>{self.boolean(e.arg)}</subterm></not>"
        if isinstance(e, A.Const) and e.kind == "bool":
            return f'<booleanconstant value="{"true" if e.value else "false"}"/>'
        if isinstance(e, A.BinOp) and e.op in _CMP:
            left, right = e.left, e.right
            ords = [isinstance(x, A.App) and isinstance(x.fn, A.Name) and self.funs.get(x.fn.name, ("",))[0] == "ord"
                    for x in (left, right)]
            if all(ords):
                left, right = left.arg, right.arg
            else:
                # S.ord x compared with S.ord y, or with a position k (the k-th constant of S)
                lo, ro = self._csop(left, "ord"), self._csop(right, "ord")
                if lo is not None and ro is not None:
                    left, right = lo[0], ro[0]
                elif lo is not None and self._position(right, lo[1]) is not None:
                    left, right = lo[0], self._position(right, lo[1])
                elif ro is not None and self._position(left, ro[1]) is not None:
                    left, right = self._position(left, ro[1]), ro[0]
            cs = self.sort_of_value(left) or self.sort_of_value(right)
            return (f"<{_CMP[e.op]}><subterm>{self.value(left, cs)}</subterm>"
                    f"<subterm>{self.value(right, cs)}</subterm></{_CMP[e.op]}>")
        raise _Unsupported("a guard that PNML symmetric nets cannot express", e)

    def _position(self, e, cs: str):
        """The constant at position e (an int literal) of enumeration cs, as a Name, or None."""
        A = self.A
        body = self.resolve(cs)[1]
        if isinstance(e, A.Const) and e.kind == "int" and body is not None and body.kind == "enum" \
                and 0 <= e.value < len(body.names):
            return A.Name(e.span, body.names[e.value])
        return None

    def sort_of_value(self, e) -> str | None:
        A = self.A
        if isinstance(e, A.Name):
            if e.name in self.vars:
                return self.resolve(self.vars[e.name])[0]
            if e.name in self.consts:
                return self.consts[e.name]
        if isinstance(e, A.App) and isinstance(e.arg, A.Name):
            return self.sort_of_value(e.arg)
        return None


class _FlatPTWriter:
    """A flattened net (`cpn.net.Net`) whose place instances all hold `unit` tokens, as a P/T net."""

    def __init__(self, net, net_id: str) -> None:
        self.net = net
        self.net_id = net_id
        self.diags: list[Diagnostic] = []

    def fail(self, span, message: str) -> None:
        self.diags.append(Diagnostic("E0502", message, span or Span(self.net.source_file or "<net>", 1, 1),
                                     hint="A net with modules is written as PNML only when its flattened form "
                                          "is a P/T net (every place of colour set unit, no guards)."))

    def run(self) -> str:
        net = self.net
        helper = _Writer.__new__(_Writer)  # only for unit_count and the document layout
        from cpn.expr import nodes as E

        helper.A, helper.net_id, helper.ids = E, self.net_id, set()
        pids, tids, page = {}, {}, []
        for p in net.places:
            if p.colour_set.kind != "unit" or p.timed:
                self.fail(p.span, f"place '{p.name}' has colour set {p.colour_set.name}, not unit")
                continue
            pids[p.index] = helper.xml_id(p.name)
            m = sum(p.initial.values())
            mark = f"<initialMarking><text>{m}</text></initialMarking>" if m else ""
            page.append(f"<place id={quoteattr(pids[p.index])}><name><text>{escape(p.name)}</text></name>"
                        f"{mark}</place>")
        k = 0
        arcs = []
        for t in net.transitions:
            if t.guards or t.delay is not None or t.priority is not None or t.free:
                self.fail(t.span, f"transition '{t.name}' has a guard, a delay, a priority or variables")
            tid = tids[t.index] = helper.xml_id(t.name)
            page.append(f"<transition id={quoteattr(tid)}><name><text>{escape(t.name)}</text></name></transition>")
            for a in t.arcs:
                if a.place not in pids:
                    continue
                w = 1
                if a.kind != "reset":
                    try:
                        w = helper.unit_count(a.expr, f"the inscription of the arc {a.label or t.name}")
                    except _Unsupported as exc:
                        self.fail(getattr(exc.node, "span", None) or a.span, str(exc))
                        continue
                pairs = {"in": [(pids[a.place], tid, "normal")], "out": [(tid, pids[a.place], "normal")],
                         "both": [(pids[a.place], tid, "normal"), (tid, pids[a.place], "normal")],
                         "inhibitor": [(pids[a.place], tid, "inhibitor")],
                         "reset": [(pids[a.place], tid, "reset")]}[a.kind]
                for src, dst, kind in pairs:
                    k += 1
                    typ = f'<type value="{kind}"/>' if kind != "normal" else ""
                    insc = f"<inscription><text>{w}</text></inscription>" if w != 1 and kind != "reset" else ""
                    arcs.append(f'<arc id="a{k}" source={quoteattr(src)} target={quoteattr(dst)}>{insc}{typ}</arc>')
        if self.diags:
            raise ModelError(self.diags)
        return helper.document(PT_TYPE, page + arcs, [])

