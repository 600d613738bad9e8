"""Library functions and syntax of SML/NJ and CPN Tools that the corpus's models with reference variables
and its FFT model need: SML's Math, ListPair, `before`, `Real.trunc` and `Real.fromString`, negative literals as arguments (`ins l ~1`), qualified type names in annotations, `inc`,
`Date.weekDay`, `OS.Path.concat`, CPN Tools' model-time conversions and simulator output folder, colour-set
file input and output (`declare input_ms, output`), and recursion some ten thousand levels deeper."""

from __future__ import annotations

import math

import pytest

import cpn
from cpn.errors import EvaluationError, ModelError

NET = "colset U = unit; place A : U = 1`(); trans t; arc A -> t;\n"


def value(expr: str, decls: str = ""):
    model = cpn.loads(f"{decls}\nval it = {expr};\n" + NET, "m.cpnet")
    [uid] = [d.pat.ref.uid for d in model.net.globals.decls
             if getattr(getattr(d, "pat", None), "name", None) == "it"]
    return model.net.globals.constants[uid]


@pytest.mark.parametrize("expr, expected", [
    ("Math.sqrt 16.0", 4.0),
    ("Math.pow (2.0, 10.0)", 1024.0),
    ("Math.cos 0.0 + Math.sin 0.0", 1.0),
    ("Math.exp (Math.ln 3.0)", pytest.approx(3.0)),
    ("Math.atan2 (1.0, 1.0) * 4.0", pytest.approx(math.pi)),
    ("ins [1] ~1", (1, -1)),  # ~1 is a constant: one argument, not 'ins [1] ~ 1'
    ("[~2.5, 3.0]", (-2.5, 3.0)),
    ("OS.Path.concat (\"out\", \"a.csv\")", "out/a.csv"),
    ("OS.Path.concat (\"out/\", \"a.csv\")", "out/a.csv"),
    ("Date.weekDay (Date.fromTimeUniv (Time.fromSeconds 0)) = Date.Thu", True),  # 1970-01-01
    ("(Date.Jan : Date.month) = Date.Jan", True),
    ("isSome (NONE : TextIO.outstream option)", False),
    ("toReal (fromInt 3)", 3.0),
    ("let val r = ref 1 in (inc r; inc r; dec r; !r) end", 2),
    ("let val r = ref 0 in (!r before r := 5) + !r end", 5),  # the value of the first, then the second
    ("ListPair.map (fn (a, b) => a + b) ([1, 2, 3], [10, 20])", (11, 22)),
    ("ListPair.zip ([1, 2], [\"a\", \"b\"])", ((1, "a"), (2, "b"))),
    ("(Real.trunc ~2.7, Real.floor ~2.5, Real.ceil 2.1, Real.round 2.5)", (-2, -3, 3, 2)),
    ("Real.fromString \" ~1.5e2x\"", ("SOME", -150.0)),
    ("Real.fromString \"x\"", "NONE"),
])
def test_values(expr, expected):
    assert value(expr) == expected


def test_math_sqrt_of_a_negative_number_is_nan_as_in_sml_nj():
    assert math.isnan(value("Math.sqrt ~1.0"))


def test_a_negative_literal_is_still_a_pattern_and_a_negation():
    assert value("case ~1 of ~1 => 5 | _ => 0") == 5
    assert value("3 - ~1 + ~ 2") == 2


def test_model_time_reads_the_clock_and_annotates_as_time():
    model = cpn.loads("fun now () = ModelTime.time () : time;\n"
                      "colset T = int timed; place A : T = 1`0; place B : T; var x : T;\n"
                      "trans t @+ 5; arc A -> t : x; arc t -> B : now ();", "m.cpnet")
    engine = model.engine()
    [(_be, s)] = engine.successors(engine.initial_state())
    assert engine.format_marking(s, 1) == "1`0@5"


def test_the_simulator_output_folder_is_simulation_only():
    model = cpn.loads('fun dir () = (Output.initSimOutputDir (); Output.getSimOutputDir ());\n'
                      'colset S = string; place A : S; trans t; arc t -> A : dir ();', "m.cpnet")
    assert sorted(w.params["name"] for w in model.warnings) == ["Output.getSimOutputDir",
                                                                 "Output.initSimOutputDir"]
    with pytest.raises(ModelError) as info:
        model.engine()
    assert [(d.code, d.span.line) for d in info.value.diagnostics] == [("E0206", 1), ("E0206", 1)]


def test_colour_set_output_is_dropped_and_input_stops_simulate():
    text = ("colset I = int; var x : I;\n"
            "fun log (v : int) = I.output (TextIO.openOut \"x.txt\", v);\n"
            "fun load () = I.input_ms (TextIO.openIn \"x.txt\");\n"
            "place A : I = 1`1; place B : I;\n"
            "trans put; arc A -> put : x; arc put -> B : (log x; x);\n"
            "trans get; arc B -> get : x; arc get -> A : load ();\n")
    engine = cpn.loads(text, "m.cpnet").engine(simulation=True, reference=True)
    [(_be, fire)] = engine.successors(engine.initial_state(), lazy=True)
    s = fire()  # put writes nothing
    assert engine.format_marking(s, 1) == "1`1"
    [(_be, fire)] = engine.successors(s, lazy=True)
    with pytest.raises(EvaluationError) as info:
        fire()
    assert "TextIO.openIn" in str(info.value)


def test_recursion_of_forty_thousand_levels_is_evaluated():
    # 200,000 Python frames held 28,571 levels of this function: a model that walks a year hour by hour
    # needs more
    assert value("f 40000", "fun f (n : int) = if n = 0 then 0.0 else 1.0 + f (n - 1);") == 40000.0


def test_reading_reals_from_a_file_is_simulation_only_and_stops_simulate():
    text = ("colset R = real; var x : R;\n"
            "fun first (f : string) = let val ins = TextIO.openIn f in\n"
            "  TextIO.scanStream Real.scan ins before TextIO.closeIn ins end;\n"
            "place A : R = 1`0.0; place B : R;\n"
            "trans t; arc A -> t : x; arc t -> B : getOpt (first \"s.txt\", x);\n")
    model = cpn.loads(text, "m.cpnet")
    assert sorted(w.params["name"] for w in model.warnings) == ["TextIO.closeIn", "TextIO.openIn",
                                                                 "TextIO.scanStream"]
    engine = model.engine(simulation=True, reference=True)
    [(_be, fire)] = engine.successors(engine.initial_state(), lazy=True)
    with pytest.raises(EvaluationError) as info:
        fire()
    assert "TextIO.openIn" in str(info.value) and "s.txt" in str(info.value)
