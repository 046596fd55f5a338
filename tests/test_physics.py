"""Physics against hand calculations (contract sections 2-3, paper section 5.1).

Every test states its hand calculation in the docstring.  Designs come from
``physics_designs`` (millimetres; geometry described there).  g = 9.81 m/s^2, plank mass =
750 kg/m^3 x volume unless the test sets the density to 1e-6 to make self-weight negligible.
Relative tolerance of hand-calculated forces and moments: 0.5 %.

The tests run in the default model (elastic, contract section 3a) where their statics hold
in both models: determinate joint wrenches (a cantilevered shelf), the thresholds of
tipping and sliding (equilibrium of the whole design, whatever the planks' stiffness).
Where a hand calculation assumes rigid planks (how an indeterminate design shares its load:
no thrust at a bench's feet, a table top that stays flat on its legs) the test passes
``model="rigid"`` and says so; ``test_elastic_physics.py`` checks the elastic model's
sharing (portal thrust, continuous shelves).  Where the verdict differs (a 12 mm shelf or
seat sags in the elastic model) the test states both, with the sag by hand.
"""

from __future__ import annotations

import numpy as np
import physics_designs as pd
import pytest

from furncheck.check import check_design
from furncheck.design import parse_design
from furncheck.design.model import with_model

G = pd.G
REL = 5e-3          # 0.5 % on hand-calculated forces and moments
BALANCE = 1e-3      # 0.1 % on force and moment balance


# --- helpers ----------

def check(design: dict, fmt: str = "yaml", model: str | None = None):
    """The report of the design dict, read as ``fmt``, in ``model`` (None: the default)."""
    text = pd.to_text(design, fmt)
    return check_design(with_model(
        parse_design(text, f"{design.get('name', 'design')}.{fmt}", fmt), model))


case_of = pd.case_of
joint_of = pd.joint_of


def contact_sum(case, plank: str | None = None) -> np.ndarray:
    """(3,) N: sum of the ground's forces (on one plank, or on all)."""
    forces = [c.force for c in case.contacts if plank is None or c.plank == plank]
    return np.sum(np.array(forces, dtype=float).reshape(-1, 3), axis=0)


def applied(design: dict, case_name: str = "default"):
    """[(plank id, force (3,) N, point (3,) m)]: self-weight of every plank at its centre and
    the case's loads, from the design dict itself (not from the loader)."""
    scale = 0.001 if design.get("units", "mm") == "mm" else 1.0
    material = design.get("material") or {}
    density = material.get("density", pd.DENSITY)
    default_t = material.get("thickness", pd.T if scale == 0.001 else pd.T / 1000)
    centres = {}
    out = []
    for plank in design["planks"]:
        t = plank.get("thickness", default_t)
        mass = density * plank["size"][0] * plank["size"][1] * t * scale ** 3
        centre = np.array(plank["center"], dtype=float) * scale
        centres[plank["id"]] = centre
        out.append((plank["id"], np.array([0.0, 0.0, -mass * G]), centre))
    for load in pd.case_loads(design, case_name):
        point = (np.array(load["at"], dtype=float) * scale if "at" in load
                 else centres[load["plank"]])
        force = (np.array([0.0, 0.0, -load["mass"] * G]) if "mass" in load
                 else np.array(load["force"], dtype=float))
        out.append((load["plank"], force, point))
    return out


def force_scale(design: dict, case_name: str = "default") -> float:
    """N: sum of the magnitudes of all applied forces (self-weight and loads)."""
    return sum(float(np.linalg.norm(f)) for _, f, _ in applied(design, case_name))


def plank_residual(design: dict, case, plank: str) -> tuple[np.ndarray, np.ndarray]:
    """Force (N) and moment about the plank centre (N m) of everything acting on one plank:
    joint wrenches (the first plank exerts +force/+moment about the joint point on the
    second, so the second exerts the opposite on the first), ground contacts, self-weight
    and loads.  Zero in equilibrium."""
    scale = 0.001 if design.get("units", "mm") == "mm" else 1.0
    centre = np.array(next(p["center"] for p in design["planks"] if p["id"] == plank),
                      dtype=float) * scale
    force = np.zeros(3)
    moment = np.zeros(3)

    def add(f, m, point):
        nonlocal force, moment
        force = force + f
        moment = moment + m + np.cross(point - centre, f)

    for j in case.joints:
        f, m = np.array(j.force, dtype=float), np.array(j.moment, dtype=float)
        point = np.array(j.point, dtype=float) * scale
        if j.planks[1] == plank:
            add(f, m, point)
        if j.planks[0] == plank:
            add(-f, -m, point)
    for c in case.contacts:
        if c.plank == plank:
            add(np.array(c.force, dtype=float), np.zeros(3), np.array(c.point) * scale)
    for owner, f, point in applied(design, case.name):
        if owner == plank:
            add(f, np.zeros(3), point)
    return force, moment


