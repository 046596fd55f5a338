"""Resting joints (``type: rests``, contract section 2): a plank lying on another without
nails, held by contact and friction only, in both models.

The test frame: two 700 x 300 x 18 mm sides standing on the floor, nailed to a bottom
stretcher, and a loose top (18 mm MDF, 750 kg/m^3) lying on the sides' top edges.  Each
resting joint is four contact corners where a side's end face lies on the top's face.

* A loose top pushed sideways at its own height (no arm to tip it over its supports)
  slides on the sides once the push passes what friction on them can hold, mu W_top:
  the sides press on it with W_top in all, friction gives at most mu W_top.  The frame
  stands meanwhile (the floor holds mu (W_top + W_frame), more).  For the 700 x 300 top
  W_top = 750 x 0.7 x 0.3 x 0.018 x 9.81 = 27.81 N, mu W_top = 13.9 N at mu = 0.5.
* A 900 mm top overhanging the right side by 300 mm, pressed down at x_p = 590 mm, tips
  about the right side's outer edge (x_e = 300 mm) once P (x_p - x_e) > W_top (x_e - x_c),
  x_c = 150 mm its centre: P = 35.76 N x 150 / 290 = 18.50 N; beyond it the top lifts off
  the left side (``lift-off``).
"""

from __future__ import annotations

import copy
import json
import re

import numpy as np
import pytest
import yaml
from cli_checks import assert_suggestions_validate
from click.testing import CliRunner

from furncheck.check import check_design
from furncheck.cli.main import main
from furncheck.design import parse_design
from furncheck.geometry import analyze

G, DENSITY, MU = 9.81, 750.0, 0.5

FRAME = {
    "furncheck": 1, "name": "loose-top",
    "material": {"thickness": 18, "friction": MU},
    "planks": [
        {"id": "side_l", "size": [700, 300], "center": [-291, 0, 350], "rotation": [0, -90, 0]},
        {"id": "side_r", "size": [700, 300], "center": [291, 0, 350], "rotation": [0, -90, 0]},
        {"id": "bottom", "size": [564, 300], "center": [0, 0, 109]},
        {"id": "top", "size": [700, 300], "center": [0, 0, 709]},
    ],
    "joints": [["side_l", "bottom"], ["side_r", "bottom"],
               {"planks": ["top", "side_l"], "type": "rests"},
               {"planks": ["top", "side_r"], "type": "rests"}],
}


def _design(model: str, loads: list, top=None):
    doc = copy.deepcopy(FRAME)
    doc["model"] = model
    doc["loads"] = loads
    if top is not None:
        doc["planks"][3] = top
    return parse_design(yaml.safe_dump(doc, sort_keys=False), "rests.yaml", "yaml")


def _top_weight(length: float) -> float:
    return DENSITY * length * 0.3 * 0.018 * G / 1000.0


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_a_loose_top_slides_at_mu_times_its_weight(model):
    threshold = MU * _top_weight(700.0)
    assert threshold == pytest.approx(13.90, abs=0.01)
    for factor, expected in ((0.9, "stable"), (1.1, "sliding")):
        push = factor * threshold
        design = _design(model, [{"plank": "top", "force": [push, 0, 0], "at": [350, 0, 709]}])
        report = check_design(design)
        (case,) = report.cases
        assert case.stability == expected, factor
        if expected == "sliding":
            (violation,) = report.violations
            assert "top slides on side_l; top slides on side_r" in violation.message
            # the joint that needs most: more sideways force than its own mu N
            needed, capacity = (float(x) for x in re.search(
                r"must pass on ([\d.]+) N along its faces, its friction gives at most "
                r"([\d.]+) N", violation.message).groups())
            assert needed > capacity and capacity < threshold
            assert set(violation.where.split(",")) == {"side_l", "side_r", "top"}
            continue
        resting = [c for c in case.contacts if c.on == "top"]
        assert len(resting) == 8 and {c.plank for c in resting} == {"side_l", "side_r"}
        # the top's force on the sides: its weight down, the push along x
        total = np.sum([c.force for c in resting], axis=0)
        assert total == pytest.approx([push, 0.0, -_top_weight(700.0)],
                                      abs=1e-6 * _top_weight(700.0))
        assert all(c.force[2] <= 1e-9 for c in resting)            # it only presses


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_a_top_loaded_on_its_overhang_lifts_off_its_far_support(model):
    """Beyond the tipping load (module docstring) the message names the least pull that
    would hold the top down, by statics in the plane of its rests, the same in both
    models: at the far corners (the left side's outer edge, x = -300 mm, a = 600 mm from
    the tipping edge), Q = (P (x_p - x_e) - W_top (x_e - x_c)) / a.  (The elastic model's
    bolted solve puts its corners' couples there instead, thousands of newtons.)"""
    top = {"id": "top", "size": [900, 300], "center": [150, 0, 709]}
    threshold = _top_weight(900.0) * (300.0 - 150.0) / (590.0 - 300.0)
    assert threshold == pytest.approx(18.50, abs=0.01)
    for factor, expected in ((0.9, "stable"), (1.1, "lift-off")):
        load = [{"plank": "top", "force": [0, 0, -factor * threshold], "at": [590, 0, 718]}]
        report = check_design(_design(model, load, top))
        assert report.cases[0].stability == expected, factor
        if expected == "lift-off":
            (violation,) = report.violations
            assert violation.kind == "lift-off" and "top lifts off side_l" in violation.message
            hold = (factor * threshold * (590.0 - 300.0)
                    - _top_weight(900.0) * (300.0 - 150.0)) / 600.0
            pull = re.search(r"held down at side_l, its rests would have to pull at least "
                             r"([\d.]+) N there", violation.message)
            assert float(pull.group(1)) == pytest.approx(hold, rel=0.005)


