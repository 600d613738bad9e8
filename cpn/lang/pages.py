"""Checking the net structure of a model: pages (the top level and modules), places, transitions, arcs,
the binding of every transition variable, and module instances.

A mixin of `cpn.lang.typecheck.Checker`, which provides inference and diagnostics.
Imports `cpn.lang.*`, `cpn.values` and layer 0.
"""

from __future__ import annotations

import re

from cpn._util import did_you_mean
from cpn.arcs import ArcKind
from cpn.diagnostics import Span
from cpn.expr.binding import all_vars, children, guard_binder, guard_conjuncts, has_delay, pattern_vars
from cpn.expr.evaluate import run_deep
from cpn.lang import ast as A
from cpn.lang import types as T
from cpn.lang.builtins import RANDOM_BUILTINS, TIME_BUILTINS, MLError
from cpn.lang.checked import Abort, ArcInfo, Env, PageInfo, TransInfo
from cpn.lang.resolve import suggestion
from cpn.lang.symbols import Symbol
from cpn.values import colours as C

_NAME_PART = re.compile(r"[A-Za-z0-9_']*")


class PageChecks:
    """Checks of pages, transitions, arcs and instances (mixed into the Checker)."""

    def replace_ran(self, e):
        """`_replace_ran(e)`, where the checker marked a node to be replaced (`ran_marked`): else e is left
        as it is, without walking it."""
        return _replace_ran(e) if self.ran_marked else e

    def page(self, name: str, mdecl: A.ModuleDecl | None, decls: list[A.Decl]) -> PageInfo:
        params = []
        penv = {}
        if mdecl is not None:
            for pname, csname, span in mdecl.params:
                cs = self.lookup_colset(csname, span)
                sym = Symbol(pname, "param", self.cstypes.get(csname, T.TVar()), span, csname)
                params.append(sym)
                penv[pname] = sym
        page = PageInfo(name, mdecl, params)
        env = self.genv.child(penv)
        page.env = env  # type: ignore[attr-defined]
        for d in decls:
            if isinstance(d, A.PlaceDecl):
                # places and transitions have separate namespaces, as in CPN Tools
                if d.name in page.places:
                    first = page.places[d.name].span
                    self.error("E0202", f"place '{d.name}' is declared twice on page '{name}'", d.name_span,
                               notes=[f"first declared at {self._where(first)}"],
                               hint="Rename one of them; place names must be unique within a page.")
                    continue
                page.places[d.name] = d
                cs = self.lookup_colset(d.colset, d.colset_span)
                if cs is not None and d.init is not None:
                    self.check_marking(d, env)
            elif isinstance(d, A.TransDecl):
                if d.name in page.transitions:
                    first = page.transitions[d.name].decl.span
                    self.error("E0202", f"transition '{d.name}' is declared twice on page '{name}'", d.name_span,
                               notes=[f"first declared at {self._where(first)}"],
                               hint="Rename one of them; transition names must be unique within a net page.")
                    continue
                page.transitions[d.name] = TransInfo(d)
                page.order.append(d.name)
            elif isinstance(d, A.InstanceDecl):
                page.instances.append(d)
            elif isinstance(d, A.ModuleDecl):
                self.error("E0206", "modules cannot be declared inside modules", d.span,
                           hint="Declare every module at the top level of the file.")
            elif isinstance(d, A.NetHeader):
                self.error("E0206", "'net' is only allowed at the top level", d.span)
            elif isinstance(d, (A.ColsetDecl, A.VarDecl, A.ValDecl, A.FunDecl, A.SymmetryDecl)):
                self.error("E0206", "declarations inside a module are not supported; declare them at the top "
                           "level", d.span, hint="CPN ML declarations are global, as in CPN Tools.")
        for d in decls:
            if isinstance(d, A.ArcDecl):
                before = len(self.diags)
                self.arc(page, d, env)
                if len(self.diags) > before:
                    page.incomplete.update((d.src, d.dst))
        for tname in page.order:
            self.transition(page, page.transitions[tname], env)
        return page

    def check_marking(self, d: A.PlaceDecl, env: Env) -> None:
        elem = self.cstypes[d.colset]
        try:
            d.init = self.infer_ms(d.init, elem, env, f"the initial marking of place '{d.name}'")
            self.resolve_pending()
        except Abort:
            self.pending.clear()

    def arc(self, page: PageInfo, d: A.ArcDecl, env: Env) -> None:
        kind = d.kind
        if kind.endswith("?"):
            self.error("E0203", f"{kind[:-1]} arcs are written with '->' from the place to the transition", d.span)
            return
        # `arc place X -> trans X` says which of a place and a transition that share a name it joins
        src_p = d.src in page.places and d.src_kind != "trans"
        dst_p = d.dst in page.places and d.dst_kind != "trans"
        src_t = d.src in page.transitions and d.src_kind != "place"
        dst_t = d.dst in page.transitions and d.dst_kind != "place"
        for nm, sp, known, nkind in ((d.src, d.src_span, src_p or src_t, d.src_kind),
                                     (d.dst, d.dst_span, dst_p or dst_t, d.dst_kind)):
            if not known and nkind is not None:
                other = "transition" if nkind == "place" else "place"
                exists = nm in (page.transitions if nkind == "place" else page.places)
                self.error("E0201", f"unknown {'transition' if nkind == 'trans' else 'place'} '{nm}' on page "
                           f"'{page.name}'" + (f" ('{nm}' is a {other})" if exists else ""), sp,
                           hint=f"Write '{'trans' if other == 'transition' else 'place'} {nm}', or leave out the "
                                f"'{nkind}'." if exists else "Declare it, or check the spelling.", name=nm)
                return
            if not known:
                cands = {n: f"the transition '{n}' (declared at {self._where(t.decl.name_span)})"
                         for n, t in page.transitions.items()}
                cands.update({n: f"the place '{n}' (declared at {self._where(p.name_span)})"
                              for n, p in page.places.items()})
                self.error("E0201", f"unknown place or transition '{nm}' on page '{page.name}'", sp,
                           hint=suggestion(nm, cands) or "Declare it with 'place' or 'trans'.", name=nm)
                return
        fixed = ArcKind.written_from_the_place(kind)
        if fixed is not None:
            if not (src_p and dst_t):
                self.error("E0203", f"{'double' if kind == '<->' else kind} arcs go from a place to a transition: "
                           f"'{d.src}' -> '{d.dst}'", d.span, hint="Write the place first.")
                return
            place, trans = d.src, d.dst
            ak = fixed
        elif src_p and dst_t and src_t and dst_p:
            self.error("E0203", f"the arc '{d.src}' -> '{d.dst}' is ambiguous: both names are a place and a "
                       f"transition on page '{page.name}'", d.span,
                       hint=f"Say which end is the place: 'arc place {d.src} -> trans {d.dst}' or 'arc trans "
                            f"{d.src} -> place {d.dst}'.")
            return
        elif src_p and dst_t:
            place, trans, ak = d.src, d.dst, ArcKind.IN
        elif src_t and dst_p:
            place, trans, ak = d.dst, d.src, ArcKind.OUT
        else:
            what = "two places" if src_p else "two transitions"
            self.error("E0203", f"an arc must connect a place and a transition, but '{d.src}' and '{d.dst}' are "
                       f"{what}", d.span, hint="Arcs go from a place to a transition or back.")
            return
        pd = page.places[place]
        expr = d.expr
        info = page.transitions[trans]
        if expr is None:
            if ak.empties or ak.blocks:
                pass
            elif pd.colset in self.colsets and self.colsets[pd.colset].kind == "unit":
                expr = A.Const(d.span, (), "unit")
            else:
                # CPN Tools' syntax check leaves such an arc, and so its transition, unchecked: the transition
                # cannot occur there either (cpntools.org, "Syntax checking" and "Arc inscriptions")
                self.error("E0301", f"the arc between '{place}' and '{trans}' has no inscription, and place "
                           f"'{place}' holds {pd.colset}, not a unit colour set: CPN Tools does not accept it either",
                           d.span, place=place, transition=trans, colset=pd.colset,
                           hint=f"Only an arc of a unit place may go without an inscription (it means 1`()); CPN "
                                f"Tools leaves any other such arc and its transition unchecked, so the transition "
                                f"cannot occur. Write the tokens the arc moves, e.g. a variable of colour set "
                                f"{pd.colset}.")
                return
        elif ak.empties:
            self.error("E0301", "reset arcs take no inscription", d.span)
            return
        preempt = None
        if expr is not None and pd.colset in self.cstypes:
            elem = self.cstypes[pd.colset]
            sink: list = []
            self.ran_sink = sink if ak == "out" else None
            try:
                expr = self.infer_ms(expr, elem, env,
                                     f"the inscription of arc '{d.src}' -> '{d.dst}' (place '{place}' holds "
                                     f"{pd.colset})")
                self.resolve_pending()
            except Abort:
                self.pending.clear()
                return
            finally:
                self.ran_sink = None
            expr = self.replace_ran(expr)  # CS.ran() and the calls of functions that draw, written out
            self.take_choices(info, sink)
            if ak.reads and has_delay(expr):
                got = self._input_delay(d, ak, place, pd.colset, expr)
                if got is None:  # refused: the arc still binds its variables (no echo of the error)
                    if isinstance(expr, A.BinOp) and expr.op in ("@+", "@++"):
                        info.arcs.append(ArcInfo(d, ak, place, trans, expr.left))
                    return
                expr, preempt = got
            delay = _delay_node(expr) if ak == "out" else None
            if delay is not None and not self.colsets[pd.colset].timed:
                self._untimed_delay(f"arc '{d.src}' -> '{d.dst}'", place, pd.colset, delay.span)
                return
        info.arcs.append(ArcInfo(d, ak, place, trans, expr, preempt))

    def _untimed_delay(self, arc: str, place: str, colset: str, span) -> None:
        """E0301 at the delay of an arc whose place is not timed (CPN Tools: 'e @+ d' is a timed multiset,
        which an untimed place cannot hold, and an untimed token has no stamp to take early)."""
        self.error("E0301", f"the inscription of {arc} has a time delay, but place '{place}' holds {colset}, "
                   "which is not timed", span, place=place,
                   hint=f"Declare the colour set timed ('colset {colset} = ... timed;'), or remove the '@+': "
                        "tokens of an untimed place carry no time stamp.")

    def _input_delay(self, d: A.ArcDecl, ak: ArcKind, place: str, colset: str, expr: A.Expr):
        """(the inscription without its delay, the delay) of an input arc `e @+ k` (CPN Tools' preempting
        time stamps: the tokens may be removed up to k time units before their timestamps), or None after
        an error. k is a constant (numbers, 'val' constants, module parameters), evaluated when the net is
        lowered; it must end the inscription, delaying all of it, and the place must be timed."""
        where = f"arc '{d.src}' -> '{d.dst}'"
        top = expr if isinstance(expr, A.BinOp) and expr.op in ("@+", "@++") else None
        if ak != ArcKind.IN:
            what = "a double arc" if ak.produces else f"an {ak.value} arc"
            self.error("E0206", f"the inscription of {what} ('{place}' {ak.syntax} '{d.dst}') has a time delay",
                       (top or expr).span, place=place,
                       hint=f"Only an input arc may remove tokens ahead of their timestamps ('e @+ k'). For a "
                            f"double arc, write an input arc 'arc {place} -> {d.dst} : e @+ k;' and an output arc "
                            f"'arc {d.dst} -> {place} : e;' (with the output's own delay, if any)."
                       if ak.produces else "Remove the '@+': this arc removes no tokens.")
            return None
        if top is None or has_delay(top.left):
            self.error("E0206", f"the delay on input {where} does not end its inscription: an input arc "
                       "has one delay, for all the tokens it removes", expr.span, place=place,
                       hint="Write the delay once, at the end: 'e @+ k' (e.g. '1`x ++ 1`y @+ 5'); different "
                            "delays need different arcs.")
            return None
        if top.op == "@++":
            self.error("E0206", f"the input {where} has a real-valued delay '@++'", top.span, place=place,
                       hint="An input arc's delay is an integer: write '@+ k' with a constant k.")
            return None
        if not self.colsets[colset].timed:
            self._untimed_delay(where, place, colset, top.span)
            return None
        culprit = _not_fixed(top.right)
        if culprit is not None:
            uses = {"var": f"uses the variable '{culprit.name}'", "fun": f"calls the function '{culprit.name}'"}.get(
                culprit.ref.kind, f"reads the clock ('{culprit.name}')" if culprit.name in TIME_BUILTINS
                else f"draws a random value ('{culprit.name}')")
            self.error("E0206", f"the delay of input {where} is not a constant: it {uses}",
                       culprit.span, place=place, name=culprit.name,
                       hint="An input arc's delay (how long before their timestamps the tokens may be removed) "
                            "is fixed: write it with numbers, 'val' constants and module parameters "
                            "(e.g. 'val D = 5;' then 'x @+ D'); a 'val' may call a function.")
            return None
        return top.left, top.right

    def transition(self, page: PageInfo, info: TransInfo, env: Env) -> None:
        d = info.decl
        ok = True
        for i, g in enumerate(d.guards):
            t = self._guard(info, i, env)
            if t is None:
                ok = False
                continue
            pt = T.prune(t)
            if isinstance(pt, T.TCon) and pt.name == "list":
                self.unify(pt.args[0], T.BOOL, g.span, f"the guard of transition '{d.name}'")
            else:
                self.unify(t, T.BOOL, g.span, f"the guard of transition '{d.name}'")
        sink: list = []
        self.ran_sink = sink  # CS.ran() in the delay is a choice of every value, as on output arcs
        try:
            interval = isinstance(d.delay, A.ListE) and len(d.delay.items) == 2
            if interval:  # a time interval @+[a,b]
                try:
                    d.delay = self.replace_ran(self.time_interval(d.delay, env))
                    self.resolve_pending()
                except Abort:
                    self.pending.clear()
                    ok = False
            if isinstance(d.delay, A.BinOp) and d.delay.op == "@++":  # `@++ d`: a real-valued delay
                try:
                    self.real_delay(d.delay, env)
                    self.resolve_pending()
                    d.delay = self.replace_ran(d.delay.right)
                except Abort:
                    self.pending.clear()
                    ok = False
            elif d.delay is not None and not interval:
                t = self.infer_top(d.delay, env)
                if t is None:
                    ok = False
                else:
                    ok = self.unify(t, T.INT, d.delay.span, f"the delay of transition '{d.name}' (an integer)") and ok
                    d.delay = self.replace_ran(d.delay)
        finally:
            self.ran_sink = None
        self.take_choices(info, sink)
        if d.delay is not None and ok and d.name not in page.incomplete:
            self._check_delay_has_effect(page, info)
        if d.priority is not None:
            t = self.infer_top(d.priority, env)
            if t is None:
                ok = False
            else:
                self.unify(t, T.INT, d.priority.span, f"the priority of transition '{d.name}' (an integer)")
        if d.action is not None:
            ok = self._action(info, env) and ok
        if not ok:
            return
        # which variables are bound, and how
        used: set[str] = set()
        for a in info.arcs:
            all_vars(a.expr, used)
        for g in d.guards:
            all_vars(g, used)
        all_vars(d.delay, used)
        all_vars(d.priority, used)
        all_vars(d.action, used)
        # the choices, tried before a guard conjunct that reads them, and the action's outputs
        bound: set[str] = {v for v, _ in info.ran} | set(d.outputs)
        for a in info.arcs:
            if a.kind.consumes and a.expr is not None:
                bound |= pattern_vars(a.expr)
        conj = guard_conjuncts(d.guards)
        changed = True
        while changed:
            changed = False
            for c in conj:
                gb = guard_binder(c, bound)
                if gb is not None:
                    bound |= pattern_vars(gb[0])
                    changed = True
        free = []
        for v in sorted(used - bound):
            sym = self.variables[v]
            cs = self.colsets[sym.data]
            if cs.values() is not None:
                free.append(v)
                continue
            span = self._first_use(info, v)
            binder = next((a for a in info.arcs if a.kind.consumes and a.expr is not None), None)
            hint = (f"A variable must occur on an input arc of '{d.name}' (or be bound by its guard as "
                    f"'{v} = ...') before it can be used; only variables of small colour sets may be unbound. ")
            if binder is not None:
                bvars = sorted(pattern_vars(binder.expr))
                if bvars:
                    hint += (f"'{bvars[0]}' is bound by the arc from '{binder.place}' at "
                             f"{self._where(binder.decl.span)}.")
            self.error("E0302", f"variable '{v}' of transition '{d.name}' is not bound (colour set "
                       f"'{sym.data}' is too large to try every value)", span, hint=hint.strip(), name=v)
        # the action's outputs are bound when the binding element occurs: no part of the binding
        info.variables = sorted(used - set(d.outputs))
        info.free = free

    def _action(self, info: TransInfo, env: Env) -> bool:
        """Type the action of a transition (`output (x, y) action e`): e's value is the output variables',
        which must be declared variables that no input arc or guard binds. simulate runs it once per
        occurrence; no state space can hold its effects (W0106, E0206 in explore and check)."""
        d = info.decl
        t = self.infer_top(d.action, env)
        if t is None:
            return False
        types = []
        for name in d.outputs:
            sym = self.variables.get(name)
            if sym is None:
                self.error("E0201", f"the output variable '{name}' of transition '{d.name}' is not declared",
                           d.action.span, name=name, hint=f"Declare it ('var {name} : COLSET;'), as CPN Tools "
                           "requires of the output variables of a code segment.")
                return False
            types.append(sym.type)
        bound_before = set()
        for a in info.arcs:
            if a.kind.consumes and a.expr is not None:
                bound_before |= pattern_vars(a.expr)
        for g in d.guards:
            all_vars(g, bound_before)
        clash = sorted(bound_before & set(d.outputs))
        if clash:
            self.error("E0206", f"the output variable '{clash[0]}' of transition '{d.name}' also occurs on "
                       "an input arc or in the guard", d.action.span,
                       hint="An output variable gets its value from the action when the transition occurs: "
                            "use another variable on the input arcs and in the guard.", name=clash[0])
            return False
        if types:
            want = types[0] if len(types) == 1 else T.TTuple(types)
            names = ", ".join(d.outputs)
            if not self.unify(t, want, d.action.span, f"the action of transition '{d.name}' (the value of "
                              f"its output variable{'s' if len(types) > 1 else ''} {names})"):
                return False
        self.simulation_only(f"transition '{d.name}' has an action (a code segment that runs at each "
                             "occurrence)", d.action.span,
                             "For a state space, compute the values with pure CPN ML in the output arc "
                             "inscriptions ('let val x = e in ... end') and drop the action.", "action")
        return True

    def _guard(self, info: TransInfo, i: int, env: Env) -> T.Type | None:
        """The type of guard i of a transition; in a conjunct that binds output variables (`y = discrete (0,
        3)`, `output_binder`) the draws are choices."""
        g = info.decl.guards[i]
        sink: list = []
        self.ran_sink = sink if self.output_binder(g, info) else None
        try:
            t = self.infer_top(g, env)
        finally:
            self.ran_sink = None
        info.decl.guards[i] = self.replace_ran(g)
        self.take_choices(info, sink)
        if sink:  # the variables it binds are functions of its draws: simulate draws them with the draws
            left = g.left.items if isinstance(g.left, A.TupleE) else [g.left]
            self.draw_outputs.setdefault(info.decl.span, set()).update(x.name for x in left)
        return t

    def _check_delay_has_effect(self, page: PageInfo, info: TransInfo) -> None:
        """A transition delay applies to the tokens put on timed places. With no timed output place it has
        no effect: CPN Tools accepts it (its check only type-checks the delay), and so do we, with a warning."""
        d = info.decl
        outputs = [a for a in info.arcs if a.kind.produces]
        colsets = [self.colsets.get(page.places[a.place].colset) for a in outputs]
        if None in colsets or any(cs.timed for cs in colsets):
            return
        places = sorted({f"'{a.place}' ({page.places[a.place].colset})" for a in outputs})
        found = ("it has no output arcs" if not places else f"its output place {places[0]} is not timed"
                 if len(places) == 1 else f"its output places {', '.join(places)} are not timed")
        self.warn("W0102", f"transition '{d.name}' has a delay, but {found}: the delay has no effect "
                  "(CPN Tools accepts it too)", d.delay.span,
                  hint="A delay gives the tokens put on timed places a later time stamp: declare the colour set "
                  "of an output place timed ('colset C = ... timed;'), or remove the '@+'.", transition=d.name)

    def _first_use(self, info: TransInfo, v: str) -> Span:
        for a in info.arcs:
            if a.expr is not None and v in all_vars(a.expr):
                return _find_name_span(a.expr, v) or a.decl.span
        for g in info.decl.guards:
            sp = _find_name_span(g, v)
            if sp:
                return sp
        return info.decl.span

    def check_instances(self, page: PageInfo, pages: dict[str, PageInfo]) -> None:
        """Check the instances of a page, and replace each family of instances by its members."""
        seen: dict[str, A.InstanceDecl] = {}
        expanded: list[A.InstanceDecl] = []
        for inst in page.instances:
            if not isinstance(inst, A.InstanceFamilyDecl):
                if inst.name in seen:
                    self._instance_clash(page, inst.name, inst, seen[inst.name])
                    continue
                seen[inst.name] = inst
                expanded.append(inst)
                self._check_instance(page, pages, inst, page.env)
                continue
            sym = Symbol(inst.var, "param", T.INT, inst.var_span, "INT")
            members = self._family_members(page, inst, sym)
            self._check_instance(page, pages, inst, page.env.child({inst.var: sym}))
            for member in members:
                if member.name in seen:
                    self._instance_clash(page, member.name, member, seen[member.name])
                    continue
                seen[member.name] = member
                expanded.append(member)
        page.instances = expanded

    def _instance_clash(self, page: PageInfo, name: str, inst: A.InstanceDecl, first: A.InstanceDecl) -> None:
        def what(d):
            if isinstance(d, A.FamilyMember):
                return f"the instance {d.family.var} = {d.value} of the family '{d.family.name}' at " \
                       f"{self._where(d.family.name_span)}"
            return f"the instance at {self._where(d.name_span)}"
        family = inst.family if isinstance(inst, A.FamilyMember) else None
        self.error("E0202", f"instance '{name}' is declared twice on page '{page.name}'"
                   + (f" ({family.var} = {inst.value} of the family '{family.name}')" if family else ""),
                   inst.name_span, notes=[f"first declared as {what(first)}"],
                   hint="Instance names must be unique within a page: a family names its instances by its name "
                   "followed by the value (Slave1, Slave2, ...); rename the family or the other instance.",
                   name=name)

    def _family_members(self, page: PageInfo, fam: A.InstanceFamilyDecl, sym: Symbol) -> list[A.FamilyMember]:
        """The instances of a family, one per value of its domain (none after an error). The bounds of a
        range are integer constants, evaluated with the values given by --set."""
        where = f"the family '{_head(fam, self.model.source)}'"
        if fam.colset is not None:
            cs = self.lookup_colset(fam.colset, fam.colset_span)
            if cs is None:
                return []
            sym.type, sym.data = self.cstypes.get(fam.colset, T.TVar()), fam.colset
            values = cs.values()
            if values is None:
                self.error("E0204", f"colour set '{fam.colset}' of {where} is too large to enumerate",
                           fam.colset_span, hint="A family ranges over a small colour set ('int with 1..MAXS', "
                           "an enumeration) or over a range of integers: 'instance S[i : 1..MAXS] = ...'.")
                return []
            shown = fam.colset
            span = fam.colset_span
        else:
            bounds = []
            for which, e in (("lower", fam.low), ("upper", fam.high)):
                t = self.infer_top(e, page.env)
                if t is None or not self.unify(t, T.INT, e.span, f"the {which} bound of {where} (an integer)"):
                    return []
                culprit = _not_constant(e)
                if culprit is not None:
                    kind = "a parameter of module" if culprit.ref.kind == "param" else "a variable"
                    self.error("E0204", f"the {which} bound of {where} is not a constant: '{culprit.name}' is "
                               f"{kind}{f' {page.name!r}' if culprit.ref.kind == 'param' else ''}", culprit.span,
                               hint="The instances of a family are fixed before the net runs: write its bounds "
                               "with literals and 'val' constants (which --set and a scenario's [set] may "
                               "change), as in 'instance Slave[i : 1..MAXS] = ...'.", name=culprit.name)
                    return []
                try:
                    bounds.append(run_deep(self.ev.eval, e, {}))
                except (MLError, ArithmeticError, RecursionError) as exc:
                    self.error("E0401", f"evaluating the {which} bound of {where} failed: {exc}", e.span)
                    return []
            low, high = bounds
            values = list(range(low, high + 1))
            shown = f"{C.format_int(low)}..{C.format_int(high)}"
            span = Span(fam.low.span.file, fam.low.span.line, fam.low.span.col, fam.high.span.end_line,
                        fam.high.span.end_col)
            cs = None
        if not values:
            self.error("E0204", f"{where} has no instance: {shown} is empty", span,
                       hint="A family needs at least one value: check the bounds (and the values given with "
                       "--set or a scenario's [set]), or remove the family.")
            return []
        members = []
        for v in values:
            # an index value ph(3) names the instance by its number, as CPN Tools numbers page instances
            text = C.format_int(v) if cs is None or isinstance(cs, C.IndexCS) else cs.format(v)
            if not _NAME_PART.fullmatch(text):
                self.error("E0204", f"the value {text} of {where} does not make an instance name "
                           f"('{fam.name}{text}')", span,
                           hint="Instance names of a family are its name followed by the value: use a range "
                           "of non-negative integers, an index colour set or an enumeration.")
                return []
            members.append(A.FamilyMember(fam.span, f"{fam.name}{text}", fam.name_span, fam.module,
                                          fam.module_span, fam.args, fam.binds, family=fam, value=v,
                                          env={sym.uid: v}))
        return members

    def _check_instance(self, page: PageInfo, pages: dict[str, PageInfo], inst: A.InstanceDecl, env: Env) -> None:
        """The module, arguments and port bindings of one instance (of a family: `env` binds its variable)."""
        mod = pages.get(inst.module)
        if mod is None:
            cand = did_you_mean(inst.module, pages)
            self.error("E0201", f"unknown module '{inst.module}'", inst.module_span,
                       hint=f"Did you mean '{cand}'?" if cand else "Declare it with 'module NAME { ... }'.",
                       name=inst.module)
            return
        given = {}
        for aname, expr, span in inst.args:
            if aname in given:
                self.error("E0204", f"parameter '{aname}' is given twice", span)
                continue
            given[aname] = expr
            psym = next((p for p in mod.params if p.name == aname), None)
            if psym is None:
                cand = did_you_mean(aname, [p.name for p in mod.params])
                self.error("E0204", f"module '{mod.name}' has no parameter '{aname}'", span,
                           hint=f"Did you mean '{cand}'?" if cand else
                           f"Its parameters are: {', '.join(p.name for p in mod.params) or 'none'}.")
                continue
            t = self.infer_top(expr, env)
            if t is not None:
                self.unify(t, psym.type, expr.span, f"parameter '{aname}' of {_label(inst)}")
        for p in mod.params:
            if p.name not in given:
                self.error("E0204", f"{_label(inst)} does not give parameter '{p.name}' of module "
                           f"'{mod.name}'", inst.span, hint=f"Add '{p.name} = VALUE' in the parentheses.")
        bound_ports = set()
        for port, pspan, sock, sspan in inst.binds:
            pd = mod.places.get(port)
            if pd is None or pd.port is None:
                ports = [n for n, x in mod.places.items() if x.port]
                cand = did_you_mean(port, ports)
                self.error("E0204", f"module '{mod.name}' has no port '{port}'", pspan,
                           hint=f"Did you mean '{cand}'?" if cand else f"Its ports are: {', '.join(ports) or 'none'}.")
                continue
            if port in bound_ports:
                self.error("E0204", f"port '{port}' is bound twice", pspan)
                continue
            bound_ports.add(port)
            sd = page.places.get(sock)
            if sd is None:
                cand = did_you_mean(sock, page.places)
                self.error("E0201", f"unknown socket place '{sock}' on page '{page.name}'", sspan,
                           hint=f"Did you mean '{cand}'?" if cand else "Sockets are places of the page that "
                           "holds the instance.", name=sock)
                continue
            if sd.colset != pd.colset and (sd.colset in self.colsets and pd.colset in self.colsets):
                a, b = self.colsets[sd.colset], self.colsets[pd.colset]
                base = lambda c: c.base if isinstance(c, C.AliasCS) else c  # noqa: E731
                if base(a) is not base(b):
                    self.error("E0301", f"port '{port}' has colour set {pd.colset} but its socket '{sock}' has "
                               f"{sd.colset}", sspan, hint="A port and its socket must have the same colour set.")
        for n, pd in mod.places.items():
            if pd.port and n not in bound_ports:
                self.warn("W0101", f"port '{n}' of module '{mod.name}' is not bound in {_label(inst)}; "
                          "it is an ordinary place of the instance", inst.span)


