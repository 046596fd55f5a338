"""Continuous suggestions (paper section 6.4, Algorithm 1): ``ContinuousSearch``.

1. The margins of the invalid design and their rates (``margins``, eq. 6 reusing the
   statics' factorization).
2. Directions of one to M DOFs, culled by the slab test (``candidates``, eq. 10-13).
3. For each direction, nearest first, a line search with the full nonlinear checks: probes
   from the predicted step outward until a valid design is met, then the lower end (the
   smallest change that works) and the upper end (searched up to REACH times the lower
   end), each by regula falsi on the joints' margin, or bisection where that margin is
   not continuous (geometry, toppling, sliding).
4. Ranking by the valid interval and the size of the change; each suggestion's design is
   the middle of its interval (``representative``; ``ranking`` writes and validates it).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from furncheck.design.model import Design
from furncheck.dofs import Blocked, Dof, OutOfReach, all_dofs, structure
from furncheck.geometry import Geometry
from furncheck.neighbourhood import suggestion_dofs
from furncheck.result import DesignReport
from furncheck.suggest.candidates import MAX_STEP, Candidate, candidates
from furncheck.suggest.edits import Editor, utilization_margin
from furncheck.suggest.margins import Margins

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
"""The lower end is bisected to this fraction of the first valid step."""

REACH = 2.0
"""The upper end is searched up to this multiple of the lower end (at most MAX_STEP): the
representative, the middle, is then the smallest change that works plus up to half of it
again -- a reserve, not a redesign (a middle leg 2 mm too long is shortened by 2.2 mm,
not by half its length although that would be valid too)."""

UPPER_RESOLUTION = 0.05
"""The upper end is bisected to this fraction of the lower end."""

INTERPOLATION_GUARD = 0.1
"""Regula falsi probes stay this fraction of the bracket away from its ends."""

MIN_RESOLUTION = 1e-4
"""No end is bisected finer than this (scaled units)."""

LINE_SEARCHES_PER_SUGGESTION = 3
"""At most this many directions are line-searched per wanted suggestion."""


@dataclass(frozen=True)
class Found:
    """A direction with its valid interval of steps, ready to become a suggestion."""

    dofs: tuple[Dof, ...]
    direction: np.ndarray
    low: float
    high: float

    @property
    def score(self) -> float:
        """Bigger is better: the interval's width minus the smallest change it needs."""
        return (self.high - self.low) - self.low


class ContinuousSearch:
    """Algorithm 1 for one invalid design: ``run`` gives the directions found, best
    first; ``representative`` turns one into its design."""

    def __init__(self, design: Design, geometry: Geometry, report: DesignReport,
                 locked: tuple[Dof, ...] = ()):
        self.report = report
        self.editor = Editor(design, geometry, structure(design, _standing(geometry)), locked)
        self.margins = Margins(design, geometry, report, self.editor,
                               suggestion_dofs(design, geometry, report.violations,
                                               [dof for dof in all_dofs(design)
                                                if dof not in locked]))
        self.searched = 0

    @property
    def restores(self) -> tuple[str, ...]:
        return tuple(sorted({m.restores for m in self.margins.violated}))

    def directions(self, max_dofs: int) -> list[Candidate]:
        """The kept directions of 1..max_dofs DOFs, nearest first (``candidates``)."""
        return candidates(self.margins, max_dofs)

    def run(self, directions: list[Candidate], wanted: int) -> list[Found]:
        """Line-search the directions in order until ``wanted`` have a valid interval (at
        most LINE_SEARCHES_PER_SUGGESTION x wanted searches); ranked by score."""
        margins = self.margins
        own_margin = utilization_margin(self.report)
        found: list[Found] = []
        for candidate in directions:
            if len(found) >= wanted or self.searched >= LINE_SEARCHES_PER_SUGGESTION * wanted:
                break
            self.searched += 1
            dofs = tuple(margins.dofs[i] for i in candidate.dofs)
            interval = _line_search(self.editor, dofs, candidate, own_margin)
            if interval is not None:
                found.append(Found(dofs, candidate.direction, *interval))
        found.sort(key=lambda f: (-f.score, len(f.dofs), [d.name for d in f.dofs]))
        return found

    def representative(self, found: Found) -> tuple[Design, float, tuple[float, ...]] | None:
        """The design at the middle of the interval, its step and DOF changes (None if
        that step cannot be made)."""
        step = 0.5 * (found.low + found.high)
        changes = self.editor.changes(found.dofs, found.direction, step)
        try:
            return self.editor.moved(found.dofs, changes), step, changes
        except (Blocked, OutOfReach):
            return None


