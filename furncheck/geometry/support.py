"""The support polygon on the floor: the convex hull of a design's ground contacts seen from
above, how far a point lies outside it, and where the line of action of the design's
loads meets the floor (a design topples where that point lies outside; a leg drawn short
widens the polygon once it stands on the floor).  Plane points are (x, y) in metres; a
hull is counter-clockwise, one or two points for a design standing on a point or a
line.  ``tipping_on_plane`` does the same for a part on supports that push it one way
(a loose top on its frame's edges)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from furncheck import tolerances as tol
from furncheck.tolerances import GRAVITY

DUPLICATE = 1e-9
"""m: points closer than this are one point of the hull."""


def convex_hull(points) -> list[int]:
    """The indices of the hull's points (Andrew's monotone chain), counter-clockwise from
    the lowest x (then y); points within DUPLICATE of the one before them in that order
    count once; one or two indices for points on a point or a line."""
    points = [np.asarray(p, dtype=float) for p in points]
    order = sorted(range(len(points)), key=lambda k: (round(float(points[k][0]), 12),
                                                      round(float(points[k][1]), 12)))
    unique: list[int] = []
    for k in order:
        if not unique or np.linalg.norm(points[k] - points[unique[-1]]) > DUPLICATE:
            unique.append(k)

    def cross(o, a, b) -> float:
        return float((a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]))

    def chain(indices: list[int]) -> list[int]:
        kept: list[int] = []
        for k in indices:
            while len(kept) >= 2 and cross(points[kept[-2]], points[kept[-1]], points[k]) <= 0:
                kept.pop()
            kept.append(k)
        return kept

    if len(unique) <= 2:
        return unique
    lower, upper = chain(unique), chain(unique[::-1])
    return lower[:-1] + upper[:-1]


def outside(hull: np.ndarray, point: np.ndarray) -> tuple[float, np.ndarray]:
    """(distance, nearest point) of ``point`` (2,) from the convex polygon ``hull`` (h, 2):
    0 and the point itself when it lies inside a polygon of three or more points (on a
    point or a line, the distance to it)."""
    if len(hull) >= 3 and all(
            (b[0] - a[0]) * (point[1] - a[1]) - (b[1] - a[1]) * (point[0] - a[0]) >= 0.0
            for a, b in zip(hull, np.roll(hull, -1, axis=0))):
        return 0.0, point
    _, distance, nearest = nearest_edge(hull, point)
    return distance, nearest


def nearest_edge(hull: np.ndarray, point: np.ndarray) -> tuple[int, float, np.ndarray]:
    """(k, distance, nearest point): the edge from hull point k to the next nearest
    ``point``, in any dimension (the first of equals)."""
    best, nearest, index = math.inf, hull[0], 0
    for k, (a, b) in enumerate(zip(hull, np.roll(hull, -1, axis=0))):
        edge = b - a
        length = float(edge @ edge)
        t = 0.0 if length == 0.0 else min(max(float((point - a) @ edge) / length, 0.0), 1.0)
        candidate = a + t * edge
        distance = float(np.linalg.norm(point - candidate))
        if distance < best:
            best, nearest, index = distance, candidate, k
    return index, best, nearest


def hold_down_ratios(hull: np.ndarray, point: np.ndarray) -> np.ndarray | None:
    """(h,): for a design whose loads' resultant V meets the floor at ``point`` outside the
    convex polygon ``hull`` (h >= 3 points, counter-clockwise), the least pull at each hull
    point that holds it down, over V (None on a point or a line).

    A pull P at hull point q moves the resultant's floor point to c + t (q - c), t = P / (V +
    P); it holds once that point is inside, from the t where the segment from c to q
    enters the polygon (the largest of its entries into each edge's inner half-plane), so
    P / V = t / (1 - t).  Where c lies beyond one edge, d from it, and q lies a inside it,
    that is d / a (W d / a); beyond a corner it is more than one edge's d / a (each edge
    next to the corner must hold)."""
    if len(hull) < 3:
        return None
    ratios = np.full(len(hull), np.inf)
    starts, edges = hull, np.roll(hull, -1, axis=0) - hull

    def side(p: np.ndarray) -> np.ndarray:     # >= 0 inside each edge's half-plane
        return edges[:, 0] * (p[1] - starts[:, 1]) - edges[:, 1] * (p[0] - starts[:, 0])

    here = side(point)
    for k, target in enumerate(hull):
        there = side(target)
        entering = here < 0.0
        if np.any(entering & (there <= here)):     # never enters that half-plane
            continue
        t = float(np.max(-here[entering] / (there[entering] - here[entering]),
                         initial=0.0))
        if t < 1.0:
            ratios[k] = t / (1.0 - t)
    return ratios


def floor_point(force: np.ndarray, moment: np.ndarray) -> np.ndarray:
    """(2,) m: where the line of action of a resultant ``force`` (3,) N (F_z < 0) with
    ``moment`` (3,) N m about the origin meets the floor, the point p with no horizontal
    moment about it (the floor's forces act in its plane): p = (-M_y / F_z, M_x / F_z)."""
    return np.array([-moment[1] / force[2], moment[0] / force[2]])


def pressure_centre(design, case) -> np.ndarray | None:
    """(2,) m: where the line of action of the planks' weights and the case's loads meets
    the floor, the centre of pressure the ground would need for rigid planks:

        c_x = sum(x_i F_zi - z_i F_xi) / sum(F_zi),   c_y = sum(y_i F_zi - z_i F_yi) / sum(F_zi)

    over the forces F_i acting at r_i (the moments about the floor point c have no
    horizontal part: friction acts in the floor's plane); None when they do not press
    down."""
    f, r = plank_loads(design, case)
    total = f.sum(axis=0)
    if total[2] >= 0.0:
        return None
    return floor_point(total, np.cross(r, f).sum(axis=0))


def plank_loads(design, case, planks=None) -> tuple[np.ndarray, np.ndarray]:
    """(forces (k, 3) N, points (k, 3) m): the weight of each plank (of ``planks``,
    design indices; all when None) at its centre and every load of ``case`` (None: none)
    on them (a spread load at its plank's centre, where its resultant acts)."""
    chosen = range(len(design.planks)) if planks is None else sorted(planks)
    forces, points = [], []
    for i in chosen:
        plank = design.planks[i]
        forces.append((0.0, 0.0, -design.plank_mass(plank) * GRAVITY))
        points.append(plank.center_array)
    for load in case.loads if case is not None else ():
        if planks is None or design.plank_index[load.plank] in planks:
            forces.append(load.force)
            points.append(design.plank(load.plank).center_array if load.point is None
                          else np.asarray(load.point))
    return np.asarray(forces, dtype=float).reshape(-1, 3), \
        np.asarray(points, dtype=float).reshape(-1, 3)


@dataclass(frozen=True, eq=False)    # holds arrays: no == by value
class Tipping:
    """A part pressed onto supports that all push it one way (the floor: up; a loose top's
    frame: up through its resting corners), seen in their plane, as ``tipping_on_plane``
    finds it: the part's load pressing it onto them (``load``, N), where the line of
    action of its loads meets that plane (``crossing`` (3,) m, world), the support polygon
    there (``hull``: indices of the supports on it, counter-clockwise), how far outside
    it the crossing lies (``outside``, m, 0 inside) and the polygon's point nearest it
    (``nearest_point`` (3,) m, world), and per hull point the least pull there that holds
    the part down, over ``load`` (``ratios``, ``hold_down_ratios``; None on a point or a
    line)."""

    load: float
    crossing: np.ndarray
    hull: np.ndarray
    outside: float
    nearest_point: np.ndarray
    ratios: np.ndarray | None

    def least_pull(self) -> tuple[float, np.ndarray] | None:
        """(N, supports): the least pull at one support that holds the part down, and the
        supports (indices) where it is that least, to HOLD_TIE (a sawhorse's two far
        feet, a loose top's two back corners); None where it stands (the crossing inside)
        or no single pull holds it (a point or a line of supports)."""
        if self.outside <= 0.0 or self.ratios is None or not np.isfinite(self.ratios.min()):
            return None
        least = float(self.ratios.min())
        tied = self.ratios <= least * (1.0 + tol.HOLD_TIE) + tol.HOLD_TIE
        return self.load * least, self.hull[tied]


def tipping_on_plane(force: np.ndarray, moment: np.ndarray, supports: np.ndarray,
                     push: np.ndarray) -> Tipping | None:
    """``Tipping`` of a part whose loads add up to ``force`` (3,) N with ``moment`` (3,)
    N m about the world origin, on ``supports`` (k, 3) m that lie in one plane and push
    it along the unit vector ``push`` (the floor's up, z): the floor's own statics
    (``floor_point``, ``convex_hull``, ``hold_down_ratios``) in a frame whose third axis
    is ``push`` and whose origin is the first support.  None where the loads do not press
    the part onto them."""
    push = np.asarray(push, dtype=float)
    first = np.array([1.0, 0.0, 0.0]) if abs(push[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    e1 = first - (first @ push) * push
    e1 /= np.linalg.norm(e1)
    frame = np.array([e1, np.cross(push, e1), push])      # rows: e1, e2, push (right-handed)
    origin = supports[0]
    local_force = frame @ force
    if not local_force[2] < 0.0:
        return None
    local_moment = frame @ (moment - np.cross(origin, force))
    crossing = floor_point(local_force, local_moment)
    flat = (supports - origin) @ frame[:2].T
    chosen = np.asarray(convex_hull(flat), dtype=int)
    distance, nearest_point = outside(flat[chosen], crossing)
    return Tipping(float(-local_force[2]), origin + crossing @ frame[:2], chosen,
                   float(distance), origin + nearest_point @ frame[:2],
                   hold_down_ratios(flat[chosen], crossing))
