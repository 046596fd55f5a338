"""Discrete suggestions (paper section 6.5): add a support plank.

When a joint is not durable, a support is added between two nearly parallel planks P_i
and P_j that a third plank P_k joins, where the failing joint is P_k's joint with one of
them -- a shelf nailed to a post gets a support standing on the base, a chair's seat a
post down to the stretcher.  Under a level P_i the floor serves as P_j too: a leg under a
ledge nailed to the outside of a bookcase.  The support stands across the gap between the
faces of P_i and P_j that face each other, its ends nailed to both (it becomes the edge
plank of two new joints; on the floor it just stands), its broad face turned toward P_k.
Candidate places are the far side of the overlap of P_i and P_j from P_k (a triangle with
the joint that fails: the woodworker's bracket) and its middle.  A plank that sags or is
overstressed (elastic model) is P_i itself: the support goes under the middle of its
overlap with a parallel plank P_j that shares a neighbour P_k with it (a divider between
a sagging shelf and the shelf below), or the floor.  Each candidate design is checked in
full -- valid in every case, the new plank joined to P_i and P_j only, no plank cutting
another -- and only working supports are suggested; a candidate that does not come near
every failing joint and plank (one joint from the planks it is nailed to, ``_reach``) is
not built at all.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from furncheck.check import check_design, is_valid
from furncheck.design.model import Design, JointSpec, Plank
from furncheck.dofs import euler_degrees
from furncheck.geometry import Geometry, analyze, interpenetrations
from furncheck.result import DesignReport
from furncheck.suggest.tried import FAILED, FOUND, NOT_APPLICABLE, Trial

PARALLEL_COS = 0.95
"""P_i and P_j count as parallel when their face normals' cosine is at least this."""

PLACES = (("far", 1.0), ("middle", 0.0))
"""Candidate places across the overlap, away from P_k: its far edge (1) and middle (0)."""

MIN_OVERLAP = 3.0
"""The overlap of P_i and P_j must be at least this many plank thicknesses wide (in
both directions) to hold a support."""

MAX_DISCRETE = 1
"""At most this many support planks are suggested (the paper lists one or two): the first
that works, far side before middle."""


@dataclass(frozen=True)
class Support:
    """A working support plank: the plank, between which planks, where, the design with
    it and that design's validation."""

    plank: Plank
    between: tuple[str, ...]     # (P_i, P_j or 'the floor'); a rail: (bent plank, its ends)
    place: str
    design: Design
    report: DesignReport
    restores: tuple[str, ...] = ("durability",)


def support_planks(design: Design, geometry: Geometry, report: DesignReport,
                   limit: int = MAX_DISCRETE, trials: list[Trial] | None = None) -> list[Support]:
    """Working support planks for the non-durable joints and the sagging or overstressed
    planks of ``report`` (see the module docstring), at most ``limit``, in the order
    tried: failing joints and planks as reported, then P_k, P_i, P_j, places.  Every
    candidate built or ruled out is appended to ``trials`` (``tried.Trial``)."""
    trials = [] if trials is None else trials
    unrepaired = sorted({v.kind for v in report.violations} - set(_REPAIRED))
    if geometry.violations or not report.violations or unrepaired:
        if report.violations:
            trials.append(Trial(SUPPORT, "", NOT_APPLICABLE,
                                "the geometry is repaired first" if geometry.violations
                                else f"it does not repair {' or '.join(unrepaired)}"))
        return []
    restores = tuple(sorted({_REPAIRED[v.kind] for v in report.violations}))
    neighbours: dict[str, list[str]] = {p.id: [] for p in design.planks}
    for joint in geometry.joints:
        a, b = joint.planks
        neighbours[a].append(b)
        neighbours[b].append(a)
    found: list[Support] = []
    tried: set[tuple] = set()
    failing = dict.fromkeys(_place(design, v.where) for v in report.violations)
    reaches = _reach(failing, neighbours)
    for where in failing:
        if "/" in where:                                 # a joint k/i: brackets and posts
            pair = where.split("/", 1)
            placements = [(k, i, PLACES) for k, i in (pair, pair[::-1])]
        else:                                            # a bent plank i
            for depth in STIFFENER_DEPTHS:
                key = (where, "stiffener")
                if key in tried or len(found) >= limit:
                    break
                support = _try_stiffener(design, geometry, where, neighbours[where], depth,
                                         reaches, trials)
                if support is not None:
                    tried.add(key)
                    found.append(replace(support, restores=restores))
            placements = [(k, where, PLACES[1:]) for k in neighbours[where]]
        out_of_reach = []
        for k, i, places in placements:
            partners = [j for j in neighbours[k]
                        if j != i and _parallel(design.plank(i), design.plank(j))]
            if _level(design.plank(i)):
                partners.append(None)                    # the floor, under a level plank
            for j in partners:
                for place, position in places:
                    key = (*sorted((i, j or "")), place)
                    if key in tried or len(found) >= limit:
                        continue
                    if not reaches({i, j}):
                        out_of_reach.append(f"{i} and {j or 'the floor'}")
                        continue
                    tried.add(key)
                    support = _try(design, geometry, k, i, j, place, position, trials, where)
                    if support is not None:
                        found.append(replace(support, restores=restores))
        if out_of_reach and len(found) < limit:
            trials.append(Trial(SUPPORT, where, FAILED,
                                f"one between {_listed(sorted(set(out_of_reach)))} would not "
                                f"come near every failing joint and plank"))
    return found


