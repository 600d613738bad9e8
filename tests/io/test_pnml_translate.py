"""Translation of PNML into .cpnet text: P/T nets, each symmetric-net operator, names, diagnostics."""

from __future__ import annotations

import glob
import os

import pytest

from cpn.errors import ModelError
from cpn.io.pnml import translate, translate_text
from tests._shared import SHARED, needs_shared

VALIDATION = os.environ.get("CPN_VALIDATION_DIR", SHARED + "/validation")
NS = "http://www.pnml.org/version-2009/grammar/pnml"


def pt(body: str) -> str:
    return (f'<?xml version="1.0"?>\n<pnml xmlns="{NS}">\n<net id="n" type="{NS.replace("pnml", "ptnet")}">'
            f"<page id='pg'>\n{body}\n</page></net></pnml>\n")


def sn(decls: str, body: str) -> str:
    return (f'<?xml version="1.0"?>\n<pnml xmlns="{NS}">\n'
            f'<net id="n" type="http://www.pnml.org/version-2009/grammar/symmetricnet">\n'
            f"<page id='pg'>\n{body}\n</page>\n"
            f"<declaration><structure><declarations>\n{decls}\n</declarations></structure></declaration>\n"
            f"</net></pnml>\n")


ENUM = """
<namedsort id="proc" name="Proc"><cyclicenumeration>
  <feconstant id="p0" name="0"/><feconstant id="p1" name="1"/><feconstant id="p2" name="2"/>
</cyclicenumeration></namedsort>
<namedsort id="fin" name="Fin"><finiteenumeration>
  <feconstant id="a" name="a"/><feconstant id="b" name="b"/>
</finiteenumeration></namedsort>
<namedsort id="rng" name="Rng"><finiteintrange start="1" end="3"/></namedsort>
<namedsort id="dotS" name="Dot"><dot/></namedsort>
<namedsort id="pair" name="Pair"><productsort><usersort declaration="proc"/><usersort declaration="fin"/></productsort></namedsort>
<variabledecl id="vx" name="x"><usersort declaration="proc"/></variabledecl>
<variabledecl id="vy" name="y"><usersort declaration="proc"/></variabledecl>
<variabledecl id="vf" name="f"><usersort declaration="fin"/></variabledecl>
<variabledecl id="vr" name="r"><usersort declaration="rng"/></variabledecl>
"""


def sub(*terms: str) -> str:
    return "".join(f"<subterm>{t}</subterm>" for t in terms)


def var(v: str) -> str:
    return f'<variable refvariable="{v}"/>'


def const(c: str) -> str:
    return f'<useroperator declaration="{c}"/>'


def num(n: int) -> str:
    return f'<numberconstant value="{n}"><positive/></numberconstant>'


def all_of(sort: str) -> str:
    return f'<all><usersort declaration="{sort}"/></all>'


def numberof(n: int, t: str) -> str:
    return f"<numberof>{sub(num(n), t)}</numberof>"


def guard_of(cond: str) -> str:
    """The .cpnet line of a transition 't' whose condition is `cond`."""
    body = (f'<place id="P"><type><structure><usersort declaration="proc"/></structure></type></place>'
            f'<transition id="t"><condition><structure>{cond}</structure></condition></transition>'
            f'<arc id="a1" source="P" target="t"><hlinscription><structure>{numberof(1, var("vx"))}'
            f"</structure></hlinscription></arc>")
    text = translate_text(sn(ENUM, body))
    return next(line for line in text.splitlines() if line.startswith("trans t"))


def inscription_of(term: str, sort: str = "proc") -> str:
    body = (f'<place id="P"><type><structure><usersort declaration="{sort}"/></structure></type></place>'
            f'<transition id="t"/>'
            f'<arc id="a1" source="t" target="P"><hlinscription><structure>{term}'
            f"</structure></hlinscription></arc>")
    text = translate_text(sn(ENUM, body))
    line = next(line for line in text.splitlines() if line.startswith("arc t -> P"))
    return line.split(" : ", 1)[1].rstrip(";")


