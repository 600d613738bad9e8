"""Foreign model formats: PNML (`cpn.io.pnml`) and CPN Tools (`cpn.io.cpntools`).

Each reader translates its format into `.cpnet` source text, which then goes through the one front end
(parser, type checker, lowering, engine). Imports `cpn.net` and layer 0 only.
"""
