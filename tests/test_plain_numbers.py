"""Numbers in human messages are plain (issue 14): ``11,210 N``, never ``1.121e+04 N``."""

import math
from pathlib import Path

import pytest
from shop_designs import SIDE_TABLE_RACK

from furncheck.plain import (
    GROUP_FROM_DIGITS,
    article,
    distinguishing_digits,
    plain_compared,
    plain_length,
    plain_number,
)
from furncheck.report.numbers import format_number, format_percent

CATALOG = Path(__file__).resolve().parents[1] / "designs"


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


@pytest.mark.parametrize(("number", "word"), [
    ("860", "an"), ("8", "an"), ("80", "an"), ("8.5", "an"), ("8000", "an"),
    ("800,000", "an"), ("11", "an"), ("18", "an"), ("11,500", "an"), ("18,000", "an"),
    ("1860", "a"), ("1100", "a"), ("118", "a"), ("110", "a"), ("0.8", "a"), ("12", "a"),
    ("1", "a"), ("-8", "a"), ("388", "a"), ("8e+15", "an"), ("1.2e+16", "a"), ("inf", "an"),
])
def test_the_article_before_a_number_is_as_the_number_is_read(number, word):
    """'an 860 mm span' (eight hundred...), 'a 1860 mm span' (one thousand...): the
    article follows the number's first spoken word (the newcomer's 'a 860 mm span')."""
    assert article(number) == word


def test_plain_length_is_in_the_design_unit():
    assert plain_length(0.004, 0.001, "mm") == "4 mm"
    assert plain_length(11.21, 0.001, "mm") == "11,210 mm"
    assert plain_length(0.004, 1.0, "m") == "0.004 m"


def test_report_helpers_use_plain_numbers():
    assert format_number(1.25e6) == "1,250,000"            # :.6g wrote 1.25e+06
    assert format_number(0.00001234) == "0.00001234"        # as a message writes it
    assert format_number(-3e-14) == "0"                     # a solver's round-off
    assert format_percent(112.1) == "11,210 %"
    assert format_percent(0.42) == "42 %"


def test_sizes_beyond_the_plain_range_use_an_exponent():
    """A 1e308 capacity in a bad file must not print three hundred digits."""
    assert plain_number(1e308) == "1e+308"
    assert plain_number(1.23456e20, 6) == "1.23456e+20"
    assert plain_number(-3e-12) == "-3e-12"
    assert plain_number(1.5e-9) == "0.0000000015"


@pytest.mark.parametrize(("value", "limit", "digits", "shown", "used"), [
    (1.2075, 1.205, 3, ("1.208", "1.205"), 4),     # 1.21 against 1.21 at three digits
    (754.7, 700.0, 4, ("754.7", "700"), 4),        # different already: as plain_number
    (700.04, 700.0, 4, ("700.04", "700"), 5),
    (1.0 + 1e-12, 1.0, 4, ("1", "1"), 8),          # beyond the most shown: left alike
    (5.0, 5.0, 3, ("5", "5"), 3),
])
def test_compared_numbers_read_differently_when_they_differ(value, limit, digits, shown,
                                                            used):
    """A value and the limit it is compared with get the fewest digits (from ``digits``)
    at which they read differently, so a message never says '1.21 mm ... allowed 1.21
    mm' for a sag over its allowance; equal numbers keep ``digits``, numbers closer than
    COMPARED_MAX_DIGITS (8) tell apart read alike at 8."""
    assert plain_compared(value, limit, digits) == shown
    assert distinguishing_digits(value, limit, digits) == used




