"""Synthetic shelving walls of any size, for benchmarks.

``shelving_wall(columns, rows)`` builds columns + 1 vertical sides standing on the ground
and ``columns x rows`` shelves nailed between neighbouring sides (two joints each), with a
books load on every shelf.  Plank count = columns + 1 + columns * rows; joints = 2 x shelves.
"""

from __future__ import annotations

from furncheck.design.model import Design, Load, LoadCase, Plank

SIDE_DEPTH = 0.30      # m
BAY_WIDTH = 0.40       # m, between the faces of two sides
SHELF_PITCH = 0.25     # m
THICKNESS = 0.012      # m

# (columns, rows) giving about 10, 28, 100 and 400 planks
SIZES = {10: (2, 4), 28: (3, 8), 100: (9, 10), 400: (19, 20)}


def shelving_wall(columns: int, rows: int, books_kg: float = 8.0,
                  heavy_kg: float | None = None) -> Design:
    """A wall of ``columns`` bays with ``rows`` shelves each (see the module docstring)."""
    height = SHELF_PITCH * (rows + 1)
    planks = []
    for c in range(columns + 1):
        x = c * (BAY_WIDTH + THICKNESS)
        planks.append(Plank(f"side{c}", height, SIDE_DEPTH, THICKNESS,
                            (x, 0.0, height / 2), (0.0, 90.0, 0.0)))
    loads = []
    for c in range(columns):
        x = c * (BAY_WIDTH + THICKNESS) + THICKNESS / 2 + BAY_WIDTH / 2
        for r in range(rows):
            shelf_id = f"shelf{c}_{r}"
            z = SHELF_PITCH * (r + 1)
            planks.append(Plank(shelf_id, BAY_WIDTH, SIDE_DEPTH, THICKNESS, (x, 0.0, z)))
            heavy = heavy_kg is not None and (c, r) == (columns // 2, rows // 2)
            loads.append(Load.of_mass(shelf_id, heavy_kg if heavy else books_kg))
    return Design(f"shelving-{len(planks)}", tuple(planks),
                  (LoadCase("default", tuple(loads)),))