# --- 1. cantilevered shelf ----------

SHELF_MASS = pd.plank_mass(300, 300)            # 0.81 kg
POST_MASS = pd.plank_mass(800, 400)             # 2.88 kg
T_EDGE = 0.012                                  # m, the shelf's (edge plank's) thickness
SHELF_EI = 3000e6 * 0.300 * 0.012 ** 3 / 12      # N m^2, the 300 x 12 mm MDF shelf: 129.6


def cantilever_shelf_sag(load: float, d: float, density: float = 750.0) -> float:
    """mm: the cantilevered shelf's tip drop from the tangent at the post (contract 3a),
    ``load`` N at ``d`` m from the post face on L = 0.3 m, plus its own weight:
    P d^2 (3 L - d) / 6 EI + w L^4 / 8 EI (shear deformation, P d / (5/6 G A) = 8e-6 m
    for 98 N, is 0.2 %)."""
    w = density * 0.3 * 0.012 * G
    return 1000.0 * (load * d ** 2 * (3 * 0.3 - d) / (6 * SHELF_EI)
                     + w * 0.3 ** 4 / (8 * SHELF_EI))


def verdict_kinds(report) -> set[str]:
    return {v.kind for v in report.violations}


@pytest.mark.parametrize("model", ["elastic", "rigid"])
@pytest.mark.parametrize("density", [750.0, 1e-6], ids=["self-weight", "weightless"])
def test_cantilever_shelf_joint_wrench(density, model):
    """Shelf joint post/shelf, 10 kg on the shelf d = 200 mm from the post face; the same
    wrench in both models (statics alone fixes it, contract 3a).

    W = 10 x 9.81 = 98.1 N; shelf weight W_s = 750 x 0.3 x 0.3 x 0.012 x 9.81 = 7.946 N at
    its centre, 150 mm from the post face (W_s ~ 0 at density 1e-6).
    Shelf equilibrium: the post holds it up with F = (0, 0, W + W_s) = (0, 0, 106.05) N and
    M = W d + W_s x 0.15 = 19.62 + 1.192 = 20.81 N m about the joint line (world y).
    Joint frame: n = +x (nail axis), x = world z (shelf thickness normal), y = joint line.
    F_n = 0 (no horizontal load), so per nail (15 nails = floor(300 / 20), t = 12 mm):
    pull = 2 M / t / 15 = 2 x 20.81 / 0.012 / 15 = 231.2 N, shear = (W + W_s) / 15 = 7.07 N.
    Weightless: F_z = 98.1 N, M = 19.62 N m, pull = 218.0 N, shear = 6.54 N.
    Verdict: valid in the rigid model; in the elastic model the shelf sags (and the 12 mm
    post it bends, too): tip drop P d^2 (3 L - d) / 6 EI + w L^4 / 8 EI = 3.53 + 0.21 mm
    (EI = 3000 x 300 x 12^3 / 12 N mm^2), 1.5 x that > 2 x 300 / 400 = 1.5 mm allowed.
    """
    design = pd.cantilever(mass=10.0, d=200.0, density=density)
    report = check(design, model=model)
    case = case_of(report)
    joint = joint_of(case, "post", "shelf")

    load = 10.0 * G
    shelf_w = pd.plank_mass(300, 300, density=density) * G
    moment = load * 0.200 + shelf_w * 0.150
    assert joint.nails == pd.CANTI_SHELF_NAILS
    assert joint.point == pytest.approx((-144.0, 0.0, 600.0), abs=1e-6)
    assert joint.force[2] == pytest.approx(load + shelf_w, rel=REL)
    assert np.hypot(joint.force[0], joint.force[1]) == pytest.approx(0.0, abs=1e-6 * load)
    assert np.linalg.norm(joint.moment) == pytest.approx(moment, rel=REL)
    assert abs(joint.moment[1]) == pytest.approx(moment, rel=REL)      # about the joint line
    assert joint.pull == pytest.approx(2.0 * moment / T_EDGE / 15, rel=REL)
    assert joint.shear == pytest.approx((load + shelf_w) / 15, rel=REL)
    assert joint.durable and case.stable
    if model == "rigid":
        assert report.valid
    else:
        assert verdict_kinds(report) == {"sagging"}
        (shelf,) = [p for p in case.planks if p.id == "shelf"]
        assert shelf.sag == pytest.approx(cantilever_shelf_sag(load, 0.2, density), rel=0.02)
        assert shelf.sag_allowed == pytest.approx(1.5)


