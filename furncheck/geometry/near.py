"""Near misses (contract section 2): planks that come close to touching but do not.

Where an auto joint or a ground contact would be, a gap or an overlap of more than the
design's tolerance but at most ``NEAR_MISS_FACTOR`` x tolerance (10 mm at the default
0.5 mm) is a slip of the drawing, not a design (a leg 4 mm short): it is reported with its
size, never silently left out.  Farther apart, planks are taken to be apart on purpose.

*A missed joint* (designs with auto-detected joints only: a file that lists its joints
says which planks are joined, and a listed joint that does not close is ``disconnected``
already): two planks not joined, where a narrow (end) face of one faces a broad face of
the other as a joint's would (tilted at most ``JOINT_MAX_TILT_DEG``, the end face's
projection overlapping the broad face, the end's plank on the face's outer side) and the
nearest point of the part of the end face over the face stands off the face (a gap) or
cuts into it (an overlap) by more than the tolerance and at most the band.  Reported as
``disconnected``, named as the joint would be (face/edge): ``seat/leg_l: 4 mm gap between
the end of leg_l and the face of seat ...``.  Two parallel shelves (face to face), or an
end face beside a plank rather than over its face, are no joint and so no near miss.

*A missed ground contact*: a plank of a group that stands on the ground elsewhere,
touching the ground nowhere itself, standing on an end (the floor taken as a face plank:
one of its narrow faces within ``JOINT_MAX_TILT_DEG`` of facing straight down), whose
lowest corner is more than the tolerance and at most the band above the floor.  Reported
as ``floating``: ``leg_l: 4 mm above the floor ...``.  A plank lying flat (a bottom shelf
5 mm above the floor in a carcass) is not a near miss; a group touching the ground nowhere
is ``floating`` as a whole (with its height) and its planks are not reported one by one.
"""

from __future__ import annotations

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design
from furncheck.geometry.boxes import meeting_pairs
from furncheck.geometry.faces import _bearing, _bears, _best_touches, _bounding_boxes, _Touch
from furncheck.geometry.model import (
    _COS_MAX_TILT,
    _GEOMETRY_EPS,
    Contact,
    Geometry,
    Joint,
    NearMiss,
)
from furncheck.plain import plain_compared, plain_length, plain_number
from furncheck.result import Violation


def near_band(design: Design) -> tuple[float, float]:
    """(tolerance, band) in m, each with the numeric slack: a near miss is farther than
    the first and at most the second."""
    return (design.tolerance + _GEOMETRY_EPS,
            tol.NEAR_MISS_FACTOR * design.tolerance + _GEOMETRY_EPS)


def near_misses(design: Design, joints: list[Joint], contacts: list[Contact],
                components: tuple[tuple[int, ...], ...],
                grounded: tuple[bool, ...]) -> list[NearMiss]:
    """The missed joints (plank pairs in order) and then the missed ground contacts (planks
    in order) of a design with these joints, contacts and components."""
    return missed_joints(design, joints) + missed_ground(design, contacts, components,
                                                         grounded)


def missed_joints(design: Design, joints: list[Joint]) -> list[NearMiss]:
    """Plank pairs without a joint whose end face and face are a near miss (module doc);
    none when the design lists its joints."""
    slack, band = near_band(design)
    if design.joints is not None or len(design.planks) < 2:
        return []
    band = max(band, slack)       # (with no band, a sliver within the tolerance all the same)
    pairs = meeting_pairs(*_bounding_boxes(design.planks), band)
    index, n = design.plank_index, len(design.planks)
    jointed = np.array([min(index[joint.face], index[joint.edge]) * n
                        + max(index[joint.face], index[joint.edge]) for joint in joints],
                       dtype=int)
    pairs = pairs[~np.isin(pairs[:, 0] * n + pairs[:, 1], jointed)]
    best = _best_touches(design.planks, pairs, band, keep_deep=False, bearing=0.0)
    missed = []
    for i, j in pairs.tolist():
        touch = best.get((i, j))
        if touch is not None and abs(touch.gap) > slack:
            missed.append(NearMiss((touch.face.id, touch.edge.id), float(touch.gap)))
        elif touch is not None and not _bears(touch):
            missed.append(sliver(touch))
    return missed


def sliver(touch: _Touch) -> NearMiss:
    """The near miss of an end face that lies on a face over a band too narrow for nails
    (``faces._bears``)."""
    return NearMiss((touch.face.id, touch.edge.id), float(touch.gap), _bearing(touch))


def missed_ground(design: Design, contacts: list[Contact],
                  components: tuple[tuple[int, ...], ...], grounded: tuple[bool, ...],
                  only: list[int] | None = None) -> list[NearMiss]:
    """Planks of grounded groups that stand on an end just above the floor (module doc);
    ``only``: look at these plank indices alone."""
    slack, band = near_band(design)
    if band <= slack:
        return []
    return [NearMiss((design.planks[i].id,), height)
            for i, height in _standing_above(design, contacts, components, grounded, band,
                                             only)]


