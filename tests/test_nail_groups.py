"""Per-nail forces of a nail row: the elastic fastener-group rule (contract section 3).

With the nails at y_i = (i + 1/2) L / n - L / 2 along the joint line and S = sum y_i^2
(so y_max = L (n - 1) / (2 n), S = L^2 (n^2 - 1) / (12 n)), the worst nail carries

    pull  = (2 |M_y| / t - F_n) / n + |M_x| y_max / S
    shear = |(|F_x| / n + |M_n| y_max / S, F_y / n)|

Designs: ``physics_designs.cantilever`` with every plank weightless (density 1e-6 kg/m^3)
and 50 kg on the base's far side to hold it down; the base/post joint (the post standing on
the base at x = -150, joint point (-150, 0, 12), L = 400 mm, 20 nails: y_max = 190 mm,
S = 266,000 mm^2 = 0.266 m^2; nail axis n = world z, joint line y = world y, x = world
x).  The tree is statically determinate, so the joint wrench is the statics of the loads
on the post above it, whatever the model.
"""

from __future__ import annotations

import numpy as np
import physics_designs as pd
import pytest

from furncheck.check import check_design
from furncheck.design import parse_design
from furncheck.geometry import Joint
from furncheck.nail_groups import nail_pull_shear, nail_row

REL = 5e-3
JOINT_Z = 12.0            # mm, the base's top face
POST_TOP = 800.0          # mm, where the post is pushed (inside its 812 mm top)
LEVER = POST_TOP - JOINT_Z


def _post_design(loads: list, joints: list | None = None) -> dict:
    design = pd.cantilever(mass=0.0, density=1e-6)
    design["loads"] = [{"plank": "base", "mass": 50.0, "at": [150, 0, 12]}] + loads
    if joints is not None:
        design["joints"] = joints
    return design


def _base_post(design: dict):
    report = check_design(parse_design(pd.to_text(design), "post.yaml", "yaml"))
    case = report.cases[0]
    assert case.stability == "stable"
    return next(j for j in case.joints if set(j.planks) == {"base", "post"})


def test_nail_row_geometry():
    """y_max and S of rows of 1, 2, 3 and 20 nails over L = 0.4 m against the sums
    themselves: n = 2: y = +-L/4, S = L^2/8; n = 3: y = 0, +-L/3, S = 2 L^2/9; n = 20:
    y_max = 0.19 m, S = 0.266 m^2; one nail: the lever rule, y_max = L/2, S = L^2/4."""
    def joint(nails):
        return Joint(("a", "b"), "a", "b", np.zeros(3), 0.4, nails, np.eye(3), 0.012)

    for nails in (2, 3, 20):
        y = (np.arange(nails) + 0.5) * 0.4 / nails - 0.2
        y_max, spread = nail_row([joint(nails)])
        assert y_max[0] == pytest.approx(np.abs(y).max(), rel=1e-12)
        assert spread[0] == pytest.approx((y * y).sum(), rel=1e-12)
    assert nail_row([joint(20)])[0][0] == pytest.approx(0.19)
    assert nail_row([joint(20)])[1][0] == pytest.approx(0.266, rel=1e-12)
    y_max, spread = nail_row([joint(1)])
    assert (y_max[0], spread[0]) == pytest.approx((0.2, 0.04))


def test_post_pushed_along_its_joint_line():
    """40 N along +y at the post's top (-150, 0, 800): the joint carries F = (0, 40, 0) N
    and M = r x F = (-0.788 x 40, 0, 0) = (-31.52, 0, 0) N m, a rocking moment about x.
    Outer nail: pull = |M_x| y_max / S = 31.52 x 0.19 / 0.266 = 22.51 N (the paper's rule
    gave 0); shear = F_y / n = 2.0 N."""
    joint = _base_post(_post_design([{"plank": "post", "force": [0, 40, 0],
                                      "at": [-150, 0, POST_TOP]}]))
    assert abs(joint.moment[0]) == pytest.approx(LEVER * 40 / 1000, rel=REL)
    assert joint.pull == pytest.approx(31.52 * 0.19 / 0.266, rel=REL)
    assert joint.shear == pytest.approx(40 / 20, rel=REL)