def test_a_sag_just_over_its_allowance_reads_over_it(tmp_path):
    """The side table's top (``shop_designs``) sags w (1 + creep) just past span / 400
    (1.2075 against 1.205 mm) in its default case: the violation and the explanation show
    both with the digits that tell them apart, and the thickness the explanation estimates
    (t (ratio)^(1/3)) above 18 mm."""
    import re

    from furncheck.check import check_file
    from furncheck.design.load import load_design
    from furncheck.report.explanation import need_text
    from furncheck.suggest import suggest_design

    path = tmp_path / "side-table.yaml"
    path.write_text(SIDE_TABLE_RACK)
    (violation,) = [v for v in check_file(path).violations
                    if (v.kind, v.where, v.case) == ("sagging", "top", "default")]
    crept, allowed = re.search(r"([\d.]+) mm with creep .*allowed ([\d.]+) mm",
                               violation.message).groups()
    assert plain_number(float(crept), 3) == plain_number(float(allowed), 3)   # the case
    assert float(crept) > float(allowed)
    explanation = suggest_design(load_design(path)).explanation
    (need,) = [n for n in explanation.needs if (n.kind, n.where) == ("sagging", "top")]
    text = need_text(need, "mm")
    crept, allowed = re.search(r"sags ([\d.]+) mm with creep .* against ([\d.]+) mm",
                               text).groups()
    assert float(crept) > float(allowed)
    ratio, needed = re.search(r"\(([\d.]+)\)\^\(1/3\) = ([\d.]+) mm", text).groups()
    assert float(ratio) > 1.0 and float(needed) > 18.0


@pytest.mark.parametrize(("value", "digits", "text"), [
    (2.235, 3, "2.24"),                 # its float is 2.23499999999999988...
    (2.2349999999999994, 3, "2.24"),    # 894 mm / 400, computed one way
    (2.2350000000000003, 3, "2.24"),    # ... and the other
    (1.095, 3, "1.1"),                  # 438 mm / 400
    (6.125, 3, "6.13"),                 # 2450 mm / 400 (exact in binary: half up)
    (2.5, 1, "3"),
    (-2.235, 3, "-2.24"),               # half away from zero
    (2.2345, 3, "2.23"),                # below the half: down
    (2.2349996, 3, "2.23"),             # near the tie, either side: each path alike
    (2.2350004, 3, "2.24"),
    (123456789012345.0, 15, "123,456,789,012,345"),    # more digits asked: read to them
])
def test_ties_round_half_up_from_the_decimal_a_number_reads_as(value, digits, text):
    """A reader rounds the decimal a report shows (the JSON's 2.235) half up, so the
    messages do too, whichever side of it the float's round-off fell: the same allowance
    read 'allowed 2.24 mm' in a violation and '2.23 mm allowed' in the suggestion's
    explanation of it before."""
    assert plain_number(value, digits) == text
    assert format_number(value, digits) == text


def test_percent_ties_round_half_up_and_round_off_reads_zero():
    """Whole percents round a tie half up as every number in a message does (12.5 % and
    14.5 % read 13 % and 15 %; Python's round() gave 12 % and 14 %); a utilization of
    round-off reads 0 %; 40 digits asked for are the float's 17."""
    assert format_percent(0.125) == "13 %"
    assert format_percent(0.145) == "15 %"
    assert format_percent(0.00145) == "0.15 %"
    assert format_percent(1e-20) == "0 %"
    assert plain_number(1.0 / 3.0, 40) == "0.33333333333333331"


def test_a_violation_and_its_explanation_give_the_same_allowance():
    """particleboard-shelf-overloaded's sides bow between supports 894 mm apart: allowed
    894 / 400 = 2.235 mm, 2.24 mm to three digits in both the violation and the
    suggestion's explanation of it (the two came from floats either side of 2.235)."""
    from furncheck.check import check_design
    from furncheck.design import load_design
    from furncheck.design.model import with_model
    from furncheck.geometry import analyze
    from furncheck.report.explanation import need_text
    from furncheck.suggest.needs import violation_needs

    design = with_model(load_design(CATALOG / "particleboard-shelf-overloaded.yaml"),
                        "elastic")
    geometry = analyze(design)
    report = check_design(design, geometry)
    sides = [v.message for v in report.violations
             if v.kind == "sagging" and v.where in ("side_l", "side_r")]
    assert len(sides) == 2 and all("894 mm apart" in m and "allowed 2.24 mm (span / 400)"
                                   in m for m in sides)
    texts = [need_text(n, "mm") for n in violation_needs(design, geometry, report)
             if n.kind == "sagging" and n.where in ("side_l", "side_r")]
    assert len(texts) == 2 and all("against 2.24 mm allowed" in t for t in texts)
