"""Translate CPN Tools `.cpn` files (XML, DTD formats 5 and 6) into `.cpnet` source text.

CPN Tools' declarations and inscriptions are CPN ML already, so the translation restructures the XML:
globbox declarations (blocks flattened), pages to modules, the root page to the top level, substitution
transitions to `instance` statements, fusion sets, ports, arcs of every orientation. Whatever cannot
have a deterministic state space (random distributions, `@++` real delays, code segments with side
effects, synchronous channels, assigned reference variables) is refused with a positioned E0502.
Every generated statement carries a comment with its origin, and `Translation.locate` maps a position
of the generated text back to the XML. Imports `cpn.diagnostics`, `cpn.errors` and the standard library.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field

from cpn.diagnostics import Diagnostic, Span
from cpn.errors import ModelError
from cpn.io import _cpntools_ml as ml
from cpn.io._cpntools_xml import Element, parse_xml

__all__ = ["Translation", "translate", "translate_file", "translate_text", "remap_error"]

# CPN Tools' standard priorities (declared in the "Standard priorities" block of a new net).
STANDARD_PRIORITIES = {"P_HIGH": "100", "P_NORMAL": "1000", "P_LOW": "10000"}
PORT_KINDS = {"in": "in", "out": "out", "i/o": "io", "io": "io", "inout": "io", "general": "io"}


@dataclass(frozen=True, slots=True)
class Origin:
    """Where a piece of generated text comes from in the `.cpn` file."""

    line: int
    col: int
    element: str  # XML id, e.g. "ID1234"
    page: str | None  # page name, None for the globbox
    what: str  # e.g. "arc inscription of 'Send Packet'"

    def describe(self) -> str:
        where = f" on page '{self.page}'" if self.page else ""
        return f"{self.what} ({self.element}{where}) at line {self.line}"


@dataclass(slots=True)
class _Piece:
    gen_line: int  # first line in the generated text (1-based)
    gen_col: int  # column where the piece starts
    n_lines: int
    origin: Origin
    exact: bool  # True if the piece is the verbatim text of the XML element


@dataclass(slots=True)
class Translation:
    """The `.cpnet` text of a `.cpn` file and the origin of every generated statement."""

    path: str
    text: str
    pieces: list[_Piece] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)

    def locate(self, line: int, col: int = 1) -> tuple[Span, Origin] | None:
        """Map a (line, col) of the generated text to a span in the `.cpn` file and the element's origin."""
        best = None
        for p in self.pieces:
            if p.gen_line <= line < p.gen_line + p.n_lines:
                if line == p.gen_line and col < p.gen_col and not p.exact:
                    continue
                if best is None or (p.exact and not best.exact) or p.gen_line > best.gen_line:
                    best = p
        if best is None:
            return None
        o = best.origin
        if best.exact:
            dl = line - best.gen_line
            c = o.col + max(col - best.gen_col, 0) if dl == 0 else col
            return Span(self.path, o.line + dl, c), o
        return Span(self.path, o.line, o.col), o


class _Out:
    """The generated text, line by line, with the origin of every piece."""

    def __init__(self) -> None:
        self.lines: list[str] = []
        self.pieces: list[_Piece] = []

    @property
    def next_line(self) -> int:
        return len(self.lines) + 1

    def raw(self, text: str = "") -> None:
        self.lines.extend(text.split("\n"))

    def stmt(self, parts: list[tuple[str, Origin | None]], origin: Origin, indent: str = "") -> None:
        """Write one statement made of parts; a part with an Origin is verbatim text of that element."""
        line = self.next_line
        self.pieces.append(_Piece(line, 1, 1, origin, False))
        buf = indent
        cur_line = line
        for text, porigin in parts:
            if porigin is not None:
                col = len(buf.rsplit("\n", 1)[-1]) + 1
                n = text.count("\n") + 1
                self.pieces.append(_Piece(cur_line, col, n, porigin, True))
            buf += text
            cur_line = line + buf.count("\n")
        comment = f"  (* {origin.element}" + (f" on page {origin.page}" if origin.page else "") + f", line {origin.line} *)"
        buf += comment
        n_lines = buf.count("\n") + 1
        self.pieces[self._first_index(line)].n_lines = n_lines
        self.lines.extend(buf.split("\n"))

    def _first_index(self, line: int) -> int:
        for i in range(len(self.pieces) - 1, -1, -1):
            if self.pieces[i].gen_line == line and not self.pieces[i].exact:
                return i
        raise AssertionError("statement piece missing")


def _clean(text: str) -> str:
    """Inscription text without surrounding white space, with Unix line ends."""
    return text.replace("\r\n", "\n").replace("\r", "\n").strip()


def _text_origin(el: Element, elem_id: str, page: str | None, what: str) -> Origin:
    """Origin of the `<text>` of an inscription element (its character data, to the column)."""
    t = el.find("text")
    if t is not None and t.parts:
        # The char data starts where expat reported it; leading white space is stripped by _clean.
        raw = t.text.replace("\r\n", "\n")
        lead = raw[: len(raw) - len(raw.lstrip())]
        line = t.text_line + lead.count("\n")
        col = (len(lead.rsplit("\n", 1)[-1]) + 1) if "\n" in lead else t.text_col + len(lead)
        return Origin(line, col, elem_id, page, what)
    return Origin(el.line, el.col, elem_id, page, what)


@dataclass
class _Place:
    el: Element
    id: str
    name: str  # ML name (white space -> _)
    type: str
    init: str
    port: str | None
    fusion: str | None
    page: _Page


@dataclass
class _Trans:
    el: Element
    id: str
    name: str
    subpage: str | None
    portsock: list[tuple[str, str]]
    page: _Page


@dataclass
class _Page:
    el: Element
    id: str
    name: str  # ML name
    places: list[_Place] = field(default_factory=list)
    transs: list[_Trans] = field(default_factory=list)
    arcs: list[Element] = field(default_factory=list)


