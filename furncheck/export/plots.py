"""The force space of a design change (paper section 6.2 and Figure 11), as one PNG.

The paper judges validity in force space: a design is durable when every joint's nail
forces lie inside the capacity box, and stable when every contact presses (normal force
N >= 0) within its friction cone (friction |T| <= mu N).  The figure has two panels, every
joint and contact drawn once, at its worst load case (a design is valid only when it is
valid in every case), before the change as grey rings, after it as dots (red when
failing), a grey line joining the two positions of the same joint or contact:

    joints    (pull / pull capacity, shear / shear capacity) per nail; shaded: the
              durable region (contract section 3; a pressed joint, pull < 0, never fails,
              so the region runs left to the edge and pressing beyond PRESSED_CLIP is
              drawn there).  Worst case: the largest utilization among the cases where
              joint forces count (a case that topples shows its joints held down, which
              raise nothing: ``findings.DURABILITY_COUNTS``).
    contacts  (N, |T|) in newtons, the friction cone |T| <= mu N shaded, left of N = 0
              the contact would have to pull on the ground (the design lifts there).
              Worst case: the largest friction demand |T| / (mu N) (a pull is worst).
              The panel's title gives the friction budget of the worst case: the
              friction the whole design needs over what its weight on the floor gives,
              |sum T| / (mu sum N) over the ground contacts.

At most LABELLED_JOINTS joints and LABELLED_CONTACTS contacts, the worst after the change
(then before), are labelled; the others are drawn unlabelled.  The heading names the
design and the change, and the verdicts before and after.

Figures are built with matplotlib's object API on an Agg canvas (no pyplot, no layout
engine: the panels sit at fixed places), their text written with Pillow (``labels``), and
saved without a software version, so the same reports always give the same bytes with one
matplotlib and Pillow installation.
"""

from __future__ import annotations

import math
import textwrap
from collections.abc import Callable, Hashable, Iterable
from pathlib import Path
from typing import TypeVar

import numpy as np

from furncheck import tolerances as tol
from furncheck.export.colours import FAILING_RGB
from furncheck.export.errors import ExportUnavailable
from furncheck.export.findings import (
    DURABILITY_COUNTS,
    friction_demand,
    tangential,
)
from furncheck.export.labels import Label, Picture, Sheet
from furncheck.files import write_atomically
from furncheck.plain import plain_number
from furncheck.result import ContactResult, DesignReport, JointResult

PRESSED_CLIP = -1.0
"""Lowest pull ratio drawn: a joint pressed harder than one nail's pull capacity is drawn
at this value (pressing never breaks a nail joint; its amount would only squash the view)."""
LABELLED_JOINTS = 3
LABELLED_CONTACTS = 3
SLIP_SLACK = 1e-6
"""Relative slack of the friction cone's edge in the drawing: the friction phase leaves a
slipping contact's |T| at mu N to about solver precision."""
MIN_CONE_SLOPE = 0.1
"""The contacts panel is at least this slope of its width tall (the cone's mu is, unless
there is no friction at all: mu = 0 would leave it no height)."""
FIGURE_SIZE = (12.0, 5.4)      # inches
PANELS = ((0.06, 0.11, 0.40, 0.64), (0.56, 0.11, 0.40, 0.64))
"""(left, bottom, width, height) of the joints and the contacts panel, figure fractions."""
DPI = 100
FONT = 8
HEADING_CHARACTERS = 110
"""The heading (design and change) is wrapped to lines of at most this many characters."""
TICKS = 6
"""Most grid lines (with their numbers) per axis."""
GRID_COLOR = "0.9"
LABEL_OFFSET = (14.0, 14.0)
LABEL_STEP = 16.0
RIGHT_ROOM = 230.0
"""Pixels a label needs: items nearer the panel's right edge are labelled to the left."""
"""Pixels from a labelled item to its label, and between stacked labels."""

