"""Nail joints cut into parts along their rows (elastic model, ``beams.nail_row_parts``,
``elastic.joint_part_counts``): planks nailed along each other are held along the row,
and bend together as a nailed composite beam, not at the joint's middle alone.

The parts' springs are the contract's one spring of the whole row where the planks do not
bend (test 1), so a rigid plank, or a joint across both beams, sees no change.  A joint
along a wide board held near its edge keeps the one spring (the board bends across its
width there, as a plate, which its one beam cannot show: holding it along the row would
understate its sag).  Hand checks, with E, G and the nails' slip modulus K of the
material (12 mm MDF: 3000 N/mm^2, 800 N/mm^2, 1200 N/mm per nail):

* A T-beam: a flange F (1000 x 80 mm, flat) nailed every 20 mm along the top edge of a
  web W (1000 x 96 mm, on edge) standing on the floor without friction, held by it at
  its end corners alone (``floor_at_corners``: as on two narrow feet, simply supported at
  its ends; the floor would hold it along its length), a spread load P on F.  F is
  carried by its joint alone, so statics fixes the joint's wrench: force P + W_F down,
  no moment about the joint's middle.  The nailed T bends as a mechanically jointed
  beam, Eurocode 5 (EN 1995-1-1) Annex B:
      gamma_F = 1 / (1 + pi^2 E A_F s / (K L^2)),   a_W = gamma_F A_F (h_F + h_W) / 2 /
      (gamma_F A_F + A_W),   a_F = (h_F + h_W) / 2 - a_W,
      (EI)_ef = E (I_F + gamma_F A_F a_F^2 + I_W + A_W a_W^2)
  and its sag is 5 w L^4 / 384 (EI)_ef + w L^2 / 8 k G A_W (the web's shear), w all the
  load over L: 1.367 mm, where the web alone (no composite action) would sag 3.08 mm and a
  glued T 1.20 mm.  With the row held at its middle alone (one spring), F's whole load
  reaches W there: P_F L^3 / 48 E I_W + P_F L / 4 k G A_W, and W's own weight's sag.
* A wide board (300 mm, 25 thicknesses) on two such webs under its edges keeps one spring
  per row; on one web under its middle (a spine) its row is cut.
* Rigid motions and the unit change leave the cut, the forces and the sags as they are.
"""

from __future__ import annotations

import math

import numpy as np
import physics_designs as pd
import pytest
import yaml

from furncheck import tolerances as tol
from furncheck.check import check_design
from furncheck.design import parse_design
from furncheck.geometry import analyze
from furncheck.statics import build_model
from furncheck.statics.beams import SHEAR_FACTOR, nail_row_parts, nail_row_springs
from furncheck.statics.offsets import skew_many

G = 9.81
LOAD_N = 600.0


def _t_beam(load_x: float | None = None, flange: float = 80.0,
            flange_y: float = 0.0) -> dict:
    """The T-beam of the module docstring: its load spread on the flange, or at
    ``load_x`` mm along it; a flange ``flange`` mm wide, its middle ``flange_y`` mm off
    the web's."""
    load = {"plank": "flange", "force": [0, 0, -LOAD_N]}
    load.update({"spread": True} if load_x is None else {"at": [load_x, flange_y, 108]})
    return {
        "furncheck": 1, "name": "t-beam", "units": "mm", "model": "elastic",
        "material": {"friction": 0},
        "planks": [
            {"id": "web", "size": [1000, 96], "center": [0, 0, 48], "rotation": [90, 0, 0]},
            {"id": "flange", "size": [1000, flange], "center": [0, flange_y, 102]},
        ],
        "loads": [load],
    }


def _parsed(doc: dict):
    return parse_design(yaml.safe_dump(doc, sort_keys=False), "t-beam.yaml", "yaml")


def _transported(springs: np.ndarray, arms: np.ndarray) -> np.ndarray:
    """sum_g A_g^T W_g A_g: springs at points r_g from a joint's point as one spring there
    (A_g = [[I, -[r_g]x], [0, I]] takes a motion (u, theta) of the joint's point to the
    deviation at r_g: u + theta x r_g)."""
    A = np.zeros((len(arms), 6, 6))
    A[:, :3, :3] = A[:, 3:, 3:] = np.eye(3)
    A[:, :3, 3:] = -skew_many(arms)
    return np.einsum("gji,gjk,gkl->il", A, springs, A)


