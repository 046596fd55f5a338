"""Anchors (contract section 2): a plank tied to a wall at a point, both ways, up to a
capacity; reported like a joint (force, utilization, ``non-durable`` beyond capacity).

Two hand checks, in both models:

* A wall shelf on a cleat.  A cleat (600 x 100 x 18 mm) stands with its back face on the
  wall y = 0, screwed to it by two anchors at height a above its bottom edge; a 250 mm
  deep shelf is nailed onto its top edge, its back edge on the wall, and carries a load.
  The load turns shelf and cleat outwards about the cleat's bottom edge, where the wall
  pushes.  Moments about that edge (a line in the wall's plane, so the wall's friction
  has no arm; an anchor holds at the cleat's mid-plane, t / 2 = 9 mm in front of the
  wall, where a screw bears on its hole, so its vertical force V has that arm):

      sum over anchors of (their pull F_y  x  a  +  V x t / 2)  -  sum of the wall's
      pushes N_c above the edge x their heights z_c above it  =  sum of the weights W_i x
      their distance y_i in front of the wall

  (W_i: the shelf's and the cleat's self-weight at their centres and the load).  Rigid
  planks leave the wall above the edge, so the anchors alone make up the moment.
  Elastic ones do too: the shelf, nailed along the cleat's whole top edge (the row cut
  into parts: the shelf hangs on it alone, ``elastic.hung_planks``), holds that edge
  straight, bending in its own plane (250 mm deep: some 480 times the cleat's 18 mm
  across its face), so the cleat cannot bow out between its anchors and curl back past
  them: its top edge leaves the wall.  (While the model held the shelf at the row's
  middle alone, the cleat's top corners, 100 mm past the anchors, bore on the wall and
  took a tenth to a fifth of the moment: an artefact of that one spring.)
* A bookcase side (1800 x 300 x 18 mm board on its end, its back edge 20 mm in front of
  the wall: touching it, its back foot could wedge against the wall and hold by the
  wall's friction) pushed forwards at the top with P.  Free, it tips about its front edge
  once P h > W d (d = 150 mm from the front edge to the centre, h = 1800 mm): 5.96 N for
  its 71.5 N.  Anchored at
  the top of its back edge, it holds 10 N: the anchor pulls it back, and the moments of
  anchor and floor about the front edge make up P h - W d (how much of it the anchor takes
  and how much the back feet is the stiffnesses' to decide: the tie is stiff both ways).
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest
import yaml
from cli_checks import assert_suggestions_validate
from click.testing import CliRunner

from furncheck.check import check_design
from furncheck.cli.main import main
from furncheck.design import parse_design
from furncheck.geometry import analyze
from furncheck.suggest import suggest_design

G = 9.81
DENSITY = 750.0


def _parse(doc: dict):
    return parse_design(yaml.safe_dump(doc, sort_keys=False), "anchored.yaml", "yaml")


def _cleat_shelf(model: str, load_kg: float = 10.0, capacity: float = 400.0,
                 anchor_height: float = 70.0) -> dict:
    """The wall shelf of the module docstring; anchors at x = +-200 mm, ``anchor_height``
    above the cleat's bottom (z = 1000 mm); the load 225 mm in front of the wall."""
    return {
        "furncheck": 1, "name": "wall-shelf", "model": model,
        "material": {"thickness": 18, "friction": 0.5},
        "planks": [
            {"id": "cleat", "size": [600, 100], "center": [0, 9, 1050],
             "rotation": [90, 0, 0]},
            {"id": "shelf", "size": [600, 250], "center": [0, 125, 1109]},
        ],
        "walls": [{"point": [0, 0, 0], "normal": [0, 1, 0]}],
        "anchors": [{"plank": "cleat", "at": [x, 0, 1000 + anchor_height], "wall": 0,
                     "capacity": capacity} for x in (-200.0, 200.0)],
        "loads": [{"plank": "shelf", "mass": load_kg, "at": [0, 225, 1118]}],
    }


