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
full geometry (``furncheck.edit_check``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design, Load, LoadCase, Plank, Vec3
from furncheck.errors import DofError
from furncheck.geometry import Geometry

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
    on the face plank ``on`` (a plank id), or on the ground or a wall (``on`` = None;
    ``wall`` its index and ``plane`` a point of it, None for the ground)."""

    axis: int
    sign: int
    on: str | None
    normal: np.ndarray      # unit normal of the supporting face, pointing at this plank
    wall: int | None = None
    plane: Vec3 | None = None

    @property
    def support(self) -> str:
        """What holds the end, for messages: a plank id, 'the ground' or 'wall n'."""
        if self.on is not None:
            return self.on
        return "the ground" if self.wall is None else f"wall {self.wall}"

    @cached_property
    def normal_xyz(self) -> Vec3:
        """``normal`` as a tuple of floats (for the scalar arithmetic of ``apply_dof``)."""
        x, y, z = self.normal.tolist()
        return x, y, z


@dataclass(frozen=True)
class Structure:
    """Per plank: its held ends, the planks whose ends rest on its faces, its ground."""

    ends: dict[str, tuple[End, ...]]
    attached: dict[str, tuple[tuple[str, End], ...]]   # plank -> (edge plank, its end)
    lies_flat: dict[str, tuple[Vec3, ...]]   # plank -> normals of what it lies flat on
    joint_count: dict[str, int]

    @cached_property
    def free(self) -> frozenset[str]:
        """Planks held by one joint only and not standing or lying on the ground: they may
        simply move along with the plank they are jointed to."""
        return frozenset(plank for plank, count in self.joint_count.items()
                         if count == 1 and plank not in self.lies_flat
                         and not any(end.on is None for end in self.ends[plank]))

    @cached_property
    def turn_starts(self) -> dict[str, _TurnStart]:
        """plank id -> the angle-independent part of its last turn (``_turn_start``): a
        cache, filled by ``apply_dof``."""
        return {}


def structure(design: Design, geometry: Geometry) -> Structure:
    """The held ends and attachments of every plank, from its joints (nailed or resting)
    and ground contacts."""
    ends: dict[str, list[End]] = {p.id: [] for p in design.planks}
    attached: dict[str, list[tuple[str, End]]] = {p.id: [] for p in design.planks}
    joint_count = {p.id: 0 for p in design.planks}
    for joint in geometry.joints:
        end = End(joint.edge_face[0], joint.edge_face[1], joint.face, joint.frame[:, 2].copy())
        ends[joint.edge].append(end)
        attached[joint.face].append((joint.edge, end))
        joint_count[joint.edge] += 1
        joint_count[joint.face] += 1
    for contact in geometry.contacts:     # a resting joint holds its end like a nailed one
        if contact.on is None or contact.corner != 0:
            continue
        normal = np.asarray(contact.frame[2], dtype=float)   # into the edge plank
        axes = design.plank(contact.plank).rotation_matrix
        along = [float(axes[:, a] @ normal) for a in (0, 1)]
        axis = int(np.argmax(np.abs(along)))
        end = End(axis, -1 if along[axis] > 0.0 else 1, contact.on, normal.copy())
        ends[contact.plank].append(end)
        attached[contact.on].append((contact.plank, end))
        joint_count[contact.plank] += 1
        joint_count[contact.on] += 1
    corners: dict[str, dict[int | None, set[int]]] = {}     # plank -> support -> corners
    for contact in geometry.contacts:
        if contact.anchor is None and contact.on is None:   # nor an anchor, nor a rest
            corners.setdefault(contact.plank, {}).setdefault(contact.wall, set()).add(
                contact.corner)
    flat: dict[str, list[Vec3]] = {}
    for plank in design.planks:
        for wall, touching in corners.get(plank.id, {}).items():
            normal = (0.0, 0.0, 1.0) if wall is None else design.walls[wall].normal
            plane = None if wall is None else design.walls[wall].point
            signs = _CORNER_SIGNS[sorted(touching)]
            for axis in (0, 1):
                if np.all(signs[:, axis] == signs[0, axis]):
                    ends[plank.id].append(End(axis, int(signs[0, axis]), None,
                                              np.array(normal, dtype=float), wall, plane))
                    break
            else:
                flat.setdefault(plank.id, []).append(normal)
    return Structure({k: tuple(v) for k, v in ends.items()},
                     {k: tuple(v) for k, v in attached.items()},
                     {k: tuple(v) for k, v in flat.items()}, joint_count)


# --- applying a DOF change --------------------------------------------------------------------
#
# ``apply_dof`` is the inner loop of the range search, so the per-plank arithmetic below is
# done on tuples of floats (``Plank.axes``, ``Plank.half_sizes``, ``End.normal_xyz``): on
# 3-vectors numpy's call overhead is many times the arithmetic.  Each formula keeps the
# operation order of the numpy expression it replaces (dot products summed left to right),
# so the results are the same to the last bit.  Products with a rotation matrix on the left
# (turning a plank in ``_turned``, placing a carried load) stay in numpy: BLAS may compute
# them with fused multiply-adds, which Python floats cannot reproduce.  What does not depend
# on the step is computed once per design and plank (``_turn_start``).

def apply_dof(design: Design, frame: Structure, dof: Dof, step: float) -> Design:
    """The design with ``dof`` changed by ``step`` (file unit or degrees) and its
    neighbours adjusted (module docstring).  Raises Blocked if the DOF cannot move."""
    before = {p.id: p for p in design.planks}
    planks = dict(before)
    plank = planks[dof.plank]
    if dof.kind in ("x", "y", "z"):
        _translate(frame, planks, plank, _AXIS[dof.kind], step * design.unit_scale)
    elif dof.is_rotation:
        _rotate(frame, planks, plank, _AXIS[dof.kind], math.radians(step), design.planks)
    else:
        _resize(frame, planks, plank, 0 if dof.kind == "length" else 1,
                step * design.unit_scale)
    edited = tuple(planks[p.id] for p in design.planks)
    changed = {plank_id for plank_id, p in planks.items() if p is not before[plank_id]}
    return replace(design, planks=edited,
                   load_cases=tuple(_carried_case(case, before, planks, changed)
                                    for case in design.load_cases),
                   anchors=tuple(anchor if anchor.plank not in changed else replace(
                       anchor, point=carried_point(anchor.point, before[anchor.plank],
                                                   planks[anchor.plank]))
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
    scaled = np.array([_dot(offset, x_axis) * (after.length / before.length),
                       _dot(offset, y_axis) * (after.width / before.width),
                       _dot(offset, z_axis)])
    (ox, oy, oz), (cx, cy, cz) = (after.rotation_matrix @ scaled).tolist(), after.center
    return (cx + ox, cy + oy, cz + oz)


def _translate(frame: Structure, planks: dict[str, Plank], plank: Plank, axis: int,
               amount: float) -> None:
    # moving along world axis ``axis``: the component of a normal n along it is n[axis]
    held = [end for end in frame.ends[plank.id] if abs(end.normal_xyz[axis]) > _PARALLEL_EPS]
    if len(held) > 1:
        names = " and ".join(sorted({end.support for end in held}))
        raise Blocked(f"both ends jointed ({names}): moving {plank.id} along "
                      f"{'xyz'[axis]} would open or press into a joint")
    if held:
        raise Blocked(_end_reason(plank.id, held[0], "moving it along " + "xyz"[axis]))
    for normal in frame.lies_flat.get(plank.id, ()):
        if abs(normal[axis]) > _PARALLEL_EPS:      # off the face it lies on, or into it
            raise Blocked(f"{plank.id} lies {_flat_on(normal)}")
    offset = _axis_offset(axis, amount)
    planks[plank.id] = _moved(plank, offset)
    for edge_id, end in frame.attached[plank.id]:
        shift = amount * end.normal_xyz[axis]              # face moves along its normal
        if abs(shift) <= _PARALLEL_EPS * max(abs(amount), 1.0):
            continue
        edge = planks[edge_id]
        if edge_id in frame.free:
            planks[edge_id] = _moved(edge, offset)
        else:
            planks[edge_id] = _extend_to_face(edge, end, shift)


def _rotate(frame: Structure, planks: dict[str, Plank], plank: Plank, axis: int,
            angle: float, design_planks: tuple[Plank, ...]) -> None:
    turn = _axis_rotation(axis, angle)
    for normal in frame.lies_flat.get(plank.id, ()):
        if abs(normal[axis]) < 1.0 - _PARALLEL_EPS:    # a turn that tips it off that face
            raise Blocked(f"{plank.id} lies {_flat_on(normal)}")
    start = _turn_start(frame, planks, plank, design_planks)
    rotated = _turned(plank, turn, plank.center_array)
    # the plank's own held ends stay on their faces: change its size at those ends
    for end, (point, normal, height) in zip(frame.ends[plank.id], start.ends):
        rotated = _reseat_end(rotated, plank.id, end, point, normal, height)
    planks[plank.id] = rotated
    for (edge_id, end), height_before in zip(frame.attached[plank.id], start.attached):
        edge = planks[edge_id]
        if height_before is None:
            planks[edge_id] = _turned(edge, turn, plank.center_array)
            continue
        point, normal = _support_plane(rotated, end)
        height_after = _end_height(edge, end, point, normal)
        along = _dot(_end_direction(edge, end), normal)
        if abs(along) <= _PARALLEL_EPS:
            raise OutOfReach(f"{edge_id} would lie along the turned face of {plank.id}")
        planks[edge_id] = _resized(edge, end.axis, end.sign, (height_before - height_after)
                                   / along)


@dataclass(frozen=True)
class _TurnStart:
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
                design_planks: tuple[Plank, ...]) -> _TurnStart:
    """The ``_TurnStart`` of ``plank`` in the design of ``design_planks`` (still unedited
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
            point, normal = _support_plane(planks[end.on], end)
        ends.append((point, normal, _end_height(plank, end, point, normal)))
    attached = tuple(None if edge_id in frame.free else
                     _end_height(planks[edge_id], end, *_support_plane(plank, end))
                     for edge_id, end in frame.attached[plank.id])
    start = _TurnStart(design_planks, tuple(ends), attached)
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
        planks[plank.id] = _resized(plank, axis, -held[0].sign, amount)
    else:
        size = (plank.length, plank.width)[axis] + amount
        planks[plank.id] = _with_size(plank, axis, size, plank.center)


# --- plank edits (all SI) ---------------------------------------------------------------------

def _dot(a: Vec3, b: Vec3) -> float:
    """a . b, summed left to right as numpy's dot of two 3-vectors (and R^T n) does."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _axis_offset(axis: int, amount: float) -> Vec3:
    """``amount`` along world axis ``axis``: amount e_axis, the other components 0 * amount
    (+-0.0, as numpy's e_axis * amount, so that a centre at -0.0 comes out the same)."""
    return amount * float(axis == 0), amount * float(axis == 1), amount * float(axis == 2)


def _moved(plank: Plank, offset: Vec3) -> Plank:
    (x, y, z), (dx, dy, dz) = plank.center, offset
    return _same_turn(plank, plank.length, plank.width, (x + dx, y + dy, z + dz))


def _same_turn(plank: Plank, length: float, width: float, center: Vec3) -> Plank:
    """A copy of ``plank`` with a new size and centre and the same rotation, given its
    rotation matrix and axes (cached properties) rather than computing them again."""
    edited = Plank(plank.id, length, width, plank.thickness,
                   (float(center[0]), float(center[1]), float(center[2])), plank.rotation,
                   plank.material)
    edited.__dict__["rotation_matrix"] = plank.rotation_matrix
    edited.__dict__["axes"] = plank.axes
    return edited


def _turned(plank: Plank, turn: np.ndarray, pivot: np.ndarray) -> Plank:
    """``plank`` turned by the rotation matrix ``turn`` about the point ``pivot``."""
    center = (pivot + turn @ (plank.center_array - pivot)).tolist()
    rotation = euler_degrees(turn @ plank.rotation_matrix, plank.rotation)
    return Plank(plank.id, plank.length, plank.width, plank.thickness, tuple(center), rotation,
                 plank.material)


def _with_size(plank: Plank, axis: int, size: float, center: Vec3) -> Plank:
    """``plank`` with its length (axis 0) or width (1) made ``size`` (m) and its centre
    ``center``.  A size below the smallest a design file may give (MIN_LENGTH) is no
    plank: OutOfReach (a plank that follows a turned or moved neighbour can be shortened
    through nothing to a negative length otherwise)."""
    if size < tol.MIN_LENGTH:
        raise OutOfReach(f"{plank.id}'s {('length', 'width')[axis]} would shrink to nothing")
    if axis == 0:
        return _same_turn(plank, float(size), plank.width, center)
    return _same_turn(plank, plank.length, float(size), center)


def _resized(plank: Plank, axis: int, sign: int, amount: float) -> Plank:
    """``plank`` grown by ``amount`` at its (axis, sign) end; the opposite end stays: the
    centre moves by amount / 2 along the end's outward direction s R_a."""
    (x, y, z), half = plank.center, 0.5 * amount
    ux, uy, uz = _end_direction_of(plank, axis, sign)
    size = (plank.length, plank.width)[axis] + amount
    return _with_size(plank, axis, size, (x + half * ux, y + half * uy, z + half * uz))


def _extend_to_face(edge: Plank, end: End, shift: float) -> Plank:
    """The edge plank's end follows its face plank's face, moved ``shift`` along the face
    normal n (which points at the edge plank): the end, outward normal u, grows by
    shift / (u . n)."""
    along = _dot(_end_direction(edge, end), end.normal_xyz)
    return _resized(edge, end.axis, end.sign, shift / along if abs(along) > 0 else 0.0)


def _reseat_end(rotated: Plank, plank_id: str, end: End, point: Vec3, normal: Vec3,
                before: float) -> Plank:
    """Grow or shrink the rotated plank at ``end`` so its nearest corner is as high above
    the supporting plane (point, normal) as it was before the rotation (``before``)."""
    after = _end_height(rotated, end, point, normal)
    along = _dot(_end_direction(rotated, end), normal)
    if abs(along) <= _PARALLEL_EPS:
        raise OutOfReach(f"{plank_id}'s end would lie along its support")
    return _resized(rotated, end.axis, end.sign, (before - after) / along)


def _support_plane(support: Plank, end: End) -> tuple[Vec3, Vec3]:
    """Point p and normal n of the broad face of ``support`` that faces ``end``'s plank:
    n = +-R_z (the plank's local z) on the side of ``end.normal``, p = c + h_z n."""
    zx, zy, zz = support.axes[2]
    side = 1.0 if _dot(end.normal_xyz, (zx, zy, zz)) > 0 else -1.0
    nx, ny, nz = side * zx, side * zy, side * zz
    (x, y, z), h = support.center, support.half_sizes[2]
    return (x + h * nx, y + h * ny, z + h * nz), (nx, ny, nz)


def _end_direction(plank: Plank, end: End) -> Vec3:
    """Outward unit normal of the plank's held narrow face."""
    return _end_direction_of(plank, end.axis, end.sign)


def _end_direction_of(plank: Plank, axis: int, sign: int) -> Vec3:
    """Outward unit normal s R_a of the plank's narrow face (axis a, sign s)."""
    ux, uy, uz = plank.axes[axis]
    return sign * ux, sign * uy, sign * uz


def _end_height(plank: Plank, end: End, point: Vec3, normal: Vec3) -> float:
    """m: height of the end face's lowest corner above the plane (point, normal).

    The end face's corners are c + s h_a R_a + sum over the other local axes b of
    +-h_b R_b (R_a the plank's local axes, h its half extents, s the end's sign), so
    the lowest is (c - p).n + s h_a (R_a.n) - sum_b h_b |R_b.n|."""
    x_axis, y_axis, z_axis = plank.axes
    along = (_dot(x_axis, normal), _dot(y_axis, normal), _dot(z_axis, normal))   # R_a . n
    half = plank.half_sizes
    spread = (abs(half[0] * along[0]), abs(half[1] * along[1]),   # |h_b| |R_b.n|: a size
              abs(half[2] * along[2]))                            # may be < 0 here
    (x, y, z), (px, py, pz) = plank.center, point
    offset = _dot((x - px, y - py, z - pz), normal)
    return (offset + end.sign * half[end.axis] * along[end.axis]
            - (spread[0] + spread[1] + spread[2] - spread[end.axis]))


def _end_reason(plank_id: str, end: End, action: str) -> str:
    where = f"its end on {end.on}" if end.on is not None else (
        "it stands on the ground" if end.wall is None else f"it leans on wall {end.wall}")
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


def _flat_on(normal: Vec3) -> str:
    """Where a plank lies flat, for messages: 'on the ground' or 'against a wall'."""
    return "on the ground" if normal[2] > 0.5 else "against a wall"
