"""Continuous suggestions (paper section 6.4, Algorithm 1): ``suggest_design``.

1. The margins of the invalid design and their rates (``margins``, eq. 6 reusing the
   statics' factorization).
2. Directions of one to M DOFs, culled by the slab test (``candidates``, eq. 10-13).
3. For each direction, nearest first, a line search with the full nonlinear checks: probes
   from the predicted step outward until a valid design is met, then the lower end (the
   smallest change that works) and the upper end (searched up to REACH times the lower
   end), each by regula falsi on the joints' margin, or bisection where that margin is
   not continuous (geometry, toppling, sliding).
4. Ranking by the valid interval and the size of the change; each suggestion's design is
   the middle of its interval, written as a design file and validated from that text --
   a representative that does not validate is dropped, never listed.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from furncheck.check import check_design
from furncheck.design.load import parse_design
from furncheck.design.model import Design
from furncheck.design.write import design_text
from furncheck.dofs import Blocked, Dof, OutOfReach, all_dofs, structure
from furncheck.geometry import Geometry, analyze
from furncheck.result import DesignReport
from furncheck.suggest.candidates import MAX_STEP, Candidate, candidates
from furncheck.suggest.edits import Editor
from furncheck.suggest.margins import Margins

PROBES = (1.05, 1.4, 2.0, 3.0)
"""Steps tried first, as multiples of the predicted step (the linear prediction is rarely
far off; when it is, MAX_STEP is tried last)."""

PROBE_BELOW = 0.85
"""When the first probe is valid, this multiple of the prediction is tried to bracket the
lower end tightly."""

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
class Suggestion:
    """One ranked continuous suggestion.

    dofs      : DOF names; ``direction`` (unit, scaled units) over them
    range     : (low, high) valid steps along the direction, scaled units
    step      : the representative step (middle of ``range``)
    changes   : each DOF's change at ``step``, its own unit (file length unit or degrees)
    restores  : the kinds of violation it removes ('durability', 'stability', 'geometry')
    design    : the representative design; ``text`` its YAML file, validated;
                ``report`` its validation
    """

    rank: int
    kind: str
    restores: tuple[str, ...]
    dofs: tuple[str, ...]
    direction: tuple[float, ...]
    range: tuple[float, float]
    step: float
    changes: tuple[float, ...]
    units: tuple[str, ...]
    design: Design
    text: str
    report: DesignReport


@dataclass(frozen=True)
class SuggestionReport:
    """Everything ``furncheck suggest`` says about one design."""

    design: str
    name: str
    report: DesignReport
    suggestions: tuple[Suggestion, ...]
    searched: int = 0          # directions line-searched
    checks: int = 0            # full validity checks made
    seconds: dict[str, float] = field(default_factory=dict, compare=False)
    """Wall time of the phases ('candidates': margins, sensitivities and directions;
    'line search': line searches and representatives), for benchmarks; never reported."""

    @property
    def valid(self) -> bool:
        return bool(self.report.valid)


@dataclass(frozen=True)
class _Found:
    candidate: Candidate
    low: float
    high: float

    @property
    def score(self) -> float:
        """Bigger is better: the interval's width minus the smallest change it needs."""
        return (self.high - self.low) - self.low


def suggest_design(design: Design, max_dofs: int = 3, max_suggestions: int = 8,
                   locked: tuple[Dof, ...] = ()) -> SuggestionReport:
    """Ranked continuous suggestions for ``design`` (none when it is valid already)."""
    geometry = analyze(design)
    report = check_design(design, geometry)
    if report.valid or max_suggestions <= 0:
        return SuggestionReport(design.source, design.name, report, ())
    start = time.perf_counter()
    editor = Editor(design, geometry, structure(design, _standing(geometry)), locked)
    margins = Margins(design, geometry, report, editor,
                      [dof for dof in all_dofs(design) if dof not in locked])
    directions = candidates(margins, max_dofs)
    searching = time.perf_counter()
    found: list[_Found] = []
    budget = LINE_SEARCHES_PER_SUGGESTION * max_suggestions
    searched = 0
    for candidate in directions:
        if len(found) >= max_suggestions or searched >= budget:
            break
        searched += 1
        interval = _line_search(editor, _dofs(margins, candidate), candidate)
        if interval is not None:
            found.append(_Found(candidate, *interval))
    found.sort(key=lambda f: (-f.score, len(f.candidate.dofs), f.candidate.dofs))
    restores = tuple(sorted({m.restores for m in margins.violated}))
    suggestions: list[Suggestion] = []
    for item in found:
        suggestion = _representative(editor, margins, item, len(suggestions) + 1, restores)
        if suggestion is not None:
            suggestions.append(suggestion)
    end = time.perf_counter()
    return SuggestionReport(design.source, design.name, report, tuple(suggestions), searched,
                            editor.checks, {"candidates": searching - start,
                                            "line search": end - searching})


