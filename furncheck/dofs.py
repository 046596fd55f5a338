"""Design degrees of freedom and the geometric constraints that go with them (paper 6.1).

Every plank has eight DOFs, named ``<plank>.x|y|z`` (translation along world axes, file
length unit), ``<plank>.rx|ry|rz`` (rotation about world axes through the plank centre,
degrees) and ``<plank>.length|width`` (file length unit).  Changing one DOF keeps the
design's joints and ground contacts by adjusting the planks next to it, as in the paper:

* a plank whose end rests on the moved plank's face (it is the *edge plank* of that joint)
  follows by changing its length at that end, its other end staying where it is; a plank
  held by nothing else (no other joint, no ground) moves along rigidly instead;
* a plank's own jointed ends (and an end standing on the ground) stay where they are:
  lengthening a plank that is jointed at one end moves its free end, a rotation lengthens
  or shortens its jointed ends so that they stay on their faces;
* a change that would pull a jointed end off its face, lift a plank off the ground or push
  it in, cannot be compensated by these rules: the DOF is *blocked*, with the reason;
* loads ride on their planks (see ``_carried``).

The rules are applied exactly (not linearized), so ``apply_dof`` gives the edited design
for any step; whether the result still has the same joints and contacts is checked by the
full geometry (``check_edit``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from furncheck.design.model import Design, Load, Plank
from furncheck.errors import DofError
from furncheck.geometry import Geometry, analyze, interpenetrations

DOF_KINDS = ("x", "y", "z", "rx", "ry", "rz", "length", "width")
_AXIS = {"x": 0, "y": 1, "z": 2, "rx": 0, "ry": 1, "rz": 2}
_PARALLEL_EPS = 1e-9
_CORNER_SIGNS = np.array([[1 if c & 1 else -1, 1 if c & 2 else -1, 1 if c & 4 else -1]
                          for c in range(8)])
"""(8, 3) local sign pattern of each corner of ``Plank.corners``."""


@dataclass(frozen=True)
class Dof:
    """One design DOF: a plank id and one of DOF_KINDS."""

    plank: str
    kind: str

    @property
    def name(self) -> str:
        return f"{self.plank}.{self.kind}"

    @property
    def is_rotation(self) -> bool:
        return self.kind in ("rx", "ry", "rz")

    def unit(self, design: Design) -> str:
        return "deg" if self.is_rotation else design.units


class Blocked(Exception):
    """The DOF cannot change at all without breaking a joint or a ground contact."""

    def __init__(self, reason: str):
        self.reason = reason
        super().__init__(reason)


class OutOfReach(Exception):
    """This particular step cannot be made (the DOF itself can move by smaller steps)."""


def parse_dof(design: Design, name: str) -> Dof:
    """``'shelf.length'`` -> Dof; plank ids may contain dots, the kind is the last part."""
    plank, dot, kind = name.rpartition(".")
    if not dot or not plank:
        raise DofError(name, f"a DOF is <plank>.<{'|'.join(DOF_KINDS)}>")
    if kind not in DOF_KINDS:
        raise DofError(name, f"unknown DOF kind {kind!r}; expected one of "
                             f"{', '.join(DOF_KINDS)}")
    if plank not in design.plank_index:
        raise DofError(name, f"no plank {plank!r} in {design.name} (planks: "
                             f"{', '.join(p.id for p in design.planks)})")
    return Dof(plank, kind)


def design_size(design: Design) -> float:
    """The largest bounding-box edge of the design, in its file unit: the scale of the
    translation and length DOFs (the paper makes them dimensionless by it)."""
    corners = np.vstack([p.corners for p in design.planks])
    return float((corners.max(axis=0) - corners.min(axis=0)).max()) / design.unit_scale


def all_dofs(design: Design) -> list[Dof]:
    """Every DOF of the design, plank by plank in file order."""
    return [Dof(p.id, kind) for p in design.planks for kind in DOF_KINDS]


def dof_value(design: Design, dof: Dof) -> float:
    """The DOF's current absolute value: file length unit or degrees."""
    plank = design.plank(dof.plank)
    if dof.kind in ("x", "y", "z"):
        return plank.center[_AXIS[dof.kind]] / design.unit_scale
    if dof.is_rotation:
        return float(plank.rotation[_AXIS[dof.kind]])
    size = plank.length if dof.kind == "length" else plank.width
    return size / design.unit_scale


