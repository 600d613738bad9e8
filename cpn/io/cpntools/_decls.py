"""Globbox declarations of a CPN Tools net: colour sets, variables, ML declarations, globrefs, `use`.

A mixin of the translator (`cpn.io.cpntools`): it also decides which declarations the net needs and which
functions draw random values. Imports the standard library and the CPN Tools helpers only.
"""

from __future__ import annotations

import os
import re

from cpn.diagnostics import Diagnostic, Span
from cpn.io.cpntools import _ml as ml
from cpn.io.cpntools._text import Origin, _clean, _short, _text_origin_from
from cpn.io.cpntools._xml import Element
from cpn.values import sml_basis
from cpn.values.builtins import FUNCTIONS as LIBRARY
from cpn.values.draws import DISTRIBUTIONS
from cpn.values.effects import SIMULATION_ONLY

# a code segment: input (..); output (..); action e (the ';' after the patterns may be left out, as CPN Tools
# reads it)
CODE_RE = re.compile(r"\s*(?:input\s*(?P<inp>\([^)]*\)|[A-Za-z][\w']*)\s*;?)?\s*"
                     r"(?:output\s*(?P<out>\([^)]*\)|[A-Za-z][\w']*)\s*;?)?\s*action\b(?P<act>.*)\Z", re.S)
_STRING = r'"(?:[^"\\]|\\.)*"'  # an SML string literal
_LITERAL = r"~?\d+(?:\.\d+)?(?:[eE]~?\d+)?|" + _STRING + r"|true|false|\(\)"  # a constant of a globref


def _unescape(text: str) -> str:
    """The characters of an SML string literal's text (`\\\\` is one backslash, `\\"` a quote)."""
    return re.sub(r"\\(.)", r"\1", text)


_LIBRARY_NAMES = set(LIBRARY) | set(sml_basis.FUNCTIONS) | set(sml_basis.CONSTRUCTORS) | set(DISTRIBUTIONS)