def test_twisted_joint():
    """Two opposite 100 N pushes along x at the post's top, at y = +150 and y = -150 mm:
    no net force, M = (0, 0, -2 x 0.15 x 100) = -30 N m about the nail axis, a twist.
    Outer nail: shear = |M_n| y_max / S = 30 x 0.19 / 0.266 = 21.43 N; pull = 0."""
    joint = _base_post(_post_design([
        {"plank": "post", "force": [100, 0, 0], "at": [-150, 150, POST_TOP]},
        {"plank": "post", "force": [-100, 0, 0], "at": [-150, -150, POST_TOP]}]))
    assert np.abs(joint.force).max() <= 1e-6
    assert abs(joint.moment[2]) == pytest.approx(30.0, rel=REL)
    assert joint.shear == pytest.approx(30.0 * 0.19 / 0.266, rel=REL)
    assert abs(joint.pull) <= 1e-6


def test_one_nail_works_against_the_far_end_of_its_joint():
    """The same push along the joint line with the base/post joint listed as one nail:
    pull = 2 |M_x| / L = 2 x 31.52 / 0.4 = 157.6 N (the lever rule of 2 |M_y| / t,
    along the joint line)."""
    joint = _base_post(_post_design([{"plank": "post", "force": [0, 40, 0],
                                      "at": [-150, 0, POST_TOP]}],
                                    joints=[{"planks": ["base", "post"], "nails": 1},
                                            ["post", "shelf"]]))
    assert joint.nails == 1
    assert joint.pull == pytest.approx(2 * LEVER * 40 / 400, rel=REL)


def test_paper_case_is_unchanged():
    """The paper's case (M_x = M_n = 0): the cantilever shelf with 10 kg at d = 200 mm on
    a weightless shelf: M_y = 98.1 N x 0.2 m = 19.62 N m, F_n = 0 across the nail axis
    (x), shear 98.1 / 15 = 6.54 N, pull = 2 x 19.62 / 0.012 / 15 = 218.0 N."""
    design = pd.cantilever(mass=10.0, d=200.0, density=1e-6)
    report = check_design(parse_design(pd.to_text(design), "c.yaml", "yaml"))
    joint = next(j for j in report.cases[0].joints if set(j.planks) == {"post", "shelf"})
    assert joint.pull == pytest.approx(2 * 98.1 * 0.2 / 0.012 / 15, rel=REL)
    assert joint.shear == pytest.approx(98.1 / 15, rel=REL)


def test_worst_nail_is_the_max_over_the_row():
    """The closed forms equal the largest pull and shear over the n nails computed one
    by one from pull_i = (2|M_y|/t - F_n)/n + M_x y_i/S and shear_i = |(F_x/n - M_n y_i/S,
    F_y/n)|, for random wrenches, frames and rows."""
    rng = np.random.default_rng(3)
    for _ in range(50):
        nails = int(rng.integers(2, 30))
        length = float(rng.uniform(0.02, 0.6))
        frame, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        joint = Joint(("f", "e"), "f", "e", np.zeros(3), length, nails, frame, 0.012)
        wrench = rng.normal(size=6) * np.array([100, 100, 100, 10, 10, 10])
        pull, shear = nail_pull_shear([joint], wrench[None])
        F, M = frame.T @ wrench[:3], frame.T @ wrench[3:]
        y = (np.arange(nails) + 0.5) * length / nails - length / 2
        S = (y * y).sum()
        pulls = (2 * abs(M[1]) / 0.012 - F[2]) / nails + M[0] * y / S
        shears = np.hypot(F[0] / nails - M[2] * y / S, F[1] / nails)
        assert pull[0] == pytest.approx(pulls.max(), rel=1e-9)
        assert shear[0] == pytest.approx(shears.max(), rel=1e-9)