def _standing(geometry: Geometry) -> Geometry:
    """The geometry without the ground contacts of planks that sink into the ground: such
    a plank does not stand on the floor, it is to be shortened or raised onto it."""
    sunk = {v.where for v in geometry.violations if v.kind == "penetration"}
    if not sunk:
        return geometry
    return replace(geometry, contacts=tuple(c for c in geometry.contacts
                                            if c.plank not in sunk))


def _line_search(editor: Editor, dofs: tuple[Dof, ...], candidate: Candidate,
                 start: float) -> tuple[float, float] | None:
    """The valid interval (low, high) of steps along the candidate's direction nearest its
    predicted step, or None if none is found.  ``start`` is the design's own margin
    (``Editor.margin_at`` at step 0)."""
    direction = candidate.direction

    def margin(step: float) -> float:
        return editor.margin_at(dofs, direction, step)

    found = _first_valid(margin, candidate.enter, start)
    if found is None:
        return None
    below, first = found
    if below[0] == 0.0 and not np.isfinite(below[1]) and \
            candidate.enter * PROBE_BELOW < first[0]:
        guess = (candidate.enter * PROBE_BELOW, margin(candidate.enter * PROBE_BELOW))
        below, first = (below, guess) if guess[1] >= 0.0 else (guess, first)
    low = _boundary(margin, first, below, max(LOWER_RESOLUTION * first[0], MIN_RESOLUTION))
    reach = min(REACH * low, MAX_STEP)
    if reach <= first[0]:
        return low, first[0]
    end = margin(reach)
    if end >= 0.0:
        return low, reach
    return low, _boundary(margin, first, (reach, end),
                          max(UPPER_RESOLUTION * low, MIN_RESOLUTION))


def _first_valid(margin, predicted: float, start: float):
    """Probe outward from the predicted step until a valid step: ((step, margin) of the
    last invalid one, or (0, start); (step, margin) of the valid one), or None when
    MAX_PROBES or MAX_STEP are used up, or the joints' margin stops growing (the linear
    prediction was wrong: a nail count that cannot grow, a load that does not move)."""
    previous = (0.0, start)
    step = min(predicted * FIRST_PROBE, MAX_STEP)
    for _ in range(MAX_PROBES):
        value = margin(step)
        if value >= 0.0:
            return previous, (step, value)
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


def _boundary(margin, good: tuple[float, float], bad: tuple[float, float],
              resolution: float) -> float:
    """Close a bracket of a valid (step, margin) ``good`` and an invalid ``bad`` to
    ``resolution``; returns the valid end.

    Where both margins are finite the next probe is where the straight line through them
    crosses zero (regula falsi), nudged by 0.4 x resolution toward the end that did not
    move last time -- so that a nearly linear margin is bracketed within the resolution in
    two probes -- and kept within the middle 80 % of the bracket so that it always
    shrinks; elsewhere the middle (bisection).
    """
    moved_good = False
    while abs(bad[0] - good[0]) > resolution:
        (g, mg), (b, mb) = good, bad
        if np.isfinite(mb) and mg - mb > 0.0:
            nudge = 0.4 * resolution / abs(b - g)
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
    return good[0]