def _head(fam: A.InstanceFamilyDecl, source: str) -> str:
    """`Slave[i : 1..MAXS]`, as written (on one line) or shortened."""
    start, end = fam.name_span, fam.colset_span if fam.colset is not None else fam.high.span
    if start.line == end.line and start.file == end.file and 0 < start.line <= source.count("\n") + 1:
        line = source.splitlines()[start.line - 1]
        text = line[start.col - 1:end.end_col]
        if text.startswith(fam.name):
            return text + "]"
    return f"{fam.name}[{fam.var} : ...]"


def _label(inst: A.InstanceDecl) -> str:
    if isinstance(inst, A.InstanceFamilyDecl):
        return f"the family of instances '{inst.name}[{inst.var} : ...]'"
    return f"instance '{inst.name}'"


def _first_name(e: A.Expr, wanted) -> A.Name | None:
    """The first name in e (depth first, left to right) for whose symbol `wanted` holds, or None."""
    stack = [e]
    while stack:
        x = stack.pop()
        if isinstance(x, A.Name) and x.ref is not None and wanted(x):
            return x
        stack.extend(reversed(children(x)))
    return None


def _not_constant(e: A.Expr) -> A.Name | None:
    """The first name in e that is a module parameter or a transition variable (None: e is a constant)."""
    return _first_name(e, lambda x: x.ref.kind in ("param", "var"))


