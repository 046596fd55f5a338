"""What ``suggest`` tried, as values: the record that ``explain`` turns into words when
the search comes back with no suggestion, or fewer than asked for.

Each part of the search appends to its own list while it runs, and nothing else:

* ``candidates`` one ``DirectionTally`` per number of DOFs combined (paper eq. 10-13:
  how many combinations were formed, kept, and culled for which reason);
* ``continuous`` one ``LineSearch`` per direction searched with the full checks (its
  probes are recorded by ``ProbeLog`` around the editor, so the search itself is
  unchanged);
* every discrete rule one ``Trial`` per candidate it built or ruled out (rule, what it
  was for, outcome, reason).  A new rule appends its own ``Trial`` values: the explanation
  and the reports list whatever is there.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from furncheck.design.model import Design

FOUND = "found"
"""``Trial.outcome`` of a candidate that works (it becomes a suggestion)."""
FAILED = "failed"
"""``Trial.outcome`` of a candidate built and checked, or ruled out by its geometry."""
NOT_APPLICABLE = "not applicable"
"""``Trial.outcome`` of a rule that does not apply to the design's violations."""


@dataclass(frozen=True)
class DirectionTally:
    """The combinations of ``size`` DOFs formed by ``candidates`` and what became of them.

    relevant    : DOFs that move the violated margins enough to be combined
    possible    : C(relevant, size)
    evaluated   : formed and tested (the others contain a smaller combination that works)
    kept        : directions along which the slab test reaches the valid region
    facing_away : culled: a violated margin does not grow along the direction
    breaks_other : culled: another margin fails before the violated ones are restored
    too_far     : culled: the valid region is beyond MAX_STEP along it
    """

    size: int
    relevant: int
    possible: int
    evaluated: int
    kept: int
    facing_away: int
    breaks_other: int
    too_far: int


@dataclass(frozen=True)
class LineSearch:
    """One direction line-searched with the full checks.

    dofs      : DOF names
    changes   : each DOF's change (its unit) per scaled step 1 along the direction
    predicted : the step (scaled units) at which the linearized margins are restored
    probes    : ((step, margin), ...) in the order evaluated; margin ``Editor.margin_at``
                (>= 0 valid, -inf where the step breaks a joint, cuts a plank, or the
                design topples or slides)
    interval  : (low, high) valid steps found, or None
    units     : each DOF's unit ('mm', 'm' or 'deg')
    verdict   : for a failed search that ``explain`` looked into: what fails at its best
                probe, in words ('' otherwise)
    contains  : for a search with an interval that is not a suggestion: the DOFs of the
                smaller direction, also valid, whose changes it contains (() otherwise)
    """

    dofs: tuple[str, ...]
    changes: tuple[float, ...]
    predicted: float
    probes: tuple[tuple[float, float], ...]
    interval: tuple[float, float] | None
    units: tuple[str, ...] = ()
    verdict: str = ""
    contains: tuple[str, ...] = ()

    @property
    def outcome(self) -> str:
        return FOUND if self.interval is not None else FAILED

    @property
    def furthest(self) -> float:
        """The largest step probed (scaled units), 0 if none."""
        return max((step for step, _ in self.probes), default=0.0)

    @property
    def looked_at(self) -> float | None:
        """The step whose design tells most about the failure: the best finite probe,
        else the one nearest the prediction (the first, or a geometric repair's aim just
        before it; ``line_search._first_valid``); None without probes."""
        best = self.best
        if best is not None:
            return best[0]
        return min((step for step, _ in self.probes),
                   key=lambda step: abs(step - self.predicted), default=None)

    @property
    def best(self) -> tuple[float, float] | None:
        """(step, margin) of the probe nearest validity: the largest finite margin, None
        when every probe was -inf."""
        finite = [probe for probe in self.probes if math.isfinite(probe[1])]
        return max(finite, key=lambda probe: (probe[1], -probe[0])) if finite else None


@dataclass(frozen=True)
class Trial:
    """One candidate of a discrete rule, or a rule that does not apply.

    rule      : 'support plank', 'stiffening rail', ... (the rule's name in the reports)
    target    : what it was for: a failing joint 'a/b' or plank; '' for the whole design
    outcome   : FOUND, FAILED or NOT_APPLICABLE
    reason    : words, with the numbers that decided it ('' for FOUND)
    plank     : the plank it would add, as the advice names it ('' when none was built)
    candidate : the design with it, kept when its checks failed, so that ``explain`` can
                name the violation that remains (never reported itself)
    """

    rule: str
    target: str
    outcome: str
    reason: str = ""
    plank: str = ""
    candidate: Design | None = field(default=None, compare=False, repr=False)


@dataclass(frozen=True)
class Tried:
    """Everything the search tried for one design.

    dofs        : the design's DOFs (8 per plank)
    free        : DOFs that could be part of a suggestion
    locked      : DOFs locked by ``--lock``
    blocked     : DOF name -> why it cannot move on its own (not locked)
    max_dofs    : the most DOFs combined
    wanted      : the most suggestions asked for (K)
    geometric   : whether the violations were geometric (only geometric repairs tried)
    directions  : per number of DOFs combined
    line_searches : in the order searched
    search_limit : the most line searches allowed (LINE_SEARCHES_PER_SUGGESTION x K)
    unsearched  : kept directions left unsearched (limit reached or enough found)
    dropped     : intervals found whose middle design's file was not valid or could
                  not be made
    discrete    : every discrete rule's trials, in the order tried
    far         : DOFs left out as far from the violations (a design of more than
                  SUGGEST_ALL_PLANKS planks changes only the planks nearest them,
                  ``neighbourhood``)
    culled_searched : single DOFs line-searched though the slab test culled them as
                  breaking another check first, no direction being kept at all
                  (``continuous.CULLED_SINGLES``)
    """

    dofs: int
    free: int
    locked: int
    blocked: dict[str, str]
    max_dofs: int
    wanted: int
    geometric: bool
    directions: tuple[DirectionTally, ...]
    line_searches: tuple[LineSearch, ...]
    search_limit: int
    unsearched: int
    dropped: int
    discrete: tuple[Trial, ...]
    far: int = 0
    culled_searched: int = 0    # single DOFs searched though culled (none kept at all)


class ProbeLog:
    """An ``Editor`` that records every ``margin_at`` it answers as (step, margin) in
    ``probes``; everything else is the editor's."""

    def __init__(self, editor, probes: list[tuple[float, float]]):
        self._editor = editor
        self._probes = probes

    def margin_at(self, dofs, direction: np.ndarray, step: float) -> float:
        value = self._editor.margin_at(dofs, direction, step)
        self._probes.append((float(step), float(value)))
        return value

    def __getattr__(self, name: str):
        return getattr(self._editor, name)
