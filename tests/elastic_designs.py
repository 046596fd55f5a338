"""Hand-checkable designs for the elastic-model tests (contract section 3a), as plain dicts
(millimetres, N/mm^2); ``physics_designs.to_text`` writes them as design files.

Every design writes ``model:`` and the material constants its hand calculation uses
explicitly (E, G, strength, creep, sag limit, nail stiffnesses), so that changing a default
changes no test.  A vertical plank standing on an end face uses rotation [0, -90, 0]
(``physics_designs.UPRIGHT``): local x (length) -> world +z, local y (width) -> world +y,
local z (thickness) -> world -x, i.e. its thickness runs along world x.

Geometry (the numbers the hand calculations use):

cantilever_shelf  base 600 x 400 lying on the ground (spans x -300..300, centre z = 6),
             post 800 x 400 standing on it at x = -150 (spans x -156..-144, z 12..812),
             shelf 400 x 200 (beam axis = world x, the longer side) whose -x end face lies on
             the post's +x face at z = 600: shelf spans x -144..256, y -100..100, z 594..606.
             Joint post/shelf at (-144, 0, 600) (L = 200: 10 nails); joint base/post at
             (-150, 0, 12) (L = 400: 20 nails).  A hold-down mass sits on the base at
             (150, 0, 12).  Tip load at the shelf's top face, free end: (256, 0, 606).
flat_shelf   a plank (`length` + 12) x `width` lying level on two 12 mm fins 50 mm tall at
             x = +-length/2 (flush with its ends), nailed with nail_withdrawal 1 N/mm so
             that they act as pins: a simply supported span `length`.  (A plank lying
             flat on the ground is held along its face by the floor: it has no sag.)
three_support_shelf  shelf (thickness 18) 2 l + 2 x 1 mm long on three uprights 150 high,
             100 wide (along y): two fins 2 mm thick at x = +-l (flush with the shelf's
             ends, spans x = +-l -+ 1) and a block 12 mm thick at x = 0.  Shelf mid-plane
             z = 159, bottom face z = 150 = the uprights' top end faces.
portal       seat 712 x 300 (spans x -356..356, mid-plane z = 456) on two legs 450 x 300,
             12 mm thick, standing on the ground at x = +-350 (each spans x +-344..+-356).
             Joints seat/leg_l, seat/leg_r at (+-350, 0, 450) (L = 300: 15 nails).
post_with_shelves  base, post and two shelves on either side of the post (a tree of planks
             on one grounded plank), with a divider standing on the right shelf.
"""

from __future__ import annotations

import physics_designs as pd

UPRIGHT = pd.UPRIGHT
WEIGHTLESS = 1e-6          # kg/m^3: self-weight negligible

E = 3000.0                 # N/mm^2
G_MOD = 800.0              # N/mm^2
STRENGTH = 22.0            # N/mm^2
CREEP = 2.25
SAG_LIMIT = 400.0
STIFF_NAIL = 1e9           # N/mm per nail: joints effectively rigid
NAIL_WITHDRAWAL = 1000.0   # N/mm per nail (the project's default)
NAIL_SLIP = 1200.0         # N/mm per nail (the project's default)


def material(density: float = WEIGHTLESS, *, nail_withdrawal: float = NAIL_WITHDRAWAL,
             nail_slip: float = NAIL_SLIP, friction: float = 0.5, creep: float = CREEP,
             sag_limit: float = SAG_LIMIT, bending_strength: float = STRENGTH,
             elastic_modulus: float = E, shear_modulus: float = G_MOD) -> dict:
    """A material block with every elastic constant written out (file units)."""
    return {"thickness": 12, "density": density, "friction": friction,
            "elastic_modulus": elastic_modulus, "shear_modulus": shear_modulus,
            "bending_strength": bending_strength, "creep": creep, "sag_limit": sag_limit,
            "nail_slip": nail_slip, "nail_withdrawal": nail_withdrawal}


def _design(name: str, model: str, mat: dict, planks: list, loads: list) -> dict:
    return {"furncheck": 1, "name": name, "units": "mm", "model": model, "material": mat,
            "planks": planks, "loads": loads}


# --- 1. cantilever shelf ----------

CANTI_ROOT_X = -144.0       # mm, the post's +x face = the shelf's fixed end
CANTI_LENGTH = 400.0        # mm, shelf length along x (its beam axis)
CANTI_WIDTH = 200.0         # mm, along y
CANTI_Z = 600.0             # mm, shelf mid-plane
CANTI_TIP = (CANTI_ROOT_X + CANTI_LENGTH, 0.0, CANTI_Z + 6.0)   # top face at the free end


