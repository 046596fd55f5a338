"""Against toppling: a leg under the overhang, or an outrigger foot that widens the stance.

A design lifts off (contract section 3: no equilibrium with the ground only pushing) when
the line of action of its loads meets the floor outside its support polygon, the convex
hull of its ground contacts.  For rigid planks on the floor that point is the centre of
pressure the ground would need::

    c_x = sum(x_i F_zi - z_i F_xi) / sum(F_zi),   c_y = sum(y_i F_zi - z_i F_yi) / sum(F_zi)

over the loads and the planks' weights F_i acting at r_i (the moments about the floor
point c have no horizontal part: friction acts in the floor's plane).  The fixes move
the polygon's edge past c, in the direction d from the polygon's nearest point to c:

- a *support* standing on the floor under the far end, along d, of a level plank that
  reaches past c (a third leg under the end of a bench where someone sits), nailed to
  that plank (``supports.support_candidate`` on the floor);
- an *outrigger*: a board on edge standing on the floor, its end nailed to the outer face
  of a leg at the polygon's edge (the face looking along d), reaching past c by
  OUTRIGGER_REACH times the distance from that face; as high as it is long (up to the
  leg's height less OUTRIGGER_CLEARANCE), so that its nail row, as long as its height,
  takes the tipping moment that its far end carries back to the leg.

Tried when the only violations are lift-off in cases without walls or anchors (a design
leaning on a wall gets a wall anchor instead, ``anchors``).
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import replace

import numpy as np

from furncheck.geometry.support import convex_hull, outside, pressure_centre
from furncheck.suggest.discrete.common import (
    Candidate,
    Fix,
    Search,
    amount,
    board,
    legs,
    level,
    new_id,
    normal,
    size_of,
    with_planks,
)
from furncheck.suggest.discrete.supports import support_candidate

OUTRIGGER_REACH = (1.5, 2.5)
"""How far past the centre of pressure an outrigger reaches, as multiples of its
distance from the leg's face: the shortest that works is suggested."""

SHOP_STEP = 1e-3
"""m: an outrigger's reach is cut up to a whole millimetre (a foot 39.6 mm long is cut
at 40: reaching further out only holds better)."""

OUTRIGGER_CLEARANCE = 2.0
"""An outrigger stays this many plank thicknesses below its leg's top (clear of the plank
the leg carries)."""

FACING_COS = 0.7
"""An outrigger goes on a leg face whose outward normal is within 45 degrees of d."""

SUPPORTS_TRIED = 3
"""Level planks tried for a support under their far end, farthest reaching first."""


OVERHANG = "support under the overhang"
"""The names of the rules in ``tried.Trial`` values."""
OUTRIGGER = "outrigger"


def overhang_supports(search: Search) -> Fix | None:
    """The first working support under the far end of an overhanging plank."""
    tipping = _tipping(search, OVERHANG)
    if tipping is None:
        return None
    return search.first_valid(_support_candidates(search, *tipping))


def outriggers(search: Search) -> Fix | None:
    """The first working outrigger foot on the leg at the polygon's edge."""
    tipping = _tipping(search, OUTRIGGER)
    if tipping is None:
        return None
    return search.first_valid(_outrigger_candidates(search, *tipping))


def _tipping(search: Search, rule: str) -> tuple[np.ndarray, np.ndarray, float] | None:
    """(c (2,) m, d (2,) unit, its distance past the polygon m) of the lift-off case whose
    centre of pressure lies farthest outside the support polygon; None (and why recorded
    for ``rule``) unless the violations are lift-offs of a design without walls or
    anchors (and, elastic, planks bending too much, which thicker boards then finish:
    ``Search.repairs``), or when the centre of pressure lies inside (a part lifts, not
    the whole)."""
    design = search.design
    if not search.repairs(rule, ("lift-off",)):
        return None
    if design.walls or design.anchors:
        search.not_applicable(rule, "the design stands by a wall (a wall anchor is tried)")
        return None
    points = np.array([c.point[:2] for c in search.geometry.contacts if c.on_floor])
    if len(points) < 3:
        search.not_applicable(rule, "the design stands on fewer than three floor points")
        return None
    hull = points[convex_hull(points)]
    worst = None
    for case_name in dict.fromkeys(v.case for v in search.report.violations):
        case = next(c for c in design.load_cases if c.name == case_name)
        centre = pressure_centre(design, case)
        if centre is None:
            continue
        nearest = _nearest_on_hull(hull, centre)
        if nearest is None:
            continue
        distance = float(np.linalg.norm(centre - nearest))
        if worst is None or distance > worst[2]:
            worst = (centre, (centre - nearest) / distance, distance)
    if worst is None:
        search.not_applicable(rule, "the loads' line of action meets the floor inside the "
                              "support polygon (a part lifts, not the whole)")
    return worst


