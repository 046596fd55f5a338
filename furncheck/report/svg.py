"""Design views as SVG, for report pages: the pictures' fixed oblique view
(``export.projection``), planks coloured on the pictures' utilization scale
(``export.colours``) by what ``export.findings`` says each uses, drawn as vector polygons.

No plotting library: a thumbnail costs well under a millisecond per plank and stays sharp
at any zoom, so a catalog page can show every design.
"""

from __future__ import annotations

from html import escape

import numpy as np

from furncheck.design.model import Design
from furncheck.export.colours import MARK_RGB, utilization_rgb
from furncheck.export.findings import utilization_of
from furncheck.export.projection import plank_faces, project, shaded, visible_order
from furncheck.result import DesignReport

_MARGIN = 6.0
"""Pixels left free around the drawing."""


def plank_utilizations(report: DesignReport, design: Design) -> dict[str, float | None]:
    """Per plank id, the most it uses of any capacity over the load cases (None: the
    statics were not solved), as every picture colours it (``findings.utilization_of``)."""
    return dict(utilization_of(report, tuple(plank.id for plank in design.planks)))


def _rgb(colour) -> str:
    return "rgb({},{},{})".format(*(int(round(255 * float(c))) for c in colour))


def design_svg(design: Design, utilization: dict[str, float | None] | None = None,
               width: int = 240, height: int = 180,
               marks: dict[str, str] | None = None, title: str | None = None) -> str:
    """An ``<svg>`` element of the design's planks, far to near, each coloured by its
    utilization (grey where None or not given); a plank in ``marks`` ('changed' or
    'added', as ``findings.changed_planks`` gives) outlined in its mark's colour."""
    planks = design.planks
    faces, normals, index = plank_faces(planks, design.unit_scale)
    order = visible_order(planks, design.unit_scale, normals,
                          design.tolerance / design.unit_scale)
    head = (f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
            f'viewBox="0 0 {width} {height}" role="img">')
    if not len(order):
        return head + "</svg>"
    used = utilization or {}
    base = np.array([utilization_rgb(used.get(planks[k].id)) for k in index[order]])
    colours = shaded(base, normals[order])
    points = project(faces[order])                                   # (m, 4, 2)
    low = points.reshape(-1, 2).min(axis=0)
    high = points.reshape(-1, 2).max(axis=0)
    scale = min((width - 2 * _MARGIN) / max(high[0] - low[0], 1e-12),
                (height - 2 * _MARGIN) / max(high[1] - low[1], 1e-12))
    offset = (np.array([width, height]) - scale * (high - low)) / 2
    xs = offset[0] + scale * (points[..., 0] - low[0])
    ys = height - (offset[1] + scale * (points[..., 1] - low[1]))
    marks = marks or {}
    parts = [head]
    if title:
        parts.append(f"<title>{escape(title)}</title>")
    for face, k in enumerate(index[order]):
        plank_id = planks[k].id
        mark = marks.get(plank_id)
        stroke = (f'stroke="{_rgb(MARK_RGB[mark])}" stroke-width="2"' if mark in MARK_RGB
                  else 'stroke="#333" stroke-width="0.4"')
        corners = " ".join(f"{x:.1f},{y:.1f}" for x, y in zip(xs[face], ys[face]))
        parts.append(f'<polygon points="{corners}" fill="{_rgb(colours[face])}" {stroke} '
                     f'stroke-linejoin="round"><title>{escape(plank_id)}</title></polygon>')
    parts.append("</svg>")
    return "".join(parts)
