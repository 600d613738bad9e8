"""PNML as GreatSPN writes it: one-component tuples around every term of a sort that is not a
product, and partition elements used as colours inside tuples with sums of constants."""

from __future__ import annotations

import glob
import os
import xml.etree.ElementTree as ET

import pytest

from cpn.errors import ModelError
from cpn.io.pnml import translate_text
from tests._shared import SHARED, needs_shared
from tests.io.test_pnml_translate import ENUM, all_of, const, numberof, sn, sub, var

VALIDATION = os.environ.get("CPN_VALIDATION_DIR", SHARED + "/validation")
PNML_NS = "http://www.pnml.org/version-2009/grammar/pnml"
COL_MODELS = sorted(glob.glob(os.path.join(VALIDATION, "*-COL-*", "model.pnml")))

# terms that denote one value (or, for 'all', the values of one sort): the ones GreatSPN wraps
_VALUE_TERMS = {"variable", "useroperator", "dotconstant", "all", "finiteintrangeconstant", "successor",
                "predecessor"}


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


def greatspn_form(data: bytes) -> tuple[bytes, int]:
    """The same net with every arc and initial-marking term of a non-product sort wrapped in a
    one-component tuple, as GreatSPN writes it; and the number of terms wrapped."""
    ET.register_namespace("", PNML_NS)
    root = ET.fromstring(data)
    product_sorts = {el.get("id") for el in root.iter() if _local(el.tag) == "namedsort"
                     and any(_local(c.tag) == "productsort" for c in el)}
    product_vars = {el.get("id") for el in root.iter() if _local(el.tag) == "variabledecl"
                    and any(c.get("declaration") in product_sorts for c in el)}
    wrapped = 0

    def of_product_sort(el) -> bool:
        tag = _local(el.tag)
        if tag == "variable":
            return el.get("refvariable") in product_vars
        if tag == "all":
            return any(c.get("declaration") in product_sorts for c in el)
        return False

    def wrap_in(holder) -> None:
        """Wrap the value terms among holder's children, descending through sums and multiplicities."""
        nonlocal wrapped
        for i, el in enumerate(list(holder)):
            tag = _local(el.tag)
            if tag in _VALUE_TERMS and not of_product_sort(el):
                tup = ET.Element(f"{{{PNML_NS}}}tuple")
                subterm = ET.SubElement(tup, f"{{{PNML_NS}}}subterm")
                holder.remove(el)
                subterm.append(el)
                holder.insert(i, tup)
                wrapped += 1
            elif tag in ("add", "subtract", "numberof", "scalarproduct"):
                for s in el:
                    wrap_in(s)

    for label in root.iter():
        if _local(label.tag) in ("hlinscription", "hlinitialMarking"):
            for structure in label:
                if _local(structure.tag) == "structure":
                    wrap_in(structure)
    return ET.tostring(root, encoding="utf-8", xml_declaration=True), wrapped


@needs_shared
@pytest.mark.parametrize("path", COL_MODELS, ids=lambda p: os.path.basename(os.path.dirname(p)))
def test_greatspn_form_of_every_coloured_instance_translates_identically(path):
    with open(path, "rb") as fh:
        data = fh.read()
    rewritten, wrapped = greatspn_form(data)
    if wrapped == 0:
        pytest.skip("every arc and initial-marking term of this net is of a product sort")
    assert b"<tuple><subterm><" in rewritten.replace(b"\n", b"").replace(b" ", b"")
    assert translate_text(rewritten, "model.pnml") == translate_text(data, "model.pnml")


def _figures(text_or_bytes: bytes, tmp_path, name: str) -> tuple:
    import cpn
    from cpn.checks import boundedness
    from cpn.statespace import ExploreOptions, Explorer

    path = tmp_path / name
    path.write_bytes(text_or_bytes)
    x = Explorer(cpn.load(str(path)).engine(), ExploreOptions()).run()
    b = boundedness(x)
    return (x.n_states, x.n_arcs, len(x.graph.dead_states()), b.max_tokens_per_marking,
            b.max_of_one_colour_in_place)


