"""`load`: a model file of any supported format to a checked, flattened net and its engines.

The public door's main entry; imports every front-end layer (lang, net, io) and the engine.
"""

from __future__ import annotations

import os

from cpn.diagnostics import Diagnostic, Span
from cpn.errors import ConfigurationError, ModelError
from cpn.io import importer_for
from cpn.lang.nesting import too_deep
from cpn.lang.overrides import parse_overrides, usage_error
from cpn.lang.parser import parse as _parse
from cpn.lang.typecheck import check as _check
from cpn.net.lower import lower as _lower


class Model:
    """A loaded model: its source, its flattened net and the checker's warnings.

    Attributes
    ----------
    path : str
        The file it was loaded from (or the name given to `loads`).
    source : str
        Its `.cpnet` text (for `.pnml` and `.cpn` files: the translation).
    net : cpn.net.Net
        The flattened net, the engines' only input.
    warnings : list of Diagnostic
        What the checker found questionable but not wrong.

    Examples
    --------
    >>> import cpn
    >>> m = cpn.loads("colset U = unit; place A : U = 1`(); trans t; arc A -> t;", "a.cpnet")
    >>> m.name, [p.name for p in m.net.places]
    ('Top', ["Top'A 1"])
    """

    def __init__(self, path: str, source: str, net, warnings: list[Diagnostic]):
        self.path = path
        self.source = source
        self.net = net
        self.warnings = warnings
        self.translation = None  # for .pnml and .cpn files: the translation to .cpnet and its origins

    def engine(self, time_condensation: bool = False, reference: bool = False, simulation: bool = False):
        """The net's successor function (`cpn.engine.compile_net`): compiled, or the reference interpreter.

        A net that calls a random distribution function (`exponential`, `uniform`, ...), or has a real-valued
        delay, a reference variable or a side effect, has no state space: unless `simulation` is given, that
        is a ModelError with one error (E0206) per call or construct.

        >>> import cpn
        >>> e = cpn.loads("colset U = unit; place A : U = 1`(); trans t; arc A -> t;").engine()
        >>> len(e.successors(e.initial_state()))
        1
        """
        from cpn.engine import compile_net

        draws = getattr(self.net.checked, "random_draws", ())
        others = getattr(self.net.checked, "simulation_only", ())  # real-valued delays, references, effects
        if (draws or others) and not simulation:
            from cpn.lang.infer import random_hint

            error = ModelError([Diagnostic("E0206", f"'{name}' draws a random value: a state space cannot hold it "
                                           "(simulate runs the model)", span, hint=random_hint(name),
                                           params={"name": name}) for name, span in draws]
                               + [Diagnostic("E0206", f"{what}: a state space cannot hold it (simulate runs the "
                                             "model)", span, hint=hint, params={"name": name})
                                  for what, span, hint, name in others],
                               {span.file: self.source for _, span, *_ in [*draws, *others] if span is not None})
            if self.translation is not None:
                importer = importer_for(self.path)
                error = importer.remap_error(error, self.translation, f"{self.path} (as .cpnet)")
            raise error
        return compile_net(self.net, time_condensation=time_condensation, reference=reference)

    @property
    def name(self) -> str:
        return self.net.name

    def symmetry(self, spec: str | None = None) -> tuple:
        """The symmetric colour sets for symmetry reduction, checked against the net (`cpn.net.symmetry`).

        `spec` is None (the model's `symmetry` declarations), "auto" (every enumeration and index colour
        set of a place that the check accepts: all permutations, else rotations) or a list such as
        ``"PH,Ring:rotations"``. Raises ModelError (E0602, at the inscription or initial marking that
        tells the values apart) or ConfigurationError (a bad `spec`, or nothing declared).

        >>> import cpn
        >>> m = cpn.loads("colset P = with a | b; var x : P; place I : P = P.all(); trans t; arc I -> t : x;")
        >>> [str(s) for s in m.symmetry("auto")]
        ['P']
        """
        from cpn.net.scalars import Scalar, parse_scalars, root, scalar_values
        from cpn.net.symmetry import symmetry_problems

        if spec is None:
            scalars = [Scalar(n, k) for n, k in getattr(self.net.checked, "symmetries", ())]
            if not scalars:
                raise ConfigurationError("the model declares no symmetry", hint="Declare one in the model "
                                         "('symmetry PH = permutations;') or name the colour sets with "
                                         "--symmetry PH[,Ring:rotations] (or --symmetry auto).")
        elif spec.strip() == "auto":
            scalars = []
            used = {id(root(c)) for c in _components(self.net.places)}
            for name, cs in self.net.colsets.items():
                values = scalar_values(cs)
                if values is None or len(values) < 2 or name != root(cs).name or id(root(cs)) not in used:
                    continue
                for kind in ("permutations", "rotations"):
                    s = parse_scalars(f"{name}:{kind}")
                    if not symmetry_problems(self.net, s):
                        scalars += s
                        break
            if not scalars:
                raise ConfigurationError("no enumeration or index colour set of the model is symmetric",
                                         hint="Explore without symmetry reduction, or name a colour set with "
                                         "--symmetry to see what tells its values apart.")
        else:
            try:
                scalars = parse_scalars(spec)
            except ValueError as exc:
                raise ConfigurationError(f"--symmetry {spec}: {exc}", hint="Give colour sets as NAME "
                                         "(all permutations) or NAME:rotations, separated by commas.") from None
        problems = symmetry_problems(self.net, scalars)
        if problems:
            files = {d.span.file for d in problems if d.span is not None} or {self.path}
            error = ModelError(problems, {f: self.source for f in files})
            if self.translation is not None:
                importer = importer_for(self.path)
                error = importer.remap_error(error, self.translation, f"{self.path} (as .cpnet)")
            raise error
        return tuple(scalars)