@pytest.mark.parametrize("model", ["rigid", "elastic"])
@pytest.mark.parametrize("anchor_height", [50.0, 90.0])
def test_a_cleat_shelfs_anchors_pull_by_the_moments_about_the_cleats_foot(model,
                                                                         anchor_height):
    design = _parse(_cleat_shelf(model, anchor_height=anchor_height))
    geometry = analyze(design)
    assert not geometry.violations
    assert [j.planks for j in geometry.joints] == [("shelf", "cleat")] or \
        [j.planks for j in geometry.joints] == [("cleat", "shelf")]
    case = check_design(design, geometry).cases[0]
    assert case.stable
    weights = {"cleat": DENSITY * 0.6 * 0.1 * 0.018 * G,
               "shelf": DENSITY * 0.6 * 0.25 * 0.018 * G}
    moment = weights["cleat"] * 9.0 + weights["shelf"] * 125.0 + 10.0 * G * 225.0   # N mm
    pull = -sum(a.force[1] for a in case.anchors)          # the wall pulls the cleat: -y
    held_up = sum(a.force[2] for a in case.anchors)
    above = [c for c in case.contacts if c.point[2] > 1000.0 + 1e-6]
    pushes = sum(c.force[1] * (c.point[2] - 1000.0) for c in above)
    assert pull * anchor_height + held_up * 9.0 - pushes == pytest.approx(moment, rel=2e-3)
    bearing = {(c.plank, *c.point) for c in above
               if abs(c.force[1]) > 1e-6 * sum(weights.values())}
    assert not bearing                  # the wall pushes only at the cleat's foot
    total = np.sum([c.force for c in case.contacts], axis=0) \
        + np.sum([a.force for a in case.anchors], axis=0)
    weight = sum(weights.values()) + 10.0 * G
    assert total == pytest.approx([0.0, 0.0, weight], abs=1e-6 * weight)
    for anchor in case.anchors:
        assert anchor.utilization == pytest.approx(anchor.size / 400.0)


def test_an_anchor_beyond_its_capacity_is_non_durable(tmp_path):
    """At 40 kg the two anchors at 70 mm pull about 2 x 640 N: over a 500 N capacity.  Each
    message names the parts of its anchor's force, as a fixer reads them: its pull out of
    the wall is half the weights' moment about the cleat's foot, less that of what the
    anchors hold up (V at the cleat's mid-plane, 9 mm from the wall), over the anchors'
    70 mm (the rigid wall pushes at the foot alone, as in the test above): (7.946 N x 9 mm
    + 19.87 N x 125 mm + 392.4 N x 225 mm - V x 9 mm) / 70 mm / 2 = 648.9 N - V x 0.0643."""
    doc = _cleat_shelf("rigid", load_kg=40.0, capacity=500.0)
    path = tmp_path / "shelf.yaml"
    path.write_text(yaml.safe_dump(doc, sort_keys=False))
    result = CliRunner().invoke(main, ["validate", str(path), "--format", "json"])
    assert result.exit_code == 1, result.output
    report = json.loads(result.output)["reports"][0]
    kinds = {(v["kind"], v["where"]) for v in report["violations"]}
    assert kinds == {("non-durable", "anchors[0]"), ("non-durable", "anchors[1]")}
    anchors = report["cases"][0]["anchors"]
    assert [a["plank"] for a in anchors] == ["cleat", "cleat"]
    assert all(a["utilization"] > 1.0 and a["wall"] == 0 for a in anchors)
    assert report["cases"][0]["durable"] is False
    # the message says what the force is made of: the wall's normal is +y, so the pull out
    # of it is -F_y, what holds the cleat up F_z, the shear along the wall |F_x|
    for violation, anchor in zip(sorted(report["violations"], key=lambda v: v["where"]),
                                 anchors):
        fx, fy, fz = anchor["force"]
        parts = re.search(r"\(a pull of ([\d.,]+) N out of the wall, ([\d.,]+) N holding it "
                          r"up(?:, ([\d.,]+) N along the wall)?\)", violation["message"])
        assert parts is not None, violation["message"]
        assert float(parts.group(1).replace(",", "")) == pytest.approx(-fy, rel=1e-3)
        moment = (DENSITY * 0.6 * 0.1 * 0.018 * G * 9.0
                  + DENSITY * 0.6 * 0.25 * 0.018 * G * 125.0 + 40.0 * G * 225.0
                  - sum(a["force"][2] for a in anchors) * 9.0)
        assert float(parts.group(1).replace(",", "")) == pytest.approx(moment / 70.0 / 2.0,
                                                                       rel=1e-3)
        assert float(parts.group(2).replace(",", "")) == pytest.approx(fz, rel=1e-3)
        along = float(parts.group(3).replace(",", "")) if parts.group(3) else 0.0
        assert along == pytest.approx(abs(fx), rel=1e-3, abs=0.5)


