"""The CPN Tools `.cpn` translator: generated text, refusals with positions, and the sample nets."""

from __future__ import annotations

import glob
import os

import pytest

from cpn.errors import ModelError
from cpn.io.cpntools import remap_error, translate, translate_text
from cpn.lang.parser import parse
from tests._shared import SHARED, needs_shared

SAMPLES = SHARED + "/cpntools-samples"
LIMIT = SHARED + "/validation/CPNBook-LimitProtocol/7-2LimitProtocol.cpn"


def cpn_xml(globbox: str = "", pages: str = "", extra: str = "", instances: str | None = None) -> str:
    """A minimal CPN Tools file around the given globbox declarations and pages."""
    if instances is None:
        instances = '<instances><instance id="I1" page="PG1"/></instances>'
    return (
        '<?xml version="1.0" encoding="iso-8859-1"?>\n'
        '<!DOCTYPE workspaceElements PUBLIC "-//CPN//DTD CPNXML 1.0//EN" "http://cpntools.org/DTD/6/cpn.dtd">\n'
        "<workspaceElements>\n<generator tool=\"CPN Tools\" version=\"4.0.1\" format=\"6\"/>\n<cpnet>\n"
        f"<globbox>\n{globbox}\n</globbox>\n{pages}\n{extra}\n{instances}\n</cpnet>\n</workspaceElements>\n"
    )


def place(pid, name, cs, init="", port=None, fusion=None):
    p = f'<port id="{pid}p" type="{port}"/>' if port else ""
    f = f'<fusioninfo id="{pid}f" name="{fusion}"/>' if fusion else ""
    return (f'<place id="{pid}"><text>{name}</text><type id="{pid}t"><text>{cs}</text></type>'
            f'<initmark id="{pid}i"><text>{init}</text></initmark>{p}{f}</place>')


def trans(tid, name, cond="", time="", code="", prio="", channel="", subst=""):
    return (f'<trans id="{tid}" explicit="false"><text>{name}</text>{subst}'
            f'<cond id="{tid}c"><text>{cond}</text></cond><time id="{tid}t"><text>{time}</text></time>'
            f'<code id="{tid}k"><text>{code}</text></code><priority id="{tid}p"><text>{prio}</text></priority>'
            f'<channel id="{tid}h"><text>{channel}</text></channel></trans>')


def arc(aid, orient, tid, pid, annot=""):
    return (f'<arc id="{aid}" orientation="{orient}" order="1"><transend idref="{tid}"/>'
            f'<placeend idref="{pid}"/><annot id="{aid}a"><text>{annot}</text></annot></arc>')


def page(pid, name, body):
    return f'<page id="{pid}"><pageattr name="{name}"/>{body}</page>'


DECLS = ('<color id="C1"><id>UNIT</id><unit/></color><color id="C2"><id>INT</id><int/></color>'
         '<color id="C3"><id>S</id><int><with><ml>0</ml><ml>3</ml></with></int></color>'
         '<var id="V1"><type><id>S</id></type><id>x</id><id>y</id></var>'
         '<ml id="M1">val N = 3</ml>')


def codes(exc: ModelError) -> list[str]:
    return [d.code for d in exc.diagnostics]


# ------------------------------------------------------------------ generated text


def test_one_page_net_translates_every_element_kind():
    body = (place("P1", "Packets\nTo Send", "S", "1`0++1`1") + place("P2", "B", "S") + place("P3", "Lim", "UNIT", "3`()")
            + trans("T1", "Send Packet", cond="[x&lt;N]", time="@+5", prio="P_HIGH")
            + arc("A1", "PtoT", "T1", "P1", "x") + arc("A2", "TtoP", "T1", "P2", "x@+2")
            + arc("A3", "BOTHDIR", "T1", "P3", "()") + arc("A4", "Inhibitor", "T1", "P2", "")
            + arc("A5", "Reset", "T1", "P2"))
    text = translate_text(cpn_xml(DECLS, page("PG1", "Top Page", body)), "t.cpn").text
    assert "net Top_Page;" in text
    assert "colset S = int with 0..3;" in text
    assert "var x, y : S;" in text
    assert "val N = 3;" in text  # the missing ';' is added
    assert "place Packets_To_Send : S = 1`0++1`1;" in text
    assert "trans Send_Packet [x<N] @+5 priority 100;" in text
    assert "arc Packets_To_Send -> Send_Packet : x;" in text
    assert "arc Send_Packet -> B : x@+2;" in text
    assert "arc Lim <-> Send_Packet : ();" in text
    assert "inhibitor B -> Send_Packet;" in text
    assert "reset B -> Send_Packet;" in text
    assert "(* A1 on page Top_Page, line" in text
    parse(text, "t.cpnet")