@needs_shared
@pytest.mark.parametrize("name", ["Philosophers-COL-000005", "SafeBus-COL-03"])
def test_greatspn_form_gives_the_published_figures(name, tmp_path):
    import json

    path = os.path.join(VALIDATION, name, "model.pnml")
    if not os.path.exists(path):
        pytest.skip("validation corpus not available")
    expected = next(i for i in json.load(open(os.path.join(VALIDATION, "expected.json")))["instances"]
                    if i["name"] == name)
    with open(path, "rb") as fh:
        rewritten, _ = greatspn_form(fh.read())
    states, arcs, _dead, per_marking, in_place = _figures(rewritten, tmp_path, "model.pnml")
    assert (states, arcs, per_marking, in_place) == (
        expected["states"], expected["arcs"], expected["max_tokens_per_marking"], expected["max_tokens_in_place"])


def test_one_component_tuples_on_arcs_and_in_initial_markings():
    one = "<tuple>" + sub(var("vx")) + "</tuple>"
    every = "<tuple>" + sub(all_of("proc")) + "</tuple>"
    body = (f'<place id="P"><type><structure><usersort declaration="proc"/></structure></type>'
            f"<hlinitialMarking><structure>{every}</structure></hlinitialMarking></place>"
            f'<transition id="t"/>'
            f'<arc id="a1" source="P" target="t"><hlinscription><structure>{numberof(1, one)}'
            f"</structure></hlinscription></arc>"
            f'<arc id="a2" source="t" target="P"><hlinscription><structure>{one}'
            f"</structure></hlinscription></arc>")
    text = translate_text(sn(ENUM, body))
    assert "place P : Proc = Proc.all();" in text
    assert "arc P -> t : 1`x;" in text
    assert "arc t -> P : 1`x;" in text


def test_one_component_tuple_for_a_product_sort_is_still_an_error():
    body = ('<place id="P"><type><structure><usersort declaration="pair"/></structure></type></place>'
            '<transition id="t"/>'
            f'<arc id="a1" source="t" target="P"><hlinscription><structure><tuple>{sub(var("vx"))}</tuple>'
            "</structure></hlinscription></arc>")
    with pytest.raises(ModelError) as exc:
        translate_text(sn(ENUM, body))
    assert "has 1 component(s)" in str(exc.value)


# A net in the style of VehicularWifi-COL: places of a product sort whose initial marking and arcs use
# partition elements as colours inside tuples, with sums of them (`<pr1, tx2, bs1+bs2>`).
PARTITIONS = """
<namedsort id="pr" name="Pr"><cyclicenumeration>
  <feconstant id="p1" name="p1"/><feconstant id="p2" name="p2"/><feconstant id="p3" name="p3"/>
</cyclicenumeration></namedsort>
<namedsort id="tx" name="Tx"><cyclicenumeration>
  <feconstant id="t1" name="t1"/><feconstant id="t2" name="t2"/>
</cyclicenumeration></namedsort>
<namedsort id="bs" name="Bs"><cyclicenumeration>
  <feconstant id="b1" name="b1"/><feconstant id="b2" name="b2"/><feconstant id="b3" name="b3"/>
  <feconstant id="b4" name="b4"/>
</cyclicenumeration></namedsort>
<namedsort id="msg" name="Msg"><productsort>
  <usersort declaration="pr"/><usersort declaration="tx"/><usersort declaration="bs"/>
</productsort></namedsort>
<partition id="prp" name="PrP"><usersort declaration="pr"/>
  <partitionelement id="pr1" name="pr1"><useroperator declaration="p1"/><useroperator declaration="p2"/></partitionelement>
  <partitionelement id="pr2" name="pr2"><useroperator declaration="p3"/></partitionelement>
</partition>
<partition id="txp" name="TxP"><usersort declaration="tx"/>
  <partitionelement id="tx1" name="tx1"><useroperator declaration="t1"/></partitionelement>
  <partitionelement id="tx2" name="tx2"><useroperator declaration="t2"/></partitionelement>
</partition>
<partition id="bsp" name="BsP"><usersort declaration="bs"/>
  <partitionelement id="bs1" name="bs1"><useroperator declaration="b1"/></partitionelement>
  <partitionelement id="bs2" name="bs2"><useroperator declaration="b2"/><useroperator declaration="b3"/></partitionelement>
  <partitionelement id="bs3" name="bs3"><useroperator declaration="b4"/></partitionelement>
</partition>
<variabledecl id="vp" name="p"><usersort declaration="pr"/></variabledecl>
<variabledecl id="vt" name="t"><usersort declaration="tx"/></variabledecl>
<variabledecl id="vb" name="b"><usersort declaration="bs"/></variabledecl>
"""

