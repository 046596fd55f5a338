"""Plain numbers for the messages people read: ``11,210 N``, never ``1.121e+04 N``.

Every number in a human message (violations, advice, input errors) goes through
``plain_number``: rounded to a few significant digits (``MESSAGE_SIGNIFICANT_DIGITS``
unless the caller says otherwise), written in positional notation without trailing zeros
(``812``, ``0.125``, ``0.000123``), with a comma between groups of three digits from
``GROUP_FROM_DIGITS`` integer digits up (``1005``, ``11,210``, ``1,000,000``: four-digit
numbers stay ungrouped, as the SI brochure and most style guides allow).  Machine-readable
numbers (JSON values) are not formatted here: see ``furncheck.report.numbers``.

Only the standard library is used, so every layer (geometry, statics, validity, loader,
reports) can import it.
"""

from __future__ import annotations

import math
from decimal import ROUND_HALF_UP, Decimal

MESSAGE_SIGNIFICANT_DIGITS = 4
"""Significant digits of a force or length in a message (919.2 N, 11,210 N, 4 mm)."""

GROUP_FROM_DIGITS = 5
"""Integer parts with at least this many digits are grouped in threes by commas."""

READ_DIGITS = 12
"""Significant digits a float is read to before ``plain_number`` rounds it (at least; more
where more are asked for, up to FLOAT_DIGITS): its binary round-off beyond them is
noise.  The same allowance computed twice, 894 mm / 400, came out 2.2350000000000003 in
a violation and 2.2349999999999994 in the suggestion's explanation, read 2.24 and 2.23
mm; read as 2.235 first, both round half up to 2.24, as a reader rounds 2.235."""

FLOAT_DIGITS = 17
"""The most significant digits ``plain_number`` writes: a float has no more."""

PLAIN_RANGE = (1e-9, 1e15)
"""Sizes written out positionally; beyond them (a 1e308 capacity in a bad file) a number
is written as ``1.2e+308``: positional it would run to hundreds of digits."""


def plain_number(value: float, digits: int = MESSAGE_SIGNIFICANT_DIGITS) -> str:
    """``value`` rounded to ``digits`` significant digits, in plain positional notation:
    half up, from the decimal it reads as to READ_DIGITS digits (2.235 reads 2.24, as a
    person rounds it, where its float, 2.23499999999999988..., would round down); at
    most FLOAT_DIGITS digits.

    >>> plain_number(1.121e4), plain_number(919.234), plain_number(0.000123)
    ('11,210', '919.2', '0.000123')
    >>> plain_number(-11213.7), plain_number(1e6), plain_number(-0.0)
    ('-11,210', '1,000,000', '0')

    Non-finite values are written as Python writes them (``inf``, ``nan``); sizes outside
    ``PLAIN_RANGE`` in exponent notation (``plain_number(1e308)`` is ``'1e+308'``).
    """
    value = float(value)
    if not math.isfinite(value):
        return str(value)
    if value == 0.0:
        return "0"
    if not PLAIN_RANGE[0] <= abs(value) < PLAIN_RANGE[1]:
        mantissa, exponent = f"{value:.{max(digits, 1) - 1}e}".split("e")
        if "." in mantissa:
            mantissa = mantissa.rstrip("0").rstrip(".")
        return f"{mantissa}e{int(exponent):+d}"
    digits = min(max(digits, 1), FLOAT_DIGITS)
    read = Decimal(f"{value:.{max(READ_DIGITS, digits) - 1}e}")
    place = Decimal(1).scaleb(read.adjusted() - digits + 1)
    rounded = read.quantize(place, rounding=ROUND_HALF_UP).normalize()
    text = format(rounded, "f")
    whole = text.lstrip("-").split(".", 1)[0]
    return format(rounded, ",f") if len(whole) >= GROUP_FROM_DIGITS else text


COMPARED_MAX_DIGITS = 8
"""``plain_compared`` shows at most this many significant digits."""


def distinguishing_digits(value: float, limit: float,
                          digits: int = MESSAGE_SIGNIFICANT_DIGITS) -> int:
    """The significant digits, from ``digits`` up to ``COMPARED_MAX_DIGITS``, at which
    ``plain_number`` writes two different numbers differently: a sag of 1.2075 mm against
    1.205 mm allowed needs 4 (``1.208`` against ``1.205``; with 3 both read ``1.21``)."""
    value, limit = float(value), float(limit)
    while (value != limit and digits < COMPARED_MAX_DIGITS
           and plain_number(value, digits) == plain_number(limit, digits)):
        digits += 1
    return digits


def plain_compared(value: float, limit: float,
                   digits: int = MESSAGE_SIGNIFICANT_DIGITS) -> tuple[str, str]:
    """``value`` and the ``limit`` it is compared with, each ``plain_number`` with the
    ``distinguishing_digits`` of the two: ``('1.208', '1.205')``, ``('754.7', '700')``."""
    digits = distinguishing_digits(value, limit, digits)
    return plain_number(value, digits), plain_number(limit, digits)


def closest(name: str, choices) -> str | None:
    """The closest of ``choices`` to a misspelt ``name``, or None (difflib is imported for
    the messages only: a file without mistakes never needs it)."""
    import difflib

    close = difflib.get_close_matches(name, list(choices), n=1)
    return close[0] if close else None


def article(number: str) -> str:
    """'a' or 'an' before a number as written (``plain_number``), as it is read aloud: an
    8, an 80, an 860 (eight...), an 11 and an 18 (eleven, eighteen), an 11,500 (eleven
    thousand...); a 1,860 (one thousand...), a 118, a 0.8, a -8 (minus...); an 8e+15 and
    an inf (infinite), as ``plain_number`` writes those beyond its plain range."""
    if number == "inf":
        return "an"
    whole = number.split("e")[0].split(".")[0].replace(",", "")
    if not whole.isdigit():
        return "a"
    lead = whole[:len(whole) % 3 or 3]          # the digits read before "thousand"...
    return "an" if lead.startswith("8") or lead in ("11", "18") else "a"


def plain_list(items) -> str:
    """Words of a list for messages: 'a', 'a and b', 'a, b and c'."""
    items = list(items)
    return items[0] if len(items) == 1 else f"{', '.join(items[:-1])} and {items[-1]}"


def plain_length(value_m: float, scale: float, unit: str,
                 digits: int = MESSAGE_SIGNIFICANT_DIGITS) -> str:
    """A length given in metres, in the design's unit (``scale`` m per unit): ``'4 mm'``."""
    return f"{plain_number(value_m / scale, digits)} {unit}"


def plain_load(mass: float | None, force) -> str:
    """A load as a message names it: its mass when the file gave one (``80 kg``), else
    the size of its force (``100 N``)."""
    if mass is not None:
        return f"{plain_number(mass)} kg"
    return f"{plain_number(math.hypot(*(float(v) for v in force)))} N"
