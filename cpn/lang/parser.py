"""Parsing `.cpnet` text into the AST, reporting every syntax error of a file in one run.

Imports lark, `cpn.lang.ast`, `cpn.lang.transform`, `cpn.lang.syntax_errors` and layer 0.
"""

from __future__ import annotations

import functools
import re
import threading
import unicodedata

from lark import Lark, Token, Tree
from lark.exceptions import UnexpectedCharacters, UnexpectedEOF, UnexpectedInput, UnexpectedToken, VisitError

from cpn._util.resources import read_text
from cpn.diagnostics import Diagnostic, Span, other_command_hint
from cpn.errors import ModelSyntaxError
from cpn.lang import ast as A
from cpn.lang.syntax_errors import SYNTAX_ERRORS, TERMINAL_NAMES
from cpn.lang.transform import ToAst, balance_chains
from cpn.lang.uses import expand_uses

MAX_SYNTAX_ERRORS: int = 50

# Standard ML's reserved words: CPN Tools refuses them as the name of a value, function, variable, colour
# set, record field or pattern variable (places and transitions are no ML names: they may be called so)
RESERVED_WORDS: frozenset[str] = frozenset(
    """abstype and andalso as case datatype do else end eqtype exception fn fun functor handle if in include
    infix infixr let local nonfix of op open orelse raise rec sharing sig signature struct structure then type
    val where while with withtype""".split()
)
BOM: str = "\ufeff"

_STMT_START = re.compile(
    r"^[ \t]*(net|use|colset|var|val|fun|place|port|trans|arc|inhibitor|reset|module|instance)\b|^[ \t]*\}",
    re.MULTILINE,
)


_lexed = threading.local()


# Statement keywords that no CPN ML name may be (`cpn.io.cpntools._ml.KEYWORDS`): one at the start of a line
# inside an expression is the next statement after a missing ';', not an argument or a type
_LINE_START_KEYWORDS: frozenset[str] = frozenset(
    "colset place trans arc inhibitor reset module instance".split())


def _note_name(tok: Token) -> Token:
    """Lexer callback: remember the names that are reserved words (for the messages of a failed parse); a
    statement keyword first on its line is that keyword (`val x = 1` without ';' before `place A : INT;`)."""
    if tok.value in RESERVED_WORDS:
        _lexed_reserved().append(tok)
    elif tok.value in _LINE_START_KEYWORDS:
        text = getattr(_lexed, "text", "")
        start = text.rfind("\n", 0, tok.start_pos) + 1
        if text[start:tok.start_pos].strip() == "":
            return Token.new_borrow_pos(tok.value.upper(), tok.value, tok)
    return tok


def _lexed_reserved() -> list:
    got = getattr(_lexed, "reserved", None)
    if got is None:
        got = _lexed.reserved = []
    return got


@functools.lru_cache(maxsize=None)
def _parser() -> Lark:
    text = read_text("lang/grammar.lark")
    # cache=True keeps the LALR tables in the temporary directory: 0.57 s of every start otherwise
    return Lark(text, parser="lalr", propagate_positions=True, maybe_placeholders=True, cache=True,
                lexer_callbacks={"NAME": _note_name})


def _expected_text(exc: UnexpectedInput) -> str:
    expected = getattr(exc, "expected", None) or getattr(exc, "allowed", None) or set()
    names = sorted({n for n in (TERMINAL_NAMES.get(t) or _pretty_terminal(t) for t in expected) if n})
    if not names:
        return ""
    if len(names) > 6:
        names = names[:6] + ["..."]
    return ", ".join(names)


def _pretty_terminal(name: str) -> str | None:
    try:
        term = _parser().get_terminal(name)
    except KeyError:
        return None
    pattern = term.pattern
    if pattern.type == "str":
        return f"'{pattern.value}'"
    return None


def _found(exc: UnexpectedInput, text: str) -> str:
    if isinstance(exc, UnexpectedToken):
        tok = exc.token
        if tok.type == "$END":
            return "the end of the file"
        return f"'{tok}'"
    if isinstance(exc, UnexpectedCharacters):
        return describe_char(text[exc.pos_in_stream]) if exc.pos_in_stream < len(text) else "the end of the file"
    return "the end of the file"


