"""The root-finding pieces of the range search (``furncheck.ranges.estimates``), on
functions and catalog edits whose answers are known exactly."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from furncheck import tolerances as tol
from furncheck.design import load_design
from furncheck.dofs import parse_dof
from furncheck.ranges import RangeFinder
from furncheck.ranges.estimates import (
    MODEL_GRID,
    _Drop,
    _flip_values,
    _margin_zero,
    _may_reach_zero,
    _modelled_flip,
    _open_groups,
    _Probe,
)
from furncheck.tolerances import NAIL_COUNT_EPS

DESIGNS = Path(__file__).resolve().parent.parent / "designs"


def probe(step: float, margin: float) -> _Probe:
    return _Probe(step, margin > 0.0, margin, None, None)


def test_margin_zero_is_exact_for_a_margin_quadratic_in_its_inverse():
    """Inverse quadratic interpolation: if the step is a quadratic in the margin,
    s(m) = 10 - 40 m + 30 m^2, three probes give its zero s(0) = 10 exactly."""
    def step_of(m):
        return 10.0 - 40.0 * m + 30.0 * m * m

    good, bad, other = probe(step_of(0.2), 0.2), probe(step_of(-0.1), -0.1), \
        probe(step_of(0.5), 0.5)
    assert _margin_zero(good, bad, [other, good, bad]) == pytest.approx(10.0, abs=1e-12)


def test_margin_zero_falls_back_to_the_secant_between_the_bracket():
    """With no third probe: the secant through (0, 0.3) and (3, -0.3) crosses at 1.5."""
    good, bad = probe(0.0, 0.3), probe(3.0, -0.3)
    assert _margin_zero(good, bad, [good, bad]) == pytest.approx(1.5, abs=1e-12)


def test_modelled_flip_finds_the_zero_of_a_quadratic_margin():
    """Required margins 1 - t^2 / 64 (zero at t = 8) and 2 - t / 5 (zero at 10): the
    model through three samples is exact, and the first flip is t = 8 to the second
    scan's step, (high - low) / MODEL_GRID^2."""
    def margins(t):
        return np.array([1.0 - t * t / 64.0, 2.0 - t / 5.0]), np.ones((1, 3))

    samples = [(t, _flip_values(_open_groups(margins(0.0)), margins(t))) for t in (0.0, 0.025, 5.0)]
    found = _modelled_flip(samples, 0.0, 15.0)
    assert 8.0 <= found <= 8.0 + 15.0 / MODEL_GRID ** 2


def test_modelled_flip_sees_a_forbidden_group_close():
    """A forbidden group (t - 3, 2, 9 - t) is all positive for 3 < t < 9: it closes at
    t = 3 (its smallest margin, t - 3 at the samples, is what is modelled); a required
    margin that stays positive does not flip."""
    def margins(t):
        return np.array([5.0]), np.array([[t - 3.0, 2.0, 9.0 - t]])

    samples = [(t, _flip_values(_open_groups(margins(0.0)), margins(t))) for t in (0.0, 0.025, 4.5)]
    found = _modelled_flip(samples, 0.0, 15.0)
    assert 3.0 <= found <= 3.0 + 15.0 / MODEL_GRID ** 2


def _scanned_flip(samples: list, low: float, high: float) -> float:
    """``_modelled_flip`` as it was before margins that cannot reach zero were left out:
    every modelled margin scanned on both grids."""
    turns = np.array([turn for turn, _ in samples])
    values = np.stack([values for _, values in samples])
    coefficients = np.linalg.solve(np.vander(turns - turns[0], 3, increasing=True), values)
    for _ in range(2):
        grid = np.linspace(low, high, MODEL_GRID + 1)[1:]
        flipped = ((np.vander(grid - turns[0], 3, increasing=True) @ coefficients)
                   <= 0.0).any(axis=1)
        if not flipped.any():
            return high
        first = int(np.argmax(flipped))
        low, high = (grid[first - 1] if first else low), grid[first]
    return float(high)


_COEFFICIENT = st.floats(-10.0, 10.0, allow_nan=False)


@settings(max_examples=200, deadline=None, derandomize=True)
@given(st.lists(st.tuples(_COEFFICIENT, _COEFFICIENT, _COEFFICIENT), min_size=1, max_size=40),
       st.floats(0.0, 5.0), st.floats(0.1, 20.0))