BEFORE_COLOR = "0.55"
AFTER_COLOR = "tab:blue"
REGION_COLOR = "tab:green"
LIFT_COLOR = "tab:red"
REGION_ALPHA = 0.15

Item = TypeVar("Item")


def plot_force_space(before: DesignReport, after: DesignReport, path: Path,
                     friction: float = tol.DEFAULT_FRICTION, change: str | None = None
                     ) -> str:
    """Write ``force_space_png`` to ``path``; return the path as a string."""
    data = force_space_png(before, after, friction, change)
    write_atomically(str(path), data)
    return str(path)


def force_space_png(before: DesignReport, after: DesignReport,
                    friction: float = tol.DEFAULT_FRICTION, change: str | None = None,
                    after_friction: float | None = None) -> bytes:
    """PNG bytes of ``force_space_picture``; the same reports give the same bytes."""
    return force_space_picture(before, after, friction, change, after_friction).png()


def force_space_picture(before: DesignReport, after: DesignReport,
                        friction: float = tol.DEFAULT_FRICTION, change: str | None = None,
                        after_friction: float | None = None) -> Picture:
    """The force space of ``before`` and ``after`` (reports of a design and of its changed
    version; ``friction``: the design's mu, ``after_friction`` the changed version's where
    it differs (non-slip pads); ``change``: what changed, for the heading):
    joints left, contacts right, drawn on an Agg canvas, with its labels.  ValueError
    when neither report has a load case (an unreadable design)."""
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError as error:
        raise ExportUnavailable("matplotlib") from error
    if not before.cases and not after.cases:
        raise ValueError(f"no load case results to plot for {after.design or after.name!r}")

    figure = Figure(figsize=FIGURE_SIZE, dpi=DPI, facecolor="white")
    FigureCanvasAgg(figure)
    picture = Picture(figure)
    width, height = (DPI * side for side in FIGURE_SIZE)
    slots = [(left * width, bottom * height, wide * width, high * height)
             for left, bottom, wide, high in PANELS]
    _draw_joints(figure, slots[0], picture, before, after)
    _draw_contacts(figure, slots[1], picture, before, after, friction,
                   friction if after_friction is None else after_friction)
    name = before.name or after.name
    heading = textwrap.wrap(f"{name}: {change}" if change else name, HEADING_CHARACTERS)
    picture.labels.insert(0, Label(8, height - 8, "\n".join(heading), FONT + 3, va="top",
                                   bold=True))
    picture.labels.insert(1, Label(
        8, height - 14 - 20 * len(heading), f"before: {_verdict(before)}  ->  after: "
        f"{_verdict(after)}.  Each joint and contact at its worst load case: before (grey "
        "rings), after (dots, red when failing).", FONT + 1, (0.2, 0.2, 0.2), va="top"))
    return picture


# --- joints -----------------------------------------------------------------------------

def _draw_joints(figure, slot, picture: Picture, before: DesignReport,
                 after: DesignReport) -> None:
    """Joints in (pull / capacity, shear / capacity) space, the durable region shaded."""
    old = _worst_joints(before)
    new = _worst_joints(after)
    ratios = [_ratio(joint) for joint, _ in [*old.values(), *new.values()]]
    left = PRESSED_CLIP - 0.05
    right = max([1.15] + [x + 0.1 for x, _ in ratios])
    top = max([1.15] + [y + 0.1 for _, y in ratios])
    axes = _sheet(figure, slot, (left, right), (-0.05, top), "joints")
    _area(axes, [(left, 0.0), (1.0, 0.0), (1.0, 1.0), (left, 1.0)], REGION_COLOR, REGION_ALPHA)
    _line(axes, [left, 1.0, 1.0], [1.0, 1.0, 0.0], REGION_COLOR, 1.0)
    _line(axes, [0.0, 0.0], [-0.05, top], "0.8", 0.8)
    _moves(axes, old, new, lambda item: _ratio(item[0]))
    _markers(axes, [_ratio(j) for j, _ in old.values()], [True] * len(old), before=True)
    _markers(axes, [_ratio(j) for j, _ in new.values()],
             [joint.durable for joint, _ in new.values()], before=False)
    _frame(axes, picture, (left, right), (-0.05, top),
           "pull / pull capacity, per nail (< 0: pressed)", "shear / shear capacity, per nail",
           f"joints: {_count_change(old, new)}, shaded: durable")
    _labels(axes, picture, old, new, LABELLED_JOINTS, lambda item: item[0].utilization,
            lambda item: _ratio(item[0]),
            lambda item: f"{'/'.join(item[0].planks)} "
                         f"{plain_number(100 * item[0].utilization, 3)} % ('{item[1]}')", right)
    if not old and not new:
        _say(picture, slot, "no joint forces")


