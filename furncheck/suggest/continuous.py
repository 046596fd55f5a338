"""Continuous suggestions (paper section 6.4, Algorithm 1): ``ContinuousSearch``.

1. The margins of the invalid design and their rates (``margins``, eq. 6 reusing the
   statics' factorization).
2. Directions of one to M DOFs, culled by the slab test (``candidates``, eq. 10-13); on a
   design with mirror planks (``symmetry``), first the symmetric directions that change
   a mirror pair together (``unit_candidates``), where they are about as near.
3. For each direction, nearest first, a line search with the full nonlinear checks
   (``line_search``): the valid interval of steps, both ends checked.
4. Each suggestion's design is the smallest change that works plus a RESERVE, its
   changes rounded to whole millimetres or half degrees where that is valid too
   (``representatives``, ``shop_round``; ``ranking`` writes, validates and ranks it).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from furncheck.design.model import Design
from furncheck.dofs import Blocked, Dof, OutOfReach, all_dofs, structure
from furncheck.edit_check import standing_geometry
from furncheck.geometry import Geometry
from furncheck.neighbourhood import suggestion_dofs
from furncheck.result import DesignReport
from furncheck.statics import StaticsModel
from furncheck.suggest.candidates import (
    Candidate,
    culled_singles,
    every_candidate,
    same_direction,
    unit_candidates,
)
from furncheck.suggest.edits import Editor, utilization_margin
from furncheck.suggest.line_search import line_search
from furncheck.suggest.margins import Margins
from furncheck.suggest.shop_round import rounded_changes
from furncheck.suggest.symmetry import mirror_planes, symmetric_units
from furncheck.suggest.tried import DirectionTally, LineSearch, ProbeLog

RESERVE = 0.5
"""A suggestion's design is the smallest change that works plus this fraction of it again
(at most the middle of the valid interval): a reserve, not a redesign (a middle leg 2 mm
too long is shortened by 3 mm, not by half its length although that would be valid too)."""

LINE_SEARCHES_PER_SUGGESTION = 3
"""At most this many directions are line-searched per wanted suggestion."""

MAX_SYMMETRIC = 3
"""At most this many symmetric directions are line-searched (before the others)."""

CULLED_SINGLES = 4
"""Where the linearization keeps no direction at all, at most this many single DOFs that
it culled only because another check was predicted to fail first are line-searched,
nearest first (``candidates.culled_singles``): the full checks decide, at the cost of a
few line searches only where nothing else would be."""

SYMMETRIC_REACH = 3.0
"""A symmetric direction is searched first when its predicted step is at most this many
times the nearest direction's (a symmetric fix needs more change: both planks move)."""


@dataclass(frozen=True)
class Found:
    """A direction with its valid interval of steps, ready to become a suggestion."""

    dofs: tuple[Dof, ...]
    direction: np.ndarray
    low: float
    high: float
    limited: bool = False       # high is the search limit (valid; not searched beyond)
    parts: frozenset = frozenset()  # what it changes: its DOFs, a mirror pair as one
    search: int = -1            # its line search's index in ``line_searches``


