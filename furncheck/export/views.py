"""Design views: the planks in 3D from the fixed oblique view (``projection``), coloured
by utilization (``colours``), as a PNG a maker opens.

    view_png(panels, heading) -> bytes            one row of panels, one PNG
    design_panel(design, report, ...) -> Panel    a design, its deflection solved here
    design_view_png(design, report) -> bytes      one design
    suggestion_view_png(original, original_report, design, report, title) -> bytes
                                                  before | after, changes outlined

Each panel draws, besides the planks:

* the loads of its governing load case (``findings.governing_case``: the first that is
  not stable, else the most utilized) as arrows ending where they act, longer for larger
  loads (a spread load as three arrows along its plank), labelled with the mass or force;
* every joint past its capacity (in any case) as a red cross, the worst labelled with
  its utilization, and the governing case's contacts that lift or slide as red triangles;
* in the elastic model the deflected beam axes of the governing case, dashed, magnified
  by a round factor that makes the largest displacement about DEFLECTION_SHARE of the
  design's size; the factor and the largest displacement are written under the panel
  (as structural tools do: 'deflected shape x 50');
* planks a suggestion changed or added outlined in blue or purple (``colours.MARK_RGB``).

All panels of a figure share one scale (lengths compare across before and after).  The
figure is built with matplotlib's object API on an Agg canvas (no pyplot) and written
without a software version: the same input gives the same bytes with one matplotlib.
"""

from __future__ import annotations

import math
import textwrap
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from furncheck.design.model import Design
from furncheck.export import projection
from furncheck.export.arrows import LOAD_ARROW_SHARE, design_extent, load_arrows
from furncheck.export.colours import (
    FAILING_RGB,
    MARK_RGB,
    NOT_SOLVED_RGB,
    scale_samples,
    utilization_rgb,
)
from furncheck.export.deflection import Deflection, deflected_shape
from furncheck.export.errors import ExportUnavailable
from furncheck.export.findings import (
    failing_contacts,
    failing_joints,
    governing_case,
    plank_utilization,
)
from furncheck.export.labels import Label, Picture, Sheet
from furncheck.plain import plain_number
from furncheck.result import NOT_SOLVED, CaseResult, DesignReport

PANEL_SIZE = (6.0, 4.6)      # inches per panel (width, height)
HEADING_LINE = 0.22          # inches per line of the heading above the panels
HEADING_CHARACTERS = 55      # per panel: the heading is wrapped to this many per line
FOOTER_HEIGHT = 0.55         # inches below them: colour bar and legend
DPI = 100
MARGIN = 0.06
"""Share of the drawing's extent left around it."""
DEFLECTION_SHARE = 0.06
"""The deflected shape's largest displacement is magnified to about this share of the
design's largest extent (by a factor 1, 2 or 5 x 10^k, never below 1)."""
LABELLED_JOINTS = 3
LABELLED_CONTACTS = 2
LABELLED_LOADS = 6
EDGE_RGB = (0.22, 0.22, 0.22)
LOAD_RGB = (0.10, 0.10, 0.35)
DEFLECTION_RGB = (0.05, 0.05, 0.05)
FLOOR_RGB = (0.93, 0.93, 0.92)
WALL_EDGE_RGB = (0.75, 0.75, 0.74)
FONT = 8
NOTE_RGB = (0.25, 0.25, 0.25)


@dataclass(frozen=True)
class Panel:
    """One drawing of a design: its report (None: grey planks, nothing marked), the
    deflection to draw (None: none), marked planks (id -> 'changed' or 'added') and a
    title."""

    design: Design
    report: DesignReport | None
    deflection: Deflection | None = None
    marks: dict[str, str] = field(default_factory=dict)
    title: str = ""


def design_panel(design: Design, report: DesignReport | None, marks: dict[str, str] | None
                 = None, title: str | None = None, deflect: bool = True) -> Panel:
    """A panel of ``design``; its deflection in the report's governing case is solved
    here when ``deflect`` (elastic model only, and only when that case is stable)."""
    case = governing_case(report) if report is not None else None
    # only an equilibrium has a deflected shape (an unstable case shows forces held down)
    deflection = deflected_shape(design, case.name) \
        if deflect and case is not None and case.stability == "stable" else None
    return Panel(design, report, deflection, dict(marks or {}),
                 verdict_title(design, report) if title is None else title)


