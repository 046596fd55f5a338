"""Planks held along their length by the floor or a wall (elastic model,
``statics.stations``): a plank whose corners touch a support at both ends of its beam
gets a contact on each such edge at the nodes between them (a node about every 250 mm,
or every four depths of a plank on edge), and what those contacts carry is reported at
the corners by the lever rule.  Hand checks (12 mm MDF, E = 3000 N/mm^2):

* A 1200 x 300 board lying on the floor, a 1000 N point load at its middle.  Held at its
  corners alone it would span 1200 mm: M = P L / 4 = 300 N m, sigma = 6 M / (w t^2) =
  41.7 N/mm^2, twice its 22 N/mm^2 strength (what furncheck read before).  On the floor
  the load goes into the floor where it acts: no bending worth the name.  The reported
  corner forces balance the load and the board's weight, and their moment about any
  point is the loads' (the lever rule keeps sum and moment): sum F = P + W, and with the
  load at the middle each corner carries (P + W) / 4 by symmetry.
* A low box (an 800 mm bottom on the floor, 300 mm sides nailed on it, a top) with 600 N
  of books spread on its bottom: the bottom, spanning 800 mm between its corners, sagged
  and pulled the sides' feet inwards (they "bowed 0.92 mm sideways"); on the floor the
  bottom does not bend, and the sides stay straight.
* The lever rule itself: a station a quarter of the way from corner a to corner b gives
  3/4 of its force to a and 1/4 to b.
* A 1200 x 80 kick board on its long edge, 500 N on its top edge 300 mm off its middle,
  upright or tilted by 1 and 3 degrees (still on both bottom edges, within the
  tolerance): stations on both edges, a station about every 320 mm (four depths) and
  under the load; it stays straight (on its end corners alone it sagged 8.2 to 9.1 mm,
  and tilted 3 degrees "bowed 18 mm sideways"), and the corners carry the stations' sum
  and moment.  One line of stations midway between the edges, tried, let the tilted
  board roll over that line between its end corners (34 % of its limit at 1 degree,
  sagging at 3).
* Rigid motions and metres change neither the corner forces (turned with the design)
  nor the planks' sag and stress.
"""

from __future__ import annotations

import numpy as np
import pytest

from furncheck.check import check_design
from furncheck.design import parse_design
from furncheck.geometry import analyze
from furncheck.statics import build_model

G = 9.81

BOARD = """furncheck: 1
name: board-on-floor
units: @UNITS
planks:
  - {id: board, size: [@L, @W], center: [@X, @Y, @Z], rotation: [0, 0, @TURN]}
loads:
  - {plank: board, force: [0, 0, -1000], at: [@AX, @AY, @AZ]}
"""

BOX = """furncheck: 1
name: low-box
planks:
  - {id: bottom, size: [800, 300], center: [0, 0, 6]}
  - {id: side_l, size: [300, 300], center: [-406, 0, 150], rotation: [0, -90, 0]}
  - {id: side_r, size: [300, 300], center: [406, 0, 150], rotation: [0, -90, 0]}
  - {id: top, size: [824, 300], center: [0, 0, 306]}
loads:
  - {plank: bottom, force: [0, 0, -600], spread: true}
"""


def _board(turn: float = 0.0, shift=(0.0, 0.0), metres: bool = False, at=(0.0, 0.0)):
    """The module docstring's board, turned by ``turn`` degrees about z and moved by
    ``shift`` mm, its load at ``at`` mm from its middle (turned with it)."""
    scale = 1e-3 if metres else 1.0
    c, s = np.cos(np.radians(turn)), np.sin(np.radians(turn))
    ax, ay = c * at[0] - s * at[1] + shift[0], s * at[0] + c * at[1] + shift[1]
    text = BOARD
    for key, value in (("UNITS", "m" if metres else "mm"), ("TURN", turn), ("AX", ax * scale),
                       ("AY", ay * scale), ("AZ", 12 * scale),
                       ("L", 1200 * scale), ("W", 300 * scale), ("X", shift[0] * scale),
                       ("Y", shift[1] * scale), ("Z", 6 * scale)):
        text = text.replace("@" + key, value if isinstance(value, str) else repr(float(value)))
    return parse_design(text, "board.yaml", "yaml")


