"""Walls (contract section 2): vertical planes a design may lean on, unilateral contacts
with friction like the ground, corners behind them penetrating.

The hand check is the ladder leaning on a wall with friction mu at the floor and at the
wall.  With the foot contact at horizontal distance x_f from the wall, the wall contact at
height h and the weight W acting d = x_f - c_x in front of the foot (c_x the centre's
distance from the wall):

    x:  N_w = F_f            z:  N_f + F_w = W
    moments about the foot:  d W = h N_w + x_f F_w

An equilibrium inside both friction cones (|F_f| <= mu N_f, |F_w| <= mu N_w) exists iff
the one with both frictions at their limit balances the weight's moment:

    d <= mu (h + mu x_f) / (1 + mu^2)

(for a thin ladder of length L at angle theta: tan theta >= (1 - mu^2) / (2 mu), 36.87
degrees for mu = 0.5; for the 1000 x 12 mm plank below, whose weight acts T/2 off the face
it leans on, x_f = L cos theta, h = L sin theta, d = L/2 cos theta - T/2 sin theta: 36.46
degrees).  The ladder leans on 2 corners on the floor and 2 on the wall.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import yaml
from cli_checks import assert_suggestions_validate
from click.testing import CliRunner

from furncheck.check import check_design
from furncheck.cli.main import main
from furncheck.design import parse_design
from furncheck.geometry import analyze

LENGTH, WIDTH, THICK = 1000.0, 300.0, 12.0
MU = 0.5


def _ladder(angle: float, turn: float = 0.0, shift=(0.0, 0.0), model: str = "rigid",
            wall_normal=None, extra: dict | None = None) -> dict:
    """A plank leaning at ``angle`` degrees from the floor on the wall x = 0 (normal +x),
    all of it turned by ``turn`` degrees about the vertical through the origin and moved
    by ``shift`` (mm)."""
    theta = math.radians(angle)
    cx = LENGTH / 2 * math.cos(theta) + THICK / 2 * math.sin(theta)
    cz = LENGTH / 2 * math.sin(theta) + THICK / 2 * math.cos(theta)
    c, s = math.cos(math.radians(turn)), math.sin(math.radians(turn))
    center = [c * cx + shift[0], s * cx + shift[1], cz]
    normal = wall_normal or [round(c, 15), round(s, 15), 0.0]
    doc = {"furncheck": 1, "name": f"ladder-{angle:g}", "model": model,
           "material": {"thickness": THICK, "friction": MU},
           "planks": [{"id": "ladder", "size": [LENGTH, WIDTH], "center": center,
                       "rotation": [0.0, angle, turn]}],
           "walls": [{"point": [shift[0], shift[1], 0.0], "normal": normal}]}
    doc.update(extra or {})
    return doc


def _design(doc: dict):
    return parse_design(yaml.safe_dump(doc), "ladder.yaml", "yaml")


def _predicted_stable(angle: float) -> bool:
    """The module docstring's condition, with the contact points of the real plank (its
    foot and its top on the face towards the floor and the wall)."""
    theta = math.radians(angle)
    x_f = LENGTH * math.cos(theta)                                # foot corner from the wall
    h = LENGTH * math.sin(theta)                                  # wall corner's height
    c_x = LENGTH / 2 * math.cos(theta) + THICK / 2 * math.sin(theta)
    return x_f - c_x <= MU * (h + MU * x_f) / (1 + MU * MU)


@pytest.mark.parametrize("model", ["rigid", "elastic"])
@pytest.mark.parametrize("angle", [30.0, 34.0, 36.3, 36.6, 40.0, 60.0])
def test_a_ladder_holds_exactly_where_friction_at_floor_and_wall_can(angle, model):
    design = _design(_ladder(angle, model=model))
    geometry = analyze(design)
    assert sorted(c.wall is not None for c in geometry.contacts) == [False, False, True, True]
    assert not geometry.violations
    case = check_design(design, geometry).cases[0]
    assert case.stable == _predicted_stable(angle)
    assert case.stability == ("stable" if _predicted_stable(angle) else "sliding")
    if case.stable:
        weight = design.material.density * LENGTH * WIDTH * THICK * 1e-9 * 9.81
        total = np.sum([c.force for c in case.contacts], axis=0)
        assert total == pytest.approx([0.0, 0.0, weight], abs=1e-9 * weight)
        for contact in case.contacts:
            force = np.array(contact.force)
            normal = np.array([1.0, 0.0, 0.0]) if contact.wall == 0 else np.array([0, 0, 1.0])
            pressing = float(force @ normal)
            assert pressing >= -1e-9 * weight              # walls and floor only push
            assert np.linalg.norm(force - pressing * normal) <= MU * pressing + 1e-9 * weight


def test_the_wall_takes_what_the_equilibrium_needs():
    """At 60 degrees the ladder is far inside its friction: both supports' forces still
    balance the weight's moment about the foot, d W = h N_w + x_f F_w (the contact forces
    summed per support, about the actual contact points)."""
    design = _design(_ladder(60.0))
    case = check_design(design).cases[0]
    weight = sum(c.force[2] for c in case.contacts)
    foot = [c for c in case.contacts if c.wall is None]
    top = [c for c in case.contacts if c.wall == 0]
    x_f = foot[0].point[0]
    moment_wall = sum(c.point[2] * c.force[0] - (c.point[0] - x_f) * c.force[2] for c in top)
    centre_x = design.planks[0].center[0] * 1000.0
    assert moment_wall == pytest.approx((x_f - centre_x) * weight, rel=1e-9)
    assert all(c.point[0] == pytest.approx(0.0, abs=1e-9) for c in top)


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_a_board_pressed_flat_on_a_wall_needs_its_weight_in_friction(model):
    """A 300 x 200 x 12 mm board flat against the wall y = 0, clear of the floor, pressed
    onto it by P at its centre: it holds iff mu P >= W, W = 750 x 0.3 x 0.2 x 0.012 x 9.81
    = 5.297 N.  At P = 10.2 N (mu P = 5.1 N) it slides, and the message gives the wall's
    need as W against mu P in both models (the elastic board's corners also pull against
    each other along the wall, and those forces cancel: they once read 95.7 N)."""
    weight = 750.0 * 0.3 * 0.2 * 0.012 * 9.81
    for push, expected in ((11.0, "stable"), (10.2, "sliding")):
        doc = {"furncheck": 1, "name": "pressed", "model": model,
               "material": {"thickness": 12, "friction": MU},
               "walls": [{"point": [0, 0, 0], "normal": [0, 1, 0]}],
               "planks": [{"id": "board", "size": [300, 200], "center": [0, 6, 1000],
                           "rotation": [90, 0, 0]}],
               "loads": [{"plank": "board", "force": [0, -push, 0], "at": [0, 12, 1000]}]}
        report = check_design(_design(doc))
        assert report.cases[0].stability == expected, push
        if expected == "sliding":
            message = report.violations[0].message
            assert f"the wall must hold {weight:.4g} N along its face" in message
            assert f"friction gives at most {MU * push:.3g} N" in message


@pytest.mark.parametrize("turn, shift", [(30.0, (100.0, -250.0)), (-135.0, (0.0, 40.0))])
def test_turning_and_moving_design_and_wall_together_changes_nothing(turn, shift):
    """A rigid motion about the vertical of the design with its wall: the same verdict and
    the same contact force sizes."""
    for angle in (34.0, 45.0):
        plain = check_design(_design(_ladder(angle))).cases[0]
        moved = check_design(_design(_ladder(angle, turn, shift))).cases[0]
        assert moved.stability == plain.stability
        sizes = sorted(float(np.linalg.norm(c.force)) for c in plain.contacts)
        assert sorted(float(np.linalg.norm(c.force)) for c in moved.contacts) == \
            pytest.approx(sizes, rel=1e-6, abs=1e-9)


def test_a_corner_behind_the_wall_penetrates_it():
    doc = _ladder(45.0)
    doc["walls"][0]["point"] = [5.0, 0.0, 0.0]            # the wall 5 mm into the top
    design = _design(doc)
    kinds = [(v.kind, v.where) for v in analyze(design).violations]
    assert ("penetration", "ladder") in kinds
    message = next(v.message for v in analyze(design).violations if v.kind == "penetration")
    assert "behind wall 0" in message and "5 mm" in message


def test_a_plank_held_only_by_walls_and_the_floor_is_not_floating():
    design = _design(_ladder(45.0))
    assert analyze(design).grounded == (True,)


def test_the_json_report_names_the_wall(tmp_path):
    path = tmp_path / "ladder.yaml"
    path.write_text(yaml.safe_dump(_ladder(45.0)))
    result = CliRunner().invoke(main, ["validate", str(path), "--format", "json"])
    assert result.exit_code == 0, result.output
    contacts = json.loads(result.output)["reports"][0]["cases"][0]["contacts"]
    assert sorted(c.get("wall") for c in contacts if "wall" in c) == [0, 0]
    assert sum("wall" not in c for c in contacts) == 2


def test_a_design_with_walls_round_trips_through_its_file(tmp_path):
    from furncheck.design import load_design, write_design

    design = _design(_ladder(40.0, turn=20.0))
    path = tmp_path / "written.yaml"
    write_design(design, str(path))
    again = load_design(str(path))
    assert len(again.walls) == 1
    assert again.walls[0].normal == pytest.approx(design.walls[0].normal, abs=1e-12)
    assert check_design(again).cases[0].stability == check_design(design).cases[0].stability


@pytest.mark.parametrize("walls, message", [
    ([{"point": [0, 0, 0], "normal": [0, 0, 0]}], "walls[0].normal: zero-length normal"),
    ([{"point": [0, 0, 0], "normal": [1, 0, 0.5]}], "walls[0].normal: a wall is vertical"),
    ([{"point": [0, 0, 0]}], 'walls[0].normal: missing required key "normal"'),
    ([{"point": [0, 0], "normal": [1, 0, 0]}], "walls[0].point: expected 3 numbers"),
    ([{"point": [0, 0, 0], "normal": [1, 0, 0], "height": 3}], "walls[0]"),
    ({"point": [0, 0, 0]}, "walls: expected a list"),
])
def test_bad_walls_give_one_line_and_exit_2(tmp_path, walls, message):
    doc = _ladder(45.0)
    doc["walls"] = walls
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(doc, sort_keys=False))
    result = CliRunner().invoke(main, ["validate", str(path)])
    assert result.exit_code == 2
    assert message in result.output
    assert "Traceback" not in result.output
    assert f"{path}:" in result.output


def test_range_and_suggest_run_on_a_leaning_design(tmp_path):
    """The ladder at 34 degrees slides; ``suggest`` writes only designs that validate (it
    may find none), and ``range`` of its tilt gives an interval or a reason."""
    path = tmp_path / "ladder.yaml"
    path.write_text(yaml.safe_dump(_ladder(34.0)))
    assert_suggestions_validate(path, "ladder.ry")


def test_range_of_a_leaning_plank_starts_at_the_hand_threshold(tmp_path):
    """``range ladder.ry`` of the sliding ladder at 30 degrees: its ends stay on the floor
    and on the wall as it turns (the wall is a support plane of the DOF structure), and
    the valid interval starts where the module docstring's condition holds: 36.46
    degrees (within the range search's resolution)."""
    path = tmp_path / "ladder.yaml"
    path.write_text(yaml.safe_dump(_ladder(30.0)))
    result = CliRunner().invoke(main, ["range", str(path), "ladder.ry", "--format", "json"])
    assert result.exit_code == 0, result.output
    (entry,) = json.loads(result.output)["ranges"]
    low, high = entry["valid"]
    assert 36.46 <= low <= 36.6
    assert high > 80.0
    blocked = CliRunner().invoke(main, ["range", str(path), "ladder.x", "--format", "json"])
    assert "leans on wall 0" in json.loads(blocked.output)["ranges"][0]["reason"]