def _worst_joints(report: DesignReport) -> dict[tuple, tuple[JointResult, str]]:
    """{(sorted plank pair, n): (joint, case)} at each joint's worst counting case."""
    worst: dict[tuple, tuple[JointResult, str]] = {}
    for case in report.cases:
        if case.stability not in DURABILITY_COUNTS:
            continue
        for key, joint in _keyed(case.joints, _joint_key).items():
            if key not in worst or joint.utilization > worst[key][0].utilization:
                worst[key] = (joint, case.name)
    return worst


def _ratio(joint: JointResult) -> tuple[float, float]:
    """(pull / pull capacity clipped at PRESSED_CLIP, shear / shear capacity)."""
    return (max(joint.pull / joint.pull_capacity, PRESSED_CLIP),
            joint.shear / joint.shear_capacity)


# --- contacts ---------------------------------------------------------------------------

def _draw_contacts(figure, slot, picture: Picture, before: DesignReport,
                   after: DesignReport, before_friction: float, friction: float) -> None:
    """Contacts in (N, |T|) space, the friction cone of ``after`` (mu ``friction``) shaded,
    before's (``before_friction``) drawn as a line where it differs."""
    old = _worst_contacts(before, before_friction)
    new = _worst_contacts(after, friction)
    points = [_cone_point(c) for c, _ in [*old.values(), *new.values()]]
    span = max([1.0] + [abs(x) for x, _ in points]
               + [y / friction for _, y in points if friction > 0.0])
    left = min([-0.08 * span] + [1.08 * x for x, _ in points])
    right, top = 1.08 * span, max([max(friction, MIN_CONE_SLOPE) * span]
                                  + [1.08 * y for _, y in points])
    bottom, ceiling = -0.03 * top, 1.05 * top
    axes = _sheet(figure, slot, (left, right), (bottom, ceiling), "contacts")
    cone = min(friction * right, ceiling)
    edge = cone / friction if friction > 0.0 else right     # mu = 0: the N axis alone
    _area(axes, [(0.0, 0.0), (right, 0.0), (right, cone), (edge, cone)],
          REGION_COLOR, REGION_ALPHA)
    _line(axes, [0.0, edge], [0.0, cone], REGION_COLOR, 1.0)
    if before_friction != friction and before_friction > 0.0:      # the cone it had
        was = min(before_friction * right, ceiling)
        _line(axes, [0.0, was / before_friction], [0.0, was], "0.5", 0.8)
    _area(axes, [(left, bottom), (0.0, bottom), (0.0, ceiling), (left, ceiling)],
          LIFT_COLOR, 0.07)
    _line(axes, [0.0, 0.0], [bottom, ceiling], "0.6", 0.8)
    _moves(axes, old, new, lambda item: _cone_point(item[0]))
    _markers(axes, [_cone_point(c) for c, _ in old.values()], [True] * len(old), before=True)
    unstable = {case.name for case in after.cases if case.stability != "stable"}
    _markers(axes, [_cone_point(c) for c, _ in new.values()],
             [case not in unstable or _holds(c, friction) for c, case in new.values()],
             before=False)
    budget = _budget_change(before, after, before_friction, friction)
    mu = plain_number(friction) if before_friction == friction else \
        f"{plain_number(before_friction)} -> {plain_number(friction)}"
    _frame(axes, picture, (left, right), (bottom, ceiling),
           "normal force N, newtons (< 0: it would pull: lifts)",
           "friction force |T|, newtons",
           f"contacts: shaded |T| <= mu N, mu {mu}; friction used {budget}")
    _labels(axes, picture, old, new, LABELLED_CONTACTS,
            lambda item: _demand_order(item[0], friction), lambda item: _cone_point(item[0]),
            lambda item: f"{item[0].plank} {_contact_state(item[0], friction)} "
                         f"('{item[1]}')", right)
    if not old and not new:
        _say(picture, slot, "no contact forces (no equilibrium)")