def test_resting_contacts_are_reported_with_the_plank_that_presses(tmp_path):
    doc = copy.deepcopy(FRAME) | {"loads": [{"plank": "top", "mass": 5}]}
    path = tmp_path / "top.yaml"
    path.write_text(yaml.safe_dump(doc, sort_keys=False))
    result = CliRunner().invoke(main, ["validate", str(path), "--format", "json"])
    assert result.exit_code == 0, result.output
    contacts = json.loads(result.output)["reports"][0]["cases"][0]["contacts"]
    resting = [c for c in contacts if "on" in c]
    assert len(resting) == 8 and {c["on"] for c in resting} == {"top"}
    assert all(c["point"][2] == pytest.approx(700.0) for c in resting)


def test_a_resting_joint_has_no_nails_and_does_not_join_the_groups():
    """The top is its own group (no nails), grounded through what it rests on; the sides'
    and the bottom's nailed joints are the only joints."""
    design = _design("rigid", [])
    geometry = analyze(design)
    assert not geometry.violations
    assert [j.planks for j in geometry.joints] == [("side_l", "bottom"), ("side_r", "bottom")]
    assert len(geometry.components) == 2 and all(geometry.grounded)


@pytest.mark.parametrize("joint, message", [
    ({"planks": ["top", "side_l"], "type": "glued"}, "joints[2].type: unknown joint type"),
    ({"planks": ["top", "side_l"], "type": "rests", "nails": 4},
     "joints[2].nails: a joint of type rests has no nails"),
])
def test_bad_resting_joints_give_one_line_and_exit_2(tmp_path, joint, message):
    doc = copy.deepcopy(FRAME) | {"loads": [{"plank": "top", "mass": 5}]}
    doc["joints"][2] = joint
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(doc, sort_keys=False))
    for command in (["validate", str(path)], ["range", str(path)], ["suggest", str(path)]):
        result = CliRunner().invoke(main, command)
        assert result.exit_code == 2, (command, result.output)
        assert message in result.output and "Traceback" not in result.output


def test_a_resting_joint_whose_planks_do_not_touch_is_disconnected(tmp_path):
    """Contract section 2: a listed joint whose planks do not touch within the tolerance
    is disconnected -- a resting one too (it was an input error, exit 2): the design is
    invalid (exit 1), with the gap, and suggest and range run on it (exit 0)."""
    doc = copy.deepcopy(FRAME) | {"loads": [{"plank": "top", "mass": 5}]}
    doc["joints"][2] = {"planks": ["top", "bottom"], "type": "rests"}
    path = tmp_path / "apart.yaml"
    path.write_text(yaml.safe_dump(doc, sort_keys=False))
    result = CliRunner().invoke(main, ["validate", str(path), "--format", "json"])
    assert result.exit_code == 1, result.output
    (report,) = json.loads(result.output)["reports"]
    (apart,) = [v for v in report["violations"] if v["where"] == "top/bottom"]
    assert apart["kind"] == "disconnected" and "do not touch" in apart["message"]
    for command in (["range", str(path), "top.z"], ["suggest", str(path)]):
        result = CliRunner().invoke(main, command)
        assert result.exit_code == 0, (command, result.output)