def _pulled_board(model: str, depth: float) -> dict:
    """A 400 x 300 x 12 mm board flat on the wall y = 0, screwed 5 mm in from its ends at
    z = 640 (``depth``: where in its 12 mm the drawing puts the screws' points), pulled
    100 N out of the wall between them."""
    return {
        "furncheck": 1, "name": "board-pull", "model": model,
        "walls": [{"point": [0, 0, 0], "normal": [0, 1, 0]}],
        "planks": [{"id": "back", "size": [400, 300], "center": [0, 6, 500],
                    "rotation": [90, 0, 0]}],
        "anchors": [{"plank": "back", "at": [x, depth, 640], "wall": 0, "capacity": 196}
                    for x in (-195.0, 195.0)],
        "loads": [{"plank": "back", "force": [0, 100, 0], "at": [0, 12, 640]}],
    }


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_an_anchor_holds_at_its_planks_mid_plane_wherever_at_is_drawn(model):
    """A screw bears on its hole over the board's thickness and pulls along its own axis,
    so the anchor holds at ``at`` brought onto the plank's mid-plane: its forces are the
    same whether ``at`` is drawn on the face against the wall, in the middle or on the
    front face.  (Held at the point as drawn, the elastic board's bending stretched its
    back face and shortened its front one between the screws, which then pulled against
    each other along the wall: 121 N each drawn at the back, 129 N the other way at the
    front, 100 N of load.)  Rigid, by symmetry and statics each screw pulls F / 2 = 50 N,
    nothing along the wall.  Elastic, what it puts along the wall stays small; its pull is
    not asserted: the board is one beam whose cross-section stays straight (contract
    3a), so a pull 140 mm above its axis twists the whole 300 mm section, its bottom
    corners bear on the wall and each screw pulls about 91 N (a plate would bend along
    the screws' line alone: README, "Anchors")."""
    forces = []
    for depth in (0.0, 6.0, 12.0):
        case = check_design(_parse(_pulled_board(model, depth))).cases[0]
        assert [a.point[1] for a in case.anchors] == pytest.approx([6.0, 6.0])
        forces.append(np.array([a.force for a in case.anchors]))
    assert forces[0] == pytest.approx(forces[1], rel=1e-9, abs=1e-9)
    assert forces[2] == pytest.approx(forces[1], rel=1e-9, abs=1e-9)
    pulls, along = -forces[1][:, 1], np.abs(forces[1][:, 0])
    if model == "rigid":
        assert pulls == pytest.approx([50.0, 50.0], rel=1e-6)
        assert along == pytest.approx([0.0, 0.0], abs=1e-6)
    else:
        assert np.all(along < 0.1 * pulls)


def _side(model: str, anchored: bool, push: float) -> dict:
    doc = {
        "furncheck": 1, "name": "side", "model": model,
        "material": {"thickness": 18, "friction": 0.5},
        "planks": [{"id": "side", "size": [1800, 300], "center": [0, 170, 900],
                    "rotation": [0, -90, 0]}],
        "walls": [{"point": [0, 0, 0], "normal": [0, 1, 0]}],
        "loads": [{"plank": "side", "force": [0, push, 0], "at": [0, 170, 1800]}],
    }
    if anchored:
        doc["anchors"] = [{"plank": "side", "at": [0, 20, 1750], "wall": 0, "capacity": 400}]
    return doc


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_a_pushed_side_topples_free_at_w_d_over_h_and_holds_anchored(model):
    weight = DENSITY * 1.8 * 0.3 * 0.018 * G
    tipping = weight * 150.0 / 1800.0                       # W d / h = 5.96 N
    assert check_design(_parse(_side(model, False, 0.9 * tipping))).cases[0].stable
    free = check_design(_parse(_side(model, False, 1.1 * tipping))).cases[0]
    assert free.stability == "lift-off"
    held = check_design(_parse(_side(model, True, 10.0))).cases[0]
    assert held.stable
    (anchor,) = held.anchors
    assert anchor.force[1] < 0.0                        # the wall pulls the side back
    # the whole force system's moment about the front edge (y = 320, z = 0): zero
    arm = [(anchor.point, anchor.force)] + [(c.point, c.force) for c in held.contacts]
    restoring = sum((p[1] - 320.0) * f[2] - p[2] * f[1] for p, f in arm)   # N mm
    assert restoring == pytest.approx(10.0 * 1800.0 - weight * 150.0, rel=1e-6)


