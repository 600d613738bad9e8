"""An invariant that follows from the net's structure (a place invariant of the incidence matrix of token
counts) is warned about; one that holds only because of how the net behaves is not."""

import cpn
from cpn.properties.structure import is_place_invariant, token_count

MODEL = """net S;
colset U = unit;
colset N = int with 0..3;
var n : N;
place A : U = 1`();
place C : U;
place D : N = 1`0;
trans move;
arc A -> move : ();
arc move -> C : ();
trans back;
arc C -> back : ();
arc back -> A : ();
trans drop [1 = 2];
arc A -> drop : ();
trans count [n < 3];
arc D -> count : n;
arc count -> D : if n = 0 then 1`(n + 1) else empty;
"""

SCENARIO = """model = "s.cpnet"
[[property]]
name = "one token in A or C"
kind = "invariant"
expr = "size (S'A 1) + size (S'C 1) = 1"

[[property]]
name = "A and C, conjunctions and multiples"
kind = "invariant"
expr = "2 * size (S'A 1) = 2 - 2 * size (S'C 1) andalso size (S'C 1) + size (S'A 1) <= 1"

[[property]]
name = "at most one A"
kind = "invariant"
expr = "size (S'A 1) <= 1"
"""

STRUCTURAL = ("follows from the net's structure: the weighted sum of token counts it compares is a place "
              "invariant (the same in every reachable marking of any initial marking), so no guard, token "
              "value or order of occurrences can break it")


def results(tmp_path, model=MODEL):
    (tmp_path / "s.cpnet").write_text(model, encoding="utf-8")
    (tmp_path / "s.toml").write_text(SCENARIO, encoding="utf-8")
    (run,) = cpn.check(str(tmp_path / "s.toml"))
    assert run.status.value == "holds"
    return {r.spec.name: r.warnings for r in run.results}


def test_a_property_that_only_the_behaviour_keeps_is_not_structural(tmp_path):
    # 'drop' takes from A and puts nothing, but its guard is never true: A + C = 1 holds, not by structure
    w = results(tmp_path)
    assert w == {"one token in A or C": [], "A and C, conjunctions and multiples": [], "at most one A": []}


def test_a_place_invariant_is_reported(tmp_path):
    w = results(tmp_path, MODEL.replace("trans drop [1 = 2];\narc A -> drop : ();\n", ""))
    assert w["one token in A or C"] == [STRUCTURAL]
    assert w["A and C, conjunctions and multiples"] == [STRUCTURAL]
    # size (S'A 1) alone is no invariant: 'move' takes its token
    assert w["at most one A"] == []


def test_token_counts_of_inscriptions():
    net = cpn.loads(MODEL).net
    count = net.transition("S'count 1")
    assert [token_count(a.expr) for a in count.arcs] == [1, None]  # the 'if' puts one token or none
    a, c, d = (net.place(f"S'{x} 1").index for x in "ACD")
    assert not is_place_invariant(net, {a: 1, c: 1})  # 'drop'
    assert not is_place_invariant(net, {d: 1})  # 'count', whose output depends on the binding
    without_drop = cpn.loads(MODEL.replace("trans drop [1 = 2];\narc A -> drop : ();\n", "")).net
    assert is_place_invariant(without_drop, {a: 1, c: 1}) and is_place_invariant(without_drop, {a: 3, c: 3})
    assert not is_place_invariant(without_drop, {a: 1, c: 2})


BOUNDS = """model = "s.cpnet"
[[property]]
name = "A at most one"
kind = "bound"
place = "S'A 1"
at_most = 1

[[property]]
name = "A: upper 1, lower 0"
kind = "bound"
place = "S'A 1"
upper_equals = 1
lower_equals = 0

[[property]]
name = "A at most one, as an expression"
kind = "bound"
expr = "size (S'A 1)"
at_most = 1

[[property]]
name = "D at most one"
kind = "bound"
place = "S'D 1"
at_most = 1
"""

STRUCTURAL_BOUND = ("follows from the net's structure: place invariants of the incidence matrix and the initial "
                    "marking give the bound (at most 1), so no guard, token value or order of occurrences can "
                    "break it")


def test_bounds_that_place_invariants_give(tmp_path):
    (tmp_path / "s.cpnet").write_text(MODEL.replace("trans drop [1 = 2];\narc A -> drop : ();\n", ""),
                                      encoding="utf-8")
    (tmp_path / "s.toml").write_text(BOUNDS, encoding="utf-8")
    (run,) = cpn.check(str(tmp_path / "s.toml"))
    w = {r.spec.name: r.warnings for r in run.results}
    assert run.status.value == "holds"
    assert w["A at most one"] == [STRUCTURAL_BOUND]  # A + C = 1
    assert w["A at most one, as an expression"] == [STRUCTURAL_BOUND]
    assert w["A: upper 1, lower 0"] == []  # the lower bound 0 needs a marking where A is empty: behaviour
    assert w["D at most one"] == []  # 'count' puts one token or none on D: no invariant covers D
    (tmp_path / "s.cpnet").write_text(MODEL, encoding="utf-8")  # with 'drop', A + C is no invariant
    (run,) = cpn.check(str(tmp_path / "s.toml"))
    assert all(not r.warnings for r in run.results)


def test_farkas_finds_the_minimal_invariants():
    from cpn.properties.structure import semi_positive_invariants, structural_bound

    net = cpn.loads(MODEL.replace("trans drop [1 = 2];\narc A -> drop : ();\n", "")).net
    a, c, d = (net.place(f"S'{x} 1").index for x in "ACD")
    assert semi_positive_invariants(net) == [{a: 1, c: 1}]
    assert structural_bound(net, a) == (1, False) and structural_bound(net, d) == (None, False)
    ring = cpn.loads("colset N = int with 0..3; var n : N; place P : N = 1`0 ++ 1`1; trans t; arc P -> t : n;"
                     " arc t -> P : (n + 1) mod 4;").net
    assert structural_bound(ring, 0) == (2, True)  # one token in, one out: the count never changes


def test_inhibitor_double_and_reset_arcs_in_the_incidence_matrix():
    # an inhibitor or double arc leaves its place's count as it is; a reset arc empties its place by an
    # amount no matrix holds: no invariant weighs that place
    from cpn.properties.structure import semi_positive_invariants

    base = MODEL.replace("trans drop [1 = 2];\narc A -> drop : ();\n", "")
    net = cpn.loads(base + "place E : U = 1`();\ninhibitor E -> move;\narc E <-> back : ();\n").net
    a, c, e = (net.place(f"S'{x} 1").index for x in "ACE")
    assert is_place_invariant(net, {a: 1, c: 1}) and is_place_invariant(net, {e: 1})
    assert sorted(semi_positive_invariants(net), key=len) == [{e: 1}, {a: 1, c: 1}]
    net = cpn.loads(base + "place E : U = 1`();\nreset E -> move;\n").net
    a, c, e = (net.place(f"S'{x} 1").index for x in "ACE")
    assert is_place_invariant(net, {a: 1, c: 1}) and not is_place_invariant(net, {a: 1, c: 1, e: 1})
    assert semi_positive_invariants(net) == [{a: 1, c: 1}]
