"""Where the suggestions for a big design look: the planks nearest its violations.

The force sensitivity of every DOF of a design costs a solve and a rebuilt model per DOF,
and the margins it gives are (DOFs x checks): both grow with the square of the design.
For a design of more than SUGGEST_ALL_PLANKS planks, ``suggest`` therefore changes only
the planks nearest the checks that fail: those its violations name, then the planks
jointed to them, then the planks jointed to those, and so on, nearer centres first within
each ring, SUGGEST_NEAR_PLANKS in all.  Every suggestion is still checked in full, on the
whole design; what a far plank could have done is not offered.
"""

from __future__ import annotations

from collections import deque

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design
from furncheck.dofs import Dof
from furncheck.geometry import Geometry
from furncheck.result import Violation


def suggestion_dofs(design: Design, geometry: Geometry, violations: tuple[Violation, ...],
                    dofs: list[Dof]) -> list[Dof]:
    """``dofs`` for a design of at most SUGGEST_ALL_PLANKS planks; else those of them that
    move the SUGGEST_NEAR_PLANKS planks nearest the violations (in the given order)."""
    if len(design.planks) <= tol.SUGGEST_ALL_PLANKS:
        return dofs
    near = nearest_planks(design, geometry, violation_planks(design, violations),
                          tol.SUGGEST_NEAR_PLANKS)
    ids = {design.planks[i].id for i in near}
    return [dof for dof in dofs if dof.plank in ids]


def violation_planks(design: Design, violations: tuple[Violation, ...]) -> list[int]:
    """Design indices of the planks the violations name (a joint 'a/b', a plank, a group
    'a,b,c', an anchor 'anchors[k]' by its plank), in order of first mention."""
    found: dict[int, None] = {}
    for violation in violations:
        where = violation.where
        if where.startswith("anchors[") and where.endswith("]"):
            index = int(where[len("anchors["):-1])
            names = [design.anchors[index].plank] if index < len(design.anchors) else []
        else:
            names = where.replace("/", ",").split(",")
        for name in names:
            if name in design.plank_index:
                found.setdefault(design.plank_index[name])
    return list(found)


def nearest_planks(design: Design, geometry: Geometry, seeds: list[int],
                   count: int) -> list[int]:
    """Design indices of the ``count`` planks nearest the ``seeds`` (those first): by
    joint rings (breadth first over the geometry's joints), within a ring by the distance
    of the centre to the nearest seed's, then by index; sorted."""
    if not seeds:
        return []
    neighbours: list[set[int]] = [set() for _ in design.planks]
    for joint in geometry.joints:
        a, b = (design.plank_index[plank] for plank in joint.planks)
        neighbours[a].add(b)
        neighbours[b].add(a)
    ring = {k: 0 for k in seeds}
    queue = deque(seeds)
    while queue:
        k = queue.popleft()
        for other in neighbours[k]:
            if other not in ring:
                ring[other] = ring[k] + 1
                queue.append(other)
    distance = np.zeros(len(design.planks))
    if len(seeds) < count:          # else the seeds fill the count, nearest or not
        centres = np.array([plank.center_array for plank in design.planks])
        distance = np.linalg.norm(centres[:, None, :] - centres[None, seeds, :],
                                  axis=2).min(axis=1)
    unreached = len(design.planks)          # planks jointed to no seed come last
    order = sorted(range(len(design.planks)),
                   key=lambda k: (ring.get(k, unreached), float(distance[k]), k))
    return sorted(order[:count])
