"""Valid ranges of design DOFs (paper section 6.3).

For one DOF, the others held (its neighbours adjusted by the geometric constraints of
``dofs``), the valid range is the interval of values around the current one for which the
design stays valid: every joint durable, stable in every load case, the same joints and
ground contacts.  The force sensitivity (eq. 6) predicts where the first joint reaches its
nail capacity or the first contact lets go; the full statics then confirms: a bracket of
one valid and one invalid value is closed by bisection to ``RANGE_RESOLUTION``, every probe
a complete ``check_design`` of the edited design.  The reported end is the last value found
valid; a value one resolution step beyond it was found invalid (or is the search limit).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from furncheck.check import check_design, is_valid
from furncheck.design.model import Design
from furncheck.dofs import (
    Blocked,
    Dof,
    OutOfReach,
    Structure,
    all_dofs,
    apply_dof,
    check_edit,
    design_size,
    dof_value,
    parse_dof,
    structure,
)
from furncheck.geometry import Geometry, analyze
from furncheck.sensitivity import Linearization, Sensitivity
from furncheck.validity import nail_pull_shear

RANGE_RESOLUTION = 1e-3
"""Bisection stops when the bracket is this fraction of the design's size (lengths) or
this many degrees x 100 (rotations: 0.1 degree)."""

SEARCH_LIMIT = 1.0
"""How far a range is searched: this fraction of the design's size for lengths, x 90
degrees for rotations."""

PREDICTION_BRACKET = 0.02
"""Relative half-width of the first bracket put around a predicted limit."""


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
        self.size = design_size(design)
        self._linear: list[Linearization] | None = None
        self._shared: dict = {}
        self._predictions: dict[Dof, tuple[float | None, float | None]] = {}
        self.evaluations = 0

    # -- public --------------------------------------------------------------------------------
    def ranges(self, names: list[str] | None = None) -> list[DofRange]:
        dofs = all_dofs(self.design) if names is None else \
            [parse_dof(self.design, name) for name in names]
        return [self.range(dof) for dof in dofs]

    def range(self, dof: Dof) -> DofRange:
        value = dof_value(self.design, dof)
        unit = dof.unit(self.design)
        if dof in self.locked:
            return DofRange(dof.name, value, None, unit, "locked")
        limit, resolution = self._scales(dof)
        try:
            if self.valid_now:
                low = self._side(dof, -1.0, limit, resolution)
                high = self._side(dof, 1.0, limit, resolution)
                return DofRange(dof.name, value, (value - low, value + high), unit)
            return self._nearest_valid(dof, value, unit, limit, resolution)
        except Blocked as why:
            return DofRange(dof.name, value, None, unit, why.reason)

    # -- validity of one step ------------------------------------------------------------------
    def valid_at(self, dof: Dof, step: float, full: bool = True) -> bool:
        """Whether the design with ``dof`` changed by ``step`` keeps its joints and ground
        contacts and (``full``) is valid in every load case."""
        try:
            edited = apply_dof(self.design, self.frame, dof, step)
        except OutOfReach:
            return False
        for lock in self.locked:
            if abs(dof_value(edited, lock) - dof_value(self.design, lock)) > 1e-9:
                raise Blocked(f"it would change the locked {lock.name}")
        self.evaluations += 1
        problem, geometry = check_edit(self.geometry, edited, self.design)
        if problem is not None:
            return False
        return is_valid(edited, geometry) if full else True

    # -- searches ------------------------------------------------------------------------------
    def _side(self, dof: Dof, sign: float, limit: float, resolution: float) -> float:
        """The furthest step (>= 0) in direction ``sign`` up to which the design was found
        valid, assuming it is valid now: first how far the geometry reaches (cheap checks
        without statics), then, if the design is not valid there, the physical limit inside
        it, bracketed around the sensitivity's prediction."""
        reach = self._expand(dof, sign, 0.0, limit, resolution, full=False)
        if reach <= 0.0 or self.valid_at(dof, sign * reach):
            return reach
        good, bad = 0.0, reach
        predicted = self._predicted(dof)[0 if sign < 0 else 1]
        if predicted is not None and predicted < reach:
            inside = max(predicted * (1.0 - PREDICTION_BRACKET), resolution)
            outside = min(predicted * (1.0 + PREDICTION_BRACKET), reach)
            if not self.valid_at(dof, sign * inside):
                bad = inside
            elif outside > inside and not self.valid_at(dof, sign * outside):
                good, bad = inside, outside
            else:
                good = max(inside, outside)
        return self._bisect(dof, sign, good, bad, resolution)

    def _expand(self, dof: Dof, sign: float, start: float, limit: float, resolution: float,
                full: bool = True) -> float:
        """From a valid step ``start``, double outward (from limit / 16) until invalid or
        at the limit, then bisect the last bracket; returns the furthest valid step."""
        good, step = start, max(start, limit / 16.0)
        while True:
            if step > good:
                if not self.valid_at(dof, sign * step, full):
                    return self._bisect(dof, sign, good, step, resolution, full)
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
            if self.valid_at(dof, sign * middle, full):
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
                if self.valid_at(dof, sign * step):
                    inner = self._bisect(dof, sign, step, previous, resolution)
                    outer = self._expand(dof, sign, step, limit, resolution)
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
