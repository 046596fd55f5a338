"""Where a load case's loads are drawn: ``load_arrows``, one arrow per load (three along
its plank for a spread load), ending where it acts, in the file's unit.  The PNG views
(``views``) and the report pages' SVG views (``report.svg``) draw the same arrows.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design
from furncheck.plain import plain_load
from furncheck.result import CaseResult

LOAD_ARROW_SHARE = 0.16
"""Length of the largest load's arrow, as a share of the design's largest extent; the
others are 40 % of it plus the rest in proportion to their size."""

SPREAD_ARROWS = 3
"""Arrows along the plank of a spread load (at its middle and a third of its length to
either side)."""


@dataclass(frozen=True)
class LoadArrow:
    """One arrow: from ``tail`` to ``head`` (where the load acts), 3D points in the file's
    unit; ``label`` the load's mass or force ('80 kg', '100 N', '30 kg spread') on the
    first arrow of each load (a spread load's at its plank's -x third, so that the label,
    drawn left of its arrow, clears the others), None on the others."""

    tail: np.ndarray
    head: np.ndarray
    label: str | None


def load_arrows(design: Design, case: CaseResult, size: float) -> list[LoadArrow]:
    """The arrows of ``case``'s loads (a load of no size, or on a plank the design does
    not have, gets none), the largest LOAD_ARROW_SHARE x ``size`` long (``size``: the
    design's largest extent, file unit)."""
    found = []          # (head point, unit direction, magnitude N, label or None)
    scale = design.unit_scale
    for load in case.loads:
        force = np.array([0.0, 0.0, -load.mass * tol.GRAVITY]) if load.mass is not None \
            else np.asarray(load.force, dtype=float)
        label = plain_load(load.mass, force)
        magnitude = float(np.linalg.norm(force))
        if magnitude == 0.0 or load.plank not in design.plank_index:
            continue
        plank = design.plank(load.plank)
        centre = plank.center_array / scale
        top = centre + 0.5 * plank.thickness / scale * upward(plank)
        if load.spread:
            axis = plank.rotation_matrix[:, 0] * plank.length / scale
            points = [top + axis * offset for offset in
                      np.linspace(-1 / 3, 1 / 3, SPREAD_ARROWS)]
            label += " spread"
        else:
            points = [np.asarray(load.at, dtype=float) if load.at is not None else top]
        for k, point in enumerate(points):
            found.append((point, force / magnitude, magnitude,
                          label if k == 0 else None))
    if not found:
        return []
    largest = max(magnitude for _, _, magnitude, _ in found)
    arrows = []
    for point, direction, magnitude, label in found:
        length = LOAD_ARROW_SHARE * size * (0.4 + 0.6 * magnitude / largest)
        arrows.append(LoadArrow(point - direction * length, point, label))
    return arrows


def design_extent(design: Design) -> float:
    """The design's largest extent along a world axis, file unit (1 for no planks): the
    pictures' measure of its size."""
    if not design.planks:
        return 1.0
    corners = np.concatenate([plank.corners for plank in design.planks]) / design.unit_scale
    return float(np.ptp(corners, axis=0).max()) or 1.0


def upward(plank) -> np.ndarray:
    """The plank's face normal turned upward (its top face's side)."""
    normal = plank.rotation_matrix[:, 2]
    return normal if normal[2] >= 0 else -normal