def cantilever_shelf(tip_mass: float = 0.0, spread_mass: float = 0.0,
                     density: float = WEIGHTLESS, model: str = "elastic",
                     nail_withdrawal: float = STIFF_NAIL, nail_slip: float = STIFF_NAIL,
                     hold_down: float = 30.0, **material_keys) -> dict:
    """Base, post and a 400 x 200 shelf cantilevered from the post (see the module doc)."""
    loads = [{"plank": "base", "mass": hold_down, "at": [150, 0, 12]}]
    if tip_mass:
        loads.append({"plank": "shelf", "mass": tip_mass, "at": list(CANTI_TIP)})
    if spread_mass:
        loads.append({"plank": "shelf", "mass": spread_mass, "spread": True})
    planks = [
        {"id": "base", "size": [600, 400], "center": [0, 0, 6], "rotation": [0, 0, 0]},
        {"id": "post", "size": [800, 400], "center": [-150, 0, 412], "rotation": list(UPRIGHT)},
        {"id": "shelf", "size": [CANTI_LENGTH, CANTI_WIDTH],
         "center": [CANTI_ROOT_X + CANTI_LENGTH / 2, 0, CANTI_Z], "rotation": [0, 0, 0]},
    ]
    mat = material(density, nail_withdrawal=nail_withdrawal, nail_slip=nail_slip,
                   **material_keys)
    return _design("elastic-cantilever", model, mat, planks, loads)


# --- 2. simply supported shelf ----------

FLAT_FIN_T = 12.0           # mm, the flat shelf's end fins
FLAT_FIN_H = 50.0           # mm
PIN_NAIL_WITHDRAWAL = 1.0   # N/mm per nail: the fins' joints turn freely (pins)


def flat_shelf(mass: float = 10.0, length: float = 800.0, width: float = 200.0,
               thickness: float = 12.0, friction: float = 0.05, model: str = "elastic",
               nail_withdrawal: float = PIN_NAIL_WITHDRAWAL, **material_keys) -> dict:
    """A simply supported shelf: a plank `length` + 12 mm long, lying level on two fins 12
    mm thick and 50 mm tall whose top end faces are nailed to its underside at x =
    +-length/2 (flush with its ends), with `mass` kg spread along it.  The fins' joints
    have nail_withdrawal 1 N/mm: about the joint line they turn with n k_w (t/2)^2 = 10 x
    1000 N/m x (6 mm)^2 = 0.36 N m/rad (pins), and the shelf sinks on them as a whole.
    Friction 0.05 keeps the fins' feet from holding the shelf's ends back."""
    mat = material(WEIGHTLESS, friction=friction, nail_withdrawal=nail_withdrawal,
                   **material_keys)
    half = length / 2
    planks = [{"id": "shelf", "size": [length + FLAT_FIN_T, width],
               "center": [0, 0, FLAT_FIN_H + thickness / 2], "rotation": [0, 0, 0],
               "thickness": thickness}]
    for pid, x in (("fin_l", -half), ("fin_r", half)):
        planks.append({"id": pid, "size": [FLAT_FIN_H, width], "center": [x, 0, FLAT_FIN_H / 2],
                       "rotation": list(UPRIGHT), "thickness": FLAT_FIN_T})
    return _design("flat-shelf", model, mat, planks,
                   [{"plank": "shelf", "mass": mass, "spread": True}])


# --- 3. shelf continuous over three supports ----------

THREE_SPAN = 800.0          # mm, each span l (support to support)
THREE_UPRIGHT_H = 150.0     # mm
THREE_UPRIGHT_W = 100.0     # mm, along y: joint length, 5 nails
THREE_FIN_T = 2.0           # mm, end fins
THREE_BLOCK_T = 12.0        # mm, middle block
THREE_SHELF_T = 18.0        # mm
THREE_SHELF_W = 200.0       # mm


def three_support_shelf(mass: float = 30.0, model: str = "elastic",
                        nail_withdrawal: float = NAIL_WITHDRAWAL,
                        nail_slip: float = NAIL_SLIP) -> dict:
    """A shelf on two thin end fins and a middle block (see the module doc), `mass` kg
    spread along the shelf; every plank weightless."""
    span, h, half_fin = THREE_SPAN, THREE_UPRIGHT_H, THREE_FIN_T / 2
    planks = [
        {"id": "shelf", "size": [2 * span + 2 * half_fin, THREE_SHELF_W],
         "center": [0, 0, h + THREE_SHELF_T / 2], "thickness": THREE_SHELF_T},
    ]
    for pid, x, t in (("fin_l", -span, THREE_FIN_T), ("block", 0.0, THREE_BLOCK_T),
                      ("fin_r", span, THREE_FIN_T)):
        planks.append({"id": pid, "size": [h, THREE_UPRIGHT_W], "center": [x, 0, h / 2],
                       "rotation": list(UPRIGHT), "thickness": t})
    mat = material(WEIGHTLESS, nail_withdrawal=nail_withdrawal, nail_slip=nail_slip)
    return _design("three-support-shelf", model, mat, planks,
                   [{"plank": "shelf", "mass": mass, "spread": True}])


