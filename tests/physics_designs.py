"""Hand-checkable designs for the physics and invariant tests, built as plain dicts and
written as design-file text (contract section 1), plus the rigid-motion and unit-change
transforms the invariant tests apply to any design dict (hand-made or from the catalog).

All designs here are in millimetres.  A vertical plank standing on an end face uses
rotation [0, -90, 0]: R = Ry(-90) maps local x (length) to world +z, local y (width) to
world +y and local z (thickness) to world -x.

Geometry of each design (the numbers the hand calculations in the tests use):

cantilever   base 400 x 400 on the ground (centre z = 6), post 800 x 400 standing on it at
             x = -150 (spans x -156..-144, z 12..812), shelf 300 x 300 whose -x end face lies
             on the post's +x broad face (x = -144) at height z = 600; shelf spans x -144..156.
             Joints: base/post (L = 400, 20 nails), post/shelf (L = 300, 15 nails, point
             (-144, 0, 600)).  A shelf load of `mass` kg sits on the shelf's top face at
             distance `d` from the post face, i.e. at (-144 + d, 0, 606).
bench        seat 800 x 300 at z = 450..462 on two legs 450 x 300 standing on their end faces
             at x = +-350 (each spans x +-6 around its centre).  Joints seat/leg_l, seat/leg_r
             (L = 300, 15 nails); ground contacts: 4 corners per leg at x = +-344, +-356.
table        top 1000 x 600 (spans x +-500, y +-300) on four legs `leg_height` x 60 at
             (+-444, +-270); each leg spans x 438..450 and y 240..300 (mirrored), so the
             support polygon is the rectangle |x| <= 450, |y| <= 300.  Joints top/leg_*
             (L = 60, 3 nails).
bench_with_back  the bench plus a back rest standing on the seat (see its docstring).
stool        a stool with listed joints and a rung (see its docstring).
"""

from __future__ import annotations

import copy
import json
import math

import yaml

DENSITY = 750.0          # kg/m^3, the default
G = 9.81                 # m/s^2
T = 12.0                 # mm, default thickness
UPRIGHT = [0, -90, 0]    # rotation of a plank standing on its end face (length along +z)


def plank_mass(length_mm: float, width_mm: float, thickness_mm: float = T,
               density: float = DENSITY) -> float:
    """kg of a plank: density x volume."""
    return density * length_mm * width_mm * thickness_mm * 1e-9


# --- cantilevered shelf ----------

CANTI_POST_FACE_X = -144.0     # mm, the post's +x broad face, where the shelf's end rests
CANTI_SHELF_Z = 600.0          # mm, shelf mid-plane height = joint point z
CANTI_SHELF_LENGTH = 300.0     # mm, along x
CANTI_SHELF_WIDTH = 300.0      # mm, along y = the joint length
CANTI_SHELF_NAILS = 15         # floor(300 / 20)
CANTI_POST_X = -150.0          # mm, the post's centre x = base/post joint point x
CANTI_BASE_NAILS = 20          # floor(400 / 20)


def cantilever(mass: float = 10.0, d: float = 200.0, density: float = DENSITY,
               push: float | None = None, friction: float | None = None,
               extra_cases: dict | None = None) -> dict:
    """Base, post and cantilevered shelf; `mass` kg on the shelf `d` mm from the post face.

    push: N, a horizontal force (-push, 0, 0) at the shelf's free end-face centre
    (156, 0, 600), i.e. pushing the shelf towards the post along the nail axis (its line of
    action passes through the joint point, so it adds no moment about the joint).
    """
    loads = []
    if mass:
        loads.append({"plank": "shelf", "mass": mass, "at": [CANTI_POST_FACE_X + d, 0, 606]})
    if push:
        loads.append({"plank": "shelf", "force": [-push, 0, 0],
                      "at": [CANTI_POST_FACE_X + CANTI_SHELF_LENGTH, 0, CANTI_SHELF_Z]})
    material = {"density": density}
    if friction is not None:
        material["friction"] = friction
    design = {
        "furncheck": 1,
        "name": "cantilever",
        "units": "mm",
        "material": material,
        "planks": [
            {"id": "base", "size": [400, 400], "center": [0, 0, 6], "rotation": [0, 0, 0]},
            {"id": "post", "size": [800, 400], "center": [CANTI_POST_X, 0, 412],
             "rotation": list(UPRIGHT)},
            {"id": "shelf", "size": [CANTI_SHELF_LENGTH, CANTI_SHELF_WIDTH],
             "center": [CANTI_POST_FACE_X + CANTI_SHELF_LENGTH / 2, 0, CANTI_SHELF_Z],
             "rotation": [0, 0, 0]},
        ],
        "loads": loads,
    }
    if extra_cases:
        design["load_cases"] = extra_cases
    return design


