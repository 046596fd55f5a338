"""Invariants of the checker (style guide: "a rigid motion of the whole design, or a change
of units, changes no verdict and no force magnitude; forces always balance the loads").

(a) A rigid motion of the whole design on the ground (rotation phi about the world z axis,
    translation in x and y) changes no verdict; joint and contact forces and moments turn
    with the design (so their magnitudes do not change), per-nail forces do not change.
(b) The same design written in metres instead of millimetres (or the reverse), or as JSON
    instead of YAML, changes nothing: verdicts, forces, moments, per-nail forces.
(c) On every design of the catalog (``designs/``) and every load case with ground forces,
    the ground's contact forces balance self-weight and loads (0.1 %), in force and moment.
(d) A vertical load anywhere inside the support polygon never reads as lift-off (contract
    section 3), nor as sliding (vertical loads need no friction).
(e) The elastic model (contract section 3a) keeps (a) and (b), and more: a rigid motion or a
    change of units leaves every plank's sag, sag_allowed, stress, strength and utilization
    unchanged (relative 1e-6, absolute 1e-6 of the plank's allowed sag, of its strength, or
    of 1 for the utilization; the round-off measured is below 1e-7 of those), sag and
    sag_allowed being in the file's unit, so that a unit change scales them.  On the
    catalog's ``model: elastic`` designs and a few catalog designs run elastic
    (``with_model``), and (c) holds for them too: in the elastic model the ground's forces
    balance self-weight and loads.

(f) The design's mirror image (in the plane x = 0), or its planks written in another
    order, changes no verdict, per-nail force, sag or stress; forces, moments and points
    are mirrored with it.

The designs are the hand-written ones of ``physics_designs`` plus every readable catalog file.
Defaults that are lengths (thickness 12 mm, nail spacing 20 mm, tolerance 0.5 mm) are left
implicit when the original leaves them implicit, so (b) also checks that they mean the same
physical length in a metre file.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import physics_designs as pd
import pytest
import yaml
from hypothesis import HealthCheck, Phase, example, given, settings
from hypothesis import strategies as st

from furncheck import tolerances as tol
from furncheck.check import check_design
from furncheck.design import parse_design
from furncheck.design.model import with_model
from furncheck.errors import DesignError

ROOT = Path(__file__).resolve().parents[1]
CATALOG_DIR = ROOT / "designs"
REL = 1e-6              # relative tolerance of (a) and (b)
ABS = 1e-7              # absolute tolerance, as a fraction of the design's force scale (N)
BALANCE = 1e-3          # 0.1 % for (c)
PHASES = (Phase.explicit, Phase.reuse, Phase.generate)
"""No shrinking: a failing example is reported as found (the design name and motion are
readable anyway), which keeps a failing run of this file short."""
SETTINGS = settings(deadline=None, max_examples=20, derandomize=True, phases=PHASES,
                    suppress_health_check=[HealthCheck.too_slow])


# --- designs ----------

def catalog_files() -> list[Path]:
    if not CATALOG_DIR.is_dir():
        return []
    return sorted(p for p in CATALOG_DIR.rglob("*")
                  if p.is_file() and p.suffix in (".yaml", ".yml", ".json"))


def fmt_of(path: Path) -> str:
    return "json" if path.suffix == ".json" else "yaml"


def _readable_catalog() -> dict[str, dict]:
    """Catalog designs that load (files meant to be rejected are left out), as dicts."""
    designs = {}
    for path in catalog_files():
        text = path.read_text(encoding="utf-8")
        try:
            parse_design(text, str(path), fmt_of(path))
            data = json.loads(text) if fmt_of(path) == "json" else yaml.safe_load(text)
        except (DesignError, ValueError, yaml.YAMLError):
            continue
        if isinstance(data, dict):
            designs[f"catalog:{path.relative_to(CATALOG_DIR)}"] = data
    return designs


DESIGNS: dict[str, dict] = {**{f"hand:{k}": v for k, v in pd.hand_designs().items()},
                            **_readable_catalog()}
NAMES = sorted(DESIGNS)


def check(design: dict, fmt: str = "yaml", name: str = "design", model: str | None = None):
    """The report of the design dict, read as ``fmt``, in ``model`` (None: the file's)."""
    text = pd.to_text(design, fmt)
    return check_design(with_model(parse_design(text, f"{name}.{fmt}", fmt), model))


def force_scale(design: dict) -> float:
    """N: total self-weight plus the magnitudes of every load of every case (from the loader,
    SI), a scale for absolute tolerances."""
    model = parse_design(pd.to_text(design), "scale.yaml", "yaml")
    total = sum(model.plank_mass(p) for p in model.planks) * pd.G
    for case in model.load_cases:
        total += sum(float(np.linalg.norm(load.force)) for load in case.loads)
    return max(total, 1e-3)


# --- comparison ----------

def assert_same_physics(a, b, scale: float, rotation=np.eye(3), map_point=lambda p: p,
                        point_tol: float = 1e-6):
    """Report ``b`` is report ``a`` seen through a rigid motion / change of unit / mirror:
    same verdicts; b's points = map_point(a's points) (file units, within point_tol); b's
    forces = rotation @ a's, and its moments too, but for a mirror (``rotation`` of
    determinant -1), where a moment, an axial vector, turns as -rotation @ it; same
    per-nail forces and nail counts.  Joints are matched by their two planks either way
    round (the file's plank order says which is first: a joint named the other way
    round carries the opposite wrench), violations by the planks they name in any
    order."""
    turn_moment = np.linalg.det(rotation) * np.asarray(rotation)
    f_abs, m_abs = ABS * scale, ABS * scale * 1.0          # N, N m (1 m lever)
    pull_abs = ABS * scale * 200.0                          # 2 |M| / t with t >= 10 mm

    def close(x, y, abs_tol, what):
        x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        assert np.allclose(y, x, rtol=REL, atol=abs_tol), f"{what}: {x} -> {y}"

    assert b.valid == a.valid
    key = lambda v: (v.kind, sorted(v.where.split(",")), v.case)        # noqa: E731
    assert sorted(map(key, b.violations)) == sorted(map(key, a.violations))
    assert [c.name for c in b.cases] == [c.name for c in a.cases]
    for ca, cb in zip(a.cases, b.cases):
        where = f"case {ca.name}"
        assert (cb.stability, cb.stable, cb.durable) == (ca.stability, ca.stable, ca.durable), \
            where
        pair = lambda joint: tuple(sorted(joint.planks))                  # noqa: E731
        assert sorted(map(pair, cb.joints)) == sorted(map(pair, ca.joints)), where
        joints_b = {pair(j): j for j in cb.joints}
        for ja in ca.joints:
            jb = joints_b[pair(ja)]
            sign = 1.0 if tuple(jb.planks) == tuple(ja.planks) else -1.0
            what = f"{where} joint {'/'.join(ja.planks)}"
            assert (jb.nails, jb.durable) == (ja.nails, ja.durable), what
            close(map_point(np.array(ja.point)), jb.point, point_tol, what + " point")
            close(np.linalg.norm(ja.force), np.linalg.norm(jb.force), f_abs, what + " |force|")
            close(np.linalg.norm(ja.moment), np.linalg.norm(jb.moment), m_abs,
                  what + " |moment|")
            close(sign * rotation @ np.array(ja.force), jb.force, f_abs, what + " force")
            close(sign * turn_moment @ np.array(ja.moment), jb.moment, m_abs,
                  what + " moment")
            close(ja.pull, jb.pull, pull_abs, what + " pull")
            close(ja.shear, jb.shear, f_abs, what + " shear")
            close(ja.utilization, jb.utilization, pull_abs / min(ja.pull_capacity,
                                                                 ja.shear_capacity),
                  what + " utilization")
        assert len(cb.contacts) == len(ca.contacts), where
        # contacts matched by position (their order may legitimately differ)
        unmatched = list(cb.contacts)
        for contact in ca.contacts:
            target = map_point(np.array(contact.point))
            distances = [np.linalg.norm(np.array(c.point) - target)
                         if c.plank == contact.plank else np.inf for c in unmatched]
            best = int(np.argmin(distances))
            assert distances[best] <= point_tol, f"{where}: contact at {contact.point} lost"
            cb_contact = unmatched.pop(best)
            close(rotation @ np.array(contact.force), cb_contact.force, f_abs,
                  f"{where} contact {contact.plank} at {contact.point}")
        # anchors in the file's order: the same ties, moved and turned with the design
        assert [x.plank for x in cb.anchors] == [x.plank for x in ca.anchors], where
        for anchor_a, anchor_b in zip(ca.anchors, cb.anchors):
            what = f"{where} anchor of {anchor_a.plank} at {anchor_a.point}"
            close(map_point(np.array(anchor_a.point)), anchor_b.point, point_tol,
                  what + " point")
            close(rotation @ np.array(anchor_a.force), anchor_b.force, f_abs, what)
            close(anchor_a.utilization, anchor_b.utilization, f_abs / anchor_a.capacity,
                  what + " utilization")


# --- (a) rigid motion ----------

def moved(design: dict, phi: float, tx_m: float, ty_m: float):
    """The moved design, the rotation matrix and the point map (file units)."""
    k = pd.unit_factor(design)
    tx, ty = tx_m * k, ty_m * k
    rotation = np.array(pd.rz(phi))
    new = pd.rigid_motion(design, phi, tx, ty)
    return new, rotation, (lambda p: rotation @ p + np.array([tx, ty, 0.0]))


def test_euler_round_trip_of_rigid_motion():
    """The transform itself: new rotation angles give exactly Rz(phi) @ R, also for upright
    planks (ry = -90, gimbal lock) and arbitrary angles."""
    for rot in ([0, -90, 0], [0, 90, 0], [10, 20, 30], [90, 0, 45], [-35, 80, 170]):
        for phi in (0.0, 33.0, -120.0, 180.0):
            new = pd.rigid_motion({"planks": [{"id": "p", "size": [1, 1], "center": [0, 0, 0],
                                               "rotation": rot}]}, phi, 0, 0)
            expected = np.array(pd.rz(phi)) @ np.array(pd.euler_matrix(rot))
            got = np.array(pd.euler_matrix(new["planks"][0]["rotation"]))
            assert np.allclose(got, expected, atol=1e-12), (rot, phi)


@pytest.mark.parametrize("name", NAMES)
def test_rigid_motion_every_design(name):
    """(a) on every design with one fixed, unremarkable motion: phi = -123.4 deg, moved by
    (0.8 m, -1.7 m)."""
    design = DESIGNS[name]
    new, rotation, map_point = moved(design, -123.4, 0.8, -1.7)
    scale = force_scale(design)
    assert_same_physics(check(design), check(new), scale, rotation, map_point,
                        point_tol=1e-9 * pd.unit_factor(design))


@SETTINGS
@given(name=st.sampled_from(NAMES), phi=st.floats(-180.0, 180.0),
       tx=st.floats(-3.0, 3.0), ty=st.floats(-3.0, 3.0))
@example(name="hand:table", phi=90.0, tx=0.0, ty=0.0)
@example(name="hand:stool", phi=180.0, tx=-1.0, ty=2.5)
def test_rigid_motion_changes_nothing(name, phi, tx, ty):
    """(a): rotation by phi (degrees) about the world z axis, then translation by (tx, ty) m."""
    design = DESIGNS[name]
    new, rotation, map_point = moved(design, phi, tx, ty)
    assert_same_physics(check(design), check(new), force_scale(design), rotation, map_point,
                        point_tol=1e-9 * pd.unit_factor(design))



def _tall_bookcase() -> dict:
    """A 2 m bookcase 318 mm wide (two 18 mm sides, seven shelves and a top nailed between
    them, books on the shelves) pushed at its top by 60 N: its left side's feet slip at
    mu N while the right side's stick.  (After ``benchmarks/catalog.py``'s design 176.)"""
    shelves = [{"id": f"shelf{i}", "size": [300, 400], "center": [159, 0, 250 * (i + 1)]}
               for i in range(7)]
    masses = [8, 5, 12, 2, 8, 5, 2]
    loads = [{"plank": f"shelf{i}", "mass": mass, **({"spread": True} if i in (4, 5) else {})}
             for i, mass in enumerate(masses)]
    loads[1]["at"] = [69, 0, 509]
    return {"furncheck": 1, "name": "tall-bookcase", "units": "mm",
            "material": {"thickness": 18},
            "planks": [{"id": "side0", "size": [2000, 400], "center": [0, 0, 1000],
                        "rotation": [0, 90, 0]},
                       {"id": "side1", "size": [2000, 400], "center": [318, 0, 1000],
                        "rotation": [0, 90, 0]},
                       *shelves,
                       {"id": "top", "size": [336, 400], "center": [159, 0, 2009]}],
            "loads": loads,
            "load_cases": {"push": {"include": ["default"], "loads": [
                {"plank": "top", "force": [60, 0, 0], "at": [159, 0, 2009]}]}}}


@pytest.mark.parametrize("phi", [37.0, -123.4])
def test_rigid_motion_of_a_design_that_slips_in_part(phi):
    """(a) where friction is at its limit at some feet only (in the rigid model; the
    elastic one's feet all stick here).  The rigid model's stiff joints
    put the round-off of its condensed matrix-vector products at about 1e-7 N here, but a
    bound of that round-off a thousand times looser (the largest entry times the sum of
    |x|) let Newton's method stop 7e-5 N short after this design was turned by 37
    degrees, and its joint and contact forces moved by 2e-5 of themselves (they now agree
    to 1e-6, the invariant's tolerance)."""
    design, model = _tall_bookcase(), "rigid"
    report = check(design, model=model)
    push = next(case for case in report.cases if case.name == "push")
    slipping = [c for c in push.contacts
                if c.force[2] > 0 and math.hypot(*c.force[:2]) >= 0.5 * c.force[2] * (1 - 1e-6)]
    sticking = [c for c in push.contacts
                if c.force[2] > 0 and math.hypot(*c.force[:2]) < 0.5 * c.force[2] * 0.99]
    assert push.stability == "stable" and slipping and sticking   # the case it is meant to be
    new, rotation, map_point = moved(design, phi, 0.8, -1.7)
    assert_same_physics(report, check(new, model=model), force_scale(design), rotation,
                        map_point, point_tol=1e-9 * pd.unit_factor(design))


def _askew_wall_shelf() -> dict:
    """``designs/wall-shelf.yaml`` after two edits of a random sweep over the catalog's
    DOFs: its shelf narrowed and turned 4.83 degrees about the vertical, the right cleat
    raised 30.8 mm (no longer nailed to the shelf, still anchored).  With the friction
    caps of its bonded solution the friction phase finds no minimum (it would slide), so
    the feasibility programs decide: it holds, near the edge of sliding, with the
    admissible forces closest to the elastic ones."""
    return {"furncheck": 1, "name": "wall-shelf-askew", "units": "mm",
            "material": {"thickness": 18},
            "walls": [{"point": [0, 0, 0], "normal": [0, 1, 0]}],
            "planks": [{"id": "cleat_l", "size": [150, 120], "center": [-220, 9, 1400],
                        "rotation": [90, 0, 0]},
                       {"id": "cleat_r", "size": [150, 120], "center": [220, 9, 1430.8],
                        "rotation": [90, 0, 0]},
                       {"id": "shelf", "size": [800, 216.6], "center": [-1.4, 141.6, 1469],
                        "rotation": [0, 0, 4.83]}],
            "anchors": [{"plank": "cleat_l", "at": [-220, 0, 1430], "wall": 0,
                         "capacity": 196},
                        {"plank": "cleat_r", "at": [220, 0, 1460.8], "wall": 0,
                         "capacity": 196}],
            "loads": [{"plank": "shelf", "mass": 15, "spread": True}]}


@pytest.mark.parametrize("phi", [5.0, 37.0, -123.4])
def test_rigid_motion_of_a_wall_shelf_the_programs_hold(phi, monkeypatch):
    """(a) where the friction programs give the forces, with walls: the pyramids of a wall's
    contacts are turned in its own frame (``feasibility._headings``).  Turned with the
    world's heading instead, they turned against the wall with the design, and this
    shelf's nail joint force moved by 0.3 % (242.46 N to 241.76 N at 5 degrees).  (Turned
    so, the shelf lies on 4.95 mm of cleat_l's 18 mm edge, too narrow for nails by the
    bearing rule; the rule is off here, the statics of the joint as found are tested.)"""
    monkeypatch.setattr(tol, "MIN_BEARING_SHARE", 0.0)
    design = _askew_wall_shelf()
    report = check(design, model="elastic")
    assert report.cases[0].stability == "stable"
    new, rotation, map_point = moved(design, phi, 0.8, -1.7)
    assert_same_physics(report, check(new, model="elastic"), force_scale(design), rotation,
                        map_point, point_tol=1e-9 * pd.unit_factor(design))


def l_shelf_edit(edit: str) -> dict:
    """``designs/l-shelf-pushed.yaml`` (pushed at 99 % of what its friction holds) after
    one edit of a random sweep over the catalog's DOFs (``benchmarks/sweep_catalog.py``):
    'post' moves its post 12.08 mm along y; 'base' moves its base 5.31 mm along -x (the
    push's point with it)."""
    design = yaml.safe_load((CATALOG_DIR / "l-shelf-pushed.yaml").read_text())
    planks = {plank["id"]: plank for plank in design["planks"]}
    if edit == "post":
        planks["post0"]["center"][1] = -7.073547761
    else:
        planks["base"]["center"][0] = -5.30933050491
        design["loads"][0]["at"][0] = 3.1244694951
    return design


@pytest.mark.parametrize("edit, phi", [("post", 37.0), ("post", -123.4), ("base", 37.0),
                                       ("base", -123.4)])
def test_rigid_motion_of_an_l_shelf_at_the_edge_of_sliding(edit, phi):
    """(a) at 99 % of friction, elastic model.  'post': its four corners all slip under
    the first caps and its Tresca energy is nearly flat along sliding; a full Newton step
    taken because it halved the out-of-balance force went uphill, 5 cm and then metres
    along that flat valley, and the minimization gave up (the programs' forces followed)
    in some turns of the design and found the minimum 0.5 mm from its start in others: a
    contact force differed by 15 %.  Such a step is now taken only where the slope along
    it is still falling at its end (``friction._FrictionEnergy._line_search``).  'base':
    its caps cannot hold it, the programs decide, and the forces closest to the elastic
    ones missed balance inside the targets' pyramids; the program's own vertex was
    reported, another one in each turn (``feasibility._admissible_edges``)."""
    design = l_shelf_edit(edit)
    report = check(design, model="elastic")
    assert report.cases[0].stability == "stable"
    new, rotation, map_point = moved(design, phi, 0.8, -1.7)
    assert_same_physics(report, check(new, model="elastic"), force_scale(design), rotation,
                        map_point, point_tol=1e-9 * pd.unit_factor(design))


def _table_with_a_short_apron() -> dict:
    """``designs/table.yaml`` after two edits of a random sweep (seed 23): its left leg
    turned 4.09 degrees about the vertical and moved 7.6 mm, its apron shortened to 829.6
    mm and moved 9.2 mm right.  The apron's end misses the leg's face by 0.62 mm where it
    meets it (tolerance 0.5 mm), though the end face's far corner lies on the face's plane
    beyond the leg."""
    design = yaml.safe_load((CATALOG_DIR / "table.yaml").read_text())
    planks = {plank["id"]: plank for plank in design["planks"]}
    planks["leg_l"].update(center=[-430.0, 7.644951, 360.0], rotation=[0.0, -90.0, 4.089682972])
    planks["apron"].update(size=[829.563094015, 100.0], center=[9.218452992, -244.0, 670.0])
    return design


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_rigid_motion_of_a_table_whose_apron_misses_a_leg(model):
    """(a) the joints themselves: an end face is measured over the part of it that lies
    on the face (``geometry.faces._region_gaps``).  Measured at its nearest corner
    anywhere, the apron was nailed to the leg only where the planks' bounding boxes met:
    turned by 37 or -123.4 degrees, not as written, and the verdicts differed."""
    design = _table_with_a_short_apron()
    report = check(design, model=model)
    missed = [v for v in report.violations if v.where == "leg_l/apron"]
    assert [v.kind for v in missed] == ["disconnected"] and "0.6243 mm" in missed[0].message
    for phi in (37.0, -123.4):
        new, rotation, map_point = moved(design, phi, 0.8, -1.7)
        assert_same_physics(report, check(new, model=model), force_scale(design), rotation,
                            map_point, point_tol=1e-9 * pd.unit_factor(design))


def _coffee_table_with_a_corner_at_the_edge() -> dict:
    """``designs/coffee-table-splayed.yaml`` after two edits of a random sweep (seed 57):
    leg_pp shortened to 397.56 mm and splayed 2.92 degrees less, leg_mp widened to 125.5
    mm.  Under the 'sit' load one foot's corner sits at the edge between sticking and
    slipping."""
    design = yaml.safe_load((CATALOG_DIR / "coffee-table-splayed.yaml").read_text())
    planks = {plank["id"]: plank for plank in design["planks"]}
    planks["leg_pp"].update(size=[397.559929298, 100.0], rotation=[0.0, -97.0811203786, 0.0])
    planks["leg_mp"]["size"] = [400.0, 125.510835245]
    return design


@pytest.mark.parametrize("phi", [37.0, -123.4])
def test_rigid_motion_of_a_coffee_table_whose_caps_went_round(phi):
    """(a) where the friction caps' updates went round: that corner's cap alternated
    between a sticking and a slipping state under Newton's and Anderson's updates, which
    settled on the 20th and last update as written (a corner lifted) and not at all when
    turned (the programs' forces closest to the elastic ones were taken): the leg_pp joint's
    force read 152.9 N and 161.6 N.  Relaxed plain updates after two that do not beat the
    least disagreement (``contacts._ActiveSet.friction_phase``) settle it in every turn."""
    design = _coffee_table_with_a_corner_at_the_edge()
    report = check(design, model="elastic")
    new, rotation, map_point = moved(design, phi, 0.8, -1.7)
    assert_same_physics(report, check(new, model="elastic"), force_scale(design), rotation,
                        map_point, point_tol=1e-9 * pd.unit_factor(design))


def _table_on_two_feet_and_a_corner() -> dict:
    """``designs/table-racking.yaml`` after three edits of a sweep with larger edits: leg_pp
    widened to 67.65 mm and moved in to x = 320.4 mm, leg_pm moved out to y = -415.5 mm,
    off the top (disconnected, standing on its own).  The top and its 20 kg rest on
    three legs, their centre of mass about a millimetre inside the line through two
    feet's corners: lifting the corners that pull once left the top on two corners of
    that line, free to turn about it."""
    design = yaml.safe_load((CATALOG_DIR / "table-racking.yaml").read_text())
    planks = {plank["id"]: plank for plank in design["planks"]}
    planks["leg_pp"].update(size=[700.0, 67.654393096], center=[320.422934694, 270.0, 350.0])
    planks["leg_pm"]["center"] = [444.0, -415.488120183, 350.0]
    return design


@pytest.mark.parametrize("motion", [(10.0, 0.0, 0.0), (90.0, 0.0, 0.0), (-123.4, -2.1, 0.3)])
def test_rigid_motion_of_a_table_left_on_two_feet(motion):
    """(a) where a lift left a part free to turn: the active set gave up (no equilibrium
    of two corners), and Newton's method on the whole law reached an equilibrium from
    every contact sticking as written and when turned by 37 or 180 degrees, but not by
    10, 90 or -123.4 (then the programs' forces closest to the elastic ones were taken): the
    legs bowed 2.14 and 3.92 mm sideways (both sagging) or 0.95 and 0.76 mm.  Seating the
    lifted corner that the turning drives into the floor
    (``contacts._ActiveSet._seat_toppling``) settles it in every turn."""
    design = _table_on_two_feet_and_a_corner()
    report = check(design, model="elastic")
    sagging = sorted(v.where for v in report.violations if v.kind == "sagging")
    assert sagging == ["leg_mm", "leg_pp", "top"]
    new, rotation, map_point = moved(design, *motion)
    assert_same_physics(report, check(new, model="elastic"), force_scale(design), rotation,
                        map_point, point_tol=1e-9 * pd.unit_factor(design))


def _table_on_one_panel() -> dict:
    """``designs/table-pine-top.yaml`` after three edits of a sweep with larger edits: its
    top turned by 7.65 degrees, leg_r moved out to x = 568.2 mm (off the top, standing on
    its own) and the apron out to y = -319.5 mm.  The top hangs on leg_l, a panel
    standing on its 12 mm edge: it topples ('lift-off'), and bolted down its leg turns so
    far on the rigid model's soft contact springs that the bolted solve moves it by about
    SLIDING_DISPLACEMENT."""
    design = yaml.safe_load((CATALOG_DIR / "table-pine-top.yaml").read_text())
    planks = {plank["id"]: plank for plank in design["planks"]}
    planks["top"]["rotation"] = [0.0, 0.0, 7.64589365311]
    planks["leg_r"]["center"] = [568.177499982, 0.0, 360.0]
    planks["apron"]["center"] = [0.0, -319.453080218, 670.0]
    return design


def test_displacement_size_is_the_length_of_each_move():
    """A node moved by (3, 4, 0) m and turned by (0, 0, 0.5) rad moves 5 m (the length of
    its translation, larger than its turn), a second node turned by (6, 0, 8) rad 10
    (its rotation vector, longer than its move), and so do their rigid turns, where the
    largest component is anything from 5 / sqrt(2) to 5 and from 8 to 10."""
    from furncheck.statics.friction import displacement_size

    ground = np.array([3.0, 4.0, 0.0, 0.0, 0.0, 0.5, 0.1, 0.0, 0.0, 6.0, 0.0, 8.0])
    assert displacement_size(ground) == pytest.approx(10.0, rel=1e-15)
    assert displacement_size(ground[:6]) == pytest.approx(5.0, rel=1e-15)
    for phi in np.radians([37.0, -123.4, 45.0]):
        turn = np.array([[np.cos(phi), -np.sin(phi), 0.0], [np.sin(phi), np.cos(phi), 0.0],
                         [0.0, 0.0, 1.0]])
        turned = (ground.reshape(-1, 3) @ turn.T).ravel()   # every translation and rotation
        assert displacement_size(turned) == pytest.approx(10.0, rel=1e-14)
        assert displacement_size(turned[:6]) == pytest.approx(5.0, rel=1e-14)


@pytest.mark.parametrize(("ground", "past"), [
    ([5.0, 5.0, 5.0, 0.0, 0.0, 0.0], False),    # largest 5, sqrt(3) x 5 = 8.66 <= 10
    ([7.0, 7.0, 0.0, 0.0, 0.0, 0.0], False),    # between: its length 9.90 <= 10
    ([7.5, 7.5, 0.0, 0.0, 0.0, 0.0], True),     # between: its length 10.6 > 10
    ([0.0, 0.0, 0.0, 0.0, 10.5, 0.0], True),    # a turn's component past 10
    ([0.0, 0.0, 0.0, 0.0, np.nan, 0.0], True),  # not a number, in a turn too
])
def test_past_sliding_is_the_length_past_sliding_displacement(ground, past):
    """``past_sliding`` says what ``displacement_size(x) > SLIDING_DISPLACEMENT`` (10 m)
    says, through each of its shortcuts, and a displacement that is not a number is past
    it (as the largest component's test took it)."""
    from furncheck.statics.friction import past_sliding

    assert tol.SLIDING_DISPLACEMENT == 10.0
    assert past_sliding(np.array(ground)) is past


@pytest.mark.parametrize("phi", [37.0, -123.4])
def test_rigid_motion_of_a_table_toppling_off_one_panel(phi):
    """(a) the size of a solve's displacements (``statics.friction.displacement_size``):
    as the largest component of the grounded planks' displacements, leg_l's bolted solve
    moved 10.3 m as written and 8.3 m turned by 37 degrees, past SLIDING_DISPLACEMENT in
    one turn and not in the other: the 'default' case's lift-off read "a mechanism" as
    written and "the design topples (held down, the ground would have to pull 12,220 N)"
    turned.  As the lengths of each node's translation and rotation vectors it is the
    same in every turn (past it: "a mechanism" in every turn)."""
    design = _table_on_one_panel()
    report = check(design, model="rigid")
    assert [case.stability for case in report.cases] == ["lift-off", "lift-off"]
    new, rotation, map_point = moved(design, phi, 0.8, -1.7)
    assert_same_physics(report, check(new, model="rigid"), force_scale(design), rotation,
                        map_point, point_tol=1e-9 * pd.unit_factor(design))


def _magazine_rack_with_a_hanging_end() -> dict:
    """``designs/magazine-rack.yaml`` after edits of a sweep with larger edits (seed 14):
    end_r cut to 278.2 x 273.9 mm, so that it hangs from the two slats, both joined to
    it at one node, above the floor; the base moved 45.1 mm along y; the kick's point
    7.6 mm higher."""
    design = yaml.safe_load((CATALOG_DIR / "magazine-rack.yaml").read_text())
    planks = {plank["id"]: plank for plank in design["planks"]}
    planks["end_r"]["size"] = [278.23386323, 273.919476451]
    planks["base"]["center"] = [0.0, -45.0776922911, 6.0]
    design["load_cases"]["kick"]["loads"][0]["at"] = [186.699400407, 87.059399128,
                                                       157.586705887]
    return design


def test_rigid_motion_of_a_magazine_rack_whose_end_does_not_bend():
    """(a) the planks' sag (``statics.sag.plank_sags``): end_r, held at one node, deviates
    in the 'default' case from the tangent there by round-off only (1e-16 to 1e-13 m) at
    both ends, and the larger sag / span of its two overhangs (spans 2 x 70.17 and 2 x
    208.06 mm) chose its measure: its allowed sag read 1.04 mm as written and 0.35 mm
    turned by 37 degrees.
    Deviations up to SAG_ROUNDOFF now tie, and the first overhang (toward its -e1 end)
    is taken in every turn: allowed 2 x 70.17 mm / 400 = 0.3509 mm."""
    design = _magazine_rack_with_a_hanging_end()
    report = check(design, model="elastic")
    default = next(case for case in report.cases if case.name == "default")
    end = next(plank for plank in default.planks if plank.id == "end_r")
    assert end.sag < 1e-9 and end.sag_allowed == pytest.approx(0.3509, abs=1e-4)
    for phi in (37.0, -123.4):
        new, rotation, map_point = moved(design, phi, 0.8, -1.7)
        assert_same_elastic(design, new, rotation, map_point, 1.0)


def _table_with_its_top_down_through_its_legs() -> dict:
    """``designs/table-pine-top.yaml`` after four edits of a sweep with larger edits (seed
    16, every third design pushed): its top (and its loads) 63.5 mm lower, through the
    legs' top ends; leg_l cut to 681.7 mm, tilted by 10 degrees and moved out to x =
    -547.7 mm; leg_r out to x = 582.3 mm; the apron 1117.9 x 36.5 mm at x = 17.3 mm,
    31.8 mm lower.  In the elastic model a near-mechanism: under the friction phase's
    first caps the minimizer turns a grounded plank by 3.3 rad."""
    design = yaml.safe_load((CATALOG_DIR / "table-pine-top.yaml").read_text())
    planks = {plank["id"]: plank for plank in design["planks"]}
    planks["top"]["center"] = [0.0, 0.0, 665.493683099]
    planks["leg_l"].update(size=[681.70052836, 500.0],
                           center=[-547.650068861, -3.30302465, 378.862725416],
                           rotation=[90.0, -80.0677195085, -90.0])
    planks["leg_r"]["center"] = [582.299347736, 0.0, 360.0]
    planks["apron"].update(size=[1117.9494166, 36.4936831],
                           center=[17.324639437, -244.0, 638.246841549])
    for load in (design["loads"][0], design["load_cases"]["lean"][0]):
        load["at"][2] = 674.493683099
    return design


@pytest.mark.parametrize("motion", [(0.0, 0.0, 0.0, True), (37.0, 0.8, -1.7, False),
                                    (-123.4, -2.1, 0.3, False)])
def test_rigid_motion_of_a_near_mechanism_the_friction_phase_settles(motion, monkeypatch):
    """(a) the round-off floors of Newton's method (``statics.friction.balance_floors``):
    the minimizer of the 'default' case's first caps turns a grounded plank by 3.3 rad,
    and each contact spring (1e10 N/m) turns the round-off of its displacement w = M x
    (5e-17 m there) into 5e-7 N: the out-of-balance force stalled at 5e-7 to 6e-7 N
    against a floor of 4.0e-7 N (the force tolerance; the floors counted the round-off
    of S0 x only), the minimization ran out of Newton steps and the programs gave the
    forces; turned by 37 or -123.4 degrees the minimization reached the floor and the
    caps settled (the joint leg_l/apron 181.6 N as written, 182.2 N turned; its 'lean'
    case stalled alike: 82.7 N against 85.6 N).  With the
    contact springs' round-off in the loose floor (CONTACT_ROUNDOFF of |M|^T K |M| |x|,
    met where a step stalls) the friction phase settles it in every turn and in metres,
    the programs never asked."""
    from furncheck.statics.contacts import _ActiveSet

    def no_programs(*arguments, **options):
        raise AssertionError("the programs were asked for the forces")

    monkeypatch.setattr(_ActiveSet, "from_programs", no_programs)
    design = _table_with_its_top_down_through_its_legs()
    report = check(design, model="elastic")
    phi, tx, ty, in_metres = motion
    new, rotation, map_point = moved(design, phi, tx, ty)
    factor = 1.0
    if in_metres:
        new = pd.convert_units(new, "m")
        factor = pd.unit_factor(new) / pd.unit_factor(design)
    assert_same_physics(report, check(new, model="elastic"), force_scale(design), rotation,
                        lambda p: map_point(p) * factor,
                        point_tol=1e-9 * pd.unit_factor(new))


def test_balance_floors_count_the_contact_springs_round_off():
    """Hand check of ``contact_magnitudes`` and ``balance_floors``: two contacts over two
    unknowns, the first (k = 1e10 N/m) with rows (1, 0), (0, 0), (0, 2), the second (an
    anchor's tie, k = 4.5e6 N/m) with rows (0.5, -3), (1, 0), (0, 0) (a resting corner's
    row has two entries, of either sign).  |M|^T K |M| = sum over rows k |M_r|^T |M_r|:
    [0][0] = 1e10 x 1 + 4.5e6 x (0.25 + 1) = 1.0005625e10, [0][1] = 4.5e6 x 0.5 x 3 =
    6.75e6, [1][1] = 1e10 x 4 + 4.5e6 x 9 = 4.00405e10.  At x = (3, 1.5) m its rows
    times |x| are 3.0027e10 and 2.025e7 + 6.006075e10 = 6.0081e10 N, so with S0 =
    diag(1, 1) N/m and b = 0: loose = max(tol, 1e-13 x 1 x 4.5 + CONTACT_ROUNDOFF x
    6.0081e10), tight = max(tol, min(loose, 1e-14 x 3)): the contact springs' round-off
    only in the loose floor (where a Newton step stalls)."""
    from furncheck.statics.friction import balance_floors, balance_sizes, contact_magnitudes

    mapping = np.array([[1.0, 0.0], [0.0, 0.0], [0.0, 2.0],
                        [0.5, -3.0], [1.0, 0.0], [0.0, 0.0]])
    contacts = contact_magnitudes(mapping, np.array([1e10, 4.5e6]))
    np.testing.assert_allclose(contacts, [[1.0005625e10, 6.75e6], [6.75e6, 4.00405e10]],
                               rtol=1e-15)
    sizes = balance_sizes(np.eye(2), np.zeros(2), contacts)
    x = np.array([3.0, 1.5])
    contact = tol.CONTACT_ROUNDOFF * 6.0081e10
    assert balance_floors(1e-9, sizes, x) == pytest.approx((1e-9, 1e-13 * 4.5 + contact),
                                                            rel=1e-12)
    assert balance_floors(1e-20, sizes, x)[0] == pytest.approx(3e-14, rel=1e-12)
    assert balance_floors(1.0, sizes, x) == (1.0, 1.0)         # the force tolerance above


def test_balance_floors_take_each_contacts_own_spring():
    """``designs/bookcase-anchored.yaml`` (elastic): its anchors' ties are springs of
    4.5e6 N/m among ground contacts of 1e10 N/m; the contact round-off of its Newton
    iterations (``_ActiveSet.balance_sizes``) takes each contact's own spring, not the
    ground's for all."""
    from furncheck.geometry import analyze
    from furncheck.statics import build_model, external_forces
    from furncheck.statics.contacts import _ActiveSet
    from furncheck.statics.friction import contact_magnitudes

    design = with_model(parse_design((CATALOG_DIR / "bookcase-anchored.yaml").read_text(),
                                     "bookcase-anchored.yaml", "yaml"), "elastic")
    model = build_model(design, analyze(design))
    springs = np.asarray(model.contact_springs)
    assert sorted(set(springs.tolist())) == [model.anchor_stiffness, model.contact_stiffness]
    solver = _ActiveSet(model, external_forces(model, design.load_cases[0]), 1.0)
    made = solver.balance_sizes[3]
    np.testing.assert_array_equal(made, contact_magnitudes(solver.contact_map(), springs))
    uniform = contact_magnitudes(solver.contact_map(),
                                 np.full(len(springs), model.contact_stiffness))
    assert (made <= uniform).all() and (made < uniform).any()


# --- (b) units and format ----------

@pytest.mark.parametrize("name", NAMES)
def test_units_change_nothing(name):
    """(b): mm -> m (or m -> mm); positions scale by 1/1000 (1000), nothing else changes."""
    design = DESIGNS[name]
    other = "m" if design.get("units", "mm") == "mm" else "mm"
    converted = pd.convert_units(design, other)
    k = pd.unit_factor(converted) / pd.unit_factor(design)
    assert_same_physics(check(design), check(converted), force_scale(design),
                        map_point=lambda p: p * k,
                        point_tol=1e-9 * pd.unit_factor(converted))


@pytest.mark.parametrize("name", NAMES)
def test_json_and_yaml_agree(name):
    """(b): the same design as JSON and as YAML gives the same report."""
    design = DESIGNS[name]
    assert_same_physics(check(design, "yaml"), check(design, "json"), force_scale(design),
                        point_tol=0.0)


@SETTINGS
@given(name=st.sampled_from(NAMES), phi=st.floats(-180.0, 180.0), tx=st.floats(-3.0, 3.0))
def test_moved_design_in_other_units(name, phi, tx):
    """(a) and (b) together: a moved design written in the other unit still agrees."""
    design = DESIGNS[name]
    new, rotation, map_point = moved(design, phi, tx, -tx / 2)
    other = "m" if design.get("units", "mm") == "mm" else "mm"
    converted = pd.convert_units(new, other)
    k = pd.unit_factor(converted) / pd.unit_factor(design)
    assert_same_physics(check(design), check(converted), force_scale(design), rotation,
                        lambda p: map_point(p) * k, point_tol=1e-9 * pd.unit_factor(converted))


# --- (f) mirror images and plank order ----------

MIRROR = np.diag([-1.0, 1.0, 1.0])


def reversed_planks(design: dict) -> dict:
    """The design with its planks written in the reverse order."""
    return {**design, "planks": list(reversed(design["planks"]))}


def assert_same_mirrored(design: dict, a, b):
    """Report ``b``, of ``design``'s mirror image (``physics_designs.mirrored``), is report
    ``a`` mirrored: the same verdicts, per-nail forces and (elastic model, every case
    solved) sags and stresses; points and forces are a's with x negated, moments -M m
    (axial vectors), M = diag(-1, 1, 1)."""
    assert_same_physics(a, b, force_scale(design), MIRROR, lambda p: MIRROR @ p,
                        point_tol=1e-9 * pd.unit_factor(design))
    if all(case.planks for case in a.cases):
        assert_same_planks(a, b)


def assert_same_reordered(design: dict, a, b):
    """Report ``b``, of ``design`` with its planks in another order, is report ``a`` (a
    joint then named the other way round carries the opposite wrench,
    ``assert_same_physics``), with the same sags and stresses (elastic model)."""
    assert_same_physics(a, b, force_scale(design), point_tol=1e-9 * pd.unit_factor(design))
    if all(case.planks for case in a.cases):
        assert_same_planks(a, b)


@pytest.mark.parametrize("name", NAMES)
def test_mirror_image_changes_nothing(name):
    """(f): the design's mirror image in the plane x = 0 (``assert_same_mirrored``).
    Physics has no handedness: a rule that read a sign or an order of the world's axes
    (a nail row's worst nail, a slip direction, a support line's side) would show here."""
    design = DESIGNS[name]
    assert_same_mirrored(design, check(design), check(pd.mirrored(design)))


@pytest.mark.parametrize("name", NAMES)
def test_plank_order_changes_nothing(name):
    """(f): the planks written in the reverse order (``assert_same_reordered``)."""
    design = DESIGNS[name]
    assert_same_reordered(design, check(design), check(reversed_planks(design)))


# --- (c) balance on the catalog ----------

def grounded_planks(case) -> set[str]:
    """Planks of the components that touch the ground (or a wall, or hang on an anchor):
    those with contacts or anchors and everything joined to them through the case's
    joints."""
    reached = {c.plank for c in case.contacts} | {a.plank for a in case.anchors}
    changed = True
    while changed:
        changed = False
        for joint in case.joints:
            a, b = joint.planks
            if (a in reached) != (b in reached):
                reached |= {a, b}
                changed = True
    return reached


CATALOG = catalog_files()


def assert_contacts_balance_loads(model, report) -> int:
    """(c) on one report: for every case with contact forces, sum of contact (and anchor)
    forces + self-weight + loads = 0 over the grounded planks, to BALANCE of the sum of
    applied force magnitudes; moments about the mean contact point to BALANCE of that
    scale x 1 m.  A spread load's resultant acts at its plank's centre.  Returns the number of cases
    checked."""
    checked = 0
    for case_model, case in zip(model.load_cases, report.cases):
        assert case.name == case_model.name
        if not case.contacts:
            continue
        planks = grounded_planks(case)
        points = np.array([c.point for c in case.contacts], dtype=float) * model.unit_scale
        reference = points.mean(axis=0)
        applied = []
        for plank in model.planks:
            if plank.id in planks:
                applied.append((np.array([0.0, 0.0, -model.plank_mass(plank) * pd.G]),
                                plank.center_array))
        centres = {p.id: p.center_array for p in model.planks}
        for load in case_model.loads:
            if load.plank in planks:
                point = centres[load.plank] if load.point is None else np.array(load.point)
                applied.append((np.array(load.force, dtype=float), point))
        scale = max(sum(float(np.linalg.norm(f)) for f, _ in applied), 1e-9)
        force, moment = np.zeros(3), np.zeros(3)
        for contact, point in zip(case.contacts, points):
            f = np.array(contact.force, dtype=float)
            force += f
            moment += np.cross(point - reference, f)
        for anchor in case.anchors:                 # the walls' forces through anchors
            f = np.array(anchor.force, dtype=float)
            force += f
            moment += np.cross(np.array(anchor.point) * model.unit_scale - reference, f)
        for f, point in applied:
            force += f
            moment += np.cross(point - reference, f)
        assert np.linalg.norm(force) <= BALANCE * scale, (case.name, force, scale)
        assert np.linalg.norm(moment) <= BALANCE * scale, (case.name, moment, scale)
        checked += 1
    return checked


@pytest.mark.skipif(not CATALOG, reason="designs/ holds no design files yet")
@pytest.mark.parametrize("path", CATALOG, ids=[str(p.relative_to(CATALOG_DIR)) for p in CATALOG])
def test_catalog_contact_forces_balance_loads(path):
    """(c): for every case with contact forces (stable ones; a toppling case's as if bolted
    down and a sliding case's with unlimited friction are equilibria too), the ground's
    forces balance self-weight and loads (``assert_contacts_balance_loads``)."""
    text = path.read_text(encoding="utf-8")
    try:
        model = parse_design(text, str(path), fmt_of(path))
    except DesignError:
        pytest.skip("an ill-formed design (rejected on purpose)")
    if not assert_contacts_balance_loads(model, check_design(model)):
        pytest.skip("no load case with ground forces (the design floats)")


def assert_planks_balance(model, report) -> int:
    """(c2) on one report: for every stable case, each plank's free body balances: the
    wrenches of its joints (what a joint's first plank exerts on its second, moment about
    the joint's point: +h on the second plank, -h on the first), its contacts' and
    anchors' forces (a resting corner's force acts on its plank and against it on the
    plank it rests on), its self-weight and its loads (a spread load's resultant at its
    centre), forces and moments about the origin to BALANCE of the case's applied force
    magnitudes (x 1 m).  Returns the number of planks checked."""
    checked = 0
    centres = {p.id: p.center_array for p in model.planks}
    for case_model, case in zip(model.load_cases, report.cases):
        if case.stability != "stable" or not case.contacts:
            continue
        held = grounded_planks(case) | {c.on for c in case.contacts if c.on is not None}
        force = {p: np.zeros(3) for p in held}
        moment = {p: np.zeros(3) for p in force}

        def push(plank, f, point, force=force, moment=moment):
            force[plank] += f
            moment[plank] += np.cross(point, f)

        for joint in case.joints:
            first, second = joint.planks
            f, m = np.array(joint.force, dtype=float), np.array(joint.moment, dtype=float)
            point = np.array(joint.point, dtype=float) * model.unit_scale
            push(second, f, point)
            moment[second] += m
            push(first, -f, point)
            moment[first] -= m
        for contact in case.contacts:
            point = np.array(contact.point, dtype=float) * model.unit_scale
            push(contact.plank, np.array(contact.force, dtype=float), point)
            if contact.on is not None:
                push(contact.on, -np.array(contact.force, dtype=float), point)
        for anchor in case.anchors:
            push(anchor.plank, np.array(anchor.force, dtype=float),
                 np.array(anchor.point, dtype=float) * model.unit_scale)
        scale = 0.0
        for plank in model.planks:
            if plank.id in force:
                weight = np.array([0.0, 0.0, -model.plank_mass(plank) * pd.G])
                push(plank.id, weight, plank.center_array)
                scale += float(np.linalg.norm(weight))
        for load in case_model.loads:
            if load.plank in force:
                point = centres[load.plank] if load.point is None else np.array(load.point)
                push(load.plank, np.array(load.force, dtype=float), point)
                scale += float(np.linalg.norm(load.force))
        for plank in force:
            assert np.linalg.norm(force[plank]) <= BALANCE * scale, (case.name, plank)
            assert np.linalg.norm(moment[plank]) <= BALANCE * scale, (case.name, plank)
            checked += 1
    return checked


@pytest.mark.skipif(not CATALOG, reason="designs/ holds no design files yet")
@pytest.mark.parametrize("model_name", ["rigid", "elastic"])
def test_catalog_planks_balance(model_name):
    """(c2): every plank of every stable case of the catalog, in both models, is in
    equilibrium under what the report says acts on it (``assert_planks_balance``): the
    joint wrenches' sign and moment point conventions of contract section 3 (JSON
    ``joints``) hold plank by plank, not only summed over the design."""
    from furncheck.design.model import with_model

    checked = 0
    for path in CATALOG:
        try:
            model = with_model(parse_design(path.read_text(encoding="utf-8"), str(path),
                                            fmt_of(path)), model_name)
        except DesignError:
            continue
        checked += assert_planks_balance(model, check_design(model))
    assert checked >= 100


# --- (d) a load inside the support polygon never topples ----------

@settings(deadline=None, max_examples=25, derandomize=True, phases=PHASES)
@given(x=st.floats(-1.0, 1.0), y=st.floats(-1.0, 1.0), mass=st.floats(0.1, 500.0))
@example(x=1.0, y=1.0, mass=500.0)
@example(x=-1.0, y=0.0, mass=500.0)
def test_vertical_load_inside_support_polygon_is_stable(x, y, mass):
    """(d) on the table (support rectangle |x| <= 450, |y| <= 300 mm; its own weight acts at
    the centre) and the bench (support rectangle |x| <= 356, |y| <= 150): a vertical load of
    any mass anywhere over the rectangle, its edges included, leaves the case stable."""
    table = pd.table(loads=[{"plank": "top", "mass": mass,
                             "at": [x * pd.TABLE_FOOT_X, y * pd.TABLE_FOOT_Y, 412]}])
    bench = pd.bench(mass=mass, x=x * 356.0)
    bench["loads"][0]["at"][1] = y * 150.0
    for design in (table, bench):
        report = check(design)
        assert report.cases[0].stability == "stable", (design["name"], report.violations)
        assert not any(v.kind in ("lift-off", "sliding") for v in report.violations)


def test_rotation_matrix_convention_matches_contract():
    """The helper's Euler convention is the contract's R = Rz @ Ry @ Rx (sanity check of the
    transform used above against the library's own function)."""
    from furncheck.design.model import rotation_matrix

    for rot in ([0, -90, 0], [10, 20, 30], [-35, 80, 170]):
        assert np.allclose(pd.euler_matrix(rot), rotation_matrix(tuple(rot)), atol=1e-12)
    assert math.isclose(pd.matrix_to_euler(pd.euler_matrix([10, 20, 30]))[2], 30.0)


# --- (e) the elastic model: planks' bending under rigid motions and unit changes ----------

ELASTIC_CATALOG = sorted(n for n in NAMES if DESIGNS[n].get("model") == "elastic")
"""The catalog's designs written for the elastic model."""
RUN_ELASTIC = ["catalog:cabinet-28.yaml", "catalog:chair-tilted.yaml",
               "catalog:magazine-rack.yaml", "catalog:shelf-cantilever.yaml",
               "catalog:table.yaml"]
"""Rigid catalog designs also run elastic: joints off the axes (chair-tilted), planks turned
in plan and tilted (magazine-rack), a cantilever, a frame with an apron, 28 planks."""
ELASTIC_NAMES = ELASTIC_CATALOG + [n for n in RUN_ELASTIC if n in DESIGNS]
PLANK_REL = 1e-6        # relative (and, of each quantity's own scale, absolute) tolerance


def test_the_elastic_invariants_have_designs():
    """(e) is not vacuous: the catalog has elastic designs, the chosen rigid ones exist."""
    assert len(ELASTIC_CATALOG) >= 2
    assert set(RUN_ELASTIC) <= set(DESIGNS)


def assert_same_planks(a, b, length_factor: float = 1.0):
    """Report ``b`` (elastic) is report ``a`` (elastic) after a rigid motion and/or a change
    of units by ``length_factor`` (file units of b per file unit of a): the same planks in
    every case, sag and sag_allowed times length_factor, the same stress, strength and
    utilization (PLANK_REL relative, and PLANK_REL absolute of the plank's allowed sag, its
    strength, or 1)."""
    for ca, cb in zip(a.cases, b.cases):
        where = f"case {ca.name}"
        assert ca.planks and cb.planks is not None, where        # the elastic model's result
        planks_b = {p.id: p for p in cb.planks}
        assert sorted(planks_b) == sorted(p.id for p in ca.planks), where
        for pa in ca.planks:
            pb = planks_b[pa.id]
            allowed = pa.sag_allowed * length_factor
            for field, factor, own_scale in (("sag", length_factor, allowed),
                                             ("sag_allowed", length_factor, allowed),
                                             ("stress", 1.0, pa.strength),
                                             ("strength", 1.0, pa.strength),
                                             ("utilization", 1.0, 1.0)):
                expected = getattr(pa, field) * factor
                assert getattr(pb, field) == pytest.approx(
                    expected, rel=PLANK_REL, abs=PLANK_REL * own_scale), \
                    f"{where} plank {pa.id} {field}"


def assert_same_elastic(design: dict, new: dict, rotation, map_point, length_factor: float):
    """(a)/(b) and the planks' bending, both designs checked in the elastic model."""
    a, b = check(design, model="elastic"), check(new, model="elastic")
    assert_same_physics(a, b, force_scale(design), rotation, map_point,
                        point_tol=1e-9 * pd.unit_factor(new))
    assert_same_planks(a, b, length_factor)


@pytest.mark.parametrize("name", ELASTIC_NAMES)
def test_elastic_planks_under_rigid_motion(name):
    """(e): phi = -123.4 deg about z, moved by (0.8 m, -1.7 m): nothing changes."""
    design = DESIGNS[name]
    new, rotation, map_point = moved(design, -123.4, 0.8, -1.7)
    assert_same_elastic(design, new, rotation, map_point, 1.0)


@pytest.mark.parametrize("name", ELASTIC_NAMES)
def test_elastic_planks_in_other_units(name):
    """(e): mm -> m (or m -> mm): sag and sag_allowed scale by 1/1000 (1000), nothing else
    changes."""
    design = DESIGNS[name]
    other = "m" if design.get("units", "mm") == "mm" else "mm"
    converted = pd.convert_units(design, other)
    k = pd.unit_factor(converted) / pd.unit_factor(design)
    assert_same_elastic(design, converted, np.eye(3), lambda p: p * k, k)


@settings(SETTINGS, max_examples=10)
@given(name=st.sampled_from(ELASTIC_NAMES), phi=st.floats(-180.0, 180.0),
       tx=st.floats(-3.0, 3.0), other_units=st.booleans())
def test_elastic_planks_under_any_motion(name, phi, tx, other_units):
    """(e) for motions drawn at random (derandomized): turned by phi, moved by
    (tx, -tx / 2) m, and written in the other unit or not."""
    design = DESIGNS[name]
    new, rotation, map_point = moved(design, phi, tx, -tx / 2)
    k = 1.0
    if other_units:
        new = pd.convert_units(new, "m" if design.get("units", "mm") == "mm" else "mm")
        k = pd.unit_factor(new) / pd.unit_factor(design)
    assert_same_elastic(design, new, rotation, lambda p: map_point(p) * k, k)


@pytest.mark.parametrize("name", ELASTIC_NAMES)
def test_elastic_contact_forces_balance_loads(name):
    """(c) in the elastic model: the ground's forces balance self-weight and loads
    (spread loads included) in every case with ground forces."""
    path = CATALOG_DIR / name.split(":", 1)[1]
    model = with_model(parse_design(path.read_text(encoding="utf-8"), str(path),
                                    fmt_of(path)), "elastic")
    assert model.model == "elastic"
    assert assert_contacts_balance_loads(model, check_design(model)) == len(model.load_cases)


def test_the_generated_catalog_sweep_checks_and_passes(tmp_path, monkeypatch):
    """``benchmarks/sweep_catalog.py`` (these invariants and the push programs over a
    generated catalog, far more designs than the suite affords) on three of its designs:
    every kind of check is made, and none fails."""
    monkeypatch.syspath_prepend(str(ROOT / "benchmarks"))
    from catalog import write_catalog
    from sweep_catalog import KINDS, sweep_one

    made = dict.fromkeys(KINDS, 0)
    paths = [str(path) for path in write_catalog(tmp_path, 3)]
    results = [sweep_one(path, pushes=True) for path in paths]
    for counts, failures in results:
        assert failures == []
        for kind in KINDS:
            made[kind] += counts[kind]
    assert all(made[kind] > 0 for kind in KINDS), made
    # --keep copies the failing designs' files: here the second, as if it had failed
    from sweep_catalog import _keep_failing

    results[1] = (results[1][0], [("motion", "a finding")])
    _keep_failing(paths, results, tmp_path / "kept")
    assert [p.name for p in (tmp_path / "kept").iterdir()] == [Path(paths[1]).name]