def describe_char(ch: str) -> str:
    """A character for a message: quoted if it is visible, else by its code point ('U+0000')."""
    if ch.isprintable() and not ch.isspace() or ch == " ":
        return f"'{ch}'"
    name = unicodedata.name(ch, "")
    return f"U+{ord(ch):04X}" + (f" ({name.lower()})" if name else "")


def reserved_word(tok: Token, filename: str) -> Diagnostic:
    """E0101 at a reserved word written where a name is expected."""
    word = str(tok)
    return Diagnostic(
        "E0101", f"'{word}' is a reserved word of CPN ML and cannot be used as a name",
        Span(filename, tok.line, tok.column, tok.end_line or tok.line, (tok.end_column or tok.column + 1) - 1),
        hint=f"Choose another name, e.g. '{word}1' or 'my_{word}': reserved words (val, fun, end, type, in, of, "
        "...) cannot name values, functions, variables, colour sets or record fields.",
        params={"found": word})


def _reserved_names(tree: Tree, filename: str) -> list[Diagnostic]:
    """A reserved word the parser took for a name (where no keyword could stand), at the word itself."""
    out = []
    for sub in tree.iter_subtrees():
        if sub.data == "name":  # a place, transition or instance name
            continue
        for tok in sub.children:
            if isinstance(tok, Token) and tok.type == "NAME" and str(tok) in RESERVED_WORDS:
                out.append(reserved_word(tok, filename))
    return out


def _diagnose(exc: UnexpectedInput, text: str, filename: str) -> Diagnostic:
    if isinstance(exc, UnexpectedToken):
        if str(exc.token) in RESERVED_WORDS and "NAME" in (exc.expected or ()):
            return reserved_word(exc.token, filename)
    pos = getattr(exc, "pos_in_stream", None)
    if pos is not None:
        # a reserved word read as a name earlier in the statement is the likely cause of a later error
        start = text.rfind(";", 0, pos)
        earlier = [t for t in _lexed_reserved() if start < t.start_pos < pos]
        if earlier:
            return reserved_word(earlier[-1], filename)
    line = getattr(exc, "line", None)
    col = getattr(exc, "column", None)
    if isinstance(exc, UnexpectedToken) and exc.token.type == "$END" or line in (None, -1):
        lines = text.splitlines() or [""]
        line, col = len(lines), len(lines[-1]) + 1
    span = Span(filename, line, col, line, col)
    found = _found(exc, text)
    if isinstance(exc, UnexpectedCharacters):
        open_ = unterminated(text, filename)
        if open_ is not None:
            return open_
    label = None
    try:
        label = exc.match_examples(_parser().parse, {i: ex for i, (_, msg, _, ex) in enumerate(SYNTAX_ERRORS)
                                    if not msg.startswith("expected ';'")},
                                   use_accepts=True)
    except Exception:  # noqa: BLE001 - matching is best effort
        label = None
    if isinstance(exc, UnexpectedToken) and exc.token == "=" and getattr(exc, "token_history", None):
        prev = exc.token_history[-1] if exc.token_history else None
        if prev is not None and str(prev) == "=":
            label = next(i for i, row in enumerate(SYNTAX_ERRORS) if row[1].startswith("'=='"))
    missing_semi = _missing_semicolon(exc, text, filename)
    if missing_semi is not None:
        return missing_semi
    if label is not None:
        code, message, hint, _ = SYNTAX_ERRORS[label]
        return Diagnostic(code, f"{message}, found {found}", span, hint=hint, params={"found": found})
    if isinstance(exc, UnexpectedCharacters):  # an unterminated string or comment returned above
        hint = _non_ascii_hint(text, exc.pos_in_stream) or "Remove it, or put it inside a string or a comment."
        pos = exc.pos_in_stream
        if text[pos:pos + 1] == "'" and text[:pos].rstrip()[-1:].isdigit():
            # `1'x`: the backquote of a multiset coefficient, as printed in books, typed as a quote
            hint = "n copies of e are written n`e in CPN ML, with a backquote, not a quote."
        return Diagnostic("E0101", f"unexpected character {found}", span, hint=hint, params={"found": found})
    expected = _expected_text(exc)
    msg = ("unexpected end of the file" if found == "the end of the file" else f"unexpected {found}") \
        + (f", expected {expected}" if expected else "")
    return Diagnostic("E0101", msg, span, params={"found": found})


