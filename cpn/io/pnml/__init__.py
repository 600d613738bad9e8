"""PNML (ISO/IEC 15909-2) P/T nets and symmetric nets: translation into `.cpnet` text, and writing.

`translate(path)` reads a PNML file and returns `.cpnet` source (docs/language.md) that the one front end
parses, checks and lowers; `write(net, path)` writes a net whose colour sets fit PNML back out.
Unsupported constructs are all collected and raised as one `ModelError` (E0501 unreadable, E0502
unsupported), each with the line and column of its XML element. Nothing is ever `eval`ed.
Imports the stdlib, `cpn.diagnostics`, `cpn.errors` and `cpn.io.pnml._*` only.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field

from cpn.diagnostics import Diagnostic, Span
from cpn.errors import ModelError
from cpn.io.pnml._names import Namespace, NodeNames, quote_name
from cpn.io.pnml._sorts import Sort
from cpn.io.pnml._terms import TermTranslator
from cpn.io.pnml._xml import Element, parse_xml

__all__ = ["translate", "translate_file", "translate_text", "translate_with_origins", "remap_error",
           "PnmlTranslation", "write", "write_text", "PT_NET", "SYMMETRIC_NET"]

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
    return translate_with_origins(path).text


def translate_text(data: bytes | str, filename: str = "<pnml>") -> str:
    """Translate PNML given as bytes or text; `filename` is used in diagnostics only."""
    return _translation(data, filename).text


@dataclass
class PnmlTranslation:
    """The `.cpnet` text of a PNML file and, per generated line, the PNML element it comes from."""

    path: str
    text: str
    origins: dict[int, Span]  # 1-based line of the generated text -> start tag of the PNML element
    notes: list[str] = field(default_factory=list)
    node_names: dict[str, str] = field(default_factory=dict)  # PNML id of a place or transition -> its name

    def locate(self, line: int) -> Span | None:
        return self.origins.get(line)

    def origin(self, line: int, col: int = 1) -> Span | None:
        """The start tag of the PNML element that line `line` of the text translates (`cpn.io.Translation`)."""
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


def translate_file(path: str | os.PathLike) -> PnmlTranslation:
    """The registry's entry (`cpn.io.importer_for`): `translate_with_origins`."""
    return translate_with_origins(path)


def remap_error(error: ModelError, translation: PnmlTranslation, generated_name: str | None = None,
                keep_generated_span: bool = False) -> ModelError:
    """Point the diagnostics of a failed load of translated text at the PNML elements they come from.

    A diagnostic in the generated text (file `generated_name` or the PNML path) moves to the element's
    start tag and keeps the generated line in a note; with `keep_generated_span` (the text is on disk,
    `cpn-verify convert`) it stays in the text and the note names the element's position.
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
        if keep_generated_span:
            note = f"from the PNML element at {span}"
            span = s
        else:
            text = lines[s.line - 1].strip() if 0 < s.line <= len(lines) else ""
            note = f"in the translation of this PNML element, line {s.line}: {text[:100]}"
        out.append(Diagnostic(d.code, d.message, span, d.hint, list(d.notes) + [note], dict(d.params),
                              d.severity))
    sources = dict(error.sources)
    if keep_generated_span:
        return type(error)(out, sources)
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
    return PnmlTranslation(filename, text, origins, node_names=dict(tr.node_names))


@dataclass
class _Arc:
    src: str
    dst: str
    kind: str  # "arc", "inhibitor", "reset", "test"
    parts: list[str] = field(default_factory=list)
    weight: int = 0
    origin: Element | None = None


class _Translator(TermTranslator):
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
        self.var_els: dict[str, Element] = {}  # colour set -> its first variabledecl
        self.node_names: dict[str, str] = {}  # PNML id -> the name of the place or transition

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
        if kind == "ptnet" and not self.has_colours(net):
            text = self.pt_net(net)
        elif kind == "ptnet":
            # TAPAAL writes coloured nets with the P/T type and sort declarations: read what is there
            text = self.symmetric_net(net)
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
            self.node_names[node_id] = self.nodes.name(self._name_of(el), node_id)
            table[node_id] = quote_name(self.node_names[node_id])
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

    @staticmethod
    def has_colours(net: Element) -> bool:
        """Whether a net declared as P/T carries sorts or high-level labels (TAPAAL's coloured nets)."""
        if any(d.find("structure", "declarations") is not None for d in net.findall("declaration")):
            return True
        return any(el.tag in ("hlinitialMarking", "hlinscription") for el in net.iter())

    def arc_kind(self, arc: Element) -> str:
        t = arc.find("type")
        if t is None:
            attr = arc.get("type")  # TAPAAL: <arc type="inhibitor">
            if attr is None:
                return "arc"
            t = Element("type", {"value": attr}, arc.line, arc.col)
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
                    self.var_els.setdefault(sort.name, el)

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
            self.text_only(p, "hlinitialMarking", f"the initial marking of place '{pid}'")
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
            self.text_only(t, "condition", f"the guard of transition '{tid}'")
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
            if self.text_only(a, "hlinscription", f"the inscription of arc '{aid}'"):
                continue
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
        out += [self.line(f"var {', '.join(vs)} : {s};", self.var_els.get(s)) for s, vs in by_sort.items()]
        if any(s.helpers for s in self.sort_order):
            arg = self.names.ident("c'")
            for s in self.sort_order:
                out += s.helper_declarations(arg)
        out.append("")
        return "\n".join(out + body) + "\n"

    def text_only(self, el: Element, label: str, what: str) -> bool:
        """Report a label given only as <text> (the term must be in <structure>); True if reported."""
        lab = el.find(label)
        if lab is None or (lab.find("structure") is not None and lab.find("structure").elements()):
            return False
        txt = lab.find("text")
        if txt is None or not txt.text:
            return False
        self.error(lab, f"{what} is given only as text ('{txt.text[:60]}'), without a <structure>",
                   hint="Symmetric nets carry terms as XML in <structure>; the <text> is only a comment.")
        return True

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


# ---------------------------------------------------------------------- writing
from cpn.io.pnml._write import write, write_text  # noqa: E402  (the writer shares nothing above)
