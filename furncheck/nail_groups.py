"""Nail groups (contract section 3, paper eq. 4-5): the per-nail pull and shear of a
joint's worst nail from its wrench, and the joints' utilization.

Per nail, with t the edge plank's thickness and F, M the joint wrench in the joint frame
(n = nail axis, F_n > 0 pressing the planks together, y = the joint line), the nails at
y_i along the joint line and S = sum y_i^2 (the elastic fastener-group rule):

    pull_i  = (2 |M_y| / t - F_n) / n + M_x y_i / S       (paper eq. 4, plus rocking)
    shear_i = |(F_x / n - M_n y_i / S, F_y / n)|           (paper eq. 5, plus twist)

and a joint's pull and shear are its worst nail's (``nail_pull_shear``); where the
elastic model cuts a joint's row into parts, its parts' nails count too, each part's
sharing its own spring's wrench (``worst_part_forces``).  A joint is durable iff pull <=
nail_pull / safety_factor and shear <= nail_shear / safety_factor.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design
from furncheck.geometry import Geometry, Joint
from furncheck.statics import StaticsModel
from furncheck.statics.beams import nail_row_spread


@dataclass(frozen=True)
class NailForces:
    """Per-nail forces of one joint, N."""

    pull: float
    shear: float
    pull_capacity: float
    shear_capacity: float

    @property
    def utilization(self) -> float:
        """max(pull / pull capacity, shear / shear capacity); > 1 means the joint fails."""
        return max(self.pull / self.pull_capacity, self.shear / self.shear_capacity)

    @property
    def durable(self) -> bool:
        return bool(within_capacity(self.pull, self.shear, self.pull_capacity,
                                    self.shear_capacity))


def within_capacity(pull, shear, pull_capacity: float, shear_capacity: float):
    """Whether per-nail pull and shear (N; floats or arrays) are within their capacities,
    up to the relative slack CAPACITY_REL_TOL: the durability verdict of a joint."""
    slack = 1.0 + tol.CAPACITY_REL_TOL
    return (pull <= pull_capacity * slack) & (shear <= shear_capacity * slack)


def nail_row(joints: list[Joint]) -> tuple[np.ndarray, np.ndarray]:
    """(y_max, S) per joint (m, m^2): the outermost nail's distance from the joint point and
    S = sum of y_i^2 over the nails at y_i = (i + 1/2) L / n - L / 2 (contract section 3),
    i.e. y_max = L (n - 1) / (2 n) and S = L^2 (n^2 - 1) / (12 n).

    One nail (y_0 = 0, S = 0: the contract's formula is 0 / 0) works against the far end
    of its contact region: lever L / 2 for a moment about x or n, taken as y_max = L / 2,
    S = L^2 / 4, so that M y_max / S = 2 M / L, the same lever rule as 2 M_y / t across
    the thickness."""
    length = np.array([j.length for j in joints], dtype=float)
    nails = np.array([j.nails for j in joints], dtype=float)
    single = nails <= 1.0
    y_max = np.where(single, 0.5 * length, length * (nails - 1.0) / (2.0 * nails))
    spread = np.where(single, 0.25 * length ** 2, nail_row_spread(length, nails))
    return y_max, np.maximum(spread, 1e-300)


class NailRows(NamedTuple):
    """What ``nail_pull_shear`` needs of each of nJ joints: its frame (nJ, 3, 3), the
    sign turning a wrench into the face plank's action (nJ, 1), the edge plank's
    thickness (m), the nails and the lever y_max / S (1/m) of its row (``nail_row``)."""

    frames: np.ndarray
    sign: np.ndarray
    thickness: np.ndarray
    nails: np.ndarray
    lever: np.ndarray


def nail_rows(joints: list[Joint]) -> NailRows:
    """The ``NailRows`` of ``joints`` (for many calls of ``nail_pull_shear`` on them)."""
    y_max, spread = nail_row(joints)
    return NailRows(np.stack([j.frame for j in joints]),
                    np.array([1.0 if j.planks[0] == j.face else -1.0 for j in joints])[:, None],
                    np.array([j.edge_thickness for j in joints]),
                    np.array([j.nails for j in joints], dtype=float), y_max / spread)


def nail_pull_shear(joints: list[Joint], wrenches: np.ndarray,
                    rows: NailRows | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Per-nail pull and shear (N) of the worst nail of many joints; wrenches (nJ, 6)
    first plank on second (or (k, nJ, 6): k sets of them at once, e.g. one per load case);
    ``rows``: the joints' ``nail_rows``, if the caller has them.

    The wrench is turned into the face plank's action on the edge plank and expressed in
    the joint frame (x edge thickness normal, y joint line, n nail axis), and shared by the
    nail row as an elastic fastener group (contract section 3), y_max and S from
    ``nail_row``:

        pull  = (2 |M_y| / t - F_n) / n + |M_x| y_max / S
        shear = |(|F_x| / n + |M_n| y_max / S, F_y / n)|

    the outermost nail on the side where the rocking moment M_x adds to the pull and the
    twist M_n to the sideways force.  With M_x = M_n = 0 this is the paper's eq. 4-5.
    """
    if not joints:
        return np.zeros(wrenches.shape[:-1]), np.zeros(wrenches.shape[:-1])
    return _group_forces(rows or nail_rows(joints), wrenches)


def part_rows(geometry: Geometry, model: StaticsModel) -> NailRows:
    """The ``NailRows`` of a model's joint springs where its joints are cut into parts
    (``StaticsModel.joint_parts``): part g of a row of n nails cut into m holds n / m of
    them over L / m, y_max = (n / m - 1) L / 2 n from its middle and S_m = L^2 (n / m^2 -
    1 / n) / 12 m (``beams.nail_row_parts``), in its joint's frame; a joint left whole
    (its one spring) has its row's own (``nail_rows``)."""
    joints = [geometry.joints[j] for j in model.joints]
    whole = nail_rows(joints)
    parts = model.joint_parts
    counts = np.asarray(model.plank_cache["joint_part_counts"], dtype=float)[parts]
    nails = whole.nails[parts]
    length = np.array([j.length for j in joints], dtype=float)[parts]
    cut = counts > 1.0                      # a whole joint's one spring: its own row
    share = np.where(cut, nails / counts, nails)
    y_max = (share - 1.0) * length / (2.0 * nails)
    spread = length * length * (nails / (counts * counts) - 1.0 / nails) / (12.0 * counts)
    lever = whole.lever[parts].copy()
    lever[cut] = y_max[cut] / spread[cut]
    return NailRows(whole.frames[parts], whole.sign[parts], whole.thickness[parts], share,
                    lever)


def worst_part_forces(model: StaticsModel, rows: NailRows,
                      part_wrenches: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per joint, the pull and shear (N) of the worst nail of its parts, each part's nails
    sharing its own spring's wrench (``nail_pull_shear``'s rule, ``part_rows``); (nS, 6)
    or (k, nS, 6) wrenches give (nJ,) or (k, nJ).  A row that the composite action of its
    planks shears along (a batten nailed on a rail) loads its end parts' nails with the
    shear flow, which the whole row's wrench sums away."""
    pull, shear = _group_forces(rows, part_wrenches)
    starts = np.flatnonzero(np.diff(model.joint_parts, prepend=-1))     # parts are in order
    return (np.maximum.reduceat(pull, starts, axis=-1),
            np.maximum.reduceat(shear, starts, axis=-1))


def _group_forces(rows: NailRows, wrenches: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``nail_pull_shear``'s formula for the nail groups of ``rows``."""
    frames, sign, thickness, nails, lever = rows
    force = np.einsum("jab,...ja->...jb", frames, sign * wrenches[..., :3])   # frame^T F
    moment = np.einsum("jab,...ja->...jb", frames, sign * wrenches[..., 3:])  # frame^T M
    pull = (2.0 * np.abs(moment[..., 1]) / thickness - force[..., 2]) / nails \
        + np.abs(moment[..., 0]) * lever
    shear = np.hypot(np.abs(force[..., 0]) / nails + np.abs(moment[..., 2]) * lever,
                     force[..., 1] / nails)
    return pull, shear


def joint_utilization(design: Design, geometry: Geometry, model: StaticsModel,
                      wrenches: np.ndarray, rows: NailRows | None = None,
                      parts: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Per model joint, for its wrenches in a solved case ((nJ, 6), or (k, nJ, 6) for k
    cases): max(pull / pull capacity, shear / shear capacity), and whether it is within
    capacity (``within_capacity``); ``rows``: the model joints' ``nail_rows``, if the
    caller has them; ``parts``: the springs' wrenches where joints are cut into parts
    ((nS, 6) or (k, nS, 6), ``CaseStatics.part_wrenches``), whose worst nails count too
    (``worst_part_forces``)."""
    pulls, shears = nail_pull_shear([geometry.joints[j] for j in model.joints], wrenches,
                                    rows)
    if parts is not None:
        part_pulls, part_shears = worst_part_forces(model, part_rows(geometry, model), parts)
        pulls, shears = np.maximum(pulls, part_pulls), np.maximum(shears, part_shears)
    pull_cap = design.material.nail_pull / design.safety_factor
    shear_cap = design.material.nail_shear / design.safety_factor
    return (np.maximum(pulls / pull_cap, shears / shear_cap),
            within_capacity(pulls, shears, pull_cap, shear_cap))
