"""Where validity is likely to change along a DOF: the estimates that place a range
search's next evaluation.

The margin's zero between a valid and an invalid full check (``_margin_zero``), the steps
at which a loaded joint loses a nail (``_nail_drops``), the first flip of the geometric
margins, linear (``_first_flip``) or modelled on a turn (``_modelled_flip``), and the
joints' and contacts' margins with their rates from the force sensitivity (``_margins``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from furncheck.geometry import Geometry
from furncheck.nail_groups import nail_pull_shear
from furncheck.sensitivity import Linearization, Sensitivity
from furncheck.statics import external_forces
from furncheck.tolerances import NAIL_COUNT_EPS

MODEL_GRID = 64
"""The modelled margins are scanned for their first flip on this many turns, twice (the
second time within the first scan's step)."""


@dataclass(frozen=True)
class _Probe:
    """A full check of one step (``check.margin_of``): valid, the margin, each joint's
    utilization and the geometry (the last two None where the step does not keep the
    joints and contacts), and the load case that failed or limits the margin (None where
    no case was solved).  An invalid step's margin and utilization are those of the
    cases solved up to the first that failed (``margin_of`` with ``first``)."""

    step: float
    valid: bool
    margin: float
    utilization: np.ndarray | None
    geometry: Geometry | None
    case: int | None = None


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
    return np.concatenate([required, -forbidden.min(axis=1)[closed]])


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
    # rows: 1, t, t^2 of each turn t (from the first sample's); columns: the margins.
    # Only margins that may reach zero in the interval are scanned (the others cannot flip
    # at any of its turns: their smallest value there is clearly positive).
    coefficients = coefficients[:, _may_reach_zero(coefficients, low - turns[0],
                                                   high - turns[0])]
    for _ in range(2):
        grid = np.linspace(low, high, MODEL_GRID + 1)[1:]
        modelled = np.vander(grid - turns[0], 3, increasing=True) @ coefficients
        flipped = (modelled <= 0.0).any(axis=1)
        if not flipped.any():
            return high
        first = int(np.argmax(flipped))
        low, high = (grid[first - 1] if first else low), grid[first]
    return float(high)


def _may_reach_zero(coefficients: np.ndarray, start: float, end: float) -> np.ndarray:
    """Per column (a, b, c) of ``coefficients``: whether a + b t + c t^2 may be <= 0 for
    some t in [start, end], i.e. its least value there (at an end, or at the vertex
    -b / 2c when that lies inside and c > 0) is not above round-off of its terms."""
    a, b, c = coefficients
    least = np.minimum(a + b * start + c * start * start, a + b * end + c * end * end)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        vertex = np.where(c > 0.0, -b / (2.0 * c), start)
    inside = (vertex > start) & (vertex < end)
    vertex = np.where(inside, vertex, start)
    least = np.where(inside, np.minimum(least, a + b * vertex + c * vertex * vertex), least)
    reach = max(abs(start), abs(end))
    scale = np.abs(a) + np.abs(b) * reach + np.abs(c) * reach * reach
    return least <= _MODEL_ROUNDOFF * scale


_MODEL_ROUNDOFF = 1e-9
"""Relative slack of ``_may_reach_zero`` (far above the round-off of evaluating a
quadratic, so that no margin the scan could find at zero is left out)."""


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
    forces = linear.model.corner_forces(linear.statics.contact_forces)
    weight = max(float(forces[:, 2].sum()), 1e-12)
    ties = linear.model.contact_anchored
    if linear.model.contact_frames is not None or ties is not None:
        applied = external_forces(linear.model, linear.case).reshape(-1, 6)[:, :3]
        weight = max(float(np.sqrt((applied * applied).sum(axis=1)).sum()), 1e-12)
    for k in np.nonzero(linear.holding[:linear.model.n_corners])[0]:
        if ties is not None and ties[k]:
            continue                    # an anchor's tie may pull
        yield sens.contact_forces[0][k, 2] / weight, forces[k, 2] / weight
