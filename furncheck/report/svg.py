"""Design views as SVG, for report pages: the pictures' fixed oblique view
(``export.projection``), planks coloured on the pictures' utilization scale
(``export.colours``) by what ``export.findings`` says each uses, drawn as vector polygons,
and the loads of a load case as arrows (``export.arrows``, as the PNG views draw them).

No plotting library: a thumbnail costs well under a millisecond per plank and stays sharp
at any zoom, so a catalog page can show every design.
"""

from __future__ import annotations

from html import escape

import numpy as np

from furncheck.design.model import Design
from furncheck.export.arrows import design_extent, load_arrows
from furncheck.export.colours import MARK_RGB, utilization_rgb
from furncheck.export.findings import utilization_of
from furncheck.export.projection import (
    box_edges,
    plank_faces,
    project,
    shaded,
    visible_order,
)
from furncheck.result import CaseResult, DesignReport

_MARGIN = 6.0
"""Pixels left free around the drawing."""

LOAD_COLOUR = "rgb(26,26,89)"
"""The load arrows' colour (``views.LOAD_RGB``)."""

LABELLED_WIDTH = 300
"""Pictures at least this many pixels wide label their load arrows (a thumbnail does
not: its labels would cover the design)."""


def plank_utilizations(report: DesignReport, design: Design) -> dict[str, float | None]:
    """Per plank id, the most it uses of any capacity over the load cases (None: the
    statics were not solved), as every picture colours it (``findings.utilization_of``)."""
    return dict(utilization_of(report, tuple(plank.id for plank in design.planks)))


def _rgb(colour) -> str:
    return "rgb({},{},{})".format(*(int(round(255 * float(c))) for c in colour))


def design_svg(design: Design, utilization: dict[str, float | None] | None = None,
               width: int = 240, height: int = 180,
               marks: dict[str, str] | None = None, title: str | None = None,
               case: CaseResult | None = None) -> str:
    """An ``<svg>`` element of the design's planks, far to near, each coloured by its
    utilization (grey where None or not given); a plank in ``marks`` ('changed' or
    'added', as ``findings.changed_planks`` gives) outlined in its mark's colour; the
    loads of ``case`` (e.g. ``findings.governing_case``) as arrows in front, labelled with
    their mass or force in a picture LABELLED_WIDTH wide or more."""
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
    arrows = [] if case is None else load_arrows(design, case, design_extent(design))
    ends = project([end for arrow in arrows for end in (arrow.tail, arrow.head)]) \
        if arrows else np.zeros((0, 2))
    every = np.concatenate([points.reshape(-1, 2), ends])
    low, high = every.min(axis=0), every.max(axis=0)
    scale = min((width - 2 * _MARGIN) / max(high[0] - low[0], 1e-12),
                (height - 2 * _MARGIN) / max(high[1] - low[1], 1e-12))
    offset = (np.array([width, height]) - scale * (high - low)) / 2

    def pixels(xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return (offset[0] + scale * (xy[..., 0] - low[0]),
                height - (offset[1] + scale * (xy[..., 1] - low[1])))

    xs, ys = pixels(points)
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
    hidden = [(plank, MARK_RGB[marks[plank.id]]) for plank in planks
              if marks.get(plank.id) in MARK_RGB]
    for plank, colour in hidden:    # a marked plank's edges over everything, as the PNG
        x, y = pixels(box_edges(plank, design.unit_scale))
        edges = "".join(f"M{x0:.1f},{y0:.1f}L{x1:.1f},{y1:.1f}"
                        for (x0, x1), (y0, y1) in zip(x, y))
        parts.append(f'<path d="{edges}" fill="none" stroke="{_rgb(colour)}" '
                     f'stroke-width="1" stroke-dasharray="2 2"/>')
    if arrows:
        parts.append(_arrows_svg(arrows, *pixels(ends), width >= LABELLED_WIDTH))
    parts.append("</svg>")
    return "".join(parts)


def _arrows_svg(arrows, xs: np.ndarray, ys: np.ndarray, labelled: bool) -> str:
    """The load arrows as one group: a shaft and a head each (xs, ys: tail and head pixels
    of each arrow in turn), each label once at the tail of its arrow."""
    parts = [f'<g class="loads" fill="{LOAD_COLOUR}" stroke="{LOAD_COLOUR}">']
    shown = set()
    for k, arrow in enumerate(arrows):
        (x0, x1), (y0, y1) = xs[2 * k:2 * k + 2], ys[2 * k:2 * k + 2]
        along = np.array([x1 - x0, y1 - y0])
        length = float(np.hypot(*along))
        unit = along / length if length > 0 else np.array([0.0, 1.0])
        across = np.array([-unit[1], unit[0]])
        size = 6.0
        back = np.array([x1, y1]) - unit * size
        tips = [(x1, y1), tuple(back + across * 0.45 * size), tuple(back - across * 0.45 * size)]
        parts.append(f'<line x1="{x0:.1f}" y1="{y0:.1f}" x2="{back[0]:.1f}" '
                     f'y2="{back[1]:.1f}" stroke-width="1.4"/>')
        parts.append('<polygon points="' + " ".join(f"{x:.1f},{y:.1f}" for x, y in tips)
                     + '" stroke="none"/>')
        if labelled and arrow.label and arrow.label not in shown:
            shown.add(arrow.label)
            parts.append(f'<text x="{x0 - 3:.1f}" y="{y0 + 4:.1f}" text-anchor="end" '
                         f'font-size="11" font-family="sans-serif" stroke="white" '
                         f'stroke-width="3" '
                         f'paint-order="stroke">{escape(arrow.label)}</text>')
    parts.append("</g>")
    return "".join(parts)