def test_cantilever_base_post_joint_wrench():
    """Joint base/post of the same cantilever (10 kg at d = 200 mm), with self-weight.

    The base holds up post + shelf + load: F = (0, 0, W + W_s + W_p) with W = 98.1 N,
    W_s = 7.946 N, W_p = 750 x 0.8 x 0.4 x 0.012 x 9.81 = 28.25 N -> F_z = 134.30 N.
    Moment about the joint point (post centre line, x = -150): load at x = 56 (arm 0.206 m),
    shelf centre at x = 6 (arm 0.156 m), post on the line: M = 98.1 x 0.206 + 7.946 x 0.156
    = 20.209 + 1.240 = 21.448 N m about world y (the joint line).
    F_n = F_z > 0 presses the post on the base; t = post thickness 12 mm, 20 nails:
    pull = (2 x 21.448 / 0.012 - 134.30) / 20 = (3574.7 - 134.3) / 20 = 172.0 N.
    """
    report = check(pd.cantilever(mass=10.0, d=200.0))
    joint = joint_of(case_of(report), "base", "post")
    load, shelf_w, post_w = 10.0 * G, SHELF_MASS * G, POST_MASS * G
    f_z = load + shelf_w + post_w
    moment = load * 0.206 + shelf_w * 0.156
    assert joint.nails == pd.CANTI_BASE_NAILS
    assert joint.point == pytest.approx((-150.0, 0.0, 12.0), abs=1e-6)
    assert joint.force[2] == pytest.approx(f_z, rel=REL)
    assert np.linalg.norm(joint.moment) == pytest.approx(moment, rel=REL)
    assert abs(joint.moment[1]) == pytest.approx(moment, rel=REL)
    assert joint.pull == pytest.approx((2.0 * moment / 0.012 - f_z) / 20, rel=REL)
    assert joint.shear == pytest.approx(0.0, abs=1e-6 * f_z)


def test_cantilever_axial_push_reduces_pull():
    """Cantilever, 10 kg at d = 200 mm, plus a horizontal push H = 20 N on the shelf's free
    end (156, 0, 600) towards the post (force (-20, 0, 0)); its line passes through the joint
    point, so M is unchanged: M = 98.1 x 0.2 + 7.946 x 0.15 = 20.81 N m.
    Horizontal equilibrium of the shelf: the post pushes it with +20 N along n = +x, i.e.
    F_n = +20 N (compressive).  pull = (2 M / t - F_n) / 15 = (3468.7 - 20) / 15 = 229.9 N;
    shear = sqrt(F_x^2 + F_y^2) / 15 = (W + W_s) / 15 = 7.07 N (F_x is the vertical force).
    (Stable: friction 0.5 x 148 N = 74 N > 20 N; tipping about x = -200 needs 12 N m against
    > 25 N m of restoring moment from the load alone.)
    """
    report = check(pd.cantilever(mass=10.0, d=200.0, push=20.0))
    case = case_of(report)
    joint = joint_of(case, "post", "shelf")
    load, shelf_w = 10.0 * G, SHELF_MASS * G
    moment = load * 0.2 + shelf_w * 0.15
    assert case.stable
    assert joint.force[0] == pytest.approx(20.0, rel=REL)
    assert joint.force[2] == pytest.approx(load + shelf_w, rel=REL)
    assert abs(joint.moment[1]) == pytest.approx(moment, rel=REL)
    assert joint.pull == pytest.approx((2.0 * moment / T_EDGE - 20.0) / 15, rel=REL)
    assert joint.shear == pytest.approx((load + shelf_w) / 15, rel=REL)


