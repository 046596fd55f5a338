"""The hand estimates in the catalog's headers, against ``check_design``.

Every file in ``designs/`` opens with a comment block that says what the design is, its
expected verdict and a hand estimate.  This file takes the numbers those estimates state
that are well defined (per-nail pull and shear, joint forces and moments, ground reactions,
self-weights, friction and tipping ratios, sag and stress bounds) and checks each against
the report, within 5 % of the hand value (``REL``: the headers round to two or three
figures) unless the entry says otherwise:

- an ``at most`` bound (the header's worst case, e.g. a fully fixed shelf end) must hold;
- a bracket (``between``: e.g. a shelf's sag between fixed and pinned ends) must hold;
- a tipping estimate "F h vs W d" is checked through the ground's forces: their moment
  about the tipping edge, sum N_i d_i (d_i the distance of contact i inside the edge), must
  equal the restoring minus the overturning moment, W d - F h, to 5 % of W d;
- a friction estimate "mu N vs H" through the report's ground forces: their normal sum and
  the ratio |sum of horizontal forces| / (mu x normal sum).

Each entry quotes the header text its number comes from, and the test checks that the
header still says it (so an edited header shows up here).  An entry whose header number
is wrong would carry the corrected hand value with its calculation and ``header_says``
the old text instead of a quote; the headers found wrong this way (bench-long-leg,
bookcase-sagging, bookshelf-20, chair-tilted, coffee-table-splayed, l-shelf-pushed,
shelf-cantilever-overloaded) have been corrected and are quoted.

Each entry names its model: by default (``model=None``) files without a ``model:`` key
are run in the rigid model (the paper's, which their rigid estimates assume), whatever the
default is, and ``model: elastic`` files in the elastic model; the headers' "Elastic model"
estimates (sag and stress of the planks that moved the catalog's verdicts, contract
section 3a) are entries with ``model="elastic"``.  The rigid model's joint forces of the
determinate designs hold in both (shelf-cantilever-overloaded is checked in both).
Per-nail values follow the nail-group rule of contract section 3.  bench-long-leg and
bookshelf-gap have geometric violations; their statics, reported for information, are
checked all the same.  Estimates not asserted: side-table-hovering's (it floats: no
statics), cabinet-28's "74 N each" at the shelf ends (the slats
and dividers share the shelves statically indeterminately; the report gives 101 N at
side_l/shelf_a1), the
bounds that are not the report's (bench's "fully fixed seat end", l-shelf-pushed's
"F > 1 kN") and the verbal ones ("tiny", "a few newtons").
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import numpy as np
import pytest

from furncheck.check import check_design
from furncheck.design import load_design
from furncheck.design.model import with_model
from furncheck.result import CaseResult, DesignReport

CATALOG = Path(__file__).resolve().parents[1] / "designs"
REL = 0.05              # relative tolerance of a hand estimate (the headers' rounding)
G = 9.81                # m/s^2, as the headers use it
T = 0.012               # m, the catalog's plank thickness


# --- reading the design and its report ----------

def header(name: str) -> str:
    """The file's opening comment block as one line of text (line breaks as spaces)."""
    lines = []
    for line in (CATALOG / f"{name}.yaml").read_text(encoding="utf-8").splitlines():
        if not line.startswith("#"):
            break
        lines.append(line.lstrip("#").strip())
    return " ".join(lines)


@cache
def design_and_report(name: str, model: str | None = None):
    """(design, report) in ``model``; None: rigid unless the file says ``model: elastic``."""
    design = load_design(str(CATALOG / f"{name}.yaml"))
    if model is None:
        text = (CATALOG / f"{name}.yaml").read_text(encoding="utf-8")
        model = "elastic" if "\nmodel: elastic" in text else "rigid"
    design = with_model(design, model)
    return design, check_design(design)


def case_of(report: DesignReport, name: str) -> CaseResult:
    (case,) = [c for c in report.cases if c.name == name]
    return case


Quantity = Callable[[object, CaseResult], float]


def joint(a: str, b: str, what: str) -> Quantity:
    """A joint's ``pull`` or ``shear`` (N per nail), ``nails``, ``force`` or ``moment``
    (magnitudes, N and N m) or ``fz`` (|vertical force|, N)."""
    def value(design, case):
        (found,) = [j for j in case.joints if set(j.planks) == {a, b}]
        if what in ("force", "moment"):
            return float(np.linalg.norm(getattr(found, what)))
        if what == "fz":
            return abs(found.force[2])
        return float(getattr(found, what))
    return value


def joints_max(planks: set[str], pairs_with: set[str], what: str) -> Quantity:
    """The largest ``what`` over the joints between a plank of ``planks`` and one of
    ``pairs_with``."""
    def value(design, case):
        return max(float(getattr(j, what)) for j in case.joints
                   if (j.planks[0] in planks and j.planks[1] in pairs_with)
                   or (j.planks[1] in planks and j.planks[0] in pairs_with))
    return value


def ground_normal(plank: str | None = None) -> Quantity:
    """N: the ground's vertical force on ``plank`` (on everything when None)."""
    def value(design, case):
        return sum(c.force[2] for c in case.contacts if plank in (None, c.plank))
    return value


def ground_horizontal(plank: str | None = None) -> Quantity:
    """N: |sum of the ground's horizontal forces| on ``plank`` (on everything when None)."""
    def value(design, case):
        total = np.sum([c.force[:2] for c in case.contacts if plank in (None, c.plank)],
                       axis=0)
        return float(np.linalg.norm(total))
    return value


def friction_capacity(design, case) -> float:
    """N: mu x the ground's normal force."""
    return design.material.friction * ground_normal()(design, case)


def friction_ratio(design, case) -> float:
    """The sideways force against what friction can give: |H| / (mu N)."""
    return ground_horizontal()(design, case) / friction_capacity(design, case)


def corner_horizontal_max(design, case) -> float:
    """N: the largest horizontal ground force at one contact corner."""
    return max(float(np.linalg.norm(c.force[:2])) for c in case.contacts)


def ground_moment_inside(edge_mm: tuple[float, float], inward: tuple[float, float]
                         ) -> Quantity:
    """N m: sum N_i d_i, the moment of the ground's normal forces about a tipping edge
    through ``edge_mm`` (x, y), with d_i the distance of contact i inside it (along
    ``inward``; resting joints' corners are inside the design, not on the ground).  The
    horizontal forces act at z = 0, on the edge's level: no moment.
    Equilibrium makes it the restoring minus the overturning moment about the edge."""
    direction = np.array(inward, dtype=float) / np.linalg.norm(inward)

    def value(design, case):
        return sum(c.force[2] * float(np.dot(np.array(c.point[:2]) - edge_mm, direction))
                   for c in case.contacts if c.on is None) / 1000.0
    return value


def pressure_centre_x(design, case) -> float:
    """mm: x of the ground forces' resultant (for vertical loads: the centre of mass)."""
    return sum(c.force[2] * c.point[0] for c in case.contacts) / ground_normal()(design, case)


