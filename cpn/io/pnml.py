"""PNML (ISO/IEC 15909-2) P/T nets and symmetric nets: translation into `.cpnet` text, and writing.

`translate(path)` reads a PNML file and returns `.cpnet` source (docs/language.md) that the one front end
parses, checks and lowers; `write(net, path)` writes a net whose colour sets fit PNML back out.
Unsupported constructs are all collected and raised as one `ModelError` (E0501 unreadable, E0502
unsupported), each with the line and column of its XML element. Nothing is ever `eval`ed.
Imports the stdlib, `cpn.diagnostics`, `cpn.errors` and `cpn.io._pnml_*` only.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field

from cpn.diagnostics import Diagnostic, Span
from cpn.errors import ModelError
from cpn.io._pnml_names import Namespace, NodeNames, quote_name
from cpn.io._pnml_sorts import Sort, int_text
from cpn.io._pnml_xml import Element, parse_xml

__all__ = ["translate", "translate_text", "translate_with_origins", "remap_error", "PnmlTranslation", "write",
           "write_text", "PT_NET", "SYMMETRIC_NET"]

PT_NET = "http://www.pnml.org/version-2009/grammar/ptnet"
SYMMETRIC_NET = "http://www.pnml.org/version-2009/grammar/symmetricnet"
_HL_NETS = ("symmetricnet", "highlevelnet", "pt-hlpng")

# The colour set of P/T places (and of PNML's `dot` sort when it is not declared by name).
DOT_COLSET = "DOT"


def translate(path: str | os.PathLike) -> str:
    """Translate the PNML file at `path` into `.cpnet` source text.

    Raises
    ------
    ModelError
        E0501 when the file cannot be read or is not PNML; E0502 for every construct that has no
        translation (all of them in one error, sorted by position).
    """
    path = os.fspath(path)
    try:
        with open(path, "rb") as fh:
            data = fh.read()
    except OSError as exc:
        raise ModelError([Diagnostic("E0501", f"cannot read the PNML file: {exc.strerror}", Span(path, 1, 1))]) \
            from None
    return translate_text(data, path)


def translate_text(data: bytes | str, filename: str = "<pnml>") -> str:
    """Translate PNML given as bytes or text; `filename` is used in diagnostics only."""
    return _translation(data, filename).text


@dataclass
class PnmlTranslation:
    """The `.cpnet` text of a PNML file and, per generated line, the PNML element it comes from."""

    path: str
    text: str
    origins: dict[int, Span]  # 1-based line of the generated text -> start tag of the PNML element

    def locate(self, line: int) -> Span | None:
        return self.origins.get(line)


def translate_with_origins(path: str | os.PathLike) -> PnmlTranslation:
    """Like `translate`, also giving the origin of every generated statement (for `remap_error`)."""
    path = os.fspath(path)
    try:
        with open(path, "rb") as fh:
            data = fh.read()
    except OSError as exc:
        raise ModelError([Diagnostic("E0501", f"cannot read the PNML file: {exc.strerror}", Span(path, 1, 1))]) \
            from None
    return _translation(data, path)


def remap_error(error: ModelError, translation: PnmlTranslation, generated_name: str | None = None) -> ModelError:
    """Point the diagnostics of a failed load of translated text at the PNML elements they come from.

    A diagnostic in the generated text (file `generated_name` or the PNML path) moves to the element's
    start tag and keeps the generated line in a note.
    """
    lines = translation.text.splitlines()
    out = []
    for d in error.diagnostics:
        s = d.span
        names = {translation.path} | ({generated_name} if generated_name else set())
        span = translation.locate(s.line) if s is not None and s.file in names else None
        if span is None:
            out.append(d)
            continue
        text = lines[s.line - 1].strip() if 0 < s.line <= len(lines) else ""
        note = f"in the translation of this PNML element, line {s.line}: {text[:100]}"
        out.append(Diagnostic(d.code, d.message, span, d.hint, list(d.notes) + [note], dict(d.params),
                              d.severity))
    sources = dict(error.sources)
    try:
        with open(translation.path, encoding="utf-8", errors="replace") as fh:
            sources[translation.path] = fh.read()
    except OSError:
        pass
    return type(error)(out, sources)


def _translation(data: bytes | str, filename: str) -> PnmlTranslation:
    if isinstance(data, str):
        data = data.encode("utf-8")
    root = parse_xml(data, filename)
    tr = _Translator(root, filename)
    text = tr.run()
    origins = {}
    for i, line in enumerate(text.splitlines(), 1):
        el = tr.origins.get(line)
        if el is not None:
            origins[i] = el.span(filename)
    return PnmlTranslation(filename, text, origins)


@dataclass
class _Term:
    """A translated PNML term: CPN ML text, whether it is a multiset, and its sort when known.

    `values` lists the (multiplicity, value text) pairs of a multiset made of `all` expansions, so that
    `numberof` and `tuple` can expand them further."""

    text: str
    is_ms: bool = False
    sort: Sort | None = None
    atomic: bool = True
    expansion: list[tuple[int, str]] | None = None

    def paren(self) -> str:
        return self.text if self.atomic else f"({self.text})"

    def as_ms(self) -> str:
        return self.text if self.is_ms else f"1`{self.paren()}"


@dataclass
class _Arc:
    src: str
    dst: str
    kind: str  # "arc", "inhibitor", "reset", "test"
    parts: list[str] = field(default_factory=list)
    weight: int = 0
    origin: Element | None = None


class _Translator:
    def __init__(self, root: Element, filename: str) -> None:
        self.root = root
        self.file = filename
        self.diags: list[Diagnostic] = []
        self.names = Namespace()
        self.nodes = NodeNames()
        self.sorts: dict[str, Sort] = {}  # namedsort / partition id -> sort
        self.sort_order: list[Sort] = []  # in declaration order (dependencies first)
        self.sort_els: dict[str, Element] = {}
        self.resolving: set[str] = set()
        self.consts: dict[str, tuple[str, Sort]] = {}  # feconstant / partitionelement id -> (ident, sort)
        self.vars: dict[str, tuple[str, Sort]] = {}
        self.anon: dict[str, Sort] = {}  # builtin sorts without a namedsort ("dot", "bool")
        self.origins: dict[str, Element] = {}  # generated statement -> the PNML element it comes from

    def line(self, text: str, origin: Element | None) -> str:
        """Record where a generated statement comes from (statements are unique lines) and return it."""
        if origin is not None:
            self.origins.setdefault(text.split("\n", 1)[0], origin)
        return text

    # ------------------------------------------------------------------ diagnostics
    def error(self, el: Element | None, message: str, hint: str | None = None, code: str = "E0502") -> None:
        span = el.span(self.file) if el is not None else Span(self.file, 1, 1)
        self.diags.append(Diagnostic(code, message, span, hint=hint))

    # ------------------------------------------------------------------ entry
    def run(self) -> str:
        root = self.root
        if root.tag != "pnml":
            self.error(root, f"expected a PNML document (root element 'pnml'), found '{root.tag}'",
                       hint="PNML files start with <pnml xmlns=\"http://www.pnml.org/version-2009/grammar/pnml\">.",
                       code="E0501")
            raise ModelError(self.diags)
        nets = root.findall("net")
        if not nets:
            self.error(root, "the PNML document contains no <net>", code="E0501")
            raise ModelError(self.diags)
        if len(nets) > 1:
            self.error(nets[1], f"the PNML document contains {len(nets)} nets; only one net per file is supported",
                       hint="Split the file so that each holds one <net>.")
        net = nets[0]
        net_type = net.get("type", "")
        kind = net_type.rstrip("/").rsplit("/", 1)[-1]
        if kind == "ptnet":
            text = self.pt_net(net)
        elif kind in _HL_NETS:
            text = self.symmetric_net(net)
        else:
            self.error(net, f"unsupported PNML net type '{net_type}'",
                       hint=f"Supported types are P/T nets ({PT_NET}) and symmetric nets ({SYMMETRIC_NET}).")
            text = ""
        if self.diags:
            raise ModelError(self.diags)
        return text

    # ------------------------------------------------------------------ structure common to both kinds
    def _name_of(self, el: Element) -> str | None:
        n = el.find("name", "text")
        return n.text if n is not None else None

    def collect_nodes(self, net: Element):
        """Places, transitions and arcs of every page; reference nodes resolved to what they refer to."""
        places: list[Element] = []
        transitions: list[Element] = []
        arcs: list[Element] = []
        refs: dict[str, tuple[str, Element]] = {}

        def walk(el: Element) -> None:
            for c in el.children:
                if c.tag == "page":
                    walk(c)
                elif c.tag == "place":
                    places.append(c)
                elif c.tag == "transition":
                    transitions.append(c)
                elif c.tag == "arc":
                    arcs.append(c)
                elif c.tag in ("referencePlace", "referenceTransition"):
                    refs[c.get("id", "")] = (c.get("ref", ""), c)

        walk(net)
        ids = {p.get("id"): "place" for p in places} | {t.get("id"): "transition" for t in transitions}

        def resolve(node_id: str, el: Element) -> str | None:
            seen = set()
            while node_id in refs and node_id not in seen:
                seen.add(node_id)
                node_id = refs[node_id][0]
            if node_id not in ids:
                return None
            return node_id

        return places, transitions, arcs, ids, resolve

    def node_table(self, places: list[Element], transitions: list[Element]) -> dict[str, str]:
        """PNML id -> quoted `.cpnet` name, unique across places and transitions."""
        table: dict[str, str] = {}
        for el in places + transitions:
            node_id = el.get("id")
            if not node_id:
                self.error(el, f"a <{el.tag}> has no id attribute", code="E0501")
                continue
            if node_id in table:
                self.error(el, f"the id '{node_id}' is used by two nodes", code="E0501")
                continue
            table[node_id] = quote_name(self.nodes.name(self._name_of(el), node_id))
        return table

    def arc_ends(self, arc: Element, ids, resolve, table) -> tuple[str, str, str] | None:
        """(source name, target name, 'in' or 'out') of an arc, or None after a diagnostic."""
        src, dst = arc.get("source", ""), arc.get("target", "")
        rs, rd = resolve(src, arc), resolve(dst, arc)
        aid = arc.get("id", "?")
        if rs is None or rd is None:
            missing = src if rs is None else dst
            self.error(arc, f"arc '{aid}' refers to '{missing}', which is not a place or transition of the net",
                       code="E0501")
            return None
        if ids[rs] == ids[rd]:
            self.error(arc, f"arc '{aid}' connects two {ids[rs]}s ('{src}' and '{dst}')", code="E0501")
            return None
        if rs not in table or rd not in table:
            return None
        direction = "in" if ids[rs] == "place" else "out"
        return table[rs], table[rd], direction

    def arc_kind(self, arc: Element) -> str:
        t = arc.find("type")
        if t is None:
            return "arc"
        value = (t.get("value") or t.text or "normal").strip().lower()
        if value in ("normal", ""):
            return "arc"
        if value in ("inhibitor", "reset"):
            return value
        if value in ("read", "test"):
            return "test"
        self.error(t, f"unsupported arc type '{value}' of arc '{arc.get('id', '?')}'",
                   hint="Supported arc types are normal, inhibitor, reset and read (test).")
        return "arc"

    def emit_arcs(self, merged: dict[tuple, _Arc], out: list[str], render) -> None:
        for (src, dst, kind), a in merged.items():
            if kind == "reset":
                out.append(self.line(f"reset {src} -> {dst};", a.origin))
                continue
            insc = render(a)
            if kind == "test":
                p, t = (src, dst)
                keyword, arrow = "arc", "<->"
            else:
                keyword, arrow, p, t = ("inhibitor" if kind == "inhibitor" else "arc"), "->", src, dst
            out.append(self.line(f"{keyword} {p} {arrow} {t}{' : ' + insc if insc else ''};", a.origin))

    # ------------------------------------------------------------------ P/T nets
    def pt_net(self, net: Element) -> str:
        places, transitions, arcs, ids, resolve = self.collect_nodes(net)
        table = self.node_table(places, transitions)
        out = [self.header(net, "P/T net"), f"colset {DOT_COLSET} = unit;", ""]
        self.names.taken.add(DOT_COLSET)
        for p in places:
            if p.get("id") not in table:
                continue
            m = self.pt_int(p, "initialMarking", 0, f"the initial marking of place '{p.get('id')}'")
            init = f" = {m}`()" if m else ""
            out.append(self.line(f"place {table[p.get('id')]} : {DOT_COLSET}{init};", p))
        out.append("")
        for t in transitions:
            if t.get("id") in table:
                out.append(self.line(f"trans {table[t.get('id')]};", t))
        out.append("")
        merged: dict[tuple, _Arc] = {}
        for a in arcs:
            ends = self.arc_ends(a, ids, resolve, table)
            kind = self.arc_kind(a)
            if ends is None:
                continue
            src, dst, direction = ends
            if direction == "out" and kind != "arc":
                self.error(a, f"arc '{a.get('id', '?')}' is a {kind} arc from a transition to a place",
                           hint="Inhibitor, reset and read arcs go from a place to a transition.", code="E0501")
                continue
            w = self.pt_int(a, "inscription", 1, f"the inscription of arc '{a.get('id', '?')}'")
            key = (src, dst, kind)
            merged.setdefault(key, _Arc(src, dst, kind, origin=a)).weight += w
        self.emit_arcs(merged, out, lambda arc: "" if arc.weight == 1 else f"{arc.weight}`()")
        return "\n".join(out) + "\n"

    def pt_int(self, el: Element, tag: str, default: int, what: str) -> int:
        lab = el.find(tag)
        if lab is None:
            return default
        txt = lab.find("text")
        raw = (txt.text if txt is not None else "").strip()
        if not raw:
            return default
        try:
            value = int(raw)
        except ValueError:
            self.error(txt or lab, f"{what} is '{raw}', not a number of tokens",
                       hint="P/T nets carry non-negative integers in <initialMarking> and <inscription>.",
                       code="E0501")
            return default
        if value < 0:
            self.error(txt or lab, f"{what} is negative ({value})", code="E0501")
            return default
        return value

    def header(self, net: Element, kind: str) -> str:
        name = self._name_of(net) or net.get("id") or ""
        base = os.path.basename(self.file)
        name = name.replace("*)", "* )").replace("(*", "( *")
        return f"(* {kind} '{name}', translated from PNML ({base}) by cpn-verify *)"

    # ------------------------------------------------------------------ symmetric nets: declarations
    def symmetric_net(self, net: Element) -> str:
        decls = [d for dec in net.findall("declaration") for s in dec.findall("structure")
                 for d in s.findall("declarations")]
        sort_decls: list[Element] = []
        for d in decls:
            for el in d.elements():
                if el.tag in ("namedsort", "partition"):
                    if el.get("id"):
                        self.sort_els[el.get("id")] = el
                    sort_decls.append(el)
                elif el.tag == "variabledecl":
                    pass
                else:
                    self.error(el, f"unsupported PNML declaration '{el.tag}'",
                               hint="Supported declarations are namedsort, partition and variabledecl.")
        for el in sort_decls:
            self.resolve_sort(el.get("id", ""), el)
        for d in decls:
            for el in d.findall("variabledecl"):
                sort = self.sort_of(el.elements()[0] if el.elements() else None, el)
                if sort is not None:
                    self.vars[el.get("id", "")] = (self.names.ident(el.get("name"), el.get("id")), sort)

        places, transitions, arcs, ids, resolve = self.collect_nodes(net)
        table = self.node_table(places, transitions)
        place_sort: dict[str, Sort] = {}
        body: list[str] = []
        for p in places:
            pid = p.get("id", "")
            if pid not in table:
                continue
            ty = p.find("type", "structure")
            sort = None
            if ty is None or not ty.elements():
                self.error(p, f"place '{pid}' has no type", hint="Give the place a <type> with a sort.")
            else:
                sort = self.sort_of(ty.elements()[0], p)
            if sort is None:
                continue
            place_sort[pid] = sort
            init = ""
            m = p.find("hlinitialMarking", "structure")
            if m is not None and m.elements():
                term = self.term(m.elements()[0], f"the initial marking of place '{pid}'", sort)
                init = " = " + term.as_ms()
            body.append(self.line(f"place {table[pid]} : {sort.name}{init};", p))
        body.append("")
        for t in transitions:
            tid = t.get("id", "")
            if tid not in table:
                continue
            guard = ""
            c = t.find("condition", "structure")
            if c is not None and c.elements():
                g = self.term(c.elements()[0], f"the guard of transition '{tid}'")
                if g.text != "true":
                    guard = f" [{g.text}]"
            body.append(self.line(f"trans {table[tid]}{guard};", t))
        body.append("")
        merged: dict[tuple, _Arc] = {}
        for a in arcs:
            ends = self.arc_ends(a, ids, resolve, table)
            kind = self.arc_kind(a)
            if ends is None:
                continue
            src, dst, direction = ends
            aid = a.get("id", "?")
            pid = resolve(a.get("source") if direction == "in" else a.get("target"), a)
            sort = place_sort.get(pid)
            ins = a.find("hlinscription", "structure")
            if kind == "reset":
                text = ""
            elif ins is not None and ins.elements():
                text = self.term(ins.elements()[0], f"the inscription of arc '{aid}'", sort).as_ms()
            elif sort is not None and sort.kind == "dot":
                text = "1`()"
            else:
                self.error(a, f"arc '{aid}' has no inscription and its place is not of sort dot",
                           hint="Give the arc an <hlinscription>.", code="E0501")
                continue
            arc = merged.setdefault((src, dst, kind), _Arc(src, dst, kind, origin=a))
            if text:
                arc.parts.append(text)
        self.emit_arcs(merged, body, lambda arc: " ++ ".join(arc.parts))

        out = [self.header(net, "symmetric net")]
        out += [self.line(s.declaration(), s.origin) for s in self.sort_order]
        by_sort: dict[str, list[str]] = {}
        for ident, sort in self.vars.values():
            by_sort.setdefault(sort.name, []).append(ident)
        out += [f"var {', '.join(vs)} : {s};" for s, vs in by_sort.items()]
        if any(s.helpers for s in self.sort_order):
            arg = self.names.ident("c'")
            for s in self.sort_order:
                out += s.helper_declarations(arg)
        out.append("")
        return "\n".join(out + body) + "\n"

    def new_sort(self, kind: str, *names: str | None, origin: Element | None = None, **kw) -> Sort:
        sort = Sort(kind, self.names.ident(*names), origin=origin, **kw)
        self.sort_order.append(sort)
        return sort

    def resolve_sort(self, sid: str, el: Element) -> Sort | None:
        if sid in self.sorts:
            return self.sorts[sid]
        if sid in self.resolving:
            self.error(el, f"sort '{sid}' is defined in terms of itself", code="E0501")
            return None
        self.resolving.add(sid)
        try:
            if el.tag == "partition":
                return self.partition(sid, el)
            inner = el.elements()
            if not inner:
                self.error(el, f"sort '{sid}' has no definition", code="E0501")
                return None
            d = inner[0]
            name = el.get("name")
            if d.tag == "usersort":
                # an alias: the same colour set under a second name
                target = self.sort_of(d, el)
                if target is not None:
                    self.sorts[sid] = target
                return target
            sort = self.define(d, sid, name)
            if sort is not None:
                self.sorts[sid] = sort
            return sort
        finally:
            self.resolving.discard(sid)

    def define(self, d: Element, sid: str, name: str | None) -> Sort | None:
        """The colour set for sort definition `d` (named `name` when given)."""
        tag = d.tag
        if tag == "dot":
            return self.new_sort("dot", name, sid, "Dot", origin=d)
        if tag == "bool":
            return self.new_sort("bool", name, sid, "Bool", origin=d)
        if tag in ("cyclicenumeration", "finiteenumeration"):
            fcs = d.findall("feconstant")
            if not fcs:
                self.error(d, f"the enumeration of sort '{sid}' has no constants", code="E0501")
                return None
            sort = self.new_sort("enum", name, sid, "Enum", origin=d, cyclic=(tag == "cyclicenumeration"))
            for fc in fcs:
                ident = self.names.ident(fc.get("name"), fc.get("id"), f"{sort.name}_{fc.get('name')}")
                sort.consts.append(ident)
                self.consts[fc.get("id", "")] = (ident, sort)
            return sort
        if tag == "finiteintrange":
            try:
                lo, hi = int(d.get("start", "")), int(d.get("end", ""))
            except ValueError:
                self.error(d, f"finiteintrange of sort '{sid}' needs integer start and end attributes",
                           code="E0501")
                return None
            if lo > hi:
                self.error(d, f"finiteintrange of sort '{sid}' is empty ({lo}..{hi})", code="E0501")
                return None
            return self.new_sort("range", name, sid, "Range", origin=d, lo=lo, hi=hi)
        if tag == "productsort":
            parts = [self.sort_of(c, d) for c in d.elements()]
            if any(p is None for p in parts):
                return None
            if len(parts) < 2:
                if len(parts) == 1:
                    return parts[0]
                self.error(d, f"productsort of sort '{sid}' has no components", code="E0501")
                return None
            return self.new_sort("product", name, sid, "Product", origin=d, parts=parts)
        self.error(d, f"unsupported PNML sort '{tag}' in the declaration of sort '{sid}'",
                   hint="Supported sorts are dot, bool, cyclicenumeration, finiteenumeration, finiteintrange, "
                        "productsort and partition.")
        return None

    def partition(self, sid: str, el: Element) -> Sort | None:
        base_el = el.find("usersort")
        base = self.sort_of(base_el, el) if base_el is not None else None
        if base is None or base.kind != "enum":
            if base is not None:
                self.error(el, f"partition '{sid}' partitions a sort that is not an enumeration")
            else:
                self.error(el, f"partition '{sid}' does not name the sort it partitions", code="E0501")
            return None
        sort = self.new_sort("enum", el.get("name"), sid, "Partition", origin=el)
        sort.base = base
        for pe in el.findall("partitionelement"):
            ident = self.names.ident(pe.get("name"), pe.get("id"))
            sort.consts.append(ident)
            self.consts[pe.get("id", "")] = (ident, sort)
            for u in pe.findall("useroperator"):
                c = self.consts.get(u.get("declaration", ""))
                if c is None or c[1] is not base:
                    self.error(u, f"partition element '{pe.get('id')}' lists '{u.get('declaration')}', "
                                  f"which is not a constant of the partitioned sort", code="E0501")
                else:
                    sort.element_of[c[0]] = ident
        missing = [c for c in base.consts if c not in sort.element_of]
        if missing:
            self.error(el, f"partition '{sid}' does not place constant(s) {', '.join(missing)} in any element",
                       code="E0501")
            return None
        self.sorts[sid] = sort
        return sort

    def sort_of(self, el: Element | None, owner: Element) -> Sort | None:
        """The sort denoted by a `usersort` reference or an inline built-in sort."""
        if el is None:
            self.error(owner, f"<{owner.tag}> '{owner.get('id', '?')}' names no sort", code="E0501")
            return None
        if el.tag == "usersort":
            ref = el.get("declaration", "")
            if ref in self.sorts:
                return self.sorts[ref]
            if ref in self.sort_els:
                return self.resolve_sort(ref, self.sort_els[ref])
            self.error(el, f"unknown sort '{ref}'", hint="Declare it with a <namedsort> in the net's <declaration>.",
                       code="E0501")
            return None
        if el.tag in ("dot", "bool"):
            # an inline dot or bool is the declared one when there is one: no duplicate colour sets
            if el.tag not in self.anon:
                same = next((s for s in self.sort_order if s.kind == el.tag), None)
                self.anon[el.tag] = same or self.define(el, el.tag, DOT_COLSET if el.tag == "dot" else "BOOL")
            return self.anon[el.tag]
        if el.tag == "finiteintrange":
            try:
                lo, hi = int(el.get("start", "")), int(el.get("end", ""))
            except ValueError:
                lo = hi = None
            same = next((s for s in self.sort_order if s.kind == "range" and (s.lo, s.hi) == (lo, hi)), None)
            if same is not None:
                return same
        return self.define(el, f"{owner.get('id', owner.tag)}_sort", None)

    # ------------------------------------------------------------------ symmetric nets: terms
    def term(self, el: Element, where: str, expect: Sort | None = None) -> _Term:
        """Translate a PNML term; unsupported operators are reported and replaced by a placeholder."""
        handler = getattr(self, "t_" + el.tag, None)
        if handler is None:
            self.error(el, f"unsupported PNML operator '{el.tag}' in {where}",
                       hint="docs/pnml.md lists the operators that cpn-verify translates.")
            return _Term("()")
        return handler(el, where, expect)

    def subterms(self, el: Element, where: str, expect: Sort | None = None) -> list[_Term]:
        out = []
        for s in el.elements():
            inner = s.elements() if s.tag == "subterm" else [s]
            if s.tag not in ("subterm",) and s.tag in ("usersort",):
                continue
            if inner:
                out.append(self.term(inner[0], where, expect))
        return out

    def _arity(self, el: Element, terms: list[_Term], n: int, where: str) -> bool:
        if len(terms) != n:
            self.error(el, f"'{el.tag}' in {where} has {len(terms)} operands, expected {n}", code="E0501")
            return False
        return True

    def t_variable(self, el, where, expect):
        ref = el.get("refvariable", "")
        if ref not in self.vars:
            self.error(el, f"unknown variable '{ref}' in {where}", code="E0501")
            return _Term("()")
        ident, sort = self.vars[ref]
        return _Term(ident, sort=sort)

    def t_useroperator(self, el, where, expect):
        ref = el.get("declaration", "")
        if ref not in self.consts:
            self.error(el, f"unknown constant '{ref}' in {where}",
                       hint="Only constants (feconstant, partitionelement) can be used as user operators.",
                       code="E0501")
            return _Term("()")
        ident, sort = self.consts[ref]
        return _Term(ident, sort=sort)

    def t_dotconstant(self, el, where, expect):
        return _Term("()", sort=self.sort_of(Element("dot", {}, el.line, el.col), el))

    def t_booleanconstant(self, el, where, expect):
        v = (el.get("value") or "").lower()
        if v not in ("true", "false"):
            self.error(el, f"booleanconstant in {where} has value '{v}'", code="E0501")
        return _Term("true" if v == "true" else "false", sort=self.sort_of(Element("bool", {}, el.line, el.col), el))

    def t_numberconstant(self, el, where, expect):
        try:
            n = int(el.get("value", ""))
        except ValueError:
            self.error(el, f"numberconstant in {where} has no integer value", code="E0501")
            n = 0
        return _Term(int_text(n), atomic=n >= 0)

    def t_finiteintrangeconstant(self, el, where, expect):
        term = self.t_numberconstant(el, where, expect)
        r = el.find("finiteintrange")
        if expect is not None and expect.kind == "range":
            term.sort = expect
        elif r is not None:
            term.sort = self.sort_of(r, el)
        return term

    def t_all(self, el, where, expect):
        sort_el = next(iter(el.elements()), None)
        sort = self.sort_of(sort_el, el) if sort_el is not None else None
        if sort is None:
            return _Term("empty", is_ms=True)
        return _Term(f"{sort.name}.all()", is_ms=True, sort=sort, expansion=[(1, v) for v in sort.values()])

    def t_numberof(self, el, where, expect):
        terms = self.subterms(el, where, expect)
        if not self._arity(el, terms, 2, where):
            return _Term("empty", is_ms=True)
        count, what = terms
        try:
            n = int(count.text.replace("~", "-"))
        except ValueError:
            self.error(el, f"the multiplicity of 'numberof' in {where} is not a constant", code="E0502")
            return _Term("empty", is_ms=True)
        if n < 0:
            self.error(el, f"the multiplicity of 'numberof' in {where} is negative", code="E0501")
            return _Term("empty", is_ms=True)
        if n == 0:
            return _Term("empty", is_ms=True, atomic=True)
        if not what.is_ms:
            return _Term(f"{n}`{what.paren()}", is_ms=True, sort=what.sort, atomic=False,
                         expansion=[(n, what.text)])
        if n == 1:
            return what
        if what.expansion is None:
            self.error(el, f"'numberof' in {where} multiplies a multiset that is not built from 'all'")
            return what
        exp = [(n * k, v) for k, v in what.expansion]
        return _Term(_ms_text(exp), is_ms=True, sort=what.sort, atomic=False, expansion=exp)

    def t_tuple(self, el, where, expect):
        comp = expect.parts if expect is not None and expect.kind == "product" else []
        terms = []
        for i, s in enumerate(el.elements()):
            inner = s.elements() if s.tag == "subterm" else [s]
            if inner:
                terms.append(self.term(inner[0], where, comp[i] if i < len(comp) else None))
        if len(terms) < 2:
            self.error(el, f"a tuple in {where} has {len(terms)} component(s)", code="E0501")
            return terms[0] if terms else _Term("()")
        if not any(t.is_ms for t in terms):
            return _Term("(" + ", ".join(t.text for t in terms) + ")", sort=expect)
        # a tuple with 'all' components is the multiset of every tuple it stands for
        choices: list[list[tuple[int, str]]] = []
        for t in terms:
            if t.is_ms:
                if t.expansion is None:
                    self.error(el, f"a tuple in {where} has a multiset component that is not 'all'")
                    return _Term("empty", is_ms=True)
                choices.append(t.expansion)
            else:
                choices.append([(1, t.text)])
        exp: list[tuple[int, str]] = [(1, "")]
        for ch in choices:
            exp = [(k1 * k2, f"{v1}, {v2}" if v1 else v2) for k1, v1 in exp for k2, v2 in ch]
        exp = [(k, f"({v})") for k, v in exp]
        return _Term(_ms_text(exp), is_ms=True, sort=expect, atomic=False, expansion=exp)

    def t_add(self, el, where, expect):
        terms = self.subterms(el, where, expect)
        if not terms:
            return _Term("empty", is_ms=True)
        if len(terms) == 1:
            return terms[0]
        exp = None
        if all(t.expansion is not None for t in terms):
            exp = [kv for t in terms for kv in t.expansion]
        return _Term(" ++ ".join(t.as_ms() for t in terms), is_ms=True, sort=expect, atomic=False, expansion=exp)

    def t_subtract(self, el, where, expect):
        terms = self.subterms(el, where, expect)
        if len(terms) < 2:
            self._arity(el, terms, 2, where)
            return terms[0] if terms else _Term("empty", is_ms=True)
        parts = [terms[0].as_ms()]
        parts += [f"({t.as_ms()})" if (" ++ " in t.text or " -- " in t.text) else t.as_ms() for t in terms[1:]]
        text = " -- ".join(parts)
        return _Term(text, is_ms=True, sort=expect, atomic=False)

    def _step(self, el, where, op):
        terms = self.subterms(el, where)
        if not self._arity(el, terms, 1, where):
            return _Term("()")
        t = terms[0]
        if t.sort is None or t.sort.kind not in ("enum", "range", "bool"):
            self.error(el, f"'{el.tag}' in {where} is applied to a value whose sort is not an enumeration or range")
            return t
        text = t.sort.succ(t.paren()) if op == "succ" else t.sort.pred(t.paren())
        return _Term(text, sort=t.sort, atomic=text.startswith("("))

    def t_successor(self, el, where, expect):
        return self._step(el, where, "succ")

    def t_predecessor(self, el, where, expect):
        return self._step(el, where, "pred")

    def _compare(self, el, where, op, ordered):
        terms = self.subterms(el, where)
        if not self._arity(el, terms, 2, where):
            return _Term("false")
        a, b = terms
        sort = a.sort or b.sort
        if ordered and sort is not None and sort.kind in ("enum", "bool"):
            return _Term(f"{sort.ord(a.paren())} {op} {sort.ord(b.paren())}", atomic=False)
        if ordered and (sort is None or sort.kind not in ("range",)):
            if sort is None and not (a.text.lstrip("~").isdigit() and b.text.lstrip("~").isdigit()):
                self.error(el, f"'{el.tag}' in {where} compares values whose sort is unknown")
            elif sort is not None:
                self.error(el, f"'{el.tag}' in {where} compares values of sort '{sort.name}', which has no order")
        return _Term(f"{a.paren()} {op} {b.paren()}", atomic=False)

    def t_equality(self, el, where, expect):
        return self._compare(el, where, "=", False)

    def t_inequality(self, el, where, expect):
        return self._compare(el, where, "<>", False)

    def t_lessthan(self, el, where, expect):
        return self._compare(el, where, "<", True)

    def t_lessthanorequal(self, el, where, expect):
        return self._compare(el, where, "<=", True)

    def t_greaterthan(self, el, where, expect):
        return self._compare(el, where, ">", True)

    def t_greaterthanorequal(self, el, where, expect):
        return self._compare(el, where, ">=", True)

    # integer operators of finite int ranges (ISO 15909-2 'integers')
    t_lt, t_leq, t_gt, t_geq = t_lessthan, t_lessthanorequal, t_greaterthan, t_greaterthanorequal

    def _arith(self, el, where, op):
        terms = self.subterms(el, where)
        if not self._arity(el, terms, 2, where):
            return _Term("0")
        a, b = terms
        return _Term(f"{a.paren()} {op} {b.paren()}", sort=a.sort or b.sort, atomic=False)

    def t_addition(self, el, where, expect):
        return self._arith(el, where, "+")

    def t_subtraction(self, el, where, expect):
        return self._arith(el, where, "-")

    def t_mult(self, el, where, expect):
        return self._arith(el, where, "*")

    def t_div(self, el, where, expect):
        return self._arith(el, where, "div")

    def t_mod(self, el, where, expect):
        return self._arith(el, where, "mod")

    def _logic(self, el, where, op):
        # and/or are associative: nested ones of the same kind become one chain
        flat: list[Element] = []

        def collect(node: Element) -> None:
            for s in node.elements():
                inner = s.elements() if s.tag == "subterm" else [s]
                if inner and inner[0].tag == node.tag:
                    collect(inner[0])
                elif inner:
                    flat.append(inner[0])

        collect(el)
        terms = [self.term(x, where) for x in flat]
        if not terms:
            return _Term("true" if op == "andalso" else "false")
        if len(terms) == 1:
            return terms[0]
        return _Term(f" {op} ".join(t.paren() for t in terms), atomic=False)

    def t_and(self, el, where, expect):
        return self._logic(el, where, "andalso")

    def t_or(self, el, where, expect):
        return self._logic(el, where, "orelse")

    def t_not(self, el, where, expect):
        terms = self.subterms(el, where)
        if not self._arity(el, terms, 1, where):
            return _Term("false")
        return _Term(f"not {terms[0].paren()}", atomic=False)

    def t_imply(self, el, where, expect):
        terms = self.subterms(el, where)
        if not self._arity(el, terms, 2, where):
            return _Term("true")
        return _Term(f"not {terms[0].paren()} orelse {terms[1].paren()}", atomic=False)

    def t_partitionelementof(self, el, where, expect):
        ref = el.get("refpartition", "")
        part = self.sorts.get(ref)
        if part is None and ref in self.sort_els:
            part = self.resolve_sort(ref, self.sort_els[ref])
        terms = self.subterms(el, where)
        if part is None or part.base is None:
            self.error(el, f"unknown partition '{ref}' in {where}", code="E0501")
            return _Term("()")
        if not self._arity(el, terms, 1, where):
            return _Term("()")
        return _Term(f"{part.helper('of', self.names)} {terms[0].paren()}", sort=part, atomic=False)


def _ms_text(exp: list[tuple[int, str]]) -> str:
    return " ++ ".join(f"{k}`{v}" for k, v in exp if k) or "empty"


# ---------------------------------------------------------------------- writing
from cpn.io._pnml_write import write, write_text  # noqa: E402  (the writer shares nothing above)