class _Declarations:
    """Reading and writing the globbox; the translator provides `out`, `error`, `cpnet`, `notes`."""

    def _all_decl_elements(self, node: Element):
        for c in node.children:
            if c.tag == "block":
                yield from self._all_decl_elements(c)
            elif c.tag in ("color", "var", "ml", "globref", "use"):
                yield c

    def _scan_code_text(self) -> None:
        """A first pass over all ML text: which references are assigned, which declarations the net needs,
        which functions draw random values or have side effects."""
        texts = [t.text for t in self.cpnet.iter("text")] + [m.text for m in self.cpnet.iter("ml")]
        for t in texts:
            self.assigned |= ml.assigned_refs(t)
        gb = self.cpnet.find("globbox")
        decl_texts, user_names = self._globbox_names(gb)
        funs = [f for t in decl_texts for f in ml.declared_functions(t)]
        self.fun_bodies: dict[str, list[str]] = {}
        for name, body in funs:
            self.fun_bodies.setdefault(name, []).append(body)
        self._ref_declarations(gb)
        self._scan_code_refs()
        self._kept_actions()
        self._needed_declarations(gb)
        self._impure_functions(funs, user_names | {name for name, _ in funs})

    def _globbox_names(self, gb: Element | None) -> tuple[list[str], set[str]]:
        """The texts of the globbox's ML declarations, and the names its colour sets and variables declare
        (enumeration constants, index and union constructors, variables)."""
        decl_texts: list[str] = []
        user_names: set[str] = set()
        for el in self._all_decl_elements(gb) if gb is not None else []:
            if el.tag == "ml":
                decl_texts.append(el.text)
            elif el.tag == "color":
                for k in el.children:
                    if k.tag in ("enum", "index"):
                        user_names |= {c.text.strip() for c in k.findall("id")}
                    elif k.tag == "union":
                        user_names |= {f.find("id").text.strip() for f in k.findall("unionfield")
                                       if f.find("id") is not None}
            elif el.tag == "var":
                user_names |= {c.text.strip() for c in el.findall("id")}
        return decl_texts, user_names

    def _ref_declarations(self, gb: Element | None) -> None:
        """`val x = ref 0;` in a declaration: a reference variable like a globref, set by code segments; never
        assigned and holding a literal, it is a constant."""
        for el in self._all_decl_elements(gb) if gb is not None else []:
            if el.tag == "ml":
                for m in re.finditer(r"\bval\s+([A-Za-z][\w']*)\s*=\s*ref\b(?:\s*(" + _LITERAL + r")\s*(?=;|\Z))?",
                                     ml.strip_comments(el.text)):
                    if m.group(2) is not None and m.group(1) not in self.assigned:
                        self.globref_consts[m.group(1)] = m.group(2)
                    else:
                        self.globrefs_refused[m.group(1)] = el

    def _impure_functions(self, funs: list[tuple[str, str]], user_names: set[str]) -> None:
        """Which declared functions draw from SML/NJ's generator or talk to other programs, directly or through
        other functions (`impure`, `impure_via`), and which are `CS.ran()` under another name (`ran_aliases`)."""
        # A user's own 'normal' or 'uniform' (an enumeration constant, say) is not the library function.
        # The distributions of CPN Tools' library that simulate draws are left to the front end, which warns
        # (lint) and refuses them in explore and check, at each call, naming the distribution.
        self.impure = set(ml.RANDOM_FUNCTIONS) - user_names - set(DISTRIBUTIONS)
        self.impure_via: dict[str, str] = {}  # a function -> the random function it calls
        # `fun DEL() = NetDelay.ran();`: a call DEL() is written NetDelay.ran(), which the engine explores
        # as a choice of every value; inside a function it would be one random draw.
        self.ran_aliases: dict[str, str] = {}
        for name, body in funs:
            m = re.fullmatch(r"\s*\(\s*\)\s*=\s*([A-Za-z][\w']*\.ran)\s*\(\s*\)\s*;?\s*", body)
            if m:
                self.ran_aliases[name] = m.group(1) + "()"
        library = set(self.impure)
        # the SML/NJ random generator (`Random.randRange (1, 36) gen`) and the libraries that talk to other
        # programs or files (`ConnManagementLayer.openConnection`): the functions that use them cannot be
        # part of a state space either
        for _name, body in funs:
            for n, _ in ml.names(body):
                if n in DISTRIBUTIONS:  # SML/NJ's Random.rand, Random.randRange, ...: as the distributions
                    continue
                if n in SIMULATION_ONLY:  # text output, the machine's clock: simulated, refused by explore
                    continue
                if n in sml_basis.FUNCTIONS:  # OS.Path.concat: a function of its arguments
                    continue
                if n.split(".")[0] in ml.RANDOM_STRUCTURES or n.split(".")[0] in ml.SIDE_EFFECT_NAMES:
                    library.add(n)
        self.impure |= library
        changed = True
        while changed:  # transitive closure: a function that calls a random one is random
            changed = False
            for name, body in funs:
                used = {n for n, _ in ml.names(body)} - {name}  # a recursive call names no new cause
                if name not in self.impure and used & self.impure:
                    # the distribution itself where the function calls one, else a function that does
                    self.impure_via[name] = sorted(used & library)[0] if used & library else sorted(used & self.impure)[0]
                    self.impure.add(name)
                    changed = True

    def _scan_code_refs(self) -> None:
        """Reference variables that a code segment assigns and only that transition's output arcs and delay read.

        CPN Tools runs a code segment's action after the input arcs and before the output arcs, so in
        `action execTime_1 := round (...)` with `c@+(!execTime_1)` on an output arc of the same transition
        the variable carries no value from one occurrence to the next: it is an output variable of the code
        segment, bound in a `let` around the inscriptions that read it (the generated process models).
        """
        self.code_assigns: dict[str, dict[str, tuple[str, int]]] = {}  # transition id -> ref -> (expr, offset)
        for tr in self.cpnet.iter("trans"):
            assigns = _code_assignments(tr.child_text("code"))
            if assigns and all(self._pure(e) for e, _ in assigns.values()):
                self.code_assigns[tr.attrs.get("id", "?")] = assigns
        assigned_by_code = {x for a in self.code_assigns.values() for x in a}
        if not assigned_by_code:
            self.code_refs: set[str] = set()
            return
        gb = self.cpnet.find("globbox")
        ok = assigned_by_code - self._read_elsewhere(assigned_by_code, gb)
        # and it is assigned nowhere else (no `x :=` outside those code segments)
        elsewhere = [t.text for t in self.cpnet.iter("text") if t.text not in
                     {tr.child_text("code") for tr in self.cpnet.iter("trans")
                      if tr.attrs.get("id", "?") in self.code_assigns}]
        elsewhere += [m.text for m in self.cpnet.iter("ml")]
        for t in elsewhere:
            ok -= ml.assigned_refs(t)
        globrefs = {el.find("id").text.strip() for el in (self._all_decl_elements(gb) if gb is not None else [])
                    if el.tag == "globref" and el.find("id") is not None}
        self.code_refs = ok & (set(self.globrefs_refused) | globrefs)
        for tid in list(self.code_assigns):
            if not set(self.code_assigns[tid]) <= self.code_refs:
                del self.code_assigns[tid]

    def _read_elsewhere(self, refs: set[str], gb: Element | None) -> set[str]:
        """The references of `refs` read (`!x`) other than by an output arc or the delay of a transition whose
        code segment assigns them: by a guard, a priority, a code segment, an input arc, an initial marking, a
        declaration, or a transition that does not assign them."""
        read: set[str] = set()
        for page in self.cpnet.findall("page"):
            for tr in page.findall("trans"):
                assigns = self.code_assigns.get(tr.attrs.get("id", "?"), {})
                for tag in ("cond", "priority", "code", "time"):
                    text = tr.child_text(tag)
                    read |= _reads(refs, _without_reads(assigns, text) if tag == "time" else text)
            for a in page.findall("arc"):
                te = a.find("transend")
                assigns = self.code_assigns.get(te.attrs.get("idref", "") if te is not None else "", {})
                text = a.child_text("annot")
                output = a.attrs.get("orientation", "").strip().lower() == "ttop"
                read |= _reads(refs, _without_reads(assigns, text) if output else text)
            for pl in page.findall("place"):
                read |= _reads(refs, pl.child_text("initmark"))
        for el in self._all_decl_elements(gb) if gb is not None else []:
            if el.tag == "ml":
                read |= _reads(refs, el.text)
        return read

    def _pure(self, text: str) -> bool:
        """True if CPN ML text draws no random value, has no side effect and uses no reference variable, directly
        or through the declared functions it calls: evaluating it twice gives one value."""
        seen: set[str] = set()
        todo = [text]
        while todo:
            t = todo.pop()
            clean = ml.strip_comments(t)
            if ":=" in clean or re.search(r"!\s*[A-Za-z(]", clean):
                return False
            for n, _ in ml.names(t):
                head = n.split(".")[0]
                if n in sml_basis.FUNCTIONS:
                    continue
                if (n in DISTRIBUTIONS or n in SIMULATION_ONLY or n in ml.RANDOM_FUNCTIONS or n.endswith(".ran")
                        or head in ml.SIDE_EFFECT_NAMES or head in ml.RANDOM_STRUCTURES or n in ml.SIDE_EFFECT_NAMES
                        or head == "TextIO"):
                    return False
                if n in self.fun_bodies and n not in seen:
                    seen.add(n)
                    todo += self.fun_bodies[n]
        return True

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
                m = CODE_RE.match(ml.strip_comments(code)) if code else None
                # bound to outputs (not `CS.output (...)` in an action), or kept as an action that assigns
                # references
                if (m is not None and m.group("out")) or tr.attrs.get("id", "?") in self.kept_actions:
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
                heads = {name for name, _ in ml.declared_functions(el.text)} | ml.datatype_names(el.text)
                mls.append((el, heads, words(el.text)))
            elif el.tag == "use":  # a used file is always read: the declarations it names are needed
                needed |= words(self._use_file(el)[4] or "")
        changed = True
        while changed:
            changed = False
            for el, heads, used in mls:
                if id(el) not in self.needed_ml and heads & needed:
                    self.needed_ml.add(id(el))
                    needed |= used
                    changed = True
        self.needed_names = needed  # a globref the net never names is left out
    def _impure_chain(self, n: str) -> list[str]:
        """`n`, the function it calls that makes it impure, and so on to the library function."""
        chain = [n]
        while chain[-1] in self.impure_via and len(chain) < 10:
            chain.append(self.impure_via[chain[-1]])
        return chain

    def _side_effect_via(self, n: str) -> bool:
        """True if declared function `n` has a side effect through the functions it calls."""
        return n in self.impure_via and self._impure_chain(n)[-1].split(".")[0] in ml.SIDE_EFFECT_NAMES

    def _refs_of(self, text: str) -> tuple[set[str], set[str]]:
        """The names CPN ML text reads with `!` and assigns with `:=`, directly or through the functions the
        globbox declares."""
        read: set[str] = set()
        assigned: set[str] = set()
        seen: set[str] = set()
        stack = [text]
        while stack:
            t = stack.pop()
            clean = ml.strip_comments(t)
            read |= set(re.findall(r"!\s*\(?\s*([A-Za-z][\w']*)", clean))
            assigned |= ml.assigned_refs(t)
            for n, _ in ml.names(t):
                if n in self.fun_bodies and n not in seen:
                    seen.add(n)
                    stack.extend(self.fun_bodies[n])
        return read, assigned

    def _kept_actions(self) -> None:
        """The transitions whose code segment binds no output variable but must run all the same
        (`kept_actions`): it assigns a reference variable that the marking can depend on, that is one read by
        an inscription, by a code segment that binds output variables, or by another such action. A code
        segment that only logs (its references read by itself and other logging code) is still left out."""
        matter: set[str] = set()
        actions: dict[str, tuple[set[str], set[str]]] = {}
        for page in self.cpnet.findall("page"):
            texts = [pl.child_text("initmark") for pl in page.findall("place")]
            texts += [a.child_text("annot") for a in page.findall("arc")]
            for tr in page.findall("trans"):
                texts += [tr.child_text(tag) for tag in ("cond", "time", "priority")]
                code = tr.child_text("code")
                m = CODE_RE.match(ml.strip_comments(code)) if code else None
                if m is None:
                    continue
                if m.group("out"):
                    texts.append(code)
                elif tr.attrs.get("id", "?") not in self.code_assigns:
                    actions[tr.attrs.get("id", "?")] = self._refs_of(m.group("act"))
        for t in texts:
            matter |= self._refs_of(t)[0]
        self.kept_actions: set[str] = set()
        changed = True
        while changed:
            changed = False
            for tid, (read, assigned) in actions.items():
                if tid not in self.kept_actions and assigned & matter:
                    self.kept_actions.add(tid)
                    matter |= read
                    changed = True

    def _uses_refs(self, text: str, assigns: bool = False) -> bool:
        """Whether CPN ML text assigns a reference variable (`x := e`), or with `assigns` False also reads one
        (`!x`), directly or through the functions the globbox declares."""
        seen: set[str] = set()
        stack = [text]
        while stack:
            t = stack.pop()
            clean = ml.strip_comments(t)
            if ":=" in clean or (not assigns and re.search(r"!\s*[A-Za-z(]", clean)):
                return True
            for n, _ in ml.names(t):
                if n in self.fun_bodies and n not in seen:
                    seen.add(n)
                    stack.extend(self.fun_bodies[n])
        return False

    def _draws(self, text: str) -> bool:
        """Whether CPN ML text draws a random value (a distribution, `CS.ran()`, SML/NJ's `Random`), directly
        or through the functions the globbox declares."""
        seen: set[str] = set()
        stack = [text]
        while stack:
            for n, _ in ml.names(stack.pop()):
                if n in self.fun_bodies:
                    if n not in seen:
                        seen.add(n)
                        stack.extend(self.fun_bodies[n])
                elif (n in ml.RANDOM_FUNCTIONS or n in DISTRIBUTIONS or n.endswith(".ran")
                      or n.split(".")[0] in ml.RANDOM_STRUCTURES):
                    return True
        return False

    def _refuse_random(self, text: str, origin: Origin, what: str, effects: bool = True,
                       finite: bool = False) -> bool:
        """Refuse text that draws random values from a distribution, or (with `effects`) calls a function with
        side effects; True if refused. With `finite`, a direct call of `discrete` or `bernoulli` is left to the
        front end, which explores it as a choice where it can (an output arc, a delay)."""
        for n, _ in ml.names(text):
            if finite and n in ml.FINITE_DRAWS and n not in self.impure_via:
                continue
            if n in self.impure:
                chain = self._impure_chain(n)
                effect = chain[-1].split(".")[0] in ml.SIDE_EFFECT_NAMES
                if effect and not effects:
                    continue
                kind = ("a side effect (input, output or communication with other programs)" if effect
                        else "SML/NJ's random generator" if chain[-1].split(".")[0] in ml.RANDOM_STRUCTURES
                        else "a random distribution function")
                why = ((f"'{n}' is {kind}" if effect else f"'{n}' draws a random value") if len(chain) == 1
                       else f"'{n}' calls " + ", which calls ".join(f"'{c}'" for c in chain[1:]) + f", {kind}")
                if effect:
                    self.error(origin, f"{what} uses {n}: {why}; its value is not a function of the marking",
                               hint="Compute the value with pure CPN ML, or keep the side effect in a code segment "
                                    "that binds no output variable (it is then left out).")
                    return True
                self.error(origin, f"{what} uses {n}: {why}; a net that does has no deterministic state space",
                           hint="Replace the distribution by a finite choice, e.g. a colour set "
                                "'colset D = int with 1..5;' and 'D.ran()', which becomes a choice of every value.")
                return True
        return False

    def _rewrite_globrefs(self, text: str) -> str:
        for name in self.globref_consts:
            text = re.sub(r"!\s*" + re.escape(name) + r"\b", name, text)
        return text

    def _unclosed(self, text: str, origin: Origin) -> bool:
        """E0102 where a comment or a string of the CPN ML text at `origin` is never closed."""
        found = ml.unclosed(text)
        if found is None:
            return False
        line, col = self._file_position(origin.line, origin.col, text[:found[0]])
        kind = found[1]
        hint = ("Close it with '*)': everything from this '(*' to the end of the text is inside the comment."
                if kind == "comment" else "Close the string with '\"' on the same line.")
        self.errors.append(Diagnostic("E0102", f"the {kind} opened at {self.path}:{line}:{col} is never "
                                      f"closed (in {origin.describe()})", Span(self.path, line, col),
                                      hint=hint, params={"kind": kind}))
        return True

    def _file_position(self, line: int, col: int, before: str) -> tuple[int, int]:
        """The position in the file of the character after `before`, the text of an element from (line, col):
        an entity ('&gt;') of the file is one character of the text."""
        lines = getattr(self, "raw_lines", None) or []
        for ch in before:
            if ch == "\n":
                line, col = line + 1, 1
                continue
            raw = lines[line - 1] if 0 < line <= len(lines) else ""
            if col - 1 < len(raw) and raw[col - 1] == "&" and ";" in raw[col - 1:col + 10]:
                col = raw.index(";", col - 1) + 2
            else:
                col += 1
        return line, col

    def _inscription(self, text: str, origin: Origin, what: str) -> str:
        """Check and prepare one inscription (guard, arc, delay, initial marking)."""
        if self._unclosed(text, origin):
            return text
        self._refuse_random(text, origin, what, finite=True)
        # '@++' (a real-valued delay) is left to the front end: simulate runs it, explore and check refuse it
        for name, ran in self.ran_aliases.items():
            text = re.sub(r"\b" + re.escape(name) + r"\s*\(\s*\)", ran, text)
        return self._rewrite_globrefs(text)

    # -- declarations ----------------------------------------------------------------------------

    def _decl_items(self, node: Element) -> list[tuple[str, Element]]:
        """The globbox in order, blocks flattened: ("block", block) before its elements, ("decl", element)."""
        items: list[tuple[str, Element]] = []
        for c in node.children:
            if c.tag == "block":
                items.append(("block", c))
                items += self._decl_items(c)
            else:
                items.append(("decl", c))
        return items

    @staticmethod
    def _top_names(el: Element) -> set[str]:
        """The names a globbox element declares at the top level."""
        if el.tag == "ml":
            return {n for n, _ in ml.declared_functions(el.text)} | ml.datatype_names(el.text)
        if el.tag in ("color", "globref"):
            idel = el.find("id")
            return {idel.text.strip()} if idel is not None else set()
        return set()

    def _forward_order(self, items: list[tuple[str, Element]]) -> list[tuple[str, Element]]:
        """Put an ML declaration that names a value declared only further down right after that declaration.

        CPN Tools checks the globbox by dependency, not in the order it is drawn: the XPDL converter appends
        `val startDate = Date.date {...}` at the end of the globbox, below the functions that use it. A name
        declared above as well (shadowed), or bound inside the declaration itself, keeps the order as written.
        """
        order = list(items)
        # each element's names and text read once: the passes below compare every pair of declarations
        # (`lint` of the corpus's LEACH-HOP model, 71 ML declarations: 18.7 s reading them for each pair,
        # 2.7 s so, measured side by side)
        top = {id(el): self._top_names(el) for kind, el in order if kind == "decl"}
        texts = {id(el): ml.strip_comments(el.text)
                 for kind, el in order if kind == "decl" and el.tag == "ml"}
        for _ in range(len(order)):
            moved = False
            declared: set[str] = set()
            for i, (kind, el) in enumerate(order):
                if kind != "decl":
                    continue
                if el.tag == "ml":
                    text = texts[id(el)]
                    # a library name (`filter`) that a later declaration redeclares is the library's here
                    used = {part for n, _ in ml.names(text) for part in n.split(".")} - declared - _LIBRARY_NAMES
                    target = None
                    for j in range(i + 1, len(order)):
                        k2, el2 = order[j]
                        if k2 != "decl":
                            continue
                        later = (top[id(el2)] & used) - top[id(el)]
                        later = {n for n in later if not re.search(
                            r"(?<![\w'.])(?:val|fun|and|fn|rec|let)\s+(?:\(\s*)?" + re.escape(n) + r"(?![\w'])", text)
                            and not re.search(r"\bfun\s+[A-Za-z][\w']*\s*\([^)]*(?<![\w'])" + re.escape(n)
                                              + r"(?![\w'])", text)}
                        if later:
                            target = j
                    if target is not None:
                        order.insert(target, order.pop(i))  # after the last declaration it needs
                        moved = True
                        break
                declared |= top[id(el)]
            if not moved:
                break
        return order

    def _decls(self, node: Element, block: str | None = None) -> None:
        for kind, c in self._forward_order(self._decl_items(node)):
            if kind == "block":
                idel = c.find("id")
                name = idel.text.strip() if idel is not None else ""
                self.out.raw(f"(* block {name} *)" if name else "(* block *)")
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
            elif c.tag == "errordecl":
                # the Design/CPN converter's declarations it could not convert: CPN Tools cannot check them
                first = _clean(c.text).split("\n", 1)[0]
                self.error(c, f"the declarations were written for Design/CPN and not converted ('{_short(first)}' "
                           "in <errordecl>): CPN Tools cannot check them either",
                           hint="Open the net in CPN Tools and rewrite the declarations in CPN ML ('color' becomes "
                                "'colset', 'declare' clauses go), then save it.")

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
        self.out.stmt([(f"colset {ml.ml_ident(name)} = {body};", None)], origin)

    def _color_body(self, el: Element) -> str | None:
        """The CPN ML text of a structured colour set, or None if its kind is not recognised."""
        kinds = [c for c in el.children if c.tag not in ("id", "layout", "timed", "declare")]
        if len(kinds) != 1:
            return None
        k = kinds[0]
        build = _COLOR_KINDS.get(k.tag)
        return build(k, k.find("with")) if build is not None else None

    def _var(self, el: Element) -> None:
        t = el.find("type")
        tname = t.find("id").text.strip() if t is not None and t.find("id") is not None else None
        names = [c.text.strip() for c in el.findall("id")]
        origin = self._origin(el, None, "variable declaration")
        if tname is None or not names:
            layout = el.find("layout")
            if layout is not None and layout.text.strip():
                text = _clean(layout.text)
                m = re.match(r"\s*var\s+([^:]*):", text)
                self.var_names.update(v.strip() for v in (m.group(1).split(",") if m else []))
                self.out.stmt([(text if text.endswith(";") else text + ";", None)], origin)
                return
            self.error(el, f"variable declaration {origin.element} has no colour set or no name")
            return
        self.var_names.update(names)
        self.out.stmt([(f"var {', '.join(names)} : {tname};", None)], origin)

    def _ml(self, el: Element, text: str | None = None, at: Origin | None = None) -> None:
        pruned = text is None and id(el) not in self.needed_ml
        own = text is None  # the element's own text: positions in it are positions in the file
        text = _clean(el.text if text is None else text)
        if not text:
            return
        if own and el.text:
            raw = el.text.replace("\r\n", "\n")
            at = _text_origin_from(el.text_line, el.text_col, raw[: len(raw) - len(raw.lstrip())],
                                   self._origin(el, None, "declaration"))
            if self._unclosed(text, at):
                return
        alias = re.fullmatch(r"\s*fun\s+([A-Za-z][\w']*)\s*\(\s*\)\s*=\s*[A-Za-z][\w']*\.ran\s*\(\s*\)\s*;?\s*",
                             ml.strip_comments(text))
        if alias and alias.group(1) in self.ran_aliases:
            # `fun DEL() = NetDelay.ran()`: every call is written NetDelay.ran() (a choice of every value where
            # it is one); the function itself would be one random draw
            self.declared.add(alias.group(1))
            self.out.raw(f"(* declaration {el.attrs.get('id', '?')} ({alias.group(1)}() = "
                         f"{self.ran_aliases[alias.group(1)]}) at line {el.line}: written out where it is called *)")
            return
        refs = re.findall(r"\bval\s+([A-Za-z][\w']*)\s*=\s*ref\b", ml.strip_comments(text))
        if refs and set(refs) <= getattr(self, "code_refs", set()) and re.fullmatch(
                r"(?:\s*val\s+[A-Za-z][\w']*\s*=\s*ref\b[^;]*;?)+\s*", ml.strip_comments(text)):
            self.out.raw(f"(* declaration {el.attrs.get('id', '?')} ({', '.join(refs)}) at line {el.line}: "
                         "assigned by code segments and read by the output arcs of the same transitions: "
                         "an output variable of each *)")
            return
        if refs and any(r in self.globref_consts for r in refs):  # `val x = ref 0` never assigned: a constant
            text = re.sub(r"(\bval\s+([A-Za-z][\w']*)\s*=\s*)ref\b",  # blanks keep the columns
                          lambda m: m.group(1) + "   " if m.group(2) in self.globref_consts else m.group(0), text)
        if pruned:
            heads = [name for name, _ in ml.declared_functions(text)]
            what = ", ".join(heads) if heads else _short(text, 30)
            self.out.raw(f"(* declaration {el.attrs.get('id', '?')} ({what}) at line {el.line}: not used by the "
                         "net, left out *)")
            return
        origin = self._origin(el, None, "declaration")
        if at is not None:  # the text of a `use`d file, from its start
            origin = at
        elif el.text:
            origin = Origin(el.text_line, el.text_col, origin.element, None, origin.what)
            raw = el.text.replace("\r\n", "\n")
            lead = raw[: len(raw) - len(raw.lstrip())]
            if lead:
                origin = _text_origin_from(el.text_line, el.text_col, lead, origin)

        for name, _ in ml.declared_functions(text):
            self.declared.add(name)
        for name, ran in self.ran_aliases.items():
            text = re.sub(r"(?<![\w'.])" + re.escape(name) + r"\s*\(\s*\)", ran, text)
        text = ml.separate_declarations(self._rewrite_globrefs(ml.single_semicolons(text)))
        if not ml.strip_comments(text).rstrip().endswith(";"):  # `val x = 1; (* ... *)` has its ';'
            text += ";"
        self.out.stmt([(text, origin)], origin)

    def _globref(self, el: Element) -> None:
        idel = el.find("id")
        name = idel.text.strip() if idel is not None else "?"
        mlel = el.find("ml")
        expr = _clean(mlel.text) if mlel is not None else ""
        origin = self._origin(el, None, f"reference variable '{name}'")
        if name in getattr(self, "code_refs", set()):
            self.out.raw(f"(* globref {name} ({origin.element}): assigned by code segments and read by the output "
                         "arcs of the same transitions: an output variable of each *)")
            return
        literal = re.fullmatch(r"~?\d+(?:\.\d+)?(?:[eE]~?\d+)?|\"[^\"]*\"|true|false|\(\)", expr) is not None
        if literal and name not in self.assigned:
            self.globref_consts[name] = expr
            self.out.raw(f"(* globref {name} = {expr} is never assigned: a constant *)")
            self.out.stmt([(f"val {name} = {expr};", None)], origin)
            self.declared.add(name)
            return
        self.globrefs_refused[name] = el
        if name not in getattr(self, "needed_names", set()):
            self.out.raw(f"(* globref {name} ({origin.element}) at line {el.line}: not used by the net, "
                         "left out *)")
            return
        # a reference variable: simulate runs the net, explore and check refuse it (docs/semantics.md)
        self.declared.add(name)
        at = (Origin(mlel.text_line, mlel.text_col, origin.element, None, origin.what) if mlel is not None
              else None)
        raw = (mlel.text or "").replace("\r\n", "\n") if mlel is not None else ""
        if at is not None and raw[: len(raw) - len(raw.lstrip())]:
            at = _text_origin_from(mlel.text_line, mlel.text_col, raw[: len(raw) - len(raw.lstrip())], at)
        self.out.stmt([(f"val {name} = ref (", None), (expr, at), (");", None)], origin)

    def _string_vals(self) -> dict[str, str]:
        """The string constants of the globbox (`val buildpath = "c:/work/";`), for `use (buildpath^"x.sml")`."""
        found: dict[str, str] = {}
        gb = self.cpnet.find("globbox")
        for el in self._all_decl_elements(gb) if gb is not None else []:
            if el.tag == "ml":
                for m in re.finditer(r'\bval\s+([A-Za-z][\w\']*)\s*=\s*((?:' + _STRING + r'|[A-Za-z][\w\']*)'
                                     r'(?:\s*\^\s*(?:' + _STRING + r'|[A-Za-z][\w\']*))*)\s*;',
                                     ml.strip_comments(el.text)):
                    value = self._string_expr(m.group(2), found)
                    if value is not None:
                        found[m.group(1)] = value
        return found

    @staticmethod
    def _string_expr(text: str, vals: dict[str, str]) -> str | None:
        """The value of `"a" ^ name ^ "b"` over the string constants `vals`, or None."""
        out = ""
        for part in re.split(r"\s*\^\s*", text.strip().strip("()").strip()):
            if part.startswith('"') and part.endswith('"') and len(part) >= 2:
                out += _unescape(part[1:-1])
            elif part in vals:
                out += vals[part]
            else:
                return None
        return out

    def _use(self, el: Element) -> None:
        written, fname, here, candidates, content, full, why = self._use_file(el)
        origin = self._origin(el, None, f"use \"{fname}\"")
        if content is None:
            base = fname.replace("\\", "/").rsplit("/", 1)[-1]
            tried = "; tried " + ", ".join(f"'{os.path.relpath(c, here)}'" for c in dict.fromkeys(candidates)) \
                if len(candidates) > 1 else ""
            what = f"'{fname}'" if written.strip('"') == fname else f"'{fname}' ({written})"
            self.error(el, f"cannot read the ML file {what} named by a 'use' declaration: {why}{tried}",
                       hint=f"Put '{base}' next to the model ({here}).")
            return
        fname = os.path.relpath(full, here)
        self.out.raw(f"(* from use \"{fname}\" ({origin.element}) *)")
        # positions in the file's text are positions in that file (its name as the model's path gives it)
        content = content.replace("\r\n", "\n")
        shown = os.path.join(os.path.dirname(self.path), fname)
        start = Origin(1, 1, origin.element, None, f"'use \"{fname}\"'", file=shown)
        self._ml(el, content, _text_origin_from(1, 1, content[: len(content) - len(content.lstrip())], start))

    def _use_file(self, el: Element) -> tuple:
        """The file a `use` element names: (as written, its name, the model's folder, the paths tried, its
        text or None, the path read, why none could be read)."""
        mlel = el.find("ml")
        raw = _clean(mlel.text if mlel is not None else el.text)
        written = raw.strip().strip(";").strip()
        here = os.path.dirname(os.path.abspath(self.path))
        if re.fullmatch(_STRING, written):
            fname = literal = _unescape(written[1:-1])
        else:
            # `use (buildpath^"session/logging.sml")`: the path the constants give (often a folder of the
            # author's machine), else the literal part
            value = self._string_expr(written, self._string_vals())
            literal = "".join(_unescape(t[1:-1]) for t in re.findall(_STRING, written))
            fname = value if value is not None else literal or written
        # CPN Tools reads the path relative to the model; a path of the author's machine (`C:\\work\\x.sml`,
        # `c:/work/x.sml`) is tried as it is, then its literal part, then its file name, beside the model
        slashed = literal.replace("\\", "/")
        paths = [fname, fname.replace("\\", "/"), slashed.lstrip("/"), slashed.rsplit("/", 1)[-1]]
        candidates = [os.path.join(here, p) for p in dict.fromkeys(paths) if p]
        content, full, why = None, None, ""
        for cand in candidates + [None]:
            if cand is None:  # the file name in another case (`Logging.SML`), beside the model
                name = slashed.rsplit("/", 1)[-1].lower()
                found = sorted(f for f in os.listdir(here) if f.lower() == name) if name and os.path.isdir(here) \
                    else []
                if not found:
                    break
                cand = os.path.join(here, found[0])
                candidates.append(cand)
            full = cand
            try:
                with open(full, encoding="utf-8", errors="replace") as f:
                    content = f.read()
                break
            except OSError as exc:
                why = exc.strerror
        return written, fname, here, candidates, content, full, why

    # -- pages -----------------------------------------------------------------------------------