@pytest.mark.parametrize("parts", [2, 3, 5, 10])
def test_parts_of_a_nail_row_are_its_one_spring_on_planks_that_do_not_bend(parts):
    """Part g of m: n / m nails at y_g = ((g + 1/2) / m - 1/2) L, S_m = L^2 (n / m^2 -
    1 / n) / 12 m.  Moved to the joint's point, the parts add up to contract 3a's spring
    of the whole row: n k_s, n k_s, n k_w; k_w S, n k_w (t/2)^2, k_s S with S = L^2 (n^2
    - 1) / 12 n (sum_g [S_m + (n / m) y_g^2] = S), to round-off."""
    design = _parsed(_t_beam())
    (joint,) = analyze(design).joints
    material = design.material
    springs, rows, fractions = nail_row_parts([joint], [parts], material.nail_slip,
                                              material.nail_withdrawal)
    assert springs.shape == (parts, 6, 6) and not rows.any()
    assert fractions == pytest.approx((np.arange(parts) + 0.5) / parts - 0.5)
    arms = fractions[:, None] * joint.length * joint.frame[:, 1]
    whole = nail_row_springs([joint], material.nail_slip, material.nail_withdrawal)[0]
    assert np.allclose(_transported(springs, arms), whole, rtol=1e-12,
                       atol=1e-12 * np.abs(whole).max())
    n, length = joint.nails, joint.length
    spread = length ** 2 * (n * n - 1) / (12 * n)
    in_frame = joint.frame.T @ whole[3:, 3:] @ joint.frame
    assert np.diag(in_frame) == pytest.approx([
        material.nail_withdrawal * spread,
        n * material.nail_withdrawal * (joint.edge_thickness / 2) ** 2,
        material.nail_slip * spread])


def _gamma_sag(design) -> tuple[float, float, float, float]:
    """m: (the nailed T's sag by Eurocode 5 Annex B, the web's alone, a glued T's, the sag
    with the whole load at the web's middle), each with the web's shear (module
    docstring)."""
    material = design.material
    E, Gs, K = material.elastic_modulus, material.shear_modulus, material.nail_slip
    web = design.planks[design.plank_index["web"]]
    flange = design.planks[design.plank_index["flange"]]
    span, s = web.length, material.nail_spacing
    weights = {p.id: design.plank_mass(p) * G for p in (web, flange)}
    w = (LOAD_N + weights["flange"] + weights["web"]) / span
    A_f, I_f, h_f = flange.width * flange.thickness, \
        flange.width * flange.thickness ** 3 / 12, flange.thickness
    A_w, I_w, h_w = web.width * web.thickness, web.thickness * web.width ** 3 / 12, web.width
    shear = w * span ** 2 / (8 * SHEAR_FACTOR * Gs * A_w)

    def composite(gamma: float) -> float:
        a_w = gamma * A_f * (h_f + h_w) / 2 / (gamma * A_f + A_w)
        a_f = (h_f + h_w) / 2 - a_w
        stiffness = E * (I_f + gamma * A_f * a_f ** 2 + I_w + A_w * a_w ** 2)
        return 5 * w * span ** 4 / (384 * stiffness) + shear

    gamma = 1 / (1 + math.pi ** 2 * E * A_f * s / (K * span ** 2))
    point = LOAD_N + weights["flange"]
    w_web = weights["web"] / span
    middle = point * span ** 3 / (48 * E * I_w) + point * span / (4 * SHEAR_FACTOR * Gs * A_w) \
        + 5 * w_web * span ** 4 / (384 * E * I_w) \
        + w_web * span ** 2 / (8 * SHEAR_FACTOR * Gs * A_w)
    return composite(gamma), composite(0.0), composite(1.0), middle


def test_a_nailed_t_beam_bends_as_eurocode_5_annex_b_says(floor_at_corners):
    """The module docstring's T-beam: its row cut into 10 parts (1000 mm / 100 mm), the
    joint's wrench statics', and the web's sag within 2 % of the Annex B (gamma method)
    value: 1.367 mm, between the glued T's 1.20 and the web's alone 3.08."""
    design = _parsed(_t_beam())
    model = build_model(design, analyze(design))
    assert model.plank_cache["joint_part_counts"].tolist() == [10]
    nailed, alone, glued, _ = _gamma_sag(design)
    assert glued < nailed < alone
    case = check_design(design).cases[0]
    flange_weight = design.plank_mass(design.planks[design.plank_index["flange"]]) * G
    (joint,) = case.joints
    assert np.array(joint.force) == pytest.approx([0, 0, -(LOAD_N + flange_weight)],
                                                  abs=1e-6 * LOAD_N)
    assert np.abs(joint.moment).max() < 1e-6 * LOAD_N
    web = next(p for p in case.planks if p.id == "web")
    assert web.sag / 1000.0 == pytest.approx(nailed, rel=0.02)