def _components(places):
    """The colour sets of the places and every colour set inside them (products, records, ...)."""
    stack = [p.colour_set for p in places]
    while stack:
        cs = stack.pop()
        yield cs
        for attr in ("base", "elem"):
            if getattr(cs, attr, None) is not None:
                stack.append(getattr(cs, attr))
        stack.extend(getattr(cs, "components", ()) or ())
        stack.extend(c for _, c in (getattr(cs, "fields", ()) or ()))
        stack.extend(c for _, c in (getattr(cs, "constructors", ()) or ()) if c is not None)


def normalise_overrides(values) -> dict[str, str]:
    out = {}
    for k, v in (values or {}).items():
        out[str(k)] = v if isinstance(v, str) else _ml_literal(v)
    return out


def _ml_literal(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return f"~{-v}" if v < 0 else str(v)
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    raise ConfigurationError(f"cannot use {v!r} as a CPN ML value; give it as CPN ML text")


def source_of(path: str) -> str:
    """The `.cpnet` source text of a model file (translated for PNML and CPN Tools files)."""
    importer = importer_for(path)
    if importer is not None:
        return importer.translate(path).text
    try:
        with open(path, encoding="utf-8-sig") as fh:
            return fh.read()
    except UnicodeDecodeError as exc:
        raise ModelError([Diagnostic("E0501", f"the file is not UTF-8 text ({exc.reason})", Span(path, 1, 1))]) from None


def loads(text: str, filename: str = "<string>", set: dict | None = None) -> Model:  # noqa: A002
    """Load a model from `.cpnet` source text: parse, check and flatten it.

    Parameters
    ----------
    text : str
        The model in the `.cpnet` language (docs/language.md).
    filename : str
        The name error messages give the text.
    set : dict, optional
        Values for `val` constants, as CPN ML text or Python int/bool/str (``{"N": 8}``).

    Returns
    -------
    Model

    Raises
    ------
    ModelError
        With every diagnostic found (``file:line:col: error[CODE]: ...``).
    ConfigurationError
        A `set` value that is not a value of the constant's type (E0305).

    Examples
    --------
    >>> import cpn
    >>> m = cpn.loads("val N = 2; colset U = unit; place A : U = N`(); trans t; arc A -> t;", set={"N": 3})
    >>> m.net.places[0].initial
    {(): 3}
    """
    overrides = parse_overrides(normalise_overrides(set))  # once, before checking: a bad value is a usage error
    model = None
    try:
        model = _parse(text, filename)
        checked = _check(model, overrides)
        net = _lower(checked)
    except RecursionError:
        # chains of operators are read in loops: only expressions nested inside each other get here
        raise ModelError([too_deep(model.decls if model is not None else [], filename)], {filename: text}) from None
    return Model(filename, text, net, checked.warnings)


def _original_position(span: Span, translation) -> str:
    """Where a position of the translation of a .cpn or .pnml file comes from, in that file."""
    found = translation.origin(span.line, span.col)
    return str(found if found is not None else span)


def load(path: str | os.PathLike, set: dict | None = None) -> Model:  # noqa: A002
    """Load a model file (`.cpnet`, `.pnml`, `.cpn`), check it and flatten it.

    Parameters
    ----------
    path : the model file.
    set : values for `val` constants, as CPN ML text or Python int/bool/str (`{"N": 8}`).

    Raises
    ------
    ModelError : with every diagnostic of the file.
    ConfigurationError : the file does not exist.

    Examples
    --------
    >>> import os, tempfile, cpn
    >>> path = os.path.join(tempfile.mkdtemp(), "one.cpnet")
    >>> with open(path, "w") as fh:
    ...     _ = fh.write("val N = 2; colset U = unit; place A : U = N`(); trans t; arc A -> t;")
    >>> cpn.load(path, set={"N": 5}).net.places[0].initial
    {(): 5}
    """
    path = os.fspath(path)
    if not os.path.exists(path):
        raise ConfigurationError(f"no such model file: '{path}'")
    if os.path.isdir(path):
        raise ConfigurationError(f"'{path}' is a directory, not a model file")
    importer = importer_for(path)
    if importer is not None:
        # foreign formats are translated to .cpnet text; errors in the translation point back at the file
        translation = importer.translate(path)
        generated = f"{path} (as .cpnet)"
        try:
            model = loads(translation.text, generated, set)
        except ModelError as exc:
            raise importer.remap_error(exc, translation, generated) from None
        except ConfigurationError as exc:
            problems = getattr(exc, "problems", None)
            if not problems:
                raise
            # a --set value that does not fit names the constant's declaration in the file the user has
            raise usage_error(problems, lambda span: _original_position(span, translation)) from None
        # a warning keeps its place in the translated text (model.source) and names the element it comes from
        model.warnings = importer.remap_error(ModelError(model.warnings), translation, generated,
                                              keep_generated_span=True).diagnostics
        model.path = path
        model.translation = translation
        return model
    return loads(source_of(path), path, set)
