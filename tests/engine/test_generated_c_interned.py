"""Colour sets without a finite layout in the generated C (`cpn.engine.ctables.Interned`): unbounded ints,
and products and records with them, as colour ids interned in the order their values are first met, the
same in C and in the Python engine. The graph must be the Python search's: the same states under the
same ids, the same arcs in the same order, the same binding elements, on random nets over such colour
sets, untimed (the native search, and its threads) and timed (the native timed search)."""

from __future__ import annotations

import random

import pytest

import cpn
from cpn.engine import ccodegen
from cpn.statespace import ExploreOptions, Explorer, native, nativetimed
from cpn.statespace.store import packed_unavailable
from tests._shared import count_calls
from tests.engine._explore import same_exploration
from tests.engine.test_generated_c import _both
from tests.statespace._partition import summary

NATIVE = packed_unavailable()
needs_native = pytest.mark.skipif(NATIVE is not None, reason=f"native code unavailable: {NATIVE}")

HEADER = """colset I = int;
colset B = bool;
colset N = int with 0..2;
colset IB = product I * B;
colset R = record a : I * n : N * f : B;
colset TI = int timed;
var x, y : I;
var b : B;
var n : N;
var r : R;
fun up (v, k) = if v < 4 then v + k else v - 5;
fun flip {a = a, n = n, f = f} = {a = a * 2 - 1, n = (n + 1) mod 3, f = not f};
"""


def _int(rng, lo: int, hi: int) -> str:
    v = rng.randint(lo, hi)
    return f"~{-v}" if v < 0 else str(v)


# per colour set: input patterns and output values, each with the variables it binds or needs
PATTERNS = {"I": [("x", "x"), ("y", "y"), ("x", "x"), ("1", "")],
            "IB": [("(x, b)", "xb"), ("(y, true)", "y")],
            "R": [("r", "r"), ("r", "r"), ("{a = x, n = n, f = b}", "xnb"), ("{a = y, n = 1, f = b}", "yb")]}
PATTERNS["TI"] = PATTERNS["I"]
VALUES = {"I": [("x", "x"), ("y", "y"), ("up (x, 1)", "x"), ("up (y, 2)", "y"), ("x - y", "xy"),
                ("x * y mod 7", "xy"), ("~3", ""), ("#a r + 1", "r")],
          "IB": [("(x, b)", "xb"), ("(up (x, 1), not b)", "xb"), ("(y, x < y)", "xy"), ("(x div 2, true)", "x"),
                 ("(0, false)", "")],
          "R": [("r", "r"), ("flip r", "r"), ("{a = up (x, 1), n = n, f = b}", "xnb"),
                ("{a = #a r + 1, n = #n r, f = #f r}", "r"), ("{a = x, n = 2, f = true}", "x"),
                ("{a = 0, n = 0, f = false}", "")]}
VALUES["TI"] = VALUES["I"]
GUARDS = [("", ""), ("", ""), ("[x <> y]", "xy"), ("[x < 5]", "x"), ("[b]", "b"), ("[x <= y + 1]", "xy"),
          ("[#a r < 6]", "r"), ("[x = y]", "xy"), ("[#f r orelse x > 1]", "rx")]


