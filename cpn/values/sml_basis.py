"""The parts of the Standard ML Basis Library that CPN Tools models compute with beyond lists and strings:
`option` (`NONE`, `SOME`, `Option.getOpt`, `Int.fromString`), `order` (`LESS`, `EQUAL`, `GREATER`,
`Int.compare`, `String.compare`) and the `Date` structure (`Date.date`, its fields, `Date.compare`,
`Date.fmt`, `Date.toString`), on the value representation of `cpn.values`.

Constructors without an argument are their tag (`"NONE"`, `"LESS"`); `SOME v` is `("SOME", v)`; a month
is its number 0..11 (an enumeration constant); a date is the tuple (year, month, day, hour, minute,
second, offset), normalised as `Date.date` normalises it (61 seconds are a minute and a second).

>>> d = FUNCTIONS["Date.date"]((1, 0, 0, 0, "NONE", 90, 2000))
>>> FUNCTIONS["Date.fmt"]("%Y-%m-%dT%H:%M:%S")(d)
'2000-01-01T00:01:30'
>>> FUNCTIONS["Option.getOpt"]((FUNCTIONS["Int.fromString"](" 12ab"), 0))
12
"""

from __future__ import annotations

import datetime
import re
from typing import Any

from cpn.values.builtins import MLError

MONTHS: tuple[str, ...] = ("Jan", "Feb", "Mar", "Apr", "May", "Jun", "Jul", "Aug", "Sep", "Oct", "Nov", "Dec")
WEEKDAYS: tuple[str, ...] = ("Mon", "Tue", "Wed", "Thu", "Fri", "Sat", "Sun")

# constructor name -> (type name, tag, has_arg): the tag is the run-time value (or its first component)
CONSTRUCTORS: dict[str, tuple[str, Any, bool]] = {
    "NONE": ("option", "NONE", False),
    "SOME": ("option", "SOME", True),
    "LESS": ("order", "LESS", False),
    "EQUAL": ("order", "EQUAL", False),
    "GREATER": ("order", "GREATER", False),
    **{f"Date.{m}": ("Date.month", i, False) for i, m in enumerate(MONTHS)},
    **{f"Date.{d}": ("Date.weekday", i, False) for i, d in enumerate(WEEKDAYS)},
}


def _order(a, b) -> str:
    return "LESS" if a < b else "GREATER" if a > b else "EQUAL"


def _get_opt(arg):
    opt, default = arg
    return opt[1] if isinstance(opt, tuple) else default


def _val_of(opt):
    if not isinstance(opt, tuple):
        raise MLError("Option.valOf NONE (SML exception Option)")
    return opt[1]


_INT_PREFIX = re.compile(r"\s*([~+-]?)(\d+)")


def _int_from_string(s: str):
    """SML's Int.fromString: skips leading white space, reads an optional sign (~, - or +) and digits, and
    ignores what follows them; NONE where no digit comes."""
    m = _INT_PREFIX.match(s)
    if m is None:
        return "NONE"
    n = int(m.group(2))
    return ("SOME", -n if m.group(1) in ("~", "-") else n)


_REAL_PREFIX = re.compile(r"\s*([~+-]?)(\d+(?:\.\d+)?|\.\d+)(?:[eE]([~+-]?\d+))?")


def _real_from_string(s: str):
    """SML's Real.fromString: leading white space, an optional sign (~, - or +), digits with an optional
    fraction and exponent; what follows is ignored; NONE where no number comes."""
    m = _REAL_PREFIX.match(s)
    if m is None:
        return "NONE"
    x = float(m.group(2) + ("e" + m.group(3).replace("~", "-") if m.group(3) else ""))
    return ("SOME", -x if m.group(1) in ("~", "-") else x)


def _date(fields):
    """Date.date {day, hour, minute, month, offset, second, year} (the record's fields in label order)."""
    day, hour, minute, month, offset, second, year = fields
    try:
        d = datetime.datetime(year, month + 1, 1) + datetime.timedelta(days=day - 1, hours=hour, minutes=minute,
                                                                       seconds=second)
    except (ValueError, OverflowError):
        raise MLError(f"Date.date: no date in year {year} (SML exception Date.Date)") from None
    return (d.year, d.month - 1, d.day, d.hour, d.minute, d.second, offset)


def _py(d) -> datetime.datetime:
    return datetime.datetime(d[0], d[1] + 1, d[2], d[3], d[4], d[5])


def _fmt(spec: str):
    def fmt(d):
        text = _py(d).strftime(spec.replace("%a", "\x01a").replace("%b", "\x01b"))
        # the English names whatever the locale, as SML/NJ writes them
        return text.replace("\x01a", WEEKDAYS[_py(d).weekday()]).replace("\x01b", MONTHS[d[1]])
    return fmt


def _field(i: int):
    return lambda d: d[i]


FUNCTIONS: dict[str, Any] = {
    "Option.getOpt": _get_opt,
    "getOpt": _get_opt,
    "Option.valOf": _val_of,
    "valOf": _val_of,
    "Option.isSome": lambda opt: isinstance(opt, tuple),
    "isSome": lambda opt: isinstance(opt, tuple),
    "Int.fromString": _int_from_string,
    "Real.fromString": _real_from_string,
    "Int.compare": lambda ab: _order(*ab),
    "IntInf.toLarge": lambda n: n,  # int and IntInf.int are one type of unbounded integers here
    "IntInf.fromLarge": lambda n: n,
    "String.compare": lambda ab: _order(*ab),
    "Date.date": _date,
    "Date.year": _field(0),
    "Date.month": _field(1),
    "Date.weekDay": lambda d: _py(d).weekday(),  # Date.Mon is 0, as the constructors are numbered
    "Date.day": _field(2),
    "Date.hour": _field(3),
    "Date.minute": _field(4),
    "Date.second": _field(5),
    "Date.offset": _field(6),
    "Date.compare": lambda ab: _order(ab[0][:6], ab[1][:6]),
    "Date.fmt": _fmt,
    "Date.toString": _fmt("%a %b %d %H:%M:%S %Y"),
    # OS.Path joins names as text (no file is touched); the rest of OS talks to the machine
    "OS.Path.concat": lambda ab: ab[0] + ab[1] if not ab[0] or ab[0].endswith("/") else ab[0] + "/" + ab[1],
}