def hovering_ends(design: Design, geometry: Geometry, reach: float) -> list[tuple[int, float]]:
    """(plank index, height m) of the planks of grounded groups that stand on an end above
    the floor, farther than the tolerance and at most ``reach`` (m): a leg drawn short,
    near miss or not (``suggest.margins`` offers to bring the lowest ones down to the
    floor when the design topples)."""
    slack, _ = near_band(design)
    if reach <= slack:
        return []
    return _standing_above(design, geometry.contacts, geometry.components, geometry.grounded,
                           reach)


def _standing_above(design: Design, contacts: list[Contact],
                    components: tuple[tuple[int, ...], ...], grounded: tuple[bool, ...],
                    reach: float, only: list[int] | None = None) -> list[tuple[int, float]]:
    """(plank index, height m), in plank order, of the planks of grounded groups (``only``:
    among these) that touch the floor nowhere and stand on an end (one of their narrow
    faces within JOINT_MAX_TILT_DEG of facing straight down), their lowest corner more
    than the tolerance and at most ``reach`` above the floor."""
    slack, _ = near_band(design)
    touching = {contact.plank for contact in contacts if contact.on is None}
    candidates = sorted(i for component, on_ground in zip(components, grounded)
                        if on_ground for i in component)
    if only is not None:
        candidates = sorted(set(candidates) & set(only))
    found = []
    for i in candidates:
        plank = design.planks[i]
        if plank.id in touching:
            continue
        axes = plank.rotation_matrix
        standing = max(abs(axes[2, 0]), abs(axes[2, 1])) >= _COS_MAX_TILT
        height = float(plank.corners[:, 2].min())
        if standing and slack < height <= reach:
            found.append((i, height))
    return found


def carried_groups(design: Design, geometry: Geometry) -> set[str]:
    """The floating groups (as a ``floating`` violation names them: plank ids joined by
    ',') that only float because joints are missed: the ``disconnected`` pairs among
    ``violations`` (a near miss, or a listed joint that does not close) join them to a
    group that stands on the ground.  Such a group hangs on those joints; closing them
    carries it (a shelf 8 mm short of both sides is no plank to lower to the floor)."""
    components, grounded = geometry.components, geometry.grounded
    parent = list(range(len(components)))

    def root(c: int) -> int:
        while parent[c] != c:
            parent[c] = parent[parent[c]]
            c = parent[c]
        return c

    of = {i: c for c, component in enumerate(components) for i in component}
    for violation in geometry.violations:
        if violation.kind == "disconnected" and "/" in violation.where:
            a, b = (of[design.plank_index[p]] for p in violation.where.split("/", 1))
            parent[root(a)] = root(b)
    standing = {root(c) for c, is_grounded in enumerate(grounded) if is_grounded}
    return {",".join(design.planks[i].id for i in component)
            for c, (component, is_grounded) in enumerate(zip(components, grounded))
            if not is_grounded and root(c) in standing}


def near_miss_violation(design: Design, miss: NearMiss) -> Violation:
    """The violation of a near miss: ``disconnected`` for a joint, ``floating`` for the
    ground, its size in the design's unit first."""
    def length(value_m: float) -> str:
        return plain_length(value_m, design.unit_scale, design.units)

    allowed = length(design.tolerance)
    if len(miss.planks) == 1:
        plank = miss.planks[0]
        return Violation(
            "floating", plank, None,
            f"{length(miss.distance)} above the floor: its end does not reach the ground "
            f"that the rest of the design stands on (a ground contact needs {allowed} or "
            f"less, the tolerance)", design.line_of(f"planks[{design.plank_index[plank]}]"))
    face, edge = miss.planks
    if miss.bearing is not None:
        return Violation("disconnected", miss.name, None, sliver_message(design, miss),
                         design.line_of(f"planks[{design.plank_index[edge]}]"))
    if miss.distance > 0:
        what = (f"{length(miss.distance)} gap between the end of {edge} and the face of "
                f"{face}: no joint forms (a joint needs {allowed} or less, the tolerance)")
    else:
        what = (f"{length(-miss.distance)} overlap: the end of {edge} cuts into the face of "
                f"{face}: no joint forms (a joint allows {allowed} at most, the tolerance)")
    return Violation("disconnected", miss.name, None, what,
                     design.line_of(f"planks[{design.plank_index[edge]}]"))


def sliver_message(design: Design, miss: NearMiss) -> str:
    """Why an end face lying on a face forms no nail joint: the band it bears on is too
    narrow (``tolerances.MIN_BEARING_SHARE``)."""
    face, edge = miss.planks
    thickness = design.plank(edge).thickness
    needed = tol.MIN_BEARING_SHARE * thickness
    scale, unit = design.unit_scale, design.units
    has, needs = plain_compared(miss.bearing / scale, needed / scale, 3)
    share = "half" if tol.MIN_BEARING_SHARE == 0.5 else \
        f"{plain_number(100.0 * tol.MIN_BEARING_SHARE, 3)} % of"
    return (f"the end of {edge} bears on only {has} {unit} of the face of {face} across its "
            f"{plain_length(thickness, scale, unit, 3)} thickness: no joint forms (nails need "
            f"at least {needs} {unit}, {share} the thickness)")