# --- the constraint structure -----------------------------------------------------------------

@dataclass(frozen=True)
class End:
    """A plank end that must stay where it is: a narrow face (axis 0/1, sign +-1) resting
    on the face plank ``on`` (a plank id), or on the ground (``on`` = None)."""

    axis: int
    sign: int
    on: str | None
    normal: np.ndarray      # unit normal of the supporting face, pointing at this plank


@dataclass(frozen=True)
class Structure:
    """Per plank: its held ends, the planks whose ends rest on its faces, its ground."""

    ends: dict[str, tuple[End, ...]]
    attached: dict[str, tuple[tuple[str, End], ...]]   # plank -> (edge plank, its end)
    lies_flat: frozenset[str]                          # planks lying on a broad face
    joint_count: dict[str, int]


def structure(design: Design, geometry: Geometry) -> Structure:
    """The held ends and attachments of every plank, from its joints and ground contacts."""
    ends: dict[str, list[End]] = {p.id: [] for p in design.planks}
    attached: dict[str, list[tuple[str, End]]] = {p.id: [] for p in design.planks}
    joint_count = {p.id: 0 for p in design.planks}
    for joint in geometry.joints:
        end = End(joint.edge_face[0], joint.edge_face[1], joint.face, joint.frame[:, 2].copy())
        ends[joint.edge].append(end)
        attached[joint.face].append((joint.edge, end))
        joint_count[joint.edge] += 1
        joint_count[joint.face] += 1
    flat = set()
    for plank in design.planks:
        corners = sorted({c.corner for c in geometry.contacts if c.plank == plank.id})
        if not corners:
            continue
        signs = _CORNER_SIGNS[corners]
        for axis in (0, 1):
            if np.all(signs[:, axis] == signs[0, axis]):
                ends[plank.id].append(End(axis, int(signs[0, axis]), None,
                                          np.array([0.0, 0.0, 1.0])))
                break
        else:
            flat.add(plank.id)
    return Structure({k: tuple(v) for k, v in ends.items()},
                     {k: tuple(v) for k, v in attached.items()}, frozenset(flat), joint_count)


# --- applying a DOF change --------------------------------------------------------------------

def apply_dof(design: Design, frame: Structure, dof: Dof, step: float) -> Design:
    """The design with ``dof`` changed by ``step`` (file unit or degrees) and its
    neighbours adjusted (module docstring).  Raises Blocked if the DOF cannot move."""
    planks = {p.id: p for p in design.planks}
    plank = planks[dof.plank]
    if dof.kind in ("x", "y", "z"):
        _translate(frame, planks, plank, _AXIS[dof.kind], step * design.unit_scale)
    elif dof.is_rotation:
        _rotate(frame, planks, plank, _AXIS[dof.kind], math.radians(step))
    else:
        _resize(frame, planks, plank, 0 if dof.kind == "length" else 1,
                step * design.unit_scale)
    edited = tuple(planks[p.id] for p in design.planks)
    return replace(design, planks=edited,
                   load_cases=tuple(replace(case, loads=tuple(
                       _carried(load, design.planks[design.plank_index[load.plank]],
                                planks[load.plank])
                       for load in case.loads)) for case in design.load_cases))


