"""The walls of a design file and the anchors into them (contract sections 1 and 2).

``walls(doc, node, units)`` reads ``walls: [{point, normal}, ...]`` (vertical planes the
design may lean on), ``anchors(...)`` reads ``anchors: [{plank, at, wall, capacity}]``
(screws or brackets tying a plank to a wall); every problem is one ``DesignError`` with
its key path and line, as in ``furncheck.design.load``.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.cases import _point_on_plank
from furncheck.design.model import Anchor, Plank, Wall
from furncheck.design.values import (
    _Doc,
    _plank_ref,
    _point,
    _quantity,
    _Skipped,
    _Units,
    _vector,
)
from furncheck.plain import plain_number

WALL_KEYS = ("point", "normal")
ANCHOR_KEYS = ("plank", "at", "wall", "capacity")


def walls(doc: _Doc, node: Any, units: _Units) -> tuple[Wall, ...] | None:
    """``[{point, normal}, ...]``: vertical planes, the normal horizontal (its z within
    WALL_NORMAL_TILT of zero, then made exactly horizontal) and made a unit vector; None
    when one of them could not be read (its problems kept: ``_Doc.collect``)."""
    read = [doc.collect(_wall, doc, item, f"walls[{index}]", units)  # each on its own
            for index, item in enumerate(doc.sequence(node, "walls"))]
    return None if None in read else tuple(read)    # (a wall missing: anchors unchecked)


def _wall(doc: _Doc, item: Any, key: str, units: _Units) -> Wall:
    """One wall of ``walls``."""
    fields = doc.mapping(item, key, WALL_KEYS, required=WALL_KEYS)
    point = _point(doc, fields["point"], f"{key}.point", units)
    normal = np.array(_vector(doc, fields["normal"], f"{key}.normal", 3,
                              -tol.MAX_COORDINATE, tol.MAX_COORDINATE))
    size = float(np.linalg.norm(normal))
    if size == 0.0:
        doc.fail(f"{key}.normal", "zero-length normal: give the direction from the wall "
                                  "into the room, e.g. [0, 1, 0]")
    if abs(normal[2]) > tol.WALL_NORMAL_TILT * size:
        shown = ", ".join(plain_number(c, 6) for c in normal)
        doc.fail(f"{key}.normal", "a wall is vertical: its normal must be horizontal "
                                  f"(z = 0), got ({shown})")
    normal[2] = 0.0
    normal /= float(np.linalg.norm(normal))
    return Wall(point, (float(normal[0]), float(normal[1]), 0.0))


def anchors(doc: _Doc, node: Any, by_id: dict[str, Plank], walls_found: tuple[Wall, ...],
            units: _Units, tolerance: float) -> tuple[Anchor, ...]:
    """``[{plank, at, wall, capacity}, ...]``: ``at`` a world point on the plank (within
    ``tolerance``) and not behind its wall, ``wall`` an index into ``walls``, ``capacity``
    N > 0."""
    read = [doc.collect(_anchor, doc, item, f"anchors[{index}]", by_id, walls_found, units,
                        tolerance)                       # each on its own
            for index, item in enumerate(doc.sequence(node, "anchors"))]
    return tuple(anchor for anchor in read if anchor is not None)


def _anchor(doc: _Doc, item: Any, key: str, by_id: dict[str, Plank],
            walls_found: tuple[Wall, ...], units: _Units, tolerance: float) -> Anchor:
    """One anchor of ``anchors``: its wall and capacity read whether or not its plank can
    be (an unknown plank, or one left unchecked: ``_Doc.unsure``), its point once the
    plank is read."""
    fields = doc.mapping(item, key, ANCHOR_KEYS, required=ANCHOR_KEYS)
    plank = doc.collect(_plank_ref, doc, fields["plank"], f"{key}.plank", by_id)
    point = None if plank is None else doc.collect(_point_on_plank, doc, fields["at"],
                                                   f"{key}.at", plank, units, tolerance)
    wall = doc.collect(_anchor_wall, doc, fields["wall"], f"{key}.wall", walls_found)
    capacity = doc.collect(_capacity, doc, fields["capacity"], f"{key}.capacity")
    if point is None or wall is None or capacity is None:   # their problems kept, or a
        raise _Skipped(key)                                 # plank left unchecked
    behind = -float(walls_found[wall].distance(np.asarray(point)))
    if behind > tolerance + tol.ON_PLANK_EPS:
        doc.fail(f"{key}.at", f"the point is {plain_number(behind / units.scale)} "
                              f"{units.name} behind wall {wall}")
    return Anchor(plank.id, point, wall, capacity, -behind)


def _capacity(doc: _Doc, node: Any, key: str) -> float:
    """N: an anchor's capacity, > 0."""
    return _quantity(doc, node, key, 0.0, tol.MAX_FORCE, unit="N", positive=True)


def _anchor_wall(doc: _Doc, node: Any, key: str, walls_found: tuple[Wall, ...]) -> int:
    """An anchor's wall: an index into ``walls_found``."""
    wall = doc.number(node, key)
    if not wall.is_integer() or not 0 <= wall < len(walls_found):
        have = (f"the design has walls 0 to {len(walls_found) - 1}" if walls_found
                else "the design has no walls: add one under walls")
        doc.fail(key, f"no wall {plain_number(wall, 6)} ({have})")
    return int(wall)
