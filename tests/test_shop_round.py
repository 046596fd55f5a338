"""Suggested changes rounded to the shop's grid (``suggest.shop_round``)."""

from __future__ import annotations

import pytest

from furncheck.suggest.shop_round import MOST_TRIED, rounded_changes


def test_nearest_whole_millimetre_first_then_away_then_the_half_millimetre():
    """39.71 mm along a direction of rate 1 per step, valid for steps 30..60: 40 first
    (nearest), then 40 again away from zero (dropped: the same), 39 toward zero, then
    the half-millimetre grid's 39.5 (nearest; 40 is tried already)."""
    tried = rounded_changes((39.71,), ("mm",), (1.0,), 30.0, 60.0)
    assert MOST_TRIED == 3 and len(tried) == 3
    assert [changes for _, changes in tried] == [(40.0,), (39.0,), (39.5,)]
    assert [step for step, _ in tried] == [40.0, 39.0, 39.5]


def test_a_mirror_pair_rounds_alike_and_no_change_rounds_to_zero():
    """-1.31 and +1.31 mm (two sides moved closer): 1 mm each, then 2 each; 1.5 each on
    the half-millimetre grid.  0.3 mm never rounds to 0 (that would drop the DOF): 1 mm
    (away from zero), then 0.5 mm."""
    tried = [c for _, c in rounded_changes((-1.31, 1.31), ("mm", "mm"), (-1.0, 1.0),
                                           0.0, 10.0)]
    assert tried == [(-1.0, 1.0), (-2.0, 2.0), (-1.5, 1.5)]
    assert [c for _, c in rounded_changes((0.3,), ("mm",), (1.0,), 0.0, 1.0)] == [(1.0,), (0.5,)]


def test_only_steps_inside_the_valid_interval_are_offered():
    """A change of 2.62 mm valid for steps 2.5..2.8 (rate 1): 3 mm is past the interval,
    2 mm before it; only the half-millimetre 2.5 stays inside."""
    tried = rounded_changes((2.62,), ("mm",), (1.0,), 2.5, 2.8)
    assert [c for _, c in tried] == [(2.5,)]


@pytest.mark.parametrize("unit, change, first", [("deg", -7.55, -7.5), ("m", 0.03971, 0.04)])
def test_degrees_and_metres_have_their_own_grids(unit, change, first):
    """Half degrees (then tenths); whole millimetres in a design in metres."""
    step, changes = rounded_changes((change,), (unit,), (1.0,), -100.0, 100.0)[0]
    assert changes == (pytest.approx(first, abs=1e-12),) and step == changes[0]


def test_changes_on_the_grid_already_are_not_tried_again():
    assert rounded_changes((40.0, -3.0), ("mm", "mm"), (1.0, -0.075), 0.0, 100.0) == []