def _worst_contacts(report: DesignReport, friction: float
                    ) -> dict[tuple, tuple[ContactResult, str]]:
    """{(plank, n): (contact, case)} at each contact's largest friction demand."""
    worst: dict[tuple, tuple[ContactResult, str]] = {}
    for case in report.cases:
        for key, contact in _keyed(case.contacts, _contact_key).items():
            if key not in worst or _demand_order(contact, friction) > \
                    _demand_order(worst[key][0], friction):
                worst[key] = (contact, case.name)
    return worst


def _holds(contact: ContactResult, friction: float) -> bool:
    """Whether a contact presses within its cone (SLIP_SLACK: a contact slipping at
    mu N sits on the cone's edge, up to round-off)."""
    return contact.pressing >= 0.0 and friction_demand(contact, friction) <= 1.0 + SLIP_SLACK


def _demand_order(contact: ContactResult, friction: float) -> float:
    """Friction demand, with pulls ranked by how hard they pull (beyond every demand)."""
    if contact.pressing < 0.0:
        return 1e12 - contact.pressing
    demand = friction_demand(contact, friction)
    return demand if math.isfinite(demand) else 1e12


def _cone_point(contact: ContactResult) -> tuple[float, float]:
    return contact.pressing, tangential(contact)


def _contact_state(contact: ContactResult, friction: float) -> str:
    if contact.pressing < 0.0:
        return f"lifts ({plain_number(-contact.pressing, 3)} N pull)"
    return f"{plain_number(100 * friction_demand(contact, friction), 3)} % of mu N"


def _budget_change(before: DesignReport, after: DesignReport, before_friction: float,
                   friction: float) -> str:
    """'41.2 % -> 23 % ('shove')', or with each case named when they differ."""
    old, new = _budget(before, before_friction), _budget(after, friction)
    if old[1] == new[1]:
        return f"{old[0]} -> {new[0]}" + (f" ('{new[1]}')" if new[1] else "")
    return " -> ".join(f"{value} ('{name}')" if name else value for value, name in (old, new))


def _budget(report: DesignReport, friction: float) -> tuple[str, str]:
    """The worst case's |sum T| / (mu sum N) over ground contacts, as ('23 %', case)."""
    worst, name = None, ""
    for case in report.cases:
        ground = [c for c in case.contacts if c.wall is None and c.on is None]
        if not ground:
            continue
        forces = np.array([c.force for c in ground], dtype=float)
        normal = float(forces[:, 2].sum())
        pushed = float(np.linalg.norm(forces[:, :2].sum(axis=0)))
        if normal > 0.0 and friction > 0.0:
            used = pushed / (friction * normal)
        else:               # lifted off, or no friction (mu = 0): all of it, if any is used
            used = 0.0 if normal > 0.0 and pushed == 0.0 else math.inf
        if worst is None or used > worst:
            worst, name = used, case.name
    if worst is None:
        return "-", ""
    if not math.isfinite(worst):
        return "all", name
    return f"{100 * worst:.1f} %", name