def test_a_row_held_at_its_middle_alone_loads_the_web_there(whole_joints, floor_at_corners):
    """Every joint one spring (as before parts): the flange's whole load reaches the web at
    the joint's middle, P_F L^3 / 48 E I_W + P_F L / 4 k G A_W plus the web's own weight's
    sag (within 2 %), more than twice the nailed T's."""
    design = _parsed(_t_beam())
    _, _, _, middle = _gamma_sag(design)
    web = next(p for p in check_design(design).cases[0].planks if p.id == "web")
    assert web.sag / 1000.0 == pytest.approx(middle, rel=0.02)
    assert middle > 2 * _gamma_sag(design)[0]


def test_a_wide_board_along_its_edges_keeps_one_spring_each(monkeypatch):
    """A 300 mm flange (25 thicknesses, JOINT_PART_NARROW) on two webs under its edges (140
    mm off its middle, JOINT_PART_CORE): each row stays one spring, and the sag of its
    overhangs says the model overstates it; on one web under its middle (a spine) the
    row is cut.  (The webs stand on the floor along their length, so the flange would
    span across between them, ``elastic._spans_across``, its beam no longer along its
    rows: that rule is off here, for a board whose beam runs along them.)"""
    monkeypatch.setattr(tol, "SPAN_ACROSS_CROSSING", 0.0)
    doc = _t_beam(flange=300.0)
    doc["planks"][:1] = [{"id": f"web_{side}", "size": [1000, 96], "center": [0, y, 48],
                          "rotation": [90, 0, 0]} for side, y in (("a", 140), ("b", -140))]
    edges = _parsed(doc)
    model = build_model(edges, analyze(edges))
    assert model.plank_cache["joint_part_counts"].tolist() == [1, 1]
    assert model.joint_parts is None
    notes = [v.message for v in check_design(edges).violations
             if v.kind == "sagging" and v.where == "flange"]
    assert notes and all("which the model holds at the joint's middle only" in note
                         for note in notes)
    spine = _parsed(_t_beam(flange=300.0))
    assert build_model(spine, analyze(spine)).plank_cache["joint_part_counts"].tolist() \
        == [10]
    assert tol.JOINT_PART_NARROW * 12 < 300 and 140 > tol.JOINT_PART_CORE * 150


@pytest.mark.parametrize("depth, parts", [(150.0, 10), (200.0, 1)])
def test_an_edge_plank_is_held_along_its_edge_up_to_16_thicknesses(depth, parts):
    """A web 150 mm deep (12.5 thicknesses) on edge under the 80 mm flange carries the
    row's force in its plane: the row is cut (a 96 mm and a 97 mm rail are alike).  A
    web 200 mm deep (16.7 thicknesses, JOINT_PART_EDGE_NARROW) would bend across its
    depth under the row's moment about its line, as a plate: the row stays whole."""
    doc = _t_beam()
    doc["planks"][0].update(size=[1000, depth], center=[0, 0, depth / 2])
    doc["planks"][1]["center"] = [0, 0, depth + 6]
    doc["loads"] = []
    design = _parsed(doc)
    assert build_model(design, analyze(design)).plank_cache["joint_part_counts"].tolist() \
        == [parts]


def test_a_shelf_deeper_than_it_is_wide_keeps_one_spring_per_end():
    """A 300 x 400 shelf between two sides 300 mm apart, its 400 mm ends nailed to them:
    its beam runs along its depth, along its rows, which lie at its edges; it is 25
    thicknesses wide and spans between the sides as a plate, so they stay whole (its
    sag then overstated, never understated)."""
    shelf = _parsed({
        "furncheck": 1, "name": "deep-shelf", "units": "mm", "model": "elastic",
        "planks": [
            {"id": "side_l", "size": [600, 400], "center": [-156, 0, 300],
             "rotation": [0, -90, 0]},
            {"id": "side_r", "size": [600, 400], "center": [156, 0, 300],
             "rotation": [0, -90, 0]},
            {"id": "shelf", "size": [300, 400], "center": [0, 0, 300]}]})
    geometry = analyze(shelf)
    assert all(joint.edge == "shelf" for joint in geometry.joints)
    assert build_model(shelf, geometry).plank_cache["joint_part_counts"].tolist() == [1, 1]


