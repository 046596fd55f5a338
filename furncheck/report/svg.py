"""Design views as SVG, for report pages: the planks drawn from a fixed oblique view,
coloured by how much of their capacity they use.

No plotting library: each plank is a box whose visible faces are projected onto the view
plane and drawn back to front (the painter's rule, by the depth of each face's centre), so
a thumbnail costs well under a millisecond per plank and needs nothing beyond numpy.

The colour scale (``utilization_colour``) is the one of every picture furncheck draws:
green at 0, yellow at 0.7, orange at 1 (the limit), red beyond (1.5 and over); grey for a
plank nothing was computed for.
"""

from __future__ import annotations

import math
from html import escape

import numpy as np

from furncheck.design.model import Design
from furncheck.result import DesignReport

AZIMUTH = -55.0
"""Degrees: the view looks at the design from the front right (world -y is the front)."""

ELEVATION = 28.0
"""Degrees above the horizon the view looks down from."""

LIGHT = np.array([0.35, -0.55, 0.76])
"""The direction light comes from (world), for the faces' shading."""

FAILED_UTILIZATION = 1.5
"""The utilization shown for a plank named by a violation that has no ratio (lift-off,
sliding, geometry): the red end of the scale."""

_SCALE = ((0.0, (46, 160, 67)), (0.7, (234, 196, 53)), (1.0, (240, 128, 30)),
          (FAILED_UTILIZATION, (205, 35, 35)))
"""(utilization, RGB) stops of the colour scale; linear in between, clamped outside."""

_FACES = ((0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4), (1, 3, 7, 5))
"""The six faces of ``Plank.corners`` (sign order ---, +--, -+-, ++-, --+, +-+, -++, +++)."""


def utilization_colour(utilization: float | None) -> tuple[int, int, int]:
    """RGB of the scale at ``utilization`` (None: grey, nothing computed)."""
    if utilization is None or not math.isfinite(utilization):
        return (150, 150, 150)
    u = max(utilization, 0.0)
    for (low, low_rgb), (high, high_rgb) in zip(_SCALE, _SCALE[1:]):
        if u <= high:
            t = (u - low) / (high - low)
            return tuple(round(a + t * (b - a)) for a, b in zip(low_rgb, high_rgb))
    return _SCALE[-1][1]


def plank_utilizations(report: DesignReport) -> dict[str, float]:
    """Per plank id, the most it uses of any capacity over the load cases: the joints it
    is in (their nails' utilization), its own sag and stress (elastic model), its anchors;
    a plank named by a violation without a ratio (lift-off, sliding, geometry) counts as
    FAILED_UTILIZATION."""
    used: dict[str, float] = {}

    def note(plank: str, value: float) -> None:
        if math.isfinite(value):
            used[plank] = max(used.get(plank, 0.0), value)

    for case in report.cases:
        for joint in case.joints:
            for plank in joint.planks:
                note(plank, joint.utilization)
        for plank in case.planks or ():
            note(plank.id, plank.utilization)
        for anchor in case.anchors:
            note(anchor.plank, anchor.utilization)
    for violation in report.violations:
        if violation.kind in ("non-durable", "sagging", "overstressed"):
            continue                        # their ratios are noted above
        for plank in violation.where.replace("/", ",").split(","):
            if plank.strip():
                note(plank.strip(), FAILED_UTILIZATION)
    return used


def _view_axes() -> np.ndarray:
    """(3, 3): rows are the view's right, up and toward-the-viewer directions (world)."""
    azimuth, elevation = math.radians(AZIMUTH), math.radians(ELEVATION)
    toward = np.array([math.cos(elevation) * math.cos(azimuth),
                       math.cos(elevation) * math.sin(azimuth), math.sin(elevation)])
    right = np.cross([0.0, 0.0, 1.0], toward)
    right /= np.linalg.norm(right)
    up = np.cross(toward, right)
    return np.array([right, up, toward])


def design_svg(design: Design, utilization: dict[str, float] | None = None,
               width: int = 240, height: int = 180, outlined: frozenset[str] = frozenset(),
               title: str | None = None) -> str:
    """An ``<svg>`` element of the design's planks, each coloured by its utilization
    (``plank_utilizations``; grey where not given), those in ``outlined`` drawn with a
    thick dark outline (a suggestion's changed and added planks)."""
    axes = _view_axes()
    polygons = []                           # (depth, points (4, 2), fill, plank id)
    light = LIGHT / np.linalg.norm(LIGHT)
    for plank in design.planks:
        corners = plank.corners
        centre = plank.center_array
        rgb = np.array(utilization_colour(None if utilization is None
                                          else utilization.get(plank.id)), dtype=float)
        for face in _FACES:
            points = corners[list(face)]
            middle = points.mean(axis=0)
            normal = np.cross(points[1] - points[0], points[3] - points[0])
            size = float(np.linalg.norm(normal))
            if size == 0.0:
                continue
            normal /= size
            if normal @ (middle - centre) < 0.0:
                normal = -normal            # outward
            if normal @ axes[2] <= 1e-9:
                continue                    # faces away from the viewer
            shade = 0.55 + 0.45 * max(float(normal @ light), 0.0)
            fill = tuple(int(min(255, round(c * shade))) for c in rgb)
            projected = points @ axes[:2].T
            polygons.append((float(middle @ axes[2]), projected, fill, plank.id))
    if not polygons:
        return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" '
                f'height="{height}"></svg>')
    everything = np.concatenate([p[1] for p in polygons])
    low, high = everything.min(axis=0), everything.max(axis=0)
    margin = 6.0
    scale = min((width - 2 * margin) / max(high[0] - low[0], 1e-12),
                (height - 2 * margin) / max(high[1] - low[1], 1e-12))
    offset_x = (width - scale * (high[0] - low[0])) / 2
    offset_y = (height - scale * (high[1] - low[1])) / 2
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
             f'viewBox="0 0 {width} {height}" role="img">']
    if title:
        parts.append(f"<title>{escape(title)}</title>")
    for _, projected, fill, plank_id in sorted(polygons, key=lambda p: p[0]):
        xs = offset_x + scale * (projected[:, 0] - low[0])
        ys = height - (offset_y + scale * (projected[:, 1] - low[1]))
        points = " ".join(f"{x:.1f},{y:.1f}" for x, y in zip(xs, ys))
        stroke = ('stroke="#111" stroke-width="2"' if plank_id in outlined
                  else 'stroke="#333" stroke-width="0.4"')
        parts.append(f'<polygon points="{points}" fill="rgb{fill}" {stroke} '
                     f'stroke-linejoin="round"><title>{escape(plank_id)}</title></polygon>')
    parts.append("</svg>")
    return "".join(parts)
