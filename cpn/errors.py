"""The exception hierarchy of cpn-verify. Imports `cpn.diagnostics` only."""

from __future__ import annotations

from cpn.diagnostics import Diagnostic, Severity, Span, shorten_words


class CpnError(Exception):
    """Base class of every error cpn-verify raises on purpose."""

    exit_status = 70

    def render(self) -> str:
        return f"error: {self}"


class ConfigurationError(CpnError):
    """Bad options given to the API or the command line."""

    exit_status = 64

    def __init__(self, message: str = "", hint: str | None = None, code: str | None = None):
        super().__init__(message)
        self.hint = hint
        self.code = code  # a stable code from `cpn.diagnostics.CODES`, when the error has one

    def render(self) -> str:
        head = f"error[{self.code}]" if self.code else "error"
        return f"{head}: {self}" + (f"\nhint: {self.hint}" if self.hint else "")


class ModelError(CpnError):
    """A model file is malformed or ill-typed; holds every diagnostic found in one run."""

    exit_status = 65

    def __init__(self, diagnostics: list[Diagnostic], sources: dict[str, str] | None = None):
        self.diagnostics = sorted(diagnostics, key=Diagnostic.sort_key)
        self.sources = dict(sources or {})
        first = self.diagnostics[0] if self.diagnostics else None
        text = shorten_words(first.message) if first else ""
        super().__init__(f"{first.span}: {text}" if first and first.span else text)

    @property
    def errors(self) -> list[Diagnostic]:
        return [d for d in self.diagnostics if d.severity is Severity.ERROR]

    def render(self) -> str:
        parts = []
        for d in self.diagnostics:
            src = self.sources.get(d.span.file) if d.span else None
            parts.append(d.render(src))
        n = len(self.errors)
        parts.append(f"{n} error{'s' if n != 1 else ''} found")
        return "\n\n".join(parts[:-1]) + "\n" + parts[-1]


class ModelSyntaxError(ModelError):
    """The model text does not follow the grammar (raised before any name is resolved)."""


class EvaluationError(CpnError):
    """An inscription, guard or initial marking raised an error while the net was evaluated.

    `code` is E0401 (an evaluation failed) or E0402 (a transition puts a token outside its place's
    colour set).
    """

    exit_status = 65

    def __init__(self, message: str, span: Span | None = None, element: str | None = None,
                 binding: dict | None = None, hint: str | None = None, source: str | None = None,
                 code: str = "E0401"):
        self.message = message
        self.code = code
        self.span = span
        self.element = element
        self.binding = binding
        self.hint = hint
        self.source = source
        self.trace: list[str] = []
        super().__init__(f"{span}: {message}" if span else message)

    def diagnostic(self) -> Diagnostic:
        return Diagnostic(self.code, self.message, self.span, hint=self.hint)

    def render(self) -> str:
        text = self.diagnostic().render(self.source)
        if self.trace:
            n = len(self.trace)
            text += f"\nnote: reached after {n} step{'' if n == 1 else 's'} from the initial marking:\n"
            text += "\n".join(f"  {i}. {step}" for i, step in enumerate(self.trace, 1))
        return text