_WORD_CHARS = re.compile(r"[\w']+")


def _non_ascii_hint(text: str, pos: int) -> str | None:
    """The hint for a letter outside ASCII (`place Überlauf`): quoting the name where a quoted name is allowed
    (places, transitions, arcs' ends, instances: `"Überlauf"`, tried on the statement), else an ASCII name."""
    if pos >= len(text) or text[pos].isascii() or not text[pos].isalnum():
        return None
    start = pos
    while start > 0 and (text[start - 1].isalnum() or text[start - 1] in "_'"):
        start -= 1
    word = _WORD_CHARS.match(text, start).group()
    if word[0] == "'" or not word[0].isalpha():
        return None
    stmt_start = max(text.rfind(";", 0, start), text.rfind("{", 0, start), text.rfind("}", 0, start)) + 1
    stmt_end = text.find(";", start)
    stmt_end = len(text) if stmt_end < 0 else stmt_end + 1
    quoted = text[stmt_start:start] + f'"{word}"' + text[start + len(word):stmt_end]
    at = start - stmt_start
    outer = getattr(_lexed, "text", "")
    _lexed.text = quoted
    try:
        tree = _parser().parse(quoted)
    except UnexpectedInput:
        tree = None
    finally:
        _lexed_reserved().clear()
        _lexed.text = outer
    if tree is None or not any(sub.data == "name" and isinstance(tok, Token) and tok.start_pos == at
                               for sub in tree.iter_subtrees() for tok in sub.children):
        parts = ["".join(x for x in unicodedata.normalize("NFKD", c) if x.isascii()) for c in word]
        ascii_name = "".join(parts)
        example = f", e.g. '{ascii_name}'" if all(parts) and ascii_name[0].isalpha() else ""
        return (f"Names of colour sets, variables, constants and functions are written in ASCII letters, digits, "
                f"'_' and \"'\": rename '{word}'{example}. Only the names of places, transitions and module "
                f"instances may be quoted to hold other characters.")
    return (f"Write the name in double quotes: \"{word}\". A place, transition or instance may have any name in "
            f"quotes; every use of it is quoted too (arc \"{word}\" -> ...; in a property, Mark \"Page'{word}\" 1).")


def _missing_semicolon(exc: UnexpectedInput, text: str, filename: str) -> Diagnostic | None:
    """A statement keyword at the start of a line after a line without ';': the classic missing ';'."""
    line = getattr(exc, "line", None)
    if not isinstance(line, int) or line < 2:
        return None
    lines = text.splitlines()
    if line > len(lines):
        return None
    m = _STMT_START.match(lines[line - 1])
    if not m or not m.group(1):
        return None
    prev = line - 1
    while prev >= 1 and not lines[prev - 1].strip():
        prev -= 1
    if prev < 1:
        return None
    tail = re.sub(r"\(\*.*?\*\)|//.*$", "", lines[prev - 1]).rstrip()
    if not tail or tail.endswith((";", "{", "}")):
        return None
    kw = m.group(1)
    col = m.start(1) + 1
    return Diagnostic(
        "E0101",
        f"expected ';' after the declaration on line {prev}, found '{kw}'",
        Span(filename, line, col, line, col + len(kw) - 1),
        hint=f"Each declaration ends with ';'. Add one at the end of line {prev}.",
        params={"found": kw, "line": prev},
    )


_OPENERS = re.compile(r'\(\*|"|//')
_IN_COMMENT = re.compile(r"\(\*|\*\)")


