"""How far the geometry lets a DOF go, and the plain bracket searches (``ReachSearch``).

The first stage of a side's search (see the package's docstring): the furthest step that
keeps the joints and contacts (``check_edit``, no statics), predicted from the margins of
the geometry check's criteria (``geometry.EditMargins``) and confirmed by geometry checks;
and the doubling and bisection that close a bracket of a valid and an invalid step (of
the geometry alone, or of full checks).  ``RangeFinder`` builds on it.
"""

from __future__ import annotations

from furncheck.design.model import Design
from furncheck.dofs import Dof, OutOfReach
from furncheck.geometry import EditMargins
from furncheck.ranges.batches import Evaluator, _Margins
from furncheck.ranges.estimates import (
    _first_flip,
    _flip_values,
    _flipped,
    _modelled_flip,
    _open_groups,
)

REACH_PREDICTIONS = 4
"""Most predictions of the geometric reach of one side of a DOF before it is bisected."""

ROTATION_WATCH = 15.0
"""Degrees: a rotation's reach is first predicted within this turn, watching only the
faces that so small a turn can bring to rest on one another (far fewer than all); past
it, all of them."""

MARGINS_KEPT = 32
"""How many ``EditMargins`` (with their values for the design) a finder keeps."""

REACH_PROBE = 0.25
"""The margins' slope is taken over this fraction of the resolution."""

REACH_SECANTS = 8
"""Most evaluations of the margins refining a rotation's predicted reach."""

MODEL_OFFSET = 0.2
"""A rotation's margins are evaluated this fraction of the resolution past the modelled
flip (before it, once the last evaluation was flipped): a good model closes the bracket
to half a resolution in two evaluations."""