def test_a_board_on_the_floor_does_not_bend_under_a_point_load():
    """Module docstring: 41.7 N/mm^2 on its corners alone; on the floor under 0.1 N/mm^2
    (the load passes into the floor under it), the corners' forces (P + W) / 4 each."""
    design = _board()
    model = build_model(design, analyze(design))
    assert model.station_corners is not None and len(model.contacts) > 4
    case = check_design(design).cases[0]
    (board,) = case.planks
    assert board.stress < 0.1                               # N/mm^2, not 41.7
    assert board.sag == pytest.approx(0.0, abs=1e-3)        # mm
    weight = design.plank_mass(design.planks[0]) * G
    assert [c.plank for c in case.contacts] == ["board"] * 4       # its corners alone
    normals = np.array([c.force[2] for c in case.contacts])
    assert normals == pytest.approx(np.full(4, (1000.0 + weight) / 4), rel=1e-6)


@pytest.mark.parametrize("at", [(400.0, 100.0), (-550.0, -120.0)])
def test_the_corners_carry_what_the_floor_does_with_its_sum_and_moment(at):
    """A load off the middle: the reported corner forces sum to the loads and weight, and
    their moment about the origin is the loads' and weight's (to 1e-9 of P x the board's
    size), every normal force >= 0."""
    design = _board(at=at)
    case = check_design(design).cases[0]
    weight = design.plank_mass(design.planks[0]) * G
    points = np.array([c.point for c in case.contacts]) / 1000.0
    forces = np.array([c.force for c in case.contacts])
    assert forces.sum(axis=0) == pytest.approx([0.0, 0.0, 1000.0 + weight], abs=1e-9 * 1000)
    load_point = np.array([at[0], at[1], 12.0]) / 1000.0
    applied = np.cross(load_point, [0.0, 0.0, -1000.0]) \
        + np.cross([0.0, 0.0, 0.006], [0.0, 0.0, -weight])
    assert np.cross(points, forces).sum(axis=0) + applied == pytest.approx(
        np.zeros(3), abs=1e-9 * 1000 * 1.2)
    assert (forces[:, 2] >= -1e-9).all()


def test_a_box_standing_on_its_bottom_keeps_its_sides_straight():
    """Module docstring: the sides bowed 0.92 mm sideways (sagging) while the bottom spanned
    between its corners (it read 5.46 N/mm^2); on the floor they stay straight (under
    0.05 mm), and the bottom's stress is at most that of a simply supported span between
    its stations, a third of its 800 mm: w (L/3)^2 / 8 / (b t^2 / 6) with w = 600 N / 800
    mm, b t^2 / 6 = 300 x 12^2 / 6 = 7200 mm^3: 0.93 N/mm^2."""
    report = check_design(parse_design(BOX, "box.yaml", "yaml"))
    assert report.valid, report.violations
    planks = {p.id: p for p in report.cases[0].planks}
    assert planks["side_l"].sag < 0.05 and planks["side_r"].sag < 0.05
    w, span = 600.0 / 800.0, 800.0 / 3.0
    assert planks["bottom"].stress < w * span ** 2 / 8.0 / (300.0 * 12.0 ** 2 / 6.0)


def test_the_lever_rule_shares_a_station_between_its_corners():
    """``corner_forces``: the first corner rows keep their own forces; a station at
    share t adds (1 - t) of its force to its edge's first corner and t to its second,
    for forces and for rates with leading axes alike."""
    design = _board()
    model = build_model(design, analyze(design))
    n, stations = model.n_corners, len(model.station_corners)
    forces = np.zeros((len(model.contacts), 3))
    forces[n] = [1.0, 2.0, 4.0]
    a, b = model.station_corners[0]
    t = model.station_shares[0]
    lumped = model.corner_forces(forces)
    assert lumped.shape == (n, 3)
    expected = np.zeros((n, 3))
    expected[a] += (1 - t) * forces[n]
    expected[b] += t * forces[n]
    assert lumped == pytest.approx(expected, abs=1e-15)
    rates = np.stack([forces, 2 * forces])
    assert model.corner_forces(rates) == pytest.approx(np.stack([expected, 2 * expected]))
    assert stations == len(model.station_shares) and ((0 <= model.station_shares)
                                                     & (model.station_shares <= 1)).all()


