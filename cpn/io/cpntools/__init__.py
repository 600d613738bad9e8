"""Translate CPN Tools `.cpn` files (XML, DTD formats 5 and 6) into `.cpnet` source text.

CPN Tools' declarations and inscriptions are CPN ML already, so the translation restructures the XML:
globbox declarations (blocks flattened), pages to modules, the root page to the top level, substitution
transitions to `instance` statements, fusion sets, ports, arcs of every orientation. Whatever cannot
have a deterministic state space is left to the front end where `simulate` can run it (random
distributions, `@++` real delays, reference variables and the code segments that use them, which become
transition actions: lint warns, explore refuses each) and refused with a positioned E0502 otherwise (code
segments with other side effects, synchronous channels).
Every generated statement carries a comment with its origin, and `Translation.locate` maps a position
of the generated text back to the XML. Imports `cpn.diagnostics`, `cpn.errors` and the standard library.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field

from cpn.diagnostics import Diagnostic, Span
from cpn.errors import ModelError
from cpn.io.cpntools import _ml as ml
from cpn.io.cpntools._decls import CODE_RE, _Declarations
from cpn.io.cpntools._text import (
    Origin,
    Translation,
    _balanced_outer,
    _clean,
    _Out,
    _short,
    _text_origin,
    _timed_literals,
)
from cpn.io.cpntools._xml import Element, parse_xml
from cpn.values import sml_basis
from cpn.values.effects import SIMULATION_ONLY

__all__ = ["Origin", "Translation", "translate", "translate_file", "translate_text", "remap_error"]

# CPN Tools' standard priorities (declared in the "Standard priorities" block of a new net).
STANDARD_PRIORITIES = {"P_HIGH": "100", "P_NORMAL": "1000", "P_LOW": "10000"}
# The colour set CPN Tools gives a place without a colour-set inscription.
UNIT_NAME = "UNIT"
PORT_KINDS = {"in": "in", "out": "out", "i/o": "io", "io": "io", "inout": "io", "general": "io"}


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
    untyped: bool = False  # no colour-set inscription in the file: UNIT, as in CPN Tools


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


@dataclass
class _CodeOutputs:
    """The output variables of a transition's code segment and the action that binds them."""

    names: list[str]
    action: str
    origin: Origin  # where the action starts in the .cpn file
    bound: bool = False  # bound once by a guard conjunct (the action draws and several inscriptions use it)

    @property
    def pattern(self) -> str:
        return self.names[0] if len(self.names) == 1 else "(" + ", ".join(self.names) + ")"


# the statement of each arc orientation (reset arcs, which take no inscription, apart)
_ARC_HEADS = {"ptot": "arc {p} -> {t}", "ttop": "arc {t} -> {p}", "bothdir": "arc {p} <-> {t}",
              "inhibitor": "inhibitor {p} -> {t}"}



def _origin_at(origin: Origin, text: str, offset: int) -> Origin:
    """The origin of the character at `offset` of `text`, which starts at `origin`."""
    before = text[:offset]
    if "\n" in before:
        return Origin(origin.line + before.count("\n"), len(before.rsplit("\n", 1)[-1]) + 1, origin.element,
                      origin.page, origin.what)
    return Origin(origin.line, origin.col + offset, origin.element, origin.page, origin.what)