def test_listed_joint_order_flips_the_wrench_not_the_nail_forces():
    """Listing the shelf joint as [shelf, post] (edge plank first) reports what the shelf
    exerts on the post: F = (0, 0, -(W + W_s)) = (0, 0, -106.05) N, the moment reversed; the
    nail forces are the same, pull = 2 M / t / 15 = 231.2 N, shear = 106.05 / 15 = 7.07 N."""
    design = pd.cantilever(mass=10.0, d=200.0)
    design["joints"] = [["base", "post"], ["shelf", "post"]]
    case = case_of(check(design))
    joint = joint_of(case, "shelf", "post")
    reference = joint_of(case_of(check(pd.cantilever(mass=10.0, d=200.0))), "post", "shelf")
    load, shelf_w = 10.0 * G, SHELF_MASS * G
    moment = load * 0.2 + shelf_w * 0.15
    assert joint.force[2] == pytest.approx(-(load + shelf_w), rel=REL)
    assert np.allclose(joint.force, -np.array(reference.force), rtol=1e-9, atol=1e-9)
    assert np.allclose(joint.moment, -np.array(reference.moment), rtol=1e-9, atol=1e-9)
    assert joint.nails == 15
    assert joint.pull == pytest.approx(2.0 * moment / T_EDGE / 15, rel=REL)
    assert joint.shear == pytest.approx((load + shelf_w) / 15, rel=REL)


def test_shelf_plank_equilibrium():
    """The shelf has one joint: the post's wrench on it balances its loads exactly.
    F_joint + W_load + W_shelf = 0 and M_joint + sum (r_i - p) x F_i = 0 about the joint
    point p, with r_load = p + (0.2, 0, 0.006) m, r_shelf = p + (0.15, 0, 0) m."""
    design = pd.cantilever(mass=10.0, d=200.0)
    case = case_of(check(design))
    joint = joint_of(case, "post", "shelf")
    p = np.array(joint.point) / 1000.0
    force = np.array(joint.force, dtype=float)
    moment = np.array(joint.moment, dtype=float)
    for _owner, f, point in pd_applied_on(design, "shelf"):
        force += f
        moment += np.cross(point - p, f)
    scale = (10.0 + SHELF_MASS) * G
    assert np.linalg.norm(force) <= BALANCE * scale
    assert np.linalg.norm(moment) <= BALANCE * scale * 0.3


def pd_applied_on(design: dict, plank: str):
    return [(o, f, p) for o, f, p in applied(design) if o == plank]


def test_backrest_lean_pull_with_compression():
    """Bench with a back rest (800 x 300, 40 nails along the seat's back edge, joint point
    (0, -144, 462)); case `lean`: 100 N backwards (-y) at the back rest's top (z = 760).
    Back rest equilibrium: the seat holds it with F = (0, +100, W_b), W_b = 750 x 0.8 x 0.3 x
    0.012 x 9.81 = 21.19 N (its own weight presses it on the seat: F_n = +21.19 N), and
    M = 100 N x (0.760 - 0.462) m = 29.8 N m about world x (the joint line).
    pull = (2 x 29.8 / 0.012 - 21.19) / 40 = (4966.7 - 21.19) / 40 = 123.6 N;
    shear = 100 / 40 = 2.5 N (the horizontal force is across the nails).
    Each leg takes half the lean sideways: leg/seat shear = 50 / 15 = 3.33 N.
    The rigid model (the paper's): in the elastic model the 800 mm seat's sag also pushes
    the legs apart (a thrust in their joints' shear; test_elastic_physics's portals check
    that) and the seat sags beyond its allowance."""
    report = check(pd.bench_with_back(mass=70.0, lean=100.0), model="rigid")
    case = case_of(report, "lean")
    joint = joint_of(case, "seat", "back")
    back_w = pd.plank_mass(800, 300) * G
    moment = 100.0 * (0.760 - 0.462)
    assert joint.nails == 40
    assert joint.force[1] == pytest.approx(100.0, rel=REL)
    assert joint.force[2] == pytest.approx(back_w, rel=REL)
    assert abs(joint.moment[0]) == pytest.approx(moment, rel=REL)
    assert np.linalg.norm(joint.moment) == pytest.approx(moment, rel=REL)
    assert joint.pull == pytest.approx((2 * moment / 0.012 - back_w) / 40, rel=REL)
    assert joint.shear == pytest.approx(100.0 / 40, rel=REL)
    for leg in ("leg_l", "leg_r"):
        assert joint_of(case, "seat", leg).shear == pytest.approx(50.0 / 15, rel=REL)
    assert case.stable and report.valid


# --- 2. bench reactions ----------

SEAT_MASS = pd.plank_mass(800, 300)             # 2.16 kg
BENCH_LEG_MASS = pd.plank_mass(450, 300)        # 1.215 kg


