"""Lexical helpers for the CPN ML text found in CPN Tools files: names, keywords, impure identifiers.

Nothing here parses CPN ML; the one front end (`cpn.lang`) does. These helpers only look at tokens, to
decide how to write a name and to refuse what no state space can hold. Imports the standard library only.
"""

from __future__ import annotations

import re

# A name that can be written without quotes in `.cpnet`.
IDENT_RE = re.compile(r"[A-Za-z][A-Za-z0-9_]*\Z")
# A CPN ML name (a colour set, a variable, a function): letters, digits, '_' and primes (`L'RNG`)
ML_IDENT_RE = re.compile(r"[A-Za-z][A-Za-z0-9_']*\Z")

# Words that cannot be bare names: SML reserved words and the `.cpnet` structure keywords.
KEYWORDS: frozenset[str] = frozenset(
    """abstype and andalso as case datatype do else end eqtype exception fn fun functor handle if in
    include infix infixr let local nonfix of op open orelse raise rec sharing sig signature struct
    structure then type val where while with withtype not div mod
    colset var net place trans transition arc inhibitor reset module port out io instance fusion priority
    timed unit bool int real string index product record list union subset by empty true false
    """.split()
)

# Functions that draw random values from an infinite or continuous domain (CPN Tools' random
# distribution library). A net that calls them has no deterministic occurrence graph.
RANDOM_FUNCTIONS: frozenset[str] = frozenset(
    """exponential normal uniform erlang gamma beta chisq student weibull rayleigh cauchy lognormal
    discrete bernoulli binomial poisson""".split()
)

# Names (or the first part of qualified names) of side effects: I/O, monitors, charts, communication
# (Comms/CPN's ConnManagementLayer).
SIDE_EFFECT_NAMES: frozenset[str] = frozenset(
    """TextIO print MSC OS Posix Unix send_to_applet acceptConnection openConnection closeConnection
    send receive ConnManagementLayer Comms""".split()
)

# Random draws over finitely many integers: a choice of every value where CS.ran() is one (cpn.lang.infer)
FINITE_DRAWS: frozenset[str] = frozenset({"discrete", "bernoulli"})

# Structures whose functions draw random values (SML/NJ's random generator: `Random.randRange (1, 36) gen`).
RANDOM_STRUCTURES: frozenset[str] = frozenset({"Random"})

_TOKEN_RE = re.compile(
    r"""(?P<comment>\(\*)|(?P<string>"(?:[^"\\]|\\.)*")|(?P<name>[A-Za-z][A-Za-z0-9_']*(?:\.[A-Za-z][A-Za-z0-9_']*)*)
    |(?P<assign>:=)|(?P<bang>!(?=\s*[A-Za-z(]))|(?P<other>.)""",
    re.S | re.X,
)


def unclosed(text: str) -> tuple[int, str] | None:
    """(offset, 'comment' or 'string') of the first (nested) comment or string that is never closed."""
    depth = 0
    opened: list[int] = []
    i = 0
    n = len(text)
    while i < n:
        two = text[i : i + 2]
        if depth == 0 and text[i] == '"':
            j = i + 1
            while j < n and text[j] not in '"\n':
                j += 2 if text[j] == "\\" else 1
            if j >= n or text[j] != '"':
                return i, "string"
            i = j + 1
            continue
        if two == "(*":
            depth += 1
            opened.append(i)
            i += 2
            continue
        if two == "*)" and depth:
            depth -= 1
            opened.pop()
            i += 2
            continue
        i += 1
    return (opened[0], "comment") if opened else None


def strip_comments(text: str) -> str:
    """Replace (nested) ML comments by blanks of the same shape, so positions stay valid."""
    out = []
    depth = 0
    i = 0
    n = len(text)
    in_string = False
    while i < n:
        two = text[i : i + 2]
        ch = text[i]
        if depth == 0 and ch == '"':
            in_string = not in_string
            out.append(ch)
            i += 1
            continue
        if in_string:
            if ch == "\\" and i + 1 < n:
                out.append(text[i : i + 2])
                i += 2
                continue
            out.append(ch)
            i += 1
            continue
        if two == "(*":
            depth += 1
            out.append("  ")
            i += 2
            continue
        if two == "*)" and depth:
            depth -= 1
            out.append("  ")
            i += 2
            continue
        out.append(ch if depth == 0 or ch == "\n" else " ")
        i += 1
    return "".join(out)


def names(text: str) -> list[tuple[str, int]]:
    """The (possibly qualified) identifiers of a CPN ML text with their offsets, outside strings/comments."""
    result = []
    for m in _TOKEN_RE.finditer(strip_comments(text)):
        if m.lastgroup == "name":
            result.append((m.group(), m.start()))
    return result


def assigned_refs(text: str) -> set[str]:
    """Names assigned with `:=` in a text (`x := e`)."""
    clean = strip_comments(text)
    return set(re.findall(r"([A-Za-z][A-Za-z0-9_']*)\s*:=", clean))