def _standing(geometry: Geometry) -> Geometry:
    """The geometry without the ground contacts of planks that sink into the ground: such
    a plank does not stand on the floor, it is to be shortened or raised onto it."""
    sunk = {v.where for v in geometry.violations if v.kind == "penetration"}
    if not sunk:
        return geometry
    return replace(geometry, contacts=tuple(c for c in geometry.contacts
                                            if c.plank not in sunk))


def _dofs(margins: Margins, candidate: Candidate) -> tuple[Dof, ...]:
    return tuple(margins.dofs[i] for i in candidate.dofs)


def _line_search(editor: Editor, dofs: tuple[Dof, ...],
                 candidate: Candidate) -> tuple[float, float] | None:
    """The valid interval (low, high) of steps along the candidate's direction nearest its
    predicted step, or None if no probe is valid."""
    direction = candidate.direction

    def margin(step: float) -> float:
        return editor.margin_at(dofs, direction, step)

    probes = sorted({min(candidate.enter * factor, MAX_STEP) for factor in PROBES} | {MAX_STEP})
    below, first = (0.0, -np.inf), None
    for step in probes:
        value = margin(step)
        if value >= 0.0:
            first = (step, value)
            break
        below = (step, value)
    if first is None:
        return None
    if below[0] == 0.0 and candidate.enter * PROBE_BELOW < first[0]:
        guess = candidate.enter * PROBE_BELOW
        value = margin(guess)
        if value >= 0.0:
            first = (guess, value)
        else:
            below = (guess, value)
    low = _boundary(margin, first, below, max(LOWER_RESOLUTION * first[0], MIN_RESOLUTION))
    reach = min(REACH * low, MAX_STEP)
    if reach <= first[0]:
        return low, first[0]
    end = margin(reach)
    if end >= 0.0:
        return low, reach
    return low, _boundary(margin, first, (reach, end),
                          max(UPPER_RESOLUTION * low, MIN_RESOLUTION))


def _boundary(margin, good: tuple[float, float], bad: tuple[float, float],
              resolution: float) -> float:
    """Close a bracket of a valid (step, margin) ``good`` and an invalid ``bad`` to
    ``resolution``; returns the valid end.  Where both margins are finite the next probe
    is where the straight line through them crosses zero (regula falsi), kept within the
    middle 80 % of the bracket so that it always shrinks; else the middle."""
    while abs(bad[0] - good[0]) > resolution:
        (g, mg), (b, mb) = good, bad
        if np.isfinite(mb) and mg - mb > 0.0:
            fraction = min(max(mg / (mg - mb), INTERPOLATION_GUARD), 1.0 - INTERPOLATION_GUARD)
        else:
            fraction = 0.5
        step = g + fraction * (b - g)
        value = margin(step)
        if value >= 0.0:
            good = (step, value)
        else:
            bad = (step, value)
    return good[0]


def _representative(editor: Editor, margins: Margins, found: _Found, rank: int,
                    restores: tuple[str, ...]) -> Suggestion | None:
    """The suggestion's design at the middle of its interval, written and validated from
    its own text; None if that text does not validate (the contract's promise)."""
    candidate = found.candidate
    dofs = _dofs(margins, candidate)
    step = 0.5 * (found.low + found.high)
    changes = editor.changes(dofs, candidate.direction, step)
    try:
        moved = editor.moved(dofs, changes)
    except (Blocked, OutOfReach):
        return None
    design = editor.design
    name = f"{design.name}-suggestion-{rank:02d}"
    text = design_text(_renamed(moved, name), "yaml")
    written = parse_design(text, f"suggestion-{rank:02d}.yaml", "yaml")
    geometry = editor.keeps(written)
    report = None if geometry is None else check_design(written, geometry)
    if report is None or not report.valid:
        return None
    return Suggestion(rank, "continuous", restores, tuple(d.name for d in dofs),
                      tuple(float(v) for v in candidate.direction), (found.low, found.high),
                      step, changes, tuple(d.unit(design) for d in dofs), written, text,
                      report)


def _renamed(design: Design, name: str) -> Design:
    return replace(design, name=name)
