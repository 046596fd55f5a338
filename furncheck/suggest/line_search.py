"""The valid interval of steps along one direction (paper 6.4: "a bisection search along
the direction using all the nonlinear constraints"): ``line_search``.

Every probe is a full check of the design moved that far (``Editor.margin_at``: >= 0
exactly when it is valid and keeps its joints).  From the step predicted by the linearized
margins, probes go outward until one is valid; then

* the lower end (the smallest change that works) is closed to LOWER_RESOLUTION of itself
  (at least MIN_RESOLUTION), against the invalid probe below it (or the design itself);
  a geometric repair's window found at the aim (``_first_valid``), twice the tolerance
  wide, has both ends closed to WINDOW_TOLERANCE of the tolerance in every length DOF
  where that is finer;
* the upper end is searched to where validity really ends, not to a multiple of the lower
  end: the step where the edit's geometry stops being the design's (a plank's size
  reaching zero, an end face leaving the face it is nailed to, two planks meeting) is
  predicted from the edit's geometric margins (``geometry.EditMargins``, linear in the
  step for moves and size changes) and checked just before (valid) and just after
  (invalid); when that prediction is missing or wrong, the probes double outward.  The
  bracket of a valid and an invalid step is closed to UPPER_RESOLUTION of the lower end.
  A direction still valid at MAX_STEP ends there: ``Interval.limited`` says so (the
  search stopped at its limit, not at an invalid step).

Both ends are thus valid steps with an invalid step at most one resolution beyond them
(or, for the upper end, the search limit).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from furncheck.dofs import Blocked, Dof, OutOfReach
from furncheck.geometry import EditMargins
from furncheck.ranges.estimates import _first_flip
from furncheck.ranges.nearest import window_resolution
from furncheck.suggest.candidates import MAX_STEP, Candidate
from furncheck.suggest.edits import Editor

FIRST_PROBE = 1.05
"""The first step tried, as a multiple of the predicted step (the linear prediction is
rarely far off)."""

MAX_PROBES = 5
"""Steps tried before a direction is given up."""

GROWTH = (1.2, 1.5, 3.0)
"""Each further probe is at least the first, at most the last factor times the previous
one: the secant's crossing of the joints' margin where it is continuous, else the
middle factor."""

PROBE_BELOW = 0.85
"""When the first probe is valid and nothing below it is known, this multiple of the
prediction is tried to bracket the lower end tightly."""

LOWER_RESOLUTION = 0.02
"""The lower end is closed to this fraction of itself."""

UPPER_RESOLUTION = 0.05
"""The upper end is closed to this fraction of the lower end."""

OUTWARD = 2.0
"""Past the last valid step, the upper end is looked for this many times further out."""

INTERPOLATION_GUARD = 0.1
"""Regula falsi probes stay this fraction of the bracket away from its ends."""

MIN_RESOLUTION = 1e-4
"""No end is closed finer than this (scaled units)."""

REACH_PROBE = 0.97
"""Where the probes from the predicted step find nothing, one more probe at this fraction
of the edit's geometric reach (the step where it stops keeping the geometry of a design
that stands as drawn: a leg moved off the end of the seat it holds; ``_before_reach``):
a valid window can only lie before it, and the probes may have stepped over it."""


@dataclass(frozen=True)
class Interval:
    """The valid steps along a direction: low .. high (scaled units); ``limited``: high
    is the search limit MAX_STEP, valid itself (nothing beyond it was searched)."""

    low: float
    high: float
    limited: bool = False


def line_search(editor: Editor, dofs: tuple[Dof, ...], candidate: Candidate,
                start: float) -> Interval | None:
    """The valid interval of steps along the candidate's direction nearest its predicted
    step, or None if none is found.  ``start`` is the design's own margin
    (``Editor.margin_at`` at step 0)."""
    direction = candidate.direction

    def margin(step: float) -> float:
        return editor.margin_at(dofs, direction, step)

    probed: list[tuple[float, float]] = []
    found = _first_valid(margin, candidate.enter, start, candidate.aim, probed)
    if found is None and not editor.geometry.violations:
        found = _before_reach(editor, dofs, direction, margin, candidate.enter, start,
                              all(value == -math.inf for _, value in probed))
    if found is None:
        return None
    below, first, *beyond = found
    if below[0] == 0.0 and not np.isfinite(below[1]) and \
            candidate.enter * PROBE_BELOW < first[0]:
        guess = (candidate.enter * PROBE_BELOW, margin(candidate.enter * PROBE_BELOW))
        below, first = (below, guess) if guess[1] >= 0.0 else (guess, first)
    if beyond:                  # the probe past the valid one closes the bracket
        *upper, window = beyond[0]
        fine = _tolerance_step(editor, dofs, direction) if window else math.inf
        low = _boundary(margin, first, below, min(LOWER_RESOLUTION, fine / first[0]))
        resolution = min(max(UPPER_RESOLUTION * low[0], MIN_RESOLUTION), fine)
        return Interval(low[0], _boundary(margin, first, tuple(upper), resolution)[0])
    low = _boundary(margin, first, below, LOWER_RESOLUTION)
    resolution = max(UPPER_RESOLUTION * low[0], MIN_RESOLUTION)
    reach = _geometric_reach(editor, dofs, direction, low[0], max(first[0], low[0] + resolution))
    high, limited = _upper_end(margin, first, reach, resolution)
    return Interval(low[0], high, limited)


def _first_valid(margin, predicted: float, start: float, aim: float = math.inf,
                 probed: list | None = None):
    """Probe outward from the predicted step until a valid step: ((step, margin) of the
    last invalid one, or (0, start); (step, margin) of the valid one), or None when
    MAX_PROBES or MAX_STEP are used up, or the joints' margin stops growing (the linear
    prediction was wrong: a nail count that cannot grow, a load that does not move).

    Where the first probe fails outright (margin -inf) and the candidate's ``aim`` (the
    least-squares step toward the violated margins' targets) lies between the
    prediction and that probe, the aim is tried next: a geometric repair is valid only
    within the tolerance on either side of closing its gap (a board 94 mm above the
    floor stands on it when lowered by 93.5 to 94.5 mm, tolerance 0.5 mm), a window that
    FIRST_PROBE's overshoot of the prediction (its near edge) steps over, and every probe
    further out cuts the plank into the floor.  A valid aim comes back with that first
    probe as a third item, (step, margin, True): invalid, beyond the valid one
    (``line_search`` brackets the upper end with it, to the window's resolution).  So
    does the predicted step itself, tried where the first probe fails with a finite
    margin, with (step, margin, False) (bracketed to the usual resolution): the valid
    interval may end between the prediction and its overshoot (a stool's leg moved
    toward the other until the stool balances on it, where that leg bends as a
    cantilever: valid to 176 mm, predicted 169, first probed at 177), and probes further
    out would only step away from it.  ``probed``: a list to which every (step, margin)
    probed is added."""
    previous = (0.0, start)
    step = min(predicted * FIRST_PROBE, MAX_STEP)
    probed = [] if probed is None else probed
    for probe in range(MAX_PROBES):
        value = margin(step)
        probed.append((step, value))
        if value >= 0.0:
            return previous, (step, value)
        if probe == 0 and value == -math.inf and predicted <= aim < step:
            aimed = margin(aim)
            if aimed >= 0.0:
                return previous, (aim, aimed), (step, value, True)
        if probe == 0 and np.isfinite(value) and predicted < step:
            at = margin(predicted)      # the overshoot may have stepped past the window
            probed.append((predicted, at))
            if at >= 0.0:
                return previous, (predicted, at), (step, value, False)
            if start == -math.inf and np.isfinite(at):
                found = _past_failing(margin, predicted, probed)
                if found is not None:
                    return (*found, (predicted, at, False))
        if step >= MAX_STEP:
            return None
        growth = GROWTH[1]
        if np.isfinite(value) and np.isfinite(previous[1]):
            if value <= previous[1]:
                return None
            crossing = step - value * (step - previous[0]) / (value - previous[1])
            growth = min(max(crossing * FIRST_PROBE / step, GROWTH[0]), GROWTH[2])
        previous, step = (step, value), min(step * growth, MAX_STEP)
    return None


def _past_failing(margin, high: float, probed: list):
    """Where the design fails outright (margin -inf: it topples, slides or loses a
    joint) and the prediction ``high`` fails by a finite margin (the violation repaired
    before it, another check failing there: a bench's legs moved apart hold it up, and
    the seat they span sags), the steps just past the repair, before the other check
    fails too: the first step with a finite margin, bisected between 0 and ``high`` to
    LOWER_RESOLUTION of itself; ((step, -inf) of the last failing one, (step, margin) of
    a valid one) as ``_first_valid`` returns them, or None where none is valid (the
    other check fails as soon as the repair holds).  (The bench-tips bench in the
    elastic model: its legs moved apart hold it from 230 mm, its seat sags past its
    limit beyond 254 mm; predicted 281, where the seat sags.)"""
    low = 0.0
    while high - low > max(LOWER_RESOLUTION * high, MIN_RESOLUTION):
        middle = 0.5 * (low + high)
        value = margin(middle)
        probed.append((middle, value))
        if value >= 0.0:
            return (low, -math.inf), (middle, value)
        if value == -math.inf:
            low = middle
        else:
            high = middle
    return None


def _before_reach(editor: Editor, dofs: tuple[Dof, ...], direction: np.ndarray, margin,
                  predicted: float, start: float, toppling: bool = False):
    """``_first_valid``'s result from a probe at REACH_PROBE of the edit's geometric reach
    (``_flip``, what the design has lost), or None: a design that topples has margin
    -inf until the window, so probes past the reach (a leg moved off the end of the seat
    it holds) cannot find it.  Probed where the first probe already lay past the reach,
    or where every probe (``toppling``) read -inf, whose growth may have stepped over the
    window (a bench's legs moved apart, tipping at each probe below the window, 214 to
    300 mm, then off the seat's ends past it); not where the margins were finite, whose
    secant aims at the window (a cantilever shelf that sags, shortened: the probe at the
    reach would offer a shelf cut to a 9 mm stub)."""
    first = min(predicted * FIRST_PROBE, MAX_STEP)
    reach = _flip(editor, dofs, direction, 0.0, first, kept_only=True)
    if reach is None or (reach >= first and not toppling):
        return None
    step = REACH_PROBE * reach
    value = margin(step)
    return ((0.0, start), (step, value)) if value >= 0.0 else None


def _tolerance_step(editor: Editor, dofs: tuple[Dof, ...], direction: np.ndarray) -> float:
    """The step (scaled units) along ``direction`` in which no length DOF changes by more
    than WINDOW_TOLERANCE of the design's tolerance (inf for a direction of turns alone):
    the resolution of a geometric repair's window, twice the tolerance wide (an L drawn
    50 mm up stands on the floor lowered by 49.5 to 50.5 mm; closed to 2 % of the step,
    its ends read "50 mm only")."""
    per_step = [abs(change) for dof, change in zip(dofs, editor.changes(dofs, direction, 1.0))
                if not dof.is_rotation and change != 0.0]
    if not per_step:
        return math.inf
    return max(window_resolution(editor.design) / max(per_step), MIN_RESOLUTION)


def _geometric_reach(editor: Editor, dofs: tuple[Dof, ...], direction: np.ndarray,
                     low: float, step: float) -> float | None:
    """The step at which the edit along ``direction`` is predicted to stop keeping the
    design's geometry, from the edit's geometric margins at two valid steps ``low`` and
    ``step`` (linear in the step for moves and size changes; None for a direction that
    turns a plank, or when the edits cannot be made or nothing flips before MAX_STEP),
    when that lies beyond ``step``."""
    reach = _flip(editor, dofs, direction, low, step)
    return reach if reach is not None and step < reach else None


def _flip(editor: Editor, dofs: tuple[Dof, ...], direction: np.ndarray, low: float,
          step: float, kept_only: bool = False) -> float | None:
    """``_geometric_reach`` from the margins at ``low`` and ``step``, wherever it lies
    after ``low`` (None for a turn, an edit that cannot be made, or no flip before
    MAX_STEP); ``kept_only``: where a criterion the design passes stops passing (a joint's
    end leaving its face, a size reaching zero, a corner reaching the floor), the
    forbidden groups left out (planks coming to meet or cut into each other: the full
    check sees those)."""
    if any(dof.is_rotation for dof in dofs) or step <= low:
        return None
    try:
        at_low = editor.moved(dofs, editor.changes(dofs, direction, low))
        at_step = editor.moved(dofs, editor.changes(dofs, direction, step))
    except (Blocked, OutOfReach):
        return None
    design = editor.design
    changed = tuple(i for i, (a, b) in enumerate(zip(design.planks, at_step.planks)) if a != b)
    if not changed:
        return None
    margins = EditMargins(design, editor.geometry, changed, 0.0, ())
    (required, forbidden), (required_at, forbidden_at) = margins(at_low), margins(at_step)
    kept = required > 0.0           # a criterion the valid edit already passes otherwise
    groups = slice(0, 0) if kept_only else slice(None)
    reach = _first_flip((required[kept], forbidden[groups]),
                        (required_at[kept], forbidden_at[groups]), low, step, MAX_STEP)
    return reach if low < reach < MAX_STEP else None


def _upper_end(margin, good: tuple[float, float], reach: float | None,
               resolution: float) -> tuple[float, bool]:
    """The furthest valid step beyond the valid ``good`` (step, margin): (step, whether
    it is the search limit MAX_STEP).  The predicted geometric ``reach`` is checked first
    (half a resolution before it, then half after), else the probes go OUTWARD times
    further each; the last bracket is closed by ``_boundary``."""
    if reach is not None and reach - 0.5 * resolution > good[0]:
        before = reach - 0.5 * resolution
        value = margin(before)
        if value < 0.0:
            return _boundary(margin, good, (before, value), resolution)[0], False
        good = (before, value)
        after = min(reach + 0.5 * resolution, MAX_STEP)
        value = margin(after)
        if value < 0.0:
            return good[0], False
        good = (after, value)
    while good[0] < MAX_STEP:
        step = min(OUTWARD * good[0], MAX_STEP)
        value = margin(step)
        if value < 0.0:
            return _boundary(margin, good, (step, value), resolution)[0], False
        good = (step, value)
    return good[0], True


def _boundary(margin, good: tuple[float, float], bad: tuple[float, float],
              resolution: float) -> tuple[float, float]:
    """Close a bracket of a valid (step, margin) ``good`` and an invalid ``bad`` to
    ``resolution`` (below the valid end: the lower end, to ``resolution`` times the valid
    step, at least MIN_RESOLUTION; above it: the upper end, to ``resolution`` itself);
    returns the valid end (step, margin).

    Where both margins are finite the next probe is where the straight line through them
    crosses zero (regula falsi), nudged by 0.4 x resolution toward the end that did not
    move last time -- so that a nearly linear margin is bracketed within the resolution in
    two probes -- and kept within the middle 80 % of the bracket so that it always
    shrinks; elsewhere the middle (bisection).
    """
    relative = bad[0] < good[0]

    def width() -> float:
        return max(resolution * good[0], MIN_RESOLUTION) if relative else resolution

    moved_good = False
    while abs(bad[0] - good[0]) > width():
        (g, mg), (b, mb) = good, bad
        if math.isfinite(mb) and mg - mb > 0.0:
            nudge = 0.4 * width() / abs(b - g)
            fraction = mg / (mg - mb) + (nudge if moved_good else -nudge)
            fraction = min(max(fraction, INTERPOLATION_GUARD), 1.0 - INTERPOLATION_GUARD)
        else:
            fraction = 0.5
        step = g + fraction * (b - g)
        value = margin(step)
        moved_good = value >= 0.0
        if moved_good:
            good = (step, value)
        else:
            bad = (step, value)
    return good