def test_names_that_are_not_identifiers_are_quoted():
    body = place("P1", "val", "S") + place("P2", "1st", "S") + place("P3", "a.b", "S") + place("P4", "Acknowledg-\nment", "S") + trans("T1", "in")
    text = translate_text(cpn_xml(DECLS, page("PG1", "Top", body)), "t.cpn").text
    assert 'place "val" : S;' in text and 'place "1st" : S;' in text and "place a_b : S;" in text
    assert "place Acknowledg__ment : S;" in text
    assert 'trans "in";' in text
    parse(text, "t.cpnet")


def test_guard_without_brackets_is_wrapped_and_list_guard_kept():
    body = place("P1", "A", "S", "1`0") + trans("T1", "t", cond="x = 1") + trans("T2", "u", cond="[x = 1, y = 2]")
    body += arc("A1", "PtoT", "T1", "P1", "x") + arc("A2", "PtoT", "T2", "P1", "x")
    text = translate_text(cpn_xml(DECLS, page("PG1", "Top", body)), "t.cpn").text
    assert "trans t [x = 1];" in text and "trans u [x = 1, y = 2];" in text


def test_structured_colour_sets():
    decls = ('<color id="C1"><id>E</id><enum><id>a</id><id>b</id></enum></color>'
             '<color id="C2"><id>PH</id><index><ml>1</ml><ml>5</ml><id>ph</id></index></color>'
             '<color id="C3"><id>P</id><timed/><product><id>E</id><id>PH</id></product></color>'
             '<color id="C4"><id>R</id><record><recordfield><id>f</id><id>E</id></recordfield>'
             '<recordfield><id>g</id><id>PH</id></recordfield></record></color>'
             '<color id="C5"><id>L</id><list><id>E</id></list></color>'
             '<color id="C6"><id>U</id><union><unionfield><id>A</id><type><id>E</id></type></unionfield>'
             '<unionfield><id>B</id></unionfield></union></color>'
             '<color id="C7"><id>Al</id><alias><id>E</id></alias></color>'
             '<color id="C8"><id>Sub</id><subset><id>PH</id><by><ml>ok</ml></by></subset></color>'
             '<block id="B1"><id>Standard</id><color id="C9"><id>BOOL</id><bool/></color></block>'
             '<color id="C10"><id>X</id><layout>colset X = int with 1..2;</layout></color>')
    text = translate_text(cpn_xml(decls, page("PG1", "Top", place("P1", "A", "E"))), "t.cpn").text
    for line in ["colset E = with a | b;", "colset PH = index ph with 1..5;", "colset P = product E * PH timed;",
                 "colset R = record f : E * g : PH;", "colset L = list E;", "colset U = union A : E + B;",
                 "colset Al = E;", "colset Sub = subset PH by ok;", "(* block Standard *)", "colset BOOL = bool;",
                 "colset X = int with 1..2;"]:
        assert line in text, line


def test_timed_initial_marking_with_time_stamps():
    decls = '<color id="C1"><id>T</id><timed/><int/></color>'
    text = translate_text(cpn_xml(decls, page("PG1", "Top", place("P1", "A", "T", "1`3@5+++2`4@0"))), "t.cpn").text
    assert "place A : T = 1`3@+ 5+++2`4@+ 0;" in text