def random_interned_net(seed: int, timed: bool = False) -> str:
    """A random net over an unbounded int (its values kept small by guards and functions), a product and a
    record with one; with `timed`, some places hold timed ints."""
    rng = random.Random(seed)
    kinds = ["I", "IB", "R"] + (["TI"] if timed else [])
    places = []
    lines = [HEADER]
    for i in range(rng.randint(2, 4)):
        k = rng.choice(kinds) if i else (rng.choice(["TI", "I"]) if timed else "I")
        places.append((f"p{i}", k))
        init = {"I": lambda: " ++ ".join(f"{rng.randint(1, 2)}`{_int(rng, -2, 3)}" for _ in range(rng.randint(1, 2))),
                "TI": lambda: " ++ ".join(f"(1`{_int(rng, -2, 3)}@+{rng.randint(0, 2)})" for _ in range(rng.randint(1, 2))),
                "IB": lambda: " ++ ".join(f"1`({_int(rng, -1, 3)},{rng.choice(['true', 'false'])})"
                                          for _ in range(rng.randint(0, 2))),
                "R": lambda: " ++ ".join(f"1`{{a = {_int(rng, -1, 3)}, n = {rng.randint(0, 2)}, f = true}}"
                                         for _ in range(rng.randint(0, 2)))}[k]()
        lines.append(f"place p{i} : {k}" + (f" = {init}" if init else "") + ";")

    for t in range(rng.randint(1, 4)):
        at = len(lines)
        lines.append("")
        bound: set[str] = set()
        later = []
        for name, k in rng.sample(places, k=rng.randint(1, min(3, len(places)))):
            kind = rng.choice(["->", "->", "->", "<->", "inhibitor"])
            if kind == "inhibitor":
                later.append((name, k))
                continue
            pat, binds = rng.choice(PATTERNS[k])
            bound |= set(binds)
            lines.append(f"arc {name} {kind} t{t} : {rng.choice(['', '', '2`']) if kind == '->' else ''}{pat};")
        for name, k in later:
            pat = rng.choice([p for p, vs in VALUES[k] if set(vs) <= bound])
            lines.append(f"inhibitor {name} -> t{t} : {pat};")
        for name, k in rng.sample(places, k=rng.randint(1, min(2, len(places)))):
            v = rng.choice([p for p, vs in VALUES[k] if set(vs) <= bound])
            if k == "TI" and rng.random() < 0.6:
                v = f"{v} @+ {rng.randint(0, 3)}"
            lines.append(f"arc t{t} -> {name} : {v};")
        guard = rng.choice([g for g, vs in GUARDS if set(vs) <= bound])
        lines[at] = f"trans t{t} {guard};"
    return "\n".join(lines) + "\n"


def _model(text: str, name: str):
    """The net, or None where it does not load (a variable bound by no arc: the generator's doing)."""
    try:
        return cpn.loads(text, name)
    except cpn.ModelError:
        return None


def _sixteen_random_nets_give_the_python_graph(monkeypatch, generate, prefix: str, seeds: int) -> None:
    """The first 16 nets of `generate` that load, both ways: the same graph, each in C (12 at least wholly,
    never going back to the Python engine)."""
    returns = count_calls(monkeypatch, native.NativeSearch, "_fill")
    wholly = tried = 0
    for seed in range(seeds):
        text = generate(seed)
        model = _model(text, f"{prefix}{seed}.cpnet")
        if model is None:
            continue
        tried += 1
        before = returns[0]
        try:
            c = _both(model, limit=400)
        except AssertionError:
            raise AssertionError(f"C and Python differ on random net {seed}:\n{text}") from None
        assert c.backend == "c"
        code, why = model.engine().native_code()
        assert why is None, why
        if not code.left:
            assert returns[0] == before, f"random net {seed} went back to the Python engine:\n{text}"
            wholly += 1
        if tried == 16:
            break
    assert tried == 16 and wholly >= 12, (tried, wholly)


@needs_native
def test_unbounded_ints_products_and_records_give_the_python_graph(monkeypatch):
    _sixteen_random_nets_give_the_python_graph(monkeypatch, random_interned_net, "interned", 40)


@needs_native
def test_the_threads_give_the_one_process_graph_with_interned_values():
    tried = 0
    for seed in range(40):
        model = _model(random_interned_net(seed), f"interned{seed}.cpnet")
        if model is None:
            continue
        one = Explorer(model.engine(), ExploreOptions(backend="python", max_states=400, packed_states=False)).run()
        if not one.complete:
            continue
        x = Explorer(model.engine(), ExploreOptions(workers=2, max_states=400)).run()
        assert x.backend == "threads", x.notes
        assert summary(x) == summary(one), f"random net {seed}"
        tried += 1
        if tried == 6:
            break
    assert tried == 6, tried


