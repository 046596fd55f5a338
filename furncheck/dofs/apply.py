"""Applying a DOF change: ``apply_dof`` edits the design exactly (not linearized), the
planks next to the changed one following as the module ``furncheck.dofs`` says."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design, Load, LoadCase, Plank, Vec3
from furncheck.dofs.frame import Structure
from furncheck.dofs.names import AXIS, Blocked, Dof, OutOfReach
from furncheck.dofs.plank_edits import (
    axis_offset,
    axis_rotation,
    dot,
    end_direction,
    end_height,
    end_reason,
    extend_to_face,
    flat_on,
    moved,
    reseat_end,
    resized,
    support_plane,
    turned,
    with_size,
)

# ``apply_dof`` is the inner loop of the range search, so the per-plank arithmetic below is
# done on tuples of floats (``Plank.axes``, ``Plank.half_sizes``, ``End.normal_xyz``): on
# 3-vectors numpy's call overhead is many times the arithmetic.  Each formula keeps the
# operation order of the numpy expression it replaces (dot products summed left to right),
# so the results are the same to the last bit.  Products with a rotation matrix on the left
# (``plank_edits.turned``, placing a carried load) stay in numpy: BLAS may compute
# them with fused multiply-adds, which Python floats cannot reproduce.  What does not depend
# on the step is computed once per design and plank (``_turn_start``).

def apply_dof(design: Design, frame: Structure, dof: Dof, step: float) -> Design:
    """The design with ``dof`` changed by ``step`` (file unit or degrees) and its
    neighbours adjusted (module docstring).  Raises Blocked if the DOF cannot move,
    OutOfReach if this step cannot be made (a plank would shrink to nothing, an end would
    lie along its support)."""
    before = {p.id: p for p in design.planks}
    planks = dict(before)
    plank = planks[dof.plank]
    if dof.kind in ("x", "y", "z"):
        _translate(frame, planks, plank, AXIS[dof.kind], step * design.unit_scale)
    elif dof.is_rotation:
        _rotate(frame, planks, plank, AXIS[dof.kind], math.radians(step), design.planks)
    else:
        _resize(frame, planks, plank, 0 if dof.kind == "length" else 1,
                step * design.unit_scale)
    return with_planks_carried(design, tuple(planks[p.id] for p in design.planks))


def with_planks_carried(design: Design, planks: tuple[Plank, ...]) -> Design:
    """The design with ``planks`` in place of its own (one each, in its order), the load
    and anchor points on each plank that changed (not the same object) carried with it
    (``_carried``, ``carried_point``): an edit of a DOF, a plank lengthened to close a
    gap, a leg given a quarter turn."""
    before = {p.id: p for p in design.planks}
    after = {p.id: p for p in planks}
    changed = {plank_id for plank_id, p in after.items() if p is not before[plank_id]}
    return replace(design, planks=planks,
                   load_cases=tuple(_carried_case(case, before, after, changed)
                                    for case in design.load_cases),
                   anchors=tuple(anchor if anchor.plank not in changed else replace(
                       anchor, point=carried_point(anchor.point, before[anchor.plank],
                                                   after[anchor.plank]))
                       for anchor in design.anchors))


def _carried_case(case: LoadCase, before: dict[str, Plank], after: dict[str, Plank],
                  changed: set[str]) -> LoadCase:
    """The load case with its loads carried by their edited planks (``_carried``); the
    case itself when none of its loaded planks changed."""
    if not any(load.plank in changed for load in case.loads):
        return case
    return replace(case, loads=tuple(_carried(load, before[load.plank], after[load.plank])
                                     for load in case.loads))


def _carried(load: Load, before: Plank, after: Plank) -> Load:
    """A load rides on its plank: its point keeps its place relative to the plank, as a
    fraction of the plank's length and width (a load at the end of a shelf stays at the
    end when the shelf grows), at the same height above its face.  The force keeps its
    world direction (gravity does not turn with the plank)."""
    if load.point is None or before is after or before == after:
        return load
    return Load(load.plank, load.force, carried_point(load.point, before, after), load.mass)


def carried_point(point: Vec3, before: Plank, after: Plank) -> Vec3:
    """Where a point on plank ``before`` (a load's, an anchor's) is on its edit ``after``:
    at the same fraction of the plank's length and width, the same height above its
    face."""
    if before is after or before == after:
        return point
    (px, py, pz), (cx, cy, cz) = point, before.center
    offset = (px - cx, py - cy, pz - cz)
    x_axis, y_axis, z_axis = before.axes                      # local = R^T (p - c), scaled
    scaled = np.array([dot(offset, x_axis) * (after.length / before.length),
                       dot(offset, y_axis) * (after.width / before.width),
                       dot(offset, z_axis)])
    (ox, oy, oz), (cx, cy, cz) = (after.rotation_matrix @ scaled).tolist(), after.center
    return (cx + ox, cy + oy, cz + oz)


def _translate(frame: Structure, planks: dict[str, Plank], plank: Plank, axis: int,
               amount: float) -> None:
    # moving along world axis ``axis``: the component of a normal n along it is n[axis]
    held = [end for end in frame.ends[plank.id] if abs(end.normal_xyz[axis]) > tol.DOF_PARALLEL_EPS]
    if len(held) > 1:
        names = " and ".join(sorted({end.support for end in held}))
        raise Blocked(f"both ends jointed ({names}): moving {plank.id} along "
                      f"{'xyz'[axis]} would open or press into a joint")
    if held:
        raise Blocked(end_reason(plank.id, held[0], "moving it along " + "xyz"[axis]))
    for normal in frame.lies_flat.get(plank.id, ()):
        if abs(normal[axis]) > tol.DOF_PARALLEL_EPS:      # off the face it lies on, or into it
            raise Blocked(f"{plank.id} lies {flat_on(normal)}")
    offset = axis_offset(axis, amount)
    planks[plank.id] = moved(plank, offset)
    for edge_id, end in frame.attached[plank.id]:
        shift = amount * end.normal_xyz[axis]              # face moves along its normal
        if abs(shift) <= tol.DOF_PARALLEL_EPS * max(abs(amount), 1.0):
            continue
        edge = planks[edge_id]
        if edge_id in frame.free:
            planks[edge_id] = moved(edge, offset)
        else:
            planks[edge_id] = extend_to_face(edge, end, shift)


def _rotate(frame: Structure, planks: dict[str, Plank], plank: Plank, axis: int,
            angle: float, design_planks: tuple[Plank, ...]) -> None:
    turn = axis_rotation(axis, angle)
    for normal in frame.lies_flat.get(plank.id, ()):
        if abs(normal[axis]) < 1.0 - tol.DOF_PARALLEL_EPS:    # a turn that tips it off that face
            raise Blocked(f"{plank.id} lies {flat_on(normal)}")
    start = _turn_start(frame, planks, plank, design_planks)
    rotated = turned(plank, turn, plank.center_array)
    # the plank's own held ends stay on their faces: change its size at those ends
    for end, (point, normal, height) in zip(frame.ends[plank.id], start.ends):
        rotated = reseat_end(rotated, plank.id, end, point, normal, height)
    planks[plank.id] = rotated
    for (edge_id, end), height_before in zip(frame.attached[plank.id], start.attached):
        edge = planks[edge_id]
        if height_before is None:
            planks[edge_id] = turned(edge, turn, plank.center_array)
            continue
        point, normal = support_plane(rotated, end)
        height_after = end_height(edge, end, point, normal)
        along = dot(end_direction(edge, end), normal)
        if abs(along) <= tol.DOF_PARALLEL_EPS:
            raise OutOfReach(f"{edge_id} would lie along the turned face of {plank.id}")
        planks[edge_id] = resized(edge, end.axis, end.sign, (height_before - height_after)
                                   / along)


@dataclass(frozen=True)
class TurnStart:
    """The part of turning a plank that does not depend on the angle (``_rotate``).

    planks   : the design's planks it was computed from
    ends     : per held end of the plank (``Structure.ends`` order): the supporting plane
               (point, normal; the ground for an end on the ground) and the end's height
               above it
    attached : per attached edge plank (``Structure.attached`` order): the height of its
               end above the plank's face, or None for a free plank (it turns along)
    """

    planks: tuple[Plank, ...]
    ends: tuple[tuple[Vec3, Vec3, float], ...]
    attached: tuple[float | None, ...]


def _turn_start(frame: Structure, planks: dict[str, Plank], plank: Plank,
                design_planks: tuple[Plank, ...]) -> TurnStart:
    """The ``TurnStart`` of ``plank`` in the design of ``design_planks`` (still unedited
    in ``planks``), remembered in ``frame.turn_starts`` while that design is the one
    being turned: the range search turns the planks of one design thousands of times."""
    start = frame.turn_starts.get(plank.id)
    if start is not None and start.planks is design_planks:
        return start
    ends = []
    for end in frame.ends[plank.id]:
        if end.on is None:
            point, normal = ((0.0, 0.0, 0.0), (0.0, 0.0, 1.0)) if end.plane is None \
                else (end.plane, end.normal_xyz)
        else:
            point, normal = support_plane(planks[end.on], end)
        ends.append((point, normal, end_height(plank, end, point, normal)))
    attached = tuple(None if edge_id in frame.free else
                     end_height(planks[edge_id], end, *support_plane(plank, end))
                     for edge_id, end in frame.attached[plank.id])
    start = TurnStart(design_planks, tuple(ends), attached)
    frame.turn_starts[plank.id] = start
    return start


def _resize(frame: Structure, planks: dict[str, Plank], plank: Plank, axis: int,
            amount: float) -> None:
    held = [end for end in frame.ends[plank.id] if end.axis == axis]
    if len({end.sign for end in held}) == 2:
        names = " and ".join(sorted({end.support for end in held}))
        raise Blocked(f"both ends jointed ({names})")
    if held:
        # the held end stays: the other end moves by the whole amount
        planks[plank.id] = resized(plank, axis, -held[0].sign, amount)
    else:
        size = (plank.length, plank.width)[axis] + amount
        planks[plank.id] = with_size(plank, axis, size, plank.center)