SUM_TUPLE = ("<tuple>" + sub(const("pr1"), const("tx2"), "<add>" + sub(const("bs1"), const("bs2")) + "</add>")
             + "</tuple>")


def _partition_net(output: str) -> str:
    msg = '<type><structure><usersort declaration="msg"/></structure></type>'
    triple = "<tuple>" + sub(var("vp"), var("vt"), var("vb")) + "</tuple>"
    guard = ('<condition><structure><equality>'
             + sub('<partitionelementof refpartition="bsp">' + sub(var("vb")) + "</partitionelementof>",
                   const("bs2"))
             + "</equality></structure></condition>")
    body = (f'<place id="Air">{msg}<hlinitialMarking><structure>{SUM_TUPLE}</structure></hlinitialMarking></place>'
            f'<place id="Heard">{msg}</place>'
            f'<transition id="relay">{guard}</transition>'
            f'<arc id="a1" source="Air" target="relay"><hlinscription><structure>{numberof(1, triple)}'
            f"</structure></hlinscription></arc>"
            f'<arc id="a2" source="relay" target="Heard"><hlinscription><structure>{output}'
            f"</structure></hlinscription></arc>")
    return sn(PARTITIONS, body)


def test_partition_elements_inside_a_tuple_with_a_sum_are_their_constants():
    text = translate_text(_partition_net("<tuple>" + sub(var("vp"), var("vt"), var("vb")) + "</tuple>"))
    initial = next(line for line in text.splitlines() if line.startswith("place Air"))
    # <pr1, tx2, bs1+bs2> = {p1,p2} x {t2} x {b1,b2,b3}
    assert initial == ("place Air : Msg = 1`(p1, t2, b1) ++ 1`(p1, t2, b2) ++ 1`(p1, t2, b3) ++ "
                       "1`(p2, t2, b1) ++ 1`(p2, t2, b2) ++ 1`(p2, t2, b3);")


def test_partition_net_loads_and_explores(tmp_path):
    import cpn
    from cpn.statespace import ExploreOptions, Explorer

    path = tmp_path / "relay.pnml"
    path.write_text(_partition_net("<tuple>" + sub(var("vp"), var("vt"), var("vb")) + "</tuple>"))
    x = Explorer(cpn.load(str(path)).engine(), ExploreOptions()).run()
    # relay moves the four messages whose base station is in bs2 ({b2, b3}), in any order: 2^4 states
    assert x.complete and x.n_states == 16 and x.n_arcs == 32


def test_partition_net_with_an_infinite_state_space_explores_under_a_limit(tmp_path):
    import cpn
    from cpn.statespace import ExploreOptions, Explorer, StopReason

    # relay puts the message back and adds <pr1, tx2, bs1+bs2> to Heard each time: Heard grows forever
    output = ("<add>" + sub("<tuple>" + sub(var("vp"), var("vt"), var("vb")) + "</tuple>", SUM_TUPLE) + "</add>")
    path = tmp_path / "flood.pnml"
    path.write_text(_partition_net(output).replace('target="Heard"', 'target="Air"'))
    x = Explorer(cpn.load(str(path)).engine(), ExploreOptions(max_states=500)).run()
    assert x.stop_reason is StopReason.MAX_STATES and x.n_states >= 500 and x.unexpanded > 0


def test_a_value_compared_with_a_partition_element_is_tested_for_membership():
    cond = "<equality>" + sub(var("vb"), const("bs2")) + "</equality>"
    body = ('<place id="P"><type><structure><usersort declaration="bs"/></structure></type></place>'
            f'<transition id="t"><condition><structure>{cond}</structure></condition></transition>'
            f'<arc id="a1" source="P" target="t"><hlinscription><structure>{numberof(1, var("vb"))}'
            "</structure></hlinscription></arc>")
    text = translate_text(sn(PARTITIONS, body))
    assert "trans t [(of_BsP b) = bs2];" in text
    assert "fun of_BsP c' =" in text
    import cpn

    cpn.loads(text).engine()  # the translation type-checks
