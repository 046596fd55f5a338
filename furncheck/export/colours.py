"""The colours of every picture and mesh: one utilization scale, one mark per change.

Utilization is what validity measures against 1 (contract section 3): a joint's worst
nail pull or shear over its capacity, an anchor's force over its capacity and, in the
elastic model, a plank's sag (with creep) over its allowance or its bending stress over
its strength.  A plank's utilization (``findings.plank_utilization``) is the largest of
its own and of the joints and anchors it takes part in, over every load case.

The scale runs green -> yellow -> red, linear in RGB between its stops:

    utilization   0      0.5      1.0      >= 1.5
    colour        green  yellow   red      dark red

so everything that holds is green to red and everything past its capacity is a darker
red.  A plank without a utilization (the design's statics were not solved: it does not
stand as drawn) is grey.  Pure numpy: the meshes use it without matplotlib.
"""

from __future__ import annotations

import numpy as np

RGB = tuple[float, float, float]

UTILIZATION_STOPS: tuple[tuple[float, RGB], ...] = (
    (0.0, (0.16, 0.62, 0.24)),     # green
    (0.5, (0.96, 0.80, 0.14)),     # yellow
    (1.0, (0.87, 0.17, 0.12)),     # red
    (1.5, (0.45, 0.02, 0.06)),     # dark red: 50 % past capacity and beyond
)
"""(utilization, RGB) stops of the scale; values between stops are linear in RGB,
values past the last stop take its colour."""

NOT_SOLVED_RGB: RGB = (0.72, 0.72, 0.72)
"""A plank whose statics were not solved (the design does not stand as drawn)."""

MARK_RGB: dict[str, RGB] = {
    "changed": (0.05, 0.35, 0.90),   # blue outline: moved, turned or resized
    "added": (0.62, 0.10, 0.78),     # purple outline: a new plank
}
"""Outline colour of a plank a suggestion changes or adds (views and meshes)."""

FAILING_RGB: RGB = (0.80, 0.0, 0.0)
"""Markers of failing joints and contacts."""


def utilization_rgb(utilization: float | None) -> RGB:
    """The scale's colour of one utilization (None: NOT_SOLVED_RGB)."""
    if utilization is None or not np.isfinite(utilization):
        return NOT_SOLVED_RGB if utilization is None else UTILIZATION_STOPS[-1][1]
    stops = [value for value, _ in UTILIZATION_STOPS]
    colours = np.array([colour for _, colour in UTILIZATION_STOPS])
    return tuple(float(np.interp(utilization, stops, colours[:, channel]))
                 for channel in range(3))


def scale_samples(count: int = 64) -> tuple[np.ndarray, np.ndarray]:
    """(count,) utilizations from 0 to the last stop and their (count, 3) colours: the
    colour bar of the views."""
    values = np.linspace(0.0, UTILIZATION_STOPS[-1][0], count)
    return values, np.array([utilization_rgb(float(value)) for value in values])