def blank_comments(text: str, filename: str) -> tuple[str, Diagnostic | None]:
    """The text with its comments `(* .. *)` blanked out (nested, as in SML; line breaks kept, so positions
    stay), and E0102 for the first comment without its `*)` or string without its closing quote on its line.

    Scanned in the order the lexer reads: a `(*` inside a string or after `//` opens no comment, a quote
    inside a comment opens no string.
    """
    out = []
    done = pos = 0
    while True:
        m = _OPENERS.search(text, pos)
        if m is None:
            break
        start = m.start()
        if m.group() == "//":
            end = text.find("\n", start)
            if end < 0:
                break
            pos = end + 1
        elif m.group() == "(*":
            depth, at = 1, start + 2
            while depth:
                c = _IN_COMMENT.search(text, at)
                if c is None:
                    line, col = _line_col(text, start)
                    return text, Diagnostic(
                        "E0102", f"the comment opened at {filename}:{line}:{col} is never closed",
                        Span(filename, line, col, line, col + 1), params={"kind": "comment"},
                        hint="Close it with '*)': everything from this '(*' to the end of the text is inside the "
                        "comment (comments nest: each '(*' inside it needs its own '*)').")
                depth += 1 if c.group() == "(*" else -1
                at = c.end()
            out.append(text[done:start])
            out.append(re.sub(r"[^\n]", " ", text[start:at]))
            done = pos = at
        else:
            string = _STRING_AT.match(text, start)
            if string is None:
                line, col = _line_col(text, start)
                return text, Diagnostic(
                    "E0102", f"the string opened at {filename}:{line}:{col} is never closed",
                    Span(filename, line, col, line, col), params={"kind": "string"},
                    hint="Close the string with '\"' on the same line (write a line break inside a string as \\n).")
            pos = string.end()
    out.append(text[done:])
    return "".join(out), None


def unterminated(text: str, filename: str) -> Diagnostic | None:
    """E0102 for the first comment or string of the text that is never closed (`blank_comments`)."""
    return blank_comments(text, filename)[1]


_STRING_AT = re.compile(r'"(?:\\.|[^"\\\n])*"')


def _offset(text: str, line: int, col: int) -> int:
    lines = text.splitlines(keepends=True)
    return sum(len(x) for x in lines[: line - 1]) + col - 1


_OPEN = {"(": ")", "[": "]", "{": "}"}
_TOKENS = re.compile(r'\(\*.*?\*\)|//[^\n]*|"(?:\\.|[^"\\\n])*"|[()\[\]{}]', re.DOTALL)


def _line_col(text: str, pos: int) -> tuple[int, int]:
    return text.count("\n", 0, pos) + 1, pos - (text.rfind("\n", 0, pos) + 1) + 1


def _statement_starts(text: str) -> list[int]:
    """Where the statements of `text` start: a line that begins with a statement keyword, but for `val` and
    `fun` inside open brackets, which declare inside a `let` (a CPN Tools action `(let val f = .. in .. end)`
    spans lines that begin with `val`)."""
    starts: list[int] = []
    depth, last = 0, 0
    for m in _STMT_START.finditer(text):
        if not m.group(1):
            continue
        for t in _TOKENS.finditer(text, last, m.start()):
            tok = t.group()
            depth += 1 if tok in _OPEN else -1 if tok in (")", "]", "}") else 0
        last = m.start()
        if m.group(1) in ("val", "fun") and depth > 0:
            continue
        starts.append(m.start())
        depth = 0  # a statement starts afresh: an error before it is its own
    return starts


def _unbalanced(text: str, filename: str) -> list[tuple[Diagnostic, int, int]]:
    """Statements whose brackets do not balance: (diagnostic, start, end) of each such statement."""
    starts = _statement_starts(text) + [len(text)]
    out = []
    for a, b in zip(starts, starts[1:]):
        seg = text[a:b]
        stack: list[tuple[str, int]] = []
        bad = None
        for m in _TOKENS.finditer(seg):
            tok = m.group()
            if tok in _OPEN:
                stack.append((tok, a + m.start()))
            elif tok in (")", "]", "}"):
                if stack and _OPEN[stack[-1][0]] == tok:
                    stack.pop()
                elif tok == "}" and not stack:
                    continue  # the end of a module body
                elif any(_OPEN[t] == tok for t, _ in stack):
                    # `[(x < 3]`: the ']' has its partner; the '(' opened after it is the one left open
                    bad = (stack[-1][0], stack[-1][1], "opening", tok, a + m.start())
                    break
                else:
                    bad = (tok, a + m.start(), "closing")
                    break
        if bad is None and stack:
            tok, pos = next(((t, q) for t, q in stack if t != "{"), (None, None))
            if tok is not None:
                bad = (tok, pos, "opening")
        if bad:
            tok, pos, kind = bad[:3]
            line, col = _line_col(text, pos)
            msg = (f"'{tok}' is never closed" if kind == "opening" else f"'{tok}' closes nothing")
            hint = "Check that every '(', '[' and '{' has its closing partner in the same declaration."
            if len(bad) > 3:
                close = bad[3]
                msg = "'{}' is not closed before the '{}' at {}:{}".format(tok, close, *_line_col(text, bad[4]))
                hint = f"Add '{_OPEN[tok]}' before the '{close}', or remove the '{tok}'."
            out.append((Diagnostic("E0101", f"unbalanced parentheses or brackets: {msg}",
                                   Span(filename, line, col, line, col), hint=hint), a, b))
    return out


