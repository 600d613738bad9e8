"""Layers import only what their allow-list names (STYLE.md 2.2, docs/internals.md): checked by walking
the imports of every module."""

import ast
import pathlib

ROOT = pathlib.Path(__file__).resolve().parent.parent / "cpn"

# the order of the layers, as docs/internals.md draws it: text -> lang -> net -> engine -> statespace ->
# checks -> properties -> gate -> report -> cli; an allow-list may only name earlier layers
ORDER = ["diagnostics", "_native", "_util", "arcs", "errors", "values", "expr", "lang", "net", "io", "engine", "model", "statespace",
         "checks", "properties", "gate", "report", "__init__", "cli", "__main__"]

FOUNDATION = {"diagnostics", "_util", "errors", "arcs"}

# what each top-level part of the package may import (besides itself)
ALLOWED: dict[str, set[str]] = {
    "diagnostics": set(),
    # the package's C and its build manifest, under every layer that builds C (the engine's generated code
    # and the state space's searches through cpn._util.cbuild)
    "_native": set(),
    "_util": {"_native"},
    "arcs": set(),
    "errors": {"diagnostics"},
    "values": FOUNDATION,
    # the one expression tree (nodes, evaluator, binding analysis, printer): under the language and the engine
    "expr": FOUNDATION | {"values"},
    "lang": FOUNDATION | {"values", "expr"},
    "net": FOUNDATION | {"values", "expr", "lang"},  # lowering and translation read the checked model
    "io": FOUNDATION | {"values", "expr", "lang", "net"},  # foreign formats to and from .cpnet text
    "engine": FOUNDATION | {"values", "expr", "net"},  # the Net is the engine's only input: never the language
    "model": FOUNDATION | {"values", "expr", "lang", "net", "io", "engine"},  # the loader: file to net and engines
    "statespace": FOUNDATION | {"values", "engine"},  # through the engine protocol only
    # the algorithms over an explored state space: they read the graph and the engine, never a property text
    "checks": FOUNDATION | {"values", "engine", "statespace"},
    # property texts are CPN ML, typed by the language's checker against the model's declarations and
    # compiled in the net's expression form; each kind is decided with an algorithm of checks
    # (the contest's property files are XML, read as cpn.io reads its formats)
    "properties": FOUNDATION | {"values", "expr", "lang", "net", "io", "engine", "statespace", "checks"},
    # the gate reads scenario files, loads the models they name and decides their properties
    "gate": FOUNDATION | {"values", "expr", "lang", "net", "model", "engine", "statespace", "checks", "properties"},
    # drawings of the net print its inscriptions (cpn.expr.pretty)
    "report": FOUNDATION | {"values", "expr", "net", "engine", "statespace", "checks", "properties", "gate"},
    "__init__": FOUNDATION | {"values", "expr", "lang", "net", "engine", "model", "statespace", "checks", "properties",
                              "gate", "report"},
    "cli": FOUNDATION | {"values", "io", "engine", "model", "statespace", "checks", "properties", "gate", "report",
                         "__init__"},
    "__main__": {"cli"},
}


def _part(modname: str) -> str | None:
    parts = modname.split(".")
    if parts[0] != "cpn":
        return None
    if len(parts) == 1:
        return "__init__"
    return parts[1].removesuffix(".py")


