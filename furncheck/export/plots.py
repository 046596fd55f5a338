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
engine: the panels sit at fixed places) and written without a software version, so the
same reports always give the same bytes with one matplotlib installation.
"""

from __future__ import annotations

import io
import math
from collections.abc import Callable, Hashable, Iterable
from pathlib import Path
from typing import TYPE_CHECKING, TypeVar

import numpy as np

from furncheck import tolerances as tol
from furncheck.export.colours import FAILING_RGB
from furncheck.export.errors import ExportUnavailable
from furncheck.export.findings import (
    DURABILITY_COUNTS,
    friction_demand,
    tangential,
)
from furncheck.plain import plain_number
from furncheck.result import ContactResult, DesignReport, JointResult

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

PRESSED_CLIP = -1.0
"""Lowest pull ratio drawn: a joint pressed harder than one nail's pull capacity is drawn
at this value (pressing never breaks a nail joint; its amount would only squash the view)."""
LABELLED_JOINTS = 3
LABELLED_CONTACTS = 3
SLIP_SLACK = 1e-6
"""Relative slack of the friction cone's edge in the drawing: the friction phase leaves a
slipping contact's |T| at mu N to about solver precision."""
FIGURE_SIZE = (12.0, 5.2)      # inches
PANELS = ((0.06, 0.12, 0.40, 0.68), (0.56, 0.12, 0.40, 0.68))
"""(left, bottom, width, height) of the joints and the contacts panel, figure fractions."""
DPI = 100
PNG_METADATA = {"Software": None}
"""PNG text chunks: matplotlib writes its version as 'Software' unless told not to."""
PNG_OPTIONS = {"compress_level": 6}
FONT = 8

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
    Path(path).write_bytes(data)
    return str(path)


def force_space_png(before: DesignReport, after: DesignReport,
                    friction: float = tol.DEFAULT_FRICTION, change: str | None = None
                    ) -> bytes:
    """PNG bytes of ``force_space_figure``; the same reports give the same bytes."""
    figure = force_space_figure(before, after, friction, change)
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=DPI, metadata=PNG_METADATA,
                   pil_kwargs=PNG_OPTIONS)
    return buffer.getvalue()


def force_space_figure(before: DesignReport, after: DesignReport,
                       friction: float = tol.DEFAULT_FRICTION, change: str | None = None
                       ) -> Figure:
    """The force space of ``before`` and ``after`` (reports of a design and of its changed
    version; ``friction``: the design's mu; ``change``: what changed, for the heading) on
    an Agg canvas: joints left, contacts right.  ValueError when neither report has a
    load case (an unreadable design)."""
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError as error:
        raise ExportUnavailable("matplotlib") from error
    if not before.cases and not after.cases:
        raise ValueError(f"no load case results to plot for {after.design or after.name!r}")

    figure = Figure(figsize=FIGURE_SIZE, dpi=DPI, facecolor="white")
    FigureCanvasAgg(figure)
    joints_axes = figure.add_axes(PANELS[0])
    contacts_axes = figure.add_axes(PANELS[1])
    _draw_joints(joints_axes, before, after)
    _draw_contacts(contacts_axes, before, after, friction)
    name = after.name or before.name
    figure.text(0.01, 0.975, f"{name}: {change}" if change else name, fontsize=FONT + 3,
                weight="bold", va="top", ha="left")
    figure.text(0.01, 0.915, f"before: {_verdict(before)}  ->  after: {_verdict(after)}.  "
                "Force space, each joint and contact at its worst load case: before "
                "(grey rings), after (dots, red when failing).", fontsize=FONT + 1,
                va="top", ha="left", color="0.2")
    return figure


# --- joints -----------------------------------------------------------------------------

def _draw_joints(axes: Axes, before: DesignReport, after: DesignReport) -> None:
    """Joints in (pull / capacity, shear / capacity) space, the durable region shaded."""
    old = _worst_joints(before)
    new = _worst_joints(after)
    ratios = [_ratio(joint) for joint, _ in [*old.values(), *new.values()]]
    left = PRESSED_CLIP - 0.05
    right = max([1.15] + [x + 0.1 for x, _ in ratios])
    top = max([1.15] + [y + 0.1 for _, y in ratios])
    axes.fill_between([left, 1.0], 0.0, 1.0, color=REGION_COLOR, alpha=REGION_ALPHA, lw=0)
    axes.plot([left, 1.0, 1.0], [1.0, 1.0, 0.0], color=REGION_COLOR, lw=1)
    axes.axvline(0.0, color="0.8", lw=0.8, zorder=0)
    _moves(axes, old, new, lambda item: _ratio(item[0]))
    _markers(axes, [_ratio(j) for j, _ in old.values()], [True] * len(old), before=True)
    _markers(axes, [_ratio(j) for j, _ in new.values()],
             [joint.durable for joint, _ in new.values()], before=False)
    _labels(axes, old, new, LABELLED_JOINTS, lambda item: item[0].utilization,
            lambda item: _ratio(item[0]),
            lambda item: f"{'/'.join(item[0].planks)} "
                         f"{plain_number(100 * item[0].utilization, 3)} % ('{item[1]}')")
    axes.set_xlim(left, right)
    axes.set_ylim(-0.05, top)
    axes.set_xlabel("pull / pull capacity, per nail (< 0: pressed)", fontsize=FONT)
    axes.set_ylabel("shear / shear capacity, per nail", fontsize=FONT)
    axes.tick_params(labelsize=FONT)
    axes.set_title(f"joints: {_count_change(old, new)}, shaded: durable", fontsize=FONT + 1)
    if not old and not new:
        _say(axes, "no joint forces")


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

