"""The package's C: the units (`.c` and `.h` files) of the native store, searches, graph algorithms and the
run-time of the C generated from a net, and their build manifest (`manifest`). The engine's generated code
and the state space's searches both build on them, so they sit under both (tests/test_layering.py)."""
