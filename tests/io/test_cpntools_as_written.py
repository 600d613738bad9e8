"""CPN Tools models as people write them: forms that CPN Tools reads and that must load, or be refused
with one positioned error, never a traceback. Each test writes the smallest `.cpn` file that shows it."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import ModelError
from cpn.io.cpntools import translate_text
from tests.io.test_cpntools import DECLS, arc, cpn_xml, page, place, trans
from tests.io.test_cpntools_statespace import explore as bfs


def arc_without_annot(aid, orient, tid, pid):
    """An arc as some files write it: no `<annot>` element at all (not even an empty one)."""
    return (f'<arc id="{aid}" orientation="{orient}" order="1"><transend idref="{tid}"/>'
            f'<placeend idref="{pid}"/></arc>')


def write(tmp_path, xml: str, name: str = "m.cpn") -> str:
    path = tmp_path / name
    path.write_text(xml)
    return str(path)


def load(tmp_path, xml: str, name: str = "m.cpn"):
    return cpn.load(write(tmp_path, xml, name))


def explore_counts(tmp_path, xml: str) -> tuple[int, int]:
    """(nodes, arcs) of the complete state space of the net in `xml`."""
    space = bfs(write(tmp_path, xml))
    assert space.complete
    return space.nodes, space.arcs


# ------------------------------------------------------------------ arcs without <annot>


def test_an_arc_without_annot_element_of_a_unit_place_is_one_unit_token(tmp_path):
    body = (place("P1", "A", "UNIT", "2`()") + place("P2", "B", "UNIT") + trans("T1", "t")
            + arc_without_annot("A1", "PtoT", "T1", "P1") + arc_without_annot("A2", "TtoP", "T1", "P2"))
    # 2`() on A: t occurs twice, one token each time
    assert explore_counts(tmp_path, cpn_xml(DECLS, page("PG1", "Top", body))) == (3, 2)


def test_an_arc_without_annot_element_of_a_non_unit_place_is_one_positioned_error(tmp_path):
    body = (place("P1", "A", "S", "1`0") + trans("T1", "t") + arc_without_annot("A1", "PtoT", "T1", "P1"))
    xml = cpn_xml(DECLS, page("PG1", "Top", body))
    with pytest.raises(ModelError) as info:
        load(tmp_path, xml)
    [d] = info.value.diagnostics
    assert d.code == "E0301" and "has no inscription" in d.message
    # CPN Tools refuses it too, and the message says so, naming the place's colour set
    assert (d.params["place"], d.params["colset"]) == ("A", "S") and "CPN Tools does not accept it" in d.message
    assert "a variable of colour set S" in d.hint
    line = xml.splitlines()[d.span.line - 1]
    assert line[d.span.col - 1:].startswith('<arc id="A1"')


# ------------------------------------------------------------------ places without a colour set


def test_a_place_without_colour_set_is_unit_as_in_cpn_tools(tmp_path):
    # the globbox declares no UNIT: the translation declares it
    decls = '<color id="C2"><id>INT</id><int/></color>'
    body = (place("P1", "A", "", "1`()") + place("P2", "B", "") + trans("T1", "t")
            + arc_without_annot("A1", "PtoT", "T1", "P1") + arc("A2", "TtoP", "T1", "P2", "()"))
    xml = cpn_xml(decls, page("PG1", "Top", body))
    t = translate_text(xml, "m.cpn")
    assert "place A : UNIT = 1`();" in t.text and "colset UNIT = unit;" in t.text
    assert any("has no colour set: UNIT" in n for n in t.notes)
    assert explore_counts(tmp_path, xml) == (2, 1)


def test_other_tokens_on_an_arc_to_a_place_without_colour_set_are_a_type_error_that_says_why(tmp_path):
    # the mip model: 'satisfied student' has no colour set (UNIT in CPN Tools), its arc from 'eat' carries x : s
    body = (place("P1", "A", "S", "1`0") + place("P2", "B", "") + trans("T1", "t")
            + arc("A1", "PtoT", "T1", "P1", "x") + arc("A2", "TtoP", "T1", "P2", "x"))
    xml = cpn_xml(DECLS, page("PG1", "Top", body))
    with pytest.raises(ModelError) as info:
        load(tmp_path, xml)
    [d] = info.value.diagnostics
    assert d.code == "E0301" and "type mismatch" in d.message
    assert "Place 'B' has no colour set in the file" in d.hint and "type error in CPN Tools too" in d.hint


def test_a_place_without_colour_set_uses_the_nets_own_unit(tmp_path):
    body = place("P1", "A", "", "1`()") + trans("T1", "t") + arc_without_annot("A1", "PtoT", "T1", "P1")
    t = translate_text(cpn_xml(DECLS, page("PG1", "Top", body)), "m.cpn")
    assert t.text.count("colset UNIT") == 1  # DECLS declares it
    assert explore_counts(tmp_path, cpn_xml(DECLS, page("PG1", "Top", body))) == (2, 1)


def test_an_arc_to_a_transition_that_is_not_in_the_file_says_which_end():
    body = place("P1", "A", "S", "1`0") + trans("T1", "t") + arc("A1", "PtoT", "T9", "P1", "x")
    xml = cpn_xml(DECLS, page("PG1", "Top", body))
    with pytest.raises(ModelError) as info:
        translate_text(xml, "m.cpn")
    [d] = info.value.diagnostics
    assert "its transition end 'T9' is no transition of the file" in d.message and d.hint
    assert xml.splitlines()[d.span.line - 1][d.span.col - 1:].startswith('<arc id="A1"')


# ------------------------------------------------------------------ a delay whose output places are untimed


def test_a_transition_delay_with_untimed_outputs_is_accepted_as_in_cpn_tools(tmp_path):
    # the CPN book's 10-19TimedStateSpaces.cpn has such a transition: CPN Tools type-checks the delay only
    body = (place("P1", "A", "S", "1`0") + trans("T1", "t", cond="[x &lt; 3]", time="@+7")
            + arc("A1", "PtoT", "T1", "P1", "x") + arc("A2", "TtoP", "T1", "P1", "(x + 1) mod 4"))
    xml = cpn_xml(DECLS, page("PG1", "Top", body))
    model = load(tmp_path, xml)
    [w] = model.warnings
    assert w.code == "W0102" and "the delay has no effect" in w.message
    # the warning names the time inscription, not the guard written before it on the same line
    assert any("time inscription of 't'" in n for n in w.notes), w.notes
    assert explore_counts(tmp_path, xml) == (4, 3)  # x = 0, 1, 2, 3: the delay changes nothing


def test_a_delay_that_is_not_an_integer_is_still_an_error_at_the_time_inscription(tmp_path):
    body = (place("P1", "A", "S", "1`0") + trans("T1", "t", cond="[x &lt; 3]", time="@+true")
            + arc("A1", "PtoT", "T1", "P1", "x") + arc("A2", "TtoP", "T1", "P1", "x"))
    xml = cpn_xml(DECLS, page("PG1", "Top", body))
    with pytest.raises(ModelError) as info:
        load(tmp_path, xml)
    [d] = info.value.diagnostics
    assert d.code == "E0301" and "the delay of transition 't'" in d.message
    assert xml.splitlines()[d.span.line - 1][d.span.col - 1:].startswith("true</text></time>")


def test_locate_picks_the_element_that_starts_last_on_a_line():
    body = place("P1", "A", "S", "1`0") + trans("T1", "t", cond="[x = 1]", time="@+ 5", prio="P_LOW")
    body += arc("A1", "PtoT", "T1", "P1", "x")
    xml = cpn_xml(DECLS, page("PG1", "Top", body))
    t = translate_text(xml, "m.cpn")
    lines = t.text.splitlines()
    n = next(i for i, s in enumerate(lines, 1) if s.startswith("trans t"))
    for needle, rest in (("x = 1", "]</text></cond>"), ("5", "</text></time>")):
        span, origin = t.locate(n, lines[n - 1].index(needle) + 1)
        assert xml.splitlines()[span.line - 1][span.col - 1:].startswith(needle + rest), needle


# ------------------------------------------------------------------ a place and a transition of one name


def test_an_arc_between_a_place_and_a_transition_of_one_name(tmp_path):
    body = (place("P1", "job", "S", "1`0") + place("P2", "done", "S") + trans("T1", "job", cond="[x &lt; 3]")
            + arc("A1", "PtoT", "T1", "P1", "x") + arc("A2", "TtoP", "T1", "P1", "x + 1")
            + arc("A3", "TtoP", "T1", "P2", "x") + arc("A4", "Inhibitor", "T1", "P2", "3"))
    xml = cpn_xml(DECLS, page("PG1", "Top", body))
    text = translate_text(xml, "m.cpn").text
    assert "arc place job -> trans job : x;" in text and "arc trans job -> place job : x + 1;" in text
    assert "inhibitor place done -> trans job : 3;" in text
    # job: 0 -> 1 -> 2 -> 3, the guard stops it; done collects 0, 1, 2
    assert explore_counts(tmp_path, xml) == (4, 3)


# ------------------------------------------------------------------ declarations as CPN Tools reads them


def test_colour_set_names_with_primes_and_declarations_without_semicolons(tmp_path):
    decls = (DECLS + '<color id="C7"><id>L&apos;S</id><list><id>S</id></list></color>'
             '<var id="V2"><type><id>L&apos;S</id></type><id>l&apos;s</id></var>'
             # two declarations without ';' between them (SML allows it), the second with a comment after its ';'
             '<ml id="M2">fun l&apos;val (x : S) : L&apos;S = [x]\n\nfun twice (l : L&apos;S) = l ^^ l; (* [\n]; *)</ml>')
    body = (place("P1", "A", "S", "1`0") + place("P2", "B", "L&apos;S") + trans("T1", "t")
            + arc("A1", "PtoT", "T1", "P1", "x") + arc("A2", "TtoP", "T1", "P2", "twice (l&apos;val x)"))
    xml = cpn_xml(decls, page("PG1", "Top", body))
    text = translate_text(xml, "m.cpn").text
    assert "colset L'S = list S;" in text
    model = load(tmp_path, xml)
    e = model.engine()
    [(_be, s1)] = list(e.successors(e.initial_state()))
    assert e.format_marking(s1, 1) == "1`[0,0]"


def test_an_empty_let_and_a_typed_expression_in_a_cpn_file(tmp_path):
    decls = (DECLS + '<color id="C7"><id>L</id><list><id>S</id></list></color>'
             '<ml id="M2">fun next (x : S) = let\nin (x + 1) mod 4 : S\nend</ml>'
             '<ml id="M3">val none = [] : L</ml>')
    body = (place("P1", "A", "S", "1`0") + place("P2", "B", "L", "1`none") + trans("T1", "t", cond="[x &lt; 2]")
            + arc("A1", "PtoT", "T1", "P1", "x") + arc("A2", "TtoP", "T1", "P1", "next x"))
    assert explore_counts(tmp_path, cpn_xml(decls, page("PG1", "Top", body))) == (3, 2)


def test_a_code_segment_without_semicolon_before_action_is_read_as_cpn_tools_reads_it():
    body = (place("P1", "A", "S", "1`0") + trans("T1", "t", code="input(x)\naction\nprint(Int.toString x)")
            + trans("T2", "u", code="input (x)\noutput (y)\naction\nx + 1") + place("P2", "B", "S")
            + arc("A1", "PtoT", "T1", "P1", "x") + arc("A2", "TtoP", "T1", "P2", "x")
            + arc("A3", "PtoT", "T2", "P2", "x") + arc("A4", "TtoP", "T2", "P1", "y"))
    t = translate_text(cpn_xml(DECLS, page("PG1", "Top", body)), "m.cpn")
    assert any("code segment of transition 't'" in n and "not executed" in n for n in t.notes)
    assert "arc u -> A : (let val y = x + 1 in y end);" in t.text


# ------------------------------------------------------------------ messages


def test_a_recursive_function_that_draws_names_the_distribution_once(tmp_path):
    decls = DECLS + ('<ml id="M2">fun localize 0 = 0\n  | localize n = localize (n - 1) + floor (uniform (0.0, 1.0))'
                     '</ml><ml id="M3">fun place2 n = localize n + 1</ml>')
    body = (place("P1", "A", "S", "1`0") + trans("T1", "t") + arc("A1", "PtoT", "T1", "P1", "x")
            + arc("A2", "TtoP", "T1", "P1", "localize x") + trans("T2", "u") + arc("A3", "PtoT", "T2", "P1", "x")
            + arc("A4", "TtoP", "T2", "P1", "place2 x"))
    model = load(tmp_path, cpn_xml(decls, page("PG1", "Top", body)))
    assert [w.code for w in model.warnings] == ["W0105"]
    with pytest.raises(ModelError) as info:
        model.engine()
    [d] = info.value.diagnostics  # one call of uniform: one error, at it, naming it
    assert d.code == "E0206" and d.message.startswith("'uniform' draws a random value")
    assert "localize" not in d.message and d.span.file.endswith("m.cpn")


def test_an_error_in_a_used_sml_file_is_reported_in_that_file(tmp_path):
    # declarations without ';' between them, an error on line 5 of the .sml file
    (tmp_path / "lib.sml").write_text("\n\nfun twice x = 2 * x\n\nfun bad y = y + true\n")
    decls = DECLS + '<use id="U1"><ml>"lib.sml"</ml></use>'
    model = tmp_path / "m.cpn"
    model.write_text(cpn_xml(decls, page("PG1", "Top", place("P1", "A", "S", "1`(twice 1)"))))
    with pytest.raises(ModelError) as info:
        cpn.load(str(model))
    [d] = info.value.diagnostics
    assert d.span.file == str(tmp_path / "lib.sml") and (d.span.line, d.span.col) == (5, 17)
    assert "fun bad y = y + true" in info.value.render()


def test_a_used_sml_file_without_semicolons_between_declarations_loads(tmp_path):
    (tmp_path / "lib.sml").write_text("fun twice x = 2 * x\nval one = 1\n")
    decls = DECLS + '<use id="U1"><ml>"lib.sml"</ml></use>'
    model = tmp_path / "m.cpn"
    model.write_text(cpn_xml(decls, page("PG1", "Top", place("P1", "A", "S", "1`(twice one)"))))
    assert cpn.load(str(model)).net.places[0].initial == {2: 1}


def test_a_use_that_names_its_file_by_an_expression_is_found_beside_the_model(tmp_path):
    # `use (libpath^"config/lib.sml")` with libpath a folder of the author's machine
    (tmp_path / "config").mkdir()
    (tmp_path / "config" / "lib.sml").write_text("fun twice x = 2 * x;\n")
    decls = DECLS + ('<ml id="M2">val libpath = "c:/work/git/project/";</ml>'
                     '<use id="U1"><ml>(libpath^"config/lib.sml")</ml></use>')
    model = tmp_path / "m.cpn"
    model.write_text(cpn_xml(decls, page("PG1", "Top", place("P1", "A", "S", "1`(twice 1)"))))
    assert cpn.load(str(model)).net.places[0].initial == {2: 1}
    # only the file itself beside the model
    (tmp_path / "config" / "lib.sml").rename(tmp_path / "lib.sml")
    assert cpn.load(str(model)).net.places[0].initial == {2: 1}
    (tmp_path / "lib.sml").unlink()
    with pytest.raises(ModelError) as info:
        cpn.load(str(model))
    [d] = info.value.diagnostics
    assert "cannot read the ML file 'c:/work/git/project/config/lib.sml'" in d.message
    assert "'lib.sml' next to the model" in d.hint


def test_declarations_the_design_cpn_converter_left_unconverted_are_one_clear_error():
    decls = '<errordecl>val n = 5;\ncolor PH = index ph with 1..n declare ms;\nvar p : PH;</errordecl>'
    body = place("P1", "Think", "PH", "PH") + trans("T1", "t") + arc("A1", "PtoT", "T1", "P1", "p")
    with pytest.raises(ModelError) as info:
        translate_text(cpn_xml(decls, page("PG1", "Top", body)), "m.cpn")
    [d] = info.value.diagnostics
    assert d.code == "E0502" and "written for Design/CPN" in d.message and "'val n = 5;'" in d.message


def test_functions_that_talk_to_other_programs_or_use_the_sml_random_generator_are_named(tmp_path):
    decls = DECLS + ('<ml id="M2">fun conn (c, p) = let in MSC.addEvent (c, p) '
                     'end</ml><ml id="M3">fun pick n = Random.randRange (1, n) (Random.rand (1, 2))</ml>')
    body = (place("P1", "A", "S", "1`0") + trans("T1", "t") + arc("A1", "PtoT", "T1", "P1", "x")
            + arc("A2", "TtoP", "T1", "P1", "conn (x, 80)") + trans("T2", "u") + arc("A3", "PtoT", "T2", "P1", "x")
            + arc("A4", "TtoP", "T2", "P1", "pick 3"))
    with pytest.raises(ModelError) as info:
        translate_text(cpn_xml(decls, page("PG1", "Top", body)), "m.cpn")
    msgs = [d.message for d in info.value.diagnostics]
    assert len(msgs) == 1 and all(d.code == "E0502" for d in info.value.diagnostics)
    assert "'conn' calls 'MSC.addEvent', a side effect" in msgs[0]
    # Comms/CPN is kept: simulate stops where it is called, explore refuses each call
    # (tests/io/test_cpntools_other_programs.py)
    comms = decls.replace("MSC.addEvent (c, p)", 'ConnManagementLayer.openConnection (c, "127.0.0.1", p)')
    model = load(tmp_path, cpn_xml(comms, page("PG1", "Top", body.replace("conn (x, 80)", "(conn (\"c\", 80); x)"))))
    with pytest.raises(ModelError) as info:
        model.engine()
    assert sorted(d.params["name"] for d in info.value.diagnostics) == [
        "ConnManagementLayer.openConnection", "Random.rand", "Random.randRange"]
    # SML/NJ's Random is simulated; explore refuses each call of it, naming it (tests/lang/test_random_distributions.py)
    model = load(tmp_path, cpn_xml(decls, page("PG1", "Top", body.replace("conn (x, 80)", "x"))))
    with pytest.raises(ModelError) as info:
        model.engine()
    assert sorted(d.message.split("'")[1] for d in info.value.diagnostics) == ["Random.rand", "Random.randRange"]


def test_time_intervals_on_a_transition_and_an_output_arc(tmp_path):
    decls = ('<color id="C7"><id>TS</id><timed/><int><with><ml>0</ml><ml>3</ml></with></int></color>'
             '<var id="V1"><type><id>TS</id></type><id>x</id></var>')
    body = (place("P1", "A", "TS", "1`0") + place("P2", "B", "TS") + trans("T1", "t", cond="[x &lt; 2]", time="@+[1,2]")
            + arc("A1", "PtoT", "T1", "P1", "x") + arc("A2", "TtoP", "T1", "P2", "x@+[0,1]"))
    xml = cpn_xml(decls, page("PG1", "Top", body))
    model = load(tmp_path, xml)
    e = model.engine()
    # delays 1 + 0, 1 + 1, 2 + 0, 2 + 1: four binding elements, three different successors
    succ = list(e.successors(e.initial_state()))
    assert len(succ) == 4 and len({s for _, s in succ}) == 3


def test_discrete_on_an_output_arc_is_a_choice_and_inside_a_function_called_in_a_guard_only_simulated(tmp_path):
    body = (place("P1", "A", "S", "1`0") + place("P2", "B", "INT") + trans("T1", "t", cond="[x = 0]")
            + arc("A1", "PtoT", "T1", "P1", "x") + arc("A2", "TtoP", "T1", "P2", "discrete(1, 3)"))
    model = load(tmp_path, cpn_xml(DECLS, page("PG1", "Top", body)))
    assert [w.code for w in model.warnings] == ["W0104"]
    e = model.engine()
    assert len(list(e.successors(e.initial_state()))) == 3
    decls = DECLS + '<ml id="M2">fun roll () = discrete(1, 6)</ml>'
    # called on the output arc, the function is written out there: a choice of its six values
    model = load(tmp_path, cpn_xml(decls, page("PG1", "Top", body.replace("discrete(1, 3)", "roll ()"))))
    assert [w.code for w in model.warnings] == ["W0104"]
    e = model.engine()
    assert len(list(e.successors(e.initial_state()))) == 6
    # called in a guard, it is a random draw
    body = body.replace("discrete(1, 3)", "x").replace("[x = 0]", "[x = 0 andalso roll () > 1]")
    model = load(tmp_path, cpn_xml(decls, page("PG1", "Top", body)))
    assert [w.code for w in model.warnings] == ["W0105"]
    with pytest.raises(ModelError) as info:
        model.engine()
    [d] = info.value.diagnostics
    assert d.code == "E0206" and d.message.startswith("'discrete' draws a random value") and "roll" not in d.message


def test_a_reference_declared_with_val_and_read_by_an_inscription_is_simulated_and_refused_at_the_ref(tmp_path):
    decls = DECLS + '<ml id="M2">val delay = ref 0;</ml>'
    # read by the guard: the value the previous occurrence assigned (tests/io/test_cpntools_code_refs.py has
    # the variable read only by the outputs of the transition that assigns it, which is explored)
    body = (place("P1", "A", "S", "1`0") + trans("T1", "t", cond="x = (!delay)", code="input (x)\naction\ndelay := x")
            + arc("A1", "PtoT", "T1", "P1", "x") + arc("A2", "TtoP", "T1", "P1", "x"))
    xml = cpn_xml(decls, page("PG1", "Top", body))
    model = load(tmp_path, xml)
    assert sorted(w.code for w in model.warnings) == ["W0106", "W0106"]  # the ref and the action
    with pytest.raises(ModelError) as info:
        model.engine()
    line = next(i + 1 for i, x in enumerate(xml.splitlines()) if "val delay = ref 0" in x)
    ref = [d for d in info.value.diagnostics if d.params["name"] == "ref"]
    assert [(d.code, d.span.line) for d in ref] == [("E0206", line)]
