"""Loose parts: planks that lie on others by resting joints alone (contract section 2,
``type: rests``), a top on its frame, a shelf on pins, a block on a board, each with what
rests on it in turn.

A part is a jointed group (``Geometry.components``) with no ground, wall or anchor
contact of its own, together with every such group that rests on it and on nothing
else (a block on a loose top tips with the top).  It stands on its resting corners on the
planks outside it; where they all push it the same way, to within PUSH_ANGLE (a top on
two frames' edges, a shelf on four pins), its statics are the floor's in the plane of
those corners (``geometry.support.tipping_on_plane``): whether it tips off them, and the
least pull that would hold it down (``statics.outcomes`` for the lift-off message,
``suggest.needs`` for the hand estimates).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design
from furncheck.geometry.model import Geometry


@dataclass(frozen=True, eq=False)    # holds arrays: no == by value
class LoosePart:
    """A loose part (module docstring).

    planks  : design indices of its planks, what rests on it included
    corners : indices into ``Geometry.contacts`` of its resting corners on planks outside it
    points  : (k, 3) m those corners' points
    push    : the unit direction in which they push it (their normals' mean)
    under   : the plank under each corner
    rests   : the resting joints (indices into ``Design.joints``) it stands on
    """

    planks: frozenset[int]
    corners: tuple[int, ...]
    points: np.ndarray
    push: np.ndarray
    under: tuple[str, ...]
    rests: frozenset[int]

    def names(self, design: Design) -> str:
        """Its planks' ids, comma-joined, in the file's order."""
        return ",".join(design.planks[i].id for i in sorted(self.planks))

    def under_names(self, design: Design) -> str:
        """The ids of the planks it lies on, comma-joined, in the file's order."""
        return ",".join(sorted(set(self.under), key=design.plank_index.__getitem__))


def loose_parts(design: Design, geometry: Geometry) -> list[LoosePart]:
    """Every loose part of the design (module docstring), in the order of its first
    plank; a group whose corners push it different ways, or that carries a group that
    rests on something else too, is none."""
    index = design.plank_index
    group_of = {plank: g for g, group in enumerate(geometry.components) for plank in group}
    standing = {group_of[index[c.plank]] for c in geometry.contacts if c.on is None}
    standing |= {group_of[index[a.plank]] for a in design.anchors}
    rests_on: dict[int, set[int]] = {}      # group -> the groups it rests on
    corners_of: dict[int, list[int]] = {}   # group -> its resting corners (as the upper one)
    for k, contact in enumerate(geometry.contacts):
        if contact.on is None:
            continue
        upper, lower = contact.resting
        above, below = group_of[index[upper]], group_of[index[lower]]
        rests_on.setdefault(above, set()).add(below)
        corners_of.setdefault(above, []).append(k)
    parts = []
    for group in range(len(geometry.components)):
        if group in standing or group not in rests_on:
            continue
        body = _body(group, rests_on, standing)
        if body is None:
            continue
        planks = frozenset(p for g in body for p in geometry.components[g])
        corners = [k for g in body for k in corners_of.get(g, ())
                   if index[geometry.contacts[k].resting[1]] not in planks]
        part = _part(design, geometry, planks, corners)
        if part is not None:
            parts.append(part)
    return parts


def _body(group: int, rests_on: dict[int, set[int]], standing: set[int]) -> set[int] | None:
    """The groups that tip with ``group``: it and every loose group resting on it alone,
    and on those in turn; None where a group rests on it that also rests on something
    else or stands on its own (what it puts on the part is not known by statics alone)."""
    body, frontier = {group}, [group]
    while frontier:
        below = frontier.pop()
        for above, under in rests_on.items():
            if above in body or below not in under:
                continue
            if above in standing or not under <= body:    # a load it cannot tell
                return None
            body.add(above)
            frontier.append(above)
    return body


def _part(design: Design, geometry: Geometry, planks: frozenset[int],
          corners: list[int]) -> LoosePart | None:
    """The part of ``planks`` on its resting ``corners``, or None where there are none or
    they push it different ways (by more than PUSH_ANGLE)."""
    if not corners:
        return None
    pushes, under = [], []
    for k in corners:
        contact = geometry.contacts[k]
        normal = np.asarray(contact.frame[2], dtype=float)
        pushes.append(-normal if contact.face_above else normal)
        under.append(contact.resting[1])
    pushes = np.array(pushes)
    push = pushes.mean(axis=0)
    push /= np.linalg.norm(push)
    if not np.all(pushes @ push >= np.cos(np.radians(tol.PUSH_ANGLE))):
        return None
    return LoosePart(planks, tuple(corners),
                     np.array([geometry.contacts[k].point for k in corners], dtype=float),
                     push, tuple(under),
                     frozenset(geometry.contacts[k].rest for k in corners))