def _not_fixed(e: A.Expr) -> A.Name | None:
    """The first name in e that makes it other than a constant of the net instance: a transition variable,
    the clock, a random draw (`CS.ran()`, `uniform`, ...) or a function of the model (which may read the
    clock or draw); None if there is none."""
    return _first_name(e, lambda x: x.ref.kind in ("var", "fun") or (x.ref.kind == "csop" and x.name.endswith(".ran"))
                       or (x.ref.kind == "builtin" and x.name in TIME_BUILTINS | RANDOM_BUILTINS))


def _delay_node(e):
    """The first '@+' of an output inscription, wherever it delays the tokens the arc produces."""
    stack = [e]  # depth first, left to right, without recursion (a sum may have thousands of terms)
    while stack:
        x = stack.pop()
        if isinstance(x, A.BinOp):
            if x.op in ("@+", "@++"):
                return x
            if x.op in ("++", "+++", "--"):
                stack += (x.right, x.left)
        elif isinstance(x, A.If):
            stack += (x.else_, x.then)
        elif isinstance(x, A.Case):
            stack.extend(b for _, b in reversed(x.rules))
        elif isinstance(x, A.Let):
            stack.append(x.body)
    return None


_RAN_FIELDS = ("fn", "arg", "left", "right", "operand", "cond", "then", "else_", "expr", "body", "subject")