def test_margins_left_out_of_a_turn_scan_never_flip(margins, low, width):
    """Leaving out the margins whose least value on the interval is positive
    (``_may_reach_zero``) changes no modelled flip: a quadratic a + b t + c t^2 kept out
    is above zero at every scanned turn, and the scan finds the same first flip as one
    over all margins.  Samples at t = 0, 0.025 and 2 of random quadratics."""
    coefficients = np.array(margins, dtype=float).T                     # (3, M)
    high = low + width
    kept = _may_reach_zero(coefficients, low, high)
    grid = np.linspace(low, high, 4097)
    values = np.vander(grid, 3, increasing=True) @ coefficients
    assert not (values[:, ~kept] <= 0.0).any()
    samples = [(t, np.vander(np.array([t]), 3, increasing=True)[0] @ coefficients)
               for t in (0.0, 0.025, 2.0)]
    assert _modelled_flip(samples, low, high) == _scanned_flip(samples, low, high)


def test_modelled_flip_returns_high_when_nothing_flips():
    def margins(t):
        return np.array([1.0 + t]), np.zeros((0, 3))

    samples = [(t, _flip_values(_open_groups(margins(0.0)), margins(t))) for t in (0.0, 0.025, 4.0)]
    assert _modelled_flip(samples, 0.0, 15.0) == 15.0


def _turn_for_kick_joint_length(length_mm: float) -> float:
    """Degrees of side_r.rx at which the cabinet's side_r/kick joint is ``length_mm`` long
    (see the test below), by bisection of L(theta) = (200 - 188 cos theta) / sin theta
    - 420, which falls from 80 mm at 1.375 degrees to 0 at about 1.64."""
    low, high = math.radians(1.0), math.radians(2.0)
    for _ in range(80):
        middle = 0.5 * (low + high)
        length = (200.0 - 188.0 * math.cos(middle)) / math.sin(middle) - 420.0
        low, high = (middle, high) if length > length_mm else (low, middle)
    return math.degrees(0.5 * (low + high))


def test_drop_step_is_where_the_joint_loses_its_nail(monkeypatch):
    """Turning the cabinet's right side about x shortens its joint with the kick board.
    side_r stands at x = 588..600 mm (y -200..200, z 0..1000, centre (y, z) = (0, 500));
    the kick's end face lies on its inner face x = 588, at y -200..-188 (the kick's 12 mm)
    and z 0..80, so the joint is 80 mm long along z (4 nails at 20 mm).  Turning side_r by
    theta about x keeps that face's plane; its front edge becomes the line
    y cos theta + (z - 500) sin theta = -200, and the kick's face is covered where
    -188 cos theta + (z - 500) sin theta >= -200, i.e. above
    z = 500 - (200 - 188 cos theta) / sin theta: the joint's length is
    L(theta) = (200 - 188 cos theta) / sin theta - 420 mm once that is below 80.
    Probes at L = 70 mm (3 nails) and L = 30 mm (1 nail), turns from L(theta) by
    bisection, bracket the loss of the nail that takes the joint below 2 nails, at
    L = 40 mm: the step found from the joint's followed length lies within a tenth of
    the resolution (0.1 degree) of that turn, and the nail count changes there.  (The
    band of the kick's end that the turned side still covers narrows with the joint, a
    sliver at these turns: the bearing rule, ``tolerances.MIN_BEARING_SHARE``, which
    would drop the joint first, is off here, so the nail count's own step is tested.)"""
    monkeypatch.setattr(tol, "MIN_BEARING_SHARE", 0.0)
    design = load_design(str(DESIGNS / "cabinet-28.yaml"))
    finder = RangeFinder(design)
    dof = parse_dof(design, "side_r.rx")
    resolution = finder._scales(dof)[1]
    good, bad = (finder._now(finder._probe(dof, 1.0, _turn_for_kick_joint_length(length)),
                             dof) for length in (70.0, 30.0))
    key = ("side_r", "kick", next(j.edge_face for j in finder.geometry.joints
                                  if (j.face, j.edge) == ("side_r", "kick")))
    spacing = design.material.nail_spacing

    def joint_of(geometry):
        return next(j for j in geometry.joints if (j.face, j.edge, j.edge_face) == key)

    def nails(step):
        return joint_of(finder._now(finder._probe(dof, 1.0, step), dof).geometry).nails

    assert joint_of(finder.geometry).nails == 4                     # 80 mm at 20 mm
    assert joint_of(good.geometry).length == pytest.approx(0.070, abs=1e-9)
    assert joint_of(bad.geometry).length == pytest.approx(0.030, abs=1e-9)
    assert (nails(good.step), nails(bad.step)) == (3, 1)
    length = (nails(bad.step) + 1) * spacing / (1.0 + NAIL_COUNT_EPS)
    drop = finder._drop_step(dof, 1.0, good, bad, _Drop(good.step, key, length,
                                                         joint_of(good.geometry).length,
                                                         joint_of(bad.geometry).length),
                             resolution)
    assert good.step < drop < bad.step
    assert drop == pytest.approx(_turn_for_kick_joint_length(40.0), abs=0.1 * resolution)
    assert nails(drop - 0.1 * resolution) > nails(drop + 0.1 * resolution)