class ReachSearch(Evaluator):
    """The geometric reach of each side of a DOF and bracket searches, as generators of
    evaluations (``Evaluator._run``).  A subclass gives each DOF's search limit and
    resolution (``_scales``)."""

    def __init__(self, design: Design, locked: tuple[str, ...] = ()):
        super().__init__(design, locked)
        self._margins: dict[tuple, tuple[EditMargins, tuple]] = {}
        self._changes: dict[Dof, tuple[tuple[int, ...], tuple[int, ...]]] = {}

    def _scales(self, dof: Dof) -> tuple[float, float]:
        """(search limit, resolution) of ``dof``: the subclass's."""
        raise NotImplementedError

    def _geometric_reach(self, dof: Dof, sign: float, limit: float, resolution: float) -> float:
        """The furthest step (>= 0) in direction ``sign`` keeping the joints and contacts
        (``check_edit``, no statics), within ``resolution``.

        A rotation is first checked one resolution step out: most turns that change
        anything do so at once.  The margins of the criteria (``EditMargins``) predict
        the step at which the first one flips; two checks confirm it: the step half a
        resolution before is valid, the one half a resolution after is not.  A flip that
        changes nothing (two faces that meet but do not outrank the joint's) is passed and
        the next one predicted; a check failing before the prediction falls back to
        bisection, as does a DOF whose margins cannot be computed.
        """
        good = 0.0
        if dof.is_rotation:     # most turns that part a joint or cut a neighbour do it at once
            if not (yield from self._valid_at(dof, sign * resolution, full=False)):
                return 0.0
            good = resolution
        for _ in range(REACH_PREDICTIONS):
            if good >= limit:
                return limit
            predicted = yield from self._predicted_reach(
                dof, sign, good if good > resolution else 0.0, limit, resolution)
            if predicted is None:
                break
            end = limit if predicted >= limit else predicted - 0.5 * resolution
            if end >= good + 0.5 * resolution:      # else one step past good is past the flip
                if not (yield from self._valid_at(dof, sign * end, full=False)):
                    return (yield from self._bisect(dof, sign, good, end, resolution,
                                                    full=False))
                good = end
            if good >= limit:
                return limit
            beyond = min(good + resolution, limit)
            if not (yield from self._valid_at(dof, sign * beyond, full=False)):
                return good
            good = beyond
        return (yield from self._expand(dof, sign, good, limit, resolution, full=False))

    def _predicted_reach(self, dof: Dof, sign: float, start: float, limit: float,
                         resolution: float) -> float | None:
        """The step (>= ``start``, at most ``limit``) at which the first criterion of
        ``EditMargins`` flips, the margins taken as linear in the step through their
        values at ``start`` and one nearby step; None if an edited design cannot be made.

        A rotation's margins are not linear (a corner's height changes with the cosine of
        the turn): ``_predicted_turn`` refines the prediction on the margins themselves,
        first within ROTATION_WATCH degrees watching only the faces that so small a turn
        can bring to rest on one another, then, if nothing flips there, from that turn on
        watching all of them."""
        try:
            if dof.is_rotation:
                horizons = (ROTATION_WATCH, limit) if start < ROTATION_WATCH < limit \
                    else (limit,)
                for horizon in horizons:
                    predicted = yield from self._predicted_turn(dof, sign, start, horizon,
                                                                resolution)
                    if predicted < horizon:
                        return predicted
                    start = horizon
                return limit
            margins, now = self._edit_margins(dof, 0.0)
            at_start = now if start == 0.0 else \
                (yield _Margins(margins, self._edited(dof, sign * start)))
            step = start + REACH_PROBE * resolution
            at_step = yield _Margins(margins, self._edited(dof, sign * step))
            return _first_flip(at_start, at_step, start, step, limit)
        except OutOfReach:
            return None

    def _predicted_turn(self, dof: Dof, sign: float, start: float, horizon: float,
                        resolution: float) -> float:
        """For a rotation: the turn (>= ``start``) at which the first criterion of
        ``EditMargins`` (faces within ``horizon`` degrees of resting on one another)
        flips, ``horizon`` if none does up to there.

        Every margin is modelled as a quadratic in the turn through three evaluated turns
        (``_modelled_flip``; at first the start, a turn just past it and the linear
        prediction from the slope there), the modelled flip is evaluated a little past
        (or before) itself, so that two good predictions close a bracket of an unflipped
        and a flipped turn to half a resolution; the horizon is evaluated before it is
        returned.  A bracket whose same end moves three times running, or whose flipped
        end is a turn the DOF cannot make, is halved.  At most REACH_SECANTS evaluations: the last
        prediction is returned, to be confirmed."""
        margins, now = self._edit_margins(dof, horizon)
        at_start = now if start == 0.0 else \
            (yield _Margins(margins, self._edited(dof, sign * start)))
        step = start + REACH_PROBE * resolution
        at_step = yield _Margins(margins, self._edited(dof, sign * step))
        closed = _open_groups(at_start)
        samples = [(start, _flip_values(closed, at_start)),
                   (step, _flip_values(closed, at_step))]
        predicted = _first_flip(at_start, at_step, start, step, horizon)
        del at_start, at_step           # kept while the search waits: large for big designs
        low, high, high_made = start, None, True
        offset = MODEL_OFFSET * resolution
        moved = []                      # whether each evaluation moved the flipped end
        for _ in range(REACH_SECANTS):
            try:
                measured = yield _Margins(margins, self._edited(dof, sign * predicted))
                flipped = _flipped(closed, measured)
                samples.append((predicted, _flip_values(closed, measured)))
                made = True
                del measured
            except OutOfReach:          # no such design: past the reach as well
                flipped, made = True, False
            if flipped:
                high, high_made = predicted, made
            elif predicted >= horizon:
                return horizon
            else:
                low = predicted
            moved.append(flipped)
            end = horizon if high is None else high
            if high is not None and high - low <= 0.5 * resolution:
                return high
            if high is not None and (not high_made or moved[-3:] in ([True] * 3,
                                                                    [False] * 3)):
                predicted = 0.5 * (low + high)
                continue
            nearest = sorted(samples, key=lambda sample: min(abs(sample[0] - low),
                                                             abs(sample[0] - end)))[:3]
            modelled = _modelled_flip(nearest, low, end)
            if modelled >= end and high is None:
                predicted = horizon
                continue
            predicted = modelled + (-offset if flipped else offset)
            predicted = min(max(predicted, low + REACH_PROBE * resolution),
                            end - REACH_PROBE * resolution)
        return predicted

    def _edit_margins(self, dof: Dof, turn: float) -> tuple[EditMargins, tuple]:
        """The margins of the planks that ``dof`` changes (one small step either way) for
        steps turning them at most ``turn`` degrees, and their values for the design
        itself.  They depend only on which planks change and turn, so DOFs that change
        the same planks share them (the MARGINS_KEPT used last are kept)."""
        if dof not in self._changes:
            changed, turning = set(), set()
            for sign in (-1.0, 1.0):
                try:
                    edited = self._edited(dof, sign * REACH_PROBE * self._scales(dof)[1])
                except OutOfReach:
                    continue
                for i, (a, b) in enumerate(zip(self.design.planks, edited.planks)):
                    if a != b:
                        changed.add(i)
                    if a.rotation != b.rotation:
                        turning.add(i)
            self._changes[dof] = (tuple(sorted(changed)), tuple(sorted(turning)))
        changed, turning = self._changes[dof]
        key = (changed, turning, turn if turning else 0.0)
        if key in self._margins:
            self._margins[key] = self._margins.pop(key)        # used last
        else:
            margins = EditMargins(self.design, self.geometry, changed, turn, turning)
            if len(self._margins) >= MARGINS_KEPT:
                del self._margins[next(iter(self._margins))]
            self._margins[key] = (margins, margins(self.design))
        return self._margins[key]

    def _expand(self, dof: Dof, sign: float, start: float, limit: float, resolution: float,
                full: bool = True) -> float:
        """From a valid step ``start``, double outward (from limit / 16) until invalid or
        at the limit, then bisect the last bracket; returns the furthest valid step."""
        good, step = start, max(start, limit / 16.0)
        while True:
            if step > good:
                if not (yield from self._valid_at(dof, sign * step, full)):
                    return (yield from self._bisect(dof, sign, good, step, resolution, full))
                good = step
            if good >= limit:
                return limit
            step = min(2.0 * good, limit)

    def _bisect(self, dof: Dof, sign: float, good: float, bad: float,
                resolution: float, full: bool = True) -> float:
        """Close a bracket of a valid step ``good`` and an invalid step ``bad`` (either may
        be the larger) to ``resolution``, or until no float lies between them; returns
        the valid end."""
        while abs(bad - good) > resolution:
            middle = 0.5 * (good + bad)
            if middle == good or middle == bad:     # adjacent floats: closed
                break
            if (yield from self._valid_at(dof, sign * middle, full)):
                good = middle
            else:
                bad = middle
        return good