# --- two-legged bench ----------

BENCH_LEG_X = 350.0            # mm, leg centres at x = +-350
BENCH_SEAT_TOP = 462.0


def bench(mass: float = 80.0, x: float = 0.0, density: float = DENSITY) -> dict:
    """Seat 800 x 300 on two 450 x 300 legs; `mass` kg on the seat's top face at (x, 0)."""
    loads = [{"plank": "seat", "mass": mass, "at": [x, 0, BENCH_SEAT_TOP]}] if mass else []
    return {
        "furncheck": 1,
        "name": "bench",
        "material": {"density": density},
        "planks": [
            {"id": "seat", "size": [800, 300], "center": [0, 0, 456]},
            {"id": "leg_l", "size": [450, 300], "center": [-BENCH_LEG_X, 0, 225],
             "rotation": list(UPRIGHT)},
            {"id": "leg_r", "size": [450, 300], "center": [BENCH_LEG_X, 0, 225],
             "rotation": list(UPRIGHT)},
        ],
        "loads": loads,
    }


# --- four-legged table ----------

TABLE_HALF_X = 500.0           # mm, top spans x +-500
TABLE_HALF_Y = 300.0
TABLE_FOOT_X = 450.0           # mm, support polygon |x| <= 450
TABLE_FOOT_Y = 300.0           # mm, support polygon |y| <= 300
TABLE_LEGS = {"leg_pp": (444, 270), "leg_mp": (-444, 270), "leg_pm": (444, -270),
              "leg_mm": (-444, -270)}


def table(leg_height: float = 400.0, loads: list | None = None, friction: float = 0.5,
          density: float = DENSITY, load_cases: dict | None = None) -> dict:
    """Top 1000 x 600 x 12 on four 60 mm wide legs; top mid-plane at leg_height + 6."""
    planks = [{"id": "top", "size": [2 * TABLE_HALF_X, 2 * TABLE_HALF_Y],
               "center": [0, 0, leg_height + T / 2]}]
    for name, (x, y) in TABLE_LEGS.items():
        planks.append({"id": name, "size": [leg_height, 60], "center": [x, y, leg_height / 2],
                       "rotation": list(UPRIGHT)})
    design = {"furncheck": 1, "name": "table",
              "material": {"density": density, "friction": friction},
              "planks": planks, "loads": list(loads or [])}
    if load_cases:
        design["load_cases"] = load_cases
    return design


def table_self_mass(leg_height: float = 400.0, density: float = DENSITY) -> float:
    """kg: top + four legs."""
    return (plank_mass(2 * TABLE_HALF_X, 2 * TABLE_HALF_Y, density=density)
            + 4 * plank_mass(leg_height, 60, density=density))


# --- a less regular design for the invariants: a stool with listed joints ----------

def stool_with_listed_joints() -> dict:
    """A small stool with listed joints (one with an explicit nail count), a shelf between
    the legs and named load cases including a sideways push."""
    return {
        "furncheck": 1,
        "name": "stool",
        "material": {"thickness": 18, "friction": 0.6},
        "planks": [
            {"id": "seat", "size": [400, 300], "center": [0, 0, 459]},
            {"id": "leg_l", "size": [450, 300], "center": [-150, 0, 225],
             "rotation": list(UPRIGHT)},
            {"id": "leg_r", "size": [450, 300], "center": [150, 0, 225],
             "rotation": list(UPRIGHT)},
            {"id": "rung", "size": [282, 200], "center": [0, 0, 150], "thickness": 12},
        ],
        "joints": [
            ["seat", "leg_l"],
            {"planks": ["seat", "leg_r"], "nails": 10},
            ["leg_l", "rung"],
            ["leg_r", "rung"],
        ],
        "loads": [{"plank": "seat", "mass": 60, "at": [50, 40, 468]}],
        "load_cases": {
            "push": [{"plank": "seat", "force": [20, 15, 0], "at": [-200, 0, 459]},
                     {"plank": "rung", "mass": 5}],
            "empty": [],
        },
    }


