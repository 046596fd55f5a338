"""The walls of a design file (contract sections 1 and 2): vertical planes it may lean on.

``walls(doc, node, units)`` reads ``walls: [{point, normal}, ...]``; every problem is one
``DesignError`` with its key path and line, as in ``furncheck.design.load``.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Wall
from furncheck.design.values import _Doc, _point, _Units, _vector

WALL_KEYS = ("point", "normal")


def walls(doc: _Doc, node: Any, units: _Units) -> tuple[Wall, ...]:
    """``[{point, normal}, ...]``: vertical planes, the normal horizontal (its z within
    WALL_NORMAL_TILT of zero, then made exactly horizontal) and made a unit vector."""
    found = []
    for index, item in enumerate(doc.sequence(node, "walls")):
        key = f"walls[{index}]"
        fields = doc.mapping(item, key, WALL_KEYS, required=WALL_KEYS)
        point = _point(doc, fields["point"], f"{key}.point", units)
        normal = np.array(_vector(doc, fields["normal"], f"{key}.normal", 3,
                                  -tol.MAX_COORDINATE, tol.MAX_COORDINATE))
        size = float(np.linalg.norm(normal))
        if size == 0.0:
            doc.fail(f"{key}.normal", "zero-length normal: give the direction from the wall "
                                      "into the room, e.g. [0, 1, 0]")
        if abs(normal[2]) > tol.WALL_NORMAL_TILT * size:
            doc.fail(f"{key}.normal", "a wall is vertical: its normal must be horizontal "
                                      f"(z = 0), got ({', '.join(f'{c:g}' for c in normal)})")
        normal[2] = 0.0
        normal /= float(np.linalg.norm(normal))
        found.append(Wall(point, (float(normal[0]), float(normal[1]), 0.0)))
    return tuple(found)