def verdict_title(design: Design, report: DesignReport | None) -> str:
    """'stool: INVALID, 3 violations' or 'stool: valid, worst 52 %'."""
    if report is None or report.valid is None:
        return design.name
    if not report.valid:
        count = len(report.violations)
        return f"{design.name}: INVALID, {count} violation{'s' * (count != 1)}"
    worst = max((value for value in plank_utilization(report, design.planks).values()
                 if value is not None), default=0.0)
    return f"{design.name}: valid, worst {plain_number(100 * worst, 3)} %"


def design_view_png(design: Design, report: DesignReport | None, deflect: bool = True
                    ) -> bytes:
    """The PNG of one design (its ``design_panel``)."""
    return view_png([design_panel(design, report, deflect=deflect)])


def suggestion_view_png(original: Design, original_report: DesignReport | None,
                        design: Design, report: DesignReport | None, heading: str,
                        marks: dict[str, str], before: Panel | None = None) -> bytes:
    """Before | after of a suggestion, the planks it changed or added (``marks``)
    outlined in both; ``before``: the original's panel if already made (its deflection
    is then not solved again)."""
    before = before or design_panel(original, original_report)
    before = Panel(before.design, before.report, before.deflection,
                   {key: value for key, value in marks.items() if value == "changed"},
                   f"before: {before.title}")
    after = design_panel(design, report, marks, f"after: {verdict_title(design, report)}")
    return view_png([before, after], heading)


def view_png(panels: list[Panel], heading: str | None = None) -> bytes:
    """The panels side by side as PNG bytes."""
    return view_picture(panels, heading).png()


def view_figure_modules() -> None:
    """Import what drawing a view needs (matplotlib, Pillow), or raise ExportUnavailable:
    done once before forking workers that draw, so that none imports them again."""
    try:
        import matplotlib.backends.backend_agg  # noqa: F401
        import matplotlib.collections  # noqa: F401
        import matplotlib.figure  # noqa: F401
        import matplotlib.lines  # noqa: F401
        import PIL.ImageDraw  # noqa: F401
    except ImportError as error:
        raise ExportUnavailable("matplotlib") from error


def view_picture(panels: list[Panel], heading: str | None = None) -> Picture:
    """The figure (Agg canvas) and labels of ``view_png``."""
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError as error:
        raise ExportUnavailable("matplotlib") from error
    if not panels:
        raise ValueError("no design to draw")
    width = PANEL_SIZE[0] * len(panels)
    lines = textwrap.wrap(heading, int(HEADING_CHARACTERS * len(panels))) if heading else []
    height = HEADING_LINE * (len(lines) + 0.5 * bool(lines)) + PANEL_SIZE[1] + FOOTER_HEIGHT
    figure = Figure(figsize=(width, height), dpi=DPI, facecolor="white")
    FigureCanvasAgg(figure)
    picture = Picture(figure)
    limits = _shared_limits(panels)
    factor = _shared_magnification(panels)
    bottom = FOOTER_HEIGHT * DPI
    for k, panel in enumerate(panels):
        slot = (k * PANEL_SIZE[0] * DPI, bottom, PANEL_SIZE[0] * DPI, PANEL_SIZE[1] * DPI)
        title, notes = _draw_panel(Sheet(figure, _fit(limits, slot)), picture, panel, factor)
        left = (k * PANEL_SIZE[0] + 0.12) * DPI
        picture.labels.append(Label(left, bottom + (PANEL_SIZE[1] - 0.1) * DPI, title,
                                    FONT + 1, va="top"))
        if notes:
            picture.labels.append(Label(left, bottom + 5, "\n".join(notes), FONT,
                                        NOTE_RGB, va="bottom"))
    if lines:
        picture.labels.append(Label(0.12 * DPI, (height - 0.12) * DPI, "\n".join(lines),
                                    FONT + 2, va="top", bold=True))
    _draw_scale(figure, picture, width, height, any(panel.marks for panel in panels))
    return picture


# --- one panel --------------------------------------------------------------------------

def _fit(limits, slot):
    """The Affine2D taking the picture rectangle ``limits`` (x0, x1, y0, y1) into the
    middle of the pixel rectangle ``slot`` (left, bottom, width, height), one scale for
    both axes."""
    from matplotlib.transforms import Affine2D

    x0, x1, y0, y1 = limits
    left, bottom, width, height = slot
    scale = min(width / (x1 - x0), height / (y1 - y0))
    return Affine2D().translate(-(x0 + x1) / 2, -(y0 + y1) / 2).scale(scale).translate(
        left + width / 2, bottom + height / 2)


