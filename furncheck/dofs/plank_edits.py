"""The plank arithmetic of ``apply_dof``, all SI: moved, turned and resized copies of a
plank, its ends, the planes it rests on, and the Euler angles of a turned plank.  Done on
tuples of floats where numpy's per-call cost on 3-vectors would exceed the arithmetic
(``apply``'s note)."""

from __future__ import annotations

import math

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Plank, Vec3
from furncheck.dofs.frame import End
from furncheck.dofs.names import OutOfReach


def dot(a: Vec3, b: Vec3) -> float:
    """a . b, summed left to right as numpy's dot of two 3-vectors (and R^T n) does."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def axis_offset(axis: int, amount: float) -> Vec3:
    """``amount`` along world axis ``axis``: amount e_axis, the other components 0 * amount
    (+-0.0, as numpy's e_axis * amount, so that a centre at -0.0 comes out the same)."""
    return amount * float(axis == 0), amount * float(axis == 1), amount * float(axis == 2)


def moved(plank: Plank, offset: Vec3) -> Plank:
    (x, y, z), (dx, dy, dz) = plank.center, offset
    return same_turn(plank, plank.length, plank.width, (x + dx, y + dy, z + dz))


def same_turn(plank: Plank, length: float, width: float, center: Vec3) -> Plank:
    """A copy of ``plank`` with a new size and centre and the same rotation, given its
    rotation matrix and axes (cached properties) rather than computing them again."""
    edited = Plank(plank.id, length, width, plank.thickness,
                   (float(center[0]), float(center[1]), float(center[2])), plank.rotation,
                   plank.material)
    edited.__dict__["rotation_matrix"] = plank.rotation_matrix
    edited.__dict__["axes"] = plank.axes
    return edited


def turned(plank: Plank, turn: np.ndarray, pivot: np.ndarray) -> Plank:
    """``plank`` turned by the rotation matrix ``turn`` about the point ``pivot``."""
    center = (pivot + turn @ (plank.center_array - pivot)).tolist()
    rotation = euler_degrees(turn @ plank.rotation_matrix, plank.rotation)
    return Plank(plank.id, plank.length, plank.width, plank.thickness, tuple(center), rotation,
                 plank.material)


def with_size(plank: Plank, axis: int, size: float, center: Vec3) -> Plank:
    """``plank`` with its length (axis 0) or width (1) made ``size`` (m) and its centre
    ``center``.  A size below the smallest a design file may give (MIN_LENGTH) is no
    plank: OutOfReach (a plank that follows a turned or moved neighbour can be shortened
    through nothing to a negative length otherwise)."""
    if size < tol.MIN_LENGTH:
        raise OutOfReach(f"{plank.id}'s {('length', 'width')[axis]} would shrink to nothing")
    if axis == 0:
        return same_turn(plank, float(size), plank.width, center)
    return same_turn(plank, plank.length, float(size), center)


def resized(plank: Plank, axis: int, sign: int, amount: float) -> Plank:
    """``plank`` grown by ``amount`` at its (axis, sign) end; the opposite end stays: the
    centre moves by amount / 2 along the end's outward direction s R_a."""
    (x, y, z), half = plank.center, 0.5 * amount
    ux, uy, uz = end_direction_of(plank, axis, sign)
    size = (plank.length, plank.width)[axis] + amount
    return with_size(plank, axis, size, (x + half * ux, y + half * uy, z + half * uz))


def extend_to_face(edge: Plank, end: End, shift: float) -> Plank:
    """The edge plank's end follows its face plank's face, moved ``shift`` along the face
    normal n (which points at the edge plank): the end, outward normal u, grows by
    shift / (u . n)."""
    along = dot(end_direction(edge, end), end.normal_xyz)
    return resized(edge, end.axis, end.sign, shift / along if abs(along) > 0 else 0.0)


def reseat_end(rotated: Plank, plank_id: str, end: End, point: Vec3, normal: Vec3,
                before: float) -> Plank:
    """Grow or shrink the rotated plank at ``end`` so its nearest corner is as high above
    the supporting plane (point, normal) as it was before the rotation (``before``)."""
    after = end_height(rotated, end, point, normal)
    along = dot(end_direction(rotated, end), normal)
    if abs(along) <= tol.DOF_PARALLEL_EPS:
        raise OutOfReach(f"{plank_id}'s end would lie along its support")
    return resized(rotated, end.axis, end.sign, (before - after) / along)


def support_plane(support: Plank, end: End) -> tuple[Vec3, Vec3]:
    """Point p and normal n of the broad face of ``support`` that faces ``end``'s plank:
    n = +-R_z (the plank's local z) on the side of ``end.normal``, p = c + h_z n."""
    zx, zy, zz = support.axes[2]
    side = 1.0 if dot(end.normal_xyz, (zx, zy, zz)) > 0 else -1.0
    nx, ny, nz = side * zx, side * zy, side * zz
    (x, y, z), h = support.center, support.half_sizes[2]
    return (x + h * nx, y + h * ny, z + h * nz), (nx, ny, nz)


def end_direction(plank: Plank, end: End) -> Vec3:
    """Outward unit normal of the plank's held narrow face."""
    return end_direction_of(plank, end.axis, end.sign)


def end_direction_of(plank: Plank, axis: int, sign: int) -> Vec3:
    """Outward unit normal s R_a of the plank's narrow face (axis a, sign s)."""
    ux, uy, uz = plank.axes[axis]
    return sign * ux, sign * uy, sign * uz


def end_height(plank: Plank, end: End, point: Vec3, normal: Vec3) -> float:
    """m: height of the end face's lowest corner above the plane (point, normal).

    The end face's corners are c + s h_a R_a + sum over the other local axes b of
    +-h_b R_b (R_a the plank's local axes, h its half extents, s the end's sign), so
    the lowest is (c - p).n + s h_a (R_a.n) - sum_b h_b |R_b.n|."""
    x_axis, y_axis, z_axis = plank.axes
    along = (dot(x_axis, normal), dot(y_axis, normal), dot(z_axis, normal))   # R_a . n
    half = plank.half_sizes
    spread = (abs(half[0] * along[0]), abs(half[1] * along[1]),   # |h_b| |R_b.n|: a size
              abs(half[2] * along[2]))                            # may be < 0 here
    (x, y, z), (px, py, pz) = plank.center, point
    offset = dot((x - px, y - py, z - pz), normal)
    return (offset + end.sign * half[end.axis] * along[end.axis]
            - (spread[0] + spread[1] + spread[2] - spread[end.axis]))


def end_reason(plank_id: str, end: End, action: str) -> str:
    where = f"its end on {end.on}" if end.on is not None else (
        "it stands on the ground" if end.wall is None else f"it leans on wall {end.wall}")
    verb = "would open or press into that joint" if end.on else "would lift or sink it"
    return f"{plank_id}: {where}; {action} {verb}"


def axis_rotation(axis: int, angle: float) -> np.ndarray:
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


def flat_on(normal: Vec3) -> str:
    """Where a plank lies flat, for messages: 'on the ground' or 'against a wall'."""
    return "on the ground" if normal[2] > 0.5 else "against a wall"

