"""Lowering a checked model to a `Net`: instantiate modules, bind ports to sockets, merge fusion sets,
evaluate initial markings, translate inscriptions to `cpn.expr.nodes`. With `cpn.net.translate`, the only
place where `cpn.net` touches `cpn.lang`.
"""

from __future__ import annotations

from collections import defaultdict

from cpn.arcs import ArcKind
from cpn.diagnostics import Diagnostic
from cpn.errors import ModelError
from cpn.expr.evaluate import run_deep
from cpn.lang import ast as A
from cpn.lang.builtins import MLError
from cpn.lang.typecheck import CheckedModel, PageInfo
from cpn.net.model import ArcInstance, Net, PageInstance, PlaceInstance, TransitionInstance
from cpn.net.translate import Translator
from cpn.values.colours import outside
from cpn.values.multiset import TimedMultiset

MAX_INSTANCE_DEPTH: int = 64


class _Lowerer:
    def __init__(self, cm: CheckedModel):
        self.cm = cm
        self.places: list[PlaceInstance] = []
        self.transitions: list[TransitionInstance] = []
        self.counter: dict[str, int] = defaultdict(int)
        self.fusion: dict[str, int] = {}
        self.diags: list[Diagnostic] = []
        self.tr = Translator()
        self.instances: list[PageInstance] = []

    def error(self, code, msg, span, hint=None):
        d = Diagnostic(code, msg, span, hint=hint)
        if not any((x.code, x.message, x.span) == (code, msg, span) for x in self.diags):  # once, not per instance
            self.diags.append(d)

    def run(self) -> Net:
        self.instantiate(self.cm.top, {}, {}, [self.cm.top.name], None, None)
        if self.diags:
            raise ModelError(self.diags, {self.cm.model.file: self.cm.model.source})
        cm = self.cm
        variables = {name: self.tr.ref(sym) for name, sym in cm.variables.items()}
        globals_ = self.tr.globals(cm.model, cm.evaluator.globals)
        return Net(cm.net_name, self.places, self.transitions, cm.colsets, variables, globals_, cm.model.source,
                   cm.model.file, cm, self.instances)

    def initial(self, d: A.PlaceDecl, cs, env) -> dict:
        if d.init is None:
            return {}
        try:
            m = run_deep(self.cm.evaluator.eval, d.init, env)  # a deeply recursive function: deep stack
        except (MLError, ArithmeticError, RecursionError) as exc:
            self.error("E0401", f"evaluating the initial marking of place '{d.name}' failed: {exc}", d.init.span)
            return {}
        timed = cs.timed
        out: dict = {}
        items = m.items if isinstance(m, TimedMultiset) else [(v, n, 0) for v, n in m.items()]
        if not timed and any(delay for _, _, delay in items):
            self.error("E0301", f"the initial marking of place '{d.name}' has a time delay, but colour set "
                       f"{cs.name} is not timed", d.init.span,
                       hint="Remove the '@+' or declare the colour set with 'timed'.")
        for v, n, delay in items:
            if not cs.contains(v):
                self.error("E0303", f"the initial marking of place '{d.name}' contains {_fmt(cs, v)}, which is "
                           f"outside colour set {outside(cs, v)}", d.init.span,
                           hint=f"Use values of {cs.name}, or widen the colour set.")
                continue
            key = (v, delay) if timed else v
            out[key] = out.get(key, 0) + n
        return out

    def instantiate(self, page: PageInfo, params: dict, binds: dict[str, int], path: list[str], parent, decl) -> None:
        self.counter[page.name] += 1
        k = self.counter[page.name]
        local: dict[str, int] = {}
        me = PageInstance(len(self.instances), page.name, k, dict(params), local, {}, parent, [], decl)
        self.instances.append(me)
        if parent is not None:
            self.instances[parent].children.append(me.index)
        for name, d in page.places.items():
            iname = f"{page.name}'{name} {k}"
            cs = self.cm.colsets.get(d.colset)
            if d.port and name in binds:
                idx = binds[name]
                self.places[idx].aliases.append(iname)
                local[name] = idx
                continue
            if d.fusion is not None and d.fusion in self.fusion:
                idx = self.fusion[d.fusion]
                other = self.places[idx]
                if other.colour_set is not cs and other.colour_set.name != cs.name:
                    self.error("E0205", f"place '{name}' is in fusion set '{d.fusion}' with colour set {cs.name}, "
                               f"but '{other.name}' in the same set has {other.colour_set.name}", d.span,
                               hint="All places of a fusion set must have the same colour set.")
                if d.init is not None and self.initial(d, cs, params) != other.initial:
                    self.error("E0205", f"place '{name}' is in fusion set '{d.fusion}' with an initial marking "
                               f"different from that of '{other.name}'", d.init.span,
                               hint="The places of a fusion set are one place: give the initial marking once.")
                other.aliases.append(iname)
                local[name] = idx
                continue
            idx = len(self.places)
            self.places.append(PlaceInstance(idx, iname, page.name, name, k, cs, cs.timed,
                                             self.initial(d, cs, params), d.span))
            if d.fusion is not None:
                self.fusion[d.fusion] = idx
            local[name] = idx
        for tname in page.order:
            info = page.transitions[tname]
            d = info.decl
            tr = self.tr
            arcs = [ArcInstance(local[a.place], a.kind, tr.expr(a.expr), a.decl.span, _arc_label(a),
                                self.preemption(a, params)) for a in info.arcs]
            self.one_preemption(tname, arcs, info.arcs)
            variables = sorted(set(info.variables) | {v for v, _ in info.ran})
            free = sorted(set(info.free) | {v for v, _ in info.ran})
            me.transitions[tname] = len(self.transitions)
            self.transitions.append(TransitionInstance(
                len(self.transitions), f"{page.name}'{tname} {k}", page.name, tname, k, tr.exprs(d.guards),
                tr.expr(d.delay), tr.expr(d.priority), arcs, variables, free, dict(params), d.span,
                tr.expr(d.action), tuple(d.outputs)))
        for inst in page.instances:
            child = self.cm.modules[inst.module]
            if len(path) >= MAX_INSTANCE_DEPTH or inst.module in path:
                self.error("E0204", f"module '{inst.module}' instantiates itself (through "
                           f"{' -> '.join(path + [inst.module])})", inst.span,
                           hint="Module instances must form a tree.")
                continue
            cparams = {}
            env = {**params, **inst.env} if isinstance(inst, A.FamilyMember) else params  # the family's variable
            for aname, expr, _span in inst.args:
                psym = next((p for p in child.params if p.name == aname), None)
                if psym is None:
                    continue
                try:
                    cparams[psym.uid] = self.cm.evaluator.eval(expr, env)
                except (MLError, ArithmeticError) as exc:
                    self.error("E0401", f"evaluating parameter '{aname}' failed: {exc}", expr.span)
                    continue
                cs = self.cm.colsets.get(psym.data)
                if cs is not None and not cs.contains(cparams[psym.uid]):
                    self.error("E0303", f"parameter '{aname}' of instance '{inst.name}' is "
                               f"{_fmt(cs, cparams[psym.uid])}, outside colour set {cs.name}", expr.span)
            cbinds = {port: local[sock] for port, _, sock, _ in inst.binds if sock in local}
            self.instantiate(child, cparams, cbinds, path + [inst.module], me.index, inst)

    def preemption(self, a, params: dict) -> int:
        """The value of an input arc's delay `e @+ k` (0 without one): an integer constant, not negative."""
        if a.preempt is None:
            return 0
        where = f"the delay of input arc {_arc_label(a)}"
        try:
            k = run_deep(self.cm.evaluator.eval, a.preempt, params)
        except (MLError, ArithmeticError, RecursionError) as exc:
            self.error("E0401", f"evaluating {where} failed: {exc}", a.preempt.span)
            return 0
        if k < 0:
            self.error("E0301", f"{where} is {k}: it must not be negative", a.preempt.span,
                       hint="'e @+ k' on an input arc lets the transition remove the tokens up to k time units "
                            "before their timestamps (CPN Tools' preempting time stamps); k is 0 or more.")
            return 0
        return k

    def one_preemption(self, tname: str, arcs: list[ArcInstance], infos) -> None:
        """Refuse two arcs that remove tokens from one place for one transition with different delays: which
        tokens each may take would depend on the order the arcs are matched in."""
        first: dict[int, tuple] = {}
        for arc, info in zip(arcs, infos):
            if not arc.kind.consumes or arc.expr is None:
                continue
            seen = first.setdefault(arc.place, (arc, info))
            if seen[0].preemption != arc.preemption:
                span = (info.preempt or seen[1].preempt).span
                self.error("E0206", f"transition '{tname}' removes tokens from place '{info.place}' by two arcs "
                           f"with different delays ({seen[0].preemption} and {arc.preemption})", span,
                           hint="Give both arcs the same delay, or join them into one arc: 'e1 ++ e2 @+ k'"
                                + (" (a double arc takes its tokens with no delay)."
                                   if seen[0].kind.produces or arc.kind.produces else "."))


def _fmt(cs, v) -> str:
    try:
        return cs.format(v)
    except Exception:  # noqa: BLE001 - a value outside the colour set may not format
        return repr(v)


def _arc_label(a) -> str:
    if a.kind is ArcKind.OUT:
        return f"'{a.trans}' -> '{a.place}'"
    return f"'{a.place}' -> '{a.trans}'"


def lower(cm: CheckedModel) -> Net:
    """Flatten a checked model into a Net of place and transition instances."""
    return _Lowerer(cm).run()


__all__ = ["lower"]
