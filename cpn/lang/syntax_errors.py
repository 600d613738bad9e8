"""Friendly syntax errors: a table of (code, message, hint, malformed examples), as lark's GRAMMAR_ERRORS.

Each example is parsed in tests and must produce its row's message. The parser matches an error against
the examples by parser state (`UnexpectedInput.match_examples`).
"""

from __future__ import annotations

SYNTAX_ERRORS: list[tuple[str, str, str, list[str]]] = [
    (
        "E0101",
        "expected ':' and a colour set after the place name",
        "A place is declared as 'place NAME : COLSET = INITIAL_MARKING;'.",
        ["place A;", "place A = 1`1;", "port in A;"],
    ),
    (
        "E0101",
        "expected 'then' in the if-expression",
        "Write 'if CONDITION then E1 else E2'.",
        ["val x = if a b;", "val x = if a else b;"],
    ),
    (
        "E0101",
        "expected 'else': every if-expression in CPN ML needs an else branch",
        "Add 'else E2'; for multisets 'else empty' is common.",
        ["val x = if a then b;"],
    ),
    (
        "E0101",
        "'==' is not an operator in CPN ML",
        "Equality is written with a single '=' in CPN ML.",
        ["val x = a == b;", "trans T [a == b];"],
    ),
    (
        "E0101",
        "expected an expression",
        "An expression is missing here.",
        ["val x = ;", "arc A -> T : ;", "val x = 1 + ;"],
    ),
    (
        "E0101",
        "unbalanced parentheses or brackets",
        "Check that every '(' , '[' and '{' has its closing partner.",
        ["val x = (1 + 2;", "val x = [1, 2;", "trans T [x = 1;"],
    ),
    (
        "E0101",
        "a family of instances names its variable and its values: 'instance NAME[i : LOW..HIGH] = ...'",
        "Write 'instance Slave[i : 1..MAXS] = Slave(me = i) { ... };' (the values LOW..HIGH, integer constants) "
        "or 'instance Slave[i : SIX] = ...' (the values of a colour set).",
        ["instance S[i] = M(me = i);", "instance S[i : 1..] = M(me = i);", "instance S[i : ] = M;"],
    ),
    (
        "E0101",
        "expected ';' after the declaration",
        "Each declaration ends with ';'. Add one at the end of the previous declaration.",
        [
            "place A : INT\nplace B : INT;",
            "val N = 5\nval M = 6;",
            "trans T\ntrans U;",
            "arc A -> T : x\narc T -> B : x;",
            "var x : INT\nplace A : INT;",
            "colset A = int\ncolset B = int;",
        ],
    ),
]

# readable names of terminals for "expected ..." messages
TERMINAL_NAMES: dict[str, str] = {
    "SEMICOLON": "';'", "COLON": "':'", "EQUAL": "'='", "NAME": "a name", "STRING": "a string",
    "INT": "a number", "LPAR": "'('", "RPAR": "')'", "LSQB": "'['", "RSQB": "']'", "LBRACE": "'{'",
    "RBRACE": "'}'", "COMMA": "','", "ARROW": "'->'", "THEN": "'then'", "ELSE": "'else'", "END": "'end'",
    "IN": "'in'", "OF": "'of'", "DARROW": "'=>'", "QUALNAME": "a qualified name", "$END": "the end of the file",
    "VBAR": "'|'", "DOT": "'.'", "__ANON_0": "'..'",
}