def test_a_plank_lying_flat_on_another_is_named_so():
    """Two boards lying face to face form no joint (a joint is an end on a face): the
    disconnected message says so, not that their corners are 70 mm apart."""
    design = parse_design(
        "furncheck: 1\nplanks:\n"
        "  - {id: bottom, size: [400, 300], center: [0, 0, 6]}\n"
        "  - {id: top, size: [300, 200], center: [0, 0, 18]}\n"
        "joints:\n  - {planks: [top, bottom], type: rests}\n", "stack.yaml", "yaml")
    (apart,) = [v for v in analyze(design).violations if v.kind == "disconnected"]
    assert apart.where == "top/bottom"
    assert apart.message.startswith("top lies flat on bottom, face to face")


def test_resting_joints_round_trip_through_a_written_file(tmp_path):
    from furncheck.design import load_design, write_design

    design = _design("rigid", [{"plank": "top", "mass": 5}])
    path = tmp_path / "written.yaml"
    write_design(design, str(path))
    again = load_design(str(path))
    assert [j.rests for j in again.joints] == [False, False, True, True]
    assert check_design(again).valid == check_design(design).valid


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_suggest_on_a_sliding_top_writes_only_designs_that_validate(tmp_path, model):
    doc = copy.deepcopy(FRAME) | {"model": model, "loads": [
        {"plank": "top", "force": [15.0, 0, 0], "at": [350, 0, 709]}]}
    path = tmp_path / "top.yaml"
    path.write_text(yaml.safe_dump(doc, sort_keys=False))
    assert_suggestions_validate(path, "top.x", "top.length")


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_a_block_standing_on_a_board_slides_on_it_at_mu_times_its_weight(model):
    """The other way round: the edge plank on top.  A 200 x 300 x 18 mm block stands on
    its 300 mm end on a board lying on the floor (it rests on the board's face), pushed
    along its width at its top: it tips at W x 150 / 200 = 0.75 W, so it slides first, at
    mu W = 3.973 N (W = 750 x 0.2 x 0.3 x 0.018 x 9.81 = 7.946 N).  The message gives the
    force the joint must pass on, its corners' forces summed, against mu W."""
    weight = DENSITY * 0.2 * 0.3 * 0.018 * G
    for factor, expected in ((0.9, "stable"), (1.1, "sliding")):
        doc = {"furncheck": 1, "name": "block", "model": model,
               "material": {"thickness": 18, "friction": MU},
               "planks": [{"id": "board", "size": [600, 400], "center": [0, 0, 9]},
                          {"id": "block", "size": [200, 300], "center": [0, 0, 118],
                           "rotation": [0, -90, 0]}],
               "joints": [{"planks": ["block", "board"], "type": "rests"}],
               "loads": [{"plank": "block", "force": [0, factor * MU * weight, 0],
                          "at": [0, 0, 218]}]}
        report = check_design(parse_design(yaml.safe_dump(doc), "block.yaml", "yaml"))
        assert report.cases[0].stability == expected, factor
        if expected == "sliding":
            message = report.violations[0].message
            assert "block slides on board" in message
            assert f"must pass on {1.1 * MU * weight:.3g} N" in message
            assert f"at most {MU * weight:.4g} N" in message


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_a_block_tipping_on_its_resting_joint_is_named_with_the_pull_it_needs(model):
    """A 400 x 300 x 60 mm block stands loose on its 60 x 300 end on a board lying on the
    floor, pushed along x at its top, 400 mm above the board: it tips about its end's edge,
    30 mm from its centre line, once P h > W a (it slides only at mu W, far beyond):
    W = 750 x 0.4 x 0.3 x 0.06 x 9.81 = 52.97 N, P_tip = W x 30 / 400 = 3.973 N.  At
    P = 4.10 N it lifts off: held down, the corners along the far edge would have to pull
    (P h - W a) / 60 mm = (1640 - 1589.2) / 60 = 0.846 N.  The message names the resting
    joint, which presses as a whole (W) but tips about an edge, not the ground."""
    weight = DENSITY * 0.4 * 0.3 * 0.06 * G
    tipping = weight * 30.0 / 400.0
    for push, expected in ((0.97 * tipping, "stable"), (4.10, "lift-off")):
        doc = {"furncheck": 1, "name": "block", "model": model,
               "material": {"thickness": 12, "friction": MU},
               "planks": [{"id": "base", "size": [600, 400], "center": [0, 0, 6]},
                          {"id": "block", "size": [400, 300], "center": [0, 0, 212],
                           "rotation": [0, -90, 0], "thickness": 60}],
               "joints": [{"planks": ["block", "base"], "type": "rests"}],
               "loads": [{"plank": "block", "force": [push, 0, 0], "at": [-30, 0, 412]}]}
        report = check_design(parse_design(yaml.safe_dump(doc), "block.yaml", "yaml"))
        assert report.cases[0].stability == expected, push
        if expected == "lift-off":
            message = report.violations[0].message
            assert "block lifts off base" in message and "support polygon" not in message
            pull = float(re.search(r"held down at base, its rests would have to pull at "
                                   r"least ([\d.]+) N there", message).group(1))
            assert pull == pytest.approx((push * 400.0 - weight * 30.0) / 60.0, rel=0.01)


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_the_force_sensitivity_of_a_resting_top_matches_finite_differences(model):
    """``sensitivity`` on the loose top (pushed with 10 N, below its 13.9 N): for every
    DOF that keeps the contacts, their holding set and the top on its sides, the joint
    wrench and contact force rates (each contact's force in its own frame, as the statics
    reports it: a resting corner's frame turns with the plank it rests on) equal the central
    differences of the full solve, (F(+h) - F(-h)) / 2h, to 1e-4 of the DOF's largest rate
    (plus half the one-sided slopes' spread where they differ by more than 1e-3 of it)."""
    from furncheck.dofs import all_dofs, apply_dof, structure
    from furncheck.edit_check import check_edit
    from furncheck.sensitivity import sensitivity
    from furncheck.statics import build_model, solve_load_case

    design = _design(model, [{"plank": "top", "force": [10, 0, 0], "at": [350, 0, 709]}])
    geometry = analyze(design)
    frame = structure(design, geometry)

    def state(edited):
        statics = solve_load_case(build_model(edited, analyze(edited)), edited.load_cases[0])
        if statics.stability != "stable":
            return None
        return statics, np.concatenate([statics.joint_wrenches.ravel(),
                                        statics.contact_forces.ravel()])

    base, base_forces = state(design)
    sens = sensitivity(design, all_dofs(design), "default")
    compared = 0
    for row, dof in enumerate(sens.dofs):
        h = 1e-3 if dof.is_rotation else 1e-2
        sides = [apply_dof(design, frame, dof, step) for step in (h, -h)]
        if any(check_edit(geometry, side)[0] for side in sides):
            continue
        found = [state(side) for side in sides]
        if any(f is None or not np.array_equal(f[0].holding, base.holding) for f in found):
            continue
        (_, plus), (_, minus) = found
        central = (plus - minus) / (2 * h)
        kink = np.abs((plus - base_forces) / h - (base_forces - minus) / h).max()
        analytic = np.concatenate([sens.joint_wrenches[row].ravel(),
                                   sens.contact_forces[row].ravel()])
        scale = max(np.abs(central).max(), np.abs(analytic).max())
        if scale < 1e-6 * _top_weight(700.0):
            continue
        allowed = 1e-4 * scale + (0.5 * kink if kink > 1e-3 * scale else 0.0)
        assert np.abs(analytic - central).max() <= allowed, dof.name
        compared += 1
    assert compared >= 5