def full(term: str, sort: str = "proc") -> str:
    body = (f'<place id="P"><type><structure><usersort declaration="{sort}"/></structure></type></place>'
            f'<transition id="t"/>'
            f'<arc id="a1" source="t" target="P"><hlinscription><structure>{term}'
            f"</structure></hlinscription></arc>")
    return translate_text(sn(ENUM, body))


# ---------------------------------------------------------------------- P/T nets

def test_pt_net_places_transitions_weights():
    text = translate_text(pt("""
      <place id="p1"><name><text>p1</text></name><initialMarking><text>3</text></initialMarking></place>
      <place id="p2"/>
      <transition id="t1"><name><text>t1</text></name></transition>
      <arc id="a" source="p1" target="t1"><inscription><text>2</text></inscription></arc>
      <arc id="b" source="t1" target="p2"/>
    """))
    lines = text.splitlines()
    assert "colset DOT = unit;" in lines
    assert "place p1 : DOT = 3`();" in lines
    assert "place p2 : DOT;" in lines
    assert "trans t1;" in lines
    assert "arc p1 -> t1 : 2`();" in lines
    assert "arc t1 -> p2;" in lines


def test_pt_parallel_arcs_are_merged_and_special_arcs_kept():
    text = translate_text(pt("""
      <place id="p"/><place id="q"/><transition id="t"/>
      <arc id="a" source="p" target="t"/><arc id="b" source="p" target="t"><inscription><text>2</text></inscription></arc>
      <arc id="c" source="q" target="t"><type value="inhibitor"/><inscription><text>2</text></inscription></arc>
      <arc id="d" source="q" target="t"><type value="reset"/></arc>
    """))
    assert "arc p -> t : 3`();" in text
    assert "inhibitor q -> t : 2`();" in text
    assert "reset q -> t;" in text


def test_names_are_quoted_made_unique_and_kept():
    text = translate_text(pt("""
      <place id="p1"><name><text>my place</text></name></place>
      <place id="p2"><name><text>my place</text></name></place>
      <transition id="t.1"><name><text>t.1</text></name></transition>
      <arc id="a" source="p1" target="t.1"/>
    """))
    assert 'place "my place" : DOT;' in text
    assert 'place "my place (p2)" : DOT;' in text
    assert 'trans "t.1";' in text
    assert 'arc "my place" -> "t.1";' in text


def test_reference_nodes_and_nested_pages():
    text = translate_text(pt("""
      <place id="p"/><page id="inner"><transition id="t"/><referencePlace id="rp" ref="p"/>
      <arc id="a" source="rp" target="t"/></page>
    """))
    assert "arc p -> t;" in text


# ---------------------------------------------------------------------- symmetric nets: sorts

def test_sorts_become_colour_sets():
    text = full(numberof(1, var("vx")))
    assert "colset Proc = with p0 | p1 | p2;" in text
    assert "colset Fin = with a | b;" in text
    assert "colset Rng = int with 1..3;" in text
    assert "colset Dot = unit;" in text
    assert "colset Pair = product Proc * Fin;" in text
    assert "var x, y : Proc;" in text
    assert "var f : Fin;" in text


def test_identifiers_are_valid_and_unique():
    decls = """
    <namedsort id="s1" name="val"><cyclicenumeration><feconstant id="c1" name="1"/><feconstant id="c2" name="x y"/></cyclicenumeration></namedsort>
    <namedsort id="s2" name="S-2"><cyclicenumeration><feconstant id="d1" name="1"/><feconstant id="c1 " name="c1"/></cyclicenumeration></namedsort>
    <variabledecl id="v" name="val"><usersort declaration="s1"/></variabledecl>
    """
    body = '<place id="P"><type><structure><usersort declaration="s2"/></structure></type></place>'
    text = translate_text(sn(decls, body))
    # a name that is no identifier gives way to the id, then to a sanitized, unique form
    assert "colset s1 = with c1 | c2;" in text
    assert "colset s2 = with d1 | s2_c1;" in text
    assert "var v : s1;" in text


# ---------------------------------------------------------------------- symmetric nets: operators