def test_hierarchy_ports_sockets_instances_and_fusion():
    sub = page("PG2", "Sub Page", place("Q1", "In", "S", port="In") + place("Q2", "Out", "S", port="Out")
               + place("Q3", "Loc", "S", "1`1", fusion="Fusion 1")
               + trans("U1", "Move") + arc("B1", "PtoT", "U1", "Q1", "x") + arc("B2", "TtoP", "U1", "Q2", "x"))
    st = '<subst subpage="PG2" portsock="(Q1,P1)(Q2,P2)"><subpageinfo id="SI" name="Sub Page"/></subst>'
    st2 = '<subst subpage="PG2" portsock="(Q2,P3)(Q1,P2)"><subpageinfo id="SJ" name="Sub Page"/></subst>'
    top = page("PG1", "Top", place("P1", "A", "S", "1`0") + place("P2", "B", "S") + place("P3", "C", "S")
               + place("P4", "F", "S", fusion="Fusion 1")
               + trans("T1", "First", subst=st) + trans("T2", "Second", subst=st2)
               + arc("A1", "PtoT", "T1", "P1", "x"))
    inst = ('<instances><instance id="I1" page="PG1"><instance id="I3" trans="T2"/>'
            '<instance id="I2" trans="T1"/></instance></instances>')
    t = translate_text(cpn_xml(DECLS, sub + top, instances=inst), "t.cpn")
    text = t.text
    assert "module Sub_Page {" in text
    assert "port in In : S;" in text and "port out Out : S;" in text
    assert "place Loc : S = 1`1 fusion Fusion_1;" in text
    assert "place F : S fusion Fusion_1;" in text
    # instances in the order of the instance tree (Second is page instance 1), socket arcs dropped
    second, first = text.index("instance Second"), text.index("instance First")
    assert second < first
    assert "instance First = Sub_Page() { In = A, Out = B };" in text
    assert "instance Second = Sub_Page() { Out = C, In = B };" in text
    assert "arc A -> First" not in text
    assert text.index("module Sub_Page") < text.index("place A")
    parse(text, "t.cpnet")


def test_several_root_pages_become_instances_of_the_top_level():
    p1 = page("PG1", "One", place("P1", "A", "S"))
    p2 = page("PG2", "Two", place("Q1", "B", "S"))
    inst = '<instances><instance id="I1" page="PG1"/><instance id="I2" page="PG2"/></instances>'
    text = translate_text(cpn_xml(DECLS, p1 + p2, instances=inst), "t.cpn").text
    assert "net One;" in text and "module Two {" in text and "instance Two = Two() { };" in text
    parse(text, "t.cpnet")


def test_globref_never_assigned_is_a_constant():
    decls = DECLS + '<globref id="G1"><id>lim</id><ml>4</ml></globref>'
    body = place("P1", "A", "S", "1`0") + trans("T1", "t", cond="[x &lt; !lim]") + arc("A1", "PtoT", "T1", "P1", "x")
    text = translate_text(cpn_xml(decls, page("PG1", "Top", body)), "t.cpn").text
    assert "val lim = 4;" in text and "trans t [x < lim];" in text


def test_code_segment_without_output_is_noted_and_dropped():
    body = place("P1", "A", "S", "1`0") + trans("T1", "t", code="input (x);\naction\nprint(Int.toString x);")
    body += arc("A1", "PtoT", "T1", "P1", "x")
    t = translate_text(cpn_xml(DECLS, page("PG1", "Top", body)), "t.cpn")
    assert any("code segment" in n for n in t.notes)
    assert "(* note: the code segment" in t.text


# ------------------------------------------------------------------ refusals


def refused(xml: str) -> ModelError:
    with pytest.raises(ModelError) as info:
        translate_text(xml, "bad.cpn")
    return info.value


def test_refusals_are_positioned_and_all_reported_in_one_run():
    body = (place("P1", "A", "S", "1`0")
            + trans("T1", "t", code="input (x);\noutput (y);\naction (send(Int.toString x); x+1);")
            + trans("T2", "u", time="@++1.5")
            + trans("T3", "v", channel="ch.?x")
            + arc("A1", "TtoP", "T2", "P1", "exponential(1.0)"))
    err = refused(cpn_xml(DECLS, page("PG1", "Top", body)))
    # exponential(1.0) and '@++' are simulated (tests/lang/test_random_distributions.py, test_real_delays.py)
    assert codes(err) == ["E0502"] * 2
    msgs = " | ".join(d.message for d in err.diagnostics)
    assert "output variable(s) y" in msgs and "synchronous channel" in msgs
    assert all(d.span.file == "bad.cpn" and d.span.line > 1 for d in err.diagnostics)


