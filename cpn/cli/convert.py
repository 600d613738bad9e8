"""`cpn-verify convert FILE [-o FILE.cpnet]`: translate a CPN Tools or PNML net into the `.cpnet` language.

The translation goes to standard output, or to the file named by -o (checked before anything is read),
never beside the input. It is then loaded through the front end (parser, type checker, lowering) so that
a net that would not load is reported at once. Exit status: 0 written and loads, 64 bad usage, 65 the
net cannot be translated or the translation does not load (the diagnostics name the element of the
input file), 73 the -o file cannot be written.
"""

from __future__ import annotations

import argparse
import os
import sys

from cpn.cli._common import ExitStatus, UsageError, add_quiet_option, prepare_outputs, write_output


def add_parser(subparsers) -> argparse.ArgumentParser:
    p = subparsers.add_parser(
        "convert", help="translate a CPN Tools .cpn or PNML net into a .cpnet model",
        description=__doc__.split("\n\n")[1], formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("model", metavar="FILE", help="a net saved by CPN Tools (.cpn) or a PNML file (.pnml)")
    p.add_argument("-o", "--output", metavar="FILE.cpnet",
                   help="write the translation to FILE.cpnet ('-' or no -o: standard output)")
    p.add_argument("--no-check", action="store_true",
                   help="write the translation without loading it through the front end")
    add_quiet_option(p)
    return p


def _default_output(model: str) -> str:
    from cpn.io import importer_for

    root, _ext = os.path.splitext(model)
    return (root if importer_for(model) is not None else model) + ".cpnet"


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
    (output,) = prepare_outputs(("-o", args.output or "-"))
    if not os.path.isfile(args.model):
        raise UsageError(f"no such model file: '{args.model}'" if not os.path.exists(args.model)
                         else f"'{args.model}' is not a file")
    from cpn.io import IMPORTERS, importer_for

    importer = importer_for(args.model)
    if importer is None:
        known = ", ".join(f"{imp.name} ({' '.join(imp.suffixes)})" for imp in IMPORTERS)
        raise UsageError(f"'{args.model}' is not a file convert reads: it reads {known}")
    translation = importer.translate(args.model)
    out = output.path
    write_output(output, translation.text)
    name = out if out != "-" else _default_output(args.model)  # the name a redirection would give it
    if not args.quiet:
        for note in translation.notes:
            print(f"note: {note}", file=sys.stderr)
    if args.no_check:
        return ExitStatus.OK
    err = _check(translation.text, name)
    if err is not None:
        # the translation is on disk: diagnostics keep their place in it and name the element they come from
        mapped = importer.remap_error(err, translation, name, keep_generated_span=True)
        mapped.sources.setdefault(name, translation.text)
        print(mapped.render(), file=sys.stderr)
        print(f"note: the translation was written to {out if out != '-' else 'standard output'}, "
              "but it does not load", file=sys.stderr)
        return ExitStatus.DATAERR
    if out != "-" and not args.quiet:
        print(f"wrote {out}", file=sys.stderr)
    return ExitStatus.OK