def test_numberof_variable_and_tuple():
    assert inscription_of(numberof(2, var("vx"))) == "2`x"
    tup = f"<tuple>{sub(var('vx'), var('vf'))}</tuple>"
    assert inscription_of(numberof(1, tup), "pair") == "1`(x, f)"
    assert inscription_of(tup, "pair") == "1`(x, f)"


def test_all_add_subtract():
    assert inscription_of('<all><usersort declaration="proc"/></all>') == "Proc.all()"
    assert inscription_of(numberof(2, '<all><usersort declaration="fin"/></all>'), "fin") == "2`a ++ 2`b"
    add = f"<add>{sub(numberof(1, var('vx')), numberof(1, const('p1')))}</add>"
    assert inscription_of(add) == "1`x ++ 1`p1"
    minus = f"<subtract>{sub(all_of('proc'), numberof(1, var('vx')))}</subtract>"
    assert inscription_of(minus) == "Proc.all() -- 1`x"


def test_tuple_with_all_expands():
    tup = f"<tuple>{sub(var('vx'), all_of('fin'))}</tuple>"
    assert inscription_of(numberof(3, tup), "pair") == "3`(x, a) ++ 3`(x, b)"


def test_dot_and_bool_constants():
    assert inscription_of(numberof(2, "<dotconstant/>"), "dotS") == "2`()"


def test_successor_and_predecessor_wrap_around():
    text = full(numberof(1, f"<successor>{sub(var('vx'))}</successor>"))
    assert "arc t -> P : 1`(Proc.col ((Proc.ord x + 1) mod 3));" in text
    text = full(numberof(1, f"<predecessor>{sub(var('vx'))}</predecessor>"))
    assert "arc t -> P : 1`(Proc.col ((Proc.ord x + 2) mod 3));" in text
    text = full(numberof(1, f"<successor>{sub(var('vr'))}</successor>"), "rng")
    assert "arc t -> P : 1`(if r = 3 then 1 else r + 1);" in text
    text = full(numberof(1, f"<predecessor>{sub(var('vr'))}</predecessor>"), "rng")
    assert "arc t -> P : 1`(if r = 1 then 3 else r - 1);" in text


def test_comparisons_and_connectives():
    eq = f"<equality>{sub(var('vx'), const('p0'))}</equality>"
    ne = f"<inequality>{sub(var('vx'), var('vy'))}</inequality>"
    assert guard_of(eq) == "trans t [x = p0];"
    assert guard_of(f"<and>{sub(eq, ne)}</and>") == "trans t [(x = p0) andalso (x <> y)];"
    assert guard_of(f"<or>{sub(eq, ne)}</or>") == "trans t [(x = p0) orelse (x <> y)];"
    assert guard_of(f"<not>{sub(eq)}</not>") == "trans t [not (x = p0)];"
    assert guard_of(f"<imply>{sub(eq, ne)}</imply>") == "trans t [not (x = p0) orelse (x <> y)];"
    for tag, op in [("lessthan", "<"), ("lessthanorequal", "<="), ("greaterthan", ">"),
                    ("greaterthanorequal", ">=")]:
        assert guard_of(f"<{tag}>{sub(var('vx'), var('vy'))}</{tag}>") == f"trans t [Proc.ord x {op} Proc.ord y];"


def test_partition():
    decls = ENUM + """
    <partition id="part" name="Half"><usersort declaration="proc"/>
      <partitionelement id="lo" name="lo"><useroperator declaration="p0"/><useroperator declaration="p1"/></partitionelement>
      <partitionelement id="hi" name="hi"><useroperator declaration="p2"/></partitionelement>
    </partition>"""
    pof = '<partitionelementof refpartition="part">' + sub(var("vx")) + "</partitionelementof>"
    body = (f'<place id="P"><type><structure><usersort declaration="proc"/></structure></type></place>'
            f'<transition id="t"><condition><structure><equality>'
            f'{sub(pof, const("lo"))}'
            f"</equality></structure></condition></transition>"
            f'<arc id="a1" source="P" target="t"><hlinscription><structure>{numberof(1, var("vx"))}'
            f"</structure></hlinscription></arc>")
    text = translate_text(sn(decls, body))
    assert "colset Half = with lo | hi;" in text
    assert "trans t [(of_Half x) = lo];" in text
    assert "fun of_Half c' =\n  case c' of\n    p0 => lo\n  | p1 => lo\n  | p2 => hi;" in text


