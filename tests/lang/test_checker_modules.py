"""The checker of the language keeps colour-set construction and type inference in modules of their own, and
no module of cpn/lang/ grows past its size."""

import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_the_checker_keeps_colour_sets_and_inference_in_their_own_modules():
    from cpn.lang.colsets import ColourSetConstruction
    from cpn.lang.infer import TypeInference
    from cpn.lang.typecheck import Checker

    assert {ColourSetConstruction, TypeInference} <= set(Checker.__mro__)
    assert "colset_decl" in vars(ColourSetConstruction) and "infer" in vars(TypeInference)
    sizes = {p.name: len(p.read_text(encoding="utf-8").splitlines()) for p in (ROOT / "cpn" / "lang").glob("*.py")}
    assert sizes["typecheck.py"] < 300 and max(sizes.values()) < 800, sizes