def self_weight(design, case) -> float:
    """kg: the planks' mass."""
    return sum(design.plank_mass(p) for p in design.planks)


def plank(plank_id: str, what: str) -> Quantity:
    """An elastic result of a plank: ``sag``, ``sag_allowed`` (mm), ``stress`` (N/mm^2)."""
    def value(design, case):
        (found,) = [p for p in case.planks if p.id == plank_id]
        return float(getattr(found, what))
    return value


def stability(design, case) -> str:
    return case.stability


def anchors_total(axis: int) -> Quantity:
    """N: |sum of the anchors' forces along world ``axis``| (the wall's pull on the
    planks)."""
    def value(design, case):
        return abs(sum(a.force[axis] for a in case.anchors))
    return value


def anchors_largest(what: str, axis: int | None = None) -> Quantity:
    """The largest anchor ``size`` (N) or ``utilization``, or with ``axis`` the largest
    |force component| along it (N)."""
    def value(design, case):
        if axis is not None:
            return max(abs(a.force[axis]) for a in case.anchors)
        return max(float(getattr(a, what)) for a in case.anchors)
    return value


def wall_push(design, case) -> float:
    """N: the walls' normal forces on the planks, summed (the pressing part of each wall
    contact's force)."""
    return sum(float(np.dot(c.force, design.walls[c.wall].normal)) for c in case.contacts
               if c.wall is not None)


def supports_moment_about(edge_yz: tuple[float, float]) -> Quantity:
    """N m: the moment of every contact's and anchor's force about the x-parallel line
    through (y, z) = ``edge_yz`` (mm), positive turning +y over -z (what holds a design
    pushed towards +y from toppling over that edge); equilibrium makes it the loads'
    overturning minus restoring moment about the edge."""
    y0, z0 = edge_yz

    def value(design, case):
        pairs = [(c.point, c.force) for c in case.contacts] + \
            [(a.point, a.force) for a in case.anchors]
        return sum((p[1] - y0) * f[2] - (p[2] - z0) * f[1] for p, f in pairs) / 1000.0
    return value


# --- the estimates ----------

@dataclass(frozen=True)
class Estimate:
    """One number of a header.  ``kind``: 'about' (within rel/abs of ``hand``), 'at most',
    'at least', 'between' (``hand`` is (low, high)) or 'is' (equal)."""

    design: str
    case: str
    what: str
    quantity: Callable
    hand: object
    quote: str | None                   # the header's text holding the number
    kind: str = "about"
    rel: float = REL
    abs: float = 0.0
    header_says: str | None = None      # a wrong header number: what it says (reported)
    model: str | None = None            # None: the file's own model, rigid without one


def tipping(design: str, case: str, edge_mm, inward, restoring: float, overturning: float,
            quote: str) -> Estimate:
    """The tipping estimate 'overturning vs restoring' (N m) as the ground's moment inside
    the edge: restoring - overturning, to 5 % of the restoring moment."""
    return Estimate(design, case, "ground moment inside the tipping edge (N m)",
                    ground_moment_inside(edge_mm, inward), restoring - overturning, quote,
                    rel=0.0, abs=REL * restoring)


_C25, _S25 = math.cos(math.radians(25.0)), math.sin(math.radians(25.0))
SHELVES_HUNG = {f"shelf_{bay}{k}" for bay in "ab" for k in (1, 2, 3, 4)}
SIDES = {"side_l", "side_m", "side_r"}