def test_initial_marking_and_default_dot_inscription():
    body = ('<place id="P"><type><structure><usersort declaration="dotS"/></structure></type>'
            f"<hlinitialMarking><structure>{numberof(4, '<dotconstant/>')}</structure></hlinitialMarking></place>"
            '<transition id="t"/><arc id="a" source="P" target="t"/>')
    text = translate_text(sn(ENUM, body))
    assert "place P : Dot = 4`();" in text
    assert "arc P -> t : 1`();" in text


# ---------------------------------------------------------------------- diagnostics

def test_unsupported_operators_are_all_reported_with_positions():
    body = ('<place id="P"><type><structure><usersort declaration="proc"/></structure></type></place>\n'
            '<transition id="t"/>\n'
            '<arc id="a12" source="P" target="t"><hlinscription><structure>\n'
            "<xyz/></structure></hlinscription></arc>\n"
            '<arc id="a13" source="t" target="P"><hlinscription><structure>\n'
            "<cardinality/></structure></hlinscription></arc>\n")
    with pytest.raises(ModelError) as info:
        translate_text(sn(ENUM, body), "m.pnml")
    diags = info.value.diagnostics
    assert [d.code for d in diags] == ["E0502", "E0502"]
    assert diags[0].message == "unsupported PNML operator 'xyz' in the inscription of arc 'a12'"
    assert (diags[0].span.file, diags[0].span.line, diags[0].span.col) == ("m.pnml", 8, 1)
    assert "'cardinality'" in diags[1].message and diags[1].span.line == 10


def test_malformed_xml_and_unknown_net_type():
    with pytest.raises(ModelError) as info:
        translate_text("<pnml><net>", "bad.pnml")
    assert info.value.diagnostics[0].code == "E0501"
    with pytest.raises(ModelError) as info:
        translate_text(f'<pnml xmlns="{NS}"><net id="n" type="urn:x/coloured"/></pnml>', "x.pnml")
    assert info.value.diagnostics[0].code == "E0502"
    assert "urn:x/coloured" in info.value.diagnostics[0].message


def test_missing_file():
    with pytest.raises(ModelError) as info:
        translate("/nonexistent/model.pnml")
    assert info.value.diagnostics[0].code == "E0501"


def test_unknown_references():
    body = ('<place id="P"><type><structure><usersort declaration="nope"/></structure></type></place>'
            '<transition id="t"/><arc id="a" source="Q" target="t"/>')
    with pytest.raises(ModelError) as info:
        translate_text(sn(ENUM, body), "r.pnml")
    msgs = [d.message for d in info.value.diagnostics]
    assert "unknown sort 'nope'" in msgs
    assert any("refers to 'Q'" in m for m in msgs)


# ---------------------------------------------------------------------- the corpus

CORPUS = sorted(glob.glob(os.path.join(VALIDATION, "*", "model.pnml")))


@needs_shared
@pytest.mark.parametrize("path", CORPUS, ids=lambda p: os.path.basename(os.path.dirname(p)))
def test_corpus_translates_and_parses(path):
    from cpn.lang.parser import parse

    text = translate(path)
    parse(text, path + ".cpnet")


def test_origins_point_at_the_pnml_elements(tmp_path):
    from cpn.diagnostics import Diagnostic, Span
    from cpn.io.pnml import remap_error, translate_with_origins

    path = tmp_path / "m.pnml"
    path.write_text(pt('<place id="p"/>\n<transition id="t"/>\n<arc id="a" source="p" target="t"/>'))
    tr = translate_with_origins(path)
    lines = tr.text.splitlines()
    arc_line = lines.index("arc p -> t;") + 1
    assert tr.locate(arc_line).line == 6
    assert tr.locate(lines.index("place p : DOT;") + 1).line == 4
    err = ModelError([Diagnostic("E0301", "type mismatch", Span(str(path), arc_line, 5))])
    mapped = remap_error(err, tr)
    d = mapped.diagnostics[0]
    assert (d.span.line, d.code) == (6, "E0301") and "arc p -> t;" in d.notes[-1]


