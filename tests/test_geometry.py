"""Joint detection, roles, frames and ground contacts (contract section 2), for axis-aligned
and rotated planks, and the statics' refusal to return numbers for a mechanism."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from furncheck.check import check_design
from furncheck.design import parse_design
from furncheck.geometry import analyze, interpenetrations

CANTILEVER = """\
furncheck: 1
planks:
  - {id: base, size: [400, 300], center: [0, 0, 6]}
  - {id: post, size: [700, 300], center: [0, 0, 362], rotation: [0, 90, 0]}
  - {id: shelf, size: [300, 300], center: [156, 0, 600]}
"""


def design(text: str):
    return parse_design(text, "test.yaml", "yaml")


def turned(text: str, degrees: float):
    """The cantilever turned about world z by ``degrees`` (centres and rotations)."""
    phi = np.radians(degrees)
    c, s = np.cos(phi), np.sin(phi)
    out = design(text)
    planks = []
    from dataclasses import replace

    from furncheck.design.model import rotation_matrix

    for plank in out.planks:
        x, y, z = plank.center
        matrix = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]) @ rotation_matrix(plank.rotation)
        ry = np.degrees(np.arcsin(-matrix[2, 0]))
        rx = np.degrees(np.arctan2(matrix[2, 1], matrix[2, 2]))
        rz = np.degrees(np.arctan2(matrix[1, 0], matrix[0, 0]))
        planks.append(replace(plank, center=(c * x - s * y, s * x + c * y, z),
                              rotation=(rx, ry, rz)))
    return replace(out, planks=tuple(planks))


def test_roles_point_length_nails_and_frame():
    """post/shelf: the shelf's -x end face (300 x 12 mm) lies on the post's +x face.

    Face plank first: planks = (post, shelf); point = centroid of the 300 x 12 mm region at
    x = 6 mm, z = 600 mm; L = 300 mm along y, floor(300 / 20) = 15 nails; frame n = +x
    (post face into the shelf), x = shelf's thickness normal (+z) made orthogonal to n,
    y = n x x = -y.
    """
    geometry = analyze(design(CANTILEVER))
    joints = {j.planks: j for j in geometry.joints}
    assert set(joints) == {("base", "post"), ("post", "shelf")}
    joint = joints[("post", "shelf")]
    assert (joint.face, joint.edge) == ("post", "shelf")
    assert np.allclose(joint.point, [0.006, 0.0, 0.600], atol=1e-9)
    assert joint.length == pytest.approx(0.300)
    assert joint.nails == 15
    assert np.allclose(joint.frame[:, 2], [1, 0, 0])     # n
    assert np.allclose(joint.frame[:, 0], [0, 0, 1])     # x
    assert np.allclose(joint.frame[:, 1], [0, -1, 0])    # y = n x x
    assert joint.edge_face == (0, -1)                    # the shelf's -x end
    assert joint.edge_thickness == pytest.approx(0.012)


@pytest.mark.parametrize("degrees", [30.0, -115.0])
def test_detection_turns_with_the_design(degrees):
    """Turned about z, the same joints with the same lengths, nails and turned frames."""
    straight = {j.planks: j for j in analyze(design(CANTILEVER)).joints}
    turn = turned(CANTILEVER, degrees)
    rotated = {j.planks: j for j in analyze(turn).joints}
    assert set(rotated) == set(straight)
    phi = np.radians(degrees)
    rz = np.array([[np.cos(phi), -np.sin(phi), 0], [np.sin(phi), np.cos(phi), 0], [0, 0, 1]])
    for key, joint in straight.items():
        other = rotated[key]
        assert other.nails == joint.nails and other.length == pytest.approx(joint.length)
        assert np.allclose(other.point, rz @ joint.point, atol=1e-9)
        assert np.allclose(other.frame, rz @ joint.frame, atol=1e-9)


def test_tilted_edge_plank_still_forms_a_joint():
    """A brace whose end is bevelled by its tilt: a plank tilted 10 degrees about y resting
    with its lower end edge on the base still touches (nearest corner at the face)."""
    tilt = 10.0
    half_length, half_t = 0.2, 0.006
    # the end face's lowest corner on z = 12 mm: centre height = 12 + L/2 cos + t/2 sin
    z = 12 + 1000 * (half_length * np.cos(np.radians(tilt)) + half_t * np.sin(np.radians(tilt)))
    text = (CANTILEVER.split("  - {id: post")[0]
            + f"  - {{id: brace, size: [400, 100], center: [50, 0, {z:.9f}], "
              f"rotation: [0, {90 - tilt}, 0]}}\n")
    joints = analyze(design(text)).joints
    assert [j.planks for j in joints] == [("base", "brace")]
    assert joints[0].nails == 5                     # floor(100 / 20)


def _shelf_and_slat(degrees: float) -> str:
    """A 500 x 300 shelf at z = 400 mm, its back edge along y = 0 from x = 0 to 500, turned
    by ``degrees`` about the vertical through its back-left corner; a 100 mm slat standing
    behind it (y from 0 to 12 mm) under its right end only (x from 400 to 500)."""
    phi = np.radians(degrees)
    x, y = 250 * np.cos(phi) + 150 * np.sin(phi), 250 * np.sin(phi) - 150 * np.cos(phi)
    return ("furncheck: 1\nplanks:\n"
            "  - {id: slat, size: [800, 100], center: [450, 6, 400], rotation: [90, 90, 0]}\n"
            f"  - {{id: shelf, size: [500, 300], center: [{x:.12f}, {y:.12f}, 400], "
            f"rotation: [0, 0, {degrees}]}}\n")


def test_an_end_face_is_measured_where_it_meets_the_face():
    """The gap of an end face on a face is that of the part that lies on it: the shelf's
    back edge turned 0.2 degrees away from the slat stays on the slat's plane at x = 0,
    but over the slat (x >= 400 mm) it lies 400 tan(0.2 deg) = 1.396 mm off: no joint
    (tolerance 0.5 mm).  Measured at its nearest corner anywhere, it counted as touching
    (gap 0), but only where the planks' bounding boxes met: turned by 37 degrees, a table's
    apron gained a joint with a leg 0.62 mm away (``benchmarks/sweep_catalog.py``)."""
    from furncheck.geometry import end_gap

    flush = design(_shelf_and_slat(0.0))
    assert [j.planks for j in analyze(flush).joints] == [("slat", "shelf")]
    turned_away = design(_shelf_and_slat(-0.2))
    assert analyze(turned_away).joints == ()
    gap = end_gap(turned_away, 0, 1)
    assert gap == pytest.approx(0.4 * np.tan(np.radians(0.2)), rel=1e-9)     # m


def test_edit_margins_measure_an_end_face_where_it_meets_the_face():
    """The edit margins (``geometry.edits.EditMargins``) watch the same gap: the shelf's
    joint margins gap + slack and slack - gap (the first two of its row) for the shelf
    turned 0.2 degrees are those of the 1.396 mm gap, so the margin says the joint is
    lost; with its nearest corner anywhere (on the slat's plane) they stayed at 0.5 mm."""
    from furncheck.geometry import EditMargins, end_gap
    from furncheck.geometry.model import _GEOMETRY_EPS

    flush = design(_shelf_and_slat(0.0))
    margins = EditMargins(flush, analyze(flush), (1,))
    turned_away = design(_shelf_and_slat(-0.2))
    required, _ = margins(turned_away)
    gap, slack = end_gap(turned_away, 0, 1), flush.tolerance + _GEOMETRY_EPS
    assert required[:2] == pytest.approx([gap + slack, slack - gap], rel=1e-9, abs=1e-12)
    assert required[1] < 0.0


def test_ground_contacts_penetration_and_floating():
    """Corners within tolerance of z = 0 are contacts; deeper ones penetrate; a design
    touching the ground nowhere floats."""
    assert len(analyze(design(CANTILEVER)).contacts) == 4       # the base's lower corners
    sunk = analyze(design(CANTILEVER.replace("center: [0, 0, 6]", "center: [0, 0, 5]")))
    assert [v.kind for v in sunk.violations].count("penetration") == 1
    lifted = CANTILEVER.replace("[0, 0, 6]", "[0, 0, 16]").replace("362", "372") \
        .replace("600]", "610]")
    floating = analyze(design(lifted))
    assert [v.kind for v in floating.violations] == ["floating"]


def test_plank_joined_to_nothing_is_disconnected():
    text = CANTILEVER + "  - {id: lamp, size: [100, 100], center: [900, 0, 6]}\n"
    report = check_design(design(text))
    assert report.valid is False
    assert [(v.kind, v.where) for v in report.violations] == [("disconnected", "lamp")]


@pytest.mark.parametrize("degrees", [0.5, 0.8, 1.2])
def test_a_turned_listed_joint_reports_how_deep_its_corner_sinks(degrees):
    """bookshelf-gap's 597 mm shelf (centre x = -1.5 mm, 250 mm deep) turned about z by
    ``degrees``: one corner of its left end sinks into side_l's face at x = -300 by
    298.5 cos(a) + 125 sin(a) + 1.5 - 300 (1.079 mm at 0.5 degrees), beyond the 0.5 mm
    tolerance, and the listed joint reads so.  The side's end face, whose plane the
    shelf's lower face runs through (both at z = 450), lay 450 mm "inside" it and, the
    flusher of the two, was reported: "interpenetrate by 450 mm"."""
    from pathlib import Path

    text = (Path(__file__).resolve().parent.parent / "designs" / "bookshelf-gap.yaml") \
        .read_text()
    text = text.replace("{id: shelf, size: [597, 250], center: [-1.5, 0, 456]}",
                        f"{{id: shelf, size: [597, 250], center: [-1.5, 0, 456], "
                        f"rotation: [0, 0, {degrees}]}}")
    a = np.radians(degrees)
    depth = 298.5 * np.cos(a) + 125.0 * np.sin(a) + 1.5 - 300.0
    (found,) = [v for v in analyze(design(text)).violations if v.where == "side_l/shelf"]
    assert found.message.startswith("planks interpenetrate by ")
    reported = float(found.message.split(" by ")[1].split(" mm")[0])
    assert reported == pytest.approx(depth, abs=1e-3)


def test_balanced_on_an_edge_is_reported_in_words_not_numbers():
    """A lone plank standing on one long edge (two collinear ground corners) cannot be held
    even bolted down: the case reads lift-off (never "mechanism") and has no forces."""
    text = """\
furncheck: 1
planks:
  - {id: board, size: [400, 300], center: [0, 0, 150], rotation: [90, 0, 0]}
"""
    tipped = text.replace("rotation: [90, 0, 0]", "rotation: [90, 0, 0]")
    board = design(tipped)
    assert len(analyze(board).contacts) == 4       # thin edge: 2 x 2 corners 12 mm apart
    single = design(text.replace("center: [0, 0, 150]", "center: [0, 0, 110.308658284]")
                    .replace("rotation: [90, 0, 0]", "rotation: [45, 0, 0]"))
    assert len(analyze(single).contacts) == 2      # resting on one corner line
    report = check_design(single)
    assert report.valid is False
    case = report.cases[0]
    assert case.stability == "lift-off" and not case.stable
    assert case.joints == () and case.contacts == ()
    assert report.violations[0].kind == "lift-off"
    assert "one line" in report.violations[0].message


def test_catalog_planks_do_not_cut_into_each_other():
    from pathlib import Path

    from furncheck.design import load_design

    for path in sorted((Path(__file__).resolve().parents[1] / "designs").glob("*.yaml")):
        assert interpenetrations(load_design(str(path))) == [], path.name


def test_reanalysis_of_an_edit_equals_a_fresh_analysis():
    """analyze(edited, previous=(design, geometry)) reuses joints between unchanged planks;
    on random DOF edits of catalog designs it must give exactly what analyze(edited) gives."""
    compared = 0
    for original, geometry, edited in _catalog_edits(
            ("shelf-cantilever.yaml", "chair-tilted.yaml", "bookshelf-20.yaml",
             "magazine-rack.yaml"), 24, 7):
        if any(p.length <= 0 or p.width <= 0 for p in edited.planks):
            continue
        fresh, reused = analyze(edited), analyze(edited, (original, geometry))
        assert [(j.planks, j.nails, j.edge_face) for j in fresh.joints] == \
            [(j.planks, j.nails, j.edge_face) for j in reused.joints]
        for a, b in zip(fresh.joints, reused.joints):
            assert np.allclose(a.point, b.point) and np.allclose(a.frame, b.frame)
        assert fresh.violations == reused.violations
        assert fresh.components == reused.components
        compared += 1
    assert compared > 30


def _catalog_edits(names, per_design, seed, largest=40.0):
    """(design, geometry, edited) for random DOF edits of catalog designs."""
    import random
    from pathlib import Path

    from furncheck.design import load_design
    from furncheck.dofs import Blocked, OutOfReach, all_dofs, apply_dof, structure

    rng = random.Random(seed)
    for name in names:
        original = load_design(str(Path(__file__).resolve().parents[1] / "designs" / name))
        geometry = analyze(original)
        frame = structure(original, geometry)
        for dof in rng.sample(all_dofs(original), per_design):
            try:
                edited = apply_dof(original, frame, dof, rng.uniform(-largest, largest))
            except (Blocked, OutOfReach):
                continue
            yield original, geometry, edited


def test_edits_checked_together_are_checked_as_alone():
    """check_edit_many (the geometries and plank cuts of many edits in one pass) gives,
    edit by edit, what check_edit gives for the edit on its own with a fresh analysis:
    the same problem (or none) and the same joints, contacts and violations.  The random
    edits of three catalog designs include kept ones, parted and new joints, cuts and
    planks left without length."""
    from furncheck.edit_check import check_edit, check_edit_many

    batches: dict[int, tuple] = {}
    for original, geometry, edited in _catalog_edits(
            ("cabinet-28.yaml", "chair-tilted.yaml", "bookshelf-20.yaml"), 40, 11, 120.0):
        batches.setdefault(id(original), (original, geometry, []))[2].append(edited)
    problems = set()
    for original, geometry, edits in batches.values():
        together = check_edit_many(geometry, edits, original)
        for edited, (problem, found) in zip(edits, together):
            alone, fresh = check_edit(geometry, edited)
            assert problem == alone
            problems.add(None if problem is None else problem.split()[0])
            if fresh is None:
                assert found is None
                continue
            assert [(j.planks, j.nails, j.edge_face, j.face_side) for j in found.joints] == \
                [(j.planks, j.nails, j.edge_face, j.face_side) for j in fresh.joints]
            for a, b in zip(found.joints, fresh.joints):
                assert np.allclose(a.point, b.point) and a.length == pytest.approx(b.length)
            assert [(c.plank, c.corner) for c in found.contacts] == \
                [(c.plank, c.corner) for c in fresh.contacts]
            assert found.violations == fresh.violations
            assert found.components == fresh.components
    assert None in problems and len(problems) >= 3, problems


def test_edit_margins_of_many_edits_are_each_edits_own():
    """edit_margins_many evaluates the margins of different edits (different changed
    planks) in one pass: each edit's values are exactly those of evaluating its margins
    alone, in any batch."""
    import range_designs as rd

    from furncheck.dofs import apply_dof, parse_dof, structure
    from furncheck.geometry import EditMargins, edit_margins_many

    bay = rd.parse(rd.bay())
    geometry = analyze(bay)
    frame = structure(bay, geometry)
    requests = []
    for name, step in (("shelf.z", 40.0), ("side_r.x", -3.0), ("shelf.rx", 2.0),
                       ("shelf.z", -120.0)):
        dof = parse_dof(bay, name)
        edited = apply_dof(bay, frame, dof, step)
        changed = tuple(i for i, (a, b) in enumerate(zip(bay.planks, edited.planks)) if a != b)
        requests.append((EditMargins(bay, geometry, changed, turn=5.0), edited))
    together = edit_margins_many(requests)
    backwards = edit_margins_many(requests[::-1])[::-1]
    for (margins, edited), values, other in zip(requests, together, backwards):
        alone = margins(edited)
        for a, b, c in zip(values, alone, other):
            assert a.shape == b.shape and np.array_equal(a, b) and np.array_equal(a, c)
    assert len({len(values[0]) for values in together}) > 1     # different rows


def test_edit_margins_are_linear_in_a_translation_and_vanish_where_the_checks_flip():
    """A shelf (12 thick, mid-plane z = 300) between two 600 mm sides, moved along z by s:
    its end faces span z 294 + s .. 306 + s on the sides' faces (z 0..600), so the overlap
    margin of both joints, less the bearing its nails need (MIN_BEARING_SHARE x 12 = 6
    mm), is 600 - (294 + s) - 6 mm and reaches 0 at s = 300; its lowest
    corner (294 + s) comes within the tolerance 0.5 mm of the ground at s = -293.5.  Every
    margin is linear in s (a translation), and check_edit agrees on both sides of both
    flips."""
    import range_designs as rd

    from furncheck.dofs import apply_dof, parse_dof, structure
    from furncheck.edit_check import check_edit
    from furncheck.geometry import EditMargins

    bay = rd.parse(rd.bay())
    geometry = analyze(bay)
    frame, dof = structure(bay, geometry), parse_dof(bay, "shelf.z")
    margins = EditMargins(bay, geometry, (bay.plank_index["shelf"],), turn=0.0)

    def at(step):
        return margins(apply_dof(bay, frame, dof, step))

    (required, forbidden), (up, forbidden_up) = at(0.0), at(100.0)
    assert required.min() > 0 and not (forbidden > 0).all(axis=1).any()
    for step in (-200.0, 50.0, 250.0):            # linear: values on the line through 0, 100
        values, groups = at(step)
        assert np.allclose(values, required + step / 100.0 * (up - required), atol=1e-12)
        assert np.allclose(groups, forbidden + step / 100.0 * (forbidden_up - forbidden),
                           atol=1e-12)
    rate = (up - required) / 100.0
    falling = rate < 0
    assert (required[falling] / -rate[falling]).min() == pytest.approx(300.0, abs=1e-3)
    rising = rate > 0
    assert (required[rising] / rate[rising]).min() == pytest.approx(293.5, abs=1e-3)
    for step, kept in ((299.9, True), (300.1, False), (-293.4, True), (-293.6, False)):
        assert (check_edit(geometry, apply_dof(bay, frame, dof, step), bay)[0] is None) == kept


def test_edit_margins_watch_tilts_only_where_a_plank_turns():
    """Between planks that an edit does not turn, the tilt of a narrow face to a broad
    face stays as it is: only faces within the largest joint tilt (60 degrees) can come to
    rest.  With the shelf of the bay listed as changed but not turning, a 90-degree turn
    horizon watches as many face pairs as no turn at all, and fewer than when the shelf
    turns; every joint's row is kept either way."""
    import range_designs as rd

    from furncheck.geometry import EditMargins

    bay = rd.parse(rd.bay())
    geometry = analyze(bay)
    shelf = (bay.plank_index["shelf"],)
    still = EditMargins(bay, geometry, shelf, turn=90.0, turning=())
    flat = EditMargins(bay, geometry, shelf, turn=0.0)
    turning = EditMargins(bay, geometry, shelf, turn=90.0, turning=shelf)
    assert len(still.edge) == len(flat.edge) < len(turning.edge)
    assert still.is_joint.sum() == flat.is_joint.sum() == turning.is_joint.sum() == 2
    for margins in (still, turning):
        required, _ = margins(bay)
        assert required.min() > 0


def test_a_designs_tables_are_kept_read_only_and_made_afresh_for_unhashable_planks():
    """``_design_tables`` keeps the face tables of a design's planks for its many edits
    (the same object again, its arrays read only); planks that cannot be hashed (a centre
    given as an array) get fresh tables with the same values."""
    from dataclasses import replace
    from pathlib import Path

    from furncheck.design import load_design
    from furncheck.geometry.faces import _design_tables, _Faces, _tables

    design = load_design(str(Path(__file__).resolve().parents[1] / "designs" / "stool.yaml"))
    kept = _design_tables(design.planks)
    assert _design_tables(design.planks) is kept
    assert not kept[0].narrow_corners.flags.writeable and not kept[1][0].flags.writeable
    planks = (replace(design.planks[0], center=np.array(design.planks[0].center)),) \
        + design.planks[1:]
    fresh, expected = _design_tables(planks), _tables(design.planks)
    for name in _Faces.__dataclass_fields__:
        assert np.array_equal(getattr(fresh[0], name), getattr(expected[0], name))
    assert all(np.array_equal(a, b) for a, b in zip(fresh[1], expected[1]))


def test_edits_found_to_keep_the_structure_have_a_fresh_analysis_geometry():
    """``EditedTables.geometries`` takes an edit's geometry from the design's when the
    edit keeps every joint (the same faces) and ground contact (the same corners): on
    random catalog edits, those edits' geometries equal a fresh ``analyze`` of the edit
    (joints in order with their points, lengths, nails and frames; contacts; components;
    no violations), and the others are told apart (a parted joint, a new one, a lifted
    corner)."""
    from furncheck.geometry.edits import EditedTables

    batches: dict[int, tuple] = {}
    for original, geometry, edited in _catalog_edits(
            ("cabinet-28.yaml", "stool.yaml", "bookshelf-20.yaml"), 30, 5, 60.0):
        if all(p.length > 0 and p.width > 0 for p in edited.planks):
            batches.setdefault(id(original), (original, geometry, []))[2].append(edited)
    kept_count = other_count = 0
    for original, geometry, edits in batches.values():
        tables = EditedTables(original, geometry, edits)
        for edited, found, kept in zip(edits, tables.geometries(), tables.kept):
            fresh = analyze(edited)
            same = [(j.face, j.edge, j.edge_face, j.face_side) for j in fresh.joints] == \
                [(j.face, j.edge, j.edge_face, j.face_side) for j in geometry.joints] and \
                [(c.plank, c.corner) for c in fresh.contacts] == \
                [(c.plank, c.corner) for c in geometry.contacts] and not fresh.violations
            assert kept == same
            if not kept:
                other_count += 1
                continue
            kept_count += 1
            for a, b in zip(found.joints, fresh.joints):
                assert (a.planks, a.nails, a.length) == (b.planks, b.nails, b.length)
                assert np.array_equal(a.point, b.point) and np.array_equal(a.frame, b.frame)
            assert [(c.plank, c.corner, tuple(c.point)) for c in found.contacts] == \
                [(c.plank, c.corner, tuple(c.point)) for c in fresh.contacts]
            assert found.components == fresh.components and found.grounded == fresh.grounded
            assert found.violations == ()
    assert kept_count > 10 and other_count > 10, (kept_count, other_count)


def test_quads_clipped_to_rectangles_by_hand():
    """A 2 x 2 square centred at (1, 0) clipped to |x|, |y| <= 1 keeps x in [0, 1]: area
    2, centroid (0.5, 0), extent 1 along x and 2 along y; a quad inside is kept as it is;
    one outside leaves nothing."""
    from furncheck.geometry.faces import _clipped_to_rectangles, _polygon_measures

    xs = np.array([[0.0, 2.0, 2.0, 0.0], [-0.5, 0.5, 0.5, -0.5], [3.0, 4.0, 4.0, 3.0]])
    ys = np.array([[-1.0, -1.0, 1.0, 1.0], [-0.2, -0.2, 0.2, 0.2], [0.0, 0.0, 1.0, 1.0]])
    half = np.ones(3)
    cx, cy, count = _clipped_to_rectangles(xs, ys, half, half)
    assert count.tolist() == [4, 4, 0]
    area, mx, my, extent = _polygon_measures(cx, cy, count, np.array([[1.0, 0.0]] * 3))
    assert area[:2].tolist() == pytest.approx([2.0, 0.4]) and mx[0] == pytest.approx(0.5)
    assert my[0] == pytest.approx(0.0, abs=1e-15) and extent[:2].tolist() == [1.0, 1.0]
    assert np.array_equal(cx[1, :4], xs[1]) and np.array_equal(cy[1, :4], ys[1])
    _, _, _, extent = _polygon_measures(cx, cy, count, np.array([[0.0, 1.0]] * 3))
    assert extent[0] == 2.0


@settings(max_examples=150, deadline=None, derandomize=True)
@given(st.lists(st.floats(-2.0, 2.0), min_size=4, max_size=4),
       st.floats(0.1, 1.5), st.floats(0.1, 1.5), st.floats(0.0, 6.3))
def test_quads_are_clipped_at_once_as_one_at_a_time(coordinates, half_x, half_y, turn):
    """Touching regions are clipped as arrays for large batches and one by one in plain
    floats for small ones (``faces.CLIP_AT_ONCE``): for a random quad (a rectangle of
    random half sizes, turned and moved, over a tilted plane) both give the same
    vertices, area, centroid, extent and least height to the last bit."""
    from furncheck.geometry.faces import (
        _clip_to_rectangle,
        _clipped_region,
        _clipped_to_rectangles,
        _polygon_measures,
        _region_gaps,
    )

    a, b, ox, oy = abs(coordinates[0]) + 0.05, abs(coordinates[1]) + 0.05, *coordinates[2:]
    c, s = np.cos(turn), np.sin(turn)
    quad = [(ox + c * x - s * y, oy + s * x + c * y)
            for x, y in ((a, b), (-a, b), (-a, -b), (a, -b))]
    xs, ys = np.array([[p[0] for p in quad]]), np.array([[p[1] for p in quad]])
    cx, cy, count = _clipped_to_rectangles(xs, ys, np.array([half_x]), np.array([half_y]))
    expected = _clip_to_rectangle(quad, half_x, half_y)
    assert int(count[0]) == len(expected)
    assert [(float(x), float(y)) for x, y in zip(cx[0, :count[0]], cy[0, :count[0]])] == \
        [(float(x), float(y)) for x, y in expected]
    along = (np.cos(2.0 * turn), np.sin(2.0 * turn))
    slope = np.array([[0.3 * ox, 0.1 * c, -0.2 * s]])       # a tilted plane's heights
    corners = slope[0, 0] + slope[0, 1] * xs[0] + slope[0, 2] * ys[0]
    gap = float(corners.min()) - 1e-3     # the corners' own, told apart from the fitted one
    region = _clipped_region(quad, half_x, half_y, *along, 0.0, slope[0].tolist(), gap)
    if region is not None:
        measured = _polygon_measures(cx, cy, count, np.array([along]))
        local = np.stack([xs, ys], axis=2)
        least = _region_gaps(cx, cy, count, slope, local, np.array([[half_x, half_y]]),
                             np.array([gap]))
        assert (*(float(m[0]) for m in measured), float(least[0])) == region
        whole = expected is quad                # nothing clipped: the corners' gap as given
        assert (region[4] == gap) if whole else (region[4] >= corners.min() - 1e-12)


def test_fresh_pairs_from_the_changed_planks_alone():
    """``_fresh_pairs`` (from the changed planks' boxes) lists exactly the pairs that
    ``_pairs_to_detect`` (all pairs of boxes that meet) marks for detection, in order."""
    from furncheck.geometry.analysis import _pairs_to_detect, _unchanged_planks
    from furncheck.geometry.edits import _fresh_pairs
    from furncheck.geometry.faces import _bounding_boxes
    from furncheck.geometry.model import _GEOMETRY_EPS

    compared = 0
    for original, geometry, edited in _catalog_edits(
            ("cabinet-28.yaml", "chair-tilted.yaml", "magazine-rack.yaml"), 20, 3, 80.0):
        same = _unchanged_planks(edited, (original, geometry))
        changed = [i for i, plank in enumerate(edited.planks) if plank.id not in same]
        lo, hi = _bounding_boxes(edited.planks)
        pairs, fresh = _pairs_to_detect(edited, lo, hi, {"planks": same})
        slack = edited.tolerance + _GEOMETRY_EPS
        assert _fresh_pairs(changed, lo, hi, slack).tolist() == pairs[fresh].tolist()
        compared += bool(changed)
    assert compared > 20


def test_planks_tabulated_together_are_the_planks_computed_alone():
    """``design.model.tabulate_planks`` (a design's planks' rotation matrices, centres, half
    sizes and corners computed at once, stacked, where its geometry is analysed) gives
    every plank the very bytes that its own cached properties compute: 200 planks of random
    sizes, positions and turns, upright and gimbal-locked ones among them."""
    import random

    from furncheck.design.model import Plank, tabulate_planks

    rng = random.Random(6)
    angles = [0.0, 90.0, -90.0, 180.0, 45.0]

    def random_plank(k: int) -> Plank:
        turn = tuple(rng.choice(angles) if rng.random() < 0.4 else rng.uniform(-180, 180)
                     for _ in range(3))
        return Plank(f"p{k}", rng.uniform(0.01, 2.0), rng.uniform(0.01, 1.0),
                     rng.uniform(0.006, 0.05),
                     tuple(rng.uniform(-3.0, 3.0) for _ in range(3)), turn)

    planks = [random_plank(k) for k in range(200)]
    alone = [Plank(p.id, p.length, p.width, p.thickness, p.center, p.rotation) for p in planks]
    tabulate_planks(planks)
    for together, single in zip(planks, alone):
        assert "corners" in together.__dict__           # filled by the batch, not lazily
        for name in ("rotation_matrix", "center_array", "half_extents", "corners"):
            assert getattr(together, name).tobytes() == getattr(single, name).tobytes(), name