def _draw_panel(sheet: Sheet, picture: Picture, panel: Panel,
                factor: float = 1.0) -> tuple[str, list[str]]:
    """Draw the panel on ``sheet`` (its deflection magnified ``factor`` times); return its
    title and the notes to write under it."""
    from matplotlib.collections import LineCollection, PolyCollection

    design, report = panel.design, panel.report
    scale = design.unit_scale
    size = design_extent(design)

    backdrop = [_floor(design), *_walls(design)]
    sheet.add(PolyCollection(projection.project(np.array(backdrop)), facecolors=[FLOOR_RGB],
                             edgecolors=[WALL_EDGE_RGB],
                             linewidths=[0.0] + [0.6] * (len(backdrop) - 1), zorder=0))
    faces, normals, owner, order = _faces(design.planks, scale, design.tolerance / scale)
    used = plank_utilization(report, design.planks) if report is not None else {}
    colours = np.array([utilization_rgb(used.get(plank.id)) if report is not None
                        else NOT_SOLVED_RGB for plank in design.planks]).reshape(-1, 3)
    face_colours = projection.shaded(colours[owner[order]], normals[order])
    mark_of = [panel.marks.get(design.planks[i].id) for i in owner[order]]
    edge_colours = [MARK_RGB[mark] if mark else EDGE_RGB for mark in mark_of]
    widths = [1.8 if mark else 0.4 for mark in mark_of]
    sheet.add(PolyCollection(projection.project(faces[order]), facecolors=face_colours,
                             edgecolors=edge_colours, linewidths=widths, zorder=1))
    _draw_mark_edges(sheet, design, panel.marks, LineCollection)
    case = governing_case(report) if report is not None else None
    notes = []
    if panel.deflection is not None and panel.deflection.largest > 0.0:
        notes.append(_draw_deflection(sheet, panel.deflection, factor, design.units,
                                      LineCollection))
    elif not design.elastic:
        notes.append("rigid planks: no deflection drawn")
    elif case is not None and case.stability not in ("stable", NOT_SOLVED):
        notes.append("no deflection drawn: the case has no equilibrium")
    if case is not None:
        _draw_loads(sheet, picture, design, case, size, LineCollection, PolyCollection)
        _draw_failures(sheet, picture, design, report, case)
        notes.insert(0, f"loads of case '{case.name}'"
                        + (f" (worst of {len(report.cases)})" if len(report.cases) > 1 else ""))
        if case.stability == NOT_SOLVED:
            notes.insert(1, "statics not solved: the design does not stand as drawn")
    return panel.title, notes


@lru_cache(maxsize=16)
def _faces(planks: tuple, unit_scale: float, slack: float):
    """``projection.plank_faces`` of the planks and their ``visible_order``: kept for the
    planks of a design drawn again (the design before each of its suggestions)."""
    faces, normals, owner = projection.plank_faces(planks, unit_scale)
    return faces, normals, owner, projection.visible_order(planks, unit_scale, normals, slack)


def _draw_mark_edges(sheet: Sheet, design: Design, marks: dict[str, str],
                     LineCollection) -> None:
    """The box edges of every marked plank (changed or added) as thin dashed lines in its
    mark's colour, over everything: a part hidden behind another (a rail under a shelf)
    still shows where it goes, as hidden lines do in a drawing."""
    marked = [(plank, MARK_RGB[marks[plank.id]]) for plank in design.planks
              if marks.get(plank.id) in MARK_RGB]
    if not marked:
        return
    lines, colours = [], []
    for plank, colour in marked:
        edges = projection.box_edges(plank, design.unit_scale)
        lines.extend(edges)
        colours.extend([colour] * len(edges))
    sheet.add(LineCollection(lines, colors=colours, linewidths=1.0, linestyles=(0, (2, 2)),
                             alpha=0.9, zorder=3))


def _shared_magnification(panels: list[Panel]) -> float:
    """The deflection's magnification, one for all panels (before and after compare):
    ``_magnification`` of the largest displacement of any panel and the largest design."""
    drawn = [panel for panel in panels
             if panel.deflection is not None and panel.deflection.largest > 0.0]
    if not drawn:
        return 1.0
    return _magnification(max(panel.deflection.largest for panel in drawn),
                          max(design_extent(panel.design) for panel in drawn))