def parse(text: str, filename: str = "<string>", *, using: tuple[str, ...] = ()) -> A.Model:
    """Parse `.cpnet` source text into an `ast.Model`, with the declarations of the files it `use`s.

    `using` holds the files whose `use` led here (cpn.lang.uses).

    Raises `ModelSyntaxError` with one diagnostic per erroneous statement (at most one per line).
    """
    parser = _parser()
    if text.startswith(BOM):
        # a UTF-8 byte-order mark is no part of the text (editors on Windows write one)
        text = text[len(BOM):]
    diags: list[Diagnostic] = []
    work, open_ = blank_comments(text, filename)
    if open_ is not None:
        # the rest of the text is inside the comment or string: nothing after it can be read
        raise ModelSyntaxError([open_], {filename: text})
    seen_lines: set[int] = set()
    while True:
        _lexed_reserved().clear()
        _lexed.text = work
        try:
            tree = parser.parse(work)
            break
        except UnexpectedInput as exc:
            unbalanced = _unbalanced(work, filename)
            if unbalanced:
                for d, a, b in unbalanced:
                    if d.span.line not in seen_lines:
                        seen_lines.add(d.span.line)
                        diags.append(d)
                    work = work[:a] + re.sub(r"[^\n]", " ", work[a:b]) + work[b:]
                continue
            d = _diagnose(exc, work, filename)
            if d.span.line not in seen_lines:
                seen_lines.add(d.span.line)
                diags.append(d)
            if isinstance(exc, UnexpectedEOF) or (isinstance(exc, UnexpectedToken) and exc.token.type == "$END"):
                tree = None
                break
            if len(diags) >= MAX_SYNTAX_ERRORS:
                tree = None
                break
            # blank out the erroneous statement (keeping positions) and parse again
            pos = _offset(work, d.span.line, d.span.col)
            start = work.rfind(";", 0, pos) + 1
            m = _STMT_START.search(work, pos + 1)
            nxt = m.start() if m else len(work)
            if nxt <= start:
                tree = None
                break
            blank = re.sub(r"[^\n]", " ", work[start:nxt])
            work = work[:start] + blank + work[nxt:]
    if tree is not None:
        seen = {d.span.line for d in diags}
        diags += [d for d in _reserved_names(tree, filename) if d.span.line not in seen]
    if diags:
        diags.sort(key=lambda d: (d.span.line, d.span.col))
        other = other_command_hint(filename, text, "model")
        if other is not None:
            # a scenario file given to lint or explore: its first error and where it belongs, not one per line
            first = diags[0]
            first.hint = other
            if len(diags) > 1:
                first.notes.append(f"{len(diags) - 1} more syntax {'error' if len(diags) == 2 else 'errors'} "
                                   "not shown: the file is not a model")
            diags = [first]
        raise ModelSyntaxError(diags, {filename: text})
    try:
        decls = ToAst(filename).transform(balance_chains(tree))
    except VisitError as exc:
        if isinstance(exc.orig_exc, RecursionError):
            raise exc.orig_exc from None  # too deeply nested: the caller reports E0206
        raise
    if any(isinstance(d, (A.UseDecl, A.ModuleDecl)) for d in decls):
        decls = expand_uses(decls, filename, text, parse, using)
    return A.Model(filename, text, decls)