def _carried(load: Load, before: Plank, after: Plank) -> Load:
    """A load rides on its plank: its point keeps its place relative to the plank, as a
    fraction of the plank's length and width (a load at the end of a shelf stays at the
    end when the shelf grows), at the same height above its face.  The force keeps its
    world direction (gravity does not turn with the plank)."""
    if load.point is None or before is after or before == after:
        return load
    local = before.to_local(np.asarray(load.point)[None, :])[0]
    scale = np.array([after.length / before.length, after.width / before.width, 1.0])
    point = after.center_array + after.rotation_matrix @ (local * scale)
    return replace(load, point=tuple(float(v) for v in point))


def _translate(frame: Structure, planks: dict[str, Plank], plank: Plank, axis: int,
               amount: float) -> None:
    direction = np.eye(3)[axis]
    held = [end for end in frame.ends[plank.id] if abs(direction @ end.normal) > _PARALLEL_EPS]
    if len(held) > 1:
        names = " and ".join(sorted({end.on or "the ground" for end in held}))
        raise Blocked(f"both ends jointed ({names}): moving {plank.id} along "
                      f"{'xyz'[axis]} would open or press into a joint")
    if held:
        raise Blocked(_end_reason(plank.id, held[0], "moving it along " + "xyz"[axis]))
    if plank.id in frame.lies_flat and axis == 2:
        raise Blocked(f"{plank.id} lies on the ground")
    planks[plank.id] = _moved(plank, direction * amount)
    for edge_id, end in frame.attached[plank.id]:
        shift = amount * float(direction @ end.normal)     # face moves along its normal
        if abs(shift) <= _PARALLEL_EPS * max(abs(amount), 1.0):
            continue
        edge = planks[edge_id]
        if _is_free(frame, edge_id):
            planks[edge_id] = _moved(edge, direction * amount)
        else:
            planks[edge_id] = _extend_to_face(edge, end, shift)


def _rotate(frame: Structure, planks: dict[str, Plank], plank: Plank, axis: int,
            angle: float) -> None:
    turn = _axis_rotation(axis, angle)
    if plank.id in frame.lies_flat and axis != 2:
        raise Blocked(f"{plank.id} lies on the ground")
    old_faces = {}
    for edge_id, end in frame.attached[plank.id]:
        old_faces[edge_id] = _support_plane(plank, end)
    rotated = _turned(plank, turn, plank.center_array)
    # the plank's own held ends stay on their faces: change its size at those ends
    for end in frame.ends[plank.id]:
        support = (planks[end.on] if end.on is not None else None)
        rotated = _reseat_end(rotated, plank, end, support)
    planks[plank.id] = rotated
    for edge_id, end in frame.attached[plank.id]:
        edge = planks[edge_id]
        if _is_free(frame, edge_id):
            planks[edge_id] = _turned(edge, turn, plank.center_array)
            continue
        point, normal = _support_plane(rotated, end)
        height_before = _end_height(edge, end, *old_faces[edge_id])
        height_after = _end_height(edge, end, point, normal)
        along = _end_direction(edge, end) @ normal
        if abs(along) <= _PARALLEL_EPS:
            raise OutOfReach(f"{edge_id} would lie along the turned face of {plank.id}")
        planks[edge_id] = _resized(edge, end.axis, end.sign, (height_before - height_after)
                                   / along)


def _resize(frame: Structure, planks: dict[str, Plank], plank: Plank, axis: int,
            amount: float) -> None:
    held = [end for end in frame.ends[plank.id] if end.axis == axis]
    if len({end.sign for end in held}) == 2:
        names = " and ".join(sorted({end.on or "the ground" for end in held}))
        raise Blocked(f"both ends jointed ({names})")
    if held:
        # the held end stays: the other end moves by the whole amount
        planks[plank.id] = _resized(plank, axis, -held[0].sign, amount)
    else:
        size = (plank.length, plank.width)[axis] + amount
        planks[plank.id] = _with_size(plank, axis, size, plank.center_array)


# --- plank edits (all SI) ---------------------------------------------------------------------

def _moved(plank: Plank, offset: np.ndarray) -> Plank:
    return _same_turn(replace(plank, center=tuple(float(v) for v in
                                                  plank.center_array + offset)), plank)


