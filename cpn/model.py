"""`load`: a model file of any supported format to a checked, flattened net and its engines.

The public door's main entry; imports every front-end layer (lang, net, io) and the engine.
"""

from __future__ import annotations

import contextlib
import io
import os
import pickle
import re
from collections import OrderedDict

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
        What the checker found questionable but not wrong (for `.pnml` and `.cpn` files, at their place in
        that file where the element is known; `text_of` gives the text a warning points into).

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
        self.sources: dict[str, str] = {}  # the texts of the files the warnings point into, beside `source`

    def text_of(self, span) -> str | None:
        """The text of the file `span` points into: the imported file, a `use`d file, or `source`."""
        if span is None:
            return None
        return self.sources.get(span.file, self.source)

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
    values = normalise_overrides(set)
    overrides = parse_overrides(values)  # once, before checking: a bad value is a usage error
    cache = _active
    if cache is not None:
        key = cache.key(text, filename, values)
        found = cache.nets.get(key)
        if found is not None:
            cache.nets.move_to_end(key)
            return Model(filename, text, found[0], list(found[1]))
    model = None
    try:
        model = _parse(text, filename) if cache is None else cache.parse(text, filename, key[2])
        checked = _check(model, overrides)
        net = _lower(checked)
    except RecursionError:
        # chains of operators are read in loops: only expressions nested inside each other get here
        raise ModelError([too_deep(model.decls if model is not None else [], filename)], {filename: text}) from None
    if cache is not None:
        cache.keep(cache.nets, key, (net, tuple(checked.warnings)))
    return Model(filename, text, net, checked.warnings)


class LoadCache:
    """What `loads` reuses while `caching()` is active: the parse of a text and the checked, flattened net
    of a text with a set of constant values.

    A key holds everything the result depends on: the name the text is loaded under (positions and the
    paths of `use` name it), the text, the bytes of every file it uses (recursively) and, for a net, the
    constant values. A parse is kept pickled and each type check gets its own copy: the checker annotates
    and rewrites the tree it is given (the copies share the spans, which nothing writes into: `_TreeCopy`). A net is shared by the models loaded from it (nothing writes into a
    net); every `Model.engine()` builds a fresh engine from it (its stores and memo tables are its own), and
    the compiled engine compiles the same generated code once per process (`cpn.engine.compiled`).
    """

    TREES = 16  # parses kept (a mutant is a text of its own)
    NETS = 2  # nets kept (the MODBUS model's is a few megabytes, some 15,000 objects the collector walks)

    def __init__(self):
        self.trees: OrderedDict = OrderedDict()
        self.nets: OrderedDict = OrderedDict()

    def key(self, text: str, filename: str, values: dict[str, str]) -> tuple:
        return filename, text, _used_files(text, filename), tuple(sorted(values.items()))

    def parse(self, text: str, filename: str, used: tuple):
        """The parse of `text` (a fresh copy of the kept one, sharing its spans)."""
        key = (filename, text, used)
        kept = self.trees.get(key)
        if kept is not None:
            self.trees.move_to_end(key)
            return _TreeCopy.copy(*kept)
        tree = _parse(text, filename)
        try:
            self.keep(self.trees, key, _TreeCopy.kept(tree))
        except RecursionError:  # expressions nested too deeply to pickle: parsed again the next time
            pass
        return tree

    def keep(self, table: OrderedDict, key, value) -> None:
        table[key] = value
        while len(table) > (self.TREES if table is self.trees else self.NETS):
            table.popitem(last=False)


class _TreeCopy(pickle.Pickler):
    """A parse kept as pickled bytes, its spans kept aside: a copy is unpickled from the bytes and shares
    the spans (immutable; every node has one, and unpickling a frozen dataclass runs Python code per
    object: with them inside, copying the MODBUS model's parse took three times as long)."""

    def __init__(self, out: io.BytesIO):
        super().__init__(out, pickle.HIGHEST_PROTOCOL)
        self.spans: list[Span] = []
        self._ids: dict[int, int] = {}

    def persistent_id(self, obj):
        if type(obj) is not Span:
            return None
        i = self._ids.get(id(obj))  # the spans are held in self.spans, so their ids stay theirs
        if i is None:
            i = self._ids[id(obj)] = len(self.spans)
            self.spans.append(obj)
        return i

    @staticmethod
    def kept(tree) -> tuple[bytes, list[Span]]:
        """The parse as (its bytes, its spans)."""
        out = io.BytesIO()
        pickler = _TreeCopy(out)
        pickler.dump(tree)
        return out.getvalue(), pickler.spans

    @staticmethod
    def copy(data: bytes, spans: list[Span]):
        """A fresh copy of a kept parse."""
        unpickler = pickle.Unpickler(io.BytesIO(data))
        unpickler.persistent_load = spans.__getitem__
        return unpickler.load()


_active: LoadCache | None = None


@contextlib.contextmanager
def caching():
    """Within the block, `load` and `loads` parse a text once and type-check and flatten it once per
    set of constant values (`LoadCache`); a `check` or `mutate` run loads each model this way. Nested
    blocks share the outer one's cache.

    >>> import cpn
    >>> from cpn.model import caching
    >>> text = "val N = 2; colset U = unit; place A : U = N`(); trans t; arc A -> t;"
    >>> with caching():
    ...     a, b, c = cpn.loads(text), cpn.loads(text), cpn.loads(text, set={"N": 3})
    >>> a.net is b.net, a.net is c.net
    (True, False)
    """
    global _active
    if _active is not None:
        yield _active
        return
    _active = LoadCache()
    try:
        yield _active
    finally:
        _active = None


_USE = re.compile(r'\buse\s+"([^"\n]*)"')


def _used_files(text: str, filename: str) -> tuple:
    """The files `text` may use, directly or through others, with their bytes (None: unreadable), as
    `cpn.lang.uses` finds them; a `use` in a comment or a string is counted too (it only costs a read)."""
    out: list = []
    seen: set = set()
    stack = [(text, filename)]
    while stack:
        body, name = stack.pop()
        if "use" not in body:
            continue
        base = os.path.dirname(name) if name and not name.startswith("<") else "."
        for m in _USE.finditer(body):
            path = os.path.normpath(os.path.join(base, m.group(1)))
            if path in seen:
                continue
            seen.add(path)
            try:
                with open(path, "rb") as fh:
                    data = fh.read()
            except OSError:
                data = None
            out.append((path, data))
            if data is not None:
                stack.append((data.decode("utf-8", "replace"), path))
    return tuple(out)


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
        # a warning points, as an error does, at its element in the file the user has (with the line of the
        # translated text in a note); one without a known element keeps its place in the translation
        remapped = importer.remap_error(ModelError(model.warnings, {generated: translation.text}), translation,
                                        generated)
        model.warnings = remapped.diagnostics
        model.sources = remapped.sources
        model.path = path
        model.translation = translation
        return model
    return loads(source_of(path), path, set)