def test_scalarproduct_empty_and_repeated_multisets():
    two_x = f"<scalarproduct>{sub(num(2), numberof(1, var('vx')))}</scalarproduct>"
    assert inscription_of(two_x) == "2`x"
    add = f"<add>{sub(numberof(1, var('vx')), numberof(1, var('vy')))}</add>"
    assert inscription_of(f"<scalarproduct>{sub(num(2), add)}</scalarproduct>") == "2`x ++ 2`y"
    succ = f"<successor>{sub(var('vx'))}</successor>"
    add2 = f"<add>{sub(numberof(1, var('vx')), numberof(1, succ))}</add>"
    assert inscription_of(f"<scalarproduct>{sub(num(2), add2)}</scalarproduct>") \
        == "2`x ++ 2`(Proc.col ((Proc.ord x + 1) mod 3))"
    sub_ms = f"<subtract>{sub(all_of('proc'), numberof(1, var('vx')))}</subtract>"
    assert inscription_of(f"<scalarproduct>{sub(num(2), sub_ms)}</scalarproduct>") \
        == "(Proc.all() -- 1`x) ++ (Proc.all() -- 1`x)"
    assert inscription_of('<empty><usersort declaration="proc"/></empty>') == "empty"


def test_partition_order():
    decls = ENUM + """
    <partition id="part" name="Half"><usersort declaration="proc"/>
      <partitionelement id="lo" name="lo"><useroperator declaration="p0"/><useroperator declaration="p1"/></partitionelement>
      <partitionelement id="hi" name="hi"><useroperator declaration="p2"/></partitionelement>
    </partition>"""
    pof = '<partitionelementof refpartition="part">' + sub(var("vx")) + "</partitionelementof>"
    body = (f'<place id="P"><type><structure><usersort declaration="proc"/></structure></type></place>'
            f'<transition id="t"><condition><structure><ltp>{sub(pof, const("hi"))}</ltp>'
            f"</structure></condition></transition>"
            f'<arc id="a1" source="P" target="t"><hlinscription><structure>{numberof(1, var("vx"))}'
            f"</structure></hlinscription></arc>")
    text = translate_text(sn(decls, body))
    assert "trans t [Half.ord (of_Half x) < Half.ord hi];" in text


@pytest.mark.parametrize("weight, states", [(1, 2), (2, 3), (3, 3)])
def test_inhibitor_weight_semantics_end_to_end(weight, states):
    import cpn
    from cpn.cli.validate import explore_figures

    text = translate_text(pt(f"""
      <place id="p"><initialMarking><text>2</text></initialMarking></place><place id="q"/>
      <transition id="t"/>
      <arc id="a" source="p" target="t"/><arc id="b" source="t" target="q"/>
      <arc id="c" source="q" target="t"><type value="inhibitor"/><inscription><text>{weight}</text></inscription></arc>
    """))
    f = explore_figures(cpn.loads(text, "inh.cpnet").engine())
    assert f.states == states


def test_reset_arc_end_to_end():
    import cpn
    from cpn.cli.validate import explore_figures

    text = translate_text(pt("""
      <place id="p"><initialMarking><text>3</text></initialMarking></place><place id="go"><initialMarking><text>1</text></initialMarking></place>
      <transition id="t"/>
      <arc id="a" source="go" target="t"/><arc id="r" source="p" target="t"><type value="reset"/></arc>
    """))
    f = explore_figures(cpn.loads(text, "reset.cpnet").engine())
    assert (f.states, f.arcs, f.max_tokens_per_marking) == (2, 1, 4)


