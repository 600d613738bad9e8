"""The machine's clock and text output, which CPN Tools models call through SML/NJ's Basis Library: the
`Time` structure (CPN Tools names it `SMLTime`, its own `Time` being the model time), `Date.fromTimeLocal`
and `Date.fromTimeUniv`, `TextIO`'s output streams, and SML's references (`ref e`, a `Cell`).

A time (`Time.time`) is a number of seconds since 1970-01-01 00:00 UTC; `Time.fromSeconds`,
`Time.toSeconds`, `Time.fromReal`, `Time.toReal` and `Date.fromTimeUniv` are functions of their argument.
The others have no state-space meaning (`SIMULATION_ONLY`): `Time.now` reads the machine's clock and
`Date.fromTimeLocal` the machine's time zone, so a run that reads them depends on when and where it runs, not
only on its seed. `TextIO` output is accepted and dropped: `openOut`, `openAppend` create no file, `output`
and `print` write nothing (a stream is the name of its file). explore and check refuse a net that calls any of
them where the net uses it, and so is a reference variable (docs/semantics.md).

>>> d = FUNCTIONS["Date.fromTimeUniv"](FUNCTIONS["SMLTime.fromSeconds"](86400 + 3661))
>>> d[:6]
(1970, 0, 2, 1, 1, 1)
>>> FUNCTIONS["TextIO.output"]((FUNCTIONS["TextIO.openOut"]("log.txt"), "not written"))
()
"""

from __future__ import annotations

import datetime
import math
import time as _time

from cpn.values.builtins import MLError


def _from_time(t, tz) -> tuple:
    d = datetime.datetime.fromtimestamp(t, tz) if tz is not None else datetime.datetime.fromtimestamp(t)
    offset = ("SOME", 0) if tz is not None else "NONE"
    return (d.year, d.month - 1, d.day, d.hour, d.minute, d.second, offset)


def _now(_unit):
    return _time.time()


def _dropped(_arg):
    return ()


_TIME_FUNCTIONS: dict[str, tuple[str, object]] = {
    "fromSeconds": ("int -> Time.time", lambda n: n),
    "toSeconds": ("Time.time -> int", lambda t: math.floor(t)),
    "fromReal": ("real -> Time.time", float),
    "toReal": ("Time.time -> real", float),
    "now": ("unit -> Time.time", _now),
}

# name -> (type, implementation)
BUILTINS: dict[str, tuple[str, object]] = {
    **{f"{s}.{f}": v for s in ("Time", "SMLTime") for f, v in _TIME_FUNCTIONS.items()},
    "Date.fromTimeLocal": ("Time.time -> Date.date", lambda t: _from_time(t, None)),
    "Date.fromTimeUniv": ("Time.time -> Date.date", lambda t: _from_time(t, datetime.timezone.utc)),
    "TextIO.openOut": ("string -> TextIO.outstream", lambda name: name),
    "TextIO.openAppend": ("string -> TextIO.outstream", lambda name: name),
    "TextIO.output": ("TextIO.outstream * string -> unit", _dropped),
    "TextIO.flushOut": ("TextIO.outstream -> unit", _dropped),
    "TextIO.closeOut": ("TextIO.outstream -> unit", _dropped),
    "TextIO.print": ("string -> unit", _dropped),
    "print": ("string -> unit", _dropped),
    # CPN Tools' simulator names a folder for a run's output and creates it: simulate creates nothing
    "Output.getSimOutputDir": ("unit -> string", lambda _u: "output/"),
    "Output.initSimOutputDir": ("unit -> unit", _dropped),
    "TextIO.stdOut": ("TextIO.outstream", "<stdOut>"),
    "TextIO.stdErr": ("TextIO.outstream", "<stdErr>"),
}



class Cell:
    """A reference variable's cell (`ref e`, CPN Tools' `globref`): its value changes in place (`x := e`) and
    `!x` reads it. Equal only to itself, as SML's `=` on references. A cell made by a global `val` belongs
    to the net; each engine works on copies of those made once (`cpn.expr.evaluate.Evaluator`), so a run
    starts from the values the declarations gave them.

    >>> c = FUNCTIONS["ref"](1)
    >>> c.value = c.value + 1
    >>> c.value, c == FUNCTIONS["ref"](2)
    (2, False)
    """

    __slots__ = ("value",)

    def __init__(self, value):
        self.value = value

    def __repr__(self) -> str:
        return f"ref {self.value!r}"


def _add(n: int):
    def add(cell: Cell):
        cell.value += n
        return ()
    return add


BUILTINS["ref"] = ("'a -> 'a ref", Cell)
BUILTINS["inc"] = ("int ref -> unit", _add(1))  # SML/NJ's inc and dec
BUILTINS["dec"] = ("int ref -> unit", _add(-1))


class OtherProgram(MLError):
    """A call that needs a program or a file that simulate does not have: a socket to another program (CPN
    Tools' Comms/CPN library) or a file to read. The evaluator reports it as a run-time error (E0401) at the
    occurrence that makes the call, naming the function."""


def cannot_run(name: str, what: str):
    """A library function that simulate cannot run: calling it raises OtherProgram naming `name`."""
    def run(arg):
        raise OtherProgram(f"'{name}' {what}: simulate cannot run it ({_describe(arg)})")
    return run