SUPPORT = "support plank"
"""The name of the support-plank rule in ``Trial`` values."""

STIFFENER = "stiffening rail"
"""The name of the stiffening-rail rule in ``Trial`` values."""


_PLACE_WORDS = {"far": "at the far side", "middle": "in the middle"}
"""``PLACES`` in a ``Trial``'s reason."""


def _listed(items: list[str], most: int = 3) -> str:
    """'a, b, c' or 'a, b, c and 2 more'."""
    head = ", ".join(items[:most])
    return head if len(items) <= most else f"{head} and {len(items) - most} more"


def _reach(failing, neighbours: dict[str, list[str]]) -> Callable[[set], bool]:
    """Whether an added plank nailed to ``ends`` (a set of plank ids) comes near every
    failing place (``failing``: violations' ``where``, a joint 'a/b' or a plank): each
    failing joint and plank is one of ``ends`` or jointed to one (``neighbours``).  A
    support relieves what it is nailed to and the planks those carry (a support under a
    cantilevered shelf unloads its post too, a leg under a table top its legs), not a
    shelf two joints away; so a candidate that does not come near every failing place is
    not built and checked (a bookcase whose shelves all sag gets no support tried, at
    once instead of after a full check of each)."""
    joints = [set(where.split("/", 1)) for where in failing if "/" in where]
    planks = [{where} for where in failing if "/" not in where]

    def reaches(ends: set) -> bool:
        near = set(ends)
        for end in ends:
            near.update(neighbours.get(end, ()))
        return all(place & near for place in (*joints, *planks))
    return reaches


def _place(design: Design, where: str) -> str:
    """A violation's place as the discrete fixes take it: a joint k/i, a plank i, and for
    an anchor over its capacity (``anchors[n]``) the plank it holds (a support under that
    plank takes load off the anchor)."""
    if where.startswith("anchors["):
        return design.anchors[int(where[len("anchors["):-1])].plank
    return where


_REPAIRED = {"non-durable": "durability", "sagging": "stiffness", "overstressed": "strength"}
"""The violations a support plank can repair, and what it restores."""

STIFFENER_DEPTHS = (4.0, 6.0, 8.0)
"""Depths of a stiffening rail tried under a bent plank, in plank thicknesses (48, 72 and
96 mm for 12 mm stock): the shallowest that works is suggested."""