def test_int_range_constants_arithmetic_and_booleans():
    rc = '<finiteintrangeconstant value="2"><finiteintrange start="1" end="3"/></finiteintrangeconstant>'
    assert guard_of(f"<lessthan>{sub(var('vr'), rc)}</lessthan>").endswith("[r < 2];")
    plus = f"<addition>{sub(var('vr'), rc)}</addition>"
    assert guard_of(f"<equality>{sub(plus, rc)}</equality>").endswith("[(r + 2) = 2];")
    assert guard_of('<booleanconstant value="true"/>') == "trans t;"
    assert guard_of('<booleanconstant value="false"/>') == "trans t [false];"
    text = full(numberof(1, rc), "rng")
    assert "arc t -> P : 1`2;" in text
    assert "colset Rng = int with 1..3;" in text and text.count("int with 1..3;") == 1


def test_unordered_comparison_is_refused():
    body = ('<place id="P"><type><structure><usersort declaration="pair"/></structure></type></place>'
            '<transition id="t"><condition><structure><lessthan>'
            f"{sub('<tuple>' + sub(var('vx'), var('vf')) + '</tuple>', '<tuple>' + sub(var('vy'), var('vf')) + '</tuple>')}"
            "</lessthan></structure></condition></transition>")
    with pytest.raises(ModelError) as info:
        translate_text(sn(ENUM, body), "o.pnml")
    assert info.value.diagnostics[0].code == "E0502"
    assert "sort is unknown" in info.value.diagnostics[0].message


def test_text_only_labels_are_refused_and_single_term_numberof_is_one():
    body = ('<place id="P"><type><structure><usersort declaration="proc"/></structure></type>'
            "<hlinitialMarking><text>1'p0</text></hlinitialMarking></place>"
            '<transition id="t"/><arc id="a" source="P" target="t"><hlinscription><text>x</text></hlinscription></arc>')
    with pytest.raises(ModelError) as info:
        translate_text(sn(ENUM, body), "t.pnml")
    assert [d.code for d in info.value.diagnostics] == ["E0502", "E0502"]
    assert "without a <structure>" in info.value.diagnostics[0].message
    assert inscription_of(f"<numberof>{sub(var('vx'))}</numberof>") == "1`x"


def test_tapaal_coloured_net_with_ptnet_type():
    # TAPAAL writes coloured nets with the P/T net type, arc types as attributes, and the dot
    # constant as a user operator naming the dot sort
    doc = f'''<?xml version="1.0"?>
<pnml xmlns="{NS}"><net id="c" type="http://www.pnml.org/version-2009/grammar/ptnet">
<declaration><structure><declarations>
  <namedsort id="dot" name="dot"><dot/></namedsort>
  <namedsort id="r" name="r"><finiteintrange start="2" end="3"/></namedsort>
  <variabledecl id="Varv" name="v"><usersort declaration="r"/></variabledecl>
</declarations></structure></declaration>
<page id="page0">
  <place id="P0"><type><structure><usersort declaration="r"/></structure></type>
    <hlinitialMarking><structure>{numberof(1, '<finiteintrangeconstant value="3"><finiteintrange start="2" end="3"/></finiteintrangeconstant>')}</structure></hlinitialMarking></place>
  <place id="P1"><type><structure><usersort declaration="dot"/></structure></type></place>
  <place id="P2"><type><structure><usersort declaration="dot"/></structure></type></place>
  <transition id="T1"><condition><structure><greaterthan>{sub(var("Varv"), '<finiteintrangeconstant value="2"><finiteintrange start="2" end="3"/></finiteintrangeconstant>')}</greaterthan></structure></condition></transition>
  <arc id="a" source="P0" target="T1" type="normal"><hlinscription><structure>{numberof(1, var("Varv"))}</structure></hlinscription></arc>
  <arc id="b" source="T1" target="P1" type="normal"><hlinscription><structure>{numberof(1, const("dot"))}</structure></hlinscription></arc>
  <arc id="c" source="P2" target="T1" type="inhibitor"><hlinscription><structure>{numberof(1, const("dot"))}</structure></hlinscription></arc>
</page></net></pnml>'''
    text = translate_text(doc)
    assert "colset r = int with 2..3;" in text
    assert "place P0 : r = 1`3;" in text
    assert "trans T1 [v > 2];" in text
    assert "arc T1 -> P1 : 1`();" in text
    assert "inhibitor P2 -> T1 : 1`();" in text
