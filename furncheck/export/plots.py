"""The force-space view of a design change (paper section 6.2 and Figure 11), as one PNG.

The paper judges validity in force space: a design is durable when every joint's nail
forces lie inside the capacity box and stable when every ground contact's normal force is
non-negative.  The figure has one row per load case and two panels per row:

    durability  every nail joint at (pull / pull capacity, shear / shear capacity), per
                nail.  Shaded: the durable region, pull <= capacity and shear <= capacity
                (contract section 3; a pressed joint, pull < 0, never fails, so the region
                runs left to the edge and pressing beyond ``PRESSED_CLIP`` is drawn there).
                Grey rings are the joints before the change, dots after, red when the joint
                fails; an arrow joins the two positions of a joint present in both
                (matched by its pair of planks); the worst few joints are labelled 'a/b'.
    stability   every ground contact's normal force before (grey, hatched red when
                negative) and after (blue, red when negative) the change, with the zero
                line: below it the contact would have to pull on the ground, so the design
                lifts there.  Contacts are matched by plank and their order on it.

Figures are built with matplotlib's object API on an Agg canvas (no pyplot, no global
backend switch) and written without a software version, so the same reports always give
the same bytes with one matplotlib installation.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable, Iterable
from pathlib import Path
from typing import TYPE_CHECKING, TypeVar

from furncheck.export.errors import ExportUnavailable
from furncheck.result import NOT_SOLVED, CaseResult, ContactResult, DesignReport, JointResult

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

PRESSED_CLIP = -1.0
"""Lowest pull ratio drawn: a joint pressed harder than one nail's pull capacity is drawn
at this value (pressing never breaks a nail joint; its amount would only squash the view)."""
LABELLED_JOINTS = 3
"""How many joints, worst utilization (before or after) first, are labelled 'a/b'."""
MIN_ARROW = 1e-3
"""Shortest move (in capacity ratios) drawn as an arrow; a joint that moves less shows
just its two markers on top of each other."""
FIGURE_WIDTH = 12.0      # inches
ROW_HEIGHT = 3.8         # inches per load case
DPI = 100
PNG_METADATA = {"Software": None}
"""PNG text chunks: matplotlib writes its version as 'Software' unless told not to."""

BEFORE_COLOR = "0.55"
AFTER_COLOR = "tab:blue"
FAILING_COLOR = "tab:red"
REGION_COLOR = "tab:green"
REGION_ALPHA = 0.15
LIFTING_BEFORE = {"edgecolor": FAILING_COLOR, "hatch": "///"}
"""How a contact that lifted before the change is drawn: a grey bar hatched in red."""

Item = TypeVar("Item")


def plot_force_space(before: DesignReport, after: DesignReport, path: Path) -> str:
    """Draw ``force_space_figure(before, after)`` into the PNG ``path``; return the path
    as a string.  The same reports always give the same bytes."""
    figure = force_space_figure(before, after)
    figure.savefig(path, format="png", dpi=DPI, metadata=PNG_METADATA)
    return str(path)


def force_space_figure(before: DesignReport, after: DesignReport) -> Figure:
    """The force space of ``before`` and ``after`` (reports of a design and of its changed
    version): one row per load case, durability left, stability right, on an Agg canvas.

    Load cases are drawn in the order of ``before``, then those only ``after`` has.
    ValueError when neither report has a load case (an unreadable design).
    """
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError as error:
        raise ExportUnavailable("matplotlib") from error

    names = [case.name for case in before.cases]
    names += [case.name for case in after.cases if case.name not in names]
    if not names:
        raise ValueError(f"no load case results to plot for {after.design or after.name!r}")
    old_cases = {case.name: case for case in before.cases}
    new_cases = {case.name: case for case in after.cases}
    design_name = after.name or before.name

    figure = Figure(figsize=(FIGURE_WIDTH, ROW_HEIGHT * len(names)), dpi=DPI,
                    layout="constrained")
    FigureCanvasAgg(figure)
    rows = figure.subplots(len(names), 2, squeeze=False)
    for (durability, stability), name in zip(rows, names):
        old, new = old_cases.get(name), new_cases.get(name)
        durability.set_title(f"case '{name}': durability ({_durability_change(old, new)})")
        _draw_durability(durability, old, new)
        stability.set_title(f"case '{name}': stability ({_stability_change(old, new)})")
        _draw_stability(stability, old, new)
    figure.suptitle(f"{design_name}: force space before (grey) and after the change")
    figure.legend(handles=_legend_handles(), loc="outside lower center", ncols=7)
    return figure


def _draw_durability(axes: Axes, before: CaseResult | None, after: CaseResult | None) -> None:
    """Joints in (pull / capacity, shear / capacity) space, the durable region shaded."""
    old = _keyed(before.joints if before else (), _joint_key)
    new = _keyed(after.joints if after else (), _joint_key)
    keys = [*new, *(key for key in old if key not in new)]
    left = PRESSED_CLIP - 0.05
    ratios = [_ratio(joint) for joint in [*old.values(), *new.values()]]
    right = max([1.15] + [x + 0.1 for x, _ in ratios])
    top = max([1.15] + [y + 0.1 for _, y in ratios])

    axes.fill_between([left, 1.0], 0.0, 1.0, color=REGION_COLOR, alpha=REGION_ALPHA, lw=0)
    axes.plot([left, 1.0, 1.0], [1.0, 1.0, 0.0], color=REGION_COLOR, lw=1)
    axes.axvline(0.0, color="0.8", lw=0.8, zorder=0)
    for key in keys:
        if key in old and key in new:
            start, end = _ratio(old[key]), _ratio(new[key])
            if max(abs(end[0] - start[0]), abs(end[1] - start[1])) >= MIN_ARROW:
                axes.annotate("", xy=end, xytext=start, zorder=2,
                              arrowprops={"arrowstyle": "->", "color": BEFORE_COLOR,
                                          "shrinkA": 3, "shrinkB": 3})
    _scatter(axes, list(old.values()), before=True)
    _scatter(axes, list(new.values()), before=False)

    worst = sorted(keys, key=lambda key: -max(
        joint.utilization for joint in (old.get(key), new.get(key)) if joint is not None))
    for rank, key in enumerate(worst[:LABELLED_JOINTS]):
        joint = new.get(key) or old[key]
        # Stacked by rank with a leader line: joints crowd near zero shear, labels must not.
        axes.annotate("/".join(joint.planks), _ratio(joint), xytext=(8, 8 + 11 * rank),
                      textcoords="offset points", fontsize=8, zorder=5,
                      arrowprops={"arrowstyle": "-", "color": "0.5", "lw": 0.6,
                                  "shrinkA": 0, "shrinkB": 2})

    axes.set_xlim(left, right)
    axes.set_ylim(-0.05, top)
    axes.set_xlabel("pull / pull capacity, per nail (< 0: pressed)")
    axes.set_ylabel("shear / shear capacity, per nail")
    if not keys:
        _say(axes, "no joint forces")


def _scatter(axes: Axes, joints: list[JointResult], before: bool) -> None:
    """Before: rings (red when failing); after: dots (red when failing)."""
    if not joints:
        return
    x, y = zip(*(_ratio(joint) for joint in joints))
    ok = BEFORE_COLOR if before else AFTER_COLOR
    colors = [ok if joint.durable else FAILING_COLOR for joint in joints]
    if before:
        axes.scatter(x, y, s=40, facecolors="none", edgecolors=colors, lw=1.2, zorder=3)
    else:
        axes.scatter(x, y, s=22, color=colors, zorder=4)


def _draw_stability(axes: Axes, before: CaseResult | None, after: CaseResult | None) -> None:
    """Normal force of each ground or wall contact before and after, as paired bars."""
    old = _keyed(before.contacts if before else (), _contact_key)
    new = _keyed(after.contacts if after else (), _contact_key)
    keys = [*new, *(key for key in old if key not in new)]
    width = 0.4
    for position, key in enumerate(keys):
        if key in old:
            normal = old[key].pressing
            axes.bar(position - width / 2, normal, width, color=BEFORE_COLOR,
                     **({} if normal >= 0.0 else LIFTING_BEFORE))
        if key in new:
            normal = new[key].pressing
            axes.bar(position + width / 2, normal, width,
                     color=AFTER_COLOR if normal >= 0.0 else FAILING_COLOR)
    axes.axhline(0.0, color="black", lw=0.8)
    axes.set_xticks(range(len(keys)), [f"{plank} {index + 1}" for plank, index in keys],
                    rotation=90, fontsize=7)
    axes.set_xlim(-0.75, max(len(keys), 1) - 0.25)
    axes.set_ylabel("ground normal force, N (< 0: lifts)")
    if not keys:
        _say(axes, "no contact forces (no equilibrium)")


def _durability_change(before: CaseResult | None, after: CaseResult | None) -> str:
    return " -> ".join("-" if case is None else NOT_SOLVED if case.stability == NOT_SOLVED
                       else "durable" if case.durable else "not durable"
                       for case in (before, after))


def _stability_change(before: CaseResult | None, after: CaseResult | None) -> str:
    return " -> ".join("-" if case is None else case.stability for case in (before, after))


def _ratio(joint: JointResult) -> tuple[float, float]:
    """(pull / pull capacity clipped at PRESSED_CLIP, shear / shear capacity)."""
    return (max(joint.pull / joint.pull_capacity, PRESSED_CLIP),
            joint.shear / joint.shear_capacity)


def _joint_key(joint: JointResult) -> Hashable:
    """A joint is the same joint after a change when it joins the same two planks, in
    whichever order they are listed."""
    return tuple(sorted(joint.planks))


def _contact_key(contact: ContactResult) -> Hashable:
    """Contacts are matched by their plank (and, through ``_keyed``, their order on it):
    their points move with the plank when the design changes."""
    return contact.plank


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


def _legend_handles() -> list:
    """Proxy artists for the figure's one legend (the same in every row)."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    return [
        Line2D([], [], ls="", marker="o", mfc="none", mec=BEFORE_COLOR, label="joint before"),
        Line2D([], [], ls="", marker="o", color=AFTER_COLOR, label="joint after"),
        Line2D([], [], ls="", marker="o", color=FAILING_COLOR, label="joint fails"),
        Patch(color=REGION_COLOR, alpha=REGION_ALPHA, label="durable region"),
        Patch(color=BEFORE_COLOR, label="contact before"),
        Patch(color=AFTER_COLOR, label="contact after"),
        Patch(color=FAILING_COLOR, label="contact lifts"),
    ]