def _try_stiffener(design: Design, geometry: Geometry, i: str, neighbours: list[str],
                   depth: float, reaches: Callable[[set], bool],
                   trials: list[Trial]) -> Support | None:
    """A rail on edge under one long edge of the level plank i (a shelf's front lip), or
    under its middle, between the two parallel planks that hold i's ends, nailed to i and
    to both: the woodworker's fix for a sagging shelf.  (A lip at one edge carries that
    edge; the beam model's shelf, whose section does not bend across its width, then
    twists about its axis: where that is too much, the rail under the middle does it.)
    None when i is not level, is not held at both ends by parallel planks, or the rail
    does not work (checked as ``_try`` does), or it would not reach every failing place
    (``reaches``, see ``_reach``).  What it tried is appended to ``trials``."""
    shelf = design.plank(i)
    if not _level(shelf):
        trials.append(Trial(STIFFENER, i, NOT_APPLICABLE, f"{i} is not level"))
        return None
    from furncheck.statics.beams import beam_frame, beam_length_width

    frame = beam_frame(shelf)
    axis = frame[:, 0]
    ends = []
    for k in neighbours:
        other = design.plank(k)
        normal = other.rotation_matrix[:, 2]
        if abs(float(normal @ axis)) >= PARALLEL_COS:
            ends.append((float((other.center_array - shelf.center_array) @ axis), other))
    below = [e for e in ends if e[0] < 0]
    above = [e for e in ends if e[0] > 0]
    if not below or not above:
        trials.append(Trial(STIFFENER, i, NOT_APPLICABLE,
                            f"{i} is not held at both ends by parallel planks"))
        return None
    (s_low, low), (s_high, high) = max(below, key=lambda e: e[0]), min(above, key=lambda e: e[0])
    if not reaches({i, low.id, high.id}):
        trials.append(Trial(STIFFENER, i, FAILED, f"a rail under {i} would not come near "
                                                  f"every failing joint and plank"))
        return None
    start = s_low + low.half_extents[2]
    stop = s_high - high.half_extents[2]
    thickness = design.material.thickness
    rail_depth = depth * thickness
    length, width = beam_length_width(shelf)
    down = -frame[:, 2] if frame[2, 2] > 0 else frame[:, 2]
    taken = {p.id for p in design.planks}
    name = next(f"rail-{n}" for n in range(1, len(taken) + 2) if f"rail-{n}" not in taken)
    for side, edge in ((-1.0, 1.0), (1.0, 1.0), (1.0, 0.0)):  # a long edge of i, its middle
        across = frame[:, 1] * side
        centre = (shelf.center_array + axis * 0.5 * (start + stop)
                  + across * edge * (0.5 * width - 0.5 * thickness)
                  + down * (shelf.half_extents[2] + 0.5 * rail_depth))
        rotation = euler_degrees(np.column_stack([axis, np.cross(across, axis), across]),
                                 (0.0, 0.0, 0.0))
        rail = Plank(name, float(stop - start), float(rail_depth), thickness,
                     tuple(float(v) for v in centre), tuple(float(v) for v in rotation))
        why: list = []
        support = _checked(design, geometry, rail, (i, low.id, high.id), why)
        if support is not None:
            trials.append(Trial(STIFFENER, i, FOUND, plank=name))
            return Support(rail, (i, low.id, high.id), f"under {i}", support[0], support[1])
    trials.append(Trial(STIFFENER, i, FAILED,
                        f"{_length(rail_depth, design)} deep, from {low.id} to {high.id}, under "
                        f"either long edge or the middle: {why[0]}", name, why[1]))
    return None


def _length(value: float, design: Design) -> str:
    """A length (m) in the design's unit, for a reason: '48 mm'."""
    return f"{float(f'{value / design.unit_scale:.4g}'):g} {design.units}"


def _checked(design: Design, geometry: Geometry, plank: Plank, ends: tuple[str, ...],
             why: list | None = None) -> tuple[Design, DesignReport] | None:
    """(the design with ``plank`` added, nailed to ``ends``, and its report) when it is
    valid, the new plank is joined to exactly ``ends`` and cuts into nothing; else None,
    and ``why`` (when given) gets [the reason in words, the design with the plank when
    its checks failed, else None]."""
    why = [] if why is None else why
    joints = None if design.joints is None else \
        (*design.joints, *(JointSpec((end, plank.id)) for end in ends))
    edited = replace(design, planks=(*design.planks, plank), joints=joints)
    after = analyze(edited)
    new = {frozenset(joint.planks) for joint in after.joints if plank.id in joint.planks}
    wanted = {frozenset((end, plank.id)) for end in ends}
    if after.violations:
        first = after.violations[0]
        why[:] = [f"with it, {first.kind}: {first.where}: {first.message}", None]
        return None
    if new != wanted:
        others = sorted({p for pair in new - wanted for p in pair} - {plank.id})
        why[:] = [f"it would also meet {', '.join(others)}" if others
                  else "it would not be nailed to every plank it spans", None]
        return None
    cuts = interpenetrations(edited)
    if len(after.joints) != len(geometry.joints) + len(ends) or cuts:
        crossed = sorted({p for pair in cuts for p in pair[:2]} - {plank.id})
        why[:] = [f"it would cut into {', '.join(crossed)}" if crossed
                  else "it would change the design's other joints", None]
        return None
    if not is_valid(edited, after):      # stops at the first case that fails
        why[:] = ["the design with it is still not valid", edited]
        return None
    return edited, check_design(edited, after)      # the winner's report, solved once more


