"""Numbers in reports: rounded once, the same way, by every reporter.

Reports promise byte-identical output for the same input (contract section 4), so floats
are rounded to ``REPORT_SIGNIFICANT_DIGITS`` significant digits before they are written:
the last bits of a linear solve never leak into a report.  ``-0.0`` is written as ``0.0``.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping
from typing import Any

from furncheck.files import readable
from furncheck.plain import plain_number
from furncheck.tolerances import REPORT_DECIMALS, REPORT_SIGNIFICANT_DIGITS


def round_significant(value: float, digits: int = REPORT_SIGNIFICANT_DIGITS) -> float:
    """``value`` rounded to ``REPORT_DECIMALS`` decimals, then to ``digits`` significant
    digits, with -0.0 turned into 0.0.

    Non-finite values (nan, inf) are returned unchanged.
    """
    value = float(value)
    if not math.isfinite(value):
        return value
    value = round(value, REPORT_DECIMALS)      # solver round-off (1e-14 mm, 1e-16 N) -> 0
    return float(f"{value:.{digits}g}") + 0.0  # + 0.0 turns -0.0 into 0.0


_ROUNDED = f"%.{REPORT_SIGNIFICANT_DIGITS}g"


def real_text(value: float) -> str:
    """``json.dumps(json_ready(value))`` of a float, the same steps as ``round_significant``
    written out for the JSON writer (it runs for every number of every report): the
    rounded value's ``repr``, or null when it is not finite."""
    if value - value != 0.0:                    # nan or inf
        return "null"
    return float.__repr__(float(_ROUNDED % round(value, REPORT_DECIMALS)) + 0.0)


def json_ready(value: Any) -> Any:
    """A copy of ``value`` that ``json.dumps`` writes deterministically.

    Floats are rounded (``round_significant``); non-finite floats become None (JSON has no
    nan/inf); ints and bools stay as they are; strings are ``readable``; tuples become
    lists; mappings keep their key order.  numpy scalars and arrays are accepted through
    their ``item``/``tolist`` methods, so this module never imports numpy.
    """
    if isinstance(value, str):
        return readable(value)
    if value is None or isinstance(value, bool):
        return value
    if isinstance(value, numbers.Integral):
        return int(value)
    if isinstance(value, numbers.Real):
        rounded = round_significant(float(value))
        return rounded if math.isfinite(rounded) else None
    if isinstance(value, Mapping):
        return {str(key): json_ready(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_ready(item) for item in value]
    if hasattr(value, "tolist"):  # numpy array or scalar
        return json_ready(value.tolist())
    raise TypeError(f"cannot write a {type(value).__name__} into a report")


def format_number(value: float, digits: int = REPORT_SIGNIFICANT_DIGITS) -> str:
    """``value`` for human eyes, as every message writes it (``furncheck.plain.
    plain_number``: ``digits`` significant digits, a tie half up from the decimal it reads
    as, plain digits without trailing zeros: ``812``, ``0.125``, ``12,500``), so that a
    report's text and a violation's message write one number alike (894 mm / 400 reads
    2.24 in both); 0 where the JSON report rounds it to 0 (REPORT_DECIMALS: a solver's
    round-off)."""
    value = float(value)
    if not math.isfinite(value):
        return str(value)
    if round(value, REPORT_DECIMALS) == 0.0:
        return "0"
    return plain_number(value, digits)


def format_percent(fraction: float) -> str:
    """A utilization (1.0 = at capacity) as a percentage: ``'42 %'``, ``'0.35 %'``.

    Whole percents from 1 % up (the capacity check itself is exact; this is for reading);
    two significant digits below, so a lightly loaded joint does not read as 0 %.
    """
    percent = float(fraction) * 100.0
    if not math.isfinite(percent):
        return f"{percent} %"
    if round(percent, REPORT_DECIMALS) == 0.0:     # a solver's round-off
        return "0 %"
    if abs(percent) >= 1.0:                         # whole percents, a tie half up
        return f"{plain_number(percent, len(str(int(abs(percent)))))} %"
    return f"{plain_number(percent, 2)} %"