LOOSE_TOP_ON_LEGS = """
furncheck: 1
name: loose-top-on-legs
planks:
  - {id: top, size: [400, 300], center: [0, 0, 450.5], thickness: 25}
  - {id: leg_l, size: [438, 60], center: [-170, 0, 219], rotation: [0, -90, 0]}
  - {id: leg_r, size: [438, 60], center: [170, 0, 219], rotation: [0, -90, 0]}
joints:
  - {planks: [top, leg_l], type: rests}
  - {planks: [top, leg_r], type: rests}
loads:
  - {plank: top, mass: 80, at: [0, 0, 463]}
  - {plank: leg_l, force: [48, 0, 0], at: [-170, 0, 219]}
  - {plank: leg_r, force: [-48, 0, 0], at: [170, 0, 219]}
"""


def test_a_leg_under_a_loose_top_bows_between_its_foot_and_the_top():
    """A 25 mm top lying loose (type: rests) on two 438 x 60 x 12 mm legs, 80 kg on it, the
    legs squeezed inward at mid-height by P = 48 N each.  The top presses each leg's end
    and holds it there by friction: it reaches the floor through the other leg, so it
    carries this one as a nailed top does (contract 3a: sag from the line through the
    two outermost supports that carry the plank), and the leg is a beam pinned at its foot
    and at the top, L = 438 mm, not a cantilever from its foot.  Both ends bear on the
    leg's inner corner line, e = t / 2 = 6 mm off its axis, under N = (80 g + the top's
    weight) / 2 = (784.8 + 22.07) / 2 = 403.4 N: equal end moments N e, bowing it outward
    by N e L^2 / 8EI = 2.239 mm against P's P L^3 / 48EI = 3.242 mm inward (EI = E b t^3 /
    12 = 3000 x 60 x 12^3 / 12 N mm^2), plus P's shear deflection P L / (4 kappa G A) =
    0.011 mm: 1.014 mm, allowed L / 400 = 1.095 mm, and with creep (x 1.5) 1.52 mm:
    sagging.  (Read as a cantilever, the tip's deviation from the foot's tangent, it
    was 0.733 mm against 2 L / 400 = 2.19 mm: valid.)"""
    design = parse_design(LOOSE_TOP_ON_LEGS, "loose.yaml", "yaml")
    material = design.material
    b, t, length = 0.060, 0.012, 0.438
    ei = material.elastic_modulus * b * t ** 3 / 12
    top_weight = material.density * 0.4 * 0.3 * 0.025 * G
    axial = (80 * G + top_weight) / 2
    shear = 48 * length / (4 * (5 / 6) * material.shear_modulus * b * t)
    hand = abs(48 * length ** 3 / (48 * ei) - axial * (t / 2) * length ** 2 / (8 * ei)) + shear
    assert hand == pytest.approx(1.014e-3, abs=2e-6)
    report = check_design(design)
    (case,) = report.cases
    legs = [p for p in case.planks if p.id.startswith("leg")]
    for leg in legs:
        assert leg.sag == pytest.approx(hand * 1000, rel=0.02)
        assert leg.sag_allowed == pytest.approx(438 / 400)
    assert sorted(v.where for v in report.violations if v.kind == "sagging") == [
        "leg_l", "leg_r"]
    assert all("between supports 438 mm apart" in v.message for v in report.violations)