@pytest.mark.parametrize("turn, shift, metres", [(37.0, (250.0, -80.0), False),
                                                 (90.0, (0.0, 0.0), True)])
def test_stations_under_rigid_motion_and_in_metres(turn, shift, metres):
    """The board with its load off the middle, turned and moved, or written in metres:
    the same corner forces (turned with it; N either way), sag and stress."""
    at = (400.0, 100.0)
    base = check_design(_board(at=at)).cases[0]
    moved = check_design(_board(turn, shift, metres, at=at)).cases[0]
    c, s = np.cos(np.radians(turn)), np.sin(np.radians(turn))
    turn_matrix = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    size = 1e-3 if metres else 1.0
    reference = sorted((tuple(np.round(turn_matrix @ np.array(k.point) + [*shift, 0.0], 6)),
                        tuple(turn_matrix @ np.array(k.force))) for k in base.contacts)
    found = sorted((tuple(np.round(np.array(k.point) / size, 6)), tuple(k.force))
                   for k in moved.contacts)
    for (point, force), (point2, force2) in zip(reference, found):
        assert point2 == pytest.approx(point, abs=1e-6)
        assert force2 == pytest.approx(force, abs=1e-7 * 1000)
    assert moved.planks[0].stress == pytest.approx(base.planks[0].stress, rel=1e-6, abs=1e-9)
    assert moved.planks[0].sag / size == pytest.approx(base.planks[0].sag, abs=1e-9)


KICK = """furncheck: 1
name: kick-board
planks:
  - {id: kick, size: [1200, 80], center: [0, 0, 40], rotation: [TILT, 0, 0]}
loads:
  - {plank: kick, force: [0, 0, -500], at: [300, 0, 80]}
"""


@pytest.mark.parametrize("tilt", [90.0, 91.0, 93.0])
def test_a_board_on_edge_is_held_along_both_its_edges(tilt):
    """Module docstring: the kick board upright and tilted; stations on both bottom edges
    at x = -300, 0 and 300 mm; its sag under 0.05 mm and its stress under 0.2 N/mm^2;
    the four corners' forces sum to 500 N + its weight and their moment about the origin
    is the loads' (the load acts at its point, whatever the tilt)."""
    design = parse_design(KICK.replace("TILT", repr(tilt)), "kick.yaml", "yaml")
    model = build_model(design, analyze(design))
    assert model.n_corners == 4 and len(model.station_corners) == 6
    points = model.contact_points[model.n_corners:] * 1000
    assert sorted(set(np.round(points[:, 0], 6).tolist())) == [-300.0, 0.0, 300.0]
    case = check_design(design).cases[0]
    (kick,) = case.planks
    assert kick.sag < 0.05 and kick.stress < 0.2
    weight = design.plank_mass(design.planks[0]) * G
    forces = np.array([c.force for c in case.contacts])
    where = np.array([c.point for c in case.contacts]) / 1000.0
    assert len(forces) == 4 and (forces[:, 2] >= -1e-9).all()
    assert forces.sum(axis=0) == pytest.approx([0.0, 0.0, 500.0 + weight], abs=1e-9 * 500)
    centre = design.planks[0].center_array
    applied = np.cross([0.3, 0.0, 0.08], [0.0, 0.0, -500.0]) \
        + np.cross(centre, [0.0, 0.0, -weight])
    assert np.cross(where, forces).sum(axis=0) + applied == pytest.approx(
        np.zeros(3), abs=1e-9 * 500)