def test_random_function_called_through_a_declared_function_is_simulated_and_refused_by_explore(tmp_path):
    import cpn

    # called in a guard, the draw is a random draw (called in a delay, it would be a choice of every value,
    # tests/lang/test_function_draws.py)
    decls = DECLS + '<ml id="M2">fun Delay() = discrete(1,3);</ml>'
    body = (place("P1", "A", "S", "1`0") + trans("T1", "t", cond="Delay() > 1")
            + arc("A1", "PtoT", "T1", "P1", "x"))
    path = tmp_path / "t.cpn"
    path.write_text(cpn_xml(decls, page("PG1", "Top", body)))
    model = cpn.load(path)
    [w] = [w for w in model.warnings if w.code == "W0105"]
    assert "'discrete'" in w.message
    with pytest.raises(ModelError) as info:
        model.engine()
    [d] = info.value.diagnostics
    # the distribution, not the function that calls it, at its place in the .cpn file
    assert d.code == "E0206" and d.message.startswith("'discrete' draws a random value") and "Delay" not in d.message
    assert d.span.file == str(path) and d.span.line > 1


def test_an_enumeration_constant_named_like_a_distribution_is_not_refused():
    decls = DECLS + '<color id="C9"><id>M</id><enum><id>normal</id><id>fast</id></enum></color>'
    body = place("P1", "A", "M", "1`normal")
    translate_text(cpn_xml(decls, page("PG1", "Top", body)), "t.cpn")


def test_bad_portsock():
    sub = page("PG2", "S", place("Q1", "In", "S"))
    st = '<subst subpage="PG2" portsock="(Q1,P1)(Q9,P1)"/>'
    top = page("PG1", "Top", place("P1", "A", "") + trans("T1", "x", subst=st))
    err = refused(cpn_xml(DECLS, sub + top, instances=""))
    msgs = [d.message for d in err.diagnostics]
    assert any("is not a port" in m for m in msgs)
    assert any("(Q9,P1)" in m for m in msgs)
    assert len(msgs) == 2  # a place without a colour set is UNIT (test_cpntools_as_written.py)


def test_malformed_xml_is_e0501_with_position():
    err = refused("<workspaceElements><cpnet></workspaceElements>")
    assert codes(err) == ["E0501"] and err.diagnostics[0].span.line == 1


def test_not_a_cpn_file():
    err = refused("<pnml/>")
    assert "not a CPN Tools net" in err.diagnostics[0].message


def test_missing_file_is_e0501():
    with pytest.raises(ModelError) as info:
        translate("/nonexistent/x.cpn")
    assert codes(info.value) == ["E0501"]


def test_use_file_is_read_relative_to_the_model(tmp_path):
    (tmp_path / "lib.sml").write_text("fun twice x = 2 * x;\n")
    decls = DECLS + '<use id="U1"><ml>"lib.sml"</ml></use>'
    model = tmp_path / "m.cpn"
    model.write_text(cpn_xml(decls, page("PG1", "Top", place("P1", "A", "S", "1`(twice 1)"))))
    assert "fun twice x = 2 * x;" in translate(str(model))
    (tmp_path / "lib.sml").unlink()
    with pytest.raises(ModelError) as info:
        translate(str(model))
    assert "lib.sml" in info.value.diagnostics[0].message


def test_errors_in_generated_text_map_back_to_the_cpn_file():
    body = place("P1", "A", "S", "1`0") + trans("T1", "t") + arc("A1", "PtoT", "T1", "P1", "x +")
    xml = cpn_xml(DECLS, page("PG1", "Top", body))
    t = translate_text(xml, "m.cpn")
    line = next(i for i, s in enumerate(t.text.splitlines(), 1) if s.startswith("arc A -> t"))
    col = t.text.splitlines()[line - 1].index("x +") + 1
    span, origin = t.locate(line, col + 2)
    xml_lines = xml.splitlines()
    assert origin.element == "A1"
    assert xml_lines[span.line - 1][span.col - 1] == "+"
    from cpn.diagnostics import Diagnostic, Span

    mapped = remap_error(ModelError([Diagnostic("E0101", "boom", Span("m.cpnet", line, col + 2))]), t, "m.cpnet")
    d = mapped.diagnostics[0]
    assert (d.span.file, d.span.line) == ("m.cpn", span.line) and "A1" in d.notes[0]


# ------------------------------------------------------------------ the sample nets

