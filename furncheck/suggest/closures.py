"""Near misses closed along the continuous search's directions and finished with thicker
boards: ``finished_closures``.

A design drawn with a gap (a shelf 3 mm short of the side it should be nailed to) whose
boards also sag (elastic model) gets no continuous suggestion: every direction that
closes the gap leaves the 12 mm boards sagging, so no line search finds a valid step,
and ``reconnect`` closes the gap one way, at the plank that misses.  The directions the
line searches tried are the other ways a maker closes it (the sides moved closer, either
side moved, the shelf lengthened).  Each, at its line search's first probe (the step the
linearized margins predict, times FIRST_PROBE), whose design keeps its geometry (the
continuous suggestions' rule: every joint kept, only the missed ones added) and fails only
by planks that bend too much, is finished by the thicker rule (``thicker.finish``) and is a
fix when that is valid.  Its changes are rounded to the shop's grid first
(``shop_round``: 1.5 mm each rather than 1.31), the exact ones kept where no rounding
closes it.  A closure that changes only the planks ``reconnect`` moves is
left to it.
"""

from __future__ import annotations

from dataclasses import dataclass

from furncheck.check import check_design
from furncheck.design.model import Design
from furncheck.dofs import Blocked, Dof, OutOfReach
from furncheck.result import DesignReport
from furncheck.suggest.candidates import MAX_STEP, Candidate
from furncheck.suggest.continuous import ContinuousSearch
from furncheck.suggest.discrete.common import BENDING, Search
from furncheck.suggest.discrete.growth import cut_phrase
from furncheck.suggest.discrete.reconnect import RECONNECT
from furncheck.suggest.discrete.thicker import finish, thickness_phrase
from furncheck.suggest.line_search import FIRST_PROBE
from furncheck.suggest.shop_round import rounded_changes
from furncheck.suggest.tried import FAILED, FOUND, Trial


@dataclass(frozen=True)
class Closure:
    """A near miss closed along a direction, with the planks it then needs thicker.

    dofs, changes : the DOFs and their changes (their units) that close it
    design        : the closed design with the thicker planks; ``report`` its validation
    advice        : 'make shelf 18 mm thick (now 12 mm) and ...' (the change itself is
                    said in shop words by the report, from ``dofs`` and ``changes``)
    """

    dofs: tuple[Dof, ...]
    changes: tuple[float, ...]
    design: Design
    report: DesignReport
    advice: str


def finished_closures(search: ContinuousSearch, directions: list[Candidate],
                      discrete: Search, moved_by_reconnect: set[str]) -> list[Closure]:
    """The closures of the module docstring, in the order the directions were searched
    (the first ``search.searched`` of ``directions``); each one tried is recorded in
    ``discrete.trials``."""
    closures: list[Closure] = []
    for candidate in directions[:search.searched]:
        dofs = tuple(search.margins.dofs[i] for i in candidate.dofs)
        target = " + ".join(dof.name for dof in dofs)
        if {dof.plank for dof in dofs} == moved_by_reconnect:
            continue
        step = min(candidate.enter * FIRST_PROBE, MAX_STEP)
        changes = search.editor.changes(dofs, candidate.direction, step)
        rates = search.editor.changes(dofs, candidate.direction, 1.0)
        units = tuple(dof.unit(discrete.design) for dof in dofs)
        closed = None
        for _, amounts in [*rounded_changes(changes, units, rates, 0.0, MAX_STEP),
                           (step, changes)]:
            tried = _closed(search, discrete, dofs, amounts)
            if isinstance(tried, tuple):            # closed and finished: the fix
                closed = tried
                break
            if tried is _NOT_FINISHED:              # closed, not finished: try on
                closed = _NOT_FINISHED
        if closed is None:
            continue
        if closed is _NOT_FINISHED:
            discrete.trials.append(Trial(RECONNECT, target, FAILED, "closed along the "
                                         "direction: no thicker boards (up to 44 mm) make "
                                         "it valid"))
            continue
        amounts, design, valid_report, thickened, cut = closed
        discrete.trials.append(Trial(RECONNECT, target, FOUND))
        closures.append(Closure(dofs, amounts, design, valid_report,
                                f"{thickness_phrase(thickened, discrete.design)}{cut}."))
    return closures


_NOT_FINISHED = object()
"""``_closed``'s answer for a closed design that no thicker boards make valid."""


def _closed(search: ContinuousSearch, discrete: Search, dofs: tuple[Dof, ...],
            changes: tuple[float, ...]):
    """The design closed by ``changes`` and finished with thicker boards: (changes, design,
    report, the planks thickened, the planks cut to make room for them in words,
    ``cut_phrase``); _NOT_FINISHED if it keeps its geometry and fails only
    by bending but no thicker boards make it valid; None if it is no closure (a change
    that cannot be made, a geometry not kept, valid already, or another violation)."""
    try:
        edited = search.editor.moved(dofs, changes)
    except (Blocked, OutOfReach):
        return None
    geometry = search.editor.keeps(edited)
    if geometry is None or geometry.violations:
        return None
    report = check_design(edited, geometry)
    if report.valid or not all(v.kind in BENDING for v in report.violations):
        return None
    finished = finish(discrete, edited, geometry, report)
    if finished is None:
        return _NOT_FINISHED
    return (tuple(changes), *finished, cut_phrase(edited, finished[0]))