class _Translator:
    def __init__(self, path: str, root: Element) -> None:
        self.path = path
        self.root = root
        self.errors: list[Diagnostic] = []
        self.notes: list[str] = []
        self.out = _Out()
        self.pages: dict[str, _Page] = {}
        self.places: dict[str, _Place] = {}
        self.transs: dict[str, _Trans] = {}
        self.timed_colsets: set[str] = set()
        self.declared: set[str] = set()  # names declared by val/fun/colset in the globbox
        self.impure: set[str] = set(ml.RANDOM_FUNCTIONS)  # functions that draw random values
        self.code_outputs: dict[str, tuple] = {}  # transition id -> (outputs, pattern, action, origin)
        self.globref_consts: dict[str, str] = {}  # globrefs translated as constants
        self.globrefs_refused: dict[str, Element] = {}
        self.assigned: set[str] = set()

    # -- diagnostics -------------------------------------------------------------------------------

    def error(self, el: Element | Origin, message: str, hint: str | None = None) -> None:
        self.errors.append(Diagnostic("E0502", message, Span(self.path, el.line, el.col), hint=hint))

    # -- entry ---------------------------------------------------------------------------------------

    def run(self) -> Translation:
        cpnet = self.root.find("cpnet")
        if self.root.tag != "workspaceElements" or cpnet is None:
            self.error(self.root, f"not a CPN Tools net: the root element is <{self.root.tag}>, "
                       "expected <workspaceElements> with a <cpnet>",
                       hint="Give a file saved by CPN Tools (File > Save Net).")
            raise ModelError(self.errors)
        self.cpnet = cpnet
        self._scan_code_text()
        self._read_pages()
        self.out.raw(f"(* Translated by cpn-verify from the CPN Tools net {os.path.basename(self.path)}.")
        self.out.raw("   Each statement ends with a comment naming the XML element it comes from. *)")
        self._options()
        roots = self._instance_roots()
        top = self.pages[roots[0]] if roots else None
        if top is not None:
            self.out.raw(f"net {ml.quote(top.name)};")
        self.out.raw()
        gb = cpnet.find("globbox")
        if gb is not None:
            self._decls(gb)
        self.out.raw()
        emitted: set[str] = set()
        for r in roots:
            self._emit_modules_below(r, emitted, set())
        for r in roots[1:]:
            if r not in emitted:
                self._module(self.pages[r])
                emitted.add(r)
        if top is not None:
            self.out.raw(f"(* page {top.name} ({top.id}): the top level *)")
            self._page_body(top, "")
            for r in roots[1:]:
                p = self.pages[r]
                o = Origin(p.el.line, p.el.col, p.id, p.name, f"page '{p.name}'")
                self.out.stmt([(f"instance {ml.quote(p.name)} = {ml.quote(p.name)}() {{ }};", None)], o)
        else:
            self.error(self.root, "the net has no page", hint="Add a page with places and transitions.")
        if self.errors:
            raise ModelError(self.errors)
        return Translation(self.path, "\n".join(self.out.lines) + "\n", self.out.pieces, self.notes)

    # -- options ---------------------------------------------------------------------------------

    def _options(self) -> None:
        opts = self.cpnet.find("options")
        if opts is None:
            return
        for o in opts.findall("option"):
            if o.attrs.get("name") == "realtimestamp":
                vals = [b.text.strip() for b in o.iter("boolean")]
                if vals and vals[0] == "true":
                    note = ("the net sets the option 'realtimestamp' (real-valued time stamps); "
                            "integer delays give the same state space, '@++' delays are refused")
                    self.notes.append(note)
                    self.out.raw(f"(* note: {note} *)")

    # -- a first pass over all ML text: which globrefs are assigned, which functions are random ------

    def _all_decl_elements(self, node: Element):
        for c in node.children:
            if c.tag == "block":
                yield from self._all_decl_elements(c)
            elif c.tag in ("color", "var", "ml", "globref", "use"):
                yield c

    def _scan_code_text(self) -> None:
        texts = [t.text for t in self.cpnet.iter("text")] + [m.text for m in self.cpnet.iter("ml")]
        for t in texts:
            self.assigned |= ml.assigned_refs(t)
        gb = self.cpnet.find("globbox")
        decl_texts = []
        user_names: set[str] = set()
        if gb is not None:
            for el in self._all_decl_elements(gb):
                if el.tag == "ml":
                    decl_texts.append(el.text)
                elif el.tag == "color":
                    for k in el.children:  # enumeration constants, index and union constructors
                        if k.tag in ("enum", "index"):
                            user_names |= {c.text.strip() for c in k.findall("id")}
                        elif k.tag == "union":
                            user_names |= {f.find("id").text.strip() for f in k.findall("unionfield")
                                           if f.find("id") is not None}
                elif el.tag == "var":
                    user_names |= {c.text.strip() for c in el.findall("id")}
        funs = [f for t in decl_texts for f in ml.declared_functions(t)]
        self._needed_declarations(gb)
        user_names |= {name for name, _ in funs}
        # A user's own 'normal' or 'uniform' (an enumeration constant, say) is not the library function.
        self.impure = set(ml.RANDOM_FUNCTIONS) - user_names
        self.impure_via: dict[str, str] = {}  # a function -> the random function it calls
        # `fun DEL() = NetDelay.ran();`: a call DEL() is written NetDelay.ran(), which the engine explores
        # as a choice of every value; inside a function it would be one random draw.
        self.ran_aliases: dict[str, str] = {}
        for name, body in funs:
            m = re.fullmatch(r"\s*\(\s*\)\s*=\s*([A-Za-z][\w']*\.ran)\s*\(\s*\)\s*;?\s*", body)
            if m:
                self.ran_aliases[name] = m.group(1) + "()"
        changed = True
        while changed:  # transitive closure: a function that calls a random one is random
            changed = False
            for name, body in funs:
                used = {n for n, _ in ml.names(body)}
                if name not in self.impure and used & self.impure:
                    self.impure.add(name)
                    self.impure_via[name] = sorted(used & self.impure)[0]
                    changed = True

    def _needed_declarations(self, gb: Element | None) -> None:
        """Find the ML declarations the net uses, directly or through other declarations.

        Monitors, I/O helpers and functions for simulation reports are declared in the globbox too, and
        often use what a state space cannot have (references, files, the simulator's API). A declaration
        that no inscription and no colour set needs is left out, with a note.
        """
        self.needed_ml: set[int] = set()
        if gb is None:
            return

        def words(text: str) -> set[str]:
            out = set()
            for n, _ in ml.names(text):
                out.add(n)
                out.update(n.split("."))
            return out

        needed: set[str] = set()
        for page in self.cpnet.findall("page"):
            for pl in page.findall("place"):
                needed |= words(pl.child_text("type")) | words(pl.child_text("initmark"))
            for tr in page.findall("trans"):
                for tag in ("cond", "time", "priority"):
                    needed |= words(tr.child_text(tag))
                code = tr.child_text("code")
                if re.search(r"\boutput\b", ml.strip_comments(code)):
                    needed |= words(code)
            for a in page.findall("arc"):
                needed |= words(a.child_text("annot"))
        mls = []
        for el in self._all_decl_elements(gb):
            if el.tag == "color":
                for sub in el.iter("ml"):
                    needed |= words(sub.text)
                lay = el.find("layout")
                if lay is not None and el.find("by") is None:
                    needed |= words(lay.text)
            elif el.tag == "ml":
                heads = {name for name, _ in ml.declared_functions(el.text)}
                mls.append((el, heads, words(el.text)))
        changed = True
        while changed:
            changed = False
            for el, heads, used in mls:
                if id(el) not in self.needed_ml and heads & needed:
                    self.needed_ml.add(id(el))
                    needed |= used
                    changed = True

    def _refuse_random(self, text: str, origin: Origin, what: str) -> bool:
        """Refuse text that draws random values from a distribution; True if refused."""
        for n, _ in ml.names(text):
            if n in self.impure:
                chain = [n]
                while chain[-1] in self.impure_via and len(chain) < 10:
                    chain.append(self.impure_via[chain[-1]])
                why = (f"'{n}' draws a random value" if len(chain) == 1
                       else f"'{n}' calls " + ", which calls ".join(f"'{c}'" for c in chain[1:])
                       + ", a random distribution function")
                self.error(origin, f"{what} uses {n}: {why}; a net that does has no deterministic state space",
                           hint="Replace the distribution by a finite choice, e.g. a colour set "
                                "'colset D = int with 1..5;' and 'D.ran()', which becomes a choice of every value.")
                return True
        return False

    def _rewrite_globrefs(self, text: str) -> str:
        for name in self.globref_consts:
            text = re.sub(r"!\s*" + re.escape(name) + r"\b", name, text)
        return text

    def _check_globref_use(self, text: str, origin: Origin, what: str) -> None:
        for name in self.globrefs_refused:
            if re.search(r"!\s*" + re.escape(name) + r"\b", ml.strip_comments(text)):
                self.error(origin, f"{what} reads the reference variable '{name}' (globref), whose value "
                           "is not part of the marking",
                           hint="Make it a constant ('val') or a token on a place.")

    def _inscription(self, text: str, origin: Origin, what: str) -> str:
        """Check and prepare one inscription (guard, arc, delay, initial marking)."""
        self._refuse_random(text, origin, what)
        if "@++" in text:
            self.error(origin, f"{what} uses '@++', a real-valued delay ('{_short(text)}'): a state space "
                       "needs integer model time",
                       hint="Write an integer delay with '@+', e.g. '@+5'.")
        self._check_globref_use(text, origin, what)
        for name, ran in self.ran_aliases.items():
            text = re.sub(r"\b" + re.escape(name) + r"\s*\(\s*\)", ran, text)
        return self._rewrite_globrefs(text)

    # -- declarations ----------------------------------------------------------------------------

    def _decls(self, node: Element, block: str | None = None) -> None:
        for c in node.children:
            if c.tag == "block":
                idel = c.find("id")
                name = idel.text.strip() if idel is not None else ""
                self.out.raw(f"(* block {name} *)" if name else "(* block *)")
                self._decls(c, name)
            elif c.tag == "color":
                self._color(c)
            elif c.tag == "var":
                self._var(c)
            elif c.tag == "ml":
                self._ml(c)
            elif c.tag == "globref":
                self._globref(c)
            elif c.tag == "use":
                self._use(c)

    def _origin(self, el: Element, page: str | None, what: str) -> Origin:
        return Origin(el.line, el.col, el.attrs.get("id", "?"), page, what)

    def _color(self, el: Element) -> None:
        idel = el.find("id")
        name = idel.text.strip() if idel is not None else ""
        origin = self._origin(el, None, f"colour set '{name}'")
        layout = el.find("layout")
        timed = el.find("timed") is not None
        body = self._color_body(el)
        if body is None:
            if layout is not None and layout.text.strip():
                text = _clean(layout.text)
                m = re.match(r"colset\s+([A-Za-z][A-Za-z0-9_']*)", text)
                if m:
                    name = m.group(1)
                if re.search(r"\btimed\s*;?\s*$", text):
                    timed = True
                if not text.endswith(";"):
                    text += ";"
                self.declared.add(name)
                if timed:
                    self.timed_colsets.add(name)
                self.out.stmt([(text, Origin(layout.text_line, layout.text_col, origin.element, None, origin.what))],
                              origin)
                return
            self.error(el, f"colour set '{name}' ({origin.element}) has a kind this translator does not read",
                       hint="Declare it with one of unit, bool, int, real, string, with (enumeration), "
                            "index, product, record, list, union, subset or an alias.")
            return
        if timed:
            self.timed_colsets.add(name)
            body += " timed"
        self.declared.add(name)
        if el.find("declare") is not None:
            extra = ", ".join(d.text.strip() for d in el.find("declare").findall("id"))
            self.out.raw(f"(* colour set {name}: 'declare {extra}' generates I/O functions; ignored *)")
        self.out.stmt([(f"colset {ml.quote(name)} = {body};", None)], origin)

    def _color_body(self, el: Element) -> str | None:
        """The CPN ML text of a structured colour set, or None if its kind is not recognised."""
        kinds = [c for c in el.children if c.tag not in ("id", "layout", "timed", "declare")]
        if len(kinds) != 1:
            return None
        k = kinds[0]

        def ids(node: Element) -> list[str]:
            return [c.text.strip() for c in node.findall("id")]

        def mls(node: Element) -> list[str]:
            return [_clean(c.text) for c in node.findall("ml")]

        w = k.find("with")
        if k.tag in ("unit", "bool", "real", "intinf", "time"):
            if w is not None:
                return None if k.tag in ("real", "time") else (
                    f"{k.tag} with {ids(w)[0]}" if k.tag == "unit" and ids(w)
                    else f"bool with ({', '.join(ids(w))})" if k.tag == "bool" and len(ids(w)) == 2 else None)
            return k.tag
        if k.tag in ("int", "string"):
            if w is None:
                return k.tag
            lo_hi = mls(w)
            if k.tag == "int" and len(lo_hi) == 2:
                return f"int with {lo_hi[0]}..{lo_hi[1]}"
            return None
        if k.tag == "enum":
            return "with " + " | ".join(ids(k))
        if k.tag == "index":
            b = mls(k)
            i = ids(k)
            if len(b) == 2 and len(i) == 1:
                return f"index {i[0]} with {b[0]}..{b[1]}"
            return None
        if k.tag == "product":
            return "product " + " * ".join(ids(k))
        if k.tag == "record":
            fields = []
            for f in k.findall("recordfield"):
                fi = ids(f)
                if len(fi) != 2:
                    return None
                fields.append(f"{fi[0]} : {fi[1]}")
            return "record " + " * ".join(fields)
        if k.tag == "list":
            i = ids(k)
            if len(i) != 1:
                return None
            if w is not None:
                b = mls(w)
                return f"list {i[0]} with {b[0]}..{b[1]}" if len(b) == 2 else None
            return f"list {i[0]}"
        if k.tag == "union":
            parts = []
            for f in k.findall("unionfield"):
                fi = ids(f)
                t = f.find("type")
                ti = ids(t) if t is not None else fi[1:]
                parts.append(f"{fi[0]} : {ti[0]}" if ti else fi[0])
            return "union " + " + ".join(parts)
        if k.tag == "alias":
            i = ids(k)
            return i[0] if len(i) == 1 else None
        if k.tag == "subset":
            i = ids(k)
            by = k.find("by")
            if i and by is not None and mls(by):
                return f"subset {i[0]} by {mls(by)[0]}"
            if i and w is not None and mls(w):
                return f"subset {i[0]} with {mls(w)[0]}"
            return None
        return None

    def _var(self, el: Element) -> None:
        t = el.find("type")
        tname = t.find("id").text.strip() if t is not None and t.find("id") is not None else None
        names = [c.text.strip() for c in el.findall("id")]
        origin = self._origin(el, None, "variable declaration")
        if tname is None or not names:
            layout = el.find("layout")
            if layout is not None and layout.text.strip():
                text = _clean(layout.text)
                self.out.stmt([(text if text.endswith(";") else text + ";", None)], origin)
                return
            self.error(el, f"variable declaration {origin.element} has no colour set or no name")
            return
        self.out.stmt([(f"var {', '.join(names)} : {tname};", None)], origin)

    def _ml(self, el: Element, text: str | None = None) -> None:
        pruned = text is None and id(el) not in self.needed_ml
        text = _clean(el.text if text is None else text)
        if not text:
            return
        if pruned:
            heads = [name for name, _ in ml.declared_functions(text)]
            what = ", ".join(heads) if heads else _short(text, 30)
            self.out.raw(f"(* declaration {el.attrs.get('id', '?')} ({what}) at line {el.line}: not used by the "
                         "net, left out *)")
            return
        origin = self._origin(el, None, "declaration")
        if el.parts:
            origin = Origin(el.text_line, el.text_col, origin.element, None, origin.what)
            raw = el.text.replace("\r\n", "\n")
            lead = raw[: len(raw) - len(raw.lstrip())]
            if lead:
                origin = _text_origin_from(el.text_line, el.text_col, lead, origin)
        for name, _ in ml.declared_functions(text):
            self.declared.add(name)
        self._check_globref_use(text, origin, f"the declaration {origin.element}")
        text = self._rewrite_globrefs(text)
        if not text.rstrip().endswith(";"):
            text += ";"
        self.out.stmt([(text, origin)], origin)

    def _globref(self, el: Element) -> None:
        idel = el.find("id")
        name = idel.text.strip() if idel is not None else "?"
        mlel = el.find("ml")
        expr = _clean(mlel.text) if mlel is not None else ""
        origin = self._origin(el, None, f"reference variable '{name}'")
        literal = re.fullmatch(r"~?\d+|\"[^\"]*\"|true|false|\(\)", expr) is not None
        if literal and name not in self.assigned:
            self.globref_consts[name] = expr
            self.out.raw(f"(* globref {name} = {expr} is never assigned: a constant *)")
            self.out.stmt([(f"val {name} = {expr};", None)], origin)
            self.declared.add(name)
            return
        self.globrefs_refused[name] = el
        why = "it is assigned with ':='" if name in self.assigned else "its initial value is not a literal"
        self.out.raw(f"(* globref {name} = {_short(expr)} ({origin.element}): a reference variable, not translated "
                     f"because {why}; any inscription that reads it is refused *)")

    def _use(self, el: Element) -> None:
        mlel = el.find("ml")
        raw = _clean(mlel.text if mlel is not None else el.text)
        fname = raw.strip().strip(";").strip().strip('"')
        origin = self._origin(el, None, f"use \"{fname}\"")
        full = os.path.join(os.path.dirname(os.path.abspath(self.path)), fname)
        try:
            with open(full, encoding="utf-8", errors="replace") as f:
                content = f.read()
        except OSError as exc:
            self.error(el, f"cannot read the ML file '{fname}' named by a 'use' declaration: {exc.strerror}",
                       hint=f"Put '{fname}' next to the model ({full}).")
            return
        self.out.raw(f"(* from use \"{fname}\" ({origin.element}) *)")
        self._ml(el, content)

    # -- pages -----------------------------------------------------------------------------------

    def _read_pages(self) -> None:
        fusion_of: dict[str, str] = {}
        for fu in self.cpnet.findall("fusion"):
            for elm in fu.findall("fusion_elm"):
                fusion_of[elm.attrs.get("idref", "")] = ml.ml_name(fu.attrs.get("name", fu.attrs.get("id", "")))
        for pel in self.cpnet.findall("page"):
            attr = pel.find("pageattr")
            pname = attr.attrs.get("name", "") if attr is not None else ""
            page = _Page(pel, pel.attrs.get("id", "?"), self._module_name(pname, pel))
            self.pages[page.id] = page
            seen: dict[str, int] = {}
            for pl in pel.findall("place"):
                name = self._element_name(pl, "place", page, seen)
                port = pl.find("port")
                finfo = pl.find("fusioninfo")
                fusion = fusion_of.get(pl.attrs.get("id", ""))
                if finfo is not None and fusion is None:
                    fusion = ml.ml_name(finfo.attrs.get("name", ""))
                kind = None
                if port is not None:
                    ptype = port.attrs.get("type", "I/O").strip().lower()
                    kind = PORT_KINDS.get(ptype)
                    if kind is None:
                        self.error(port, f"place '{name}' on page '{page.name}' has port type '{ptype}'; "
                                   "expected In, Out or I/O")
                        kind = "io"
                place = _Place(pl, pl.attrs.get("id", "?"), name, _clean(pl.child_text("type")),
                               _clean(pl.child_text("initmark")), kind, fusion, page)
                page.places.append(place)
                self.places[place.id] = place
            # CPN Tools keeps place and transition names apart; `.cpnet` has one namespace per page.
            for tr in pel.findall("trans"):
                name = self._element_name(tr, "transition", page, seen)
                sub = tr.find("subst")
                pairs = []
                subpage = None
                if sub is not None:
                    subpage = sub.attrs.get("subpage")
                    pairs = re.findall(r"\(\s*([^,()\s]+)\s*,\s*([^,()\s]+)\s*\)", sub.attrs.get("portsock", ""))
                t = _Trans(tr, tr.attrs.get("id", "?"), name, subpage, pairs, page)
                page.transs.append(t)
                self.transs[t.id] = t
            page.arcs = pel.findall("arc")

    def _module_name(self, pname: str, pel: Element) -> str:
        """A page name as a module name: `.cpnet` module names are identifiers, unique in the net."""
        name = ml.ml_name(pname) or pel.attrs.get("id", "Page")
        if not ml.IDENT_RE.match(name) or name in ml.KEYWORDS:
            new = re.sub(r"[^A-Za-z0-9_]", "_", name)
            if not new[:1].isalpha():
                new = "P" + new
            if new in ml.KEYWORDS:
                new += "_"
            self.notes.append(f"page '{pname}' is called '{new}': a module name must be an identifier")
            name = new
        taken = {p.name for p in self.pages.values()}
        if name in taken:
            i = 2
            while f"{name}_{i}" in taken:
                i += 1
            self.notes.append(f"two pages are named '{name}'; the one at line {pel.line} is called '{name}_{i}'")
            name = f"{name}_{i}"
        return name

    def _element_name(self, el: Element, kind: str, page: _Page, seen: dict[str, int]) -> str:
        t = el.find("text")
        name = ml.ml_name(t.text) if t is not None else ""
        if not name:
            name = el.attrs.get("id", kind)
            self.notes.append(f"{kind} {name} on page '{page.name}' has no name; named after its id")
        if name in seen:
            seen[name] += 1
            new = f"{name}_{seen[name]}"
            self.notes.append(f"two elements on page '{page.name}' are named '{name}'; "
                              f"the {kind} at line {el.line} is called '{new}'")
            return new
        seen[name] = 1
        return name

    def _instance_roots(self) -> list[str]:
        """Root pages in the order of <instances>; pages used by no substitution transition."""
        used = {t.subpage for t in self.transs.values() if t.subpage}
        for t in self.transs.values():
            if t.subpage and t.subpage not in self.pages:
                self.error(t.el, f"substitution transition '{t.name}' on page '{t.page.name}' names subpage "
                           f"'{t.subpage}', which is not a page of this net")
        roots: list[str] = []
        inst = self.cpnet.find("instances")
        self.child_order: dict[str, list[str]] = {}
        if inst is not None:
            def walk(node: Element, page_id: str) -> None:
                order = []
                for c in node.findall("instance"):
                    tid = c.attrs.get("trans")
                    t = self.transs.get(tid or "")
                    if t is None or not t.subpage:
                        continue
                    order.append(tid)
                    walk(c, t.subpage)
                self.child_order.setdefault(page_id, order)

            for r in inst.findall("instance"):
                pid = r.attrs.get("page")
                if pid in self.pages and pid not in used and pid not in roots:
                    roots.append(pid)
                    walk(r, pid)
        for pid in self.pages:
            if pid not in used and pid not in roots:
                roots.append(pid)
        # A root page with neither places nor transitions (query pages, ASK-CTL pages) is left out.
        nonempty = [r for r in roots if self.pages[r].places or self.pages[r].transs]
        for r in roots:
            if r not in nonempty:
                self.notes.append(f"page '{self.pages[r].name}' has no places or transitions; left out")
        cycle = self._find_cycle()
        if cycle:
            self.error(self.pages[cycle[0]].el, "the page hierarchy has a cycle: "
                       + " -> ".join(self.pages[p].name for p in cycle),
                       hint="A page cannot be a subpage of itself, directly or indirectly.")
            return []
        return nonempty

    def _find_cycle(self) -> list[str] | None:
        state: dict[str, int] = {}

        def visit(pid: str, path: list[str]) -> list[str] | None:
            state[pid] = 1
            for t in self.pages[pid].transs:
                if t.subpage in self.pages:
                    if state.get(t.subpage) == 1:
                        return path + [pid, t.subpage]
                    if t.subpage not in state:
                        found = visit(t.subpage, path + [pid])
                        if found:
                            return found
            state[pid] = 2
            return None

        for pid in self.pages:
            if pid not in state:
                found = visit(pid, [])
                if found:
                    return found
        return None

    def _subst_order(self, page: _Page) -> list[_Trans]:
        substs = [t for t in page.transs if t.subpage in self.pages]
        order = self.child_order.get(page.id)
        if order:
            ranked = {tid: i for i, tid in enumerate(order)}
            substs.sort(key=lambda t: ranked.get(t.id, len(ranked)))
        return substs

    def _emit_modules_below(self, pid: str, emitted: set[str], stack: set[str]) -> None:
        for t in self._subst_order(self.pages[pid]):
            sp = t.subpage
            if sp in emitted or sp in stack:
                continue
            stack.add(sp)
            self._emit_modules_below(sp, emitted, stack)
            stack.discard(sp)
            self._module(self.pages[sp])
            emitted.add(sp)

    def _module(self, page: _Page) -> None:
        o = Origin(page.el.line, page.el.col, page.id, page.name, f"page '{page.name}'")
        self.out.stmt([(f"module {ml.quote(page.name)} {{", None)], o)
        self._page_body(page, "  ")
        self.out.raw("}")
        self.out.raw()

    def _page_body(self, page: _Page, ind: str) -> None:
        for p in page.places:
            self._place(p, ind)
        for t in page.transs:
            if t.subpage is None:
                self._trans(t, ind)
        for t in self._subst_order(page):
            self._instance(t, ind)
        for a in page.arcs:
            self._arc(a, page, ind)

    def _place(self, p: _Place, ind: str) -> None:
        o = Origin(p.el.line, p.el.col, p.id, p.page.name, f"place '{p.name}'")
        if not p.type:
            self.error(p.el, f"place '{p.name}' ({p.id}) on page '{p.page.name}' has no colour set",
                       hint="Give the place a colour set, e.g. UNIT.")
            return
        head = f"port {p.port} " if p.port else "place "
        parts: list[tuple[str, Origin | None]] = [
            (f"{head}{ml.quote(p.name)} : ", None),
            (p.type, _text_origin(p.el.find("type"), p.id, p.page.name, f"colour set of place '{p.name}'")),
        ]
        if p.init:
            io = _text_origin(p.el.find("initmark"), p.id, p.page.name, f"initial marking of place '{p.name}'")
            init = self._inscription(p.init, io, f"the initial marking of place '{p.name}'")
            if p.type in self.timed_colsets:
                init = _timed_literals(init)
            parts += [(" = ", None), (init, io)]
        if p.fusion:
            parts.append((f" fusion {ml.quote(p.fusion)}", None))
        parts.append((";", None))
        self.out.stmt(parts, o, ind)

    def _trans(self, t: _Trans, ind: str) -> None:
        o = Origin(t.el.line, t.el.col, t.id, t.page.name, f"transition '{t.name}'")
        parts: list[tuple[str, Origin | None]] = [(f"trans {ml.quote(t.name)}", None)]
        what = f"transition '{t.name}' on page '{t.page.name}'"
        chan = _clean(t.el.child_text("channel"))
        if chan:
            self.error(_text_origin(t.el.find("channel"), t.id, t.page.name, ""),
                       f"{what} has a synchronous channel inscription '{_short(chan)}'; synchronous channels "
                       "(CPN Tools 4 extensions) are not supported",
                       hint="Merge the transitions that synchronise into one transition.")
        code = _clean(t.el.child_text("code"))
        if code:
            co = _text_origin(t.el.find("code"), t.id, t.page.name, f"code segment of '{t.name}'")
            self._code_segment(t, code, co, what)
        guard = _clean(t.el.child_text("cond"))
        if guard:
            go = _text_origin(t.el.find("cond"), t.id, t.page.name, f"guard of '{t.name}'")
            guard = self._inscription(guard, go, f"the guard of {what}")
            if guard.startswith("[") and guard.endswith("]") and _balanced_outer(guard):
                parts += [(" ", None), (guard, go)]
            else:
                parts += [(" [", None), (guard, go), ("]", None)]
        delay = _clean(t.el.child_text("time"))
        if delay:
            do = _text_origin(t.el.find("time"), t.id, t.page.name, f"time inscription of '{t.name}'")
            delay = self._inscription(delay, do, f"the time inscription of {what}")
            if not delay.startswith("@+"):
                self.error(do, f"{what} has the time inscription '{_short(delay)}'; expected '@+ delay'")
            elif delay.startswith("@+[") or re.match(r"@\+\s*\[", delay):
                self.error(do, f"{what} has the time interval '{_short(delay)}'; time intervals are not "
                           "supported by the model language yet",
                           hint="Split the transition into one transition per delay, or use a fixed delay.")
            elif t.id in self.code_outputs:
                rest = delay[2:]
                do2 = Origin(do.line, do.col + 2 + len(rest) - len(rest.lstrip()), do.element, do.page, do.what)
                parts += [(" @+ ", None)] + self._with_code(t, rest.strip(), do2)
            else:
                parts += [(" ", None), (delay, do)]
        prio = _clean(t.el.child_text("priority"))
        if prio:
            po = _text_origin(t.el.find("priority"), t.id, t.page.name, f"priority of '{t.name}'")
            if prio in STANDARD_PRIORITIES and prio not in self.declared:
                parts += [(f" priority {STANDARD_PRIORITIES[prio]}", None)]
            else:
                parts += [(" priority ", None), (prio, po)]
        parts.append((";", None))
        self.out.stmt(parts, o, ind)

    def _code_segment(self, t: _Trans, code: str, origin: Origin, what: str) -> None:
        """Translate a code segment: without output variables its action cannot change the marking and is
        dropped (with a note); a pure action that binds output variables becomes a `let` around the output
        arc inscriptions and the time inscription that use them. Everything else is refused."""
        clean = ml.strip_comments(code)
        m = re.match(r"\s*(?:input\s*(?P<inp>\([^)]*\)|[A-Za-z][\w']*)\s*;)?\s*"
                     r"(?:output\s*(?P<out>\([^)]*\)|[A-Za-z][\w']*)\s*;)?\s*action\b(?P<act>.*)\Z", clean, re.S)
        if not m:
            self.error(origin, f"{what} has a code segment that is not 'input (..); output (..); action e'",
                       hint="Rewrite the code segment, or move its computation into arc inscriptions.")
            return
        outs = [v.strip() for v in (m.group("out") or "").strip("()").split(",") if v.strip()]
        act = code[m.start("act"):].strip()
        if act.endswith(";"):
            act = act[:-1].rstrip()
        if not outs:
            note = (f"the code segment of {what} binds no output variable: its action is not "
                    "executed (it cannot change the marking)")
            self.notes.append(note)
            self.out.raw(f"(* note: {note} *)")
            return
        if self._refuse_random(act, origin, f"the code segment of {what}"):
            return
        effects = sorted({n for n, _ in ml.names(act) if n.split(".")[0] in ml.SIDE_EFFECT_NAMES
                          or n in ml.SIDE_EFFECT_NAMES})
        if effects or ":=" in ml.strip_comments(act) or re.search(r"!\s*[A-Za-z(]", ml.strip_comments(act)):
            used = ", ".join(effects) if effects else "a reference variable"
            self.error(origin, f"{what} has a code segment that binds the output variable(s) {', '.join(outs)} "
                       f"with an action that uses {used}: code with side effects has no place in a state space",
                       hint="Compute the output values with pure CPN ML (no I/O, no references, no MSC), or "
                            "remove the code segment.")
            return
        # Where the action starts in the .cpn file, for error positions in the generated `let`.
        offset = code.index(act) if act in code else 0
        before = code[:offset]
        if "\n" in before:
            ao = Origin(origin.line + before.count("\n"), len(before.rsplit("\n", 1)[-1]) + 1, origin.element,
                        origin.page, origin.what)
        else:
            ao = Origin(origin.line, origin.col + offset, origin.element, origin.page, origin.what)
        pat = outs[0] if len(outs) == 1 else "(" + ", ".join(outs) + ")"
        self.code_outputs[t.id] = (outs, pat, act, ao)
        note = (f"the code segment of {what} binds {', '.join(outs)}; its action is evaluated in a 'let' "
                "around the output inscriptions that use them")
        self.notes.append(note)
        self.out.raw(f"(* note: {note} *)")

    def _with_code(self, t: _Trans, text: str, origin: Origin) -> list[tuple[str, Origin | None]]:
        """Parts of an inscription of `t`, wrapped in the `let` of t's code segment if it uses an output."""
        co = self.code_outputs.get(t.id)
        if co is None:
            return [(text, origin)]
        outs, pat, act, ao = co
        used = {n for n, _ in ml.names(text)}
        if not used & set(outs):
            return [(text, origin)]
        return [(f"(let val {pat} = ", None), (act, ao), (" in ", None), (text, origin), (" end)", None)]

    def _instance(self, t: _Trans, ind: str) -> None:
        o = Origin(t.el.line, t.el.col, t.id, t.page.name, f"substitution transition '{t.name}'")
        sub = self.pages[t.subpage]
        binds = []
        for port_id, sock_id in t.portsock:
            port = self.places.get(port_id)
            sock = self.places.get(sock_id)
            if port is None or sock is None or port.page is not sub or sock.page is not t.page:
                # Some files write the pair the other way round: accept it if it is unambiguous.
                if port is not None and sock is not None and port.page is t.page and sock.page is sub:
                    port, sock = sock, port
                else:
                    self.error(t.el, f"substitution transition '{t.name}' on page '{t.page.name}' pairs "
                               f"({port_id},{sock_id}), which is not (port place on '{sub.name}', socket "
                               f"place on '{t.page.name}')")
                    continue
            if port.port is None:
                self.error(port.el, f"place '{port.name}' on page '{sub.name}' is assigned to socket "
                           f"'{sock.name}' by '{t.name}' but is not a port",
                           hint="Make the place a port (In, Out or I/O) in CPN Tools.")
                continue
            binds.append(f"{ml.quote(port.name)} = {ml.quote(sock.name)}")
        body = " " + ", ".join(binds) + " " if binds else " "
        self.out.stmt([(f"instance {ml.quote(t.name)} = {ml.quote(sub.name)}() {{{body}}};", None)], o, ind)

    def _arc(self, a: Element, page: _Page, ind: str) -> None:
        aid = a.attrs.get("id", "?")
        orient = a.attrs.get("orientation", "").strip().lower()
        te = a.find("transend")
        pe = a.find("placeend")
        t = self.transs.get(te.attrs.get("idref", "")) if te is not None else None
        p = self.places.get(pe.attrs.get("idref", "")) if pe is not None else None
        if t is None or p is None or t.page is not page or p.page is not page:
            self.error(a, f"arc {aid} on page '{page.name}' does not connect a place and a transition of the page")
            return
        if t.subpage is not None:
            return  # a socket arc of a substitution transition: drawn only; portsock carries the meaning
        annot = _clean(a.child_text("annot"))
        what = f"the inscription of the arc between '{p.name}' and '{t.name}' on page '{page.name}'"
        ao = _text_origin(a.find("annot"), aid, page.name, f"arc inscription {p.name}/{t.name}")
        o = Origin(a.line, a.col, aid, page.name, f"arc between '{p.name}' and '{t.name}'")
        if annot:
            annot = self._inscription(annot, ao, what)
        pq, tq = ml.quote(p.name), ml.quote(t.name)
        if orient == "ptot":
            head = f"arc {pq} -> {tq}"
        elif orient == "ttop":
            head = f"arc {tq} -> {pq}"
        elif orient == "bothdir":
            head = f"arc {pq} <-> {tq}"
        elif orient == "inhibitor":
            head = f"inhibitor {pq} -> {tq}"
        elif orient == "reset":
            if annot:
                self.notes.append(f"the inscription of reset arc {aid} is ignored: a reset arc removes every token")
            o2 = Origin(a.line, a.col, aid, page.name, o.what)
            self.out.stmt([(f"reset {pq} -> {tq};", None)], o2, ind)
            return
        else:
            self.error(a, f"arc {aid} on page '{page.name}' has orientation '{a.attrs.get('orientation')}'; "
                       "expected PtoT, TtoP, BOTHDIR, Inhibitor or Reset")
            return
        parts: list[tuple[str, Origin | None]] = [(head, None)]
        if annot and orient == "ttop":
            parts += [(" : ", None)] + self._with_code(t, annot, ao)
        elif annot:
            parts += [(" : ", None), (annot, ao)]
        parts.append((";", None))
        self.out.stmt(parts, o, ind)


