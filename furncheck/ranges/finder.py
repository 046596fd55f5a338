"""Valid ranges of design DOFs: the searches of each side of a DOF (``RangeFinder``).

See the package's docstring for the two stages of a side's search.
"""

from __future__ import annotations

import math
from collections.abc import Generator
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from furncheck import tolerances as tol
from furncheck.check import check_design, margin_of
from furncheck.design.model import Design, rotation_matrix
from furncheck.dofs import (
    Blocked,
    Dof,
    OutOfReach,
    all_dofs,
    apply_dof,
    design_size,
    dof_value,
    parse_dof,
)
from furncheck.geometry import follow_many
from furncheck.plain import plain_number
from furncheck.ranges.estimates import (
    _Drop,
    _margin_zero,
    _margins,
    _nail_drops,
    _Probe,
)
from furncheck.ranges.nearest import (
    OUTWARD_SAMPLES,
    nearest_window,
    outward_samples,
    predicted_steps,
)
from furncheck.ranges.notes import BeamTurns, floor_reason, pinned_reason, turn_reasons
from furncheck.ranges.reach import ReachSearch
from furncheck.sensitivity import Linearization, Sensitivity

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

ROTATION_MATCH = 1e-6
"""Degrees within which a turn counts as its file angle's alone (entries of the two
rotation matrices within this many radians' worth)."""

DROP_STEPS = 6
"""Most geometry evaluations finding the step at which a joint loses a nail."""

@dataclass(frozen=True)
class DofRange:
    """The valid interval of one DOF (absolute values, file unit or degrees), or None with
    the reason it cannot move or has no valid value within the search limit."""

    dof: str
    value: float
    valid: tuple[float, float] | None
    unit: str
    reason: str | None = None
    limited: tuple[bool, bool] = (False, False)   # (low, high) end is the search limit,
    limit: float = 0.0                            # this far from the value: valid there,
                                                  # nothing beyond it was searched
    rotations: tuple[tuple[float, ...], tuple[float, ...]] | None = None
    """For a turn (rx, ry, rz: about a world axis through the plank's centre) that the
    file's own angle of that name does not follow alone (a leg drawn with ry = -90 turned
    about x changes all three of its angles): the file's ``rotation`` at the interval's
    low and high ends, so that no one types the interval into that one angle."""