def _code_assignments(code: str) -> dict[str, tuple[str, int]]:
    """The assignments `x := e; y := f` that are all of a code segment without output variables: reference
    -> (e as written, its offset in `code`); empty if the action is anything else."""
    if not code.strip() or "action" not in code:
        return {}
    clean = ml.strip_comments(code)
    m = re.match(r"\s*(?:input\s*(?:\([^)]*\)|[A-Za-z][\w']*)\s*;?)?\s*(?:output\s*\(\s*\)\s*;?)?\s*action\b",
                 clean)
    if not m:
        return {}
    body, start = clean[m.end():], m.end()
    assigns: dict[str, tuple[str, int]] = {}
    for part in re.finditer(r"[^;]+", body):
        a = re.fullmatch(r"(\s*)([A-Za-z][\w']*)\s*:=(\s*)(.*?)\s*", part.group(), re.S)
        if not a or not a.group(4) or ":=" in a.group(4) or a.group(2) in assigns:
            return {}
        offset = start + part.start() + a.start(4)
        assigns[a.group(2)] = (code[offset:start + part.start() + a.end(4)], offset)
    return assigns


def _reads(refs: set[str], text: str) -> set[str]:
    """The references of `refs` that `text` reads (`!x`)."""
    return {x for x in refs if re.search(r"!\s*" + re.escape(x) + r"\b", text)}


