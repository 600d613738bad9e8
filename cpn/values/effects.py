"""The machine's clock and text output, which CPN Tools models call through SML/NJ's Basis Library: the
`Time` structure (CPN Tools names it `SMLTime`, its own `Time` being the model time), `Date.fromTimeLocal`
and `Date.fromTimeUniv`, and `TextIO`'s output streams.

A time (`Time.time`) is a number of seconds since 1970-01-01 00:00 UTC; `Time.fromSeconds`,
`Time.toSeconds`, `Time.fromReal`, `Time.toReal` and `Date.fromTimeUniv` are functions of their argument.
The others have no state-space meaning (`SIMULATION_ONLY`): `Time.now` reads the machine's clock and
`Date.fromTimeLocal` the machine's time zone, so a run that reads them depends on when and where it runs, not
only on its seed. `TextIO` output is accepted and dropped: `openOut`, `openAppend` create no file, `output`
and `print` write nothing (a stream is the name of its file). explore and check refuse a net that calls any of
them where the net uses it (docs/semantics.md).

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
    "TextIO.stdOut": ("TextIO.outstream", "<stdOut>"),
    "TextIO.stdErr": ("TextIO.outstream", "<stdErr>"),
}

FUNCTIONS: dict[str, object] = {name: fn for name, (_, fn) in BUILTINS.items()}

_CLOCK_HINT = ("For a state space, use the model time (time()) or a value on a token: the machine's clock and "
               "time zone are no part of a state.")
_OUTPUT_HINT = ("For a state space, remove the output, or move it into a code segment that binds no output "
                "variable (it is left out); simulate accepts it and writes nothing.")

# the names with no state-space meaning: name -> (what it is, what to change)
SIMULATION_ONLY: dict[str, tuple[str, str]] = {
    **{f"{s}.now": ("reads the machine's clock", _CLOCK_HINT) for s in ("Time", "SMLTime")},
    "Date.fromTimeLocal": ("reads the machine's time zone", "Use Date.fromTimeUniv, which is a function of "
                           "its argument; " + _CLOCK_HINT[0].lower() + _CLOCK_HINT[1:]),
    **{name: ("writes text output (dropped: simulate writes nothing)", _OUTPUT_HINT)
       for name, (_, fn) in BUILTINS.items() if (name.startswith("TextIO.") or name == "print") and callable(fn)},
}

__all__ = ["BUILTINS", "FUNCTIONS", "SIMULATION_ONLY"]