@pytest.mark.parametrize("anchors, message", [
    ([{"plank": "cleat", "at": [0, 0, 1070], "wall": 3, "capacity": 400}],
     "anchors[0].wall: no wall 3 (the design has walls 0 to 0)"),
    ([{"plank": "cleat", "at": [0, 0, 1300], "wall": 0, "capacity": 400}],
     "anchors[0].at: point (0, 0, 1300) is not on plank"),
    ([{"plank": "cleat", "at": [0, 0, 1070], "wall": 0, "capacity": 0}],
     "anchors[0].capacity: must be positive"),
    ([{"plank": "clet", "at": [0, 0, 1070], "wall": 0, "capacity": 400}],
     "anchors[0].plank: unknown plank"),
    ([{"plank": "cleat", "at": [0, 0, 1070], "wall": 0}],
     'anchors[0].capacity: missing required key "capacity"'),
    ([{"plank": "cleat", "at": [0, 0, 1070], "wall": 0.5, "capacity": 400}],
     "anchors[0].wall: no wall 0.5"),
])
def test_bad_anchors_give_one_line_and_exit_2(tmp_path, anchors, message):
    doc = _cleat_shelf("rigid")
    doc["anchors"] = anchors
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(doc, sort_keys=False))
    result = CliRunner().invoke(main, ["validate", str(path)])
    assert result.exit_code == 2, result.output
    assert message in result.output
    assert "Traceback" not in result.output and f"{path}:" in result.output


def test_an_anchor_without_walls_is_refused(tmp_path):
    doc = _cleat_shelf("rigid")
    del doc["walls"]
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(doc, sort_keys=False))
    result = CliRunner().invoke(main, ["validate", str(path)])
    assert result.exit_code == 2
    assert "the design has no walls" in result.output


def test_anchors_round_trip_and_ride_with_their_plank(tmp_path):
    """Written and read back: the same anchors and verdict; a DOF edit of the anchored
    plank carries its anchors along (as loads ride on their planks)."""
    from furncheck.design import load_design, write_design
    from furncheck.dofs import apply_dof, parse_dof, structure

    design = _parse(_cleat_shelf("rigid"))
    path = tmp_path / "written.yaml"
    write_design(design, str(path))
    again = load_design(str(path))
    assert again.anchors == pytest.approx(design.anchors) or again.anchors == design.anchors
    assert check_design(again).valid == check_design(design).valid
    geometry = analyze(design)
    moved = apply_dof(design, structure(design, geometry), parse_dof(design, "cleat.x"), 30.0)
    assert [a.point[0] for a in moved.anchors] == pytest.approx([-0.17, 0.23])


def test_suggest_on_an_overloaded_anchored_shelf_writes_only_valid_designs(tmp_path):
    path = tmp_path / "shelf.yaml"
    path.write_text(yaml.safe_dump(_cleat_shelf("rigid", load_kg=40.0, capacity=500.0)))
    assert_suggestions_validate(path)


def test_an_edit_that_moves_an_anchor_off_its_wall_is_no_design():
    """An anchor rides with its plank, but its wall stays: an edit that takes the point
    farther from the wall than drawn (or into it) by more than the tolerance would need
    another bracket (``edit_check.design_problem``); one along the wall keeps it."""
    from dataclasses import replace

    from furncheck.edit_check import design_problem

    design = _parse(_cleat_shelf("rigid"))
    assert design.anchors[0].gap == pytest.approx(0.0)
    assert design_problem(design) is None
    along = replace(design, anchors=(replace(design.anchors[0], point=(0.1, 0.0, 1.07)),
                                     design.anchors[1]))
    assert design_problem(along) is None
    off = replace(design, anchors=(replace(design.anchors[0], point=(-0.2, 0.005, 1.07)),
                                   design.anchors[1]))
    assert design_problem(off) == "anchors[0] would move 5 mm off wall 0"


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_a_warm_start_keeps_a_pulling_anchor_holding(model):
    """The side anchored at the top, pushed back towards the wall with 3 N: its anchor
    pulls or pushes, it never lifts; started from the solved case's holding contacts, or
    from the solved case itself (as range and suggest start edits), the result is the cold
    one."""
    from furncheck.check import case_statics
    from furncheck.statics import build_model, external_forces, solve_case

    design = _parse(_side(model, True, -3.0))
    geometry = analyze(design)
    model_ = build_model(design, geometry)
    (solved,) = case_statics(design, geometry)
    assert solved.holding[model_.contact_anchored].all()
    f = external_forces(model_, design.load_cases[0])
    cold = solve_case(model_, f)
    for warm in (solve_case(model_, f, solved.holding), solve_case(model_, f, near=solved)):
        assert np.abs(cold.contact_forces - warm.contact_forces).max() \
            <= 1e-9 * np.abs(f).sum()