def test_symmetric_bench_reactions():
    """Seat on two legs, 80 kg at the seat centre.  W = (80 + 2.16 + 2 x 1.215) x 9.81
    = 829.8 N.  By symmetry each leg's ground reaction is W / 2 = 414.9 N; the vertical
    reactions add up to W; with vertical loads only there is no horizontal reaction
    (each leg's sideways ground force ~ 0, here <= 0.1 % of W).
    The seat presses each leg down with (80 x 9.81 + 2.16 x 9.81) / 2 = 403.0 N.
    The rigid model (the paper's): no horizontal reaction holds for rigid planks; elastic
    ones bend like a portal frame, whose feet push out against friction (the thrust of
    test_elastic_physics's portal, Kleinlogel), and the 800 mm seat sags."""
    report = check(pd.bench(mass=80.0, x=0.0), model="rigid")
    case = case_of(report)
    weight = (80.0 + SEAT_MASS + 2 * BENCH_LEG_MASS) * G
    for leg in ("leg_l", "leg_r"):
        reaction = contact_sum(case, leg)
        assert reaction[2] == pytest.approx(weight / 2, rel=REL)
        assert np.hypot(reaction[0], reaction[1]) <= 1e-3 * weight
        assert len([c for c in case.contacts if c.plank == leg]) == 4
        joint = joint_of(case, "seat", leg)
        assert joint.force[2] == pytest.approx(-(80.0 + SEAT_MASS) * G / 2, rel=REL)
    assert contact_sum(case)[2] == pytest.approx(weight, rel=BALANCE)
    assert report.valid


@pytest.mark.parametrize("model", ["elastic", "rigid"])
@pytest.mark.parametrize("density", [750.0, 1e-6], ids=["self-weight", "weightless"])
def test_asymmetric_bench_lever_rule(density, model):
    """Seat on legs at x = -350 and +350 mm, P = 80 x 9.81 = 784.8 N at x = a = 200 mm.
    Lever rule about the left leg: R_right = W_seat / 2 + W_leg + P (350 + a) / 700,
    R_left = W_seat / 2 + W_leg + P (350 - a) / 700.  With self-weight (W_seat = 21.19 N,
    W_leg = 11.92 N): R_right = 10.59 + 11.92 + 616.6 = 639.1 N, R_left = 10.59 + 11.92 +
    168.2 = 190.7 N.  Weightless: R_right = 616.6 N, R_left = 168.2 N.  (Each leg stands on a
    12 mm wide end face around its centre line; treating it as a point at the centre line
    errs by < 0.05 % in the rigid model.)  In the elastic model the legs bend with the seat
    and the ground's force on each foot may sit anywhere on its 12 mm face: the moment
    balance about the left foot moves R_right by at most W x 6 mm / 700 mm (0.86 % of the
    total weight W) from the lever rule; the vertical forces still add up to W."""
    report = check(pd.bench(mass=80.0, x=200.0, density=density), model=model)
    case = case_of(report)
    load = 80.0 * G
    seat_w = pd.plank_mass(800, 300, density=density) * G
    leg_w = pd.plank_mass(450, 300, density=density) * G
    right = seat_w / 2 + leg_w + load * (350 + 200) / 700
    left = seat_w / 2 + leg_w + load * (350 - 200) / 700
    if model == "rigid":
        assert contact_sum(case, "leg_r")[2] == pytest.approx(right, rel=REL)
        assert contact_sum(case, "leg_l")[2] == pytest.approx(left, rel=REL)
    else:
        shift = (right + left) * 6.0 / 700.0
        assert abs(contact_sum(case, "leg_r")[2] - right) <= shift
        assert abs(contact_sum(case, "leg_l")[2] - left) <= shift
        assert contact_sum(case)[2] == pytest.approx(right + left, rel=BALANCE)
    assert case.stable


# --- 3. table: sliding and tipping thresholds ----------

TABLE_LOAD = 20.0                          # kg at the top's centre
PUSH_AT = [-pd.TABLE_HALF_X, 0, 406]       # mm, centre of the top's -x end face
PUSH_HEIGHT = 0.406                        # m


def table_weight() -> float:
    """N: (20 + 5.4 + 4 x 0.216) x 9.81 = 26.264 x 9.81 = 257.65 N."""
    return (TABLE_LOAD + pd.table_self_mass()) * G


def pushed_table(push: float, friction: float) -> dict:
    return pd.table(friction=friction, loads=[
        {"plank": "top", "mass": TABLE_LOAD, "at": [0, 0, 412]},
        {"plank": "top", "force": [push, 0, 0], "at": PUSH_AT}])