BRACKET_SHELF = """
furncheck: 1
name: bracket-shelf
planks:
  - {id: side_l, size: [800, 300], center: [-306, 0, 400], rotation: [0, -90, 0]}
  - {id: side_r, size: [800, 300], center: [306, 0, 400], rotation: [0, -90, 0]}
  - {id: top, size: [624, 300], center: [0, 0, 806]}
  - {id: bottom, size: [600, 300], center: [0, 0, 60]}
  - {id: arm_f, size: [250, 40], center: [-175, 120, 480], rotation: [90, 0, 0]}
  - {id: arm_b, size: [250, 40], center: [-175, -120, 480], rotation: [90, 0, 0]}
  - {id: board, size: [250, 300], center: [-175, 0, 506]}
joints:
  - [top, side_l]
  - [top, side_r]
  - [side_l, bottom]
  - [side_r, bottom]
  - [side_l, arm_f]
  - [side_l, arm_b]
  - {planks: [board, arm_f], type: rests}
  - {planks: [board, arm_b], type: rests}
loads:
  - {plank: board, mass: 15, spread: true}
"""


def test_an_arm_under_a_loose_board_stays_a_cantilever():
    """Two 250 x 40 mm arms nailed by their ends to a side, a board lying loose on them
    with 15 kg: the board presses each arm down along its bending and holds nothing (the
    arms hold it), so each arm's sag is its free end's deflection from its nail's tangent
    (contract 3a), not the small bow between the nail and the board (0.17 mm), unlike a
    leg whose end bears on a loose top."""
    report = check_design(parse_design(BRACKET_SHELF, "bracket.yaml", "yaml"))
    arms = {v.where: v.message for v in report.violations if v.kind == "sagging"
            and v.where.startswith("arm")}
    assert set(arms) == {"arm_f", "arm_b"}
    assert all("at the free end of its 250 mm overhang" in m for m in arms.values())