def _ran_name(e):
    """The synthetic variable of an App node marked by CS.ran(), or None."""
    vsym = getattr(e, "ran_var", None) if isinstance(e, A.App) else None
    if vsym is None:
        return None
    if isinstance(vsym, A.Expr):  # a call of a function that draws, written out (infer.drawing_call)
        return _replace_ran(vsym)
    n = A.Name(e.span, vsym.name, ty=e.ty)
    n.ref = vsym
    return n


def _replace_ran(e):
    """Replace the App nodes marked by CS.ran() with their synthetic variables (iteratively: an expression
    may be a chain thousands of terms long)."""
    top = _ran_name(e)
    if top is not None:
        return top
    stack = [e]
    while stack:
        x = stack.pop()

        def fix(y):
            n = _ran_name(y)
            if n is not None:
                return n
            stack.append(y)
            return y
        if isinstance(getattr(x, "items", None), list):
            x.items = [fix(y) for y in x.items]
        if isinstance(x, A.RecordE):
            x.fields = [(label, fix(y)) for label, y in x.fields]
        for attr in _RAN_FIELDS:
            if isinstance(getattr(x, attr, None), A.Expr):
                setattr(x, attr, fix(getattr(x, attr)))
        if isinstance(x, A.Case):
            x.rules = [(p, fix(b)) for p, b in x.rules]
        if isinstance(x, A.Let):  # `let val p = discrete (0, 99) in ...` in a function written out
            for d in x.decls:
                if isinstance(d, A.ValDecl):
                    d.expr = fix(d.expr)
    return e


def _find_name_span(e, name: str) -> Span | None:
    stack = [e]  # depth first, left to right, without recursion
    while stack:
        x = stack.pop()
        if isinstance(x, A.Name) and x.name == name:
            return x.span
        stack.extend(reversed(children(x)))
    return None