def bench_with_back(mass: float = 70.0, lean: float = 100.0) -> dict:
    """The bench with a back rest 800 x 300 standing on the seat's top face along its back
    edge: rotation [90, 0, 0] puts its width (local y) along world z and its thickness along
    world -y (spans y -150..-138, z 462..762); joint seat/back (L = 800, 40 nails).  Case
    `lean`: `lean` N pushing the top of the back rest backwards (-y) at (0, -144, 760)."""
    design = bench(mass=mass, x=-100.0)
    design["name"] = "bench-with-back"
    design["planks"].append({"id": "back", "size": [800, 300], "center": [0, -144, 612],
                             "rotation": [90, 0, 0]})
    design["load_cases"] = {"lean": [{"plank": "seat", "mass": mass, "at": [0, 0, 462]},
                                     {"plank": "back", "force": [0, -lean, 0],
                                      "at": [0, -144, 760]}]}
    return design


def hand_designs() -> dict[str, dict]:
    """Named hand-written designs for the invariant tests (all with self-weight)."""
    return {
        "cantilever": cantilever(mass=12.0, d=180.0, push=15.0),
        "bench": bench(mass=70.0, x=120.0),
        "bench-with-back": bench_with_back(),
        "table": table(loads=[{"plank": "top", "mass": 40, "at": [300, 150, 412]}],
                       load_cases={"push": [{"plank": "top", "force": [20, -10, 0],
                                             "at": [-500, 0, 406]}],
                                   "shove": [{"plank": "top", "force": [45, 0, 0],
                                              "at": [-500, 0, 406]}]}),
        "stool": stool_with_listed_joints(),
    }


# --- text ----------

def to_text(design: dict, fmt: str = "yaml") -> str:
    """Design dict -> file text (YAML or JSON)."""
    if fmt == "json":
        return json.dumps(design, indent=2)
    return yaml.safe_dump(design, sort_keys=False, default_flow_style=None)


# --- transforms (for the invariant tests) ----------

def rz(phi_deg: float) -> list[list[float]]:
    c, s = math.cos(math.radians(phi_deg)), math.sin(math.radians(phi_deg))
    return [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]


def euler_matrix(rotation_deg) -> list[list[float]]:
    """R = Rz @ Ry @ Rx for [rx, ry, rz] degrees (contract section 1), as nested lists."""
    a, b, c = (math.radians(v) for v in rotation_deg)
    ca, sa, cb, sb, cc, sc = math.cos(a), math.sin(a), math.cos(b), math.sin(b), math.cos(c), \
        math.sin(c)
    return [[cc * cb, cc * sb * sa - sc * ca, cc * sb * ca + sc * sa],
            [sc * cb, sc * sb * sa + cc * ca, sc * sb * ca - cc * sa],
            [-sb, cb * sa, cb * ca]]


def matrix_to_euler(m) -> list[float]:
    """Inverse of ``euler_matrix``: [rx, ry, rz] degrees; at gimbal lock (ry = +-90) rx = 0."""
    sb = -m[2][0]
    sb = max(-1.0, min(1.0, sb))
    b = math.asin(sb)
    if abs(math.cos(b)) > 1e-9:
        a = math.atan2(m[2][1], m[2][2])
        c = math.atan2(m[1][0], m[0][0])
    else:
        a = 0.0
        c = math.atan2(-m[0][1], m[1][1])
    return [math.degrees(a), math.degrees(b), math.degrees(c)]


def _matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def _apply(m, v):
    return [sum(m[i][k] * v[k] for k in range(3)) for i in range(3)]


def _all_loads(design: dict):
    """Every load the file writes: ``loads`` and each case's own (a case is a list of loads
    or ``{include: [...], loads: [...]}``)."""
    for load in design.get("loads") or []:
        yield load
    for case in (design.get("load_cases") or {}).values():
        for load in (case.get("loads") if isinstance(case, dict) else case) or []:
            yield load


def case_loads(design: dict, name: str = "default") -> list[dict]:
    """The loads acting in case ``name`` of the design dict, ``include`` followed (contract
    section 1): every case reached through includes contributes its own loads once, the
    included ones first in include order, then the case's own."""
    cases = {"default": design.get("loads") or []} | dict(design.get("load_cases") or {})
    seen: set[str] = set()

    def gather(case_name: str) -> list[dict]:
        seen.add(case_name)
        case = cases[case_name]
        if not isinstance(case, dict):
            return list(case or [])
        loads = []
        for included in case.get("include", []):
            if included not in seen:
                loads += gather(included)
        return loads + list(case.get("loads") or [])

    return gather(name)