@needs_native
@pytest.mark.parametrize("condensation", [False, True], ids=["timed", "condensed"])
def test_timed_ints_give_the_python_graph(condensation, monkeypatch):
    from tests.statespace.test_native_timed_c import _both as timed_both

    monkeypatch.setattr(nativetimed, "HAND_OVER_RATE", 1e9)
    tried = native_all = 0
    for seed in range(40):
        text = random_interned_net(seed, timed=True)
        model = _model(text, f"tinterned{seed}.cpnet")
        if model is None or not model.net.is_timed:
            continue
        tried += 1
        try:
            timed_both(model, condensation, limit=300)
        except AssertionError:
            raise AssertionError(f"C and Python differ on random timed net {seed}:\n{text}") from None
        code, why = model.engine(time_condensation=condensation).timed_groups().native_code()
        native_all += code is not None and not code.left
        if tried == 10:
            break
    assert tried == 10 and native_all >= 6, (tried, native_all)


OVERFLOW = """
colset I = int;
var x : I;
place P : I = 1`3;
trans t [x < 4000000000000000000];
arc P -> t : x;
arc t -> P : x * 7;
"""


@needs_native
def test_an_unbounded_int_past_64_bits_is_computed_by_python(monkeypatch):
    """x * 3 overflows 64 bits at the 39th step: C hands that key to the engine, whose value (beyond
    64 bits) ends the chain since the guard then fails, as in the Python search."""
    returns = count_calls(monkeypatch, native.NativeSearch, "_fill")
    model = cpn.loads(OVERFLOW, "overflow.cpnet")
    code, _ = model.engine().native_code()
    assert code.left == {} and code.layouts[0].interned
    c = _both(model, limit=100)
    assert c.complete and returns[0] > 0


def test_what_is_interned_and_what_keeps_its_layout():
    model = cpn.loads(HEADER + "place P : I; place Q : N; place S : R; place T : IB;", "kinds.cpnet")
    code = ccodegen.native_code(model.engine())
    lays = code.layouts
    assert [lay.interned for lay in lays] == [True, False, True, True]
    assert lays[2].leaves == [(None, None, "int"), (0, 1, "bool"), (0, 2, "int")]  # a, f, n: by label
    assert lays[2].value(lays[2].flat((5, False, 2))) == (5, False, 2)
    with pytest.raises(OverflowError):
        lays[0].flat(1 << 64)


def test_same_exploration_is_strict():
    """The comparison these tests rest on tells two different graphs apart."""
    a = Explorer(cpn.loads("colset I = int; var x : I; place P : I = 1`0; trans t [x < 3]; arc P -> t : x;"
                           " arc t -> P : x + 1;", "a.cpnet").engine(), ExploreOptions(backend="python")).run()
    b = Explorer(cpn.loads("colset I = int; var x : I; place P : I = 1`0; trans t [x < 4]; arc P -> t : x;"
                           " arc t -> P : x + 1;", "b.cpnet").engine(), ExploreOptions(backend="python")).run()
    with pytest.raises(AssertionError):
        same_exploration(a, b)


SWITCH = """
colset N = int with 0..3;
colset I = int;
val MODE = "fast";
var x : N;
var i : I;
place P : N = 1`0;
place C : I = 1`0;
trans t [x < 3 andalso MODE = "fast"];
arc P -> t : x;
arc t -> P : x + 1;
trans u [MODE <> "fast" orelse i < 2];
arc C -> u : i;
arc u -> C : i + 1;
"""


@needs_native
@pytest.mark.parametrize("mode, states", [('"fast"', 12), ('"slow"', 100)])  # slow: i grows to the limit
def test_a_comparison_of_string_constants_is_decided_when_the_c_is_generated(mode, states, monkeypatch):
    """A model's switches (`val MODE = "fast"`, compared with string constants) are decided when the C is
    generated: the transitions reading them run in C, and the graph is the Python search's."""
    returns = count_calls(monkeypatch, native.NativeSearch, "_fill")
    model = cpn.loads(SWITCH.replace('"fast";', f"{mode};", 1), "switch.cpnet")
    code, _ = model.engine().native_code()
    assert code.left == {}
    c = _both(model, limit=100)
    assert (c.n_states, returns[0]) == (states, 0)


