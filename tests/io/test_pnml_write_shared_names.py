"""PNML writing of a net whose place and transition share a name (CPN Tools allows it): each node gets an
id of its own, and every arc joins the place to the transition in the direction the net gives."""

from __future__ import annotations

import re

from cpn.io.pnml import translate_text, write_text

NET = ("colset U = unit;\nplace go : U = 1`();\ntrans go;\nplace done : U;\n"
       "arc place go -> trans go : ();\narc trans go -> done : ();\n")


def test_a_place_and_a_transition_of_one_name_get_two_ids():
    text = write_text(NET, net_id="n")
    place_id = re.search(r'<place id="([^"]+)"><name><text>go<', text).group(1)
    trans_id = re.search(r'<transition id="([^"]+)"><name><text>go<', text).group(1)
    assert place_id != trans_id
    assert f'source="{place_id}" target="{trans_id}"' in text
    done_id = re.search(r'<place id="([^"]+)"><name><text>done<', text).group(1)
    assert f'source="{trans_id}" target="{done_id}"' in text


def test_the_written_net_reads_back_with_the_same_arcs():
    again = translate_text(write_text(NET, net_id="n"))
    # the reader keeps the PNML names and adds the id where two nodes share a name
    arcs = [line for line in again.splitlines() if line.startswith("arc")]
    assert arcs == ['arc go -> "go (go_2)";', 'arc "go (go_2)" -> done;']