def _text_origin_from(line: int, col: int, lead: str, origin: Origin) -> Origin:
    if "\n" in lead:
        return Origin(line + lead.count("\n"), len(lead.rsplit("\n", 1)[-1]) + 1, origin.element, origin.page,
                      origin.what)
    return Origin(line, col + len(lead), origin.element, origin.page, origin.what)


def _balanced_outer(text: str) -> bool:
    """True if the opening '[' of text is closed by its final ']' (a guard list, not '[a] @ [b]')."""
    depth = 0
    clean = ml.strip_comments(text)
    in_str = False
    for i, ch in enumerate(clean):
        if ch == '"' and (i == 0 or clean[i - 1] != "\\"):
            in_str = not in_str
        if in_str:
            continue
        if ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
            if depth == 0 and i != len(clean) - 1:
                return False
    return True


def _timed_literals(text: str) -> str:
    """CPN Tools writes a timed token as `x@t` (time stamp t); `.cpnet` writes `x @+ t` (the clock is 0)."""
    return re.sub(r"@(?![+@])\s*", "@+ ", text)


def _short(text: str, n: int = 40) -> str:
    one = " ".join(text.split())
    return one if len(one) <= n else one[: n - 3] + "..."


def translate_file(path: str) -> Translation:
    """Translate a `.cpn` file; the result carries the text and the origin of every statement.

    Raises
    ------
    ModelError
        With every E0501/E0502 diagnostic found, positioned in the `.cpn` file.
    """
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as exc:
        raise ModelError([Diagnostic("E0501", f"cannot read '{path}': {exc.strerror}", Span(path, 1, 1))]) from None
    return _Translator(path, parse_xml(data, path)).run()


