"""What ``suggest`` says when nothing (or not enough) works: the violations that remain,
what the search tried, and what each violation would need (``furncheck.suggest.needs``,
``furncheck.suggest.explain``, ``furncheck.report.explanation``).

Each need is derived by hand in its test's docstring and then put to the full checks:
the design with a little more than the need holds, with a little less it does not.
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from furncheck.check import check_design
from furncheck.cli.main import main
from furncheck.design import load_design
from furncheck.design.model import JointSpec, Load, Material, with_model
from furncheck.geometry import analyze
from furncheck.suggest import suggest_design
from furncheck.suggest.discrete import Search, support_planks
from furncheck.suggest.explain import explain
from furncheck.suggest.needs import violation_needs
from furncheck.suggest.tried import FAILED, FOUND, NOT_APPLICABLE, Tried

ROOT = Path(__file__).resolve().parents[1]
CATALOG = ROOT / "designs"
G = 9.81
MDF = 750.0                        # kg/m^3
TABLE_MASS = MDF * 0.012 * (1.0 * 0.6 + 2 * 0.72 * 0.5 + 0.848 * 0.1)   # 12.643 kg
BENCH_MASS = MDF * 0.012 * (1.2 * 0.3 + 2 * 0.438 * 0.3 + 0.588 * 0.08)  # 6.029 kg


def catalog(name: str, model: str):
    design = with_model(load_design(str(CATALOG / name)), model)
    geometry = analyze(design)
    return design, geometry, check_design(design, geometry)


def need_of(design, geometry, report, kind: str, where: str | None = None):
    return next(n for n in violation_needs(design, geometry, report)
                if n.kind == kind and (where is None or n.where == where))


def kinds(report, case: str | None = None) -> set[str]:
    return {v.kind for v in report.violations if case is None or v.case == case}


def with_case_load(design, case: str, load: Load):
    cases = tuple(replace(c, loads=(*c.loads, load)) if c.name == case else c
                  for c in design.load_cases)
    return replace(design, load_cases=cases)


# -- sliding -----------------------------------------------------------------------------
@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_sliding_table_needs_weight_or_friction(model):
    """table-slides, case 'shove' (no load on the table): its planks weigh
    750 kg/m^3 x 12 mm x (1.0 x 0.6 + 2 x 0.72 x 0.5 + 0.848 x 0.1) m^2 = 12.643 kg, so
    W = 124.03 N and friction holds mu W = 0.5 x 124.03 = 62.01 N against the push
    H = 110 N.  Needed: W >= H / mu = 220 N, i.e. (220 - 124.03) / 9.81 = 9.78 kg more,
    or mu >= H / W = 110 / 124.03 = 0.887.  The same in both models (hand statics)."""
    design, geometry, report = catalog("table-slides.yaml", model)
    need = need_of(design, geometry, report, "sliding")
    weight = TABLE_MASS * G
    assert need.case == "shove"
    assert need.values["push"] == pytest.approx(110.0)
    assert need.values["weight"] == pytest.approx(weight, rel=1e-6)
    assert need.values["holds"] == pytest.approx(0.5 * weight, rel=1e-6)
    assert need.values["extra_mass"] == pytest.approx((110.0 / 0.5 - weight) / G, rel=1e-6)
    assert need.values["extra_mass"] == pytest.approx(9.78, abs=0.01)
    assert need.values["friction_needed"] == pytest.approx(110.0 / weight, rel=1e-6)


def test_sliding_need_is_the_threshold_of_the_checks():
    """The rigid table-slides with 2 % more than the needed mass on its top (at the top's
    centre, in case 'shove') no longer slides; with 2 % less it still does.  Likewise the
    friction: mu = 1.02 x 0.887 holds, 0.98 x 0.887 does not."""
    design, geometry, report = catalog("table-slides.yaml", "rigid")
    need = need_of(design, geometry, report, "sliding")
    for factor, slides in ((1.02, False), (0.98, True)):
        heavier = with_case_load(design, "shove",
                                 Load.of_mass("top", factor * need.values["extra_mass"]))
        assert ("sliding" in kinds(check_design(heavier), "shove")) is slides, factor
        mu = factor * need.values["friction_needed"]
        grippier = replace(design, material=replace(design.material, friction=mu))
        assert ("sliding" in kinds(check_design(grippier), "shove")) is slides, factor


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_a_frictionless_design_pushed_needs_friction_not_weight(model, tmp_path):
    """``friction: 0`` (the schema allows it): no weight holds a push, so the need names
    only the friction, mu >= H / W.  table-slides with mu = 0, case 'shove': H = 110 N,
    W = 124.03 N (above), mu >= 0.887; ``suggest`` explains it (exit 0, no internal
    error)."""
    design = load_design(str(CATALOG / "table-slides.yaml"))
    design = with_model(replace(design, material=replace(design.material, friction=0.0)),
                        model)
    geometry = analyze(design)
    report = check_design(design, geometry)
    need = need_of(design, geometry, report, "sliding")
    weight = TABLE_MASS * G
    assert need.case == "shove" and need.values["holds"] == 0.0
    assert "extra_mass" not in need.values
    assert need.values["friction_needed"] == pytest.approx(110.0 / weight, rel=1e-6)
    path = tmp_path / "frictionless.yaml"
    path.write_text(frictionless(CATALOG / "table-slides.yaml"))
    result = CliRunner().invoke(main, ["suggest", str(path), "--model", model])
    assert result.exit_code == 0, result.output
    assert "meets no friction (mu = 0): no weight holds it; friction mu >= 0.887" \
        in result.output


def frictionless(path: Path) -> str:
    text = path.read_text()
    assert "\nunits: mm\n" in text and "\nmaterial:" not in text
    return text.replace("\nunits: mm\n", "\nunits: mm\nmaterial: {friction: 0}\n")


def test_a_frictionless_designs_pictures_are_drawn(tmp_path):
    """With mu = 0 the force-space plot's friction cone is the N axis and a contact pushed
    across uses all of it: shelf-cantilever-overloaded (rigid) gets a suggestion whose
    plot ``suggest --out`` draws; a board lying on the floor with no push (every |T| = 0)
    draws a contacts panel of some height all the same."""
    pytest.importorskip("matplotlib")
    from furncheck.export.plots import force_space_png

    path = tmp_path / "frictionless.yaml"
    path.write_text(frictionless(CATALOG / "shelf-cantilever-overloaded.yaml"))
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["suggest", str(path), "--model", "rigid",
                                       "--max-suggestions", "1", "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert (out / "suggestion-01-forces.png").stat().st_size > 0
    board = check_design(with_model(load_design(str(_board(tmp_path))), "rigid"))
    assert force_space_png(board, board, 0.0).startswith(b"\x89PNG")


def _board(tmp_path: Path) -> Path:
    path = tmp_path / "board.yaml"
    path.write_text("furncheck: 1\nmaterial: {friction: 0}\n"
                    "planks: [{id: board, size: [600, 300], center: [0, 0, 6]}]\n")
    return path


# -- lift-off ----------------------------------------------------------------------------
@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_tipping_bench_needs_a_wider_base_or_ballast(model):
    """bench-tips: planks of 750 kg/m^3 x 12 mm x (1.2 x 0.3 + 2 x 0.438 x 0.3 +
    0.588 x 0.08) m^2 = 6.029 kg (59.14 N) centred on x = 0, and 80 kg (784.8 N) at
    x = 560 mm: V = 843.94 N acts at x = 784.8 x 560 / 843.94 = 520.76 mm.  The support
    is the legs' feet, x from -306 to 306 mm: the line of action is d = 214.76 mm beyond
    leg_r's outer face.  A base reaching 214.76 mm further, or ballast over leg_l's outer
    foot edge (arm a = 612 mm from the tipping edge): V d / a = 843.94 x 214.76 / 612 =
    296.2 N = 30.19 kg."""
    design, geometry, report = catalog("bench-tips.yaml", model)
    need = need_of(design, geometry, report, "lift-off")
    weight = BENCH_MASS * G + 80 * G
    x = 80 * G * 560.0 / weight
    assert need.values["weight"] == pytest.approx(weight, rel=1e-6)
    assert need.values["point"][0] == pytest.approx(x, rel=1e-6)
    assert need.values["outside"] == pytest.approx(x - 306.0, rel=1e-6)
    assert need.values["wider"] == pytest.approx(214.76, abs=0.01)
    assert need.values["edge_plank"] == "leg_r" and need.values["ballast_plank"] == "leg_l"
    assert need.values["ballast_arm"] == pytest.approx(612.0)
    assert need.values["ballast"] == pytest.approx(weight * (x - 306.0) / 612.0 / G, rel=1e-6)
    assert need.values["ballast"] == pytest.approx(30.19, abs=0.01)
    assert "push_max" not in need.values          # no sideways load


def test_a_wall_the_design_does_not_touch_leaves_the_hand_estimate():
    """bench-tips with a wall 1 m behind it (y = 1 m, facing it), touching nothing and
    anchoring nothing: the floor alone holds it, so its tipping gets the hand estimate
    of the test above (214.76 mm wider), not 'it leans on walls or is anchored'."""
    from furncheck.design.model import Wall

    design, _, _ = catalog("bench-tips.yaml", "rigid")
    walled = replace(design, walls=(Wall((0.0, 1.0, 0.0), (0.0, -1.0, 0.0)),))
    geometry = analyze(walled)
    assert not any(c.wall is not None for c in geometry.contacts)
    need = need_of(walled, geometry, check_design(walled, geometry), "lift-off")
    assert need.why != "it leans on walls or is anchored"
    assert need.values["wider"] == pytest.approx(214.76, abs=0.01)


def test_ballast_need_is_the_threshold_of_the_checks():
    """The rigid bench-tips with 2 % more than the needed ballast at leg_l's outer foot
    edge (x = -306 mm) stands; with 2 % less it still tips."""
    design, geometry, report = catalog("bench-tips.yaml", "rigid")
    need = need_of(design, geometry, report, "lift-off")
    for factor, tips in ((1.02, False), (0.98, True)):
        ballast = Load.of_mass("leg_l", factor * need.values["ballast"], (-0.306, 0.0, 0.005))
        assert ("lift-off" in kinds(check_design(with_case_load(design, "default", ballast)))
                ) is tips, factor


def pushed_table():
    """table-slides with a friction of 2 (it cannot slide) and 300 N +x on leg_l at
    z = 700 mm instead of its shove: it topples over leg_r."""
    design = load_design(str(CATALOG / "table-slides.yaml"))
    design = replace(with_model(design, "rigid"),
                     material=replace(design.material, friction=2.0))
    cases = tuple(replace(c, loads=(Load("leg_l", (300.0, 0.0, 0.0), (-0.436, 0.0, 0.7)),))
                  if c.name == "shove" else c for c in design.load_cases)
    return replace(design, load_cases=cases)


def test_pushed_over_table_needs_a_smaller_push():
    """The table's 124.03 N of planks act at x = 0; a push H at height h = 0.7 m moves the
    line of action to x = H h / W on the floor.  It stays on the feet (x <= 436 mm, leg_r's
    outer face) for H <= 0.436 x 124.03 / 0.7 = 77.25 N.  With H = 300 N it meets the
    floor at 300 x 0.7 / 124.03 = 1.6932 m, d = 1.2572 m outside; ballast over leg_l's
    outer face (a = 872 mm): 124.03 x 1257.2 / 872 / 9.81 = 18.23 kg.  Checked: a push of
    1.02 x 77.25 N topples it, 0.98 x 77.25 N does not."""
    design = pushed_table()
    geometry = analyze(design)
    report = check_design(design, geometry)
    assert kinds(report) == {"lift-off"}
    need = need_of(design, geometry, report, "lift-off")
    weight = TABLE_MASS * G
    assert need.values["push"] == pytest.approx(300.0)
    assert need.values["push_max"] == pytest.approx(0.436 * weight / 0.7, rel=1e-6)
    assert need.values["outside"] == pytest.approx(300 * 700 / weight - 436.0, rel=1e-6)
    assert need.values["ballast"] == pytest.approx(18.23, abs=0.01)
    from furncheck.report.explanation import need_text

    assert need_text(need, "mm").endswith(        # a push or a pull: the force is level
        f", or a horizontal push or pull of at most {0.436 * weight / 0.7:.3g} N (now "
        "300 N)")
    for factor, tips in ((1.02, True), (0.98, False)):
        push = factor * need.values["push_max"]
        cases = tuple(replace(c, loads=(Load("leg_l", (push, 0.0, 0.0), (-0.436, 0.0, 0.7)),))
                      if c.name == "shove" else c for c in design.load_cases)
        assert ("lift-off" in kinds(check_design(replace(design, load_cases=cases)))) is tips


# -- durability --------------------------------------------------------------------------
def test_overloaded_joint_needs_more_nails():
    """shelf-cantilever-overloaded (its file's hand estimate): the shelf joint's moment is
    90.4 N m, so the pull per nail is 2 x 90.4 / 0.012 / 15 = 1004 N against 700 N.  It
    goes with 1 / n: ceil(15 x 1004 / 700) = ceil(21.5) = 22 nails hold it, i.e. a joint
    22 x 20 = 440 mm long (now 300 mm).  Checked with the count listed in the file: 22
    nails hold it, 21 do not (15 x 1004 / 21 = 717 N)."""
    design, geometry, report = catalog("shelf-cantilever-overloaded.yaml", "rigid")
    need = need_of(design, geometry, report, "non-durable", "post/shelf")
    assert need.values["pull"] == pytest.approx(1004, rel=0.005)
    assert need.values["pull_capacity"] == pytest.approx(700.0)
    assert (need.values["nails"], need.values["nails_needed"]) == (15, 22)
    assert need.values["length"] == pytest.approx(300.0)
    assert need.values["length_needed"] == pytest.approx(440.0)
    # the shelf's end (its 300 mm width along the joint line) has no room for 440 mm:
    # 22 nails at 20 mm do not fit on it, and the estimate says so
    assert (need.values["room"], need.values["room_plank"]) == (pytest.approx(300.0),
                                                                 "shelf")
    from furncheck.report.explanation import need_text

    assert need_text(need, "mm").endswith(
        "a joint 440 mm long at 20 mm spacing (now 300 mm), more than the 300 mm that "
        "shelf gives along the joint: a wider shelf, or a brace that takes the load off the "
        "joint")
    for nails, durable in ((22, True), (21, False)):
        joints = tuple(JointSpec(j.planks, nails if j.name == "post/shelf" else None)
                       for j in geometry.joints)
        listed = check_design(replace(design, joints=joints))
        assert ("non-durable" not in kinds(listed)) is durable, nails
        if durable:
            assert listed.valid


def test_the_room_for_a_longer_joint_is_the_chord_of_either_plank_along_its_line():
    """The room a joint's nails have along its line is the chord of each plank's box along
    it (2 min_i h_i / |c_i|), the smaller of the two planks', and names how that plank
    would grow: the cantilever shelf's 300 mm width (shelf 300 wide: 'a wider shelf');
    turned 90 degrees about z, the shelf's 300 mm side along the line is its length ('a
    longer shelf'); a post only 200 mm wide limits it instead ('a wider post'); a 700 x
    60 mm plank turned 12.5 degrees in its plane, the line across it, gives 60 / cos 12.5
    = 61.4 mm, not its projection (700 sin 12.5 + 60 cos 12.5 = 210.9 mm)."""
    from furncheck.suggest.needs import _room

    design, geometry, report = catalog("shelf-cantilever-overloaded.yaml", "rigid")
    joint = next(j for j in geometry.joints if j.name == "post/shelf")
    line = joint.frame[:, 1]
    assert _room(design.plank("shelf"), line)[::2] == (pytest.approx(0.3), 1)
    turned = replace(design.plank("shelf"), length=0.3, width=0.4,
                     rotation=(0.0, 0.0, 90.0))
    assert _room(turned, line)[::2] == (pytest.approx(0.3), 0)
    narrow = replace(design.plank("post"), width=0.2)
    assert _room(narrow, line)[::2] == (pytest.approx(0.2), 1)
    leg = replace(design.plank("post"), length=0.7, width=0.06, thickness=0.018,
                  rotation=(0.0, 0.0, 12.5))       # turned in its plane: its ends slant
    assert _room(leg, np.array([0.0, 1.0, 0.0]))[::2] == (
        pytest.approx(0.06 / math.cos(math.radians(12.5)), rel=1e-9), 1)


# -- bending (elastic model) -------------------------------------------------------------
def test_sagging_shelf_needs_a_thicker_plank():
    """shelf-cantilever-overloaded, elastic: the shelf is a 400 mm cantilever (its
    file's hand estimate: P a^2 (3 L - a) / 6 EI + w L^4 / 8 EI = 30.7 + 0.7 = 31 mm at its
    tip), 31 x 1.5 = 46.5 mm with creep, allowed 800 / 400 = 2 mm.  Sag goes with 1 / t^3:
    t' = 12 x (46.5 / 2)^(1/3) = 34.3 mm.  Checked: at that thickness (its own weight
    grown by 2.9 x, the joint unchanged: a determinate cantilever) the sag is within 10 %
    of its allowance, and not below it (the need is a lower bound)."""
    design, geometry, report = catalog("shelf-cantilever-overloaded.yaml", "elastic")
    need = need_of(design, geometry, report, "sagging", "shelf")
    assert need.values["dimension"] == "thickness" and need.values["size"] == 12.0
    assert need.values["sag"] == pytest.approx(31.0, rel=0.02)
    assert need.values["sag_allowed"] == pytest.approx(2.0)
    assert need.values["size_needed"] == pytest.approx(12 * (46.5 / 2) ** (1 / 3), rel=0.02)
    thicker = _thickened(design, "shelf", need.values["size_needed"])
    plank = _plank_result(check_design(thicker), "default", "shelf")
    used = plank.sag * 1.5 / plank.sag_allowed
    assert 1.0 <= used <= 1.1


def test_overstressed_shelf_needs_a_thicker_plank():
    """particleboard-shelf-overloaded (its file's hand estimate): the middle shelf's
    largest moment lies between w L^2 / 16 and w L^2 / 8, a stress of 13.8 to 27.6 N/mm^2
    against 11.5.  Stress goes with 1 / t^2: t' = 12 x (stress / 11.5)^(1/2), between
    13.1 and 18.6 mm.  Checked: at t' the shelf's stress is its strength to 5 %."""
    design, geometry, report = catalog("particleboard-shelf-overloaded.yaml", "elastic")
    need = need_of(design, geometry, report, "overstressed", "middle")
    assert need.values["strength"] == pytest.approx(11.5)
    assert 13.8 <= need.values["stress"] <= 27.6
    assert need.values["size_needed"] == pytest.approx(
        12 * math.sqrt(need.values["stress"] / 11.5), rel=1e-9)
    assert 13.1 <= need.values["size_needed"] <= 18.6
    plank = _plank_result(check_design(_thickened(design, "middle", need.values["size_needed"])),
                          "default", "middle")
    assert plank.stress / plank.strength == pytest.approx(1.0, abs=0.05)


def test_plank_on_edge_bends_across_its_width():
    """A rail on edge (its face vertical, its length level) under vertical loads bends in
    its own plane: its needed size is a depth (width), not a thickness."""
    from furncheck.suggest.needs import _bending_depth
    design = load_design(str(CATALOG / "table-slides.yaml"))
    assert _bending_depth(design.plank("apron")) == ("width", pytest.approx(0.1))
    assert _bending_depth(design.plank("top")) == ("thickness", pytest.approx(0.012))
    assert _bending_depth(design.plank("leg_l")) == ("thickness", pytest.approx(0.012))


def test_an_end_panel_bowed_sideways_needs_a_thicker_panel_not_a_deeper_one(
        floor_at_corners):
    """A woodworker's coffee table: 400 x 550 mm end panels on edge (their 550 mm level),
    each held by the floor at its two bottom corners (``floor_at_corners``: on two narrow
    feet; standing on the floor along its edge it is held there, and does not bow), a 9 mm
    top between them, 75 kg sat on it: the top's sag spreads the ends, which bow
    4.08 mm sideways, across their 12 mm thickness (6.12 mm with creep against 550 / 400
    = 1.38 mm).  Sag goes with 1 / t^3: t' = 12 x (6.12 / 1.38)^(1/3) = 19.7 mm thick,
    not a panel 658 mm deep (the rail rule's reading of a plank on edge, for vertical
    loads)."""
    from furncheck.design import parse_design

    text = """
furncheck: 1
name: coffee-table-thin
planks:
  - {id: top, size: [1100, 550], center: [0, 0, 404.5], thickness: 9}
  - {id: end_l, size: [400, 550], center: [-544, 0, 200], rotation: [0, -90, 0]}
  - {id: end_r, size: [400, 550], center: [544, 0, 200], rotation: [0, -90, 0]}
loads:
  - {plank: top, mass: 75, at: [0, 0, 409]}
"""
    design = parse_design(text, "coffee.yaml", "yaml")
    geometry = analyze(design)
    report = check_design(design, geometry)
    need = need_of(design, geometry, report, "sagging", "end_l")
    assert need.values["dimension"] == "thickness" and need.values["size"] == 12.0
    assert need.values["sideways"] is True      # its words: 'bows ... sideways'
    ratio = need.values["sag"] * 1.5 / need.values["sag_allowed"]
    assert need.values["size_needed"] == pytest.approx(12 * ratio ** (1 / 3), rel=1e-9)
    assert 15.0 < need.values["size_needed"] < 25.0


def _thickened(design, plank_id: str, thickness_mm: float):
    """The design with one plank that thick (about its middle plane)."""
    planks = tuple(replace(p, thickness=thickness_mm * design.unit_scale)
                   if p.id == plank_id else p for p in design.planks)
    return replace(design, planks=planks)


def _plank_result(report, case: str, plank_id: str):
    return next(p for c in report.cases if c.name == case for p in c.planks if p.id == plank_id)


# -- geometry ----------------------------------------------------------------------------
def test_geometric_needs_close_the_gap():
    """bookshelf-gap: the shelf's end is 3 mm from side_r, tolerance 0.5 mm: closing it by
    2.5 to 3.5 mm joins them.  bench-long-leg: leg_m's corner is 2 mm below the floor:
    1.5 to 2.5 mm.  side-table-hovering: 4 mm above it: 3.5 to 4.5 mm."""
    for name, kind, distance in (("bookshelf-gap.yaml", "disconnected", 3.0),
                                 ("bench-long-leg.yaml", "penetration", 2.0),
                                 ("side-table-hovering.yaml", "floating", 4.0)):
        need = need_of(*catalog(name, "rigid"), kind)
        assert need.values["distance"] == pytest.approx(distance, abs=1e-9), name
        assert need.values["change_min"] == pytest.approx(distance - 0.5, abs=1e-9)
        assert need.values["change_max"] == pytest.approx(distance + 0.5, abs=1e-9)


def test_a_plank_behind_a_wall_needs_to_come_out_of_the_wall():
    """A 400 x 400 top whose back edge lies 100 mm behind the wall (y = -100 against the
    wall's y = 0), its lowest corner 800 mm up: the need is 100 mm behind wall 0 (99.5 to
    100.5 mm to move it out), not '-800 mm into the floor'."""
    from furncheck.design import parse_design

    design = parse_design("""\
furncheck: 1
name: wall-pen
walls:
  - {point: [0, 0, 0], normal: [0, 1, 0]}
planks:
  - {id: side, size: [800, 300], center: [0, 150, 400], rotation: [0, -90, 0]}
  - {id: top, size: [400, 400], center: [206, 100, 806]}
""", "wall.yaml", "yaml")
    geometry = analyze(design)
    need = need_of(design, geometry, check_design(design, geometry), "penetration")
    assert need.values["wall"] == 0
    assert need.values["distance"] == pytest.approx(100.0, abs=1e-9)
    assert need.values["change_min"] == pytest.approx(99.5, abs=1e-9)


# -- what was tried ----------------------------------------------------------------------
def sliding_table():
    """The rigid table-slides shoved with 400 N at 20 mm above the floor: it slides (400 N
    against 62 N: 68.9 kg more weight would be needed, (400 / 0.5 - 124.03) / 9.81), and
    tipping is far (400 N x 0.02 m = 8 N m against 124 N x 0.436 m = 54 N m)."""
    text = (CATALOG / "table-slides.yaml").read_text(encoding="utf-8")
    return text.replace("force: [110, 0, 0], at: [-436, 0, 150]",
                        "force: [400, 0, 0], at: [-436, 0, 20]")


def test_no_suggestion_explains_why_with_the_numbers(tmp_path):
    """The text names every remaining violation, the sliding need with its hand numbers
    (sliding_table), the continuous search's counts and the discrete rule that does not
    apply; the JSON carries the same, byte-identical on every run."""
    path = tmp_path / "sliding.yaml"
    path.write_text(sliding_table(), encoding="utf-8")
    run = CliRunner().invoke(main, ["suggest", str(path), "--model", "rigid"],
                             catch_exceptions=False)
    assert run.exit_code == 0
    text = run.output
    assert "No suggestion" in text and "violations remain." in text
    assert ("the push of 400 N exceeds mu W = 0.5 x 124 N = 62 N; 68.9 kg more weight on "
            "it, or friction mu >= 3.23, would hold it") in text
    assert "continuous changes (paper 6.4): " in text and "directions formed" in text
    assert "support plank: not applicable: it does not repair sliding" in text
    first, second = (CliRunner().invoke(main, ["suggest", str(path), "--model", "rigid",
                                               "--format", "json"]).output for _ in range(2))
    assert first == second
    explanation = json.loads(first)["explanation"]
    assert {(v["kind"], v["where"]) for v in explanation["remaining"]} >= \
        {("sliding", "leg_l,leg_r")}
    sliding = next(n for n in explanation["needs"] if n["kind"] == "sliding")
    assert sliding["values"]["extra_mass"] == pytest.approx((800 - TABLE_MASS * G) / G,
                                                            rel=1e-4)
    tried = explanation["tried"]
    assert tried["max_dofs"] == 3 and tried["max_suggestions"] == 8
    assert [d["dofs"] for d in tried["directions"]] == [1, 2, 3]
    assert tried["discrete"][0]["outcome"] == NOT_APPLICABLE


def test_tally_adds_up():
    """Per number of DOFs combined: every combination evaluated is kept or culled for
    exactly one reason; C(relevant, m) are possible; every line search found an interval
    exactly when one of its probes was valid."""
    for name, model in (("bench-tips.yaml", "rigid"), ("table-slides.yaml", "elastic"),
                        ("bookshelf-gap.yaml", "elastic")):
        result = suggest_design(with_model(load_design(str(CATALOG / name)), model))
        tried = result.explanation.tried
        assert tried.free + len(tried.blocked) + tried.locked <= tried.dofs
        for tally in tried.directions:
            assert tally.possible == math.comb(tally.relevant, tally.size)
            assert tally.evaluated <= tally.possible
            assert tally.kept + tally.facing_away + tally.breaks_other + tally.too_far == \
                tally.evaluated
        assert len(tried.line_searches) == result.searched
        for search in tried.line_searches:
            assert (search.interval is not None) == any(m >= 0 for _, m in search.probes)
        found = sum(1 for s in tried.line_searches if s.interval is not None)
        assert found >= sum(1 for s in result.suggestions if s.kind == "continuous")
        assert bool(result.explanation.remaining) == (not result.suggestions)


def test_failed_support_names_what_remains():
    """shelf-cantilever-overloaded, elastic: every support the rule builds is recorded;
    when nothing was found, a support that was checked and failed names the violation
    that remains with it, and the rule for a post that is not level says so."""
    design, geometry, report = catalog("shelf-cantilever-overloaded.yaml", "elastic")
    search = Search(design, geometry, report)
    support = support_planks(search)
    trials = search.trials
    assert {t.outcome for t in trials} <= {FOUND, FAILED, NOT_APPLICABLE}
    assert len([t for t in trials if t.outcome == FOUND]) == (support is not None)
    tried = Tried(24, 0, 0, {}, 3, 8, False, (), (), 24, 0, 0, tuple(trials))
    explained = explain(design, geometry, report, tried, found=0).tried.discrete
    checked = [t for t in explained if t.outcome == FAILED and t.candidate is not None]
    assert checked
    for trial in checked:
        assert f"with {trial.plank}, " in trial.reason
        assert any(f"{kind}: " in trial.reason
                   for kind in ("non-durable", "sagging", "overstressed", "lift-off"))
    assert any(t.reason == "post is not level" for t in explained)
    assert len(explained) == len({(t.rule, t.target, t.outcome, t.reason) for t in explained})


def test_partial_results_say_what_was_tried():
    """bench-tips (rigid) gets fewer than the 8 suggestions it lists at most: the text says so
    after them, with the lift-off need and the line searches that found an interval."""
    run = CliRunner().invoke(main, ["suggest", str(CATALOG / "bench-tips.yaml"),
                                    "--model", "rigid"], catch_exceptions=False)
    text = run.output
    assert "Fewer than 8, the most it lists (--max-suggestions):" in text
    assert "215 mm outside the support beyond leg_r" in text
    assert "30.2 kg of ballast over leg_l" in text
    assert re.search(r"\n    \d+ line searches with the full checks, [1-9]\d* with a valid "
                     r"interval\n", text), text
    assert "support plank: not applicable: it does not repair lift-off" in text


def test_valid_design_has_no_explanation():
    result = suggest_design(with_model(load_design(str(CATALOG / "stool.yaml")), "rigid"))
    assert result.valid and result.explanation is None
    run = CliRunner().invoke(main, ["suggest", str(CATALOG / "stool.yaml"), "--model",
                                    "rigid", "--format", "json"])
    assert "explanation" not in json.loads(run.output)


def test_material_defaults_used_in_the_hand_numbers():
    """The tests' constants are the catalog's: 750 kg/m^3, mu 0.5, 700 N per nail."""
    material = Material()
    assert (material.density, material.friction, material.nail_pull) == (MDF, 0.5, 700.0)


# -- a loose part on its rests ---------------------------------------------------------------
def loose_top_desk(model: str, load: Load):
    """Two 700 x 600 x 18 mm ends standing on the floor 1364 mm apart (outer faces at
    x = +-700), a 150 mm stretcher nailed between them, and a 1400 x 800 x 18 mm top lying
    loose on the ends' top edges (``type: rests``, 600 mm deep: y from -300 to 300 mm),
    with ``load`` on the top: the woodworker's desk of session 18."""
    from furncheck.design import parse_design

    text = f"""\
furncheck: 1
name: desk-loose-top
model: {model}
material: {{thickness: 18}}
planks:
  - {{id: end_l, size: [700, 600], center: [-691, 0, 350], rotation: [0, -90, 0]}}
  - {{id: end_r, size: [700, 600], center: [691, 0, 350], rotation: [0, -90, 0]}}
  - {{id: stretcher, size: [1364, 150], center: [0, 291, 400], rotation: [90, 0, 0]}}
  - {{id: top, size: [1400, 800], center: [0, 0, 709]}}
joints:
  - [end_l, stretcher]
  - [end_r, stretcher]
  - {{planks: [top, end_l], type: rests}}
  - {{planks: [top, end_r], type: rests}}
"""
    design = parse_design(text, "desk.yaml", "yaml")
    return replace(design, load_cases=(replace(design.load_cases[0], loads=(load,)),))


TOP_WEIGHT = MDF * 1.4 * 0.8 * 0.018 * G            # 148.33 N


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_a_loose_top_tipped_off_its_rests_needs_its_hold_down(model):
    """70 kg (686.7 N) at the top's front edge, y = -390 mm, 90 mm beyond its rests'
    front edge (y = -300): the whole desk stands (its ends' feet reach as far as the
    rests, and the ends and stretcher weigh with it), but the top tips about that edge.
    The top's resultant V = 686.7 + 148.33 = 835.0 N meets the plane of its rests at
    y = -686.7 x 390 / 835.0 = -320.7 mm, d = 20.7 mm beyond the front edge; a pull at the
    back corners (a = 600 mm) holds it from V d / a = (686.7 x 90 - 148.33 x 300) / 600 =
    28.84 N, as ballast 2.94 kg.  Nailing the rests down (two nails each: the nail rule's
    first try, well above that pull) repairs it: ``suggest``'s 'nail down' fix, where the
    elastic top also sags past its allowance and no board up to the thicker rule's limit
    saves it."""
    design = loose_top_desk(model, Load.of_mass("top", 70.0, (0.0, -0.39, 0.718)))
    geometry = analyze(design)
    report = check_design(design, geometry)
    assert "lift-off" in kinds(report)
    need = need_of(design, geometry, report, "lift-off")
    load = 70.0 * G
    hold = (load * 90.0 - TOP_WEIGHT * 300.0) / 600.0
    assert need.values["part"] == "top" and need.values["on"] == "end_l,end_r"
    assert need.values["weight"] == pytest.approx(load + TOP_WEIGHT, rel=1e-6)
    assert need.values["point"][1] == pytest.approx(-load * 390.0 / (load + TOP_WEIGHT),
                                                    rel=1e-6)
    assert need.values["outside"] == pytest.approx(load * 390.0 / (load + TOP_WEIGHT)
                                                   - 300.0, rel=1e-6)
    assert need.values["hold"] == pytest.approx(hold, rel=1e-6)
    assert need.values["hold_arm"] == pytest.approx(600.0)
    assert need.values["ballast"] == pytest.approx(hold / G, rel=1e-6)
    message = next(v.message for v in report.violations if v.kind == "lift-off")
    assert f"its rests would have to pull at least {hold:.4g} N there" in message
    if model == "rigid":
        from furncheck.report.cutlist import nail_lines, nails_json
        from furncheck.suggest.cutlist import nail_changes

        first = suggest_design(design).suggestions[0]
        assert first.advice == ("Nail top to end_l and end_r, 2 nails into each (its "
                                "resting joints made nail joints).")
        assert check_design(first.design).valid
        assert "rests" not in first.text and "- planks: [top, end_l]\n  nails: 2\n" in first.text
        changes = nail_changes(design, first.design)
        assert nail_lines(changes) == ["changes 2 joints:",
                                       "  top/end_l: resting -> nailed, 2 nails",
                                       "  top/end_r: resting -> nailed, 2 nails"]
        assert nails_json(changes) == [
            {"joint": "top/end_l", "before": 0, "after": 2, "resting": True},
            {"joint": "top/end_r", "before": 0, "after": 2, "resting": True}]


def test_a_loose_top_pushed_off_its_rests_needs_friction_there():
    """160 N along x at the top's own height with 15 kg on it: the floor holds the whole
    desk (mu W of ends, stretcher, top and load, far more), but the top slides on its
    rests once the push passes mu N, N = 148.33 + 147.15 = 295.5 N what presses it onto
    them: 147.7 N < 160 N.  Needed: 160 / 0.5 - 295.5 = 24.5 N more on the top, 2.50 kg,
    or mu >= 160 / 295.5 = 0.541 (with 2 % of N more than that mass it holds, with 2 %
    less it slides); never a negative mass for the whole desk, whose floor holds."""
    design = loose_top_desk("rigid", Load("top", (160.0, 0.0, 0.0), (-0.7, 0.0, 0.709)))
    cases = design.load_cases
    design = replace(design, load_cases=(replace(cases[0], loads=(
        *cases[0].loads, Load.of_mass("top", 15.0, (0.0, 0.1, 0.718)))),))
    geometry = analyze(design)
    report = check_design(design, geometry)
    assert "sliding" in kinds(report)
    need = need_of(design, geometry, report, "sliding")
    pressing = TOP_WEIGHT + 15.0 * G
    assert need.values["part"] == "top"
    assert need.values["push"] == pytest.approx(160.0, rel=1e-9)
    assert need.values["weight"] == pytest.approx(pressing, rel=1e-6)
    assert need.values["extra_mass"] == pytest.approx((160.0 / 0.5 - pressing) / G, rel=1e-6)
    assert need.values["friction_needed"] == pytest.approx(160.0 / pressing, rel=1e-6)
    for margin, slides in ((0.02, False), (-0.02, True)):      # of N: the threshold
        heavier = with_case_load(design, "default", Load.of_mass(
            "top", need.values["extra_mass"] + margin * pressing / G, (0.0, 0.0, 0.718)))
        assert ("sliding" in kinds(check_design(heavier))) is slides, margin


def test_a_tipping_edge_made_by_two_planks_names_both():
    """A child's step (a woodworker's, session 18): two 800 x 300 sides 312 mm apart, a
    step and a handle, pulled 15 N forward (+y) at the handle, 790 mm up, with no one on
    it.  Its planks weigh 750 x 0.012 x (2 x 0.8 x 0.3 + 0.3 x 0.28 + 0.3 x 0.06) x 9.81
    = 51.38 N, the handle's 1.589 N at y = -144 mm; the push moves the resultant's floor
    point by 15 x 790 / 51.38 = 230.6 mm: y = -4.45 + 230.6 = 226.2 mm, 76.2 mm beyond the
    feet's front edge (y = 150), which runs from side_l's foot to side_r's: the step tips
    over both, and the need says 'beyond side_l and side_r', not one of them."""
    from furncheck.design import parse_design

    design = parse_design("""\
furncheck: 1
name: kids-step
model: rigid
planks:
  - {id: side_l, size: [800, 300], center: [-156, 0, 400], rotation: [0, -90, 0]}
  - {id: side_r, size: [800, 300], center: [156, 0, 400], rotation: [0, -90, 0]}
  - {id: step, size: [300, 280], center: [0, 0, 256]}
  - {id: handle, size: [300, 60], center: [0, -144, 770], rotation: [90, 0, 0]}
loads:
  - {plank: handle, force: [0, 15, 0], at: [0, -138, 790]}
""", "step.yaml", "yaml")
    geometry = analyze(design)
    report = check_design(design, geometry)
    need = need_of(design, geometry, report, "lift-off")
    weight = MDF * 0.012 * (2 * 0.8 * 0.3 + 0.3 * 0.28 + 0.3 * 0.06) * G
    y = (-144.0 * MDF * 0.012 * 0.3 * 0.06 * G + 15.0 * 790.0) / weight
    assert need.values["weight"] == pytest.approx(weight, rel=1e-6)
    assert need.values["point"][1] == pytest.approx(y, rel=1e-6)
    assert need.values["outside"] == pytest.approx(y - 150.0, rel=1e-6)
    assert need.values["edge_plank"] == "side_l and side_r"


DESK_FRAME = """\
furncheck: 1
name: desk
model: {model}
material: {{thickness: 18}}
{walls}planks:
  - {{id: end_l, size: [700, 600], center: [-691, 0, 350], rotation: [0, -90, 0]}}
  - {{id: end_r, size: [700, 600], center: [691, 0, 350], rotation: [0, -90, 0]}}
  - {{id: stretcher, size: [1364, 150], center: [0, 291, 400], rotation: [90, 0, 0]}}
{planks}joints:
  - [end_l, stretcher]
  - [end_r, stretcher]
{joints}loads:
{loads}"""


def desk_with(model: str, planks: str, joints: str, loads: str, walls: str = ""):
    from furncheck.design import parse_design

    return parse_design(DESK_FRAME.format(model=model, planks=planks, joints=joints,
                                          loads=loads, walls=walls), "desk.yaml", "yaml")


def lift_off_message(design) -> str:
    return next(v.message for v in check_design(design).violations if v.kind == "lift-off")


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_a_loose_top_with_a_box_on_it_tips_with_the_box(model):
    """The desk's loose top (148.33 N) sat on at its front edge (686.7 N at y = -390 mm)
    with a 200 x 200 x 60 mm box (17.66 N) resting on it at y = 100: the box tips with the
    top, so the pull at the back corners (a = 600 mm from the front edge) is
    (686.7 x 90 - 148.33 x 300 - 17.66 x 400) / 600 = 17.07 N, in the message and in the
    hand estimate (where the elastic model's bolted corners read 15,150 N)."""
    design = desk_with(model, """\
  - {id: top, size: [1400, 800], center: [0, 0, 709]}
  - {id: box, size: [200, 200], center: [0, 100, 818], rotation: [0, -90, 0], thickness: 60}
""", """\
  - {planks: [top, end_l], type: rests}
  - {planks: [top, end_r], type: rests}
  - {planks: [box, top], type: rests}
""", "  - {plank: top, mass: 70, at: [0, -390, 718]}\n")
    box = MDF * 0.2 * 0.2 * 0.06 * G
    hold = (70.0 * G * 90.0 - TOP_WEIGHT * 300.0 - box * 400.0) / 600.0
    assert hold == pytest.approx(17.07, abs=0.01)
    assert f"its rests would have to pull at least {hold:.4g} N there" in \
        lift_off_message(design)
    geometry = analyze(design)
    need = need_of(design, geometry, check_design(design, geometry), "lift-off")
    assert need.values["part"] == "top,box"
    assert need.values["hold"] == pytest.approx(hold, rel=1e-6)


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_two_loose_tops_are_each_held_down(model):
    """Two 700 x 800 tops (74.16 N each) on the ends and a middle divider, 40 kg at each
    one's front edge (y = -390): each tips about the front edge (y = -300) and is held
    at its corner on an end (a = 600 mm; the divider, 582 mm deep, gives less arm):
    (392.4 x 90 - 74.16 x 300) / 600 = 21.78 N each, 43.56 N in all."""
    design = desk_with(model, """\
  - {id: divider, size: [700, 582], center: [0, -9, 350], rotation: [0, -90, 0]}
  - {id: top_a, size: [700, 800], center: [-350, 0, 709]}
  - {id: top_b, size: [700, 800], center: [350, 0, 709]}
""", """\
  - [divider, stretcher]
  - {planks: [top_a, end_l], type: rests}
  - {planks: [top_a, divider], type: rests}
  - {planks: [top_b, divider], type: rests}
  - {planks: [top_b, end_r], type: rests}
""", """\
  - {plank: top_a, mass: 40, at: [-350, -390, 718]}
  - {plank: top_b, mass: 40, at: [350, -390, 718]}
""")
    weight = MDF * 0.7 * 0.8 * 0.018 * G
    each = (40.0 * G * 90.0 - weight * 300.0) / 600.0
    assert each == pytest.approx(21.78, abs=0.01)
    message = lift_off_message(design)
    assert (f"held down, top_a at end_l ({each:.4g} N) and top_b at end_r ({each:.4g} N), "
            f"their rests would have to pull at least {2 * each:.4g} N in all") in message


def test_a_loose_top_lifted_bodily_needs_its_lift_held():
    """200 N straight up on the 148.33 N top: its loads lift it off its rests by
    51.67 N, what a fixing must hold (no tipping edge: it comes off whole)."""
    design = desk_with("rigid", "  - {id: top, size: [1400, 800], center: [0, 0, 709]}\n",
                       "  - {planks: [top, end_l], type: rests}\n"
                       "  - {planks: [top, end_r], type: rests}\n",
                       "  - {plank: top, force: [0, 0, 200], at: [0, 0, 718]}\n")
    assert f"its rests would have to pull at least {200.0 - TOP_WEIGHT:.4g} N in all" in \
        lift_off_message(design)
    geometry = analyze(design)
    need = need_of(design, geometry, check_design(design, geometry), "lift-off")
    assert need.values["lifted"] == pytest.approx(200.0 - TOP_WEIGHT, rel=1e-6)


def test_a_loose_top_on_a_frame_against_a_wall_gets_its_hand_estimate():
    """The frame's ends stand against a wall behind them (y = 300 mm); the 699 mm deep top
    stops 1 mm short of it (y from -400 to 299), weighing 750 x 1.4 x 0.699 x 0.018 x 9.81
    = 129.6 N at y = -50.5: its rests run 599 mm deep (y from -300 to 299), so the pull at
    the back corners is (686.7 x 90 - 129.6 x 249.5) / 599 = 49.19 N.  The wall touches the
    frame, not the top: the top's estimate is given, not 'it leans on walls'."""
    design = desk_with("rigid", "  - {id: top, size: [1400, 699], center: [0, -50.5, 709]}\n",
                       "  - {planks: [top, end_l], type: rests}\n"
                       "  - {planks: [top, end_r], type: rests}\n",
                       "  - {plank: top, mass: 70, at: [0, -390, 718]}\n",
                       walls="walls:\n  - {point: [0, 300, 0], normal: [0, -1, 0]}\n")
    top = MDF * 1.4 * 0.699 * 0.018 * G
    hold = (70.0 * G * 90.0 - top * 249.5) / 599.0
    assert hold == pytest.approx(49.19, abs=0.01)
    assert f"at least {hold:.4g} N there" in lift_off_message(design)
    geometry = analyze(design)
    need = need_of(design, geometry, check_design(design, geometry), "lift-off")
    assert need.values["hold"] == pytest.approx(hold, rel=1e-6)


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_a_desk_that_topples_and_a_top_that_tips_are_both_named(model):
    """200 kg (1961.3 N) at the loose top's front edge, y = -390 mm: the whole desk topples
    over its feet's front edge (y = -300): held down at its back feet (a = 600 mm) from
    (1961.3 x 90 - (2 x 55.62 + 148.33) x 300 - 27.10 x 591) / 600 = 137.8 N (the ends'
    weights at y = 0, the stretcher's at 291); and held so, the top still tips off its
    rests: (1961.3 x 90 - 148.33 x 300) / 600 = 220.1 N.  Both are said: the ballast the
    whole needs would not hold the top."""
    design = desk_with(model, "  - {id: top, size: [1400, 800], center: [0, 0, 709]}\n",
                       "  - {planks: [top, end_l], type: rests}\n"
                       "  - {planks: [top, end_r], type: rests}\n",
                       "  - {plank: top, mass: 200, at: [0, -390, 718]}\n")
    load = 200.0 * G
    end = MDF * 0.7 * 0.6 * 0.018 * G
    stretcher = MDF * 1.364 * 0.15 * 0.018 * G
    whole = (load * 90.0 - (2 * end + TOP_WEIGHT) * 300.0 - stretcher * 591.0) / 600.0
    top = (load * 90.0 - TOP_WEIGHT * 300.0) / 600.0
    message = lift_off_message(design)
    assert f"the ground would have to pull at least {whole:.4g} N there); top also lifts " \
           f"off its rests (held down at end_l or end_r, its rests would have to pull at " \
           f"least {top:.4g} N there)" in message
    geometry = analyze(design)
    need = need_of(design, geometry, check_design(design, geometry), "lift-off")
    assert need.values["ballast"] * G == pytest.approx(whole, rel=1e-6)
    assert need.values["also"]["hold"] == pytest.approx(top, rel=1e-6)


def test_the_discrete_trials_past_those_shown_are_counted_by_what_they_were():
    """Nothing found: the first SHOWN discrete trials are listed, the rest counted as
    candidates tried and rules that did not apply (a maker read 'and 8 more discrete
    candidates' as eight planks tried where most were rules that did not apply)."""
    from furncheck.report.explanation import SHOWN, tried_lines
    from furncheck.suggest.tried import Trial

    trials = tuple(Trial("support plank", "shelf", FAILED, "why", "support-1")
                   for _ in range(SHOWN + 3)) + tuple(
        Trial(rule, "", NOT_APPLICABLE, "it does not repair sagging")
        for rule in ("apron", "stretcher"))
    tried = Tried(24, 0, 0, {}, 3, 8, False, (), (), 24, 0, 0, trials)
    assert tried_lines(tried, found=0)[-1] == \
        "and 5 more trials: 3 candidates tried, 2 where a rule did not apply"
    assert tried_lines(replace(tried, discrete=trials[:SHOWN + 1]), found=0)[-1] == \
        "and 1 more trial: 1 candidate tried"