def _draw_deflection(sheet: Sheet, deflection: Deflection, factor: float, units: str,
                     LineCollection) -> str:
    lines = [projection.project(points + factor * moves)
             for _, points, moves in deflection.curves]
    sheet.add(LineCollection(lines, colors=[DEFLECTION_RGB], linewidths=0.9,
                                       linestyles=(0, (3, 2)), alpha=0.85, zorder=4))
    return (f"deflected shape (dashed) x {plain_number(factor)}: largest displacement "
            f"{plain_number(deflection.largest, 3)} {units} at {deflection.where}\n"
            "(the joints' give too; sag, a plank's own bending, is in the report)")


def _magnification(largest: float, size: float) -> float:
    """1, 2 or 5 x 10^k, the largest not above DEFLECTION_SHARE size / largest (>= 1)."""
    wanted = DEFLECTION_SHARE * size / largest
    if wanted <= 1.0:
        return 1.0
    power = 10.0 ** math.floor(math.log10(wanted))
    return max(step * power for step in (1.0, 2.0, 5.0) if step * power <= wanted)


def _draw_loads(sheet: Sheet, picture: Picture, design: Design, case: CaseResult, size: float,
                LineCollection, PolyCollection) -> None:
    arrows = load_arrows(design, case, size)
    if not arrows:
        return
    shafts, heads, tails = [], [], []
    for arrow in arrows:
        tail2, head2 = projection.project([arrow.tail, arrow.head])
        shafts.append([tail2, head2])
        heads.append(_arrow_head(tail2, head2, 0.022 * size))
        tails.append(tail2)
    # each different label once first (in load order), then repeats while there is room
    labels = [(k, arrow.label) for k, arrow in enumerate(arrows) if arrow.label]
    firsts = {label: k for k, label in reversed(labels)}
    chosen = sorted(k for k, label in labels if firsts[label] == k)
    chosen += [k for k, _ in labels if k not in chosen]
    for k in sorted(chosen[:LABELLED_LOADS]):
        (x, y), = sheet.pixels(tails[k])
        picture.labels.append(Label(x - 3, y + 2, arrows[k].label, FONT, LOAD_RGB, ha="right",
                                    halo=True))
    sheet.add(LineCollection(shafts, colors=[LOAD_RGB], linewidths=1.4, zorder=5))
    sheet.add(PolyCollection(heads, facecolors=[LOAD_RGB], edgecolors="none",
                                       zorder=5))


def _arrow_head(tail: np.ndarray, head: np.ndarray, size: float) -> np.ndarray:
    """(3, 2) triangle of an arrow head at ``head`` pointing away from ``tail``."""
    along = head - tail
    norm = float(np.linalg.norm(along))
    along = along / norm if norm > 0 else np.array([0.0, -1.0])
    across = np.array([-along[1], along[0]])
    base = head - along * size
    return np.array([head, base + across * size * 0.45, base - across * size * 0.45])


def _draw_failures(sheet: Sheet, picture: Picture, design: Design, report: DesignReport,
                   case: CaseResult) -> None:
    from matplotlib.lines import Line2D

    joints = failing_joints(report)
    if joints:
        points = projection.project([joint.point for joint, _ in joints])
        sheet.add(Line2D(points[:, 0], points[:, 1], ls="", marker="X", ms=9,
                         color=FAILING_RGB, mec="white", mew=0.8, zorder=7))
        for (joint, case_name), point in list(zip(joints, points))[:LABELLED_JOINTS]:
            (x, y), = sheet.pixels(point)
            picture.labels.append(Label(
                x + 8, y, f"{'/'.join(joint.planks)} {plain_number(100 * joint.utilization, 3)}"
                f" % ('{case_name}')", FONT, FAILING_RGB, va="center", halo=True))
    contacts = failing_contacts(case, design.material.friction)
    if contacts:
        points = projection.project([item.contact.point for item in contacts])
        sheet.add(Line2D(points[:, 0], points[:, 1], ls="", marker="^", ms=8,
                         color=FAILING_RGB, mec="white", mew=0.8, zorder=7))
        named = set()
        for item, point in zip(contacts, points):
            key = (item.contact.plank, item.reason)
            if key in named or len(named) >= LABELLED_CONTACTS:
                continue
            named.add(key)
            (x, y), = sheet.pixels(point)
            picture.labels.append(Label(x + 8, y, f"{item.contact.plank} {item.reason}",
                                        FONT, FAILING_RGB, va="top", halo=True))


