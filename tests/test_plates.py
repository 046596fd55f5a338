"""A plank held along lines on both sides of its beam, checked as a plate
(``furncheck.statics.plates``): the plate against Navier's series and the strip, the nail
rows' grip between the simply supported and clamped limits, and designs that the beam
alone read as almost flat (a step box's top nailed to its four sides, a top on sides
shallower than it is deep)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from furncheck.design.model import Material, Plank
from furncheck.statics import plate_supports, plates

E, T, NU = 3.0e9, 0.012, 0.25            # the defaults: Pa, m, PLATE_POISSON
D = E * T ** 3 / (12 * (1 - NU ** 2))
KIRCHHOFF = Material(shear_modulus=1e3 * E)     # shear this stiff: Kirchhoff's plate


def _navier(a: float, b: float, load, x: float, y: float, terms: int = 199) -> tuple:
    """(w, M_x, M_y) at (x, y) of a simply supported a x b Kirchhoff plate (corner at the
    origin), Navier's double sine series: w = sum q_mn sin(m pi x / a) sin(n pi y / b) /
    (pi^4 D (m^2 / a^2 + n^2 / b^2)^2), M_x = sum D pi^2 (m^2 / a^2 + nu n^2 / b^2) w_mn
    sin sin; ``load`` ('uniform', q) with q_mn = 16 q / (pi^2 m n) for odd m, n, or
    ('patch', P, u, v, xi, eta): P over u x v about (xi, eta), q_mn = 16 P / (pi^2 m n u
    v) sin(m pi xi / a) sin(n pi eta / b) sin(m pi u / 2a) sin(n pi v / 2b)."""
    m = np.arange(1, terms + 1, dtype=float)[:, None]
    n = np.arange(1, terms + 1, dtype=float)[None, :]
    if load[0] == "uniform":
        q = np.where((m % 2 == 1) & (n % 2 == 1), 16 * load[1] / (np.pi ** 2 * m * n), 0.0)
    else:
        _, P, u, v, xi, eta = load
        q = (16 * P / (np.pi ** 2 * m * n * u * v) * np.sin(m * np.pi * xi / a)
             * np.sin(n * np.pi * eta / b) * np.sin(m * np.pi * u / (2 * a))
             * np.sin(n * np.pi * v / (2 * b)))
    w_mn = q / (np.pi ** 4 * D * (m ** 2 / a ** 2 + n ** 2 / b ** 2) ** 2)
    shape = np.sin(m * np.pi * x / a) * np.sin(n * np.pi * y / b)
    w = float((w_mn * shape).sum())
    mx = float((D * np.pi ** 2 * (m ** 2 / a ** 2 + NU * n ** 2 / b ** 2) * w_mn * shape).sum())
    my = float((D * np.pi ** 2 * (n ** 2 / b ** 2 + NU * m ** 2 / a ** 2) * w_mn * shape).sum())
    return w, mx, my


def _edges(a: float, b: float, grip: float = 0.0, which: str = "LRBT") -> list:
    """Support segments of an a x b plank (centred) on its edges: L, R (x = -a/2, a/2,
    along y), B, T (y = -b/2, b/2, along x), each with ``grip`` N m / rad per m."""
    ha, hb = a / 2, b / 2
    edges = {"L": ((-ha, -hb), (-ha, hb)), "R": ((ha, -hb), (ha, hb)),
             "B": ((-ha, -hb), (ha, -hb)), "T": ((-ha, hb), (ha, hb))}
    return [(*edges[e], grip) for e in which]


PATCH = (-0.025, 0.025, -0.025, 0.025)


@pytest.mark.parametrize("a, b", [(0.4, 0.4), (0.6, 0.4), (1.0, 0.3)])
def test_simply_supported_plate_against_navier(a: float, b: float) -> None:
    """Simply supported on four edges, Kirchhoff's limit (shear made stiff): the centre's
    deflection under a uniform 1 kPa and under 400 N over a central 50 mm square within
    2 % of Navier's series; the largest bending stress under the patch, 6 max(M_x, M_y) /
    t^2 at the centre, within 4 % (read at the centres of the patch's elements, a quarter
    of it wide)."""
    plank = Plank("p", a, b, T, (0.0, 0.0, 0.0))
    plate = plates.plate_for(plank, KIRCHHOFF, _edges(a, b), [PATCH])
    uniform, _ = plates.plate_solution(plate, 1000.0, [])
    w, _, _ = _navier(a, b, ("uniform", 1000.0), a / 2, b / 2)
    assert uniform.max() == pytest.approx(w, rel=0.02)
    patch, stress = plates.plate_solution(plate, 0.0, [(PATCH, 400.0)])
    w, mx, my = _navier(a, b, ("patch", 400.0, 0.05, 0.05, a / 2, b / 2), a / 2, b / 2, 399)
    assert patch.max() == pytest.approx(w, rel=0.02)
    assert stress == pytest.approx(6 * max(mx, my) / T ** 2, rel=0.04)


def test_strip_on_two_edges() -> None:
    """Simply supported on two opposite edges and free on the others, MDF's own shear
    modulus: under a uniform load its middle bends as a strip, w = 5 q L^4 / 384 D + q
    L^2 / 8 k G t (Mindlin's shear term, which Navier's plate leaves out), within 2 %;
    its free edges, curling the other way (anticlastic), go down further, by about 12 %
    (of (1 - nu^2)^-1 = 1.07 of a beam's EI, and more: the edges are not held)."""
    a, b, q = 0.388, 0.4, 1000.0
    plank = Plank("p", a, b, T, (0.0, 0.0, 0.0))
    plate = plates.plate_for(plank, Material(), _edges(a, b, which="LR"), [])
    w, _ = plates.plate_solution(plate, q, [])
    xs, ys = plate.grid.xs, plate.grid.ys
    middle = w.reshape(len(ys), len(xs))[np.abs(ys).argmin(), np.abs(xs).argmin()]  # centre
    strip = 5 * q * a ** 4 / (384 * D) + q * a ** 2 / (8 * 5 / 6 * Material().shear_modulus * T)
    assert middle == pytest.approx(strip, rel=0.02)
    assert 1.05 * middle < w.max() < 1.2 * middle


def test_a_plank_narrower_than_its_thickness_is_a_strip_of_few_cells() -> None:
    """A 488 x 20 mm strip of 15 mm MDF (a range's probe narrowing a shelf) simply
    supported at its ends: its cells are no shorter than PLATE_CELL_FLOOR of its
    thickness (3 across, 488 / 7.5 = 66 along; 10 across, 244 along, without the
    floor), and its middle bends as a beam's, w = 5 q b L^4 / 384 E I + q b L^2 / 8 k G A
    with I = b t^3 / 12, A = b t, within 2 %."""
    L, b, t, q = 0.488, 0.02, 0.015, 1000.0
    plank = Plank("p", L, b, t, (0.0, 0.0, 0.0))
    plate = plates.plate_for(plank, Material(), _edges(L, b, which="LR"), [])
    assert (len(plate.grid.xs), len(plate.grid.ys)) == (67, 4)
    w, _ = plates.plate_solution(plate, q, [])
    G = Material().shear_modulus
    beam = 5 * q * b * L ** 4 / (384 * E * b * t ** 3 / 12) + q * L ** 2 / (8 * 5 / 6 * G * t)
    assert np.abs(w).max() == pytest.approx(beam, rel=0.02)


def test_the_nail_rows_grip_lies_between_the_limits() -> None:
    """The nail rows' grip (N m / rad per m) makes the plate stiffer, never softer: the
    centre's deflection falls as the grip grows, from the simply supported plate's (no
    grip) towards the clamped one's, Kirchhoff's clamped square under a uniform load
    0.00126 q a^4 / D (Timoshenko and Woinowsky-Krieger, table 35), within 3 %."""
    a = 0.4
    plank = Plank("p", a, a, T, (0.0, 0.0, 0.0))
    centre = []
    for grip in (0.0, 10.0, 1e3, 1e7):
        plate = plates.plate_for(plank, KIRCHHOFF, _edges(a, a, grip), [])
        centre.append(plates.plate_solution(plate, 1000.0, [])[0].max())
    assert centre == sorted(centre, reverse=True) and centre[0] > 2.5 * centre[-1]
    assert centre[-1] == pytest.approx(0.00126 * 1000.0 * a ** 4 / D, rel=0.03)


def test_a_plate_hinged_on_one_line_is_not_solved() -> None:
    """Supports on one line only leave the plate free to turn about it (no grip): no
    factor, no plate (its beam reads it)."""
    plank = Plank("p", 0.4, 0.3, T, (0.0, 0.0, 0.0))
    assert plates.plate_for(plank, Material(), _edges(0.4, 0.3, which="L"), []) is None


@pytest.mark.parametrize("grip", [1e2, 4e3, 1e5])
def test_a_plate_hung_on_one_gripped_line_is_a_cantilever(grip: float) -> None:
    """A 900 x 250 plate hung on its long edge B (a shelf nailed by its back edge onto a
    rail), the nail row's grip (N m / rad per m) its only hold against turning; uniform
    q.  Measured from the tangent at the line (contract 3a: a plank held at one end
    only), whatever the grip: the front edge's middle deflects as a strip in cylindrical
    bending, q c^4 / 8 D (c = 250 mm, Kirchhoff's limit), within 2 %, and no point of
    it less; the free corners, no longer held to cylindrical bending, more, up to an
    eighth with the softest grip (the line turns less near its ends: the plate twists);
    its span is twice the overhang, 2 c.  The moment at the line is q c^2 / 2 along its
    middle; the stress, 6 M / t^2 of its largest, within 2 % of that and at most 3 %
    above (a clamped edge's moment rises a little towards the free corners)."""
    from furncheck.statics.plate_mesh import sag_span

    L, c, q = 0.9, 0.25, 1000.0
    plank = Plank("p", L, c, T, (0.0, 0.0, 0.0))
    plate = plates.plate_for(plank, KIRCHHOFF, _edges(L, c, grip, which="B"), [])
    w, stress = plates.plate_solution(plate, q, [])
    X, Y = plate.grid.nodes
    cylindrical = q * c ** 4 / (8 * D)
    front = np.abs(Y - c / 2) < 1e-12
    middle = front & (np.abs(X) < 1e-12)
    assert w[middle] == pytest.approx([cylindrical], rel=0.02)
    assert w[front].min() >= 0.98 * cylindrical
    assert cylindrical <= np.abs(w).max() <= 1.13 * cylindrical
    sag, span = sag_span(plate.grid, w)
    assert sag == np.abs(w).max() and span == pytest.approx(2 * c, rel=1e-12)
    root = 6 * q * c ** 2 / 2 / T ** 2
    assert root * 0.98 <= stress <= root * 1.03


def test_a_board_on_a_centre_rail_is_two_cantilevers() -> None:
    """An 800 x 300 x 12 board nailed along its middle line onto a rail (its one joint,
    grip 4,050 N m / rad per m), 217.39 N spread over it (q = 905.8 Pa): two cantilevers
    of c = 150 mm either side of the line.  Both sides loaded alike, the line does not
    turn, and the grip takes no moment: each side's moment at the line is the
    elements' own (``plate_mesh._line_moments``), q c^2 / 2 = 10.19 N m / m, 6 M / t^2 =
    0.425 N/mm^2 along its middle (a helper's PyNite plate, 10 mm cells: 0.40 at the
    centre of the element 5 mm off the line), rising by up to 6 % towards the free ends
    (the clamped edge's Poisson effect): the stress lies between.  Its sag from the
    tangent, q c^4 / 8 D + q c^2 / 2 k G t = 0.126 mm at its edges' middles (PyNite 0.126
    mm), within 2 %; its span 2 c.  (The elements' centres alone, 15 mm off the line, read
    0.355 N/mm^2.)"""
    from furncheck.statics.plate_mesh import sag_span

    L, b, t, q = 0.8, 0.3, 0.012, 217.39 / (0.8 * 0.3)
    plank = Plank("p", L, b, t, (0.0, 0.0, 0.0))
    material = Material(elastic_modulus=3e9, shear_modulus=0.8e9)
    plate = plates.plate_for(plank, material, [((-L / 2, 0.0), (L / 2, 0.0), 4050.0)], [])
    w, stress = plates.plate_solution(plate, q, [])
    X, Y = plate.grid.nodes
    rigidity = 3e9 * t ** 3 / (12 * (1 - NU ** 2))
    c = b / 2
    hand = q * c ** 4 / (8 * rigidity) + q * c ** 2 / (2 * 5 / 6 * 0.8e9 * t)
    for edge in (-c, c):                # at the edge's node nearest its middle
        on_edge = np.flatnonzero(np.abs(Y - edge) < 1e-12)
        assert w[on_edge[np.argmin(np.abs(X[on_edge]))]] == pytest.approx(hand, rel=0.02)
    assert sag_span(plate.grid, w)[1] == pytest.approx(2 * c, rel=1e-12)
    root = 6 * q * c ** 2 / 2 / t ** 2
    assert root <= stress <= 1.06 * root


def test_a_hung_plates_sag_leaves_out_how_far_its_grip_lets_it_turn() -> None:
    """The same plate with a grip a thousand times softer turns a thousand times more
    about its line (the soft one, 100 N m / rad per m, by q c^2 / 2 / 100 = 0.31 rad:
    78 mm at the front edge, some 70 times the sag); its sag, from the tangent there,
    moves by at most an eighth (the twist of the previous test), not by that turn, and
    its deflections from the tangent are zero on the line."""
    L, c, q = 0.9, 0.25, 1000.0
    plank = Plank("p", L, c, T, (0.0, 0.0, 0.0))
    readings = []
    for grip in (1e2, 1e5):
        plate = plates.plate_for(plank, KIRCHHOFF, _edges(L, c, grip, which="B"), [])
        w, _ = plates.plate_solution(plate, q, [])
        X, Y = plate.grid.nodes
        assert np.abs(w[np.abs(Y + c / 2) < 1e-12]).max() < 1e-12 * np.abs(w).max()
        readings.append(np.abs(w).max())
    assert readings[0] == pytest.approx(readings[1], rel=0.12)


STEP_BOX = """furncheck: 1
name: step-box
units: mm
planks:
  - {id: front, size: [400, 288], center: [0, -144, 144], rotation: [90, 0, 0]}
  - {id: back, size: [400, 288], center: [0, 144, 144], rotation: [90, 0, 0]}
  - {id: end_l, size: [288, 276], center: [-194, 0, 144], rotation: [0, -90, 0]}
  - {id: end_r, size: [288, 276], center: [194, 0, 144], rotation: [0, -90, 0]}
  - {id: top, size: [400, 300], center: [0, 0, 294]}
loads:
  - {plank: top, mass: 80, at: [0, 0, 300]}
"""


def _top(text: str, plank: str = "top"):
    from furncheck.check import check_design
    from furncheck.design import parse_design

    report = check_design(parse_design(text, "d.yaml", "yaml"))
    case = report.cases[0]
    return report, next(p for p in case.planks if p.id == plank)


def test_step_box_top_nailed_all_round_sags_as_a_plate() -> None:
    """A 400 x 300 top nailed to four sides (joint lines 388 mm apart one way, 288 mm the
    other), 80 kg at its centre: its beam, held all along, read 0.02 mm and valid; as a
    plate it sags between the simply supported plate's deflection (Navier, 784.8 N over
    the 50 mm patch on 388 x 288, its own weight left out: the bound is the load's, the
    weight adds under 2 %) and half of it (the nail rows' grip), and it is sagging:
    1.5 x sag > 288 / 400 = 0.72 mm."""
    report, top = _top(STEP_BOX)
    simply = _navier(0.388, 0.288, ("patch", 784.8, 0.05, 0.05, 0.194, 0.144), 0.194,
                     0.144)[0] * 1e3
    assert 0.5 * simply < top.sag < 1.02 * simply
    assert top.sag_allowed == pytest.approx(288.0 / 400, abs=0.01)
    assert ("sagging", "top") in {(v.kind, v.where) for v in report.violations}


@pytest.mark.parametrize("phi", [37.0, 90.0, -123.4])
def test_step_box_rigid_motions_and_metres_change_nothing(phi: float) -> None:
    """The step box turned about the vertical and moved, and in metres: the same top sag,
    allowed sag and stress (to 1e-9 of themselves; the plate's grid is the plank's
    own)."""
    import physics_designs as pd
    import yaml

    top = _top(STEP_BOX)[1]
    design = yaml.safe_load(STEP_BOX)
    for text, scale in ((pd.to_text(pd.rigid_motion(design, phi, 800.0, -1700.0)), 1.0),
                        (pd.to_text(pd.convert_units(design, "m")), 1000.0)):
        other = _top(text)[1]
        assert (other.sag * scale, other.sag_allowed * scale, other.stress) == pytest.approx(
            (top.sag, top.sag_allowed, top.stress), rel=1e-9)


NIGHTSTAND = """furncheck: 1
name: nightstand
units: mm
planks:
  - {id: side_l, size: [550, @DEPTH], center: [-200, 0, 275], rotation: [0, -90, 0]}
  - {id: side_r, size: [550, @DEPTH], center: [200, 0, 275], rotation: [0, -90, 0]}
  - {id: top, size: [388, 400], center: [0, 0, 544]}
loads:
  - {plank: top, mass: 40, at: [0, 0, 550]}
"""


def test_a_top_on_shallow_sides_no_longer_reads_flat() -> None:
    """A 388 x 400 top between sides 290 mm deep (under 3/4 of its depth: its beam keeps
    its length, held along 290 mm of it) read 0.46 mm, where on sides 300 mm deep it
    spans across and reads 2.31 mm: a cliff of five times at 3/4.  As a plate held along
    the 290 mm lines it reads within 10 % of the 300 mm sides' beam."""
    shallow = _top(NIGHTSTAND.replace("@DEPTH", "290"))[1].sag
    deep = _top(NIGHTSTAND.replace("@DEPTH", "300"))[1].sag
    assert shallow == pytest.approx(deep, rel=0.10)
    assert shallow > 1.5


def test_a_plank_loaded_in_its_plane_is_not_a_plate() -> None:
    """A plank standing on edge that nothing pushes across its face (a rail under a cap)
    bends as its beam does: it is not checked as a plate; one lying flat is."""
    from furncheck.design import parse_design

    design = parse_design(STEP_BOX, "d.yaml", "yaml")
    assert plate_supports._loaded_across(design, design.plank("top"))
    assert not plate_supports._loaded_across(design, design.plank("front"))
    # an end standing on edge (turned -90 degrees about y: its normal's z is 6e-17, not
    # 0) with a weight on its top edge: the weight's component across is round-off
    weighted = parse_design(STEP_BOX + "  - {plank: end_l, mass: 10, at: [-194, 0, 288]}\n",
                            "d.yaml", "yaml")
    end = weighted.plank("end_l")
    assert float(np.dot((0.0, 0.0, -98.1), end.axes[2])) != 0.0
    assert not plate_supports._loaded_across(weighted, end)
    # ... and read as a plate's load, it pushes nothing across and makes no grid lines
    load = weighted.load_cases[0].loads[-1]
    _, points = plates._case_loads(weighted, [load], end)
    assert [force for _, force in points] == [0.0]
    assert plates._load_patches((0.0, points)) == []


def test_a_pure_twist_gives_the_twisting_moment_alone() -> None:
    """w = x y (beta_x = y, beta_y = x: no shear strain) is a pure twist, kappa_xy = 2:
    every element's centre reads M_xy = D (1 - nu) / 2 x 2 = D (1 - nu) and M_x = M_y = 0
    (the bilinear element holds this field exactly)."""
    plank = Plank("p", 0.4, 0.3, T, (0.0, 0.0, 0.0))
    grid = plates.plate_for(plank, KIRCHHOFF, _edges(0.4, 0.3), []).grid
    X, Y = grid.nodes
    u = np.column_stack([X * Y, Y, X]).ravel()
    moments = np.einsum("eaj,ej->ea", grid.moments, u[grid.dofs])
    assert moments[:, 2] == pytest.approx(np.full(len(moments), D * (1 - NU)), rel=1e-9)
    assert np.abs(moments[:, :2]).max() <= 1e-9 * D


def test_a_rail_along_a_strip_bends_with_it() -> None:
    """A 600 x 50 strip simply supported at its ends, a rail along its middle line of
    nine times its own E I: under a uniform load it bends as one beam of ten times it,
    5 w L^4 / 384 (10 E I), within 2 % (a strip this narrow bends as a beam, E I = E b
    t^3 / 12; the plate's D b is 7 % stiffer, a tenth of that in the sum).  A rail a
    thousand times stiffer along one free edge holds that edge: under 1 % of the
    strip's deflection there."""
    L, b, q = 0.6, 0.05, 1000.0
    plank = Plank("p", L, b, T, (0.0, 0.0, 0.0))
    EI = E * b * T ** 3 / 12
    rail = ((-L / 2, 0.0), (L / 2, 0.0), 9 * EI)
    plate = plates.plate_for(plank, KIRCHHOFF, _edges(L, b, which="LR"), [],
                             stiffeners=[rail])
    w, _ = plates.plate_solution(plate, q, [])
    assert np.abs(w).max() == pytest.approx(5 * q * b * L ** 4 / (384 * 10 * EI), rel=0.02)
    wide = Plank("p", L, 0.3, T, (0.0, 0.0, 0.0))
    bare = plates.plate_solution(plates.plate_for(wide, KIRCHHOFF, _edges(L, 0.3, which="LR"),
                                                  []), q, [])[0]
    edge = ((-L / 2, -0.15), (L / 2, -0.15), 1e3 * E * 0.3 * T ** 3 / 12)
    held = plates.plate_for(wide, KIRCHHOFF, _edges(L, 0.3, which="LR"), [],
                            stiffeners=[edge])
    w, _ = plates.plate_solution(held, q, [])
    X, Y = held.grid.nodes
    on_edge = np.abs(Y + 0.15) < 1e-12
    assert np.abs(w[on_edge]).max() < 0.01 * np.abs(bare).max()


def test_segments_given_either_way_round_are_the_same_plate() -> None:
    """A support segment from its far end to its near one holds the plate as it does the
    other way round."""
    plank = Plank("p", 0.4, 0.3, T, (0.0, 0.0, 0.0))
    ahead = plates.plate_for(plank, Material(), _edges(0.4, 0.3), [])
    back = plates.plate_for(plank, Material(), [(b, a, g) for a, b, g in _edges(0.4, 0.3)], [])
    assert back is not None
    assert plates.plate_solution(back, 1000.0, [])[0] == pytest.approx(
        plates.plate_solution(ahead, 1000.0, [])[0], rel=1e-12)


def test_the_plate_takes_over_where_its_share_of_the_allowed_sag_is_larger() -> None:
    """``_merged``: a beam's short overhang, 0.5 mm over a 220 mm span (0.0023), keeps its
    reading against a plate's 0.6 mm over 388 mm (0.0015); the plate's 0.6 mm over 388
    mm replaces a beam's 0.4 mm over 388 mm, and clears the overhang flag; the stress is
    the larger either way."""
    from furncheck.statics.bending import PlankStatics

    beam = PlankStatics(sag=np.array([0.5e-3, 0.4e-3]), span=np.array([0.22, 0.388]),
                        stress=np.array([3e6, 3e6]), overhang=np.array([True, False]),
                        sideways=lambda k: True)
    merged = plates._merged(beam, [(0, 0.6e-3, 0.388, 2e6), (1, 0.6e-3, 0.388, 4e6)])
    assert merged.sag.tolist() == [0.5e-3, 0.6e-3]
    assert merged.span.tolist() == [0.22, 0.388]
    assert merged.overhang.tolist() == [True, False]
    assert merged.stress.tolist() == [3e6, 4e6]
    assert merged.sideways(0) is True and merged.sideways(1) is False


def test_a_rail_between_two_panels_bends_under_the_plate_it_holds() -> None:
    """The step box with a 376 x 72 mm rail on edge under the top's middle, between the
    ends (``suggest``'s rail fix).  Stiff in its own plane, the rail holds its line
    straight (``elastic._holds_straight``), but it spans between the ends, held up at
    its ends only: not a support of the top's plate but a beam that bends with it
    (``plate_supports._carried``), so the top reads more than on a rigid line there (about a
    tenth of the box without rail) and less than without the rail; the ends, standing
    on the floor, and the front and back are supports."""
    from furncheck.design import parse_design
    from furncheck.geometry import analyze
    from furncheck.statics import build_model
    from furncheck.statics.plate_supports import _carried

    railed = STEP_BOX.replace(
        "  - {id: top,", "  - {id: rail, size: [376, 72], center: [0, 0, 252], "
                         "rotation: [-90, 0, 0]}\n  - {id: top,")
    design = parse_design(railed, "d.yaml", "yaml")
    geometry = analyze(design)
    model = build_model(design, geometry)
    joints_of: dict = {}
    for j in model.joints:
        for plank_id in geometry.joints[j].planks:
            joints_of.setdefault(plank_id, []).append(geometry.joints[j])
    carried = _carried(geometry, joints_of)
    (rail_joint,) = [j for j in joints_of["top"] if "rail" in j.planks]
    (end_joint,) = [j for j in joints_of["top"] if "end_l" in j.planks]
    assert not carried("rail", rail_joint) and carried("end_l", end_joint)
    bare = _top(STEP_BOX)[1].sag
    assert 0.1 * bare < _top(railed)[1].sag < bare


@pytest.mark.parametrize(("name", "load_x"), [("end_r.x", 0), ("front.y", 0), ("top.width", 0),
                                             ("end_r.x", 33), ("end_r.x", -1)])
def test_a_plates_sag_rate_is_the_plates_own(name: str, load_x: int) -> None:
    """The force sensitivity's sag rate of a plank whose plate reading is its sag (the
    step box with its top 440 x 340, overhanging its sides by 20 mm all round: as a
    plate 1.61 mm, its beam, held all round, a few hundredths) is the plate's: the
    central difference of the full check's sag over the DOF stepped 0.01 mm either way
    (small enough that the full check's grid keeps its cells), within 2 %: end_r moved
    out, which moves a support line away from end_l's; front moved in, which shortens
    the span across; the top widened, its overhangs longer.  With the beams' rates alone
    (before) the rate read almost none of it.  The load 33 or 1 mm off centre puts its
    patch's lines a whole number of cells from a support: the sensitivity's step (1e-7
    of the design's size) cut one interval into a cell more, and the rate read 20.7 mm
    per mm against 0.0066 (PLATE_CELL_SLACK).  (The top overhangs so that a step keeps
    each side's edge under it: where an edge reaches the top's end, re-detecting the
    joint after a step puts its line half the step over, while the sensitivity follows
    the joint through the step.)"""
    from furncheck.check import check_design
    from furncheck.design import parse_design
    from furncheck.dofs import apply_dof, parse_dof, structure
    from furncheck.geometry import analyze
    from furncheck.sensitivity import Linearization

    text = STEP_BOX.replace("{id: top, size: [400, 300]", "{id: top, size: [440, 340]") \
        .replace("at: [0, 0, 300]", f"at: [{load_x}, 0, 300]")
    design = parse_design(text, "d.yaml", "yaml")
    geometry = analyze(design)
    dof = parse_dof(design, name)
    frame = structure(design, geometry)
    linear = Linearization(design, design.load_cases[0], geometry, frame)
    local = list(linear.model.planks).index(design.plank_index["top"])
    rate = 1e3 * float(linear.derivatives([dof]).plank_sags[0, local])     # mm per mm
    sags = [next(p.sag for p in check_design(apply_dof(design, frame, dof, step)).cases[0]
                 .planks if p.id == "top") for step in (-0.01, 0.01)]
    assert rate == pytest.approx((sags[1] - sags[0]) / 0.02, rel=0.02)


def test_a_load_reads_the_same_bit_for_bit_whatever_is_solved_with_it() -> None:
    """``plate_solutions`` of a load alone and in a batch with others, at any place in it:
    the same deflections and stress, bit for bit (the readings are kept by the plate and
    its loads and shared by every check, ``plates._solved``, so that ``--jobs 1`` and
    ``--jobs 2``, and a check with or without searches before it, read the same)."""
    from furncheck.statics.plate_mesh import plate_solutions

    plank = Plank("p", 0.6, 0.4, T, (0.0, 0.0, 0.0))
    plate = plates.plate_for(plank, Material(), _edges(0.6, 0.4), [PATCH])
    loads = [(1000.0 * (k + 1), [(PATCH, 37.0 * k)]) for k in range(9)]
    batch = plate_solutions(plate.grid, loads)
    for k in range(len(loads)):
        ((w, stress),) = plate_solutions(plate.grid, [loads[k]])
        assert w.tobytes() == batch[k][0].tobytes() and stress == batch[k][1]
    again = plate_solutions(plate.grid, loads[5:] + loads[:5])
    assert again[3][0].tobytes() == batch[8][0].tobytes() and again[3][1] == batch[8][1]


def test_a_cases_plate_reading_is_its_own_whatever_the_other_cases_load() -> None:
    """Each case reads a plate on the grid through its own loads' patches: the step box's
    80 kg case reads the same top sag and stress (to 1e-12 of themselves) with a second
    case that puts 40 kg near a corner of the top (its patch's edges, on one grid with
    the first case's, moved the first case's sag by 0.14 %) and a third that
    pushes the top along its face (no patch: nothing across the face), in any turn of
    the design."""
    alone = _top(STEP_BOX)[1]
    more = STEP_BOX + """\
load_cases:
  corner:
    - {plank: top, mass: 40, at: [130, 90, 300]}
  push:
    - {plank: top, force: [200, 0, 0], at: [0, 0, 300]}
"""
    with_others = _top(more)[1]
    assert (with_others.sag, with_others.stress) == pytest.approx(
        (alone.sag, alone.stress), rel=1e-12)
    assert with_others.sag > 0.5
    # and turned about the vertical and moved, the same
    import physics_designs as pd
    import yaml

    turned = _top(pd.to_text(pd.rigid_motion(yaml.safe_load(more), 37.0, 800.0, -1700.0)))[1]
    assert (turned.sag, turned.stress) == pytest.approx((alone.sag, alone.stress), rel=1e-9)


@settings(deadline=None, max_examples=200, derandomize=True)
@given(points=st.lists(st.floats(-0.2, 0.2), max_size=12),
       edges=st.lists(st.floats(-0.2, 0.2), max_size=8))
@example(points=[-0.2, -0.1996986, -0.18913107, 0.1996986, 0.2], edges=[])
@example(points=[0.01, 0.0108, 0.0116, 0.0124, 0.0132], edges=[0.0, 0.0004])
@example(points=[-0.199, 0.199], edges=[])
def test_grid_lines_mirror_and_keep_every_line_within_a_millimetre(points, edges):
    """``plate_mesh.grid_lines`` of a 400 mm side: the mirrored lines and edges give the
    mirrored grid (to round-off), every support line lies within NODE_MERGE (1 mm) of a
    grid line, every patch edge within it of one or left out only where the lines would
    pass PLATE_GRID_LINES, and the grid runs from edge to edge, ascending.  (The first
    example is the edited chair's seat whose stress moved by 1e-5 when mirrored: segment
    ends at +-199.7 and +-200 mm; the second a run of lines 0.8 mm apart, longer than
    two millimetres; the third supports 1 mm inside the edges, |-0.199 - -0.2| =
    1.0000000000000009 mm as ``_on_segment`` measures it: a support line is within
    NODE_MERGE of a grid line as measured there, exactly, or its nodes are not found.)"""
    from furncheck import tolerances as tol
    from furncheck.statics.plate_mesh import grid_lines

    cell = 0.03
    grid = grid_lines(-0.2, 0.2, points, edges, cell)
    mirrored = grid_lines(-0.2, 0.2, [-p for p in points], [-e for e in edges], cell)
    assert np.allclose(np.sort(-mirrored), grid, rtol=0.0, atol=1e-12)
    assert grid[0] == -0.2 and grid[-1] == 0.2
    assert np.all(np.diff(grid) > 0.0)
    assert np.all(np.diff(grid) <= cell * (1 + tol.PLATE_CELL_SLACK))
    for point in np.clip(points, -0.2, 0.2):
        assert np.abs(grid - point).min() <= tol.NODE_MERGE
    for point in edges:                   # (22 lines at most: no edge is left out)
        assert np.abs(grid - point).min() <= tol.NODE_MERGE + 1e-15


FOUR_FINS = """
furncheck: 1
name: four-fins
units: mm
material: {{thickness: 12, density: 1.0e-06, elastic_modulus: 3000.0, shear_modulus: 800.0,
  nail_slip: 1200.0, nail_withdrawal: 1000.0}}
planks:
  - {{id: shelf, size: [{length}, 200], center: [0, 0, 159], thickness: 18}}
  - {{id: fin0, size: [150, 100], center: [-950, 0, 75], rotation: [0, -90, 0], thickness: 2}}
  - {{id: fin1, size: [150, 100], center: [-450, 0, 75], rotation: [0, -90, 0], thickness: 2}}
  - {{id: fin2, size: [150, 100], center: [350, 0, 75], rotation: [0, -90, 0], thickness: 2}}
  - {{id: fin3, size: [150, 100], center: [950, 0, 75], rotation: [0, -90, 0], thickness: 2}}
loads:
  - {{plank: shelf, mass: 30, spread: true}}
"""


def test_a_support_a_millimetre_inside_the_edge_holds_the_plate() -> None:
    """A 1902 x 200 x 18 mm shelf on four 2 mm fins at x = -950, -450, 350 and 950 mm
    (spans 500, 800, 600; the end fins flush with its ends, their joint lines 1 mm inside
    them), 30 kg spread, weightless planks.  By the three-moment equation (pinned
    supports, uniform w = 294.3 N / 1902 mm; the 1 mm overhangs left out):

        2 M_B (l1 + l2) + M_C l2 = -w (l1^3 + l2^3) / 4
        M_B l2 + 2 M_C (l2 + l3) = -w (l2^3 + l3^3) / 4

    M_B = -6998, M_C = -8058 N mm, the largest moment: stress |M_C| / (b t^2 / 6) = 0.746
    N/mm^2.  The end lines lay 1.0000000000000009 mm from the edges as the plate measured
    them, and the plate, held on the two middle fins alone, read a 3.65 mm sag over the
    800 mm span (its middle lifting) and 2.80 N/mm^2 (the 600 mm span as a cantilever):
    'sagging'.  Now it is valid, and reads as the shelf 0.2 mm longer does (its lines
    then 1.1 mm inside)."""
    from furncheck.check import check_design
    from furncheck.design import parse_design

    def shelf(length: float):
        report = check_design(parse_design(FOUR_FINS.format(length=length), "d.yaml",
                                           "yaml"))
        return report, next(p for p in report.cases[0].planks if p.id == "shelf")

    from furncheck import tolerances as tol

    w = 30 * tol.GRAVITY / 1902.0
    l1, l2, l3 = 500.0, 800.0, 600.0
    m_b, m_c = np.linalg.solve([[2 * (l1 + l2), l2], [l2, 2 * (l2 + l3)]],
                               [-w * (l1 ** 3 + l2 ** 3) / 4, -w * (l2 ** 3 + l3 ** 3) / 4])
    assert (m_b, m_c) == pytest.approx((-6998, -8058), rel=1e-4)      # the docstring's
    report, flush = shelf(1902.0)
    longer = shelf(1902.2)[1]
    assert report.valid, report.violations
    assert flush.stress == pytest.approx(abs(m_c) / (200 * 18 ** 2 / 6), rel=0.02)
    assert (flush.sag, flush.stress) == pytest.approx((longer.sag, longer.stress), rel=0.01)