# Expected outcome of translating each CPN Tools sample: None = translates (and parses), or the
# E0502 refusal and a fragment of its message.
SAMPLE_TRANSLATION = {
    "DiningPhilosophers": None,
    "DiningPhilosophers_ASKCTL": None,
    "DiningPhilosophers_COMM": None,
    "DiningPhilosophers_COMM_Mon": None,
    "DistributedDataBase": None,  # PR.mult(1`s, DBM.all() -- 1`s)
    "DistributedDataBase_OG": None,
    "HierarchicalProtocol": None,
    "ProtocolWithTimer": None,
    "QueueSystem": None,  # exponential and JobType.ran() inside functions: simulated, refused by explore
    "QueueSystemConfigs": None,  # reference variables set by code segments: simulated, refused by explore
    "RealTimedProtocol": None,  # '@++' and its draws: simulated, refused by explore (test_real_delays.py)
    "RealTimedResourceAlloc": None,  # '@++' and exponential(..): simulated, refused by explore
    "ResourceAllocation": None,
    "ResourceAllocation_OG": None,
    "ResourceAllocation_OG_Graphviz": None,
    "RingProtocol": None,
    "SimpleProtocol": None,
    "SimpleProtocol_IO": None,  # a reference read from a file: simulate stops at the action that opens it
    "SimpleProtocol_MSC": ("E0502", "binds the output variable(s) evt"),
    "SimpleProtocol_OG": None,
    "SimpleProtocol_RP": None,
    "Telephones": None,
    "TimedProtocol": None,
    "TimedResourceAlloc": None,
    "channel": ("E0502", "synchronous channel"),
    "priorities": None,
}


@needs_shared
def test_the_table_covers_every_sample():
    names = {os.path.basename(p)[:-4] for p in glob.glob(f"{SAMPLES}/*.cpn")}
    assert names == set(SAMPLE_TRANSLATION)


@needs_shared
@pytest.mark.parametrize("name", sorted(SAMPLE_TRANSLATION))
def test_sample_loads_or_is_refused_clearly(name):
    import cpn

    path = f"{SAMPLES}/{name}.cpn"
    expected = SAMPLE_TRANSLATION[name]
    if expected is None:
        cpn.load(path)
        return
    code, fragment = expected
    with pytest.raises(ModelError) as info:
        cpn.load(path)
    diags = info.value.diagnostics
    assert code in {d.code for d in diags}
    assert any(fragment in d.message for d in diags), [d.message for d in diags]
    assert all(d.span is not None and d.span.file == path and d.span.line > 1 for d in diags)
    if code == "E0502":
        assert {d.code for d in diags} == {"E0502"}
        assert all(d.hint for d in diags)


@needs_shared
def test_limit_protocol_translates():
    text = translate(LIMIT)
    assert "net Protocol;" in text and "place Limit : UNIT = 3`();" in text
    parse(text, "limit.cpnet")


def test_code_segment_with_pure_action_becomes_a_let_around_the_outputs():
    body = (place("P1", "A", "S", "1`0") + place("P2", "B", "S")
            + trans("T1", "t", time="@+z", code="input (x);\noutput (z);\naction\n(x + 1) mod 4;")
            + arc("A1", "PtoT", "T1", "P1", "x") + arc("A2", "TtoP", "T1", "P2", "z"))
    text = translate_text(cpn_xml(DECLS, page("PG1", "Top", body)), "t.cpn").text
    assert "trans t @+ (let val z = (x + 1) mod 4 in z end);" in text
    assert "arc t -> B : (let val z = (x + 1) mod 4 in z end);" in text
    assert "arc A -> t : x;" in text
    parse(text, "t.cpnet")


def test_code_segment_with_side_effects_and_outputs_is_refused():
    body = (place("P1", "A", "S", "1`0") + trans("T1", "t", code="input (x);\noutput (z);\naction\nMSC.start(x);")
            + arc("A1", "PtoT", "T1", "P1", "x"))
    err = refused(cpn_xml(DECLS, page("PG1", "Top", body)))
    assert "uses MSC.start" in err.diagnostics[0].message


# ------------------------------------------------------------------ cpn-verify convert


@needs_shared
def test_convert_writes_a_model_that_loads(tmp_path, capsys):
    from cpn.cli.main import main

    out = tmp_path / "dp.cpnet"
    assert main(["convert", f"{SAMPLES}/DiningPhilosophers.cpn", "-o", str(out)]) == 0
    assert "place Unused_Chopsticks : CS = CS.all();" in out.read_text()


