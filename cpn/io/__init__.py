"""Foreign model formats: PNML (`cpn.io.pnml`) and CPN Tools (`cpn.io.cpntools`).

Each reader translates its format into `.cpnet` source text, which then goes through the one front end
(parser, type checker, lowering, engine); the PNML writer (`cpn.io.pnml.write`) prints a `.cpnet` model or
a flattened net as PNML. Imports `cpn.lang` (the writer reads the syntax tree), `cpn.net`, `cpn.values`
and layer 0 (tests/test_layering.py).
"""
