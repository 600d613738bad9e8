"""The one expression tree of CPN ML and what reads it: the nodes (`nodes`), the evaluator (`evaluate`), the
binding analysis (`binding`) and the printer (`pretty`).

The language parses into these nodes and types them; the net holds them with every name resolved
(`cpn.net.lower`); the engines compile and interpret them; the checks and the reports read and print
them. Imports `cpn.values` and layer 0 only (docs/internals.md).
"""
