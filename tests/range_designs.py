"""Hand-checkable designs for the range and sensitivity tests (``test_ranges.py``,
``test_sensitivity.py``), built as plain dicts and parsed with ``parse_design``.

All designs are in millimetres.  A vertical plank standing on an end face uses rotation
[0, -90, 0]: R = Ry(-90) maps local x (length) to world +z, local y (width) to world +y and
local z (thickness) to world -x, so it is 12 mm thick along x.

cantilever    base 800 x 400 on the ground, centre (200, 0, 6): spans x -200..600, so the
              whole design's centre of mass stays far inside it for every shelf length the
              tests reach (no tipping).  Post 800 x 400 standing on the base at x = -150
              (spans x -156..-144, z 12..812).  Shelf `length` x 300 whose -x end face lies on
              the post's +x face (x = -144) at height z = 600: it spans x -144..-144 + length.
              Joints listed with explicit nails: base/post 40, post/shelf 15.  A load of `mass`
              kg rides on the shelf's top face (z = 606) at the fraction `fraction` of the
              shelf's length from the post face, x = -144 + fraction x length.
              Bounding box: x -200..600 (800), y -200..200, z 0..812 -> size 812 mm.
slide_table   top 1000 x 400 (spans x +-500, y +-200), mid-plane z = 406, resting on four legs
              400 x 60 standing upright at (+-100, +-120): each leg spans x +-100 -+ 6 and
              y +-120 -+ 30, so the support polygon is |x| <= 106, |y| <= 150.  Joints
              top/leg_* detected (L = 60 mm, 3 nails).  A load of `mass` kg at the top's centre
              (0, 0, 412).  Friction 1.0.  Size 1000 mm (the top's length).
bay           two sides 600 x 300 standing upright with their inner faces at x = +-200
              (side_l spans x -212..-200, side_r 200..212, z 0..600), a shelf 400 x 300 between
              them (spans x -200..200) at mid-plane height `z`, its end faces on the sides'
              inner faces (joints side_l/shelf, side_r/shelf detected, L = 300 mm, 15 nails).
              A load of `mass` kg at the shelf's centre on its top face.  Bounding box
              x -212..212 (424), z 0..600 -> size 600 mm.
"""

from __future__ import annotations

import yaml

from furncheck.design import parse_design

DENSITY = 750.0          # kg/m^3, the default
G = 9.81                 # m/s^2
T = 12.0                 # mm, default thickness
UPRIGHT = [0, -90, 0]


def plank_mass(length_mm: float, width_mm: float, thickness_mm: float = T,
               density: float = DENSITY) -> float:
    """kg of a plank: density x volume."""
    return density * length_mm * width_mm * thickness_mm * 1e-9


def parse(design: dict, name: str | None = None):
    """The dict as a loaded Design (through the YAML loader, like a file)."""
    name = name or design.get("name", "design")
    return parse_design(yaml.safe_dump(design, sort_keys=False), f"{name}.yaml", "yaml")


# --- cantilevered shelf ----------

CANTI_POST_FACE_X = -144.0     # mm, the post's +x face where the shelf's end rests
CANTI_SHELF_WIDTH = 300.0      # mm, the joint length
CANTI_SHELF_NAILS = 15
CANTI_SIZE = 812.0             # mm, largest bounding-box edge (post top at z = 812)


def cantilever(mass: float = 10.0, fraction: float = 0.75, length: float = 300.0) -> dict:
    load_x = CANTI_POST_FACE_X + fraction * length
    return {
        "furncheck": 1,
        "name": "range-cantilever",
        "units": "mm",
        "planks": [
            {"id": "base", "size": [800, 400], "center": [200, 0, 6]},
            {"id": "post", "size": [800, 400], "center": [-150, 0, 412],
             "rotation": list(UPRIGHT)},
            {"id": "shelf", "size": [length, CANTI_SHELF_WIDTH],
             "center": [CANTI_POST_FACE_X + length / 2, 0, 600]},
        ],
        "joints": [
            {"planks": ["base", "post"], "nails": 40},
            {"planks": ["post", "shelf"], "nails": CANTI_SHELF_NAILS},
        ],
        "loads": [{"plank": "shelf", "mass": mass, "at": [load_x, 0, 606]}],
    }


# --- table whose top slides over four central legs ----------

SLIDE_LEG_OUTER_X = 106.0      # mm, the support polygon's edge |x| <= 106
SLIDE_TOP = (1000.0, 400.0)
SLIDE_LEG = (400.0, 60.0)
SLIDE_SIZE = 1000.0


def slide_table(mass: float = 10.0) -> dict:
    planks = [{"id": "top", "size": list(SLIDE_TOP), "center": [0, 0, 406]}]
    for name, x, y in (("leg_pp", 100, 120), ("leg_mp", -100, 120), ("leg_pm", 100, -120),
                       ("leg_mm", -100, -120)):
        planks.append({"id": name, "size": list(SLIDE_LEG), "center": [x, y, 200],
                       "rotation": list(UPRIGHT)})
    return {
        "furncheck": 1,
        "name": "slide-table",
        "units": "mm",
        "material": {"friction": 1.0},
        "planks": planks,
        "loads": [{"plank": "top", "mass": mass, "at": [0, 0, 412]}],
    }


# --- a shelf nailed between two sides ----------

BAY_SIDE_HEIGHT = 600.0
BAY_SIZE = 600.0


def bay(z: float = 300.0, mass: float = 5.0) -> dict:
    return {
        "furncheck": 1,
        "name": "bay",
        "units": "mm",
        "planks": [
            {"id": "side_l", "size": [BAY_SIDE_HEIGHT, 300], "center": [-206, 0, 300],
             "rotation": list(UPRIGHT)},
            {"id": "side_r", "size": [BAY_SIDE_HEIGHT, 300], "center": [206, 0, 300],
             "rotation": list(UPRIGHT)},
            {"id": "shelf", "size": [400, 300], "center": [0, 0, z]},
        ],
        "loads": [{"plank": "shelf", "mass": mass, "at": [0, 0, z + 6]}],
    }