def _draw_contacts(axes: Axes, before: DesignReport, after: DesignReport,
                   friction: float) -> None:
    """Contacts in (N, |T|) space, the friction cone shaded."""
    old = _worst_contacts(before, friction)
    new = _worst_contacts(after, friction)
    points = [_cone_point(c) for c, _ in [*old.values(), *new.values()]]
    span = max([1.0] + [abs(x) for x, _ in points] + [y / friction for _, y in points])
    left = min([-0.08 * span] + [1.08 * x for x, _ in points])
    right, top = 1.08 * span, max([friction * span] + [1.08 * y for _, y in points])
    axes.fill_between([0.0, right], 0.0, [0.0, friction * right], color=REGION_COLOR,
                      alpha=REGION_ALPHA, lw=0)
    axes.plot([0.0, right], [0.0, friction * right], color=REGION_COLOR, lw=1)
    axes.axvspan(left, 0.0, color=LIFT_COLOR, alpha=0.07, lw=0)
    axes.axvline(0.0, color="0.6", lw=0.8, zorder=0)
    _moves(axes, old, new, lambda item: _cone_point(item[0]))
    _markers(axes, [_cone_point(c) for c, _ in old.values()], [True] * len(old), before=True)
    unstable = {case.name for case in after.cases if case.stability != "stable"}
    _markers(axes, [_cone_point(c) for c, _ in new.values()],
             [case not in unstable or _holds(c, friction) for c, case in new.values()],
             before=False)
    _labels(axes, old, new, LABELLED_CONTACTS,
            lambda item: _demand_order(item[0], friction), lambda item: _cone_point(item[0]),
            lambda item: f"{item[0].plank} {_contact_state(item[0], friction)} "
                         f"('{item[1]}')")
    axes.set_xlim(left, right)
    axes.set_ylim(-0.03 * top, top * 1.05)
    axes.set_xlabel("normal force N, newtons (< 0: it would pull: lifts)", fontsize=FONT)
    axes.set_ylabel("friction force |T|, newtons", fontsize=FONT)
    axes.tick_params(labelsize=FONT)
    budget = " -> ".join(_budget(report, friction) for report in (before, after))
    axes.set_title(f"contacts: shaded the friction cone |T| <= mu N, mu = "
                   f"{plain_number(friction)}; friction used {budget}", fontsize=FONT + 1)
    if not old and not new:
        _say(axes, "no contact forces (no equilibrium)")


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


def _budget(report: DesignReport, friction: float) -> str:
    """The worst case's |sum T| / (mu sum N) over ground contacts, as '23 % ('shove')'."""
    worst, name = None, ""
    for case in report.cases:
        ground = [c for c in case.contacts if c.wall is None and c.on is None]
        if not ground:
            continue
        forces = np.array([c.force for c in ground], dtype=float)
        normal = float(forces[:, 2].sum())
        used = math.inf if normal <= 0.0 else \
            float(np.linalg.norm(forces[:, :2].sum(axis=0))) / (friction * normal)
        if worst is None or used > worst:
            worst, name = used, case.name
    if worst is None:
        return "-"
    if not math.isfinite(worst):
        return f"all ('{name}')"
    return f"{100 * worst:.1f} % ('{name}')"


# --- shared -----------------------------------------------------------------------------

def _moves(axes: Axes, old: dict, new: dict, point: Callable) -> None:
    """A grey line from each item's position before to after (one LineCollection)."""
    from matplotlib.collections import LineCollection

    segments = [[point(old[key]), point(new[key])] for key in new if key in old]
    if segments:
        axes.add_collection(LineCollection(segments, colors=BEFORE_COLOR, linewidths=0.7,
                                           zorder=2))


def _markers(axes: Axes, points: list, holds: list[bool], before: bool) -> None:
    """Before: grey rings; after: dots, red where failing."""
    if not points:
        return
    x, y = np.array(points, dtype=float).T
    if before:
        axes.plot(x, y, ls="", marker="o", mfc="none", mec=BEFORE_COLOR, ms=6.5, mew=1.1,
                  zorder=3)
        return
    ok = np.array(holds, dtype=bool)
    axes.plot(x[ok], y[ok], ls="", marker="o", color=AFTER_COLOR, ms=4.5, zorder=4)
    axes.plot(x[~ok], y[~ok], ls="", marker="o", color=FAILING_RGB, ms=5.0, zorder=4)


def _labels(axes: Axes, old: dict, new: dict, count: int, badness: Callable,
            point: Callable, text: Callable) -> None:
    """Label the ``count`` worst items after the change (then those only before),
    stacked by rank with a leader line: items crowd, labels must not."""
    ranked = sorted(new, key=lambda key: -badness(new[key]))
    ranked += sorted((key for key in old if key not in new), key=lambda key: -badness(old[key]))
    for rank, key in enumerate(ranked[:count]):
        item = new.get(key) or old[key]
        axes.annotate(text(item), point(item), xytext=(10, 10 + 12 * rank),
                      textcoords="offset points", fontsize=FONT, zorder=5,
                      arrowprops={"arrowstyle": "-", "color": "0.5", "lw": 0.6,
                                  "shrinkA": 0, "shrinkB": 2})


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


def _say(axes: Axes, text: str) -> None:
    axes.text(0.5, 0.5, text, transform=axes.transAxes, ha="center", va="center",
              color="0.4")