ESTIMATES = [
    # bench-long-leg: its statics are for information (penetration).  The header says the
    # middle panel has no ground contact; its corners 2 mm below the floor are ground
    # contacts (geometry: z <= tolerance), so the rigid seat on three equal panels with
    # symmetric loads shares the weight equally: (2 x 80 x 9.81 + 6.79 kg x 9.81) / 3.
    *(Estimate("bench-long-leg", "default", f"{leg} ground force (N)", ground_normal(leg),
               (2 * 80 * G + 6.793 * G) / 3, "= 545 N each in compression")
      for leg in ("leg_l", "leg_m", "leg_r")),

    Estimate("bench-tips", "default", "verdict", stability, "lift-off",
             "Expected INVALID: lift-off", kind="is"),
    Estimate("bench-tips", "default", "self-weight (N)",
             lambda d, c: self_weight(d, c) * G, 59.0, "59 N x 0.306 m"),
    tipping("bench-tips", "default", (306.0, 0.0), (-1.0, 0.0), 18.0, 199.0,
            "199 Nm of overturning moment against 59 N x 0.306 m = 18 Nm"),

    Estimate("bench", "default", "self-weight (kg)", self_weight, 6.35, "6.35 kg = 62 N"),
    *(Estimate("bench", "default", f"{leg} ground force (N)", ground_normal(leg), 816.0,
               "816 N per panel") for leg in ("leg_l", "leg_r")),
    *(Estimate("bench", "three", f"{leg} ground force (N)", ground_normal(leg), 1208.0,
               "1208 N per panel") for leg in ("leg_l", "leg_r")),
    Estimate("bench", "end", "seat/leg_r vertical force (N)", joint("seat", "leg_r", "fz"),
             770.0, "~770 N goes into the right panel"),
    Estimate("bench", "end", "seat/leg_l vertical force (N)", joint("seat", "leg_l", "fz"),
             46.0, "~46 N into the left"),
    Estimate("bench", "end", "seat/leg_r pull (N per nail)", joint("seat", "leg_r", "pull"),
             322.0, "322 N per nail, 46 %", kind="at most"),
    *(Estimate("bench", "push", f"{leg} sideways ground force (N)", ground_horizontal(leg),
               60.0, "60 N per panel foot") for leg in ("leg_l", "leg_r")),
    Estimate("bench", "push", "seat joints' pull (N per nail)",
             joints_max({"seat"}, {"leg_l", "leg_r"}, "pull"), 292.0,
             "292 N per nail (42 %)", kind="at most"),
    Estimate("bench", "push", "friction capacity (N)", friction_capacity, 816.0,
             "0.5 x 1632 N = 816 N"),

    # bookcase-sagging (elastic): the middle shelf, L = 0.9 m, w = 186 N/m.
    Estimate("bookcase-sagging", "default", "middle sag (mm)", plank("middle", "sag"),
             (2.9, 14.7), "w L^4 / 384 EI = 2.9 mm", kind="between"),
    Estimate("bookcase-sagging", "default", "middle allowed sag (mm)",
             plank("middle", "sag_allowed"), 900.0 / 400.0, "L / 400"),
    # the empty shelves: w = 22.07 N/m: w L^4 / 384 EI = 22.07 x 0.9^4 / (384 x 108) =
    # 0.35 mm (fixed ends) to 5 x that = 1.75 mm (pinned).
    *(Estimate("bookcase-sagging", "default", f"{shelf} sag bracket (mm)", plank(shelf, "sag"),
               (0.35, 1.75), "0.35 (fixed) to 1.75 mm (pinned)", kind="between")
      for shelf in ("bottom", "top")),
    Estimate("bookcase-sagging", "default", "top and bottom sag, as stated (mm)",
             plank("top", "sag"), 0.86, "(0.86 mm here:", model="elastic"),
    *(Estimate("bookcase-sagging", "default", f"{side}/middle force (N)",
               joint(side, "middle", "force"), 84.0, "84 N each")
      for side in ("side_l", "side_r")),
    Estimate("bookcase-sagging", "default", "side_l/middle shear (N per nail)",
             joint("side_l", "middle", "shear"), 7.0, "7 N per nail in shear"),
    Estimate("bookcase-sagging", "default", "side_l/middle moment (N m)",
             joint("side_l", "middle", "moment"), 12.5, "w L^2 / 12 = 12.5 N m",
             kind="at most"),
    Estimate("bookcase-sagging", "default", "side_l/middle pull (N per nail)",
             joint("side_l", "middle", "pull"), 174.0, "174 N per nail", kind="at most"),

    # nightstand-deep (elastic): the top spans the 388 mm between the sides, across its
    # 400 mm depth (``elastic._spans_across``), P = 392.4 N at its middle.
    Estimate("nightstand-deep", "default", "top sag (mm)", plank("top", "sag"),
             (0.71, 2.84), "= 0.71 mm", kind="between", model="elastic"),
    Estimate("nightstand-deep", "default", "top allowed sag (mm)", plank("top", "sag_allowed"),
             0.97, "L / 400 = 0.97 mm", model="elastic"),
    Estimate("nightstand-deep", "default", "shelf sag (mm)", plank("shelf", "sag"),
             0.49, "5 w L^4 / 384 EI = 0.49 mm", kind="at most", model="elastic"),
    # the stress: at least the section's average with fixed ends (a plate's peak under
    # the load lies above its section's average), under the strength / safety factor
    Estimate("nightstand-deep", "default", "top stress (N/mm^2)", plank("top", "stress"),
             (2.0, 22.0 / 1.5), "= 2.0 N/mm^2 (fixed ends)", kind="between", model="elastic"),
    *(Estimate("nightstand-deep", "default", f"{side}/top vertical force (N)",
               joint(side, "top", "fz"), 203.0, "203 N: 10 N per nail", model=model)
      for side in ("side_l", "side_r") for model in ("rigid", "elastic")),

    Estimate("bookshelf-20", "default", "self-weight (kg)", self_weight, 36.0,
             "self-weight 36 kg"),
    # a shelf hangs on its two end joints with the books AND its own weight:
    # (15 x 9.81 + 0.582 x 0.3 x 0.012 x 750 x 9.81) / 2 = (147.2 + 15.4) / 2 = 81.3 N,
    # 81.3 / 15 = 5.4 N per nail.
    *(Estimate("bookshelf-20", "default", f"{side}/{shelf} force (N)",
               joint(side, shelf, "fz"), (15 * G + 0.582 * 0.3 * T * 750 * G) / 2,
               "(147.2 + 15.4) / 2 = 81 N shear each")
      for side, shelf in (("side_l", "shelf_a2"), ("side_m", "shelf_b3"))),
    Estimate("bookshelf-20", "default", "hung shelves' shear (N per nail)",
             joints_max(SHELVES_HUNG, SIDES, "shear"),
             (15 * G + 0.582 * 0.3 * T * 750 * G) / 2 / 15, "(5.4 N per nail"),
    Estimate("bookshelf-20", "full", "hung shelves' shear (N per nail)",
             joints_max(SHELVES_HUNG, SIDES, "shear"), 20.0, "< 20 N shear per nail",
             kind="at most"),
    tipping("bookshelf-20", "pull", (0.0, -150.0), (0.0, 1.0), 274.0, 108.0,
            "tipping 60 N x 1.81 m = 108 Nm vs (150 + 36) kg x 9.81 x 0.15 m = 274 Nm"),
    Estimate("bookshelf-20", "shove", "friction capacity (N)", friction_capacity, 913.0,
             "friction 913 N"),

    Estimate("bookshelf-gap", "default", "side_l/shelf moment (N m)",
             joint("side_l", "shelf", "moment"), 27.4, "0.2985 m = 27.4 Nm"),
    Estimate("bookshelf-gap", "default", "side_l/shelf pull (N per nail)",
             joint("side_l", "shelf", "pull"), 380.0, "380 N per nail"),

    # cabinet-28 (elastic): shelf_b1 a plate held on three edges (``statics.plates``),
    # between the Ritz plate's clamped centre and its pinned front edge.
    Estimate("cabinet-28", "default", "shelf_b1 sag (mm)", plank("shelf_b1", "sag"),
             (0.47, 1.55), "its centre 0.47 mm", kind="between", model="elastic"),
    Estimate("cabinet-28", "default", "shelf_b1 allowed sag (mm)",
             plank("shelf_b1", "sag_allowed"), 1.22, "488 / 400 = 1.22 mm", model="elastic"),
    Estimate("cabinet-28", "default", "self-weight (kg)", self_weight, 43.6,
             "self-weight 43.6 kg"),
    Estimate("cabinet-28", "shove", "ground normal force (N)", ground_normal(), 1311.0,
             "0.5 x 1311 N = 655 N"),
    Estimate("cabinet-28", "shove", "friction ratio", friction_ratio, 0.23, "(ratio 0.23)"),

    Estimate("chair-tilted", "default", "self-weight (kg)", self_weight, 6.6,
             "self-weight 6.6 kg"),
    Estimate("chair-tilted", "lean", "seat/back moment (N m)", joint("seat", "back", "moment"),
             38.4, "(2 x 38.4 / 0.012"),
    Estimate("chair-tilted", "lean", "seat/back pull (N per nail)",
             joint("seat", "back", "pull"), 303.0, "303 N per nail (43 %)"),
    tipping("chair-tilted", "lean", (-200.0, 0.0), (1.0, 0.0), 143.0, 81.0,
            "Tipping backwards: 81 Nm vs 143 Nm"),
    # paper: the back joint carries the books (147.2 N) AND the backrest's own weight
    # (0.45 x 0.42 x 0.012 x 750 x 9.81 = 16.7 N), both at the backrest's centre, 46.8 mm
    # behind the joint line (x = -235.9 vs -189.1): 163.8 x 0.0468 = 7.67 Nm; along the
    # nails (the backrest, 12 degrees off vertical) 163.8 cos 12 = 160 N of compression:
    # (2 x 7.67 / 0.012 - 160) / 21 = 53 N per nail.
    Estimate("chair-tilted", "paper", "seat/back moment (N m)",
             joint("seat", "back", "moment"), (15 * G + 16.7) * 0.0468,
             "(147.2 + 16.7) N x 0.0468 m = 7.67 Nm"),
    Estimate("chair-tilted", "paper", "seat/back pull (N per nail)",
             joint("seat", "back", "pull"),
             (2 * (15 * G + 16.7) * 0.0468 / T
              - (15 * G + 16.7) * math.cos(math.radians(12))) / 21, "= 53 N per nail"),

    *(Estimate("chair-upright", "default", f"{side} ground force (N)", ground_normal(side),
               425.0, "425 N each") for side in ("side_l", "side_r")),
    Estimate("chair-upright", "lean", "seat/back moment (N m)",
             joint("seat", "back", "moment"), 35.0, "100 N x 0.35 m = 35 Nm"),
    Estimate("chair-upright", "lean", "seat/back pull (N per nail)",
             joint("seat", "back", "pull"), 277.0, "277 N per nail (40 %)"),
    tipping("chair-upright", "lean", (-200.0, 0.0), (1.0, 0.0), 143.0, 80.0,
            "100 N x 0.8 m = 80 Nm vs 785 N x 0.17 m + 65 N x 0.155 m = 143 Nm"),
    Estimate("chair-upright", "lean", "friction capacity (N)", friction_capacity, 425.0,
             "friction 425 N >> 100 N"),
    Estimate("chair-upright", "lean", "sideways ground force (N)", ground_horizontal(), 100.0,
             "friction 425 N >> 100 N"),

    *(Estimate("coffee-table-splayed", case, f"{leg} ground force (N)", ground_normal(leg),
               hand, quote)
      for case, hand, quote in (("default", 62.5, "= 62.5 N"), ("sit", 210.0, "210 N per leg"))
      for leg in ("leg_pp", "leg_mm")),
    # The joint's moment from the leg's free body: the foot's reaction R 63.5 mm outboard,
    # the leg's own weight (0.4 x 0.1 x 0.012 x 750 x 9.81 = 3.53 N) at half that, and the
    # foot's inward friction H (read from the report: the rigid model's penalty joints
    # let the splayed feet push out against their friction anchors) 396 mm below.
    *(Estimate("coffee-table-splayed", case, "top/leg_pp moment (N m)",
               joint("top", "leg_pp", "moment"), None, None, kind="leg free body")
      for case in ("default", "sit")),
    # With frictionless feet (H = 0) that is R x 0.0635 - 3.53 x 0.03175: 3.86 N m
    # (default) and 13.20 N m (sit), and the pull (2 M / t - 58.5 or 203 N along the
    # nails) / 5 = 117 and 399 N per nail, as the header says (the
    # foot's reaction, 62.5 N, includes the leg's weight).  The feet's inward
    # thrust takes some of it: 9 % in the report (0.8 and 2.7 N at 0.396 m), so the bound
    # is 'at most', and the report must be within 15 % below it.
    *(Estimate("coffee-table-splayed", case, "top/leg_pp pull (N per nail)",
               joint("top", "leg_pp", "pull"), hand, quote, kind="at most, within 15 %")
      for case, hand, quote in (("default", 117.0, "= at most 117 N per nail"),
                                ("sit", 399.0, "= at most 399 N per nail"))),

    Estimate("l-shelf-pushed", "default", "ground normal force (N)", ground_normal(), 20.1,
             "x g = 20.1 N"),
    Estimate("l-shelf-pushed", "default", "friction ratio", friction_ratio, 0.99,
             "17.25 N > 17.1 N (99 %)", rel=0.01),
    Estimate("l-shelf-pushed", "default", "base/post0 force (N)",
             joint("base", "post0", "force"), 8.2 + 2.1, "(8.2 N and 2.1 N)"),
    # the shelf weighs 287.5 x 64.9 x 15 mm^3 x 750 kg/m^3 x 9.81 = 2.06 N (and the post
    # 277.5 x 160 x 25 mm^3: 8.17 N): its joint with the post carries 2.06 N, not 1.5.
    Estimate("l-shelf-pushed", "default", "post0/shelf0 force (N)",
             joint("post0", "shelf0", "force"), 0.2875367 * 0.0649202 * 0.015 * 750 * G,
             "2.1 N"),

    Estimate("magazine-rack", "default", "self-weight (kg)", self_weight, 4.6,
             "self-weight 4.6 kg"),
    *(Estimate("magazine-rack", "default", f"{a}/{b} nails", joint(a, b, "nails"), nails,
               quote, kind="is")
      for a, b, nails, quote in (("base", "slat_a", 19, "the base (19 nails)"),
                                 ("base", "slat_b", 19, "the base (19 nails)"),
                                 ("end_l", "slat_a", 10, "(10 nails each)"),
                                 ("end_r", "slat_b", 10, "(10 nails each)"))),
    Estimate("magazine-rack", "kick", "friction capacity (N)", friction_capacity, 62.0,
             "0.5 x 123 N = 62 N"),
    Estimate("magazine-rack", "kick", "friction ratio", friction_ratio, 0.49, "(ratio 0.49)"),
    tipping("magazine-rack", "kick", (-210.0 * _C25, -210.0 * _S25), (_C25, _S25), 26.0, 4.5,
            "30 N x 0.15 m = 4.5 Nm vs 123 N x 0.21 m = 26 Nm"),
    *(Estimate("magazine-rack", "hand", f"{end}/handle force (N)",
               joint(end, "handle", "force"), 74.0, "74 N per handle end")
      for end in ("end_l", "end_r")),
    Estimate("magazine-rack", "hand", "end_l/handle shear (N per nail)",
             joint("end_l", "handle", "shear"), 37.0, "37 N shear per nail"),
    Estimate("magazine-rack", "hand", "end_l/handle nails", joint("end_l", "handle", "nails"),
             2, "on 2 nails", kind="is"),

    # particleboard-shelf-overloaded (elastic): w = 1635 N/m on L = 0.9 m, Z = 6.0e-6 m^3.
    Estimate("particleboard-shelf-overloaded", "default", "middle stress (N/mm^2)",
             plank("middle", "stress"), (13.8, 1635 * 0.81 / 8 / 6.0e-6 / 1e6),
             "stress >= 13.8 N/mm^2", kind="between"),
    Estimate("particleboard-shelf-overloaded", "default", "middle sag (mm)",
             plank("middle", "sag"), 43.0, "= 43 mm", kind="at least"),
    Estimate("particleboard-shelf-overloaded", "default", "middle allowed sag (mm)",
             plank("middle", "sag_allowed"), 2.25, "allowed 2.25 / 1.5 = 1.5 mm"),
    Estimate("particleboard-shelf-overloaded", "default", "side_l/middle moment bound (N m)",
             joint("side_l", "middle", "moment"), 110.0, "w L^2 / 12 = 110 N m",
             kind="at most"),
    Estimate("particleboard-shelf-overloaded", "default",
             "side_l/middle pull bound (N per nail)", joint("side_l", "middle", "pull"), 733.0,
             "733 N per nail", kind="at most"),
    Estimate("particleboard-shelf-overloaded", "default", "side_l/middle moment (N m)",
             joint("side_l", "middle", "moment"), 86.0, "about 86 N m"),
    Estimate("particleboard-shelf-overloaded", "default", "side_l/middle pull (N per nail)",
             joint("side_l", "middle", "pull"), 571.0, "571 N per nail"),

    Estimate("shelf-cantilever-overloaded", "default", "post/shelf moment (N m)",
             joint("post", "shelf", "moment"), 90.4, "10.6 N x 0.20 m = 90.4 Nm"),
    Estimate("shelf-cantilever-overloaded", "default", "post/shelf pull (N per nail)",
             joint("post", "shelf", "pull"), 1004.0, "= 1004 N per nail"),
    Estimate("shelf-cantilever-overloaded", "default", "base/post moment (N m)",
             joint("base", "post", "moment"), 92.2, "92.2 Nm"),
    # the post carries the books (294.3 N), the shelf (10.6 N) and itself
    # (0.8 x 0.6 x 0.012 x 750 x 9.81 = 42.4 N): 347 N of compression.
    Estimate("shelf-cantilever-overloaded", "default", "base/post compression (N)",
             joint("base", "post", "fz"), 30 * G + 10.6 + 0.8 * 0.6 * T * 750 * G,
             "= 347 N compression"),
    Estimate("shelf-cantilever-overloaded", "default", "base/post pull (N per nail)",
             joint("base", "post", "pull"), 501.0, "= 501 N per nail"),
    Estimate("shelf-cantilever-overloaded", "default", "centre of mass x (mm)",
             pressure_centre_x, 114.0, "Centre of mass at x = 114"),

    Estimate("shelf-cantilever", "default", "post/shelf moment (N m)",
             joint("post", "shelf", "moment"), 22.4, "= 22.4 Nm"),
    Estimate("shelf-cantilever", "default", "post/shelf pull (N per nail)",
             joint("post", "shelf", "pull"), 249.0, "= 249 N per nail"),
    Estimate("shelf-cantilever", "default", "post/shelf shear (N per nail)",
             joint("post", "shelf", "shear"), 10.0, "155 N / 15 = 10 N", rel=0.05, abs=0.5),
    Estimate("shelf-cantilever", "default", "base/post moment (N m)",
             joint("base", "post", "moment"), 23.3, "23.3 Nm"),
    Estimate("shelf-cantilever", "default", "base/post compression (N)",
             joint("base", "post", "fz"), 183.0, "183 N"),
    Estimate("shelf-cantilever", "default", "base/post pull (N per nail)",
             joint("base", "post", "pull"), 185.0, "= 185 N per nail"),
    Estimate("shelf-cantilever", "default", "centre of mass x (mm)", pressure_centre_x,
             -21.0, "Centre of mass at x = -21", rel=0.0, abs=1.0),
    Estimate("shelf-cantilever", "vase", "post/shelf moment (N m)",
             joint("post", "shelf", "moment"), 15.1, "15.1 Nm"),
    Estimate("shelf-cantilever", "vase", "post/shelf pull (N per nail)",
             joint("post", "shelf", "pull"), 168.0, "168 N per nail"),

    *(Estimate("stool", "default", f"{leg} ground force (N)", ground_normal(leg), 410.0,
               "= 410 N") for leg in ("leg_l", "leg_r")),
    Estimate("stool", "perch", "seat/leg_l compression (N)", joint("seat", "leg_l", "fz"),
             50.0, "far panel still carries ~ 50 N"),
    Estimate("stool", "rock", "sideways force per foot corner (N)", corner_horizontal_max,
             12.5, "12.5 N per foot corner"),
    *(Estimate("stool", "rock", f"{leg} sideways ground force (N)", ground_horizontal(leg),
               50.0, "50 N per panel") for leg in ("leg_l", "leg_r")),
    Estimate("stool", "rock", "seat joints' pull (N per nail)",
             joints_max({"seat"}, {"leg_l", "leg_r"}, "pull"), 243.0, "243 N per nail",
             kind="at most"),
    Estimate("stool", "rock", "friction capacity (N)", friction_capacity, 410.0,
             "0.5 x 821 N = 410 N"),
    tipping("stool", "rock", (176.0, 0.0), (-1.0, 0.0), 144.0, 44.0,
            "tipping moment 44 Nm vs 821 N x 0.176 m = 144 Nm"),

    Estimate("table-slides", "shove", "verdict", stability, "sliding",
             "Expected INVALID: sliding (case shove)", kind="is"),
    Estimate("table-slides", "shove", "ground normal force (N)", ground_normal(), 124.0,
             "0.5 x 124 N = 62 N"),
    Estimate("table-slides", "shove", "friction ratio", friction_ratio, 1.8,
             "needs 1.8 x what friction gives"),
    tipping("table-slides", "shove", (436.0, 0.0), (-1.0, 0.0), 54.0, 16.5,
            "110 N x 0.15 m = 16.5 Nm against 124 N x 0.436 m = 54 Nm"),
    Estimate("table-slides", "shove", "joints' pull (N per nail)",
             lambda d, c: max(j.pull for j in c.joints), 700.0, "well under 700 N per nail",
             kind="at most"),

    Estimate("table", "default", "self-weight (kg)", self_weight, 12.6,
             "self-weight 12.6 kg = 124 N"),
    *(Estimate("table", "default", f"{leg} ground force (N)", ground_normal(leg), 210.0,
               "~210 N each") for leg in ("leg_l", "leg_r")),
    tipping("table", "lean", (436.0, 0.0), (-1.0, 0.0), 54.0, 22.0,
            "491 N x 0.044 m = 22 Nm vs self-weight 124 N x 0.436 m = 54 Nm"),
    Estimate("table", "push", "friction capacity (N)", friction_capacity, 209.0,
             "0.5 x 418 N = 209 N"),
    Estimate("table", "push", "friction ratio", friction_ratio, 0.48, "(ratio 0.48)"),
    tipping("table", "push", (436.0, 0.0), (-1.0, 0.0), 182.0, 73.0,
            "100 N x 0.726 m = 73 Nm vs 418 N x 0.436 m = 182 Nm"),
    Estimate("table", "push", "top/panel joints' pull (N per nail)",
             joints_max({"top"}, {"leg_l", "leg_r"}, "pull"), 240.0, "240 N per nail (34 %)",
             kind="at most"),
    # the table on four nailed legs, racked by a push
    Estimate("table-racking", "default", "self-weight (kg)", self_weight, 6.912,
             "legs 4 x 0.378 kg: 6.912 kg"),
    *(Estimate("table-racking", "default", f"{leg} ground force (N)", ground_normal(leg),
               66.0, "each leg carries a quarter, 66 N")
      for leg in ("leg_pp", "leg_mp", "leg_pm", "leg_mm")),
    Estimate("table-racking", "push", "top/leg joints' mean pull (N per nail)",
             lambda d, c: float(np.mean([j.pull for j in c.joints])), 981.0,
             "981 N per nail on average"),
    Estimate("table-racking", "push", "friction capacity (N)", friction_capacity, 132.0,
             "0.5 x 264 N = 132 N"),
    Estimate("table-racking", "push", "friction ratio", friction_ratio, 0.76, "(ratio 0.76)"),
    tipping("table-racking", "push", (450.0, 0.0), (-1.0, 0.0), 118.8, 70.6,
            "100 N x 0.706 m = 70.6 Nm vs 264 N x 0.45 m = 118.8 Nm"),
    # the mixed-material table: its top's own material (an 18 mm C24 softwood top)
    Estimate("table-pine-top", "default", "self-weight (kg)", self_weight, 11.78,
             "11.78 kg = 115.5 N"),
    *(Estimate("table-pine-top", "default", f"{leg} ground force (N)", ground_normal(leg),
               205.0, "205 N each") for leg in ("leg_l", "leg_r")),
    tipping("table-pine-top", "lean", (436.0, 0.0), (-1.0, 0.0), 50.4, 21.6,
            "490.5 N x 0.044 m = 21.6 Nm vs self-weight 115.5 N x 0.436 m = 50.4 Nm"),
    Estimate("table-pine-top", "default", "top sag, at most pinned (mm)", plank("top", "sag"),
             1.325, "1.216 + 0.099 + 0.010 = 1.325 mm", kind="at most", model="elastic"),
    Estimate("table-pine-top", "default", "top allowed sag (mm)", plank("top", "sag_allowed"),
             2.15, "860 / 400 = 2.15 mm", rel=1e-3, model="elastic"),
    Estimate("table-pine-top", "default", "top stress, fixed ends to strength (N/mm^2)",
             plank("top", "stress"), (1.06, 24.0 / 1.5), "34,380 / 32,400 = 1.06 N/mm^2",
             kind="between", model="elastic"),
    Estimate("table-pine-top", "default", "top strength (N/mm^2)", plank("top", "strength"),
             24.0, "bending strength 24 N/mm^2", rel=1e-9, model="elastic"),

    # the bookcase with a loose shelf on pins (resting joints)
    *(Estimate("bookcase-pins", "default", f"side_{s}/pin_{s}{e} shear (N per nail)",
               joint(f"side_{s}", f"pin_{s}{e}", "shear"), 35.37, "35.37 N shear on each")
      for s in "lr" for e in "fb"),
    Estimate("bookcase-pins", "default", "shelf's press on its pins (N)",
             lambda d, c: -sum(k.force[2] for k in c.contacts if k.on == "shelf"), 141.48,
             "with 141.48 N in all", rel=1e-3),
    tipping("bookcase-pins", "push", (0.0, 150.0), (0.0, -1.0), 58.2, 20.4,
            "20 N x 1.018 m = 20.4 Nm passes 387.8 N x 0.150 m = 58.2 Nm"),
    Estimate("bookcase-pins", "default", "shelf sag bracket (mm)", plank("shelf", "sag"),
             (0.180, 0.901), "0.180 to 0.901 mm", kind="between", model="elastic"),
    Estimate("bookcase-pins", "default", "shelf allowed sag (mm)",
             plank("shelf", "sag_allowed"), 1.495, "598 / 400 = 1.495 mm", rel=1e-3,
             model="elastic"),

    # --- the elastic model (the default): the headers' "Elastic model" estimates ----------
    # Sag brackets from the beam formulas quoted in each header: the lower end with fixed
    # ends, the upper with pinned ends (own weight included); allowed = span / 400 (the
    # report's sag_allowed; the verdict compares 1.5 x sag with it).
    *(Estimate(name, case, f"{p} sag bracket (mm)", plank(p, "sag"), bracket, quote,
               kind="between", model="elastic")
      for name, case, p, bracket, quote in (
          ("stool", "default", "seat", (1.24, 5.0), "P L^3 / 48 EI = 4.96 mm"),
          ("stool-thick-seat", "default", "seat", (0.139, 0.556),
           "0.556 mm with its own weight"),
          ("table", "default", "top", (4.05, 16.5), "3.8 + 0.3 = 4.05 mm with fixed ends"),
          ("table-racking", "default", "top", (3.09, 12.7), "2.76 + 0.33 = 3.09 mm (fixed ends)"),
          ("table-slides", "default", "top", (4.05, 16.5),
           "4.05 (fixed ends) to 16.5 mm (pinned)"),
          ("bench", "default", "seat", (27.9, 172.4), "28 mm with fixed ends"),
          ("bench-long-leg", "default", "seat", (4.2, 8.43),
           "4.2 to 8.4 mm with its own weight"),
          ("chair-upright", "default", "seat", (1.62, 6.5), "1.6 mm with fixed ends"),
          ("chair-tilted", "default", "seat", (1.62, 6.5),
           "1.6 (fixed ends) to 6.5 mm (pinned)"),
          ("coffee-table-splayed", "default", "top", (2.52, 10.3),
           "2.3 + 0.2 = 2.5 mm with fixed ones"),
          ("magazine-rack", "hand", "handle", (2.60, 10.42), "2.6 mm with fixed ends"),
          ("bookshelf-gap", "default", "bottom", (1.6, 6.48),
           "1.6 (fixed ends) to 6.5 mm (pinned)"),
          *(("bookshelf-20", "default", shelf, (1.227, 4.97), "1.23 mm, with fixed ends")
            for shelf in sorted(SHELVES_HUNG)),
          *(("bookshelf-18", "default", shelf, (0.146, 0.731), "0.15 mm with fixed ends")
            for shelf in ("bottom", "middle", "top")))),
    *(Estimate(name, case, f"{p} allowed sag (mm)", plank(p, "sag_allowed"), hand, quote,
               rel=1e-3, model="elastic")
      for name, case, p, hand, quote in (
          ("stool", "default", "seat", 0.85, "L / 400 = 0.85 mm"),
          ("stool-thick-seat", "default", "seat", 0.85, "340 / 400 = 0.85 mm"),
          ("table", "default", "top", 2.15, "860 / 400 = 2.15 mm"),
          ("table-racking", "default", "top", 2.22, "888 / 400 = 2.22 mm"),
          ("bench", "default", "seat", 2.6, "1040 / 400 = 2.6 mm"),
          ("bench-long-leg", "default", "seat", 2.6, "1040 / 400 = 2.6 mm"),
          ("chair-upright", "default", "seat", 1.02, "408 / 400 = 1.02 mm"),
          ("coffee-table-splayed", "default", "top", 1.97, "788.2 / 400 = 1.97 mm"),
          ("magazine-rack", "hand", "handle", 0.97, "388 / 400 = 0.97 mm"),
          ("bookshelf-20", "default", "shelf_a1", 1.455, "582 / 400 = 1.455 mm"),
          ("shelf-cantilever", "default", "shelf", 1.5, "2 x 300 / 400 = 1.5 mm"),
          ("shelf-cantilever", "default", "post", 4.0, "2 x 800 / 400 = 4 mm"),
          ("shelf-cantilever-overloaded", "default", "shelf", 2.0, "2 x 400 / 400 = 2 mm"),
          ("bookshelf-gap", "default", "shelf", 2.985, "2 x 597 / 400 = 2.99 mm"),
          ("l-shelf-pushed", "default", "shelf0", 1.4377, "2 x 287.5 / 400 = 1.44 mm"),
          ("bookshelf-18", "default", "middle", 1.25, "500 / 400 = 1.25 mm"),
          ("chair-upright", "lean", "back", 2.25, "2 x 450 / 400 = 2.25 mm"))),
    # cantilevers, from the tangent at the held end (contract 3a): P a^2 (3 L - a) / 6 EI
    # + w L^4 / 8 EI, and the posts turned by the shelf's moment M at a above the base:
    # M a^2 / 2 EI + M a (L - a) / EI.
    *(Estimate(name, case, f"{p} sag (mm)", plank(p, "sag"), hand, quote, model="elastic")
      for name, case, p, hand, quote in (
          ("shelf-cantilever", "default", "shelf", 2.97 + 0.21, "2.97 + 0.21 = 3.2 mm"),
          ("shelf-cantilever", "default", "post", 23.3 + 16.8, "23.3 + 16.8 = 40 mm"),
          ("shelf-cantilever-overloaded", "default", "shelf", 30.66 + 0.65,
           "30.7 + 0.7 = 31 mm"),
          ("shelf-cantilever-overloaded", "default", "post", 61.5 + 44.3,
           "61.5 + 44.3 = 106 mm"),
          ("bookshelf-gap", "default", "shelf", 16.1 + 3.24, "16.1 + 3.2 = 19.4 mm"),
          ("chair-upright", "lean", "back", 11.25, "= 11.3 mm from the tangent"),
          ("chair-tilted", "lean", "back", 12.59 + 0.22, "= 12.6 mm, plus its own weight"),
          ("chair-tilted", "paper", "back", 1.60 + 0.22, "1.6 + 0.2 = 1.8 mm"),
          ("l-shelf-pushed", "default", "shelf0", 0.112, "w L^4 / 8 EI = 0.11 mm"))),
    # bench: the seat's ends hold 57 % (panels bending, pinned at the foot) to 68 % (rigid
    # panels) of a fixed end's moment through the nail rows' springs.
    Estimate("bench", "default", "seat joints' pull (N per nail)",
             joints_max({"seat"}, {"leg_l", "leg_r"}, "pull"), (830.0, 1000.0),
             "= 830 to 1000 N per nail", kind="between", model="elastic"),
    Estimate("bench", "three", "seat stress (N/mm^2)", plank("seat", "stress"),
             (24.1, 26.9), "24.1 to 26.9 N/mm^2", kind="between", model="elastic"),
    Estimate("magazine-rack", "hand", "handle stress bound (N/mm^2)",
             plank("handle", "stress"), 14.9, "= 14.9 N/mm^2 < 22", kind="at most",
             model="elastic"),
    Estimate("magazine-rack", "hand", "end_l/handle pull bound (N per nail)",
             joint("end_l", "handle", "pull"), 595.0, "595 N per nail < 700", kind="at most",
             model="elastic"),
    Estimate("stool-thick-seat", "default", "seat stress bounds (N/mm^2)",
             plank("seat", "stress"), (1.07, 22.0 / 1.5), "= 1.07 N/mm^2 (fixed",
             kind="between", model="elastic"),
    Estimate("bookshelf-18", "default", "side_l sag bound (mm)", plank("side_l", "sag"),
             0.74, "M L^2 / 8 EI = 0.74 mm", kind="at most", model="elastic"),
    Estimate("bookshelf-18", "default", "shelf end joints' pull bound (N per nail)",
             joints_max({"side_l", "side_r"}, {"bottom", "middle", "top"}, "pull"), 63.0,
             "= 63 N per nail", kind="at most", model="elastic"),
    # the determinate joints carry the same forces in both models (contract 3a)
    Estimate("shelf-cantilever-overloaded", "default", "post/shelf pull (N per nail)",
             joint("post", "shelf", "pull"), 1004.0, "= 1004 N per nail", model="elastic"),
    Estimate("l-shelf-pushed", "default", "friction ratio", friction_ratio, 0.99,
             "17.25 N > 17.1 N (99 %)", rel=0.01, model="elastic"),
    Estimate("bench-tips", "default", "verdict", stability, "lift-off",
             "Expected INVALID: lift-off", kind="is", model="elastic"),

    # the new designs' rigid statics
    Estimate("stool-thick-seat", "default", "self-weight (kg)", self_weight, 4.85,
             "self-weight 4.85 kg"),
    *(Estimate("stool-thick-seat", "default", f"seat/{leg} compression (N)",
               joint("seat", leg, "fz"), (80 + 2.25) * G / 2, "(785 + 22) / 2 = 403 N")
      for leg in ("leg_l", "leg_r")),
    Estimate("stool-thick-seat", "perch", "seat/leg_l compression (N)",
             joint("seat", "leg_l", "fz"), 57.0, "the left panel carries ~ 57 N"),
    *(Estimate("bookshelf-18", "default", f"side_l/{shelf} shear (N per nail)",
               joint("side_l", shelf, "shear"), 6.8, "6.8 N shear per nail")
      for shelf in ("bottom", "middle", "top")),
    *(Estimate("bookshelf-18", "default", f"{side} ground force (N)", ground_normal(side),
               276.0, "3 x 81.9 + 29.8 = 276 N") for side in ("side_l", "side_r")),

    # the wall shelf and the anchored bookcase (walls and anchors, contract section 2):
    # their anchors' forces, in both models
    Estimate("wall-shelf", "default", "self-weight (kg)", self_weight, 2.7 + 2 * 0.243,
             "shelf 2.7 kg = 26.49 N, blocks 0.243 kg = 2.38 N each"),
    *(Estimate("wall-shelf", "default", what, quantity, hand, quote, model=model)
      for model in ("rigid", "elastic")
      for what, quantity, hand, quote in (
          ("shelf/cleat_l moment (N m)", joint("shelf", "cleat_l", "moment"), 10.07,
           "M = 86.8 N x 0.116 m = 10.07 N m"),
          ("shelf/cleat_r pull (N per nail)", joint("shelf", "cleat_r", "pull"), 147.4,
           "= 147.4 N per nail"))),
    *(Estimate("wall-shelf", "default", what, quantity, hand, quote, kind="between",
               model=model)
      for model in ("rigid", "elastic")
      for what, quantity, hand, quote in (
          ("anchors' pull (N)", anchors_total(1), (223.8, 241.6), "= 223.8 N and 241.6 N"),
          ("each anchor's pull (N)", anchors_largest("pull", axis=1), (111.9, 120.8),
           "111.9 to 120.8 N each"),
          ("the wall's push on the feet (N)", wall_push, (223.8, 241.6),
           "the wall pushes the four feet corners with as much"))),
    *(Estimate("wall-shelf", "default", what, quantity, hand, quote, kind=kind, model=model)
      for model in ("rigid", "elastic")
      for what, quantity, hand, quote, kind in (
          ("anchor force bound (N)", anchors_largest("size"), 150.2,
           "(120.8^2 + 89.2^2)^0.5 = 150.2 N", "at most"),
          ("shelf/cleat_l nails", joint("shelf", "cleat_l", "nails"), 7,
           "7 nails down through the shelf", "is"))),
    Estimate("wall-shelf", "default", "shelf overhang sag (mm)", plank("shelf", "sag"),
             0.078 + 0.001, "w a^4 / 8 EI = 0.078 mm (+ 0.001 mm shear)", model="elastic"),
    Estimate("wall-shelf", "default", "shelf allowed sag (mm)", plank("shelf", "sag_allowed"),
             0.9, "2 x 180 / 400 = 0.9 mm", rel=1e-3, model="elastic"),
    Estimate("wall-shelf", "default", "shelf stress (N/mm^2)", plank("shelf", "stress"),
             0.26, "13,500 mm^3: 0.26 N/mm^2", model="elastic"),

    # the wall shelf on a rail: its fixings by the moments about the rail's foot, in both
    # models; elastic, the shelf hangs on its one row as a plate
    Estimate("wall-shelf-rail", "default", "self-weight (kg)", self_weight, 3.04 + 1.22,
             "shelf 3.04 kg = 29.8 N, rail 1.22 kg = 11.9 N"),
    *(Estimate("wall-shelf-rail", "default", what, quantity, hand, quote, kind=kind,
               model=model)
      for model in ("rigid", "elastic")
      for what, quantity, hand, quote, kind in (
          ("each anchor's pull (N)", anchors_largest("pull", axis=1), (251.0, 271.0),
           "251 to 271 N per screw", "between"),
          ("shelf/rail moment (N m)", joint("shelf", "rail", "moment"), 37.6,
           "M = 324.1 N x 0.116 m = 37.6 N m", "about"))),
    Estimate("wall-shelf-rail", "default", "shelf/rail pull (N per nail)",
             joint("shelf", "rail", "pull"), 85.6, "324.1) / 45 = 85.6 N", model="rigid"),
    Estimate("wall-shelf-rail", "default", "shelf sag (mm)", plank("shelf", "sag"),
             (0.394, 1.08 * 0.394), "0.390 + 0.003 = 0.394 mm along its middle",
             kind="between", model="elastic"),
    Estimate("wall-shelf-rail", "default", "shelf allowed sag (mm)",
             plank("shelf", "sag_allowed"), 1.205, "2 x 241 / 400 = 1.205 mm", rel=1e-3,
             model="elastic"),
    Estimate("wall-shelf-rail", "default", "shelf stress (N/mm^2)", plank("shelf", "stress"),
             0.774, "6 M / t^2 = 0.774 N/mm^2", rel=0.02, model="elastic"),

    Estimate("bookcase-anchored", "default", "self-weight (kg)", self_weight, 26.0,
             "26.0 kg = 255.1 N"),
    *(Estimate("bookcase-anchored", "default", f"{side}/{shelf} shear (N per nail)",
               joint(side, shelf, "shear"), 5.65, "5.65 N per nail in shear")
      for side in ("side_l", "side_r") for shelf in ("bottom", "shelf_1", "shelf_2")),
    Estimate("bookcase-anchored", "default", "anchors' vertical share, rigid (N)",
             anchors_largest("lift", axis=2), 84.4, "2/10 of W, 84.4 N each"),
    *(Estimate("bookcase-anchored", "push", what, quantity, hand, quote, rel=rel, abs=0.0,
               model=model)
      for model in ("rigid", "elastic")
      for what, quantity, hand, quote, rel in (
          ("anchors' pull (N)", anchors_total(1), 222.0, "about 111 N each", REL),
          ("supports' moment about the front edge (N m)", supports_moment_about((315.0, 0.0)),
           222.0 * 1.8 - 86.0007 * G * 0.15, "P h - W d = 273.0 N m", 1e-3))),
    *(Estimate("bookcase-anchored", case, "anchor force bound (N)", anchors_largest("size"),
               139.4, "(111^2 + 84.4^2)^0.5 = 139.4 N", kind="at most", model=model)
      for model in ("rigid", "elastic") for case in ("default", "push")),
    *(Estimate("bookcase-anchored", case, f"{shelf} sag bracket (mm)", plank(shelf, "sag"),
               (0.181, 0.905), "w L^4 / 384 EI = 0.181 mm", kind="between", model="elastic")
      for case in ("default", "push") for shelf in ("bottom", "shelf_1", "shelf_2", "shelf_3")),
    Estimate("bookcase-anchored", "default", "shelf_2 allowed sag (mm)",
             plank("shelf_2", "sag_allowed"), 1.41, "564 / 400 = 1.41 mm", rel=1e-3,
             model="elastic"),
]