def _describe(arg) -> str:
    first = arg[0] if isinstance(arg, tuple) and arg else arg
    return f"its argument is {first!r}" if isinstance(first, (str, int)) else "it talks to no other program"


# Comms/CPN (CPN Tools' library for talking to other programs over TCP): `ConnManagementLayer` opens, uses
# and closes named connections; the encode/decode functions turn values into the bytes sent. A model that
# calls them needs the other program running: simulate stops at the occurrence that calls one.
_COMMS = "talks to another program over a socket (Comms/CPN)"
BUILTINS.update({
    "ConnManagementLayer.openConnection": ("string * string * int -> unit",
                                           cannot_run("ConnManagementLayer.openConnection", _COMMS)),
    "ConnManagementLayer.acceptConnection": ("string * int -> unit",
                                             cannot_run("ConnManagementLayer.acceptConnection", _COMMS)),
    "ConnManagementLayer.closeConnection": ("string -> unit",
                                            cannot_run("ConnManagementLayer.closeConnection", _COMMS)),
    "ConnManagementLayer.send": ("string * 'a * ('a -> Word8Vector.vector) -> unit",
                                 cannot_run("ConnManagementLayer.send", _COMMS)),
    "ConnManagementLayer.receive": ("string * (Word8Vector.vector -> 'a) -> 'a",
                                    cannot_run("ConnManagementLayer.receive", _COMMS)),
    "integerEncode": ("int -> Word8Vector.vector", lambda n: str(n).encode()),
    "integerDecode": ("Word8Vector.vector -> int", lambda b: int(b.decode())),
    "stringEncode": ("string -> Word8Vector.vector", lambda x: x.encode()),
    "stringDecode": ("Word8Vector.vector -> string", lambda b: b.decode()),
    # file input: the files a model reads are not part of it, so simulate reads none
    "TextIO.openIn": ("string -> TextIO.instream", cannot_run("TextIO.openIn", "reads a file")),
    "TextIO.inputLine": ("TextIO.instream -> string option", cannot_run("TextIO.inputLine", "reads a file")),
    "TextIO.inputAll": ("TextIO.instream -> string", cannot_run("TextIO.inputAll", "reads a file")),
    "TextIO.endOfStream": ("TextIO.instream -> bool", cannot_run("TextIO.endOfStream", "reads a file")),
    "TextIO.closeIn": ("TextIO.instream -> unit", cannot_run("TextIO.closeIn", "reads a file")),
    # `TextIO.scanStream Real.scan ins`: the next real of a file (the scanners are values of their own type)
    "TextIO.scanStream": ("Real.scanner -> TextIO.instream -> real option",
                          cannot_run("TextIO.scanStream", "reads a file")),
    "Real.scan": ("Real.scanner", "<Real.scan>"),
})

FUNCTIONS: dict[str, object] = {name: fn for name, (_, fn) in BUILTINS.items()}

# those that simulate cannot run either: it stops at the first occurrence that calls one (OtherProgram)
STOPS_SIMULATE: frozenset[str] = frozenset(name for name, (ty, _) in BUILTINS.items()
                                           if name.startswith("ConnManagementLayer.") or "instream" in ty)

_CLOCK_HINT = ("For a state space, use the model time (time()) or a value on a token: the machine's clock and "
               "time zone are no part of a state.")
_OUTPUT_HINT = ("For a state space, remove the output, or move it into a code segment that binds no output "
                "variable (it is left out); simulate accepts it and writes nothing.")

_COMMS_HINT = ("The other program is no part of the model: for a state space (and for simulate), replace the "
               "calls by a place that holds the messages it may send, and a transition per answer.")
_INPUT_HINT = ("A file is no part of the model: put its values in the model (a 'val' list, or tokens of an "
               "initial marking).")

_REF_HINT = ("A reference variable has no state-space meaning: keep the value in a place (a token that the "
             "transitions which read or assign it take and put back).")

# the names with no state-space meaning: name -> (what it is, what to change)
SIMULATION_ONLY: dict[str, tuple[str, str]] = {
    **{f"{s}.now": ("reads the machine's clock", _CLOCK_HINT) for s in ("Time", "SMLTime")},
    "Date.fromTimeLocal": ("reads the machine's time zone", "Use Date.fromTimeUniv, which is a function of "
                           "its argument; " + _CLOCK_HINT[0].lower() + _CLOCK_HINT[1:]),
    **{name: ("writes text output (dropped: simulate writes nothing)", _OUTPUT_HINT)
       for name, (ty, fn) in BUILTINS.items()
       if (name.startswith("TextIO.") or name == "print") and callable(fn) and "instream" not in ty},
    **{name: (_COMMS, _COMMS_HINT) for name in BUILTINS if name.startswith("ConnManagementLayer.")},
    **{name: ("reads a file", _INPUT_HINT) for name, (ty, _) in BUILTINS.items() if "instream" in ty},
    "ref": ("makes a reference variable, whose value is not part of the marking", _REF_HINT),
    "Output.getSimOutputDir": ("names the simulator's output folder", _OUTPUT_HINT),
    "Output.initSimOutputDir": ("creates the simulator's output folder (simulate creates nothing)",
                                _OUTPUT_HINT),
}

__all__ = ["BUILTINS", "Cell", "FUNCTIONS", "cannot_run", "SIMULATION_ONLY", "STOPS_SIMULATE", "OtherProgram"]
