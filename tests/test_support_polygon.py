"""The support polygon (``geometry.support``): the hull of the floor contacts and how far a
point lies outside it, shared by the toppling fixes (``discrete.feet``), the hand
estimates of what a toppling design needs (``needs``) and the legs drawn short that
``suggest.margins`` brings down to the floor."""

from __future__ import annotations

import numpy as np
import pytest

from furncheck.geometry.support import convex_hull, hold_down_ratios, outside


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


SAWHORSE = """
furncheck: 1
name: sawhorse
planks:
  - {id: beam, size: [1000, 90], center: [0, 0, 706]}
  - {id: leg_l, size: [700, 400], center: [-400, 0, 350], rotation: [0, -90, 0]}
  - {id: leg_r, size: [700, 400], center: [400, 0, 350], rotation: [0, -90, 0]}
loads:
  - {plank: beam, mass: 20, at: [0, 0, 712]}
  - {plank: beam, force: [0, 73.3697, 0], at: [0, 0, 712]}
"""


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_a_toppling_design_names_the_least_pull_that_holds_it(model):
    """A sawhorse (a 1000 x 90 x 12 mm beam on two 700 x 400 legs standing on their 12 mm
    edges at x = +-400 mm, so its feet span y = +-200 mm) with 20 kg on the beam, pushed
    along +y with P = 73.3697 N at 712 mm, 3 % past its tipping push.  V = 20 g + the
    beam's 7.946 N + the legs' 2 x 24.72 N = 253.59 N; about the feet's +y edge the push
    turns it over with P h = 52.239 N m against V x 200 mm = 50.718 N m, so a pull at the
    feet's far edge, a = 400 mm away, holds it with (P h - V b) / a = 3.804 N: what the
    message names, in both models.  (The elastic model's bolted corners pull 901.9 N in
    all: each 12 mm foot carries its leg's bending as a pair of opposite forces.)"""
    from furncheck.check import check_design
    from furncheck.design import parse_design
    from furncheck.design.model import with_model

    design = with_model(parse_design(SAWHORSE, "sawhorse.yaml", "yaml"), model)
    g, density = 9.81, 750.0
    weight = 20 * g + density * 1.0 * 0.09 * 0.012 * g + 2 * density * 0.7 * 0.4 * 0.012 * g
    least = (73.3697 * 0.712 - weight * 0.200) / 0.400
    assert least == pytest.approx(3.804, abs=1e-3)
    (violation,) = check_design(design).violations
    assert violation.kind == "lift-off"
    assert f"held down at leg_l or leg_r, the ground would have to pull at least " \
           f"{least:.4g} N there" in violation.message
    # what falls outside is the line of action of the weight and the loads together (a
    # designer read 'the load's' of a load inside the polygon)
    assert "the line of action of its weight and loads together falls outside the " \
           "support polygon" in violation.message


LOOSE_TOP = """
furncheck: 1
name: loose-top
planks:
  - {id: side_l, size: [400, 300], center: [-294, 0, 200], rotation: [0, -90, 0]}
  - {id: side_r, size: [400, 300], center: [294, 0, 200], rotation: [0, -90, 0]}
  - {id: bottom, size: [576, 300], center: [0, 0, 50]}
  - {id: top, size: [600, 300], center: [0, 0, 406]}
joints:
  - [side_l, bottom]
  - [side_r, bottom]
  - {planks: [top, side_l], type: rests}
  - {planks: [top, side_r], type: rests}
loads:
  - {plank: top, mass: 15}
  - {plank: top, force: [0, 78, 0], at: [0, 150, 406]}
"""


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_a_frame_under_a_loose_top_topples_as_a_whole(model):
    """A frame (two 400 x 300 sides nailed to a bottom) under a loose 600 x 300 top (type:
    rests) with 15 kg on it, pushed along +y at the top's front edge, 406 mm up, with
    78 N.  V = 15 g + the planks' 5.3352 kg g = 199.49 N; about the feet's +y edge
    (y = 150 mm) the push turns it over with F h = 31.668 N m against V x 150 mm =
    29.92 N m, so the whole unit topples and a pull at the feet's far edge, a = 300 mm
    away, holds it with (F h - V b) / a = 5.816 N.  The top does not lift off its sides
    (the push acts 6 mm above its bearing, against its 15 kg): the message names the
    whole unit's toppling and that pull, in both models; the elastic model's bolted
    resting corners pulled 956 N in all, and the message used to name the top lifting
    off its sides with that."""
    from furncheck.check import check_design
    from furncheck.design import parse_design
    from furncheck.design.model import with_model

    design = with_model(parse_design(LOOSE_TOP, "loose-top.yaml", "yaml"), model)
    g, density, t = 9.81, 750.0, 0.012
    planks = density * t * (2 * 0.4 * 0.3 + 0.576 * 0.3 + 0.6 * 0.3)
    weight = (15 + planks) * g
    least = (78 * 0.406 - weight * 0.150) / 0.300
    assert least == pytest.approx(5.816, abs=1e-3)
    lift = [v for v in check_design(design).violations if v.kind == "lift-off"]
    assert len(lift) == 1
    assert "lifts off" not in lift[0].message
    assert f"the design topples (held down at side_l or side_r, the ground would have to " \
           f"pull at least {least:.4g} N there)" in lift[0].message


def test_the_least_hold_down_beyond_an_edge_and_beyond_a_corner():
    """Unit square, the loads' resultant V meeting the floor at c.  Beyond the edge x = 1
    (c = (1.5, 0.5), d = 0.5): a pull at a point of the far edge, a = 1 inside, holds it
    with V d / a = 0.5 V; at the near edge's points no pull does.  Beyond the corner (1, 1)
    (c = (1.5, 1.2)): a pull P at (0, 0) must hold it about both edges by the corner,
    x = 1 (V 0.5 = P 1) and y = 1 (V 0.2 = P 1): 0.5 V, where the one line through the
    corner normal to c's offset from it read 0.415 V (d = 0.539, a = 1.299), too little;
    at the other points none holds (the segment to them never crosses back over x = 1
    or y = 1).  On a line, no ratio."""
    square = np.array([(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)])
    edge = hold_down_ratios(square, np.array([1.5, 0.5]))
    assert edge[0] == pytest.approx(0.5) and edge[3] == pytest.approx(0.5)
    assert np.isinf(edge[1]) and np.isinf(edge[2])
    corner = hold_down_ratios(square, np.array([1.5, 1.2]))
    assert corner[0] == pytest.approx(0.5) and np.isinf(corner[1:]).all()
    assert hold_down_ratios(square[:2], np.array([0.5, 0.5])) is None
