"""How what acts on a plank is tied to its node, small rotations (paper eq. 1): the rigid
offset of a point from its node (``point_maps``), the joint deviation map's blocks, the
contacts' frames (ground, walls, resting joints) and the resting corners' maps, and point
loads moved to their node with their moment.  Shared by the rigid model (``rigid``), the
elastic one (``elastic``, ``templated``) and the feasibility programs.
"""

from __future__ import annotations

import numpy as np

from furncheck.design.model import Design
from furncheck.geometry import Geometry


def point_maps(r: np.ndarray) -> np.ndarray:
    """(n, 3, 6): displacement of points at offsets r (n, 3) from their planks' centres,
    [I, -[r]x] @ (u, theta)."""
    maps = np.zeros((len(r), 3, 6))
    maps[:, :, :3] = np.eye(3)
    maps[:, :, 3:] = -skew_many(r)
    return maps


def skew(v: np.ndarray) -> np.ndarray:
    """[v]x, so that skew(v) @ w = v x w."""
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def skew_many(v: np.ndarray) -> np.ndarray:
    """(n, 3, 3): ``skew`` of each row of v (n, 3)."""
    out = np.zeros((len(v), 3, 3))
    out[:, 0, 1], out[:, 0, 2] = -v[:, 2], v[:, 1]
    out[:, 1, 0], out[:, 1, 2] = v[:, 2], -v[:, 0]
    out[:, 2, 0], out[:, 2, 1] = -v[:, 1], v[:, 0]
    return out


def rest_maps(rest_node: np.ndarray | None, contact_points: np.ndarray,
              node_points: np.ndarray, frames: np.ndarray | None) -> np.ndarray | None:
    """``StaticsModel.rest_maps``: each resting corner's displacement from the q of the
    node it rests on (``rest_node``), in the contact's frame; zero for other contacts."""
    if rest_node is None:
        return None
    resting = rest_node >= 0
    offsets = np.where(resting[:, None], contact_points - node_points[np.maximum(rest_node, 0)],
                       0.0)
    return in_contact_frames(point_maps(offsets), frames) * resting[:, None, None]


def anchored_contacts(geometry: Geometry, contacts: list[int]) -> np.ndarray | None:
    """(nK,) bool: which of the model's contacts are anchors' ties; None if none is."""
    anchored = np.array([geometry.contacts[c].anchor is not None for c in contacts],
                        dtype=bool)
    return anchored if anchored.any() else None


def contact_frames(design: Design, geometry: Geometry, contacts: list[int]) -> np.ndarray | None:
    """(nK, 3, 3) rows t1, t2, n of each contact's frame: the world frame for the ground;
    for a wall with horizontal normal n, t1 = z x n along the wall, t2 = z up (t1 x t2 = n);
    a resting joint's own (``Contact.frame``).  None when every contact is on the ground."""
    found = [geometry.contacts[c] for c in contacts]
    if all(contact.wall is None and contact.frame is None for contact in found):
        return None
    frames = np.broadcast_to(np.eye(3), (len(contacts), 3, 3)).copy()
    for row, contact in enumerate(found):
        if contact.frame is not None:                 # a resting joint's corner
            frames[row] = contact.frame
        elif contact.wall is not None:
            nx, ny, _ = design.walls[contact.wall].normal
            frames[row] = ((-ny, nx, 0.0), (0.0, 0.0, 1.0), (nx, ny, 0.0))
    return frames


def in_contact_frames(maps: np.ndarray, frames: np.ndarray | None) -> np.ndarray:
    """Contact maps (nK, 3, 6) in world components turned into the contacts' frames."""
    return maps if frames is None else frames @ maps


def joint_deviation_blocks(points: np.ndarray, node_points: np.ndarray) -> np.ndarray:
    """The joint deviation map G (paper eq. 1, small rotations) by blocks: each joint's
    signed (6, 6) blocks ((nJ, 2, 6, 6)) for its two nodes (``node_points`` (nJ, 2, 3)),

        d^t = (u_a + theta_a x r_a) - (u_b + theta_b x r_b),   d^r = theta_a - theta_b

    with a, b the joint's first and second node and r = joint point - node point.
    """
    blocks = np.zeros((len(points), 2, 6, 6))
    for position, side in ((0, 1.0), (1, -1.0)):
        blocks[:, position, :3, :3] = side * np.eye(3)
        blocks[:, position, :3, 3:] = -side * skew_many(points - node_points[:, position])
        blocks[:, position, 3:, 3:] = side * np.eye(3)
    return blocks


def add_point_load(f: np.ndarray, node: int, node_point, force, point) -> None:
    """f[node] += ``force`` (N) and its moment r x F about ``node_point`` when it acts at
    ``point`` (None: at the node point itself)."""
    fx, fy, fz = (float(v) for v in force)
    f[6 * node:6 * node + 3] += (fx, fy, fz)
    if point is not None:
        rx, ry, rz = (float(p) - float(c) for p, c in zip(point, node_point))
        f[6 * node + 3:6 * node + 6] += (ry * fz - rz * fy, rz * fx - rx * fz, rx * fy - ry * fx)


def add_point_loads(f: np.ndarray, nodes: np.ndarray, node_points: np.ndarray,
                    forces: np.ndarray, points: np.ndarray) -> None:
    """``add_point_load`` of many loads at once ((n,) nodes, (n, 3) node points, forces
    and points), in order: the same sums, one load after the other."""
    r = points - node_points
    moments = np.column_stack([r[:, 1] * forces[:, 2] - r[:, 2] * forces[:, 1],
                               r[:, 2] * forces[:, 0] - r[:, 0] * forces[:, 2],
                               r[:, 0] * forces[:, 1] - r[:, 1] * forces[:, 0]])
    rows = 6 * nodes[:, None] + np.arange(3)
    np.add.at(f, rows.ravel(), forces.ravel())
    np.add.at(f, (rows + 3).ravel(), moments.ravel())
