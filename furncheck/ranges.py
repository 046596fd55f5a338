"""Valid ranges of design DOFs (paper section 6.3).

For one DOF, the others held (its neighbours adjusted by the geometric constraints of
``dofs``), the valid range is the interval of values around the current one for which the
design stays valid: every joint durable, stable in every load case, the same joints and
ground contacts.  Each side is searched in two stages:

* how far the geometry reaches (the same joints and contacts, ``check_edit``): the margins
  of its criteria (``geometry.EditMargins``; linear in the step for translations and size
  changes) predict the first one to flip, and two geometry checks confirm it, one half a
  resolution before (valid) and one half after (not); a rotation's prediction is refined
  on its margins first; a wrong prediction falls back to bisection;
* if the design is not valid at that reach, the physical limit inside it: a bracket of
  one valid and one invalid value is closed to ``RANGE_RESOLUTION``, every probe a full
  check of the edited design.  The probes go where validity is likely to change: just
  past the step where a loaded joint loses a nail (found from the joint's length, without
  statics), else at the force sensitivity's prediction (eq. 6) of where the first joint
  reaches its nail capacity or the first contact lets go, else at the zero of the
  design's margin interpolated through the probes; bisection where these do not halve
  the bracket.

The reported end is the last value found valid (by a full check); a value at most one
resolution step beyond it was found invalid (or the end is the search limit).

Each side's search is a generator: it yields the evaluations it needs (``_Kept``: an edit
and its geometry check; ``_Margins``: geometric margins of an edit; ``_Statics``: a full
check) and receives their results.  ``RangeFinder._run`` advances the searches of all
DOFs together, and every round answers the evaluations they wait for as one batch: the
geometry checks and the margins of all of them in one vectorized pass each
(``dofs.check_edit_many``, ``geometry.edit_margins_many``).  No search depends on
another's results, so the ranges are the same however the DOFs are batched.
"""

from __future__ import annotations

import multiprocessing
from collections.abc import Generator
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from furncheck.check import check_design, holding_states, is_valid, margin_of
from furncheck.design.model import Design
from furncheck.dofs import (
    DOF_KINDS,
    Blocked,
    Dof,
    OutOfReach,
    Structure,
    all_dofs,
    apply_dof,
    check_edit_many,
    design_size,
    dof_value,
    parse_dof,
    structure,
)
from furncheck.geometry import EditMargins, Geometry, analyze, edit_margins_many, follow_many
from furncheck.sensitivity import Linearization, Sensitivity
from furncheck.tolerances import NAIL_COUNT_EPS
from furncheck.validity import nail_pull_shear

RANGE_RESOLUTION = 1e-3
"""Bisection stops when the bracket is this fraction of the design's size (lengths) or
this many degrees x 100 (rotations: 0.1 degree)."""

SEARCH_LIMIT = 1.0
"""How far a range is searched: this fraction of the design's size for lengths, x 90
degrees for rotations."""

PAST_ESTIMATE = 0.45
"""A physical-limit probe goes this fraction of the resolution past the estimated step
where validity changes (a lost nail, or the margin's zero): when the estimate is right,
that probe and one the same distance before it close the bracket."""

INSIDE_BRACKET = 0.05
"""Probes stay this fraction of the resolution inside the bracket, so each one narrows it."""

DROP_RESOLUTION = 0.1
"""The step at which a joint loses a nail is found to this fraction of the resolution."""

DROP_STEPS = 6
"""Most geometry evaluations finding the step at which a joint loses a nail."""

PARALLEL_MIN_DOFS = 16
"""Fewer DOFs than this are searched in this process: starting workers would cost more."""

DOFS_PER_TASK = 16
"""DOFs per task of a worker process: a task's DOFs are searched together (the more, the
larger the batches of evaluations); small tasks balance the uneven DOFs."""

SEARCHES_IN_FLIGHT = 64
"""Most searches (sides of DOFs) advanced together: their evaluations are batched, their
edits kept while they run."""

MARGIN_ROWS = 1 << 14
"""Most rows of geometric margins evaluated in one batch (each row 18 margins)."""

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

MODEL_GRID = 64
"""The modelled margins are scanned for their first flip on this many turns, twice (the
second time within the first scan's step)."""