def test_the_modbus_model_has_transitions_in_c():
    """Scenario A.1's model: its unbounded ints and frames (records of them) and its switches are C's;
    what touches its lists and unions with data is left to the engine, each transition with its reason
    (the differential tests of its scenarios: tests/statespace/test_native_timed.py)."""
    import os

    from tests._shared import ROOT

    sc = cpn.load_scenario(os.path.join(ROOT, "specs", "modbus", "A_1.toml"))
    model = cpn.load(sc.model, set=sc.runs[0].values)
    code, why = model.engine(time_condensation=True).timed_groups().native_code()
    assert why is None and len(code.native) >= 50, len(code.native)


UNION_HEADER = """colset I = int;
colset B = bool;
colset N = int with 0..3;
colset R = record id : I * ok : B;
colset MSG = union Reset + Config : I + Ack : N + Frame : R;
colset LM = product N * MSG;
colset ST = union Idle + Busy : MSG;
var m : MSG;
var s : ST;
var n : N;
var x : I;
var r : R;
fun next (Config k) = if k < 3 then Config (k + 1) else Ack 2
  | next (Ack a) = Frame {id = a, ok = a > 1}
  | next (Frame {id = k, ok = b}) = if b then Reset else Ack 0
  | next Reset = Config 0;
fun isack (Ack _) = true | isack _ = false;
"""

U_PATTERNS = {"MSG": [("m", "m"), ("m", "m"), ("Config x", "x"), ("Ack n", "n"), ("Reset", ""),
                      ("Frame r", "r"), ("Frame {id = x, ok = true}", "x")],
              "LM": [("(n, m)", "nm"), ("(n, Ack n)", "n"), ("(0, m)", "m")],
              "ST": [("s", "s"), ("Idle", ""), ("Busy m", "m"), ("Busy (Config x)", "x")]}
U_VALUES = {"MSG": [("m", "m"), ("next m", "m"), ("Config (x + 1)", "x"), ("Ack n", "n"), ("Reset", ""),
                    ("Frame {id = x * 2, ok = x > 1}", "x"), ("case m of Ack a => Config a | _ => Reset", "m"),
                    ("if isack m then next m else Reset", "m"), ("Frame r", "r")],
            "LM": [("((n + 1) mod 4, next m)", "nm"), ("(n, m)", "nm"), ("(0, Reset)", "")],
            "ST": [("Idle", ""), ("Busy m", "m"), ("Busy (next m)", "m"), ("s", "s")]}
U_GUARDS = [("", ""), ("", ""), ("[x < 4]", "x"), ("[m <> Reset]", "m"), ("[isack m orelse n = 0]", "mn"),
            ("[s = Idle]", "s"), ("[#id r < 5]", "r")]


def random_union_net(seed: int) -> str:
    """A random net over unions with data (a record among their data, a product and a union holding one)."""
    rng = random.Random(seed)
    inits = {"MSG": ["1`Reset", "1`(Config 2)", "1`(Ack 1) ++ 1`Reset", "2`(Frame {id = 1, ok = false})"],
             "LM": ["1`(0, Reset)", "1`(1, Config 0)"], "ST": ["1`Idle", "1`(Busy Reset)"]}
    places = []
    lines = [UNION_HEADER]
    for i in range(rng.randint(2, 4)):
        k = rng.choice(["MSG", "MSG", "LM", "ST"]) if i else "MSG"
        places.append((f"p{i}", k))
        lines.append(f"place p{i} : {k} = {rng.choice(inits[k])};")
    for t in range(rng.randint(1, 4)):
        at = len(lines)
        lines.append("")
        bound: set[str] = set()
        for name, k in rng.sample(places, k=rng.randint(1, min(2, len(places)))):
            pat, binds = rng.choice([p for p in U_PATTERNS[k] if not set(p[1]) & bound])
            bound |= set(binds)
            lines.append(f"arc {name} {rng.choice(['->', '->', '<->'])} t{t} : {pat};")
        for name, k in rng.sample(places, k=rng.randint(1, min(2, len(places)))):
            v = rng.choice([p for p, vs in U_VALUES[k] if set(vs) <= bound])
            lines.append(f"arc t{t} -> {name} : {v};")
        guard = rng.choice([g for g, vs in U_GUARDS if set(vs) <= bound])
        lines[at] = f"trans t{t} {guard};"
    return "\n".join(lines) + "\n"