def _leg_free_body_moment(design, case) -> float:
    """coffee-table-splayed: |M| at top/leg_pp from the leg's free body, N m (above)."""
    feet = [c for c in case.contacts if c.plank == "leg_pp"]
    reaction = sum(c.force[2] for c in feet)
    thrust = abs(sum(c.force[0] for c in feet))
    leg_weight = 0.4 * 0.1 * T * 750 * G
    return reaction * 0.0635 - leg_weight * 0.03175 - thrust * 0.396


def _id(estimate: Estimate) -> str:
    model = f":{estimate.model}" if estimate.model else ""
    return f"{estimate.design}:{estimate.case}:{estimate.what}{model}"


@pytest.mark.parametrize("estimate", ESTIMATES, ids=_id)
def test_header_estimate(estimate: Estimate):
    """The report agrees with the header's hand estimate (see the module docstring)."""
    if estimate.quote is not None:
        assert estimate.quote in header(estimate.design), estimate.quote
    design, report = design_and_report(estimate.design, estimate.model)
    found = estimate.quantity(design, case_of(report, estimate.case))
    hand, kind = estimate.hand, estimate.kind
    where = f"{_id(estimate)}: report {found!r}, hand {hand!r} ({kind})"
    if kind == "is":
        assert found == hand, where
    elif kind == "about":
        assert found == pytest.approx(hand, rel=estimate.rel, abs=estimate.abs), where
    elif kind == "at most":
        assert found <= hand, where
    elif kind == "at least":
        assert found >= hand, where
    elif kind == "between":
        low, high = hand
        assert low <= found <= high, where
    elif kind == "at most, within 15 %":
        assert 0.85 * hand <= found <= hand, where
    elif kind == "leg free body":
        expected = _leg_free_body_moment(design, case_of(report, estimate.case))
        assert found == pytest.approx(expected, rel=0.01), where
    else:
        raise AssertionError(f"unknown kind {kind!r}")


def test_every_catalog_file_has_a_hand_estimate_checked_or_excused():
    """Every design file's header has a hand estimate, and every file but the floating one
    (no statics to check against) has at least one number checked here."""
    names = sorted(p.stem for p in CATALOG.glob("*.yaml"))
    for name in names:
        assert "Hand estimate" in header(name), name
    assert set(names) - {e.design for e in ESTIMATES} == {"side-table-hovering"}