@pytest.mark.parametrize("factor, slides", [(0.95, False), (1.05, True)])
def test_table_sliding_threshold(factor, slides):
    """Table (top 1000 x 600 on four legs 400 high), 20 kg on the top, horizontal push P along
    +x at the top's end face, h = 406 mm.  W = 257.65 N, mu = 0.5.
    Sliding iff P > mu W = 128.8 N: P = 0.95 mu W = 122.4 N holds, 1.05 mu W = 135.3 N slides.
    Tipping is not the limit: W d / h = 257.65 x 0.450 / 0.406 = 285.6 N > 135.3 N (d = 450 mm
    from the centre of mass to the +x legs' outer edge)."""
    weight, mu = table_weight(), 0.5
    tip = weight * pd.TABLE_FOOT_X / 1000 / PUSH_HEIGHT
    assert tip > 1.05 * mu * weight          # the premise: tipping is not the limit
    report = check(pushed_table(factor * mu * weight, mu))
    case = case_of(report)
    kinds = {v.kind for v in report.violations}
    if slides:
        assert case.stability == "sliding" and not case.stable
        assert "sliding" in kinds and "lift-off" not in kinds
    else:
        assert case.stability == "stable" and case.stable
        assert "sliding" not in kinds and "lift-off" not in kinds
        assert contact_sum(case)[0] == pytest.approx(-factor * mu * weight, rel=BALANCE)


@pytest.mark.parametrize("factor, topples", [(0.95, False), (1.05, True)])
def test_table_tipping_threshold(factor, topples):
    """Same table and push, mu = 5 so friction (5 W) is never the limit.  Tipping about the
    +x legs' outer edge x = 450 mm: lift-off iff P h > W d, P > W d / h = 257.65 x 0.450 /
    0.406 = 285.6 N.  P = 0.95 x 285.6 = 271.3 N stands, 1.05 x 285.6 = 299.9 N topples."""
    weight = table_weight()
    tip = weight * pd.TABLE_FOOT_X / 1000 / PUSH_HEIGHT
    report = check(pushed_table(factor * tip, friction=5.0))
    case = case_of(report)
    kinds = {v.kind for v in report.violations}
    if topples:
        assert case.stability == "lift-off" and not case.stable
        assert "lift-off" in kinds
    else:
        assert case.stability == "stable" and case.stable
        assert "lift-off" not in kinds and "sliding" not in kinds
        # the -x legs still stand, lightly: W / 2 - P h / 0.888 m > 0 (legs at x = +-444)
        back = contact_sum(case, "leg_mp")[2] + contact_sum(case, "leg_mm")[2]
        assert back > 0.0


# --- 4. corner load inside / outside the footprint ----------

CORNER_MASS = 100.0


def test_corner_load_inside_footprint_lifts_opposite_leg_only():
    """100 kg at (400, 250) on the table top, inside the support rectangle |x| <= 450,
    |y| <= 300.  Total mass 106.26 kg, centre of mass (376.4, 235.3) mm.  Treating the table
    as a rigid plate on equal legs at (+-444, +-270): the diagonally opposite leg (-,-) would
    carry W/4 (1 - 376.4/444 - 235.3/270) = -0.72 W/4 < 0, so it lifts (carries ~0) and the
    other three legs (whose triangle contains the centre of mass) carry W = 1042.4 N.
    Nothing topples: the case is stable (and the design valid).
    The rigid model (the paper's): the hand calculation takes the top as a rigid plate; an
    elastic top bends under the corner load and sags beyond its allowance."""
    design = pd.table(loads=[{"plank": "top", "mass": CORNER_MASS, "at": [400, 250, 412]}])
    report = check(design, model="rigid")
    case = case_of(report)
    weight = (CORNER_MASS + pd.table_self_mass()) * G
    assert case.stability == "stable" and case.stable
    assert not any(v.kind in ("lift-off", "sliding") for v in report.violations)
    assert report.valid, report.violations
    assert np.linalg.norm(contact_sum(case, "leg_mm")) <= 1e-6 * weight
    standing = sum(contact_sum(case, leg)[2] for leg in ("leg_pp", "leg_mp", "leg_pm"))
    assert standing == pytest.approx(weight, rel=BALANCE)
    assert min(contact_sum(case, leg)[2] for leg in ("leg_pp", "leg_mp", "leg_pm")) > 0.0