@needs_native
def test_unions_with_data_give_the_python_graph(monkeypatch):
    _sixteen_random_nets_give_the_python_graph(monkeypatch, random_union_net, "union", 60)


@needs_native
@pytest.mark.parametrize("name", ["modbus_a", "tcp"])
def test_modbus_scenarios_with_unions_give_the_python_graph(name, monkeypatch):
    """The Modbus-A and Modbus/TCP scenarios' models (unions with data, records and unbounded ints in C),
    both ways, up to 1,500 states."""
    import os

    from tests._shared import ROOT
    from tests.statespace.test_native_timed_c import _both as timed_both

    monkeypatch.setattr(nativetimed, "HAND_OVER_RATE", 1e9)
    sc = cpn.load_scenario(os.path.join(ROOT, "specs", "modbus", f"{name}.toml"))
    model = cpn.load(sc.model, set=sc.runs[0].values)
    code, why = model.engine(time_condensation=True).timed_groups().native_code()
    assert why is None and len(code.native) >= 8
    for condensation in (True, False):
        timed_both(model, condensation, limit=1500)


GROWING = """
colset I = int;
colset N = int with 0..3;
colset R = record a : I * n : N;
colset MSG = union Reset + Config : R;
var x : I;
var r : R;
var n : N;
place P : I = 1`0;
place Q : MSG = 1`Reset;
trans t [x < 3000];
arc P -> t : x;
arc t -> P : x + 1;
trans u;
arc Q -> u : Config {a = x, n = n};
arc u -> Q : Config {a = x + 1, n = (n + 1) mod 4};
arc P <-> u : x;
trans v;
arc Q -> v : Reset;
arc P <-> v : x;
arc v -> Q : Config {a = x, n = 0};
"""


@needs_native
def test_auto_builds_the_c_part_way_with_the_values_interned_so_far(monkeypatch):
    """The C built part-way gets a fresh context: the values the engine interned so far are given to it
    first, in their order, so that its ids are theirs; the graph is the Python search's."""
    upgrades = []
    upgrade = native.NativeSearch._upgrade

    def counted(self):
        upgrades.append(self.head)
        return upgrade(self)
    monkeypatch.setattr(native.NativeSearch, "_upgrade", counted)
    monkeypatch.setattr(native, "GENERATE_AFTER", 600)
    monkeypatch.setattr(native, "GENERATE_PER_LINE", 0)
    model = cpn.loads(GROWING, "growing.cpnet")
    auto = Explorer(model.engine(), ExploreOptions(backend="auto", max_states=5000)).run()
    py = Explorer(model.engine(), ExploreOptions(backend="python", packed_states=False, max_states=5000)).run()
    same_exploration(auto, py)
    assert auto.backend == "c" and auto.notes == [] and len(upgrades) == 1 and auto.n_states > 600


def test_a_finite_colour_set_too_large_for_a_layout_is_interned():
    model = cpn.loads("colset A = int with 0..2000; colset AA = product A * A; var p : AA;"
                      " place P : AA = 1`(0, 0); trans t [#1 p < 3]; arc P -> t : p;"
                      " arc t -> P : (#1 p + 1, 2000);", "big.cpnet")
    code = ccodegen.native_code(model.engine())
    assert code.layouts[0].interned and code.left == {}
    assert code.layouts[0].leaves == [(0, 2000, "int"), (0, 2000, "int")]
    if NATIVE is None:
        c = _both(model, limit=100)
        assert c.n_states == 4