@dataclass(frozen=True)
class DofRange:
    """The valid interval of one DOF (absolute values, file unit or degrees), or None with
    the reason it cannot move or has no valid value within the search limit."""

    dof: str
    value: float
    valid: tuple[float, float] | None
    unit: str
    reason: str | None = None


class RangeFinder:
    """Valid ranges of the DOFs of one design, sharing its analysis and linearizations."""

    def __init__(self, design: Design, locked: tuple[str, ...] = ()):
        self.design = design
        self.geometry: Geometry = analyze(design)
        self.frame: Structure = structure(design, self.geometry)
        self.locked = tuple(parse_dof(design, name) for name in locked)
        self.valid_now = check_design(design, self.geometry).valid
        self.starts = holding_states(design, self.geometry)
        _, self.margin_now, self.utilization_now = margin_of(design, self.geometry,
                                                             self.starts)
        self.size = design_size(design)
        self._joint_index = {(j.face, j.edge, j.edge_face): n
                             for n, j in enumerate(self.geometry.joints)}
        self._linear: list[Linearization] | None = None
        self._shared: dict = {}
        self._predictions: dict[Dof, tuple[float | None, float | None]] = {}
        self._margins: dict[tuple, tuple[EditMargins, tuple]] = {}
        self._changes: dict[Dof, tuple[tuple[int, ...], tuple[int, ...]]] = {}
        self._kept: dict[Dof, dict[float, tuple]] = {}
        self._edits: dict[Dof, dict[float, Design]] = {}
        self.evaluations = 0

    # -- public --------------------------------------------------------------------------------
    def ranges(self, names: list[str] | None = None, jobs: int = 1) -> list[DofRange]:
        """The ranges of the named DOFs (all when None), in order.  With ``jobs`` > 1 the
        DOFs are shared among that many worker processes; every DOF's search is independent
        of the others, so the result is the same either way.

        One process is the default: the statics' small dense solves gain nothing from a
        multi-threaded BLAS, but its threads spin on the cores that the workers need
        (2 workers on 2 cores run twice as fast as one process only with
        OPENBLAS_NUM_THREADS=1; with threaded BLAS they are slower than one process)."""
        dofs = all_dofs(self.design) if names is None else \
            [parse_dof(self.design, name) for name in names]
        if jobs > 1 and len(dofs) >= PARALLEL_MIN_DOFS:
            found = self._ranges_in_workers(dofs, jobs)
            if found is not None:
                return found
        return self._ranges_together(dofs)

    def range(self, dof: Dof) -> DofRange:
        return self._ranges_together([dof])[0]

    def _ranges_in_workers(self, dofs: list[Dof], jobs: int) -> list[DofRange] | None:
        """The ranges of ``dofs`` in forked worker processes (which inherit this finder):
        tasks of at most DOFS_PER_TASK DOFs, at least two per worker, the DOFs of each kind
        dealt out in turn (DOFs of one kind are alike in cost: rotations cost most); None
        when processes cannot be forked here."""
        global _WORKER_FINDER
        try:
            context = multiprocessing.get_context("fork")
        except ValueError:          # no fork on this platform
            return None
        count = min(len(dofs), max(2 * jobs, -(-len(dofs) // DOFS_PER_TASK)))
        order = sorted(range(len(dofs)), key=lambda n: (DOF_KINDS.index(dofs[n].kind), n))
        shares = [order[k::count] for k in range(count)]
        _WORKER_FINDER = self
        try:
            with ProcessPoolExecutor(max_workers=min(jobs, count),
                                     mp_context=context) as pool:
                done = list(pool.map(_ranges_of, [[dofs[n] for n in share]
                                                  for share in shares]))
        except (OSError, BrokenProcessPool):
            return None
        finally:
            _WORKER_FINDER = None
        self.evaluations += sum(evaluations for _, evaluations in done)
        found: list[DofRange | None] = [None] * len(dofs)
        for share, (ranges, _) in zip(shares, done):
            for n, dof_range in zip(share, ranges):
                found[n] = dof_range
        return found

    def _ranges_together(self, dofs: list[Dof]) -> list[DofRange]:
        """The ranges of ``dofs``, all their searches advanced together (``_run``): each
        side of each DOF is a generator of the evaluations it needs, and the evaluations
        that the searches wait for at one time are made as one batch."""
        searches: dict[tuple[int, float], Generator] = {}
        for n, dof in enumerate(dofs):
            if dof in self.locked:
                continue
            value, unit = dof_value(self.design, dof), dof.unit(self.design)
            limit, resolution = self._scales(dof)
            if self.valid_now:
                searches[(n, -1.0)] = self._side(dof, -1.0, limit, resolution)
                searches[(n, 1.0)] = self._side(dof, 1.0, limit, resolution)
            else:
                searches[(n, 0.0)] = self._nearest_valid(dof, value, unit, limit, resolution)
        found = self._run(searches, dofs)
        out = []
        for n, dof in enumerate(dofs):
            value, unit = dof_value(self.design, dof), dof.unit(self.design)
            if dof in self.locked:
                out.append(DofRange(dof.name, value, None, unit, "locked"))
                continue
            ends = [found[(n, sign)] for sign in ((-1.0, 1.0) if self.valid_now else (0.0,))]
            blocked = [end for end in ends if isinstance(end, Blocked)]
            if blocked:
                out.append(DofRange(dof.name, value, None, unit, blocked[0].reason))
            elif self.valid_now:
                out.append(DofRange(dof.name, value, (value - ends[0], value + ends[1]), unit))
            else:
                out.append(ends[0])
        return out

    # -- running searches ----------------------------------------------------------------------
    def _run(self, searches: dict[tuple[int, float], Generator],
             dofs: list[Dof]) -> dict[tuple[int, float], object]:
        """Advance the ``searches`` ((DOF number, side) -> generator) until each returns or
        raises Blocked: every round, the evaluations they all wait for (``_Kept``,
        ``_Margins``, ``_Statics``) are made together (``_answer``) and sent back; at most
        SEARCHES_IN_FLIGHT run at a time (the others start as they end).  Once
        the lower side of a DOF is blocked its upper side is dropped (the lower side's
        reason is reported, as when the sides are searched one after the other).  A DOF's
        cached edits are dropped when its last search ends."""
        found: dict[tuple[int, float], object] = {}
        waiting: dict[tuple[int, float], object] = {}
        active = {dof: 0 for dof in dofs}
        for n, _ in searches:
            active[dofs[n]] += 1
        queued = list(searches)[::-1]

        def ended(key: tuple[int, float], result: object) -> None:
            found[key] = result
            dof = dofs[key[0]]
            active[dof] -= 1
            if not active[dof]:
                self._edits.pop(dof, None)
                self._kept.pop(dof, None)

        def advance(key: tuple[int, float], answer: tuple) -> None:
            value, error = answer
            try:
                request = searches[key].send(value) if error is None else \
                    searches[key].throw(error)
            except StopIteration as stop:
                ended(key, stop.value)
            except Blocked as why:
                ended(key, why)
                upper = (key[0], 1.0)
                if key[1] < 0.0 and upper in waiting:
                    searches[upper].close()
                    del waiting[upper]
                    ended(upper, None)
            else:
                waiting[key] = request

        while waiting or queued:
            while queued and len(waiting) < SEARCHES_IN_FLIGHT:
                advance(queued.pop(), (None, None))
            batch, waiting = waiting, {}
            for key, answer in zip(batch, self._answer(list(batch.values()))):
                advance(key, answer)
        return found

    def _now(self, search: Generator, dof: Dof):
        """Run one search (a generator of evaluations) of ``dof`` to its end: its result."""
        return self._run({(0, 0.0): search}, [dof])[(0, 0.0)]

    def _answer(self, requests: list) -> list[tuple[object, Exception | None]]:
        """(value, error) per request: ``_Kept`` checks all at once
        (``dofs.check_edit_many``), ``_Margins`` all at once (``geometry.edit_margins_many``),
        then ``_Statics`` one by one."""
        answers: list = [None] * len(requests)
        kept = [k for k, request in enumerate(requests) if isinstance(request, _Kept)]
        for k, answer in zip(kept, self._kept_many([requests[k] for k in kept])):
            answers[k] = answer
        measured = [k for k, request in enumerate(requests) if isinstance(request, _Margins)]
        while measured:         # at most MARGIN_ROWS rows at a time (memory)
            rows = np.cumsum([len(requests[k].margins.edge) for k in measured])
            count = max(1, int(np.searchsorted(rows, MARGIN_ROWS, side="right")))
            chunk, measured = measured[:count], measured[count:]
            for k, values in zip(chunk, edit_margins_many([requests[k] for k in chunk])):
                answers[k] = (values, None)
        for k, request in enumerate(requests):
            if isinstance(request, _Statics):
                if request.margin:
                    answers[k] = (margin_of(request.design, request.geometry, self.starts),
                                  None)
                else:
                    answers[k] = (is_valid(request.design, request.geometry, self.starts),
                                  None)
        return answers

    def _kept_many(self, requests: list[_Kept]) -> list[tuple[object, Exception | None]]:
        """Per request: the design with its DOF changed by its step and the geometry if
        it keeps the joints and ground contacts, else (None, None); Blocked as the error
        if the step would change a locked DOF.  Answers are kept per DOF (while its
        search runs): the full check of a geometric reach follows the geometry check
        that found it."""
        answers: list = [None] * len(requests)
        todo = []
        for k, (dof, step) in enumerate(requests):
            known = self._kept.setdefault(dof, {})
            if step in known:
                answers[k] = (known[step], None)
                continue
            try:
                edited = apply_dof(self.design, self.frame, dof, step)
            except OutOfReach:
                known[step] = (None, None)
                answers[k] = (known[step], None)
                continue
            except Blocked as why:
                answers[k] = (None, why)
                continue
            moved_lock = next((lock for lock in self.locked if abs(
                dof_value(edited, lock) - dof_value(self.design, lock)) > 1e-9), None)
            if moved_lock is not None:
                answers[k] = (None, Blocked(f"it would change the locked {moved_lock.name}"))
                continue
            todo.append((k, dof, step, edited))
        self.evaluations += len(todo)
        checks = check_edit_many(self.geometry, [edited for *_, edited in todo], self.design)
        for (k, dof, step, edited), (problem, geometry) in zip(todo, checks):
            self._kept[dof][step] = (None, None) if problem is not None else (edited, geometry)
            answers[k] = (self._kept[dof][step], None)
        return answers

    # -- validity of one step (searches: generators of evaluations) ---------------------------
    def _valid_at(self, dof: Dof, step: float, full: bool = True):
        """Whether the design with ``dof`` changed by ``step`` keeps its joints and ground
        contacts and (``full``) is valid in every load case."""
        edited, geometry = yield _Kept(dof, step)
        if geometry is None:
            return False
        if not full:
            return True
        return (yield _Statics(edited, geometry, False))

    def _probe(self, dof: Dof, sign: float, step: float):
        """The full check of one step (>= 0) in direction ``sign``, with the design's
        margin (``check.margin_of``): a ``_Probe``."""
        edited, geometry = yield _Kept(dof, sign * step)
        if geometry is None:
            return _Probe(step, False, -np.inf, None, None)
        valid, margin, utilization = yield _Statics(edited, geometry, True)
        return _Probe(step, valid, margin, utilization, geometry)

    # -- searches ------------------------------------------------------------------------------
    def _side(self, dof: Dof, sign: float, limit: float, resolution: float) -> float:
        """The furthest step (>= 0) in direction ``sign`` up to which the design was found
        valid, assuming it is valid now: first how far the geometry reaches (cheap checks
        without statics), then, if the design is not valid there, the physical limit inside
        it (``_physical_limit``)."""
        reach = yield from self._geometric_reach(dof, sign, limit, resolution)
        if reach <= 0.0:
            return reach
        at_reach = yield from self._probe(dof, sign, reach)
        if at_reach.valid:
            return reach
        return (yield from self._physical_limit(dof, sign, at_reach, resolution))

    def _physical_limit(self, dof: Dof, sign: float, at_reach: _Probe,
                        resolution: float) -> float:
        """The furthest valid step below the geometric reach, where the design is not
        valid, to ``resolution``: a bracket of a valid and an invalid step (full checks)
        is narrowed by probes placed where validity is likely to change.

        The margin (``check.margin_of``) is continuous in the step except where a joint
        gets shorter than its nail count's length (one nail fewer: every nail of it
        carries more) or a case stops being stable.  Where the bracket's two geometries
        differ in a joint's nails, the step at which it loses a nail is found from its
        length alone (``_nail_drops``, ``_drop_step``: no statics) and the probe goes just
        past that step, or just before it once the invalid end is there; elsewhere the
        sensitivity's prediction (eq. 6) is tried first, then the margin's zero
        interpolated through the probes (``_margin_zero``), each probe a little past the
        estimated zero towards the end that has not moved (two good estimates close the
        bracket); bisection when the bracket did not halve in three probes or the margin
        is -inf.
        """
        good = _Probe(0.0, True, self.margin_now, self.utilization_now, self.geometry)
        bad = at_reach
        predicted = self._predicted(dof)[0 if sign < 0 else 1]
        spacing = self.design.material.nail_spacing
        widths, moves, probes = [bad.step], [], [good, bad]
        while bad.step - good.step > resolution:
            low = good.step + INSIDE_BRACKET * resolution
            high = bad.step - INSIDE_BRACKET * resolution
            past = PAST_ESTIMATE * resolution
            drops = _nail_drops(good, bad, spacing)
            if drops:
                drop = self._drop_step(dof, sign, good, bad, drops[len(drops) // 2],
                                       resolution)
                step = drop + past if drop + past < high else drop - past
            elif predicted is not None and low < predicted < high:
                step = predicted
            elif np.isfinite(bad.margin) and good.margin > bad.margin:
                step = _margin_zero(good, bad, probes) + (past if moves[-1:] == [True]
                                                          else -past)
            else:
                step = 0.5 * (good.step + bad.step)
            if moves[-2:] in ([True, True], [False, False]):    # one end stuck: halve
                step = 0.5 * (step + (bad.step if moves[-1] else good.step))
            if len(widths) > 3 and widths[-1] > 0.5 * widths[-4]:
                step = 0.5 * (good.step + bad.step)
            predicted = None
            probe = yield from self._probe(dof, sign, min(max(step, low), high))
            probes.append(probe)
            moves.append(probe.valid)
            if probe.valid:
                good = probe
            else:
                bad = probe
            widths.append(bad.step - good.step)
        return good.step

    def _drop_step(self, dof: Dof, sign: float, good: _Probe, bad: _Probe, drop: _Drop,
                   resolution: float) -> float:
        """The step between ``good`` and ``bad`` at which the joint of ``drop`` gets
        shorter than ``drop.length``: regula falsi (Illinois) on its length,
        the touching region of the original joint followed on each edited design
        (``geometry.follow_many``), to DROP_RESOLUTION x ``resolution`` or DROP_STEPS
        evaluations.  A joint's length bends with a turn (an end face sliding off a
        shrinking overlap): interpolating it between the bracket's ends is too coarse."""
        index, length = self._joint_index[drop.key], drop.length
        low, high = good.step, bad.step
        over_low, over_high = drop.at_good - length, drop.at_bad - length
        side = 0
        for _ in range(DROP_STEPS):
            if high - low <= DROP_RESOLUTION * resolution or over_low <= 0.0 <= over_high:
                break
            step = low + (high - low) * over_low / (over_low - over_high)
            step = min(max(step, low + 0.01 * (high - low)), high - 0.01 * (high - low))
            try:
                edited = self._edited(dof, sign * step)
            except OutOfReach:
                break
            (joints, _), = follow_many(self.geometry, [(edited, [index], [])])
            over = joints[0].length - length
            if over > 0.0:
                low, over_low = step, over
                over_high *= 0.5 if side > 0 else 1.0
                side = 1
            else:
                high, over_high = step, over
                over_low *= 0.5 if side < 0 else 1.0
                side = -1
        return 0.5 * (low + high)

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

    def _edited(self, dof: Dof, step: float) -> Design:
        """The design with ``dof`` changed by ``step``; the current DOF's are kept (the
        margins' probe steps are the same for both turn horizons)."""
        if not step:
            return self.design
        edits = self._edits.setdefault(dof, {})
        if step not in edits:
            edits[step] = apply_dof(self.design, self.frame, dof, step)
        return edits[step]

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
        be the larger) to ``resolution``; returns the valid end."""
        while abs(bad - good) > resolution:
            middle = 0.5 * (good + bad)
            if (yield from self._valid_at(dof, sign * middle, full)):
                good = middle
            else:
                bad = middle
        return good

    def _nearest_valid(self, dof: Dof, value: float, unit: str, limit: float,
                       resolution: float) -> DofRange:
        """For an invalid design: the valid interval nearest the current value, sampling
        outward on both sides, the sensitivity's favoured side first."""
        samples = [limit * 2.0 ** -k for k in range(6, -1, -1)]
        order = (1.0, -1.0) if self._favoured_sign(dof) > 0 else (-1.0, 1.0)
        for previous, step in zip([0.0] + samples, samples):
            for sign in order:
                if (yield from self._valid_at(dof, sign * step)):
                    inner = yield from self._bisect(dof, sign, step, previous, resolution)
                    outer = yield from self._expand(dof, sign, step, limit, resolution)
                    ends = sorted((value + sign * inner, value + sign * outer))
                    return DofRange(dof.name, value, (ends[0], ends[1]), unit,
                                    "the current value is invalid; this is the nearest "
                                    "valid interval")
        return DofRange(dof.name, value, None, unit,
                        f"no valid value within {limit:g} {unit} either way")

    # -- predictions from the sensitivity ------------------------------------------------------
    def _linearizations(self) -> list[Linearization]:
        if self._linear is None:
            self._linear = []
            for case in self.design.load_cases:
                try:
                    self._linear.append(Linearization(self.design, case, self.geometry,
                                                      self.frame, self._shared))
                except ValueError:
                    continue
        return self._linear

    def _sensitivities(self, dof: Dof) -> list[tuple[Linearization, Sensitivity]]:
        out = []
        for linear in self._linearizations():
            sens = linear.derivatives([dof])
            if sens.blocked:
                raise Blocked(sens.blocked[dof.name])
            out.append((linear, sens))
        return out

    def _predicted(self, dof: Dof) -> tuple[float | None, float | None]:
        """Linear predictions of the steps (down, up) at which a joint reaches capacity or
        a holding contact's normal force reaches zero; None where nothing is predicted."""
        if dof in self._predictions:
            return self._predictions[dof]
        down, up = np.inf, np.inf
        for linear, sens in self._sensitivities(dof):
            for rate, current in _margins(linear, sens):
                if rate < 0:
                    up = min(up, current / -rate)
                elif rate > 0:
                    down = min(down, current / rate)
        self._shared.clear()
        self._predictions[dof] = (None if not np.isfinite(down) else float(down),
                                  None if not np.isfinite(up) else float(up))
        return self._predictions[dof]

    def _favoured_sign(self, dof: Dof) -> float:
        """+1 if increasing the DOF improves the worst margin (linearly), else -1."""
        pairs = [(rate, current) for linear, sens in self._sensitivities(dof)
                 for rate, current in _margins(linear, sens)]
        if not pairs:
            return 1.0
        rate, _ = min(pairs, key=lambda pair: pair[1])
        return 1.0 if rate >= 0 else -1.0

    def _scales(self, dof: Dof) -> tuple[float, float]:
        if dof.is_rotation:
            return 90.0 * SEARCH_LIMIT, 100.0 * RANGE_RESOLUTION
        return self.size * SEARCH_LIMIT, self.size * RANGE_RESOLUTION


@dataclass(frozen=True)
class _Probe:
    """A full check of one step (``check.margin_of``): valid, the margin, each joint's
    utilization and the geometry (the last two None where the step does not keep the
    joints and contacts)."""

    step: float
    valid: bool
    margin: float
    utilization: np.ndarray | None
    geometry: Geometry | None


class _Kept(NamedTuple):
    """Evaluation request of a search: the design with ``dof`` changed by ``step`` and its
    geometry if that keeps the joints and contacts, else (None, None)."""

    dof: Dof
    step: float


class _Margins(NamedTuple):
    """Evaluation request: ``margins`` (an ``EditMargins``) of an edited ``design``."""

    margins: EditMargins
    design: Design


class _Statics(NamedTuple):
    """Evaluation request: the full check of an edited design that keeps the joints and
    contacts, ``check.margin_of`` if ``margin`` else ``check.is_valid``."""

    design: Design
    geometry: Geometry
    margin: bool


def _margin_zero(good: _Probe, bad: _Probe, probes: list[_Probe]) -> float:
    """Where the margin reaches zero between the valid ``good`` and the invalid ``bad``
    (finite margins, good's the larger): inverse quadratic interpolation through the two
    and the latest other probe with a finite margin (the margin bends, e.g. a joint's
    load grows with the square of a lever), if that lies inside the bracket; else the
    secant between the two (regula falsi)."""
    points = [(good.step, good.margin), (bad.step, bad.margin)]
    others = [p for p in probes if p is not good and p is not bad and np.isfinite(p.margin)
              and p.margin not in (good.margin, bad.margin)]
    if others:
        points.append((others[-1].step, others[-1].margin))
        zero = 0.0
        for i, (step, margin) in enumerate(points):
            weight = 1.0
            for j, (_, other) in enumerate(points):
                if j != i:
                    weight *= -other / (margin - other)
            zero += weight * step
        if good.step < zero < bad.step or bad.step < zero < good.step:
            return zero
    return good.step + (bad.step - good.step) * good.margin / (good.margin - bad.margin)


class _Drop(NamedTuple):
    """A step at which a joint may lose a nail (``_nail_drops``)."""

    step: float         # estimated: the joint's length taken as linear in the step
    key: tuple          # the joint's face, edge and edge face
    length: float       # m: below this length it has one nail fewer
    at_good: float      # m: its length at the bracket's valid end
    at_bad: float       # m: and at its invalid end


def _nail_drops(good: _Probe, bad: _Probe, spacing: float) -> list[_Drop]:
    """Where between ``good`` and ``bad`` a joint may lose a nail it cannot spare, sorted
    by step.  For each joint with n nails at ``good`` and m < n at ``bad``: where its
    length, taken as linear in the step between the two geometries, falls below
    k x spacing (k = n, ..., m + 1; ``geometry.nail_count``), if its load then exceeds
    what k - 1 nails carry: utilization x nails, the larger of the two ends, over k - 1
    is above 1.  Losing a nail the joint can spare changes no verdict."""
    if good.geometry is None or bad.geometry is None or bad.utilization is None:
        return []
    before = {(j.face, j.edge, j.edge_face): (n, j)
              for n, j in enumerate(good.geometry.joints)}
    steps = []
    for after, joint in enumerate(bad.geometry.joints):
        index, start = before.get((joint.face, joint.edge, joint.edge_face), (None, None))
        if start is None or joint.nails >= start.nails or joint.length >= start.length:
            continue
        load = max(good.utilization[index] * start.nails,
                   bad.utilization[after] * joint.nails)
        for k in range(joint.nails + 1, start.nails + 1):
            if load <= k - 1:
                continue
            length = k * spacing / (1.0 + NAIL_COUNT_EPS)
            fraction = (start.length - length) / (start.length - joint.length)
            steps.append(_Drop(good.step + (bad.step - good.step) * min(max(fraction, 0.0), 1.0),
                               (joint.face, joint.edge, joint.edge_face), length,
                               start.length, joint.length))
    return sorted(steps)


_WORKER_FINDER: RangeFinder | None = None
"""The finder whose DOFs a forked worker process searches (set while its pool runs)."""


def _ranges_of(dofs: list[Dof]) -> tuple[list[DofRange], int]:
    """In a worker process: the ranges of ``dofs`` and the evaluations they took."""
    finder = _WORKER_FINDER
    before = finder.evaluations
    found = finder._ranges_together(dofs)
    return found, finder.evaluations - before


def _open_groups(at_start: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """Which forbidden groups of the margins at the start are not all positive."""
    return ~(at_start[1] > 0.0).all(axis=1)


def _flipped(closed: np.ndarray, after: tuple[np.ndarray, np.ndarray]) -> bool:
    """Whether a required margin is no longer positive in ``after`` or a forbidden group
    not all positive at the start (``closed``, ``_open_groups``) is all positive."""
    required_at, forbidden_at = after
    return bool((required_at <= 0.0).any() or ((forbidden_at > 0.0).all(axis=1) & closed).any())


def _first_flip(before: tuple[np.ndarray, np.ndarray], after: tuple[np.ndarray, np.ndarray],
                start: float, step: float, limit: float) -> float:
    """The first step >= ``start`` (at most ``limit``) at which, the margins taken as
    linear through their values at ``start`` (``before``) and ``step`` (``after``), a
    required margin reaches 0 or all margins of a forbidden group become positive."""
    (required, forbidden), (required_at, forbidden_at) = before, after
    with np.errstate(divide="ignore", invalid="ignore"):
        rate = (required_at - required) / (step - start)
        falling = rate < 0.0
        first = float(np.min(start + np.maximum(required[falling], 0.0) / -rate[falling],
                             initial=limit))
        rate = (forbidden_at - forbidden) / (step - start)
        positive = forbidden > 0.0
        enters = np.where(positive, start, np.where(rate > 0.0, start - forbidden / rate,
                                                    np.inf))
        leaves = np.where(positive & (rate < 0.0), start - forbidden / rate, np.inf)
        begin, end = enters.max(axis=1), leaves.min(axis=1)
    closed = ~positive.all(axis=1) & (begin < end)
    return min(first, float(np.min(begin[closed], initial=limit)))


def _flip_values(closed: np.ndarray, margins: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """What ``_modelled_flip`` models of ``margins``: every required margin and, per
    forbidden group not all positive at the start (``closed``, ``_open_groups``), minus
    its smallest margin; the margins have flipped (``_flipped``) when one of these is
    <= 0."""
    required, forbidden = margins
    return np.concatenate([required, -forbidden[closed].min(axis=1)])


def _modelled_flip(samples: list, low: float, high: float) -> float:
    """The first turn in (``low``, ``high``] at which one of the ``_flip_values``,
    each modelled as the quadratic in the turn through its values at the three
    ``samples`` (turn, values), reaches zero; ``high`` if none does.  The model is
    scanned on MODEL_GRID turns, then on as many within the first flipped step."""
    turns = np.array([turn for turn, _ in samples])
    values = np.stack([values for _, values in samples])
    try:
        coefficients = np.linalg.solve(np.vander(turns - turns[0], 3, increasing=True), values)
    except np.linalg.LinAlgError:       # turns too close to tell a curve: no prediction
        return high
    # rows: 1, t, t^2 of each turn t (from the first sample's); columns: the margins
    for _ in range(2):
        grid = np.linspace(low, high, MODEL_GRID + 1)[1:]
        modelled = np.vander(grid - turns[0], 3, increasing=True) @ coefficients
        flipped = (modelled <= 0.0).any(axis=1)
        if not flipped.any():
            return high
        first = int(np.argmax(flipped))
        low, high = (grid[first - 1] if first else low), grid[first]
    return float(high)


def _margins(linear: Linearization, sens: Sensitivity):
    """(rate, margin) pairs, margin >= 0 meaning valid: per joint 1 - utilization (its pull
    and shear linearized), per holding contact its normal force over the case's weight."""
    model, design = linear.model, linear.design
    joints = [linear.geometry.joints[j] for j in model.joints]
    wrenches = linear.statics.joint_wrenches
    rates = sens.joint_wrenches[0]
    pull_cap = design.material.nail_pull / design.safety_factor
    shear_cap = design.material.nail_shear / design.safety_factor
    pull, shear = nail_pull_shear(joints, wrenches)
    eps = 1e-6
    pull_next, shear_next = nail_pull_shear(joints, wrenches + eps * rates)
    for p, s, p1, s1 in zip(pull, shear, pull_next, shear_next):
        yield -(p1 - p) / eps / pull_cap, 1.0 - p / pull_cap
        yield -(s1 - s) / eps / shear_cap, 1.0 - s / shear_cap
    forces = linear.statics.contact_forces
    weight = max(float(forces[:, 2].sum()), 1e-12)
    for k in np.nonzero(linear.holding)[0]:
        yield sens.contact_forces[0][k, 2] / weight, forces[k, 2] / weight


def dof_ranges(design: Design, names: list[str] | None = None,
               locked: tuple[str, ...] = ()) -> list[DofRange]:
    """Valid ranges of the named DOFs (all when None), the ``locked`` ones held."""
    return RangeFinder(design, locked).ranges(names)