class _Translator(_Declarations):
    def __init__(self, path: str, root: Element, data: bytes = b"") -> None:
        self.path = path
        self.root = root
        # the file's lines as written (entities such as '&gt;' unexpanded), to put a column in the text
        # of an element at its column in the file
        self.raw_lines = data.decode("latin-1").splitlines()
        self.errors: list[Diagnostic] = []
        self.notes: list[str] = []
        self.untyped_arcs: dict[str, str] = {}  # arc id -> the name of its place that has no colour set
        self.out = _Out()
        self.pages: dict[str, _Page] = {}
        self.places: dict[str, _Place] = {}
        self.transs: dict[str, _Trans] = {}
        self.timed_colsets: set[str] = set()
        self.declared: set[str] = set()  # names declared by val/fun/colset in the globbox
        self.var_names: set[str] = set()  # the variables the globbox declares
        self.impure: set[str] = set(ml.RANDOM_FUNCTIONS)  # functions that draw random values
        self.code_outputs: dict[str, _CodeOutputs] = {}  # transition id -> its code segment's outputs
        # transition id -> (outputs, action, origin) of a code segment that uses references: kept as an action
        self.code_actions: dict[str, tuple[list[str], str, Origin]] = {}
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
        if getattr(self, "real_time", False):
            # with real-valued time stamps CPN Tools' time() is a real; the model time is an integer in a state
            # space (where the net has no '@++') and a real in simulate, and Real.fromInt keeps it as it is
            self.out.raw("val time = fn () => Real.fromInt (time ());  (* option realtimestamp: time () is a real *)")
        self.out.raw()
        gb = cpnet.find("globbox")
        if gb is not None:
            self._decls(gb)
        if UNIT_NAME not in self.declared and any(not p.type for p in self.places.values()):
            self.out.raw(f"colset {UNIT_NAME} = unit;  (* for the places without a colour set, as in CPN Tools *)")
            self.declared.add(UNIT_NAME)
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
        return Translation(self.path, "\n".join(self.out.lines) + "\n", self.out.pieces, self.notes, self.raw_lines,
                           self.untyped_arcs)

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
                            "integer delays give the same state space, '@++' delays are simulated only")
                    self.notes.append(note)
                    self.out.raw(f"(* note: {note} *)")
                    self.real_time = True

    # -- a first pass over all ML text: which globrefs are assigned, which functions are random ------

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
            seen = {}  # places and transitions have separate namespaces, in CPN Tools and in .cpnet
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
            # CPN Tools gives a place without a colour-set inscription the colour set UNIT
            self.notes.append(f"place '{p.name}' ({p.id}) on page '{p.page.name}' has no colour set: "
                              "UNIT, as in CPN Tools")
            p.type = UNIT_NAME
            p.untyped = True
        head = f"port {p.port} " if p.port else "place "
        parts: list[tuple[str, Origin | None]] = [
            (f"{head}{ml.quote(p.name)} : ", None),
            (p.type, _text_origin(p.el.find("type"), p.id, p.page.name, f"colour set of place '{p.name}'", owner=p.el)),
        ]
        if p.init:
            io = _text_origin(p.el.find("initmark"), p.id, p.page.name, f"initial marking of place '{p.name}'",
                              owner=p.el)
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
            self.error(_text_origin(t.el.find("channel"), t.id, t.page.name, "", owner=t.el),
                       f"{what} has a synchronous channel inscription '{_short(chan)}'; synchronous channels "
                       "(CPN Tools 4 extensions) are not supported",
                       hint="Merge the transitions that synchronise into one transition.")
        code = _clean(t.el.child_text("code"))
        if code:
            co = _text_origin(t.el.find("code"), t.id, t.page.name, f"code segment of '{t.name}'", owner=t.el)
            self._code_segment(t, code, co, what)
        parts += self._guard(t, what)
        delay = _clean(t.el.child_text("time"))
        if delay:
            do = _text_origin(t.el.find("time"), t.id, t.page.name, f"time inscription of '{t.name}'", owner=t.el)
            delay = self._inscription(self._code_reads(t, delay), do, f"the time inscription of {what}")
            if not delay.startswith("@+"):
                self.error(do, f"{what} has the time inscription '{_short(delay)}'; expected '@+ delay'")
            elif t.id in self.code_outputs:
                op = "@++" if delay.startswith("@++") else "@+"
                rest = delay[len(op):]
                do2 = Origin(do.line, do.col + len(op) + len(rest) - len(rest.lstrip()), do.element, do.page,
                             do.what)
                parts += [(f" {op} ", None)] + self._with_code(t, rest.strip(), do2)
            else:
                parts += [(" ", None), (delay, do)]
        prio = _clean(t.el.child_text("priority"))
        if prio:
            po = _text_origin(t.el.find("priority"), t.id, t.page.name, f"priority of '{t.name}'", owner=t.el)
            if prio in STANDARD_PRIORITIES and prio not in self.declared:
                parts += [(f" priority {STANDARD_PRIORITIES[prio]}", None)]
            else:
                parts += [(" priority ", None), (prio, po)]
        if t.id in self.code_actions:
            outs, act, ao = self.code_actions[t.id]
            head = f" output ({', '.join(outs)})" if outs else ""
            act = self._inscription(act, ao, f"the code segment of {what}")
            parts += [(f"{head} action (", None), (act, ao), (")", None)]
        parts.append((";", None))
        self.out.stmt(parts, o, ind)

    def _guard(self, t: _Trans, what: str) -> list[tuple[str, Origin | None]]:
        """The guard of `t`, with the binding of its code segment's outputs where they are bound once."""
        co = self.code_outputs.get(t.id)
        binder = [(f"{co.pattern} = (", None), (co.action, co.origin), (")", None)] if co and co.bound else []
        guard = _clean(t.el.child_text("cond"))
        if not guard:
            return [(" [", None)] + binder + [("]", None)] if binder else []
        go = _text_origin(t.el.find("cond"), t.id, t.page.name, f"guard of '{t.name}'", owner=t.el)
        guard = self._inscription(guard, go, f"the guard of {what}")
        bracketed = guard.startswith("[") and guard.endswith("]") and _balanced_outer(guard)
        if not binder:
            return [(" ", None), (guard, go)] if bracketed else [(" [", None), (guard, go), ("]", None)]
        head = [(" ", None), (guard[:-1], go)] if bracketed else [(" [", None), (guard, go)]
        sep = [] if bracketed and not guard[1:-1].strip() else [(", ", None)]
        return head + sep + binder + [("]", None)]

    def _code_segment(self, t: _Trans, code: str, origin: Origin, what: str) -> None:
        """Translate a code segment: without output variables its action cannot change the marking and is
        dropped (with a note); a pure action that binds output variables becomes a `let` around the output
        arc inscriptions and the time inscription that use them, or, if it draws and several of them use
        it, a guard `outputs = action` (CPN Tools runs the action once per occurrence: one draw, read by
        every inscription). Everything else is refused."""
        # CPN Tools reads the ';' after the input and output patterns as optional (`input (c)` newline `action`)
        m = CODE_RE.match(ml.strip_comments(code))
        if not m:
            self.error(origin, f"{what} has a code segment that is not 'input (..); output (..); action e'",
                       hint="Rewrite the code segment, or move its computation into arc inscriptions.")
            return
        outs = [v.strip() for v in (m.group("out") or "").strip("()").split(",") if v.strip()]
        act = code[m.start("act"):].strip()
        if act.endswith(";"):
            act = act[:-1].rstrip()
        assigns = self.code_assigns.get(t.id) if not outs else None
        if assigns:
            self._code_assignments(t, code, assigns, origin, what)
        elif (t.id in self.kept_actions) if not outs else self._uses_refs(act):
            # it assigns reference variables (or, binding outputs, reads them): CPN Tools runs it once per
            # occurrence, before the output arcs; so does simulate, and explore and check refuse it
            if not self._refuse_code_action(act, outs, origin, what):
                ao = _origin_at(origin, code, code.index(act) if act in code else 0)
                self.code_actions[t.id] = (outs, act, ao)
                self._note(f"the code segment of {what} uses reference variables: it is the transition's "
                           "action, which simulate runs once per occurrence (explore and check refuse it)")
        elif not outs:
            self._note(f"the code segment of {what} binds no output variable: its action is not "
                       "executed (it cannot change the marking)")
        elif not self._refuse_code_action(act, outs, origin, what):
            # where the action starts in the .cpn file, for error positions in the generated text
            ao = _origin_at(origin, code, code.index(act) if act in code else 0)
            # (a guard binds declared variables only, as CPN Tools requires of output variables)
            bound = self._draws(act) and self._output_uses(t, outs) > 1 and set(outs) <= self.var_names
            self.code_outputs[t.id] = _CodeOutputs(outs, act, ao, bound)
            self._note(f"the code segment of {what} binds {', '.join(outs)}; " + (
                "its action draws, and several output inscriptions use them: it is evaluated once, in the "
                "guard, so that they all read the same values" if bound else
                "its action is evaluated in a 'let' around the output inscriptions that use them"))

    def _code_assignments(self, t: _Trans, code: str, assigns: dict[str, tuple[str, int]], origin: Origin,
                          what: str) -> None:
        """`action x := e` where only this transition's output arcs and delay read `!x`: x is an output."""
        names = list(assigns)
        exprs = [assigns[n][0] for n in names]
        act = exprs[0] if len(exprs) == 1 else "(" + ", ".join(exprs) + ")"
        self.code_outputs[t.id] = _CodeOutputs(names, act, _origin_at(origin, code, assigns[names[0]][1]))
        self._note(f"the code segment of {what} assigns {', '.join(names)}, which only its output arcs read: "
                   "its action is evaluated in a 'let' around them")

    def _refuse_code_action(self, act: str, outs: list[str], origin: Origin, what: str) -> bool:
        """Refuse an action with side effects other than text output, the machine's clock, other programs,
        files and reference variables, which the front end leaves to simulate (the last make the code segment
        the transition's action); True if refused."""
        if self._refuse_random(act, origin, f"the code segment of {what}", effects=False):
            return True
        effects = sorted({n for n, _ in ml.names(act)
                          if n not in SIMULATION_ONLY and n not in sml_basis.FUNCTIONS
                          and (n.split(".")[0] in ml.SIDE_EFFECT_NAMES or n in ml.SIDE_EFFECT_NAMES
                               or self._side_effect_via(n))})
        if effects:
            binds = (f"that binds the output variable(s) {', '.join(outs)} with an action that uses" if outs
                     else "whose action uses")
            self.error(origin, f"{what} has a code segment {binds} {', '.join(effects)}: code with side "
                       "effects has no place in a state space, and simulate cannot run it",
                       hint="Compute the values with pure CPN ML (no MSC, no calls of other programs), or "
                            "remove the code segment.")
            return True
        return False

    def _output_uses(self, t: _Trans, outs: list[str]) -> int:
        """How many of t's output arc inscriptions and time inscription name an output variable."""
        texts = [_clean(t.el.child_text("time"))]
        for a in t.page.arcs:
            te = a.find("transend")
            if (te is not None and te.attrs.get("idref") == t.id
                    and a.attrs.get("orientation", "").strip().lower() == "ttop"):
                texts.append(_clean(a.child_text("annot")))
        return sum(1 for x in texts if set(outs) & {n for n, _ in ml.names(x)})

    def _note(self, note: str) -> None:
        self.notes.append(note)
        self.out.raw(f"(* note: {note} *)")

    def _code_reads(self, t: _Trans, text: str) -> str:
        """`!x` written `x` where x is assigned by t's code segment and read only by its outputs (a blank keeps
        the columns)."""
        for x in self.code_assigns.get(t.id, {}) if t.id in self.code_outputs else ():
            text = re.sub(r"!(\s*" + re.escape(x) + r"\b)", r" \1", text)
        return text

    def _with_code(self, t: _Trans, text: str, origin: Origin) -> list[tuple[str, Origin | None]]:
        """Parts of an inscription of `t`, wrapped in the `let` of t's code segment if it uses an output."""
        co = self.code_outputs.get(t.id)
        if co is None or co.bound or not set(co.names) & {n for n, _ in ml.names(text)}:
            return [(text, origin)]
        return [(f"(let val {co.pattern} = ", None), (co.action, co.origin), (" in ", None), (text, origin),
                (" end)", None)]

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
        ends = self._arc_ends(a, page)
        if ends is None:
            return
        t, p = ends
        if t.subpage is not None:
            return  # a socket arc of a substitution transition: drawn only; portsock carries the meaning
        if p.untyped:
            self.untyped_arcs[aid] = p.name
        annot = _clean(a.child_text("annot"))
        what = f"the inscription of the arc between '{p.name}' and '{t.name}' on page '{page.name}'"
        ao = _text_origin(a.find("annot"), aid, page.name, f"arc inscription {p.name}/{t.name}", owner=a)
        o = Origin(a.line, a.col, aid, page.name, f"arc between '{p.name}' and '{t.name}'")
        if annot:
            annot = self._inscription(self._code_reads(t, annot) if orient == "ttop" else annot, ao, what)
        if orient == "bothdir" and self._refuse_input_delay(annot, ao, what):
            return
        pq, tq = ml.quote(p.name), ml.quote(t.name)
        if (p.name in {x.name for x in page.transs if x.subpage is None}
                or t.name in {x.name for x in page.places}):
            # a place and a transition that share a name (CPN Tools allows it): the arc says which end is which
            pq, tq = f"place {pq}", f"trans {tq}"
        if orient == "reset":
            if annot:
                self.notes.append(f"the inscription of reset arc {aid} is ignored: a reset arc removes every token")
            self.out.stmt([(f"reset {pq} -> {tq};", None)], o, ind)
            return
        head = _ARC_HEADS.get(orient)
        if head is None:
            self.error(a, f"arc {aid} on page '{page.name}' has orientation '{a.attrs.get('orientation')}'; "
                       "expected PtoT, TtoP, BOTHDIR, Inhibitor or Reset")
            return
        parts: list[tuple[str, Origin | None]] = [(head.format(p=pq, t=tq), None)]
        if annot and orient == "ttop":
            parts += [(" : ", None)] + self._with_code(t, annot, ao)
        elif annot:
            parts += [(" : ", None), (annot, ao)]
        parts.append((";", None))
        self.out.stmt(parts, o, ind)

    def _arc_ends(self, a: Element, page: _Page) -> tuple[_Trans, _Place] | None:
        """The transition and the place an arc joins, or None (with an error) if they are not both on its page."""
        te = a.find("transend")
        pe = a.find("placeend")
        t = self.transs.get(te.attrs.get("idref", "")) if te is not None else None
        p = self.places.get(pe.attrs.get("idref", "")) if pe is not None else None
        if t is not None and p is not None and t.page is page and p.page is page:
            return t, p
        why = []
        for end, found, kind in ((te, t, "transition"), (pe, p, "place")):
            ref = end.attrs.get("idref", "") if end is not None else ""
            if end is None:
                why.append(f"it has no <{kind[:5]}end>")
            elif found is None:
                why.append(f"its {kind} end '{ref}' is no {kind} of the file")
            elif found.page is not page:
                why.append(f"its {kind} '{found.name}' is on page '{found.page.name}'")
        missing = any(end is not None and found is None for end, found in ((te, t), (pe, p)))
        self.error(a, f"arc {a.attrs.get('id', '?')} on page '{page.name}' does not connect a place and a transition "
                   "of the page: " + "; ".join(why),
                   hint=(f"The file is not as CPN Tools writes it: its loader joins an arc only to a node whose "
                         f"id the file holds, so there this arc would join no {'transition' if t is None else 'place'} "
                         f"and take part in no occurrence. Delete the <arc id=\"{a.attrs.get('id', '?')}\"> element "
                         "from the file, or add the missing node to the page." if missing else
                         "Delete the arc in CPN Tools, or draw it again between a place and a transition of the page."))
        return None

    def _refuse_input_delay(self, annot: str, ao: Origin, what: str) -> bool:
        """One error at a double arc's inscription that delays, rather than the front end's, after which the
        arc's variables would be unbound; True if refused. (An input arc's delay, CPN Tools' preempting time
        stamps, goes to the front end, which checks it.)"""
        if not re.search(r"@\+", re.sub(r'"(?:[^"\\]|\\.)*"', '""', ml.strip_comments(annot))):
            return False
        self.error(Origin(ao.line, ao.col, ao.element, ao.page, ao.what),
                   f"{what} ('{_short(annot)}') is a double arc with a time delay: whether the delay lets the "
                   "transition take the token early, delays the token it puts back, or both, is not supported",
                   hint="Draw the double arc as two arcs in CPN Tools: an input arc ('e @+ k' removes the token "
                        "up to k time units early) and an output arc ('e @+ d' puts it back d time units later).")
        return True


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
    return _Translator(path, parse_xml(data, path), data).run()


def translate_text(data: bytes | str, path: str = "<cpn>") -> Translation:
    """Translate the XML text of a `.cpn` file (for tests and in-memory use)."""
    if isinstance(data, str):
        data = data.encode("utf-8")
    return _Translator(path, parse_xml(data, path), data).run()


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
                hint = d.hint
                place = translation.untyped_arcs.get(origin.element)
                if hint is None and place is not None and d.code == "E0301" and "type mismatch" in d.message:
                    hint = (f"Place '{place}' has no colour set in the file, and CPN Tools gives such a place the "
                            f"colour set UNIT, so an arc that moves other tokens is a type error in CPN Tools too: "
                            f"give the place the colour set of the arc's tokens.")
                out.append(Diagnostic(d.code, d.message, new_span, hint, list(d.notes) + [note],
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
        for path in {d.span.file for d in out if d.span is not None} - set(sources) - {translation.path}:
            try:  # a `use`d file that a diagnostic points into
                with open(path, encoding="utf-8", errors="replace") as f:
                    sources[path] = f.read()
            except OSError:
                pass
    return type(error)(out, sources)