# --- shared -----------------------------------------------------------------------------

def _sheet(figure, slot, xlim: tuple[float, float], ylim: tuple[float, float],
           name: str) -> Sheet:
    """The panel in the pixel rectangle ``slot`` (left, bottom, width, height) showing
    ``xlim`` x ``ylim``; its artists carry the gid ``name``."""
    from matplotlib.transforms import Affine2D

    left, bottom, width, height = slot
    transform = Affine2D().translate(-xlim[0], -ylim[0]).scale(
        width / (xlim[1] - xlim[0]), height / (ylim[1] - ylim[0])).translate(left, bottom)
    return Sheet(figure, transform, name)


def _area(axes: Sheet, corners: list, colour, alpha: float) -> None:
    from matplotlib.patches import Polygon

    axes.add(Polygon(corners, closed=True, facecolor=colour, alpha=alpha, lw=0, zorder=0))


def _line(axes: Sheet, xs: list, ys: list, colour, width: float) -> None:
    from matplotlib.lines import Line2D

    axes.add(Line2D(xs, ys, color=colour, lw=width, zorder=1))


def _moves(axes: Sheet, old: dict, new: dict, point: Callable) -> None:
    """A grey line from each item's position before to after (one LineCollection)."""
    from matplotlib.collections import LineCollection

    segments = [[point(old[key]), point(new[key])] for key in new if key in old]
    if segments:
        axes.add(LineCollection(segments, colors=BEFORE_COLOR, linewidths=0.7, zorder=2))


def _markers(axes: Sheet, points: list, holds: list[bool], before: bool) -> None:
    """Before: grey rings; after: dots, red where failing."""
    from matplotlib.lines import Line2D

    if not points:
        return
    x, y = np.array(points, dtype=float).T
    if before:
        axes.add(Line2D(x, y, ls="", marker="o", mfc="none", mec=BEFORE_COLOR, ms=6.5,
                        mew=1.1, zorder=3))
        return
    ok = np.array(holds, dtype=bool)
    axes.add(Line2D(x[ok], y[ok], ls="", marker="o", color=AFTER_COLOR, ms=4.5, zorder=4))
    axes.add(Line2D(x[~ok], y[~ok], ls="", marker="o", color=FAILING_RGB, ms=5.0, zorder=4))


def _labels(axes: Sheet, picture: Picture, old: dict, new: dict, count: int,
            badness: Callable, point: Callable, text: Callable, right: float) -> None:
    """Label the ``count`` worst items after the change (then those only before),
    stacked by rank with a leader line: items crowd, labels must not (``right``: the
    panel's right limit)."""
    from matplotlib.collections import LineCollection

    ranked = sorted(new, key=lambda key: -badness(new[key]))
    ranked += sorted((key for key in old if key not in new), key=lambda key: -badness(old[key]))
    leaders = []
    for rank, key in enumerate(ranked[:count]):
        item = new.get(key) or old[key]
        (x, y), = axes.pixels(point(item))
        # to the right of the item, or to its left in the panel's right part
        side = -1.0 if x > axes.pixels((right, 0.0))[0, 0] - RIGHT_ROOM else 1.0
        label_x, label_y = x + side * LABEL_OFFSET[0], y + LABEL_OFFSET[1] + LABEL_STEP * rank
        leaders.append([point(item), tuple(axes.points((label_x, label_y))[0])])
        picture.labels.append(Label(label_x + side, label_y, text(item), FONT, va="bottom",
                                    ha="left" if side > 0 else "right"))
    if leaders:
        axes.add(LineCollection(leaders, colors="0.5", linewidths=0.6, zorder=5))


