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
from decimal import Decimal

MESSAGE_SIGNIFICANT_DIGITS = 4
"""Significant digits of a force or length in a message (919.2 N, 11,210 N, 4 mm)."""

GROUP_FROM_DIGITS = 5
"""Integer parts with at least this many digits are grouped in threes by commas."""


def plain_number(value: float, digits: int = MESSAGE_SIGNIFICANT_DIGITS) -> str:
    """``value`` rounded to ``digits`` significant digits, in plain positional notation.

    >>> plain_number(1.121e4), plain_number(919.234), plain_number(0.000123)
    ('11,210', '919.2', '0.000123')
    >>> plain_number(-11213.7), plain_number(1e6), plain_number(-0.0)
    ('-11,210', '1,000,000', '0')

    Non-finite values are written as Python writes them (``inf``, ``nan``).
    """
    value = float(value)
    if not math.isfinite(value):
        return str(value)
    if value == 0.0:
        return "0"
    rounded = Decimal(f"{value:.{max(digits, 1) - 1}e}").normalize()
    text = format(rounded, "f")
    whole = text.lstrip("-").split(".", 1)[0]
    return format(rounded, ",f") if len(whole) >= GROUP_FROM_DIGITS else text


def plain_length(value_m: float, scale: float, unit: str,
                 digits: int = MESSAGE_SIGNIFICANT_DIGITS) -> str:
    """A length given in metres, in the design's unit (``scale`` m per unit): ``'4 mm'``."""
    return f"{plain_number(value_m / scale, digits)} {unit}"
