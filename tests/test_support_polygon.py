"""The support polygon (``geometry.support``): the hull of the floor contacts and how far a
point lies outside it, shared by the toppling fixes (``discrete.feet``), the hand
estimates of what a toppling design needs (``needs``) and the legs drawn short that
``suggest.margins`` brings down to the floor."""

from __future__ import annotations

import numpy as np
import pytest

from furncheck.geometry.support import convex_hull, outside


def test_hull_of_a_square_with_inner_and_repeated_points():
    """The four corners of a 2 x 1 rectangle, counter-clockwise from the lowest x (then
    y); the centre and a corner repeated within 1e-12 m are not hull points."""
    points = [(2.0, 1.0), (1.0, 0.5), (0.0, 0.0), (2.0, 0.0), (0.0, 1.0), (2.0, 1.0 + 1e-12)]
    assert convex_hull(points) == [2, 3, 0, 4]


def test_hull_of_points_on_a_line_or_at_one_point():
    """A design standing on an edge (points on a line) gives the line's two ends; on one
    point (repeated), that point."""
    assert convex_hull([(0.0, 0.0), (0.3, 0.0), (0.1, 0.0), (0.2, 0.0)]) == [0, 1]
    assert convex_hull([(0.5, 0.5), (0.5, 0.5)]) == [0]


def test_outside_distances_are_those_to_the_nearest_edge_or_corner():
    """Unit square: a point inside is 0 away (itself the nearest); (1.5, 0.5) is 0.5 from
    the edge x = 1 at (1, 0.5); (2, 2) is sqrt 2 from the corner (1, 1); from a hull of two
    points (a line), the distance to the segment, 0 on it."""
    square = np.array([(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)])
    distance, nearest = outside(square, np.array([0.25, 0.75]))
    assert distance == 0.0 and tuple(nearest) == (0.25, 0.75)
    distance, nearest = outside(square, np.array([1.5, 0.5]))
    assert distance == pytest.approx(0.5) and tuple(nearest) == pytest.approx((1.0, 0.5))
    distance, nearest = outside(square, np.array([2.0, 2.0]))
    assert distance == pytest.approx(2 ** 0.5) and tuple(nearest) == pytest.approx((1.0, 1.0))
    line = np.array([(0.0, 0.0), (1.0, 0.0)])
    assert outside(line, np.array([0.5, 0.2]))[0] == pytest.approx(0.2)
    assert outside(line, np.array([0.5, 0.0]))[0] == 0.0
