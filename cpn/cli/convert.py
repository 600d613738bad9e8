"""`cpn-verify convert FILE.cpn [-o FILE.cpnet]`: translate a CPN Tools net into the `.cpnet` language.

The translation is written, then loaded through the front end (parser, type checker, lowering) so that
a net that would not load is reported at once. Exit status: 0 written and loads, 65 the net cannot be
translated or the translation does not load (the diagnostics name the element of the .cpn file).
"""

from __future__ import annotations

import argparse
import os
import sys

EXIT_OK = 0
EXIT_DATAERR = 65


def add_parser(subparsers) -> argparse.ArgumentParser:
    p = subparsers.add_parser(
        "convert", help="translate a CPN Tools .cpn or PNML net into a .cpnet model",
        description=__doc__.split("\n\n")[1], formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("model", metavar="FILE", help="a net saved by CPN Tools (.cpn) or a PNML file (.pnml)")
    p.add_argument("-o", "--output", metavar="FILE.cpnet",
                   help="where to write the translation (default: FILE.cpnet next to the input; '-' for stdout)")
    p.add_argument("--no-check", action="store_true",
                   help="write the translation without loading it through the front end")
    return p


def _default_output(model: str) -> str:
    root, ext = os.path.splitext(model)
    return (root if ext.lower() in (".cpn", ".pnml") else model) + ".cpnet"


def _check(text: str, name: str):
    """Load the translated text through the front end; return the ModelError if it does not load."""
    import cpn
    from cpn.errors import ModelError

    try:
        cpn.loads(text, name)
    except ModelError as exc:
        return exc
    return None


def run(args) -> int:
    from cpn.errors import ModelError

    is_pnml = args.model.lower().endswith(".pnml")
    try:
        if is_pnml:
            from cpn.io.pnml import translate_with_origins

            translation = translate_with_origins(args.model)
        else:
            from cpn.io.cpntools import translate_file

            translation = translate_file(args.model)
    except ModelError as exc:
        print(exc.render(), file=sys.stderr)
        return exc.exit_status
    out = args.output or _default_output(args.model)
    if out == "-":
        sys.stdout.write(translation.text)
        name = _default_output(args.model)
    else:
        with open(out, "w", encoding="utf-8") as f:
            f.write(translation.text)
        name = out
    for note in getattr(translation, "notes", ()):
        print(f"note: {note}", file=sys.stderr)
    if args.no_check:
        return EXIT_OK
    err = _check(translation.text, name)
    if err is not None:
        if is_pnml:
            from cpn.io.pnml import remap_error

            mapped = remap_error(err, translation, name)
        else:
            from cpn.io.cpntools import remap_error

            mapped = remap_error(err, translation, name, keep_generated_span=True)
        mapped.sources.setdefault(name, translation.text)
        print(mapped.render(), file=sys.stderr)
        print(f"note: the translation was written to {out if out != '-' else 'standard output'}, "
              "but it does not load", file=sys.stderr)
        return EXIT_DATAERR
    if out != "-":
        print(f"wrote {out}", file=sys.stderr)
    return EXIT_OK