def _catalog_bookcase(push: float | None = None, anchored: bool = True) -> dict:
    """designs/bookcase-anchored.yaml as a plain document, optionally without its anchors
    and with another push in its ``push`` case."""
    from pathlib import Path

    path = Path(__file__).resolve().parents[1] / "designs" / "bookcase-anchored.yaml"
    doc = yaml.safe_load(path.read_text(encoding="utf-8"))
    if not anchored:
        del doc["anchors"]
    if push is not None:
        (load,) = doc["load_cases"]["push"]["loads"]
        load["force"] = [0.0, push, 0.0]
    return doc


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_the_catalog_bookcase_topples_without_its_anchors(model):
    """The catalog's anchored bookcase (designs/bookcase-anchored.yaml), its anchors
    removed: its 843.7 N (26.0 kg of MDF and 60 kg of books, W) act d = 150 mm behind the
    front edge of its feet, and the push acts h = 1800 mm up, so it tips once
    P h > W d, at P = W d / h = 70.3 N: the file's 222 N push topples it (lift-off)
    while its books alone stand, 90 % of 70.3 N stands and 110 % topples.  With the
    anchors the same push holds (the catalog test)."""
    weight = (26.0007 + 60.0) * G
    tipping = weight * 150.0 / 1800.0
    assert tipping == pytest.approx(70.3, abs=0.05)
    report = check_design(_parse(_catalog_bookcase(anchored=False) | {"model": model}))
    stability = {case.name: case.stability for case in report.cases}
    assert stability == {"default": "stable", "push": "lift-off"}
    assert {(v.kind, v.case) for v in report.violations} == {("lift-off", "push")}
    for factor, expected in ((0.9, "stable"), (1.1, "lift-off")):
        doc = _catalog_bookcase(push=factor * tipping, anchored=False) | {"model": model}
        (push,) = [c for c in check_design(_parse(doc)).cases if c.name == "push"]
        assert push.stability == expected, factor
    anchored = check_design(_parse(_catalog_bookcase() | {"model": model}))
    assert anchored.valid, [v.message for v in anchored.violations]


def test_the_text_summary_names_the_worst_anchor(tmp_path):
    """A valid anchored design's summary line says its most used anchor, as it says its
    worst joint (the anchors may be nearer their capacity than any nail)."""
    path = tmp_path / "shelf.yaml"
    path.write_text(yaml.safe_dump(_cleat_shelf("rigid", load_kg=5.0)))
    result = CliRunner().invoke(main, ["validate", str(path)])
    assert result.exit_code == 0, result.output
    report = check_design(_parse(_cleat_shelf("rigid", load_kg=5.0)))
    worst = max(a.utilization for a in report.cases[0].anchors)
    assert f"worst anchor anchors[0] (cleat) at {round(100 * worst)} %" in result.output


TALL_UNIT = """\
furncheck: 1
name: tall-wall
units: mm
walls: [{point: [0, -160, 0], normal: [0, 1, 0]}]
planks:
  - {id: side_l, size: [1800, 300], center: [-306, 0, 900], rotation: [0, -90, 0]}
  - {id: side_r, size: [1800, 300], center: [306, 0, 900], rotation: [0, -90, 0]}
  - {id: bottom, size: [600, 300], center: [0, 0, 60]}
  - {id: top, size: [600, 300], center: [0, 0, 1794]}
loads:
  - {plank: bottom, mass: 10, spread: true}
load_cases:
  child:
    - {plank: top, force: [0, 150, 0], at: [0, 150, 1794]}
"""


def test_a_unit_that_topples_and_sags_gets_an_anchor_with_a_thicker_board():
    """A 1.8 m unit 10 mm in front of a wall (elastic): a child pulling its top forward
    (150 N) topples it, and its 12 mm bottom sags under 10 kg.  The anchor rule repairs
    toppling only, yet applies: its candidate then fails by the sag alone, which thicker
    boards finish (as for a support plank), so the fix is to screw the top to the wall
    and use a thicker bottom, and its file validates (before, 'not applicable: it does
    not repair sagging', and no suggestion at all)."""
    design = parse_design(TALL_UNIT, "tall.yaml", "yaml")
    kinds = {v.kind for v in check_design(design, analyze(design)).violations}
    assert kinds == {"lift-off", "sagging"}
    result = suggest_design(design)
    anchored = [s for s in result.suggestions if s.rule == "anchor"]
    assert anchored
    fix = anchored[0]
    assert "make bottom" in fix.advice and fix.design.anchors
    assert fix.design.plank("bottom").thickness > design.plank("bottom").thickness
    assert check_design(parse_design(fix.text, "s.yaml", "yaml")).valid