def _same_turn(edited: Plank, plank: Plank) -> Plank:
    """``edited``, a copy of ``plank`` with the same rotation, given its rotation matrix
    (a cached property) rather than computing it again."""
    edited.__dict__["rotation_matrix"] = plank.rotation_matrix
    return edited


def _turned(plank: Plank, turn: np.ndarray, pivot: np.ndarray) -> Plank:
    center = pivot + turn @ (plank.center_array - pivot)
    return replace(plank, center=tuple(float(v) for v in center),
                   rotation=euler_degrees(turn @ plank.rotation_matrix, plank.rotation))


def _with_size(plank: Plank, axis: int, size: float, center: np.ndarray) -> Plank:
    sizes = {"length": plank.length, "width": plank.width}
    sizes["length" if axis == 0 else "width"] = float(size)
    return _same_turn(replace(plank, center=tuple(float(v) for v in center), **sizes), plank)


def _resized(plank: Plank, axis: int, sign: int, amount: float) -> Plank:
    """``plank`` grown by ``amount`` at its (axis, sign) end; the opposite end stays."""
    direction = sign * plank.rotation_matrix[:, axis]
    size = (plank.length, plank.width)[axis] + amount
    return _with_size(plank, axis, size, plank.center_array + 0.5 * amount * direction)


def _extend_to_face(edge: Plank, end: End, shift: float) -> Plank:
    """The edge plank's end follows its face plank's face, moved ``shift`` along the face
    normal n (which points at the edge plank): the end, outward normal u, grows by
    shift / (u . n)."""
    along = float(_end_direction(edge, end) @ end.normal)
    return _resized(edge, end.axis, end.sign, shift / along if abs(along) > 0 else 0.0)


def _reseat_end(rotated: Plank, original: Plank, end: End, support: Plank | None) -> Plank:
    """Grow or shrink the rotated plank at ``end`` so its nearest corner is as high above
    the supporting face (or the ground) as it was before the rotation."""
    if support is None:
        point, normal = np.zeros(3), np.array([0.0, 0.0, 1.0])
    else:
        point, normal = _support_plane(support, end)
    before = _end_height(original, end, point, normal)
    after = _end_height(rotated, end, point, normal)
    along = float(_end_direction(rotated, end) @ normal)
    if abs(along) <= _PARALLEL_EPS:
        raise OutOfReach(f"{original.id}'s end would lie along its support")
    return _resized(rotated, end.axis, end.sign, (before - after) / along)


def _support_plane(support: Plank, end: End) -> tuple[np.ndarray, np.ndarray]:
    """Point and normal of the broad face of ``support`` that faces ``end``'s plank."""
    normal = end.normal
    side = 1.0 if normal @ support.rotation_matrix[:, 2] > 0 else -1.0
    face_normal = side * support.rotation_matrix[:, 2]
    return support.center_array + support.half_extents[2] * face_normal, face_normal


def _end_direction(plank: Plank, end: End) -> np.ndarray:
    """Outward unit normal of the plank's held narrow face."""
    return end.sign * plank.rotation_matrix[:, end.axis]


def _end_height(plank: Plank, end: End, point: np.ndarray, normal: np.ndarray) -> float:
    """m: height of the end face's lowest corner above the plane (point, normal).

    The end face's corners are c + s h_a R_a + sum over the other local axes b of
    +-h_b R_b (R_a the plank's local axes, h its half extents, s the end's sign), so
    the lowest is (c - p).n + s h_a (R_a.n) - sum_b h_b |R_b.n|."""
    along = plank.rotation_matrix.T @ normal                  # R_a . n for each axis a
    spread = np.abs(plank.half_extents * along)      # |h_b| |R_b.n|: a size may be < 0 here
    return float((plank.center_array - point) @ normal
                 + end.sign * plank.half_extents[end.axis] * along[end.axis]
                 - (spread.sum() - spread[end.axis]))