@needs_shared
def test_convert_refuses_with_exit_65_and_positions(tmp_path, capsys):
    from cpn.cli.main import main

    assert main(["convert", f"{SAMPLES}/channel.cpn", "-o", str(tmp_path / "c.cpnet")]) == 65
    err = capsys.readouterr().err
    assert f"{SAMPLES}/channel.cpn:246:34: error[E0502]" in err


def test_convert_reports_front_end_errors_in_the_written_file_with_the_cpn_origin(tmp_path, capsys):
    from cpn.cli.main import main

    body = place("P1", "A", "S", "1`0") + trans("T1", "t") + arc("A1", "PtoT", "T1", "P1", "undefined_name")
    model = tmp_path / "m.cpn"
    model.write_text(cpn_xml(DECLS, page("PG1", "Top", body)))
    assert main(["convert", str(model)]) == 65
    err = capsys.readouterr().err
    assert f"{tmp_path}/m.cpnet:" in err and "unknown name 'undefined_name'" in err
    assert "from arc inscription A/t (A1 on page 'Top')" in err and f"{model}:" in err


def test_a_nullary_function_that_is_cs_ran_is_inlined():
    decls = DECLS + '<ml id="M2">fun pick() = S.ran();</ml>'
    body = place("P1", "A", "UNIT", "1`()") + place("P2", "B", "S") + trans("T1", "t")
    body += arc("A1", "PtoT", "T1", "P1", "()") + arc("A2", "TtoP", "T1", "P2", "pick()")
    text = translate_text(cpn_xml(decls, page("PG1", "Top", body)), "t.cpn").text
    assert "arc t -> B : S.ran();" in text
    import cpn

    engine = cpn.loads(text, "t.cpnet").engine()
    assert len(list(engine.successors(engine.initial_state()))) == 4  # S = int with 0..3


def test_realtimestamp_option_is_noted():
    opts = ('<options><option name="realtimestamp"><value><boolean>true</boolean></value></option></options>')
    t = translate_text(cpn_xml(DECLS, page("PG1", "Top", place("P1", "A", "S")), extra=opts), "t.cpn")
    assert any("realtimestamp" in n for n in t.notes) and "(* note: the net sets the option 'realtimestamp'" in t.text


def test_unused_declarations_are_left_out_and_used_ones_kept():
    decls = DECLS + ('<ml id="M2">fun helper x = x + 1;</ml><ml id="M3">fun used x = helper x;</ml>'
                     '<ml id="M4">fun logit () = TextIO.print "x";</ml>')
    body = place("P1", "A", "S", "1`(used 0)")
    text = translate_text(cpn_xml(decls, page("PG1", "Top", body)), "t.cpn").text
    assert "fun helper x = x + 1;" in text and "fun used x = helper x;" in text
    assert "fun logit" not in text and "(* declaration M4 (logit) at line" in text


@needs_shared
def test_convert_reads_pnml_too(tmp_path):
    from cpn.cli.main import main

    out = tmp_path / "tr.cpnet"
    src = os.path.join(os.path.dirname(SAMPLES), "validation", "TokenRing-COL-005", "model.pnml")
    assert main(["convert", src, "-o", str(out)]) == 0
    import cpn

    assert len(cpn.load(str(out)).net.places) >= 1


def test_an_error_after_entities_is_placed_at_its_column_in_the_file(tmp_path):
    """`&gt;` is one character of an inscription and four of the file: columns count the file's."""
    import cpn

    body = (place("P1", "A", "S", "1`0")
            + trans("T1", "t", cond="[x &gt; 0 andalso x &lt;&gt; 2 andalso zz]")
            + arc("A1", "PtoT", "T1", "P1", "if x &gt; 1\nthen 1`x else if x &lt; 1 then 1`x else 1`qq"))
    path = tmp_path / "e.cpn"
    path.write_text(cpn_xml(DECLS, page("PG1", "Top", body)), encoding="iso-8859-1")
    with pytest.raises(ModelError) as info:
        cpn.load(str(path))
    raw = path.read_text(encoding="iso-8859-1").split("\n")
    expected = {}
    for name, marker in (("zz", "zz]"), ("qq", "`qq")):
        line = next(i for i, text in enumerate(raw, 1) if marker in text)
        expected[name] = (line, raw[line - 1].index(marker) + 1 + marker.index(name))
    got = {d.message.split("'")[1]: (d.span.line, d.span.col) for d in info.value.diagnostics if d.code == "E0201"}
    assert got == expected