def rigid_motion(design: dict, phi_deg: float, tx: float, ty: float) -> dict:
    """The design rotated by phi about the world z axis through the origin, then moved by
    (tx, ty) in the file's length unit (``_mapped``)."""
    return _mapped(design, rz(phi_deg), (tx, ty, 0.0))


def mirrored(design: dict) -> dict:
    """The design's mirror image in the plane x = 0 (``_mapped`` by M = diag(-1, 1, 1))."""
    return _mapped(design, [[-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
                   (0.0, 0.0, 0.0))


def _mapped(design: dict, matrix, shift) -> dict:
    """The design mapped by p -> matrix p + shift (a rotation, or a mirror: determinant
    -1), in the file's length unit: plank centres, load points, wall points and anchors
    mapped, forces and wall normals turned by ``matrix``; a plank's rotation R becomes
    matrix R, or matrix R F for a mirror (F = diag(-1, 1, 1): a proper rotation again,
    since a plank's box is its own mirror image in its local x), converted back to x-y-z
    Euler angles."""
    out = copy.deepcopy(design)
    (a, b, c), (d, e, f), (g, h, i) = matrix
    mirror = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g) < 0.0
    frame = [[-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] if mirror else \
        [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]

    def vector(value):
        return _apply(matrix, [float(v) for v in value])

    def point(value):
        return [v + float(s) for v, s in zip(vector(value), shift)]

    for plank in out["planks"]:
        plank["center"] = point(plank["center"])
        new = _matmul(matrix, _matmul(euler_matrix(plank.get("rotation", [0, 0, 0])), frame))
        plank["rotation"] = matrix_to_euler(new)
    for load in _all_loads(out):
        if "at" in load:
            load["at"] = point(load["at"])
        if "force" in load:
            load["force"] = vector(load["force"])
    for wall in out.get("walls") or []:
        wall["point"], wall["normal"] = point(wall["point"]), vector(wall["normal"])
    for anchor in out.get("anchors") or []:
        anchor["at"] = point(anchor["at"])
    return out


def unit_factor(design: dict) -> float:
    """File units per metre of the design's unit: 1000 for mm, 1 for m."""
    return 1000.0 if design.get("units", "mm") == "mm" else 1.0


def convert_units(design: dict, to: str) -> dict:
    """The same physical design written in another length unit ('mm' or 'm').  Defaults of
    the material's length-valued keys and of the tolerance are written out explicitly (in
    their physical values: 12 mm, 20 mm, 0.5 mm) only if the original sets them; lengths
    converted are plank size/center/thickness (also in a plank's own material), material
    thickness/nail_spacing, tolerance, load points, wall points and anchor points.
    Masses, forces, densities and angles do not change."""
    out = copy.deepcopy(design)
    scale = (1000.0 if to == "mm" else 1.0) / unit_factor(design)
    out["units"] = to

    def conv(v):
        return [float(c) * scale for c in v]

    for plank in out["planks"]:
        plank["size"] = conv(plank["size"])
        plank["center"] = conv(plank["center"])
        if "thickness" in plank:
            plank["thickness"] = float(plank["thickness"]) * scale
        if "thickness" in (plank.get("material") or {}):
            plank["material"]["thickness"] = float(plank["material"]["thickness"]) * scale
    material = out.get("material") or {}
    for key in ("thickness", "nail_spacing"):
        if key in material:
            material[key] = float(material[key]) * scale
    if "tolerance" in out:
        out["tolerance"] = float(out["tolerance"]) * scale
    for load in _all_loads(out):
        if "at" in load:
            load["at"] = conv(load["at"])
    for wall in out.get("walls") or []:
        wall["point"] = conv(wall["point"])
    for anchor in out.get("anchors") or []:
        anchor["at"] = conv(anchor["at"])
    return out


# --- finding results in a report (shared by the physics tests) ----------

def case_of(report, name: str = "default"):
    """The report's load case called ``name``."""
    for case in report.cases:
        if case.name == name:
            return case
    raise AssertionError(f"no case {name!r} in {[c.name for c in report.cases]}")


def joint_of(case, first: str, second: str):
    """The case's one joint listed as (first, second)."""
    found = [j for j in case.joints if tuple(j.planks) == (first, second)]
    assert len(found) == 1, f"joint {first}/{second} not found once in " \
                            f"{[j.planks for j in case.joints]}"
    return found[0]
