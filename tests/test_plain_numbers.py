"""Numbers in human messages are plain (issue 14): ``11,210 N``, never ``1.121e+04 N``."""

import math

import pytest

from furncheck.plain import GROUP_FROM_DIGITS, plain_length, plain_number
from furncheck.report.numbers import format_number, format_percent


@pytest.mark.parametrize(("value", "digits", "text"), [
    (1.121e4, 4, "11,210"),             # the lift-off force
    (11213.7, 4, "11,210"),             # four significant digits, then grouped
    (919.234, 4, "919.2"),              # as :.4g wrote it below 10,000
    (1005.0, 4, "1005"),                # four-digit numbers stay ungrouped
    (9999.5, 4, "10,000"),              # rounding up into the grouped range
    (0.000123, 4, "0.000123"),
    (1.23e-7, 4, "0.000000123"),        # :.4g would write 1.23e-07
    (-11213.7, 4, "-11,210"),
    (-0.5, 4, "-0.5"),
    (1e6, 4, "1,000,000"),
    (12345678.0, 4, "12,350,000"),
    (700.0, 4, "700"),                  # no trailing zeros or point
    (0.125, 6, "0.125"),
    (-0.0, 4, "0"),                     # never "-0"
    (0.0, 4, "0"),
    (2.0e6, 6, "2,000,000"),
])
def test_plain_number(value, digits, text):
    assert plain_number(value, digits) == text


@pytest.mark.parametrize("value", [3.14159, 812.0, 0.0123, 99999.0, 1e-4, 5e6, -42.5, 1.5e-9])
def test_plain_number_reads_back_as_the_rounded_value(value):
    """The text is the value rounded to 4 significant digits (what :.4g keeps), only
    written out: parsing it back gives float(f'{value:.4g}')."""
    text = plain_number(value, 4)
    assert "e" not in text.lower()
    assert float(text.replace(",", "")) == float(f"{value:.4g}")


def test_grouping_starts_at_five_integer_digits():
    assert GROUP_FROM_DIGITS == 5
    assert plain_number(9999.0) == "9999"
    assert plain_number(10000.0) == "10,000"
    assert plain_number(123456.0, 6) == "123,456"


def test_non_finite_values_are_written_as_python_writes_them():
    assert plain_number(math.inf) == "inf"
    assert plain_number(-math.inf) == "-inf"
    assert plain_number(math.nan) == "nan"


def test_plain_length_is_in_the_design_unit():
    assert plain_length(0.004, 0.001, "mm") == "4 mm"
    assert plain_length(11.21, 0.001, "mm") == "11,210 mm"
    assert plain_length(0.004, 1.0, "m") == "0.004 m"


def test_report_helpers_use_plain_numbers():
    assert format_number(1.25e6) == "1,250,000"            # :.6g wrote 1.25e+06
    assert format_number(0.00001234) == "0.000012"          # rounded to 6 decimals first
    assert format_percent(112.1) == "11,210 %"
    assert format_percent(0.42) == "42 %"


def test_sizes_beyond_the_plain_range_use_an_exponent():
    """A 1e308 capacity in a bad file must not print three hundred digits."""
    assert plain_number(1e308) == "1e+308"
    assert plain_number(1.23456e20, 6) == "1.23456e+20"
    assert plain_number(-3e-12) == "-3e-12"
    assert plain_number(1.5e-9) == "0.0000000015"
