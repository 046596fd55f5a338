"""Planks held along their length by the floor or a wall (elastic model).

The contract's ground contacts are a plank's corners (section 2).  A plank that touches
the floor or a wall along its beam (a board lying on the floor, a kick board standing on
its long edge, a shelf's back edge against a wall) has two such corners at the two ends
of its beam on each edge of the touching face, and a beam held at its ends alone would
span between them: a board on the floor would bend under a person standing on it, and
pull what is nailed to it along.  Here each such edge gets a *station* at every node of
the beam between its two corners (``support_edges``, ``support_stations``; the beam gets
a node at least about every SUPPORT_STATION_LENGTH, ``station_segments``): a contact
like the corners, unilateral and with friction, on the straight line between them
(``station_places``).  The statics solve the corners and the stations alike; what is
reported at a corner (``StaticsModel.corner_forces``) is its own force plus its share of
each station on its edge by the lever rule.
"""

from __future__ import annotations

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design, Plank
from furncheck.geometry import Geometry


def support_edges(design: Design, geometry: Geometry, contacts: list[int],
                  owners: np.ndarray, points: np.ndarray, planks: list[Plank],
                  axes: np.ndarray, halves: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(nE, 3) int: each edge along which a plank touches the floor or a wall, as (its
    corner at the beam's -e1 end, its corner at the +e1 end, its local plank), as rows
    of ``contacts`` (geometry contact indices; ``owners`` (nK,) their local planks,
    ``points`` (nK, 3) m their points).  A plank's corners on one support (not an
    anchor's tie or a resting joint's corner) make edges where they lie at both ends of
    its beam (within the design's tolerance of its ends, half lengths ``halves``,
    directions ``axes``); each corner at the -e1 end is paired with the nearest one
    across the beam at the +e1 end.  Also (nE,) m: each edge's plank's depth across its
    support (its extent along the support's normal: up for the floor, a wall's normal)."""
    tolerance = design.tolerance
    groups: dict[tuple, list[int]] = {}
    for row, c in enumerate(contacts):
        contact = geometry.contacts[c]
        if contact.on is None and contact.anchor is None:
            key = (int(owners[row]), -1 if contact.wall is None else contact.wall)
            groups.setdefault(key, []).append(row)
    edges, depths = [], []
    for (k, wall), rows in sorted(groups.items()):
        if len(rows) < 2:
            continue
        normal = np.array([0.0, 0.0, 1.0]) if wall < 0 else \
            np.asarray(design.walls[wall].normal, dtype=float)
        heights = planks[k].corners @ normal
        relative = points[rows] - planks[k].center_array
        s = relative @ axes[k]
        across = relative - s[:, None] * axes[k]
        low = [r for r, at in zip(rows, s) if at <= -halves[k] + tolerance]
        high = [r for r, at in zip(rows, s) if at >= halves[k] - tolerance]
        place = {r: i for i, r in enumerate(rows)}
        free = list(high)
        for a in low:
            if not free:
                break
            gaps = [float(np.linalg.norm(across[place[a]] - across[place[b]])) for b in free]
            b = free.pop(int(np.argmin(gaps)))
            edges.append((a, b, k))
            depths.append(float(heights.max() - heights.min()))
    return np.array(edges, dtype=int).reshape(-1, 3), np.array(depths, dtype=float)


def station_segments(edges: np.ndarray, halves: np.ndarray,
                     depths: np.ndarray) -> dict[int, int]:
    """Local plank -> into how many equal parts its grid of station nodes cuts its beam,
    for the planks with support edges: its length over the stations' spacing, rounded;
    the spacing SUPPORT_STATION_LENGTH, or SUPPORT_STATION_DEPTHS times the plank's depth
    across its support where that is longer (``depths`` (nE,) m, per edge: a board on
    edge is stiff between stations further apart)."""
    segments: dict[int, int] = {}
    for (_, _, k), depth in zip(edges.tolist(), depths.tolist()):
        spacing = max(tol.SUPPORT_STATION_LENGTH, tol.SUPPORT_STATION_DEPTHS * depth)
        segments[k] = max(segments.get(k, 0),
                          int(np.floor(2.0 * halves[k] / spacing + 0.5)))
    return segments


def support_stations(edges: np.ndarray, origins: tuple) -> np.ndarray:
    """(nSt, 3) int: the stations of the support edges (``support_edges``), each as (its
    edge's -e1 corner row, its +e1 corner row, its node): one per edge at every node of
    its plank between the two end nodes (which hold the corners) but those of the grid
    of BEAM_SEGMENTS alone (``origins``: each node's local plank and the keys it serves,
    in order along each plank), so that a finer grid changes no station."""
    nodes: dict[int, list[int]] = {}
    for node, (plank, *_) in enumerate(origins):
        nodes.setdefault(plank, []).append(node)
    stations = []
    for a, b, k in edges.tolist():
        stations.extend((a, b, node) for node in nodes[k][1:-1]
                        if any(key[0] != "grid" for key in origins[node][1:]))
    return np.array(stations, dtype=int).reshape(-1, 3)


def station_places(stations: np.ndarray, corner_points: np.ndarray, node_s: np.ndarray,
                   node_plank: np.ndarray, centres: np.ndarray,
                   axes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(nSt, 3) m, the stations' points, and (nSt,) their shares t in 0..1: each on the
    line from its edge's -e1 corner (t = 0) to its +e1 corner (t = 1) where its node
    lies along the beam (``node_s``, m from the plank's centre along its axis); an edge
    whose corners lie at one place along the beam, to NODE_MERGE_ROUNDOFF (a design whose
    tolerance exceeds its planks' sizes makes such contacts), at its middle, not 0 / 0."""
    a, b, node = stations[:, 0], stations[:, 1], stations[:, 2]
    k = node_plank[node]
    start, end = corner_points[a], corner_points[b]
    s_start = ((start - centres[k]) * axes[k]).sum(axis=1)
    s_end = ((end - centres[k]) * axes[k]).sum(axis=1)
    span = s_end - s_start
    along = np.divide(node_s[node] - s_start, span, out=np.full(len(span), 0.5),
                      where=np.abs(span) > tol.NODE_MERGE_ROUNDOFF)
    shares = np.clip(along, 0.0, 1.0)
    return start + shares[:, None] * (end - start), shares
