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
from furncheck.geometry import Geometry, follow_many
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
from furncheck.ranges.reach import ReachSearch
from furncheck.sensitivity import Linearization, Sensitivity
from furncheck.statics.elastic import beam_layout, plank_geometry

RANGE_RESOLUTION = 1e-3
"""Bisection stops when the bracket is this fraction of the design's size (lengths) or
this many degrees x 100 (rotations: 0.1 degree)."""

TURN_RESOLUTION = 0.01
"""Where a resize turns a beam (``BeamTurns.first_turn``) is found to this share of the
range's resolution: about seven more bisections than the range's own resolution would
take, each the plank's joints followed onto the edited design (``BeamTurns.turned``),
on the rows that pass a turn."""

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
        return BeamTurns(self.design, self.geometry, self.frame, self.size * RANGE_RESOLUTION)

    def _scales(self, dof: Dof) -> tuple[float, float]:
        if dof.is_rotation:
            return 90.0 * SEARCH_LIMIT, 100.0 * RANGE_RESOLUTION
        return self.size * SEARCH_LIMIT, self.size * RANGE_RESOLUTION


def turn_reasons(design: Design, dof: Dof, value: float, low: float, high: float,
                 unit: str, turns: BeamTurns) -> list[str]:
    """Where a row's interval, or the way to it from the current ``value``, passes a value
    at which the elastic model turns a plank's one beam: that values beyond are judged
    spanning the other way, so that a sag judged there may be the model's, not the
    shop's.  The beam runs along the longer side (contract 3a), and turns at the square
    (a seat widened past its length spans from its front edge to its back); a plank
    nailed along both edges to panels spans across between them
    (``elastic.BeamLayout.candidates``), and its beam turns where those lines stop
    covering three quarters of its edges, not at the square: resized (the stool's 400
    mm seat on its 300 mm legs, widened past 401.335 mm), or as its neighbours are (a
    nightstand's sides cut shallower than 299 mm under its 400 mm deep top; a shelf
    between two sides as deep as itself spans between them either side of the square):
    ``turns`` finds where, for the DOF's plank and the planks nailed to it.  Else
    nothing."""
    if not design.elastic:
        return []
    reasons = []
    if dof.kind in ("length", "width") and dof.plank not in turns.candidates:
        plank = design.plank(dof.plank)
        other = (plank.width if dof.kind == "length" else plank.length) / design.unit_scale
        margin = design.tolerance / design.unit_scale
        if min(low, value) + margin < other < max(high, value) - margin:
            side = "length" if dof.kind == "width" else "width"
            reasons.append(f"past {plain_number(other, 6)} {unit} (its {side}) {dof.plank} "
                           "is square and then turned: the elastic model lays its one beam "
                           "along the longer side, so values beyond are judged spanning "
                           "the other way")
    turned: dict[str, list[str]] = {}            # planks turned at one value, together
    affected = turns.affected(dof)
    ends = sorted({low, high} - {value}, key=lambda end: abs(end - value))
    at_ends = [turns.turned(dof, value, end, affected) if affected else set()
               for end in ends]
    for plank_id in affected:
        end = next((end for end, there in zip(ends, at_ends) if plank_id in there), None)
        if end is not None:
            where = turns.first_turn(dof, value, end, plank_id)
            turned.setdefault(plain_number(where, 6), []).append(plank_id)
    for where, planks in turned.items():
        whose = f"{planks[0]}'s beam is" if len(planks) == 1 else \
            f"the beams of {', '.join(planks[:-1])} and {planks[-1]} are"
        reasons.append(f"past {where} {unit} {whose} turned: the elastic model lays a "
                       "plank's one beam along the longer side, or across it between "
                       "panels nailed along both its edges, so values beyond are judged "
                       "spanning the other way")
    return reasons


class BeamTurns:
    """Where an edit turns an elastic plank's beam (``turn_reasons``), for one design: the
    planks that may span across (``elastic.BeamLayout.candidates``), which of them each
    plank is nailed to, and their beams' directions now, found once."""

    def __init__(self, design: Design, geometry: Geometry, frame, resolution: float):
        self.design, self.geometry, self.frame = design, geometry, frame
        self.resolution = resolution
        layout = beam_layout(design, geometry) if design.elastic else None
        self.candidates = layout.candidates if layout is not None else frozenset()
        self._now = layout.crosswise if layout is not None else {}
        self._nailed: dict[str, set] = {}
        for joint in geometry.joints if self.candidates else ():
            a, b = joint.planks
            for one, other in ((a, b), (b, a)):
                if other in self.candidates:
                    self._nailed.setdefault(one, set()).add(other)

    def affected(self, dof: Dof) -> list[str]:
        """The planks whose beam ``dof`` may turn other than at the square: its own plank
        if that may span across (resized, moved or turned, it comes to be held along
        more or less of its edges), and the candidates nailed to it, in the design's
        order."""
        planks = set(self._nailed.get(dof.plank, ()))
        if dof.plank in self.candidates:
            planks.add(dof.plank)
        return sorted(planks, key=self.design.plank_index.get)

    def turned(self, dof: Dof, value: float, at: float, planks: list[str]) -> set[str]:
        """Which of ``planks`` have their beam the other way with ``dof`` at ``at`` (none
        where the edit cannot be made): their joints and their neighbours' floor corners
        followed onto the edited design at once (``geometry.follow_many``: the joints
        they have now, measured again; one that the edit would open or close is not
        looked for), not the whole design analysed again."""
        try:
            edited = apply_dof(self.design, self.frame, dof, at - value)
        except (Blocked, OutOfReach):
            return set()
        after = beam_layout(edited, plank_geometry(self.geometry, edited, planks), planks)
        return {plank_id for plank_id in planks
                if after.crosswise[plank_id] != self._now[plank_id]}

    def first_turn(self, dof: Dof, value: float, end: float, plank_id: str) -> float:
        """The value nearest ``value`` past which plank ``plank_id``'s beam is turned,
        toward ``end``, where it is (to within TURN_RESOLUTION of ``resolution``, by
        bisection: the turn is where joint lines stop covering a length, which the row
        names to six figures, as the interval; one turn is assumed between the value and
        that end, a turn and a turn back between them is not seen)."""
        resolution = 100.0 * RANGE_RESOLUTION if dof.is_rotation else self.resolution
        near, far = value, end
        while abs(far - near) > TURN_RESOLUTION * resolution:
            middle = 0.5 * (near + far)
            near, far = (near, middle) if self.turned(dof, value, middle, [plank_id]) \
                else (middle, far)
        return far


def floor_reason(dof: Dof, low: float, resolution: float, unit: str) -> str:
    """Why a size's interval ends within a resolution of nothing: no smaller plank is
    searched (the step beyond would be no plank at all), so that end is not one past
    which the design is invalid (a shelf cut to 0.3 mm still holds: nothing rests on
    it)."""
    return (f"{dof.kind} {plain_number(low, 5)} {unit} is the least searched: one step "
            f"of {plain_number(resolution, 5)} {unit} less leaves no plank")


def dof_ranges(design: Design, names: list[str] | None = None,
               locked: tuple[str, ...] = ()) -> list[DofRange]:
    """Valid ranges of the named DOFs (all when None), the ``locked`` ones held."""
    return RangeFinder(design, locked).ranges(names)