class ContinuousSearch:
    """Algorithm 1 for one invalid design: ``run`` gives the directions found, in the
    order searched; ``representative`` turns one into its design."""

    def __init__(self, design: Design, geometry: Geometry, report: DesignReport,
                 locked: tuple[Dof, ...] = (), model: StaticsModel | None = None,
                 solved: dict | None = None):
        """``model``, ``solved``: the design's statics model and its cases' statics by
        name (``check.check_design``), if the caller has them."""
        self.report = report
        frame = structure(design, standing_geometry(geometry))
        starts = None if solved is None or any(case.name not in solved
                                               for case in design.load_cases) \
            else tuple(solved[case.name] for case in design.load_cases)
        self.editor = Editor(design, geometry, frame, locked, starts)
        unlocked = [dof for dof in all_dofs(design) if dof not in locked]
        near = suggestion_dofs(design, geometry, report.violations, unlocked)
        self.far = len(unlocked) - len(near)        # left out of a big design's search
        self.margins = Margins(design, geometry, report, self.editor, near, model, solved)
        self.planes = mirror_planes(design)
        self.searched = 0
        self.tally: list[DirectionTally] = []       # what ``directions`` formed
        self.line_searches: list[LineSearch] = []   # what ``run`` searched
        self.unsearched = 0                         # kept directions ``run`` left
        self.culled_searched = 0                    # ``directions``' fallback, searched
        self._culled: set[int] = set()              # (its candidates' ids)

    @property
    def restores(self) -> tuple[str, ...]:
        return tuple(sorted({m.restores for m in self.margins.violated}))

    def directions(self, max_dofs: int) -> list[Candidate]:
        """The kept directions of 1..max_dofs DOFs, nearest first (``candidates``), after
        at most MAX_SYMMETRIC symmetric ones within SYMMETRIC_REACH of the nearest; where
        none is kept (but for mirror pairs culled alike), at most CULLED_SINGLES single
        DOFs culled only as breaking another check first (``candidates.culled_singles``;
        ``run`` counts those it searches in ``culled_searched``)."""
        self.tally.clear()
        self.culled_searched, self._culled = 0, set()
        found = every_candidate(self.margins, max_dofs, self.tally)
        symmetric: list[Candidate] = []
        if self.planes:
            units = symmetric_units(self.margins.design, self.planes, self.margins.dofs)
            reach = SYMMETRIC_REACH * found[0].enter if found else np.inf
            symmetric = [c for c in unit_candidates(self.margins, units, max_dofs)
                         if c.enter <= reach][:MAX_SYMMETRIC]
        if not found:               # none kept: one DOF alone too, for the full checks
            found = culled_singles(self.margins)[:CULLED_SINGLES]
            self._culled = {id(c) for c in found}
        return symmetric + [c for c in found
                            if not any(same_direction(c, s) for s in symmetric)]

    def run(self, directions: list[Candidate], wanted: int) -> list[Found]:
        """Line-search the directions in order until ``wanted`` have a valid interval (at
        most LINE_SEARCHES_PER_SUGGESTION x wanted searches).  A direction whose DOFs
        contain those of another with a valid interval is not one of them, a mirror pair
        changed together counting as one (a suggestion never changes a DOF it does not
        need: ``candidates`` skips such combinations as the linearization predicts them,
        this where the full checks found them; a bench's legs moved apart together are
        not dropped for one leg moved alone, which breaks the mirror)."""
        margins = self.margins
        own_margin = utilization_margin(self.report)
        found: list[Found] = []
        for index, candidate in enumerate(directions):
            if len(found) >= wanted or self.searched >= LINE_SEARCHES_PER_SUGGESTION * wanted:
                self.unsearched = len(directions) - index
                break
            self.searched += 1
            self.culled_searched += id(candidate) in self._culled
            dofs = tuple(margins.dofs[i] for i in candidate.dofs)
            probes: list[tuple[float, float]] = []
            interval = line_search(ProbeLog(self.editor, probes), dofs, candidate, own_margin)
            self.line_searches.append(LineSearch(
                tuple(d.name for d in dofs), self.editor.changes(dofs, candidate.direction, 1.0),
                candidate.enter, tuple(probes),
                None if interval is None else (interval.low, interval.high),
                tuple(d.unit(self.editor.design) for d in dofs)))
            parts = frozenset(frozenset(margins.dofs[i] for i in group)
                              for group in candidate.units) if candidate.units \
                else frozenset(frozenset((dof,)) for dof in dofs)
            if interval is None:
                continue
            search = len(self.line_searches) - 1
            smaller = next((f for f in found if f.parts < parts), None)
            if smaller is not None:
                self._contains(search, smaller.search)
                continue
            for bigger in [f for f in found if parts < f.parts]:
                self._contains(bigger.search, search)
            found = [f for f in found if not parts < f.parts]
            found.append(Found(dofs, candidate.direction, interval.low, interval.high,
                               interval.limited, parts, search))
        return found

    def _contains(self, search: int, smaller: int) -> None:
        """Mark line search ``search`` as left out for the smaller direction found by line
        search ``smaller`` (indices into ``line_searches``)."""
        self.line_searches[search] = replace(self.line_searches[search],
                                             contains=self.line_searches[smaller].dofs)

    def representatives(self, found: Found) -> list[tuple[Design, float, tuple[float, ...]]]:
        """The designs that may stand for ``found``, to be validated in order (the first
        valid one is the suggestion): its changes at the step RESERVE past the interval's
        lower end (at most its middle) rounded to the shop's grid
        (``shop_round.rounded_changes``), then those changes exact; each with its step and
        DOF changes (none whose changes cannot be made)."""
        step = representative_step(found.low, found.high)
        changes = self.editor.changes(found.dofs, found.direction, step)
        rates = self.editor.changes(found.dofs, found.direction, 1.0)
        units = tuple(dof.unit(self.editor.design) for dof in found.dofs)
        tried = [*rounded_changes(changes, units, rates, found.low, found.high),
                 (step, changes)]
        out = []
        for at, amounts in tried:
            try:
                out.append((self.editor.moved(found.dofs, amounts), at, amounts))
            except (Blocked, OutOfReach):
                continue
        return out


def representative_step(low: float, high: float) -> float:
    """The step of a suggestion's design in its valid interval low .. high."""
    return min((1.0 + RESERVE) * low, 0.5 * (low + high))