# --- 4, 5. portal frame ----------

PORTAL_A = 350.0            # mm, legs' centre lines at x = +-a
PORTAL_H = 450.0            # mm, leg length: foot (z = 0) to joint point (z = 450)
PORTAL_T = 12.0             # mm, every member's thickness
PORTAL_B = 300.0            # mm, every member's width (along y)
PORTAL_OVERHANG = 6.0       # mm, seat beyond each leg's centre line (flush with its face)
PORTAL_SEAT_Z = PORTAL_H + PORTAL_T / 2


def portal(spread_mass: float = 0.0, knee_mass: float = 0.0, push: float = 0.0,
           model: str = "elastic", friction: float = 0.8) -> dict:
    """Seat on two legs standing on the ground (see the module doc), stiff nails, every
    plank weightless.  spread_mass kg along the seat; knee_mass kg on the seat's top face
    above each leg, (+-350, 0, 462); push N along +x at the centre of the seat's -x end
    face, (-356, 0, 456), i.e. on the seat's axis."""
    a, h, t = PORTAL_A, PORTAL_H, PORTAL_T
    half = a + PORTAL_OVERHANG
    planks = [{"id": "seat", "size": [2 * half, PORTAL_B], "center": [0, 0, PORTAL_SEAT_Z]}]
    for pid, x in (("leg_l", -a), ("leg_r", a)):
        planks.append({"id": pid, "size": [h, PORTAL_B], "center": [x, 0, h / 2],
                       "rotation": list(UPRIGHT)})
    loads = []
    if spread_mass:
        loads.append({"plank": "seat", "mass": spread_mass, "spread": True})
    if knee_mass:
        for x in (-a, a):
            loads.append({"plank": "seat", "mass": knee_mass, "at": [x, 0, h + t]})
    if push:
        loads.append({"plank": "seat", "force": [push, 0, 0], "at": [-half, 0, PORTAL_SEAT_Z]})
    mat = material(WEIGHTLESS, nail_withdrawal=STIFF_NAIL, nail_slip=STIFF_NAIL,
                   friction=friction)
    return _design("portal", model, mat, planks, loads)


# --- 6. determinate trees ----------

def post_with_shelves(model: str = "elastic", density: float = 750.0) -> dict:
    """Base 600 x 400 on the ground; post 800 x 400 standing on it at x = -150 (spans x
    -156..-144); shelf_r 400 x 200 on the post's +x face at z = 600 (spans x -144..256);
    shelf_l 300 x 250 on the post's -x face at z = 350 (spans x -456..-156, y -125..125);
    a divider 200 x 150 standing on shelf_r's top face at x = 100 (rotation [0, -90, 0]:
    spans x 94..106, y -75..75, z 606..806).  Loads: a hold-down on the base, point and
    spread masses on the shelves, a 3-component force at the divider's top and one with a
    lever along y on shelf_l, so that every joint carries all six wrench components."""
    planks = [
        {"id": "base", "size": [600, 400], "center": [0, 0, 6]},
        {"id": "post", "size": [800, 400], "center": [-150, 0, 412], "rotation": list(UPRIGHT)},
        {"id": "shelf_r", "size": [400, 200], "center": [56, 0, 600]},
        {"id": "shelf_l", "size": [300, 250], "center": [-306, 0, 350]},
        {"id": "divider", "size": [200, 150], "center": [100, 0, 706],
         "rotation": list(UPRIGHT)},
    ]
    loads = [
        {"plank": "base", "mass": 60, "at": [150, 120, 12]},
        {"plank": "shelf_r", "mass": 4, "at": [200, 60, 606]},
        {"plank": "shelf_r", "mass": 3, "spread": True},
        {"plank": "shelf_l", "mass": 2.5, "at": [-400, -90, 356]},
        {"plank": "shelf_l", "force": [5, -8, -12], "at": [-456, 100, 350]},
        {"plank": "divider", "force": [-6, 9, 4], "at": [100, 60, 806]},
    ]
    mat = material(density)
    return _design("post-with-shelves", model, mat, planks, loads)