def _frame(axes: Sheet, picture: Picture, xlim: tuple[float, float],
           ylim: tuple[float, float], xlabel: str, ylabel: str, title: str) -> None:
    """Limits, light grid lines at round values and their numbers, axis names and the
    title (labels: see ``labels``; matplotlib's own ticks would cost more than the plot)."""
    from matplotlib.collections import LineCollection
    from matplotlib.patches import Rectangle
    from matplotlib.ticker import MaxNLocator

    xs = [t for t in MaxNLocator(TICKS).tick_values(*xlim) if xlim[0] <= t <= xlim[1]]
    ys = [t for t in MaxNLocator(TICKS).tick_values(*ylim) if ylim[0] <= t <= ylim[1]]
    axes.add(LineCollection(
        [[(x, ylim[0]), (x, ylim[1])] for x in xs] + [[(xlim[0], y), (xlim[1], y)] for y in ys],
        colors=GRID_COLOR, linewidths=0.6, zorder=-1))
    axes.add(Rectangle((xlim[0], ylim[0]), xlim[1] - xlim[0], ylim[1] - ylim[0], fill=False,
                       edgecolor="black", lw=0.8, zorder=6))
    (x0, y0), (x1, y1) = axes.pixels([(xlim[0], ylim[0]), (xlim[1], ylim[1])])
    for x in xs:
        picture.labels.append(Label(axes.pixels((x, ylim[0]))[0, 0], y0 - 4,
                                    _tick(x), FONT, ha="center", va="top"))
    for y in ys:
        picture.labels.append(Label(x0 - 4, axes.pixels((xlim[0], y))[0, 1],
                                    _tick(y), FONT, ha="right", va="center"))
    picture.labels.append(Label((x0 + x1) / 2, y0 - 20, xlabel, FONT, ha="center", va="top"))
    picture.labels.append(Label(x0 - 42, (y0 + y1) / 2, ylabel, FONT, rotation=90))
    picture.labels.append(Label((x0 + x1) / 2, y1 + 6, title, FONT + 1, ha="center"))


def _tick(value: float) -> str:
    return f"{round(value, 9):g}"


def _verdict(report: DesignReport) -> str:
    if report.valid:
        return "valid"
    kinds: dict[str, list[str]] = {}
    for violation in report.violations:
        cases = kinds.setdefault(violation.kind, [])
        if violation.case and violation.case not in cases:
            cases.append(violation.case)
    parts = [kind + (f" in '{', '.join(cases)}'" if cases else "")
             for kind, cases in kinds.items()]
    return "INVALID (" + "; ".join(parts) + ")"


def _count_change(old: dict, new: dict) -> str:
    failing_old = sum(not joint.durable for joint, _ in old.values())
    failing_new = sum(not joint.durable for joint, _ in new.values())
    return f"{failing_old} -> {failing_new} past capacity"


def _joint_key(joint: JointResult) -> Hashable:
    """A joint is the same joint after a change when it joins the same two planks, in
    whichever order they are listed."""
    return tuple(sorted(joint.planks))


def _contact_key(contact: ContactResult) -> Hashable:
    """Contacts are matched by their plank, what they touch (the ground, a wall, a plank)
    and, through ``_keyed``, their order there: their points move with the plank."""
    return (contact.plank, contact.wall, contact.on)


def _keyed(items: Iterable[Item], key: Callable[[Item], Hashable]) -> dict[tuple, Item]:
    """{(key, n): item} in the items' order, n counting earlier items with the same key,
    so that repeated keys (a plank's several contacts) are matched in order."""
    seen: dict[Hashable, int] = {}
    keyed: dict[tuple, Item] = {}
    for item in items:
        name = key(item)
        keyed[(name, seen.get(name, 0))] = item
        seen[name] = seen.get(name, 0) + 1
    return keyed


def _say(picture: Picture, slot, text: str) -> None:
    """A note in the middle of the panel in the pixel rectangle ``slot``."""
    left, bottom, width, height = slot
    picture.labels.append(Label(left + width / 2, bottom + height / 2, text, FONT + 1,
                                (0.4, 0.4, 0.4), ha="center", va="center"))
