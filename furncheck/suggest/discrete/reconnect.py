"""Reconnect a near miss: lengthen or shorten the plank that falls short.

A leg drawn 4 mm short of the seat, a side table drawn 4 mm above the floor, a middle leg
2 mm too long (contract section 2: misses up to NEAR_MISS_FACTOR x tolerance) are slips
of the drawing.  The fix moves the end face of the plank that misses by exactly the gap:

- a missed joint, or a listed joint that does not close (face plank F, edge plank E,
  gap g; g < 0 an overlap): E's end face that looks at F moves g toward it;
- a missed ground contact (a plank standing on an end, h above the floor): its lower end
  face moves h down;
- a group floating h above the floor: the planks of the group that stand on an end and
  reach lowest (within the tolerance) get their lower end h longer;
- a plank sunk d into the floor: its lower end d shorter.

A group that floats only because such joints are missed (a shelf 8 mm short of both
sides: ``geometry.near.carried_groups``) hangs on them once they close: nothing lowers it.

A plank's other end stays where it is (its joints stay); loads and anchors on a changed
plank keep their place along it.  Every geometric violation must be one of these, and
close within the band (a plank 50 mm off is no slip).  Offered only when the continuous
search found nothing (it closes the same gaps by a line search, with an interval);
in the elastic model, where the closed design often sags, the thicker planks that
finish it (``thicker.finish``) are part of the fix.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from furncheck.design.model import Design, Plank
from furncheck.dofs import with_planks_carried
from furncheck.geometry.faces import _best_touches
from furncheck.geometry.near import carried_groups, near_band
from furncheck.suggest.discrete.common import Candidate, Fix, Search, amount, names
from furncheck.tolerances import NEAR_MISS_FACTOR


def reconnect_near_misses(search: Search) -> Fix | None:
    """The design with its near misses closed, when that (or that with thicker planks)
    is valid; else None."""
    if not search.geometry.violations:
        search.not_applicable(RECONNECT, "the design stands as drawn")
        return None
    closed = _closed(search)
    if closed is None:
        search.not_applicable(RECONNECT, "a geometric violation is not a near miss within "
                              f"{NEAR_MISS_FACTOR:g} times the tolerance")
        return None
    design, ends, joints = closed
    return search.first_valid([Candidate("reconnect", design, _advice(search.design, ends),
                                         between=tuple(ends), new_joints=joints,
                                         trial_rule=RECONNECT, place="the gaps closed",
                                         plank=names(list(ends)))])


RECONNECT = "reconnect"
"""The rule's name in ``tried.Trial`` values."""


def _closed(search: Search) -> tuple[Design, dict, tuple] | None:
    """(the closed design, {plank: [(amount m, where, local axis), ...]}, the joints it
    adds) or
    None when some geometric violation is not a near miss within the band."""
    design, geometry = search.design, search.geometry
    if not geometry.violations:
        return None
    slack, band = near_band(design)
    moves: dict[str, list[tuple[int, float, float, str]]] = {}   # axis, sign, m, where
    handled: set[tuple[str, str]] = set()
    joints = []
    for miss in geometry.near_misses:
        if len(miss.planks) == 2 and miss.bearing is not None:   # a sliver: the face plank
            face, edge = miss.planks                              # covers the whole end
            axis, sign = _side_toward(design.plank(face), design.plank(edge))
            _reach_over(moves.setdefault(face, []), axis, sign,
                        design.plank(edge).thickness - miss.bearing, edge)
            handled.add(("disconnected", miss.name))
            joints.append((face, edge))
        elif len(miss.planks) == 2:
            face, edge = miss.planks
            axis, sign = _end_toward(design.plank(edge), design.plank(face))
            moves.setdefault(edge, []).append((axis, sign, miss.distance,
                                               f"at the end toward {face}"))
            handled.add(("disconnected", miss.name))
            joints.append((face, edge))
        else:
            plank = design.plank(miss.planks[0])
            axis, sign = _lower_end(plank)
            moves.setdefault(plank.id, []).append((axis, sign, miss.distance, "at its foot"))
            handled.add(("floating", plank.id))
    carried = carried_groups(design, geometry)
    for violation in geometry.violations:
        if (violation.kind, violation.where) in handled:
            continue
        if violation.kind == "floating" and violation.where in carried:
            continue            # it hangs on the missed joints, closed here
        if violation.kind == "disconnected" and "/" in violation.where:
            a, b = (design.plank_index[p] for p in violation.where.split("/", 1))
            touch = _best_touches(design.planks, np.array([[a, b]]), slack=np.inf,
                                  keep_deep=False, bearing=0.0).get((a, b))
            if touch is None or not slack < abs(float(touch.gap)) <= band:
                return None
            face, edge = touch.face.id, touch.edge.id
            axis, sign = _end_toward(touch.edge, touch.face)
            moves.setdefault(edge, []).append((axis, sign, float(touch.gap),
                                               f"at the end toward {face}"))
            joints.append((face, edge))
        elif violation.kind == "floating":
            group = [design.plank(p) for p in violation.where.split(",")]
            height = min(float(p.corners[:, 2].min()) for p in group)
            if not slack < height <= band:
                return None
            feet = [p for p in group if float(p.corners[:, 2].min()) <= height + slack
                    and _standing_on_end(p)]
            if not feet:
                return None
            for plank in feet:
                axis, sign = _lower_end(plank)
                moves.setdefault(plank.id, []).append((axis, sign, height, "at its foot"))
        elif violation.kind == "penetration":
            plank = design.plank(violation.where)
            depth = -float(plank.corners[:, 2].min())
            if not slack < depth <= band or not _standing_on_end(plank):
                return None
            axis, sign = _lower_end(plank)
            moves.setdefault(plank.id, []).append((axis, sign, -depth, "at its foot"))
        else:
            return None
    edited = with_planks_carried(design, tuple(
        _extended(p, moves[p.id]) if p.id in moves else p for p in design.planks))
    ends = {plank: [(amount_m, where, axis) for axis, _, amount_m, where in changes]
            for plank, changes in moves.items()}
    return edited, ends, tuple(joints)