def _nearest_on_hull(hull: np.ndarray, point: np.ndarray) -> np.ndarray | None:
    """The support polygon's boundary point nearest ``point`` when it lies outside; else
    None (``geometry.support.outside``)."""
    distance, nearest = outside(hull, point)
    return None if distance == 0.0 else nearest


def _support_candidates(search: Search, centre: np.ndarray, d: np.ndarray,
                        distance: float) -> Iterator[Candidate]:
    """Supports under the far end (along d) of the level planks reaching past c."""
    design = search.design
    direction = np.array([d[0], d[1], 0.0])
    beyond = float(centre @ d) + design.material.thickness
    reaching = []
    for plank in design.planks:
        if not level(plank) or not search.neighbours[plank.id]:
            continue
        reach = float((plank.corners @ direction).max())
        if reach > beyond:
            reaching.append((-reach, design.plank_index[plank.id], plank.id))
    if not reaching:
        search.failed(OVERHANG, "no level plank reaches past the point where the loads' "
                      "line of action meets the floor")
    for _, _, plank_id in sorted(reaching)[:SUPPORTS_TRIED]:
        plank = design.plank(plank_id)
        away = -(plank.rotation_matrix[:, :2].T @ direction)
        candidate = support_candidate(search, away, plank_id, None, 1.0, "support", OVERHANG)
        place = f"under the far end of {plank_id}"
        if candidate is None:
            search.failed(OVERHANG, f"{place}: no room")
            continue
        yield replace(candidate, place=place)


def _outrigger_candidates(search: Search, centre: np.ndarray, d: np.ndarray,
                          distance: float) -> Iterator[Candidate]:
    """Outriggers on the outer face (looking along d) of the legs at the polygon's edge."""
    design, geometry = search.design, search.geometry
    direction = np.array([d[0], d[1], 0.0])
    thickness = design.material.thickness
    contacts = [c for c in geometry.contacts if c.on_floor]
    edge = max(float(c.point @ direction) for c in contacts)
    at_edge = {c.plank for c in contacts if float(c.point @ direction) >= edge - thickness}
    floor_point = np.array([centre[0], centre[1], 0.0])
    facing_legs = 0
    for leg_id in legs(design, geometry):
        if leg_id not in at_edge:
            continue
        leg = design.plank(leg_id)
        outward = normal(leg) * (1.0 if normal(leg) @ direction >= 0 else -1.0)
        if float(outward @ direction) < FACING_COS:
            continue
        facing_legs += 1
        face = float(leg.center_array @ outward) + leg.half_extents[2]
        gap = float(floor_point @ outward) - face
        if gap <= 0.0:
            continue
        axes = leg.rotation_matrix[:, :2]
        up = int(np.argmax(np.abs(axes[2])))
        across = axes[:, 1 - up]
        bottom = float(leg.corners[:, 2].min())
        tall = float(leg.corners[:, 2].max()) - bottom
        for factor in OUTRIGGER_REACH:          # a whole millimetre longer at most
            length = math.ceil(factor * gap / float(outward @ direction) / SHOP_STEP - 1e-9) \
                * SHOP_STEP
            height = min(max(length, 4.0 * thickness), tall - OUTRIGGER_CLEARANCE * thickness)
            centre_3d = leg.center_array + outward * (leg.half_extents[2] + 0.5 * length)
            centre_3d[2] = bottom + 0.5 * height
            name = new_id(design, "outrigger")
            foot = board(name, length, height, thickness, centre_3d, outward, across)
            advice = (f"Add {name} ({size_of(foot, design)}), a foot on edge standing on "
                      f"the floor against the outer face of {leg_id}, reaching "
                      f"{amount(length / design.unit_scale)} {design.units} out from it, "
                      f"nailed to {leg_id}.")
            place = (f"on {leg_id}, reaching {amount(length / design.unit_scale)} "
                     f"{design.units} out")
            yield Candidate("outrigger", with_planks(design, (foot,)), advice, (foot,),
                            (leg_id,), ((leg_id, name),), OUTRIGGER, "", place, name)
    if not facing_legs:
        search.failed(OUTRIGGER, "no leg at the edge it tips over turns a broad face that way")