CATALOG_WALL_SHELF = "designs/wall-shelf.yaml"


@pytest.mark.parametrize("friction", [None, 0.0])
def test_the_summary_says_how_much_the_walls_friction_holds_up(friction, tmp_path):
    """designs/wall-shelf.yaml: an 800 x 250 x 18 mm shelf (26.49 N) on two 150 x 120
    cleats (2.38 N each), 15 kg of books (147.15 N): its supports hold up W = 178.4 N,
    the anchors' vertical forces V and the friction of the cleats' feet where they bear
    on the wall, W - V (a wall's normal is level: the vertical part of its force is
    friction; the split is the stiffnesses').  The valid line names the worst anchor and
    that friction, 'with the wall's friction holding up F N of its 178 N of weight and
    loads', F = W - V of the
    reported anchors: the anchors' margin counts on it.  With ``friction: 0`` the anchors
    hold up all of W and the line says nothing of it: each holds W / 2 = 89.2 N up and
    pulls (M - W x 9 mm) / 90 mm / 2 = 111.9 N (the design's header: M = 2 x 2.38 x 9 +
    (26.49 + 147.15) x 125 = 21,748 N mm about the cleats' feet, the screws 90 mm above
    them and 9 mm in front of the wall), 143.1 N in all, 73 % of 196 N: still valid."""
    doc = yaml.safe_load((Path(__file__).resolve().parents[1] / CATALOG_WALL_SHELF)
                         .read_text())
    if friction is not None:
        doc["material"]["friction"] = friction
    path = tmp_path / "wall-shelf.yaml"
    path.write_text(yaml.safe_dump(doc, sort_keys=False))
    weight = 26.49 + 2 * 2.38 + 15 * G
    assert weight == pytest.approx(178.4, abs=0.05)
    report = check_design(_parse(doc))
    (case,) = report.cases
    held_by_anchors = sum(a.force[2] for a in case.anchors)
    result = CliRunner().invoke(main, ["validate", str(path)])
    assert result.exit_code == 0, result.output
    if friction is None:
        by_wall = weight - held_by_anchors
        assert 0.05 * weight < by_wall < weight
        assert (f"with the wall's friction holding up {round(by_wall)} N of its "
                f"{round(weight)} N of weight and loads)") in result.output
    else:
        assert held_by_anchors == pytest.approx(weight, rel=1e-3)
        assert "wall's friction" not in result.output
        moment = 2 * 2.38 * 9 + (26.49 + 15 * G) * 125
        pull = (moment - weight * 9) / 90 / 2
        assert pull == pytest.approx(111.9, abs=0.05)
        for anchor in case.anchors:
            assert -anchor.force[1] == pytest.approx(pull, rel=0.02)
            assert anchor.utilization == pytest.approx(np.hypot(weight / 2, pull) / 196.0,
                                                       rel=0.02)


@pytest.mark.parametrize(("share", "said"), [(0.049, False), (0.051, True)])
def test_the_walls_friction_is_said_from_its_share_of_what_is_held_up(share, said):
    """WALL_FRICTION_SHARE (5 %): a case whose supports hold up 1000 N, the wall's
    contacts' vertical forces (friction: a wall's normal is level) ``share`` of it, an
    anchor and the floor the rest (a resting joint's corner, inside the design, does not
    count): said from 5 %, not below."""
    from furncheck.report.text import _wall_friction_phrase
    from furncheck.result import AnchorResult, CaseResult, ContactResult

    wall = 1000.0 * share
    case = CaseResult("default", True, True, (), (
        ContactResult("back", (0, 0, 0), (0.0, 50.0, wall / 2), wall=0),
        ContactResult("back", (1, 0, 0), (0.0, 50.0, wall / 2), wall=0),
        ContactResult("foot", (0, 1, 0), (0.0, 0.0, 400.0)),
        ContactResult("shelf", (0, 2, 0), (0.0, 0.0, 999.0), on="foot")),
        anchors=(AnchorResult("back", 0, (0, 0, 1), (0.0, -100.0, 600.0 - wall), 620.0,
                              196.0, 3.2, 0),))
    phrase = _wall_friction_phrase(case)
    assert bool(phrase) is said
    if said:
        assert phrase == (", with the wall's friction holding up 51 N of its 1000 N of "
                          "weight and loads")