def test_corner_load_outside_footprint_topples():
    """The same 100 kg at (495, 250) on the overhanging top, beyond the leg line x = 450:
    about that edge the load tips with 100 x 9.81 x 0.045 = 44.1 N m, the table's own weight
    (6.264 kg at x = 0) holds with only 6.264 x 9.81 x 0.450 = 27.7 N m -> lift-off."""
    design = pd.table(loads=[{"plank": "top", "mass": CORNER_MASS, "at": [495, 250, 412]}])
    report = check(design)
    case = case_of(report)
    assert case.stability == "lift-off" and not case.stable
    assert any(v.kind == "lift-off" for v in report.violations)
    assert report.valid is False


@pytest.mark.parametrize("factor, topples", [(0.95, False), (1.05, True)])
def test_overhang_tipping_mass_threshold(factor, topples):
    """A mass m on the top at (495, 0), 45 mm beyond the tipping edge x = 450; the table's
    own mass M = 5.4 + 4 x 0.216 = 6.264 kg acts at x = 0, 450 mm inside the edge.
    Lift-off iff m x 0.045 > M x 0.450, m* = 10 M = 62.64 kg: 0.95 m* = 59.5 kg stands,
    1.05 m* = 65.8 kg topples."""
    m_star = pd.table_self_mass() * 0.450 / 0.045
    design = pd.table(loads=[{"plank": "top", "mass": factor * m_star, "at": [495, 0, 412]}])
    case = case_of(check(design))
    assert case.stability == ("lift-off" if topples else "stable")


# --- 5. nail-pull limit of the cantilever ----------

def shelf_limit_mass(d: float = 0.200) -> float:
    """kg: the shelf mass m* at which the post/shelf pull per nail is 700 N.
    700 = 2 M / t / 15 -> M* = 700 x 15 x 0.012 / 2 = 63 N m = m* g d + W_s x 0.15
    -> m* = (63 - 7.946 x 0.15) / (9.81 x 0.2) = (63 - 1.192) / 1.962 = 31.50 kg."""
    m_limit = 700.0 * pd.CANTI_SHELF_NAILS * T_EDGE / 2.0
    return (m_limit - SHELF_MASS * G * 0.150) / (G * d)


@pytest.mark.parametrize("model", ["elastic", "rigid"])
@pytest.mark.parametrize("factor, durable", [(0.95, True), (1.05, False)])
def test_shelf_nail_pull_limit(factor, durable, model):
    """Cantilever with m = 0.95 m* = 29.93 kg (pull 666 N, durable) and 1.05 m* = 33.08 kg
    (pull 734 N > 700 N: non-durable), m* = 31.50 kg from ``shelf_limit_mass`` (self-weight of
    the shelf included).  pull = 2 (m g 0.2 + 1.192) / 0.012 / 15.  The base/post joint (20
    nails) stays below its limit in both: F_n = 33.08 x 9.81 + 7.95 + 28.25 = 360.7 N,
    pull = (2 x (33.08 x 9.81 x 0.206 + 1.24) / 0.012 - 360.7) / 20 = 549 N.  The centre
    of mass stays over the base, so both cases are stable.  The same in both models (the
    shelf's joint is determinate); in the elastic model the shelf also sags: ~30 kg at
    0.2 m drop its tip P d^2 (3 L - d) / 6 EI = 10.6 mm or more, 1.5 x that > 1.5 mm."""
    mass = factor * shelf_limit_mass()
    report = check(pd.cantilever(mass=mass, d=200.0), model=model)
    case = case_of(report)
    joint = joint_of(case, "post", "shelf")
    moment = mass * G * 0.2 + SHELF_MASS * G * 0.15
    assert joint.pull == pytest.approx(2 * moment / T_EDGE / 15, rel=REL)
    assert joint.pull == pytest.approx(700.0 * factor, rel=0.01)
    assert joint.durable is durable
    assert case.durable is durable
    assert case.stable
    assert joint_of(case, "base", "post").durable
    non_durable = [v for v in report.violations if v.kind == "non-durable"]
    if model == "elastic":
        (shelf,) = [p for p in case.planks if p.id == "shelf"]
        assert shelf.sag == pytest.approx(cantilever_shelf_sag(mass * G, 0.2), rel=0.02)
        assert "sagging" in verdict_kinds(report)
        assert verdict_kinds(report) <= {"sagging", "non-durable"}
    if durable:
        assert not non_durable
        assert report.valid is (model == "rigid")
    else:
        assert report.valid is False
        assert [(v.where, v.case) for v in non_durable] == [("post/shelf", "default")]


