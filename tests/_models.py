"""The small models of the tests (tests/models/: local declarations, exceptions, lists as multisets, long
chains, records, recursion, branching options, a model-time bound, a model that reads the clock), their
state-space figures, and a CPN Tools document built from its parts."""

import functools
import os

import cpn
from cpn.statespace.explore import Explorer
from cpn.statespace.options import ExploreOptions

MODELS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "models")


def model_path(name: str) -> str:
    return os.path.join(MODELS, name)


@functools.lru_cache(maxsize=None)
def _model(name: str):
    """A model of tests/models, loaded once for both engines' figures (a model is only read: each
    engine is compiled from its net anew; chains.cpnet took a second to load)."""
    return cpn.load(model_path(name))


def figures(name: str, reference: bool = False, **options) -> tuple[int, int, int]:
    """(nodes, arcs, dead markings) of the state space of a model of tests/models."""
    return engine_figures(_model(name).engine(reference=reference), **options)


def engine_figures(engine, **options) -> tuple[int, int, int]:
    """(nodes, arcs, dead markings) of the state space of an engine."""
    result = Explorer(engine, ExploreOptions(**options)).run()
    g = result.graph
    dead = sum(1 for i in range(g.expanded) if g.offsets[i] == g.offsets[i + 1])
    return result.n_states, result.n_arcs, dead


def cpn_document(colours: list[tuple[str, str]], variables: list[tuple[str, str]], mls: list[str],
                 places: list[tuple[str, str, str]], transitions: list[tuple[str, str]],
                 arcs: list[tuple[str, str, str]]) -> str:
    """A CPN Tools document of one page: colour sets (name, CPN XML body such as '<int/>'), variables
    (name, colour set), ML declarations, places (name, colour set, initial marking), transitions (name,
    guard) and arcs (source, target, inscription)."""
    from xml.sax.saxutils import escape

    ids = iter(range(1, 1_000_000))
    out = ['<?xml version="1.0" encoding="iso-8859-1"?>', "<workspaceElements>",
           '<generator tool="CPN Tools" version="4.0.1" format="6"/>', "<cpnet>", "<globbox>"]
    for name, body in colours:
        out.append(f'<color id="C{next(ids)}"><id>{name}</id>{body}</color>')
    for name, cs in variables:
        out.append(f'<var id="V{next(ids)}"><type><id>{cs}</id></type><id>{name}</id></var>')
    for text in mls:
        out.append(f'<ml id="M{next(ids)}">{escape(text)}</ml>')
    out += ["</globbox>", '<page id="PG1">', '<pageattr name="Top"/>']
    node = {}
    for name, cs, init in places:
        node[name] = f"P{next(ids)}"
        out.append(f'<place id="{node[name]}"><text>{name}</text><type id="{node[name]}t"><text>{cs}</text></type>'
                   f'<initmark id="{node[name]}i"><text>{escape(init)}</text></initmark></place>')
    for name, guard in transitions:
        node[name] = f"T{next(ids)}"
        out.append(f'<trans id="{node[name]}" explicit="false"><text>{name}</text>'
                   f'<cond id="{node[name]}c"><text>{escape(guard)}</text></cond></trans>')
    for src, dst, text in arcs:
        to_trans = node[dst].startswith("T")
        place, trans = (node[src], node[dst]) if to_trans else (node[dst], node[src])
        out.append(f'<arc id="A{next(ids)}" orientation="{"PtoT" if to_trans else "TtoP"}" order="1">'
                   f'<transend idref="{trans}"/><placeend idref="{place}"/>'
                   f'<annot id="A{next(ids)}a"><text>{escape(text)}</text></annot></arc>')
    out += ["</page>", '<instances><instance id="I1" page="PG1"/></instances>', "</cpnet>", "</workspaceElements>"]
    return "\n".join(out)