def _without_reads(refs, text: str) -> str:
    """`text` without its reads of `refs` (an output inscription of the transition that assigns them)."""
    return re.sub(r"!\s*(" + "|".join(map(re.escape, refs)) + r")\b", "", text) if refs else text


# -- colour sets: one function per kind of <color> element, (element, its <with> or None) -> CPN ML or None

def _ids(node: Element) -> list[str]:
    return [c.text.strip() for c in node.findall("id")]


def _mls(node: Element) -> list[str]:
    return [_clean(c.text) for c in node.findall("ml")]


def _simple_color(k: Element, w: Element | None) -> str | None:
    """unit, bool, real, intinf, time; `unit with student` (one colour, named: an enumeration of one
    constant) and `bool with (no, yes)`."""
    if w is None:
        return k.tag
    if k.tag == "unit" and _ids(w):
        return f"with {_ids(w)[0]}"
    if k.tag == "bool" and len(_ids(w)) == 2:
        return f"bool with ({', '.join(_ids(w))})"
    return None


def _int_or_string_color(k: Element, w: Element | None) -> str | None:
    if w is None:
        return k.tag
    lo_hi = _mls(w)
    if len(lo_hi) != 2:
        return None
    if k.tag == "int":
        return f"int with {lo_hi[0]}..{lo_hi[1]}"
    lengths = _mls(w.find("and")) if w.find("and") is not None else []  # `string with "a".."z" and 3..9`
    return f"string with {lo_hi[0]}..{lo_hi[1]}" + (f" and {lengths[0]}..{lengths[1]}" if len(lengths) == 2 else "")