def test_cut_joints_under_rigid_motion_and_in_metres():
    """A point load 200 mm off the middle (the parts share it unevenly): the joint's moment
    is statics', the load's r x F about the joint's middle (0, 120, 0) N m, summed from
    its parts' wrenches and arms; the design turned by -123.4 degrees about z and moved by
    (0.8, -1.7) m, and written in metres, gives the same cut, joint wrench (turned), sags
    and stresses."""
    doc = _t_beam(load_x=200.0)
    base = check_design(_parsed(doc)).cases[0]
    (joint,) = base.joints          # statics: the load's moment about the joint's middle
    arm = np.array([0.200, 0.0, 0.108 - 0.096])                 # m, load point - joint point
    assert np.array(joint.moment) == pytest.approx(np.cross(arm, [0, 0, -LOAD_N]),
                                                   abs=1e-6 * LOAD_N)
    turned = np.array(pd.rz(-123.4))
    for other, rotation, factor in ((pd.rigid_motion(doc, -123.4, 800.0, -1700.0), turned,
                                     1.0), (pd.convert_units(doc, "m"), np.eye(3), 1000.0)):
        design = _parsed(other)
        model = build_model(design, analyze(design))
        assert model.plank_cache["joint_part_counts"].tolist() == [10]
        case = check_design(design).cases[0]
        for a, b in zip(base.joints, case.joints):
            assert rotation @ np.array(a.force) == pytest.approx(b.force, abs=1e-9 * LOAD_N)
            assert rotation @ np.array(a.moment) == pytest.approx(b.moment, abs=1e-9 * LOAD_N)
        for a, b in zip(base.planks, case.planks):
            assert a.sag == pytest.approx(b.sag * factor, rel=1e-6, abs=1e-9)
            assert a.stress == pytest.approx(b.stress, rel=1e-6, abs=1e-9)


@pytest.mark.parametrize("dof_name", ["flange.length", "flange.x", "web.x"])
def test_the_force_sensitivity_of_a_cut_joint_follows_its_parts_arms(dof_name):
    """A point load 200 mm off the middle: the joint's wrench about its point is statics',
    P x (load point - joint point) for its moment, and a change of either plank's length
    or place moves the joint's point and its parts' arms.  The sensitivity (its parts'
    wrench rates summed about the joint's point, plus each part's arm rate x its force)
    equals the central difference of full checks at +-0.5 mm to 1e-4 of its scale."""
    from furncheck.dofs import apply_dof, parse_dof, structure
    from furncheck.sensitivity import sensitivity

    design = _parsed(_t_beam(load_x=200.0))
    dof = parse_dof(design, dof_name)
    rates = sensitivity(design, [dof], design.load_cases[0].name).joint_wrenches[0, 0]
    frame = structure(design, analyze(design))
    step = 0.5                                  # mm, the file's unit

    def wrench(sign: float) -> np.ndarray:
        edited = apply_dof(design, frame, dof, sign * step)
        (joint,) = check_design(edited).cases[0].joints
        return np.concatenate([joint.force, joint.moment])

    central = (wrench(1.0) - wrench(-1.0)) / (2 * step)
    scale = max(np.abs(central).max(), np.abs(rates).max())
    assert scale > 1e-3
    assert np.abs(rates - central).max() <= 1e-4 * scale, (rates, central)


def test_the_shear_flow_of_a_nailed_t_beam_loads_its_end_nails(floor_at_corners):
    """The T-beam bends compositely because its nails carry the shear flow between
    flange and web: Eurocode 5 Annex B, F = gamma_F E A_F a_F s V / (EI)_ef per nail for
    the shear force V.  Near the supports V is largest; the end part (the 100 mm of row
    next to a support, its mean V = w x 450 mm) holds 5 nails at about that mean: about
    59 N each, where the whole row's wrench sums the two ends' flows away (no shear).
    The joint's reported shear is its worst part's (within 10 % of the hand value), and
    its utilization counts it."""
    from furncheck.nail_groups import nail_pull_shear

    design = _parsed(_t_beam())
    material = design.material
    E, K = material.elastic_modulus, material.nail_slip
    web = design.planks[design.plank_index["web"]]
    flange = design.planks[design.plank_index["flange"]]
    span, s = web.length, material.nail_spacing
    w = (LOAD_N + (design.plank_mass(web) + design.plank_mass(flange)) * G) / span
    A_f, I_f, h_f = flange.width * flange.thickness, \
        flange.width * flange.thickness ** 3 / 12, flange.thickness
    A_w, I_w, h_w = web.width * web.thickness, web.thickness * web.width ** 3 / 12, web.width
    gamma = 1 / (1 + math.pi ** 2 * E * A_f * s / (K * span ** 2))
    a_w = gamma * A_f * (h_f + h_w) / 2 / (gamma * A_f + A_w)
    a_f = (h_f + h_w) / 2 - a_w
    stiffness = E * (I_f + gamma * A_f * a_f ** 2 + I_w + A_w * a_w ** 2)
    per_nail = gamma * E * A_f * a_f * s * (w * 0.45) / stiffness
    case = check_design(design).cases[0]
    (joint,) = case.joints
    assert joint.shear == pytest.approx(per_nail, rel=0.10)
    (whole,) = nail_pull_shear(analyze(design).joints,
                               np.array([list(joint.force) + list(joint.moment)]))[1]
    assert whole < 0.01 * joint.shear
    assert joint.utilization == pytest.approx(
        max(joint.pull / joint.pull_capacity, joint.shear / joint.shear_capacity))