def translate_text(data: bytes | str, path: str = "<cpn>") -> Translation:
    """Translate the XML text of a `.cpn` file (for tests and in-memory use)."""
    if isinstance(data, str):
        data = data.encode("utf-8")
    return _Translator(path, parse_xml(data, path)).run()


def translate(path: str) -> str:
    """Translate the CPN Tools net in `path` into `.cpnet` source text.

    Examples
    --------
    >>> text = translate("DiningPhilosophers.cpn")  # doctest: +SKIP
    >>> "net Page;" in text  # doctest: +SKIP
    True
    """
    return translate_file(path).text


def remap_error(error: ModelError, translation: Translation, generated_name: str | None = None,
                keep_generated_span: bool = False) -> ModelError:
    """Point the diagnostics of a failed load of generated text back at the `.cpn` file.

    A diagnostic positioned in the generated text gets a note with the element's id, page and `.cpn`
    position. Unless `keep_generated_span` (the generated text is on disk, `cpn-verify convert`), its span
    moves to the `.cpn` file too.
    """
    out = []
    for d in error.diagnostics:
        s = d.span
        if s is not None and (generated_name is None or s.file in (generated_name, translation.path)):
            found = translation.locate(s.line, s.col)
            if found is not None:
                span, origin = found
                if keep_generated_span:
                    note = f"from {origin.describe()}: {span}"
                    new_span = s
                else:
                    note = f"in {origin.describe()}; line {s.line} of the translated text"
                    new_span = span
                out.append(Diagnostic(d.code, d.message, new_span, d.hint, list(d.notes) + [note],
                                      dict(d.params), d.severity))
                continue
        out.append(d)
    sources = dict(error.sources)
    if not keep_generated_span:
        try:
            with open(translation.path, encoding="iso-8859-1") as f:
                sources[translation.path] = f.read()
        except OSError:
            pass
    return type(error)(out, sources)
