"""Against toppling and racking by a wall: screw the design to it (contract section 2,
``anchors``).

A bookcase that a child's pull tips over is anchored to the wall behind it at the top:
the fixing holds the top back, the floor takes the rest.  Where the design has walls,
the plank to anchor is one within WALL_ANCHOR_REACH in front of a wall: one lying face
to the wall first (a back board, a cleat: screwed through its face), then one showing
the wall an edge (a top, a tall side: screwed through angle brackets, as the advice
says), the highest of each kind; the anchors go on its face or edge nearest the
wall, at its middle, or two at a quarter of its length from each end when it is longer
than ANCHOR_PAIR_FROM plank thicknesses (one near the top of an upright face).  Each is
rated ``tolerances.ANCHOR_CAPACITY`` N (one plasterboard fixing's safe load; the advice
gives the largest force one takes, for a maker choosing another fixing).

Tried when a wall stands by the design and its violations are lift-off, sliding or
failing joints (which a tie at the top can relieve of a push).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import replace

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Anchor, Design
from furncheck.plain import plain_number
from furncheck.suggest.discrete.common import (
    PARALLEL_COS,
    Candidate,
    Fix,
    Search,
    amount,
    names,
    point_of,
)

REPAIRED = ("lift-off", "sliding", "non-durable")

ANCHOR = "wall anchor"
"""The rule's name in ``tried.Trial`` values."""

UPRIGHT_COS = 0.7
"""A near face whose long side is within 45 degrees of vertical counts as upright."""


ANCHOR_PAIR_FROM = 20.0
"""A plank at least this many plank thicknesses long (240 mm of 12 mm stock) gets two
anchors, at a quarter of its length from each end; a shorter one one, at its middle."""


def wall_anchors(search: Search) -> Fix | None:
    """The first working anchors into a wall behind the design."""
    design = search.design
    if not design.walls:
        search.not_applicable(ANCHOR, "the design stands by no wall")
        return None
    if not search.repairs(ANCHOR, REPAIRED):
        return None
    fix = search.first_valid(_candidates(search))
    if fix is None:
        return None
    added = [np.asarray(a.point) / design.unit_scale
             for a in fix.design.anchors[len(design.anchors):]]
    force = max((a.size for case in fix.report.cases for a in case.anchors
                 if any(np.allclose(a.point, point) for point in added)), default=0.0)
    advice = f"{fix.advice[:-1]}; each takes at most {plain_number(force, 3)} N."
    return replace(fix, advice=advice)


def _candidates(search: Search) -> Iterator[Candidate]:
    design = search.design
    slack = design.tolerance + tol.ON_PLANK_EPS
    reach = tol.WALL_ANCHOR_REACH
    found = []
    for plank in design.planks:
        for w, wall in enumerate(design.walls):
            distances = wall.distance(plank.corners)
            nearest = float(distances.min())
            if nearest < -slack or nearest > reach:
                continue
            near = plank.corners[distances <= nearest + slack]
            facing = abs(float(plank.rotation_matrix[:, 2] @ np.asarray(wall.normal)))
            edge = facing < PARALLEL_COS    # its broad face is not the one at the wall
            found.append((edge, -float(near[:, 2].mean()), design.plank_index[plank.id],
                          plank.id, w, near))
    if not found:
        search.failed(ANCHOR, f"no plank stands within "
                      f"{amount(reach / design.unit_scale)} {design.units} of a wall")
    ranked = sorted(found, key=lambda f: f[:3])
    tried = [next(f for f in ranked if f[0] == edge) for edge in (False, True)
             if any(f[0] == edge for f in ranked)]         # the highest of each kind
    for edge, _, _, plank_id, wall, near in tried:
        plank = design.plank(plank_id)
        points = _anchor_points(plank, near, design.material.thickness)
        anchors = tuple(Anchor(plank_id, tuple(float(v) for v in p), wall,
                               tol.ANCHOR_CAPACITY,
                               float(design.walls[wall].distance(np.asarray(p))))
                        for p in points)
        where = names([point_of(p, design) for p in points])
        wall_name = "the wall" if len(design.walls) == 1 else wall_words(design, wall)
        more = bool(design.anchors)             # beside the fixings the design has
        fixings = (("another fixing" if more else "a fixing") if len(points) == 1
                   else f"{len(points)} more fixings" if more else "fixings")
        gap = max(anchor.gap for anchor in anchors)
        packed = f", packing the {amount(gap / design.unit_scale)} {design.units} gap to " \
                 f"the wall" if gap > design.tolerance and not edge else ""  # (a bracket
        # bridges it)
        beside = f" (beside the {len(design.anchors)} it has)" if more else ""
        bracket = " through angle brackets at its edge" if edge else ""
        advice = (f"Screw {plank_id} to {wall_name} at {where} with {fixings} rated "
                  f"{plain_number(tol.ANCHOR_CAPACITY, 3)} N{bracket}{beside}{packed}.")
        yield Candidate("anchor", replace(design, anchors=(*design.anchors, *anchors)),
                        advice, between=(plank_id,), trial_rule=ANCHOR,
                        place=f"{plank_id} to {wall_name} at {where}",
                        plank=f"{len(points)} {'fixing' if len(points) == 1 else 'fixings'}")


def wall_words(design: Design, wall: int) -> str:
    """'wall 0 (the one facing +x)': a design's wall by its index in ``walls`` and the
    way its face looks (its normal's largest component), for a maker who has several."""
    normal = np.asarray(design.walls[wall].normal, dtype=float)
    axis = int(np.argmax(np.abs(normal)))
    return f"wall {wall} (the one facing {'+' if normal[axis] > 0 else '-'}{'xyz'[axis]})"


def _anchor_points(plank, near: np.ndarray, thickness: float) -> list[np.ndarray]:
    """The anchor points on the plank's corners nearest the wall (a face, an edge or a
    corner): its middle, or two points a quarter of its long side from each end; on a
    long side that stands upright (a tall side's back edge), one point an eighth of its
    length below its top."""
    middle = near.mean(axis=0)
    if len(near) < 2:
        return [middle]
    spread = near - middle
    _, _, axes = np.linalg.svd(spread)
    along = axes[0] if axes[0][2] >= 0 else -axes[0]
    extent = spread @ along
    length = float(extent.max() - extent.min())
    if length < ANCHOR_PAIR_FROM * thickness:
        return [middle]
    if abs(float(along[2])) >= UPRIGHT_COS:
        return [middle + along * 0.375 * length]
    return [middle - along * 0.25 * length, middle + along * 0.25 * length]
