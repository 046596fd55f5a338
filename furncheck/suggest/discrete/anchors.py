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
from furncheck.design.model import Anchor, Design, Wall
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
from furncheck.suggest.symmetry import mirror_planes

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
    # a maker fixes a symmetric piece symmetrically: each plank with its mirror images
    # just before it alone, in the rule's order of planks (``Candidate.preferred``: of
    # the two finished with as much thicker board, the symmetric one)
    fix = search.first_valid(candidate for pair in _candidates(search) for candidate in pair
                             if candidate is not None)
    if fix is None:
        return None
    return replace(fix, advice=f"{fix.advice[:-1]}; {_largest_forces(fix, design)}.")


def _largest_forces(fix: Fix, design: Design) -> str:
    """Words for the largest force an added fixing takes, in any case, and where the
    design had fixings, the largest one of those takes then ('each takes at most 100
    N' read as if every fixing did, where the old ones still took 142 N)."""
    def largest(added: bool) -> float:
        return max((a.size for case in fix.report.cases for a in case.anchors
                    if (a.index >= len(design.anchors)) is added), default=0.0)

    new = f"at most {plain_number(largest(True), 3)} N"
    if not design.anchors:
        return f"each takes {new}"
    return f"each added fixing takes {new}, each of the {len(design.anchors)} already there " \
           f"at most {plain_number(largest(False), 3)} N"


def _candidates(search: Search) -> Iterator[tuple[Candidate | None, Candidate]]:
    """Per plank to anchor (the highest of each kind): anchors on it and its mirror
    images (None where it has none by the same wall), and anchors on it alone."""
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
    planes = mirror_planes(design)
    for edge, _, _, plank_id, wall, near in tried:
        points = _anchor_points(design.plank(plank_id), near, design.material.thickness)
        points = [_onto_wall(p, design.walls[wall], slack) for p in points]
        fixed = [(plank_id, points)]
        images = _mirror_images(design, planes, plank_id, points, wall)
        yield (replace(_candidate(search, fixed + images, wall, edge), preferred=True)
               if images else None, _candidate(search, fixed, wall, edge))


def _candidate(search: Search, fixed: list[tuple[str, list[np.ndarray]]], wall: int,
               edge: bool) -> Candidate:
    """The design with anchors at each (plank, its points) of ``fixed`` into ``wall`` and
    its advice (``edge``: the planks show the wall an edge, screwed through brackets)."""
    design = search.design
    anchors = tuple(Anchor(plank_id, tuple(float(v) for v in p), wall, tol.ANCHOR_CAPACITY,
                           float(design.walls[wall].distance(np.asarray(p))))
                    for plank_id, points in fixed for p in points)
    planks = [plank_id for plank_id, _ in fixed]
    count = len(anchors)
    where = names([point_of(np.asarray(a.point), design) for a in anchors])
    wall_name = "the wall" if len(design.walls) == 1 else wall_words(design, wall)
    more = bool(design.anchors)             # beside the fixings the design has
    fixings = (("another fixing" if more else "a fixing") if count == 1
               else f"{count} more fixings" if more else "fixings")
    gap = max(anchor.gap for anchor in anchors)
    packed = f", packing the {amount(gap / design.unit_scale)} {design.units} gap to " \
             f"the wall" if gap > design.tolerance and not edge else ""  # (a bracket
    # bridges it)
    beside = f" (beside the {len(design.anchors)} already there)" if more else ""
    bracket = "" if not edge else " through angle brackets at its edge" if len(planks) == 1 \
        else " through angle brackets at their edges"
    advice = (f"Screw {names(planks)} to {wall_name} at {where} with {fixings} rated "
              f"{plain_number(tol.ANCHOR_CAPACITY, 3)} N{bracket}{beside}{packed}.")
    return Candidate("anchor", replace(design, anchors=(*design.anchors, *anchors)),
                     advice, between=tuple(planks), trial_rule=ANCHOR,
                     place=f"{names(planks)} to {wall_name} at {where}",
                     plank=f"{count} {'fixing' if count == 1 else 'fixings'}")


def _onto_wall(point: np.ndarray, wall: Wall, slack: float) -> np.ndarray:
    """``point`` moved onto the wall's plane where it lies within ``slack`` of it (a
    corner drawn a round-off into or off the wall: the fixing is at the wall, and the
    advice should not read y = -0.00011), else as it is (a gap to pack)."""
    distance = float(wall.distance(point))
    return point - distance * np.asarray(wall.normal) if abs(distance) <= slack else point


def _mirror_images(design: Design, planes, plank_id: str, points: list[np.ndarray],
                   wall: int) -> list[tuple[str, list[np.ndarray]]]:
    """The mirror images of ``plank_id`` (``symmetry.mirror_planes``, every plane and
    their combinations: the four legs of a table) with the mirrored anchor points,
    where those lie as far from ``wall`` as the originals (a mirror plane along the wall;
    one across it would put them off the wall)."""
    reach = {plank_id: [np.asarray(p, dtype=float) for p in points]}
    frontier = [plank_id]
    slack = design.tolerance + tol.ON_PLANK_EPS
    distances = design.walls[wall].distance(np.asarray(points))
    while frontier:
        current = frontier.pop()
        for plane in planes:
            image = plane.partner.get(current)
            if image is None or image in reach:
                continue
            mirrored = [p.copy() for p in reach[current]]
            for p in mirrored:
                p[plane.axis] = 2.0 * plane.offset - p[plane.axis]
            if np.abs(design.walls[wall].distance(np.asarray(mirrored))
                      - distances).max() > slack:
                continue
            reach[image] = [_onto_wall(_on(design.plank(image), p), design.walls[wall],
                                       slack) for p in mirrored]
            frontier.append(image)
    return [(image, reach[image]) for image in sorted(reach, key=design.plank_index.get)
            if image != plank_id]


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


def _on(plank, point: np.ndarray) -> np.ndarray:
    """``point`` moved onto ``plank``'s box where it lies outside (a mirror image matches
    its plank within a few tolerances; an anchor must lie on its plank within one)."""
    local = plank.to_local(point)
    if np.all(np.abs(local) <= plank.half_extents):
        return point
    local = np.clip(local, -plank.half_extents, plank.half_extents)
    return plank.center_array + plank.rotation_matrix @ local