# --- shared geometry --------------------------------------------------------------------

def _floor(design: Design) -> np.ndarray:
    """(4, 3) the floor's rectangle under the design, a margin around its footprint."""
    if not design.planks:
        return np.zeros((4, 3))
    corners = np.concatenate([plank.corners for plank in design.planks]) / design.unit_scale
    low, high = corners.min(axis=0), corners.max(axis=0)
    pad = 0.08 * float(np.ptp(corners, axis=0).max())
    (x0, y0), (x1, y1) = low[:2] - pad, high[:2] + pad
    return np.array([[x0, y0, 0.0], [x1, y0, 0.0], [x1, y1, 0.0], [x0, y1, 0.0]])


def _walls(design: Design) -> list[np.ndarray]:
    """(4, 3) per wall: its plane from the floor to a little above the design, as wide
    as the design along it (plus a margin), file unit."""
    if not design.planks or not design.walls:
        return []
    corners = np.concatenate([plank.corners for plank in design.planks]) / design.unit_scale
    pad = 0.08 * float(np.ptp(corners, axis=0).max())
    top = corners[:, 2].max() + pad
    walls = []
    for wall in design.walls:
        normal = np.asarray(wall.normal, dtype=float)
        point = np.asarray(wall.point, dtype=float) / design.unit_scale
        along = np.cross([0.0, 0.0, 1.0], normal)
        reach = (corners - point) @ along
        low, high = reach.min() - pad, reach.max() + pad
        base = point - (point @ [0.0, 0.0, 1.0]) * np.array([0.0, 0.0, 1.0])
        walls.append(np.array([base + along * low, base + along * high,
                               base + along * high + [0.0, 0.0, top],
                               base + along * low + [0.0, 0.0, top]]))
    return walls


def _shared_limits(panels: list[Panel]) -> tuple[float, float, float, float]:
    """Picture limits that hold every panel's planks, floor and load arrows."""
    points = []
    for panel in panels:
        design = panel.design
        if design.planks:
            corners = np.concatenate([plank.corners for plank in design.planks])
            points.append(projection.project(corners / design.unit_scale))
            points.append(projection.project(_floor(design)))
            points.extend(projection.project(wall) for wall in _walls(design))
            size = design_extent(design)
            top = corners[:, 2].max() / design.unit_scale
            points.append(projection.project(corners / design.unit_scale
                                             + [0, 0, LOAD_ARROW_SHARE * size])
                          [corners[:, 2] / design.unit_scale >= top - 1e-9])
    if not points:
        return (-1.0, 1.0, -1.0, 1.0)
    everything = np.concatenate(points)
    low, high = everything.min(axis=0), everything.max(axis=0)
    pad = MARGIN * float((high - low).max() or 1.0)
    # room for the title above and the notes below
    return (low[0] - pad, high[0] + pad, low[1] - 2.5 * pad, high[1] + 1.5 * pad)


def _draw_scale(figure, picture: Picture, width: float, height: float, marked: bool
                ) -> None:
    """The utilization colour bar (right) and the legend (left) along the bottom."""
    values, colours = scale_samples()
    left, bar_width = width - 2.2, 2.0
    columns = int(bar_width * DPI)
    strip = colours[np.minimum((np.arange(columns) * len(colours)) // columns,
                               len(colours) - 1)]
    figure.figimage(np.repeat(strip[None], int(0.14 * DPI), axis=0), xo=int(left * DPI),
                    yo=int(0.3 * DPI), origin="upper")
    for value in (0.0, 0.5, 1.0, 1.5):
        x = (left + bar_width * value / values[-1]) * DPI
        picture.labels.append(Label(x, 0.27 * DPI, f"{value * 100:.0f} %"
                                    + ("+" if value == 1.5 else ""), FONT - 1, ha="center",
                                    va="top"))
    picture.labels.append(Label(left * DPI, 0.48 * DPI, "utilization (worst of all cases)",
                                FONT - 1))
    picture.labels.append(Label(0.1 * DPI, 0.3 * DPI, "red X: joint past its capacity\n"
                                "red triangle: contact that lifts or slides"
                                + ("\noutline: blue changed, purple added" if marked else ""),
                                FONT - 1, NOTE_RGB, va="center"))