def _standing_on_end(plank: Plank) -> bool:
    """Whether one of the plank's narrow faces looks (nearly) straight down."""
    axis, sign = _lower_end(plank)
    return float(plank.rotation_matrix[2, axis]) * sign <= -0.95


def _lower_end(plank: Plank) -> tuple[int, int]:
    """(local axis 0/1, sign) of the plank's narrow face that looks most downward."""
    z = plank.rotation_matrix[2, :2]
    axis = int(np.argmax(np.abs(z)))
    return axis, (-1 if z[axis] > 0 else 1)


def _end_toward(edge: Plank, face: Plank) -> tuple[int, int]:
    """(local axis, sign) of the edge plank's narrow face that looks at the face plank's
    broad face (its outward normal most against the face's normal toward it)."""
    toward = face.rotation_matrix[:, 2]
    if float((edge.center_array - face.center_array) @ toward) < 0:
        toward = -toward
    best = None
    for axis in (0, 1):
        for sign in (1, -1):
            facing = float(edge.rotation_matrix[:, axis] @ toward) * sign
            if best is None or facing < best[0]:
                best = (facing, axis, sign)
    return best[1], best[2]


def _side_toward(face: Plank, edge: Plank) -> tuple[int, int]:
    """(local axis, sign) of the face plank's side that a sliver of the edge plank's end
    lies under: across the band, the face's in-plane axis nearest the edge plank's
    thickness normal, on the side of the edge plank's centre."""
    across = edge.rotation_matrix[:, 2]
    axis = int(np.argmax([abs(float(face.rotation_matrix[:, k] @ across)) for k in (0, 1)]))
    offset = float(face.rotation_matrix[:, axis] @ (edge.center_array - face.center_array))
    return axis, 1 if offset > 0 else -1


def _reach_over(moves: list, axis: int, sign: int, amount_m: float, edge: str) -> None:
    """The face plank's end (axis, sign) moved out by ``amount_m`` to cover ``edge``'s end:
    the larger move where another edge plank's sliver already moves that end (two legs
    under one end of a top), both named."""
    for k, (a, s, other, where) in enumerate(moves):
        if (a, s) == (axis, sign):
            moves[k] = (a, s, max(other, amount_m), f"{where} and {edge}")
            return
    moves.append((axis, sign, amount_m, f"at the {'end' if axis == 0 else 'side'} over {edge}"))


def _extended(plank: Plank, changes: list[tuple[int, int, float, str]]) -> Plank:
    """The plank with each end face (axis, sign) moved out by its amount (m)."""
    sizes = [plank.length, plank.width]
    centre = plank.center_array.copy()
    for axis, sign, amount_m, _ in changes:
        sizes[axis] += amount_m
        centre = centre + plank.rotation_matrix[:, axis] * sign * 0.5 * amount_m
    return replace(plank, length=float(sizes[0]), width=float(sizes[1]),
                   center=tuple(float(v) for v in centre))


def _advice(design: Design, ends: dict) -> str:
    """'Lengthen leg_l by 8 mm (4 mm at the end toward seat and 4 mm at its foot).' or
    'Lengthen leg_l by 4 mm at its foot.'"""
    scale, unit = design.unit_scale, design.units
    phrases = []
    for plank, changes in ends.items():
        total = sum(a for a, _, _ in changes)
        across = all(axis == 1 for _, _, axis in changes)   # its width (a sliver's side)
        verb = ("widen" if total >= 0 else "narrow") if across else \
            ("lengthen" if total >= 0 else "shorten")
        size = f"{amount(abs(total) / scale)} {unit}"
        if len(changes) == 1:
            phrases.append(f"{verb} {plank} by {size} {changes[0][1]}")
            continue
        detail = names([f"{amount(abs(a) / scale)} {unit} {where}" for a, where, _ in changes])
        phrases.append(f"{verb} {plank} by {size} ({detail})")
    sentence = names(phrases)
    return f"{sentence[0].upper()}{sentence[1:]}."