def _index_color(k: Element, w: Element | None) -> str | None:
    b, i = _mls(k), _ids(k)
    return f"index {i[0]} with {b[0]}..{b[1]}" if len(b) == 2 and len(i) == 1 else None


def _record_color(k: Element, w: Element | None) -> str | None:
    fields = [_ids(f) for f in k.findall("recordfield")]
    if any(len(fi) != 2 for fi in fields):
        return None
    return "record " + " * ".join(f"{fi[0]} : {fi[1]}" for fi in fields)


def _list_color(k: Element, w: Element | None) -> str | None:
    i = _ids(k)
    if len(i) != 1:
        return None
    if w is None:
        return f"list {i[0]}"
    b = _mls(w)
    return f"list {i[0]} with {b[0]}..{b[1]}" if len(b) == 2 else None


def _union_color(k: Element, w: Element | None) -> str | None:
    parts = []
    for f in k.findall("unionfield"):
        fi = _ids(f)
        t = f.find("type")
        ti = _ids(t) if t is not None else fi[1:]
        parts.append(f"{fi[0]} : {ti[0]}" if ti else fi[0])
    return "union " + " + ".join(parts)


def _subset_color(k: Element, w: Element | None) -> str | None:
    i = _ids(k)
    by = k.find("by")
    if i and by is not None and _mls(by):
        return f"subset {i[0]} by {_mls(by)[0]}"
    if i and w is not None and _mls(w):
        return f"subset {i[0]} with {_mls(w)[0]}"
    return None


_COLOR_KINDS = {
    "unit": _simple_color, "bool": _simple_color, "intinf": _simple_color,
    "real": lambda k, w: k.tag if w is None else None, "time": lambda k, w: k.tag if w is None else None,
    "int": _int_or_string_color, "string": _int_or_string_color,
    "enum": lambda k, w: "with " + " | ".join(_ids(k)),
    "index": _index_color,
    "product": lambda k, w: "product " + " * ".join(_ids(k)),
    "record": _record_color,
    "list": _list_color,
    "union": _union_color,
    "alias": lambda k, w: _ids(k)[0] if len(_ids(k)) == 1 else None,
    "subset": _subset_color,
}