def _is_free(frame: Structure, plank_id: str) -> bool:
    """Held by one joint only and not standing on the ground: it may simply move along."""
    return frame.joint_count[plank_id] == 1 and not any(
        end.on is None for end in frame.ends[plank_id]) and plank_id not in frame.lies_flat


def _end_reason(plank_id: str, end: End, action: str) -> str:
    where = f"its end on {end.on}" if end.on is not None else "it stands on the ground"
    verb = "would open or press into that joint" if end.on else "would lift or sink it"
    return f"{plank_id}: {where}; {action} {verb}"


def _axis_rotation(axis: int, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    if axis == 0:
        return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
    if axis == 1:
        return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def euler_degrees(matrix: np.ndarray, previous: tuple[float, float, float]) -> tuple:
    """Angles (degrees) about x, then y, then z with R = Rz @ Ry @ Rx.

    Of the two angle triples giving the same matrix (ry and 180 - ry), and of their
    360-degree copies, the one nearest ``previous`` is returned, so that a small turn reads
    as a small change in the file.
    """
    ry = math.asin(max(-1.0, min(1.0, -float(matrix[2, 0]))))
    if abs(math.cos(ry)) > 1e-9:
        rx = math.atan2(matrix[2, 1], matrix[2, 2])
        rz = math.atan2(matrix[1, 0], matrix[0, 0])
        candidates = [(rx, ry, rz), (rx + math.pi, math.pi - ry, rz + math.pi)]
    else:
        candidates = [(0.0, ry, math.atan2(-matrix[0, 1], matrix[1, 1]))]
    best, best_distance = None, math.inf
    for triple in candidates:
        angles = []
        for value, before in zip(triple, previous):
            degrees = math.degrees(value)
            degrees += 360.0 * round((before - degrees) / 360.0)
            angles.append(round(degrees, 12) + 0.0)
        distance = sum(abs(a - b) for a, b in zip(angles, previous))
        if distance < best_distance:
            best, best_distance = tuple(angles), distance
    return best


# --- checking an edit -------------------------------------------------------------------------

def check_edit(original: Geometry, edited: Design,
               design: Design | None = None) -> tuple[str | None, Geometry | None]:
    """Why the edited design no longer has the original's joints and contacts (or None),
    and the edited design's geometry (None when a plank lost its length).  With the
    original ``design``, joints between unchanged planks are not detected again."""
    for plank in edited.planks:
        if plank.length <= 0 or plank.width <= 0:
            return f"{plank.id} would have no length left", None
    geometry = analyze(edited, None if design is None else (design, original))
    problem = _edit_problem(original, geometry)
    if problem is None:
        cutting = interpenetrations(edited)
        if cutting:
            a, b, depth = cutting[0]
            problem = f"{a} would cut {depth / edited.unit_scale:.3g} {edited.units} into {b}"
    return problem, geometry


def _edit_problem(original: Geometry, geometry: Geometry) -> str | None:
    known = {(v.kind, v.where) for v in original.violations}
    problems = [v for v in geometry.violations if (v.kind, v.where) not in known]
    if problems:
        first = problems[0]
        return f"{first.kind} {first.where}: {first.message}"
    before = {(j.face, j.edge, j.edge_face) for j in original.joints}
    after = {(j.face, j.edge, j.edge_face) for j in geometry.joints}
    if before - after:
        face, edge, _ = sorted(before - after)[0]
        return f"joint {face}/{edge} would come apart"
    if after - before:
        face, edge, _ = sorted(after - before)[0]
        return f"planks {face}/{edge} would touch and form a new joint"
    grounded_before = {c.plank for c in original.contacts}
    grounded_after = {c.plank for c in geometry.contacts}
    if grounded_before != grounded_after:
        changed = sorted(grounded_before ^ grounded_after)
        return f"{changed[0]} would {'leave' if changed[0] in grounded_before else 'touch'} " \
               "the ground"
    return None