def _level(plank: Plank) -> bool:
    """Whether the plank lies level (its broad faces horizontal)."""
    return abs(float(plank.rotation_matrix[2, 2])) >= PARALLEL_COS


def _parallel(a: Plank, b: Plank) -> bool:
    return abs(float(a.rotation_matrix[:, 2] @ b.rotation_matrix[:, 2])) >= PARALLEL_COS


def _try(design: Design, geometry: Geometry, k: str, i: str, j: str | None, place: str,
         position: float, trials: list[Trial], target: str) -> Support | None:
    """The design with a support between i and j (None: the floor) at ``position`` (1 far
    side, 0 middle) of their overlap, away from k; None when it does not fit or does not
    work.  The attempt, for ``target`` (the failing joint or plank), is appended to
    ``trials``."""
    other = None if j is None else design.plank(j)
    plank = _support(design, design.plank(k), design.plank(i), other, position)
    between = f"between {i} and {j or 'the floor'} {_PLACE_WORDS.get(place, place)}"
    if plank is None:
        trials.append(Trial(SUPPORT, target, FAILED,
                            f"{between}: no room (a gap no wider than a plank, or an overlap "
                            f"narrower than {MIN_OVERLAP:g} plank thicknesses)"))
        return None
    ends = (i,) if j is None else (i, j)
    why: list = []
    checked = _checked(design, geometry, plank, ends, why)
    if checked is None:
        trials.append(Trial(SUPPORT, target, FAILED, f"{between}: {why[0]}", plank.id, why[1]))
        return None
    trials.append(Trial(SUPPORT, target, FOUND, plank=plank.id))
    return Support(plank, (i, j or "the floor"), place, *checked)


def _support(design: Design, k: Plank, i: Plank, j: Plank | None,
             position: float) -> Plank | None:
    """The support plank between the facing broad faces of i and j, or between i's
    underside and the floor (j None); None if they do not face each other over an
    overlap wide enough."""
    normal = i.rotation_matrix[:, 2]
    if j is None:
        normal = -normal if normal[2] > 0 else normal                 # down, to the floor
        gap = float(i.corners[:, 2].min())
    else:
        offset = float((j.center_array - i.center_array) @ normal)
        if offset < 0:
            normal, offset = -normal, -offset
        gap = offset - i.half_extents[2] - j.half_extents[2]
    thickness = design.material.thickness
    if gap <= thickness:
        return None
    axes = i.rotation_matrix[:, :2]                                   # in-plane x, y of i
    low, high = -i.half_extents[:2], i.half_extents[:2].copy()
    if j is not None:
        corners_j = (j.corners - i.center_array) @ axes               # j seen in i's plane
        low = np.maximum(low, corners_j.min(axis=0))
        high = np.minimum(high, corners_j.max(axis=0))
    if np.any(high - low < MIN_OVERLAP * thickness):
        return None
    away = (k.center_array - i.center_array) @ axes                   # where k stands
    along = int(np.argmax(np.abs(away)))                              # axis away from k
    sign = -1.0 if away[along] > 0 else 1.0
    middle = 0.5 * (low + high)
    half_span = 0.5 * (high[along] - low[along]) - 0.5 * thickness
    spot = middle.copy()
    spot[along] += sign * position * half_span
    across = 1 - along
    width = float(high[across] - low[across])
    centre = i.center_array + axes @ spot + normal * (i.half_extents[2] + 0.5 * gap)
    x_axis = normal                                                   # its length spans the gap
    z_axis = axes[:, along] * sign                                    # its face looks at k
    y_axis = np.cross(z_axis, x_axis)
    rotation = euler_degrees(np.column_stack([x_axis, y_axis, z_axis]), (0.0, 0.0, 0.0))
    taken = {p.id for p in design.planks}
    name = next(f"support-{n}" for n in range(1, len(taken) + 2) if f"support-{n}" not in taken)
    return Plank(name, float(gap), width, thickness, tuple(float(v) for v in centre),
                 tuple(float(v) for v in rotation))