PINS = """\
furncheck: 1
name: bookcase-pins
model: {model}
material: {{thickness: 18}}
planks:
  - {{id: side_l, size: [1000, 300], center: [-309, 0, 500], rotation: [0, -90, 0]}}
  - {{id: side_r, size: [1000, 300], center: [309, 0, 500], rotation: [0, -90, 0]}}
  - {{id: top, size: [636, 300], center: [0, 0, 1009]}}
  - {{id: bottom, size: [600, 300], center: [0, 0, 59]}}
  - {{id: shelf_a, size: [598, 300], center: [0, 0, 359]}}
  - {{id: shelf_b, size: [598, 300], center: [0, 0, 679]}}
""" + "".join(
    f"  - {{{{id: pin_{s}{x}{y}, size: [20, 12], center: [{sx}, {sy}, {z}], "
    f"rotation: [0, -90, -90], thickness: 8}}}}\n"
    for s, z in (("a", 340), ("b", 660)) for x, sx in (("l", -294), ("r", 294))
    for y, sy in (("f", 120), ("b", -120))) + """\
joints:
  - [top, side_l]
  - [top, side_r]
  - [side_l, bottom]
  - [side_r, bottom]
""" + "".join(
    f"  - {{{{planks: [side_{x}, pin_{s}{x}{y}], nails: 1}}}}\n"
    f"  - {{{{planks: [shelf_{s}, pin_{s}{x}{y}], type: rests}}}}\n"
    for s in "ab" for x in "lr" for y in "fb") + """\
loads:
  - {{plank: shelf_a, mass: 30, at: [0, 145, 368]}}
"""


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_a_shelf_on_pins_tips_off_its_back_pins_and_the_empty_one_stays(model):
    """Two loose shelves on four pins each (a woodworker's bookcase, session 18); 30 kg
    (294.3 N) at shelf_a's front edge, y = 145 mm, shelf_b empty.  shelf_a (23.76 N) tips
    over its front pins' edge (y = 124 mm): its resultant meets the pins' plane at
    y = 294.3 x 145 / 318.06 = 134.17 mm, d = 10.17 mm beyond, and its back pins (a =
    248 mm) would have to pull V d / a = 13.04 N.  It lifts off its back pins; its front
    pins, the edge it tips over, and the empty shelf_b are not named, in both models
    (the elastic model's bolted solve shows couples at every pin, 60 N in all)."""
    design = parse_design(PINS.format(model=model), "pins.yaml", "yaml")
    report = check_design(design)
    (violation,) = [v for v in report.violations if v.kind == "lift-off"]
    weight = 294.3 + DENSITY * 0.598 * 0.3 * 0.018 * G
    pull = weight * (294.3 * 145.0 / weight - 124.0) / 248.0
    assert pull == pytest.approx(13.04, abs=0.01)
    assert violation.message.endswith(
        "shelf_a lifts off pin_alb; shelf_a lifts off pin_arb (held down at pin_alb or "
        f"pin_arb, its rests would have to pull at least {pull:.4g} N there)")
    assert violation.where == "shelf_a,pin_alb,pin_arb"


def test_a_plank_resting_along_its_length_is_told_its_sag_is_overstated():
    """A loose 800 x 300 seat lying along two 800 mm rails on edge (under its long edges),
    500 N spread on it: the resting joints' contacts are the corners of the touching
    regions (contract section 2), so the model holds the seat at the rails' ends only
    and reads a span of 800 mm where it lies on them all along; the sagging message says
    it is overstated.  The loose top of this module's frame, resting on the sides' top
    edges across its beam, spans between them as in the shop: no such note."""
    doc = {
        "furncheck": 1, "name": "seat-resting", "model": "elastic",
        "planks": [
            {"id": "seat", "size": [800, 300], "center": [0, 0, 306]},
            {"id": "rail_a", "size": [800, 300], "center": [0, 140, 150],
             "rotation": [90, 0, 0]},
            {"id": "rail_b", "size": [800, 300], "center": [0, -140, 150],
             "rotation": [90, 0, 0]}],
        "joints": [{"planks": ["seat", "rail_a"], "type": "rests"},
                   {"planks": ["seat", "rail_b"], "type": "rests"}],
        "loads": [{"plank": "seat", "force": [0, 0, -500], "spread": True}],
    }
    report = check_design(parse_design(yaml.safe_dump(doc), "seat.yaml", "yaml"))
    sagging = [v.message for v in report.violations if v.kind == "sagging"]
    assert sagging and all(message.endswith(
        "(it rests along its length on rail_a, which the model holds at the rest's corners "
        "only: this overstates its sag)") for message in sagging)
    heavy = _design("elastic", [{"plank": "top", "mass": 200, "spread": True}])
    spans = [v.message for v in check_design(heavy).violations if v.kind == "sagging"]
    assert spans and not any("rests" in message for message in spans)