def _nest(kw: str | None, blocks: list[str]) -> bool:
    """Follow SML's nesting of blocks at keyword `kw`: `blocks` is the stack of open let/local/struct/sig
    blocks, a `local` marked 'local-in' once its `in` is read. Whether `kw` was a block keyword."""
    if kw in ("let", "local", "struct", "sig"):
        blocks.append(kw)
    elif kw == "in":
        if blocks and blocks[-1] == "local":
            blocks[-1] = "local-in"
    elif kw == "end":
        if blocks:
            blocks.pop()
    else:
        return False
    return True


def datatype_names(text: str) -> set[str]:
    """The type names and constructors that the `datatype` declarations of an ML text declare."""
    out: set[str] = set()
    for m in re.finditer(r"\bdatatype\s+([A-Za-z][\w']*)\s*=([^;]*)", strip_comments(text)):
        out.add(m.group(1))
        out |= {c.group(1) for c in re.finditer(r"(?:^|\|)\s*([A-Za-z][\w']*)", m.group(2))}
    return out


def declared_functions(text: str) -> list[tuple[str, str]]:
    """(name, body text) for each top-level `fun NAME` / `val NAME` of an ML declaration text.

    Top level means outside `let` ... `end` and outside the private part of `local` ... `in`; the
    declarations between the `in` and the `end` of a `local` block are top level (the net sees them).
    The body is everything up to the next top-level declaration: enough to decide which names a
    declaration depends on.
    """
    clean = strip_comments(text)
    heads = []
    blocks: list[str] = []  # the open let/local/struct/sig blocks; 'local-in' once a local's 'in' is read
    for m in re.finditer(r'"(?:[^"\\]|\\.)*"|(?<![\w\'])(let|local|struct|sig|in|end)(?![\w\'])'
                         r"|(?<![\w'])(fun|val|and|exception)(?![\w'])"
                         r"(?:\s+(?:rec\s+)?(?:\(\s*)?(?:op\s+)?(?!(?:fun|val|and|in|end|local|let)\b)([A-Za-z][A-Za-z0-9_']*))?",
                         clean):
        kw = m.group(1) or m.group(2)
        if _nest(kw, blocks):
            continue
        if kw in ("fun", "val", "and", "exception") and m.group(3) and all(b == "local-in" for b in blocks):
            heads.append((m.group(3), m.start(), m.end()))
    out = []
    for i, (name, _start, end) in enumerate(heads):
        stop = heads[i + 1][1] if i + 1 < len(heads) else len(clean)
        out.append((name, clean[end:stop]))
    return out


def separate_declarations(text: str) -> str:
    """Put the ';' that SML lets a file leave out between two top-level declarations (`fun f x = ..` and
    `fun g y = ..` on the next lines) at the end of the line before the second one, so that every other
    character keeps its line and column."""
    clean = strip_comments(text)
    blocks: list[str] = []
    inserts: list[int] = []
    for m in re.finditer(r'"(?:[^"\\]|\\.)*"|(?<![\w\'])(let|local|struct|sig|in|end|fun|val|exception)(?![\w\'])',
                         clean):
        kw = m.group(1)
        if kw == "local" and not blocks:
            before = clean[:m.start()].rstrip()
            if before and not before.endswith(";"):
                inserts.append(len(before))
        if _nest(kw, blocks):
            continue
        if kw in ("fun", "val", "exception") and not blocks:
            before = clean[:m.start()].rstrip()
            # `val` after `fun ... =` is no declaration (`val` only starts one); `op val` cannot occur
            if before and not before.endswith(";") and not before.endswith("="):
                inserts.append(len(before))
    for at in reversed(inserts):
        text = text[:at] + ";" + text[at:]
    return text


def single_semicolons(text: str) -> str:
    """`val x = 1;;` as SML reads it: the ';' after a ';' (an empty declaration) becomes a blank, so that
    every character keeps its line and column. Strings and comments are left as they are."""
    clean = strip_comments(text)
    out = list(text)
    for m in re.finditer(r'"(?:[^"\\\n]|\\.)*"|;((?:\s*;)+)', clean):
        if m.group(1):
            for i in range(m.start(1), m.end(1)):
                if clean[i] == ";":
                    out[i] = " "
    return "".join(out)


def ml_name(text: str) -> str:
    """The name CPN Tools gives an element in ML and in its reports.

    Every character an ML identifier cannot hold becomes `_`, one for one, in the name as drawn: a place
    named "Packets<newline>To Send" is `Packets_To_Send` (`Mark.Top'Send_Mes`, `Bind.Page'Take_Chopsticks`
    in the sample nets' saved queries; cpncheck documents the same rule, checked against CPN Tools 4.0.1).
    """
    return re.sub(r"[^A-Za-z0-9_']", "_", text.strip())


def ml_ident(name: str) -> str:
    """A CPN ML name as written in `.cpnet`: as it is when it is one (primes included), else quoted."""
    return name if ML_IDENT_RE.match(name) and name not in KEYWORDS else quote(name)


def quote(name: str) -> str:
    """`name` as written in `.cpnet`: bare if it is an identifier and no keyword, else quoted."""
    if IDENT_RE.match(name) and name not in KEYWORDS:
        return name
    return '"' + name.replace("\\", "\\\\").replace('"', '\\"') + '"'