def test_safety_factor_divides_capacity():
    """Safety factor 2: capacities 700 / 2 = 350 N pull, 190 / 2 = 95 N shear.  With
    m = 0.6 m* = 18.90 kg: M = 18.90 x 9.81 x 0.2 + 1.192 = 38.28 N m, pull = 2 x 38.28 /
    0.012 / 15 = 425.3 N: durable without a factor (< 700 N) but not with it (> 350 N)."""
    design = pd.cantilever(mass=0.6 * shelf_limit_mass(), d=200.0)
    assert joint_of(case_of(check(design)), "post", "shelf").durable
    design["safety_factor"] = 2.0
    joint = joint_of(case_of(check(design)), "post", "shelf")
    assert joint.pull_capacity == pytest.approx(350.0)
    assert joint.shear_capacity == pytest.approx(95.0)
    moment = 0.6 * shelf_limit_mass() * G * 0.2 + SHELF_MASS * G * 0.15
    assert joint.pull == pytest.approx(2 * moment / T_EDGE / 15, rel=REL)
    assert not joint.durable


# --- 6. balance of forces on every design above ----------

def balance_designs() -> dict[str, dict]:
    weight = table_weight()
    return {
        "cantilever": pd.cantilever(mass=10.0, d=200.0),
        "cantilever-push": pd.cantilever(mass=10.0, d=200.0, push=20.0),
        "cantilever-limit": pd.cantilever(mass=1.05 * shelf_limit_mass(), d=200.0),
        "bench": pd.bench(mass=80.0, x=0.0),
        "bench-asym": pd.bench(mass=80.0, x=200.0),
        "table-slide": pushed_table(0.95 * 0.5 * weight, 0.5),
        "table-tip": pushed_table(0.95 * weight * 0.45 / PUSH_HEIGHT, 5.0),
        "table-corner": pd.table(loads=[{"plank": "top", "mass": CORNER_MASS,
                                         "at": [400, 250, 412]}]),
        "bench-with-back": pd.bench_with_back(),
        "bench-push-included": {**pd.bench(mass=80.0, x=100.0), "load_cases": {
            "push": {"include": ["default"],
                     "loads": [{"plank": "seat", "force": [60, 20, 0], "at": [-400, 0, 456]}]}}},
        **{f"hand-{k}": v for k, v in pd.hand_designs().items()},
    }


def stable_cases():
    for name, design in balance_designs().items():
        cases = ["default"] + list(design.get("load_cases") or {})
        for case_name in cases:
            yield pytest.param(name, case_name, id=f"{name}-{case_name}")


@pytest.mark.parametrize("name, case_name", list(stable_cases()))
def test_contact_forces_balance_loads(name, case_name):
    """In every stable case: sum of contact forces + sum of loads + self-weight = 0 (to 0.1 %
    of the sum of the applied force magnitudes), and likewise the moments about the origin
    (to 0.1 % of that force scale x 1 m)."""
    design = balance_designs()[name]
    case = case_of(check(design), case_name)
    if not case.stable:
        pytest.skip(f"case {case_name} is {case.stability}: no equilibrium to balance")
    scale = force_scale(design, case_name)
    force, moment = np.zeros(3), np.zeros(3)
    for c in case.contacts:
        f, p = np.array(c.force, dtype=float), np.array(c.point, dtype=float) / 1000.0
        force += f
        moment += np.cross(p, f)
    for _, f, p in applied(design, case_name):
        force += f
        moment += np.cross(p, f)
    assert np.linalg.norm(force) <= BALANCE * scale, force
    assert np.linalg.norm(moment) <= BALANCE * scale * 1.0, moment


@pytest.mark.parametrize("name, case_name", list(stable_cases()))
def test_every_plank_in_equilibrium(name, case_name):
    """Each plank separately: joint wrenches on it (+F, +M from the first listed plank on the
    second; -F, -M on the first), its ground contacts, self-weight and loads sum to zero in
    force (0.1 % of the force scale) and in moment about its centre (0.1 % x scale x 1 m)."""
    design = balance_designs()[name]
    case = case_of(check(design), case_name)
    if not case.stable:
        pytest.skip(f"case {case_name} is {case.stability}")
    scale = force_scale(design, case_name)
    for plank in design["planks"]:
        force, moment = plank_residual(design, case, plank["id"])
        assert np.linalg.norm(force) <= BALANCE * scale, (plank["id"], force)
        assert np.linalg.norm(moment) <= BALANCE * scale, (plank["id"], moment)