class RangeFinder(ReachSearch):
    """Valid ranges of the DOFs of one design, sharing its analysis and linearizations."""

    def __init__(self, design: Design, locked: tuple[str, ...] = ()):
        super().__init__(design, locked)
        self.valid_now = check_design(design, self.geometry, self.model).valid
        self.stand = not self.valid_now     # its nearest window may stand a plank on the floor
        _, self.margin_now, self.utilization_now, self.limiting_now = margin_of(
            design, self.geometry, self.starts, self.model)
        self.size = design_size(design)
        self._joint_index = {(j.face, j.edge, j.edge_face): n
                             for n, j in enumerate(self.geometry.joints)}
        self._linear: list[Linearization] | None = None
        self._shared: dict = {}
        self._predictions: dict[Dof, tuple[float | None, float | None]] = {}

    # -- public --------------------------------------------------------------------------------
    def ranges(self, names: list[str] | None = None, jobs: int = 1,
               client=None) -> list[DofRange]:
        """The ranges of the named DOFs (all when None), in order.  With ``jobs`` > 1 the
        DOFs are shared among that many worker processes; every DOF's search is independent
        of the others, so the result is the same either way.  With a Dask ``client``
        (``furncheck.cluster.connect``) every share of the DOFs, dealt out as for ``jobs``
        workers (its threads), is searched on the cluster.

        One process is the default: the statics' small dense solves gain nothing from a
        multi-threaded BLAS, but its threads spin on the cores that the workers need
        (2 workers on 2 cores run twice as fast as one process only with
        OPENBLAS_NUM_THREADS=1; with threaded BLAS they are slower than one process).

        With ``jobs`` > 1 the work is sized first: a sample of each of the first two of
        the shares the workers would get is searched here (``shares.SAMPLE_STRIDE``; the
        first also pays for what every search shares: imports, the design's
        sensitivities), and the rest goes to workers only if it would take
        ``shares.PARALLEL_AFTER`` CPU seconds or more at the second sample's pace per DOF
        (CPU time: the work, whatever else the machine is doing); else it is searched
        here as well, all together.  Small designs so stay in one process, and
        the workers, forked after those samples, start with what they imported
        (scipy.optimize, when an edit needed a feasibility program: 0.5 s or more to
        import in every worker)."""
        from furncheck.ranges import shares

        dofs = all_dofs(self.design) if names is None else \
            [parse_dof(self.design, name) for name in names]
        if client is not None:
            return shares.ranges_on_cluster(self, dofs, client)
        if jobs > 1 and len(dofs) >= shares.PARALLEL_MIN_DOFS:
            return shares.ranges_shared(self, dofs, jobs)
        return self._ranges_together(dofs)

    def range(self, dof: Dof) -> DofRange:
        return self._ranges_together([dof])[0]

    def search(self, dofs: list[Dof]) -> tuple[list[DofRange], int]:
        """The ranges of ``dofs`` searched here, and the full checks they took."""
        before = self.evaluations
        found = self._ranges_together(dofs)
        return found, self.evaluations - before

    def _ranges_together(self, dofs: list[Dof]) -> list[DofRange]:
        """The ranges of ``dofs``, all their searches advanced together (``_run``): each
        side of each DOF is a generator of the evaluations it needs, and the evaluations
        that the searches wait for at one time are made as one batch."""
        searches: dict[tuple[int, float], Generator] = {}
        predicted = {} if self.valid_now else predicted_steps(
            self.design, self.geometry, self.frame, self.locked, dofs)
        for n, dof in enumerate(dofs):
            if dof in self.locked:
                continue
            value, unit = dof_value(self.design, dof), dof.unit(self.design)
            limit, resolution = self._scales(dof)
            if self.valid_now:
                searches[(n, -1.0)] = self._side(dof, -1.0, limit, resolution)
                searches[(n, 1.0)] = self._side(dof, 1.0, limit, resolution)
            else:
                searches[(n, 0.0)] = self._nearest_valid(dof, value, unit, limit, resolution,
                                                         predicted.get(dof))
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
                limit, resolution = self._scales(dof)
                low, high = value - ends[0], value + ends[1]
                floor = dof.kind in ("length", "width") and low <= resolution
                reasons = [floor_reason(dof, low, resolution, unit)] if floor else []
                reasons += turn_reasons(self.design, dof, value, low, high, unit,
                                        self._turns)
                if ends[0] <= 0.0 and ends[1] <= 0.0:
                    reasons.append(pinned_reason(resolution, unit))
                out.append(DofRange(dof.name, value, (low, high), unit,
                                    "; ".join(reasons) or None,
                                    limited=(ends[0] >= limit, ends[1] >= limit),
                                    limit=limit,
                                    rotations=self._file_rotations(dof, (-ends[0], ends[1]))))
            else:
                out.append(ends[0])
        return out

    def _file_rotations(self, dof: Dof, steps: tuple[float, float]):
        """``DofRange.rotations`` of a turn by ``steps`` (degrees) either way, or None
        (not a turn, or one that the file's angle of its name alone, changed by the
        step, writes: the same matrix, whatever triple the edit reads it back as)."""
        if not dof.is_rotation:
            return None
        before = self.design.plank(dof.plank).rotation
        axis = "xyz".index(dof.kind[1])
        try:
            after = [apply_dof(self.design, self.frame, dof, step).plank(dof.plank).rotation
                     for step in steps]
        except (Blocked, OutOfReach):
            return None
        alone = all(np.allclose(rotation_matrix(angles), rotation_matrix(tuple(
            before[k] + (step if k == axis else 0.0) for k in range(3))),
            rtol=0.0, atol=math.radians(ROTATION_MATCH)) for angles, step in zip(after, steps))
        return None if alone else (tuple(after[0]), tuple(after[1]))

    # -- searches ------------------------------------------------------------------------------
    def _side(self, dof: Dof, sign: float, limit: float, resolution: float) -> float:
        """The furthest step (>= 0) in direction ``sign`` up to which the design was found
        valid, assuming it is valid now: first how far the geometry reaches (cheap checks
        without statics), then, if the design is not valid there, the physical limit inside
        it (``_physical_limit``)."""
        reach = yield from self._geometric_reach(dof, sign, limit, resolution)
        if reach <= 0.0:
            return reach
        at_reach = yield from self._probe(dof, sign, reach, self.limiting_now)
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
        is -inf.  Each probe solves first the load case that failed last (at first the
        one that limits the design) and an invalid probe stops at its first failing case:
        its verdict is the full check's, its margin that of the cases solved.
        """
        good = _Probe(0.0, True, self.margin_now, self.utilization_now, self.geometry,
                      self.limiting_now)
        bad = at_reach
        predicted = self._predicted(dof)[0 if sign < 0 else 1]
        spacing = self.design.material.nail_spacing
        failing = self.limiting_now if bad.case is None else bad.case
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
            probe = yield from self._probe(dof, sign, min(max(step, low), high), failing)
            probes.append(probe)
            moves.append(probe.valid)
            if probe.valid:
                good = probe
            else:
                bad = probe
                failing = failing if probe.case is None else probe.case
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

    def _nearest_valid(self, dof: Dof, value: float, unit: str, limit: float,
                       resolution: float, predicted: float | None = None) -> DofRange:
        """For an invalid design: the valid window at the ``predicted`` change, else the
        valid interval nearest the current value (``nearest.nearest_window``)."""
        found = yield from nearest_window(self, dof, limit, resolution, predicted)
        if found is None:
            first = outward_samples(limit)[0]
            return DofRange(dof.name, value, None, unit,
                            f"no valid value found within {plain_number(limit, 6)} {unit} "
                            f"either way ({OUTWARD_SAMPLES} probes each way, from "
                            f"{plain_number(first, 4)} {unit} out, each 1.41 times the one "
                            "before)")
        (inner, outer), reason = found
        steps = sorted((inner, outer))
        far = abs(outer) >= limit        # its outer end is the search limit
        turned = turn_reasons(self.design, dof, value, value + steps[0], value + steps[1],
                              unit, self._turns)
        return DofRange(dof.name, value, (value + steps[0], value + steps[1]), unit,
                        "; ".join([f"the current value is invalid; this is the {reason}",
                                   *turned]),
                        limited=(far and outer < 0.0, far and outer > 0.0), limit=limit,
                        rotations=self._file_rotations(dof, (steps[0], steps[1])))

    # -- predictions from the sensitivity ------------------------------------------------------
    def _linearizations(self) -> list[Linearization]:
        if self._linear is None:
            self._linear = []
            for case in self.design.load_cases:
                try:
                    self._linear.append(Linearization(self.design, case, self.geometry,
                                                      self.frame, self._shared,
                                                      model=self.model))
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
        """+1 if increasing the DOF improves the worst margin (linearly), -1 if it worsens
        it; +1 where the worst margins do not decide: no margin, rates that are round-off
        (they change the margin by less than RATE_ROUNDOFF of its size, at least 1, over
        the DOF's whole reach: a mirror-symmetric turn, whose true rates are zero), or
        worst margins as low as each other (to RATE_ROUNDOFF) whose rates disagree (a
        mirror pair's; the two joints of a shelf turned in the gap between its sides).
        The nearest valid window's search looks on this side first, so where both sides
        hold windows as near as each other, the side searched first does not depend on
        the last bits of the sums."""
        pairs = [(float(rate), float(current)) for linear, sens in self._sensitivities(dof)
                 for rate, current in _margins(linear, sens)]
        if not pairs:
            return 1.0
        least = min(current for _, current in pairs)
        reach, _ = self._scales(dof)
        signs = {1.0 if rate > 0.0 else -1.0 for rate, current in pairs
                 if current - least <= tol.RATE_ROUNDOFF * max(1.0, abs(least))
                 and abs(rate) * reach > tol.RATE_ROUNDOFF * max(1.0, abs(current))}
        return signs.pop() if len(signs) == 1 else 1.0

    @cached_property
    def _turns(self) -> BeamTurns:
        """Where resizes turn the elastic planks' beams (``turn_reasons``), to the
        resolution of a size's range."""
        return BeamTurns(self.design, self.geometry, self.frame, self.size * RANGE_RESOLUTION,
                         100.0 * RANGE_RESOLUTION)

    def _scales(self, dof: Dof) -> tuple[float, float]:
        if dof.is_rotation:
            return 90.0 * SEARCH_LIMIT, 100.0 * RANGE_RESOLUTION
        return self.size * SEARCH_LIMIT, self.size * RANGE_RESOLUTION


def dof_ranges(design: Design, names: list[str] | None = None,
               locked: tuple[str, ...] = ()) -> list[DofRange]:
    """Valid ranges of the named DOFs (all when None), the ``locked`` ones held."""
    return RangeFinder(design, locked).ranges(names)