def _imports(source: str) -> list[str]:
    names = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            names += [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names.append(node.module)
    return names


def _problems(mod: str, own: str, source: str, allowed: dict[str, set[str]]) -> list[str]:
    """What module `mod` of part `own` imports beyond its allow-list."""
    if own not in allowed:
        return [f"{mod}: not assigned to a layer (add it to ALLOWED)"]
    out = []
    for name in _imports(source):
        other = _part(name)
        if other is not None and other != own and other not in allowed[own]:
            out.append(f"{mod} imports {name}: {own} may import only "
                       f"{', '.join(sorted(allowed[own])) or 'nothing of cpn'}")
    return out


def _is_private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def _private_uses(mod: str, own: str, source: str) -> list[str]:
    """What module `mod` of part `own` uses of another part's private names: a private name imported from
    it, a private member of a module, class or object that comes from it (an engine made by
    `compile_net`, a module such as `cpn.engine.clock`), and `getattr(engine, "_...")`."""
    tree = ast.parse(source)
    foreign: set[str] = set()  # local names (and `self.x` paths) of modules, classes and objects of other parts
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            other = _part(node.module)
            if other is None or other == own:
                continue
            if any(_is_private(p) for p in node.module.split(".")[2:]):
                out.append(f"{mod}:{node.lineno} imports from the private module {node.module}")
            for a in node.names:
                if _is_private(a.name):
                    out.append(f"{mod}:{node.lineno} imports the private {node.module}.{a.name}")
                foreign.add(a.asname or a.name)
        elif isinstance(node, ast.Import):
            for a in node.names:
                other = _part(a.name)
                if other is not None and other != own:
                    if any(_is_private(p) for p in a.name.split(".")[2:]):
                        out.append(f"{mod}:{node.lineno} imports the private module {a.name}")
                    foreign.add(a.asname or a.name.split(".")[0])
    assigns = [n for n in ast.walk(tree) if isinstance(n, ast.Assign)]
    grew = True
    while grew:  # what a foreign name makes or is copied to is foreign too
        grew = False
        for n in assigns:
            v = n.value.func if isinstance(n.value, ast.Call) else n.value
            if isinstance(v, ast.Attribute | ast.Name) and ast.unparse(v).split(".")[0] in foreign \
                    or ast.unparse(v) in foreign:
                for t in n.targets:
                    if isinstance(t, ast.Name | ast.Attribute) and ast.unparse(t) not in foreign:
                        foreign.add(ast.unparse(t))
                        grew = True
    engine_like = own != "engine"
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and _is_private(node.attr):
            owner = ast.unparse(node.value)
            if owner in foreign or owner.split(".")[0] in foreign - {"self"} \
                    or engine_like and (owner == "engine" or owner.endswith(".engine")):
                out.append(f"{mod}:{node.lineno} reads the private member {ast.unparse(node)} of another package")
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in (
                "getattr", "hasattr", "setattr") and len(node.args) >= 2 and isinstance(node.args[1], ast.Constant) \
                and isinstance(node.args[1].value, str) and _is_private(node.args[1].value):
            owner = ast.unparse(node.args[0])
            if engine_like and (owner == "engine" or owner.endswith(".engine")) or owner in foreign:
                out.append(f"{mod}:{node.lineno} probes {ast.unparse(node)}: declare it in the engine's protocol")
    return out


def _each_module(check, *args) -> list[str]:
    """The problems `check(module, package, source, *args)` finds in every module of the package."""
    problems = []
    for path in sorted(ROOT.rglob("*.py")):
        rel = path.relative_to(ROOT.parent).with_suffix("")
        problems += check(".".join(rel.parts), rel.parts[1], path.read_text(encoding="utf-8"), *args)
    return problems


def test_no_module_reaches_into_another_packages_private_members():
    problems = _each_module(_private_uses)
    assert not problems, "\n".join(problems)


def test_private_member_access_across_packages_fails():
    def bad(source, own="statespace"):
        return _private_uses(f"cpn.{own}.x", own, source)

    assert bad('plan = getattr(engine, "_plan", None)\n')
    assert bad('memo = getattr(self.engine, "_fire_memo", None)\n')
    assert bad("engine._plan.clear()\n")
    assert bad("from cpn.engine import clock\nclock._global_readers([])\n", "checks")
    assert bad("from cpn.model import _normalise_overrides\n", "checks")
    assert bad("from cpn.io._xml import parse_xml\n", "properties")
    assert bad("import cpn.io.pnml._terms\n", "properties")
    assert bad("from cpn.engine import compile_net\n"
               "class P:\n    def __init__(self, net):\n        self.ref = compile_net(net, reference=True)\n"
               "    def go(self, t, b):\n        ref = self.ref\n        return ref._env(t, b)\n", "report")
    # the public face, and a package's own private names, are fine
    assert not bad('groups = getattr(engine, "successor_groups", None)\nengine.forget_memo()\n')
    assert not bad("from cpn.statespace.store import _CDEF\nself._memo = {}\n")
    assert not bad("from cpn.statespace._memory import peak\n")
    assert not bad("from cpn._native.manifest import SOURCES\n", "engine")
    assert not bad("engine._plan.clear()\n", "engine")


def test_every_module_imports_only_what_its_layer_allows():
    problems = _each_module(_problems, ALLOWED)
    assert not problems, "\n".join(problems)


def test_allow_lists_point_only_downward():
    for part, allowed in ALLOWED.items():
        later = {a for a in allowed if ORDER.index(a) >= ORDER.index(part)}
        assert not later, f"{part} may import the later layers {sorted(later)}"


def test_an_engine_importing_the_language_fails():
    assert _problems("cpn.engine.x", "engine", "from cpn.lang import ast as A\n", ALLOWED)
    assert _problems("cpn.engine.x", "engine", "import cpn.lang.evaluate\n", ALLOWED)
    assert not _problems("cpn.engine.x", "engine", "from cpn.expr import nodes\n", ALLOWED)
    assert _problems("cpn.expr.x", "expr", "from cpn.lang import ast\n", ALLOWED)
    assert _problems("cpn.expr.x", "expr", "from cpn.engine import codegen\n", ALLOWED)
    assert _problems("cpn.statespace.x", "statespace", "from cpn.net import Net\n", ALLOWED)


def test_the_checks_the_property_language_and_the_gate_import_only_downward():
    # checks -> properties -> gate: the algorithms never read a property text, the property language never
    # reads a scenario file
    assert _problems("cpn.checks.x", "checks", "from cpn.properties.kinds import Check\n", ALLOWED)
    assert _problems("cpn.checks.x", "checks", "def f():\n    from cpn.gate import run_scenario\n", ALLOWED)
    assert _problems("cpn.checks.x", "checks", "from cpn.lang import ast\n", ALLOWED)
    assert _problems("cpn.properties.x", "properties", "from cpn.gate.scenario import Scenario\n", ALLOWED)
    assert _problems("cpn.properties.x", "properties", "from cpn.model import load\n", ALLOWED)
    assert _problems("cpn.gate.x", "gate", "from cpn.report import build_report\n", ALLOWED)
    assert not _problems("cpn.properties.x", "properties", "from cpn.checks.ctl import Kripke\n", ALLOWED)
    assert not _problems("cpn.gate.x", "gate", "from cpn.properties.spec import PropertySpec\n", ALLOWED)
    # inside the property language: the kinds come after the texts' compiler, the warnings after the kinds
    found = _inner_problems("properties", {"predicates": "from cpn.properties.kinds import Check\n",
                                           "kinds": "from cpn.properties.predicates import walk\n"},
                            MODULE_ORDER["properties"])
    assert any("predicates:1 imports kinds" in p for p in found) and any("circle" in p for p in found)
    found = _inner_problems("gate", {"scenario": "def f():\n    from cpn.gate.run import check\n", "run": ""},
                            MODULE_ORDER["gate"])
    assert any("scenario:2 imports run" in p for p in found)

# what the algorithms, the property language and the gate may import of the engine: its protocol, and the
# analysis of which of the net's functions read the clock (of the net's declarations, not of an engine)
ENGINE_DOOR = {"cpn.engine", "cpn.engine.protocol", "cpn.engine.clock"}


def _engine_imports(mod: str, own: str, source: str) -> list[str]:
    """Imports of the engine's modules beyond its door by a module of checks, properties or gate."""
    if own not in ("checks", "properties", "gate"):
        return []
    from cpn import engine

    out = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names = [node.module] if node.module != "cpn.engine" else \
                [f"cpn.engine.{a.name}" for a in node.names if a.name not in engine.__all__]
        elif isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        else:
            continue
        out += [f"{mod}:{node.lineno} imports {n}: the engine is reached through cpn.engine.protocol"
                for n in names if n.startswith("cpn.engine.") and n not in ENGINE_DOOR]
    return out


def test_the_checks_and_the_property_language_reach_the_engine_through_its_protocol():
    problems = _each_module(_engine_imports)
    assert not problems, "\n".join(problems)
    # what cpn.properties.predicates imported before the engine declared its predicate compiler
    assert _engine_imports("cpn.properties.x", "properties", "from cpn.engine.codegen import ExprCompiler\n")
    assert _engine_imports("cpn.properties.x", "properties", "from cpn.engine import runtime\n")
    assert not _engine_imports("cpn.properties.x", "properties", "from cpn.engine import Engine, clock\n")
    assert not _engine_imports("cpn.report.x", "report", "from cpn.engine.reference import ReferenceEngine\n")

# Inside a package: its modules bottom to top (docs/internals.md, "Inside the state space"). A module
# imports only modules before it in its package's list, at the top of the file or inside a function, so
# the package has no upward import and no import circle. A module missing from the list fails.
MODULE_ORDER: dict[str, list[str]] = {
    "statespace": ["_memory", "options", "store", "graph", "graphnative", "scc", "trace", "symmetry", "reduction",
                   "result", "native", "nativetimed", "threads", "parallel", "distributed", "chooser", "explore",
                   "sweep", "__init__"],
    "checks": ["verdict", "columns", "bounds", "liveness", "fairness", "ctl", "buchi", "ltl", "mcc", "__init__"],
    "properties": ["spec", "predicates", "kinds", "ltl", "build", "vacuity", "structure", "reduction", "symmetry", "contest",
                   "__init__"],
    "gate": ["scenario", "sweep", "run", "mutants", "mutation", "__init__"],
}


def _package_imports(package: str, source: str) -> list[tuple[str, int]]:
    """(module of `package`, line) for every import of one of its modules in `source`, wherever it is."""
    out = []
    prefix = f"cpn.{package}"
    tree = ast.parse(source)
    # an import only a type checker runs (`if TYPE_CHECKING:`) is not an import at run time
    typing_only = {id(n) for b in ast.walk(tree) if isinstance(b, ast.If) and getattr(b.test, "id", "") == "TYPE_CHECKING"
                   for n in ast.walk(b)}
    for node in ast.walk(tree):
        if id(node) in typing_only:
            continue
        names = []
        if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names = [node.module] + ([f"{node.module}.{a.name}" for a in node.names] if node.module == prefix else [])
        elif isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        for name in names:
            parts = name.split(".")
            if parts[:2] == ["cpn", package] and len(parts) >= 3:
                out.append((parts[2], node.lineno))
    return out


def _inner_problems(package: str, modules: dict[str, str], order: list[str]) -> list[str]:
    """Upward imports (against `order`) and import circles among `modules` (name -> source) of `package`."""
    out = [f"cpn.{package}.{m}: not in MODULE_ORDER[{package!r}] (add it where it belongs)"
           for m in modules if m not in order]
    graph: dict[str, set[str]] = {m: set() for m in modules}
    for m, source in modules.items():
        for other, line in _package_imports(package, source):
            if other not in modules or other == m:
                continue
            graph[m].add(other)
            if m in order and other in order and order.index(other) > order.index(m):
                out.append(f"cpn.{package}.{m}:{line} imports {other}, which comes later in {package}/")
    # a circle: a module that reaches itself again
    for start in graph:
        seen, todo = set(), list(graph[start])
        while todo:
            m = todo.pop()
            if m == start:
                out.append(f"cpn.{package}.{start} is on an import circle")
                break
            if m not in seen:
                seen.add(m)
                todo.extend(graph[m])
    return out


def test_no_upward_import_and_no_circle_inside_a_package():
    problems = []
    for package, order in MODULE_ORDER.items():
        modules = {p.stem: p.read_text(encoding="utf-8") for p in sorted((ROOT / package).glob("*.py"))}
        problems += _inner_problems(package, modules, order)
    assert not problems, "\n".join(problems)



def test_no_import_circle_inside_any_other_package():
    # the packages without a MODULE_ORDER of their own still have no import circle among their modules
    problems = []
    for folder in sorted(p for p in ROOT.iterdir() if p.is_dir() and any(p.glob("*.py"))):  # cli/ has no __init__
        if folder.name in MODULE_ORDER:
            continue
        modules = {p.stem: p.read_text(encoding="utf-8") for p in sorted(folder.glob("*.py"))}
        problems += [p for p in _inner_problems(folder.name, modules, list(modules)) if "circle" in p]
    assert not problems, "\n".join(problems)
    # what report/ had before the HTML page read the report model only for its types
    report = {"model": "def f():\n    from cpn.report.html import page\n",
              "html": "from cpn.report.model import Report\n"}
    assert any("circle" in p for p in _inner_problems("report", report, list(report)))
    typed = dict(report, html="from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from cpn.report.model import Report\n")
    assert not [p for p in _inner_problems("report", typed, list(typed)) if "circle" in p]

def test_an_upward_import_or_a_circle_inside_a_package_fails():
    order = ["low", "mid", "top"]
    fine = {"low": "", "mid": "from cpn.p.low import x\n", "top": "from cpn.p import low, mid\n"}
    assert not _inner_problems("p", fine, order)
    # a deferred import counts as much as one at the top of the file
    up = dict(fine, low="def f():\n    from cpn.p.top import y\n")
    assert any("low:2 imports top" in p for p in _inner_problems("p", up, order))
    assert any("circle" in p for p in _inner_problems("p", up, order))
    assert any("mid:1 imports top" in p for p in _inner_problems("p", dict(fine, mid="from cpn.p import top\n"), order))
    assert any("not in MODULE_ORDER" in p for p in _inner_problems("p", dict(fine, new=""), order))
    # what the state space had before its search chooser: native <-> explore, trace <-> symmetry
    before = {"native": "def rate():\n    from cpn.statespace.explore import HAND_OVER_RATE\n",
              "explore": "from cpn.statespace import native\n",
              "trace": "def t():\n    from cpn.statespace.symmetry import lifted_trace\n",
              "symmetry": "from cpn.statespace.trace import Step, Trace\n"}
    found = _inner_problems("statespace", before, MODULE_ORDER["statespace"])
    assert any("native:2 imports explore" in p for p in found) and any("trace:2 imports symmetry" in p for p in found)
    assert sum("circle" in p for p in found) == 4


def _capability_probes(mod: str, own: str, source: str) -> list[str]:
    """`getattr(engine, "<capability>")`, `hasattr(...)` on an engine outside the engine's package: a
    capability is looked up with `cpn.engine.protocol.capability` or `has`, which know only the declared
    ones."""
    from cpn.engine.protocol import CAPABILITIES

    if own == "engine":
        return []
    out = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in ("getattr", "hasattr") \
                and len(node.args) >= 2 and isinstance(node.args[1], ast.Constant) \
                and node.args[1].value in CAPABILITIES:
            owner = ast.unparse(node.args[0])
            if owner in ("engine", "eng") or owner.endswith(".engine"):
                out.append(f"{mod}:{node.lineno} probes {ast.unparse(node)}: use cpn.engine.protocol.capability "
                           "or has")
    return out


def test_no_module_probes_an_engines_capabilities_with_getattr():
    problems = _each_module(_capability_probes)
    assert not problems, "\n".join(problems)


def test_a_capability_probed_with_getattr_fails_and_an_undeclared_one_is_refused():
    import pytest

    from cpn.engine.protocol import capability, has

    assert _capability_probes("cpn.statespace.x", "statespace", 'g = getattr(engine, "successor_groups", None)\n')
    assert _capability_probes("cpn.report.x", "report", 'c = hasattr(self.engine, "place_view")\n')
    # required members, other objects, and the engine's own package are not probes of a capability
    assert not _capability_probes("cpn.statespace.x", "statespace", 'getattr(engine, "is_timed", False)\n')
    assert not _capability_probes("cpn.checks.x", "checks", 'getattr(store, "views", None)\n')
    assert not _capability_probes("cpn.engine.x", "engine", 'getattr(engine, "native_code", None)\n')

    class Bare:
        pass

    assert capability(Bare(), "native_code") is None and not has(Bare(), "place_view")
    with pytest.raises(ValueError, match="not a capability declared"):
        capability(Bare(), "native_cod")
