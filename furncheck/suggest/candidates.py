"""Search directions of one to M DOFs that lead back to a valid design (paper 6.4,
Algorithm 1), from the linearized margins of ``margins``.

For a combination c of m DOFs, with J the margins' rates and g their values (violated rows
V below zero), the direction is the least-squares step that brings the violated margins to
their targets (paper eq. 11 and 13; the minimum-norm solution when there are fewer
violated margins than DOFs)::

    y* = argmin || J_Vc y - (target_V - g_V) ||,     s = y* / |y*|

and the ray g + t J_c s is tested against the valid region {g >= 0} -- the paper's
durability cuboid, here one slab per margin: it *enters* at t_in = max over V of
-g_i / (J_c s)_i (every violated margin must grow) and *leaves* at t_out = min over the
others of g_i / -(J_c s)_i.  A direction is kept when t_in < t_out and t_in <= MAX_STEP;
one whose violated margins do not all grow faces away from the region and is culled, as
is a weak one (the region is too far along it).  Combinations containing a kept smaller
combination are skipped, so a suggestion never adds a DOF that is not needed.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

import numpy as np

from furncheck.suggest.margins import Margins

MAX_STEP = 0.5
"""Furthest step searched along a direction, scaled units: half the design's size for
lengths, 0.5 rad (29 degrees) for rotations."""

MAX_RELEVANT_DOFS = 48
"""Combinations are formed from at most this many DOFs, those whose rates move the
violated margins most (a DOF that hardly moves them needs a huge step)."""

RELEVANT_RATE = 1e-3
"""A DOF is relevant when its largest rate on a violated margin is at least this fraction
of the largest rate of any DOF."""

_CHUNK = 4096
"""Combinations evaluated per vectorized batch (bounds memory: rows x chunk x m)."""

_CHUNK_BYTES = 64 * 2 ** 20
"""...and fewer when a batch's rates (rows x chunk x m) would take more than this (a
2,000-plank design has 12,000 margins: 4,096 triples of them would take 1.2 GB)."""


@dataclass(frozen=True)
class Candidate:
    """A direction to line-search.

    dofs      : indices into ``Margins.dofs``, ascending
    direction : (m,) unit vector, scaled DOF units
    enter     : predicted step at which every violated margin is restored
    leave     : predicted step at which another margin fails (inf if none)
    """

    dofs: tuple[int, ...]
    direction: np.ndarray
    enter: float
    leave: float


def candidates(margins: Margins, max_dofs: int) -> list[Candidate]:
    """Kept directions of 1..max_dofs DOFs, nearest (smallest predicted step) first."""
    rows = margins.margins
    if not rows or not margins.dofs:
        return []
    rates = np.array([m.rates for m in rows])                        # (rows, n)
    values = np.array([m.value for m in rows])
    violated = values < 0.0
    if not violated.any():
        return []
    deficit = np.array([m.target for m in rows])[violated] - values[violated]
    relevant = _relevant(np.abs(rates[violated]).max(axis=0))
    kept: list[Candidate] = []
    found: set[tuple[int, ...]] = set()
    for m in range(1, max_dofs + 1):
        combos = _combinations(relevant, m, found)
        size = max(1, min(_CHUNK, _CHUNK_BYTES // (8 * len(rows) * m)))
        for start in range(0, len(combos), size):
            chunk = combos[start:start + size]
            for candidate in _evaluate(rates, values, violated, deficit, chunk):
                kept.append(candidate)
                found.add(candidate.dofs)
    kept.sort(key=lambda c: (c.enter, len(c.dofs), c.dofs))
    return kept


def _relevant(strength: np.ndarray) -> list[int]:
    """The DOFs worth combining: strong enough, at most MAX_RELEVANT_DOFS, in DOF order."""
    top = float(strength.max(initial=0.0))
    if top <= 0.0:
        return []
    order = np.argsort(-strength, kind="stable")[:MAX_RELEVANT_DOFS]
    return sorted(int(i) for i in order if strength[i] >= RELEVANT_RATE * top)


def _combinations(relevant: list[int], m: int, found: set[tuple[int, ...]]) -> np.ndarray:
    """(B, m) combinations of the relevant DOFs that contain no kept smaller one."""
    singles = {c[0] for c in found if len(c) == 1}
    pool = [i for i in relevant if i not in singles]
    pairs = {c for c in found if len(c) == 2}
    combos = [c for c in combinations(pool, m)
              if m < 3 or not any(p in pairs for p in combinations(c, 2))]
    return np.array(combos, dtype=int).reshape(-1, m)


def _evaluate(rates: np.ndarray, values: np.ndarray, violated: np.ndarray,
              deficit: np.ndarray, combos: np.ndarray) -> list[Candidate]:
    """Least-squares directions and slab tests of a batch of combinations."""
    block = np.transpose(rates[:, combos], (1, 0, 2))                # (B, rows, m)
    system = block[:, violated, :]                                   # (B, |V|, m)
    y = np.einsum("bmv,v->bm", np.linalg.pinv(system), deficit)
    norm = np.linalg.norm(y, axis=1)
    usable = norm > 0.0
    s = np.where(usable[:, None], y / np.where(usable, norm, 1.0)[:, None], 0.0)
    slope = np.einsum("brm,bm->br", block, s)                        # (B, rows)
    with np.errstate(divide="ignore", invalid="ignore"):
        grows = slope[:, violated] > 0.0
        enter_each = np.where(grows, -values[violated] / slope[:, violated], np.inf)
        enter = enter_each.max(axis=1)
        falling = (slope[:, ~violated] < 0.0)
        leave_each = np.where(falling, values[~violated] / -slope[:, ~violated], np.inf)
        leave = leave_each.min(axis=1, initial=np.inf)
    keep = usable & (enter < leave) & (enter <= MAX_STEP)
    return [Candidate(tuple(int(i) for i in combos[b]), s[b].copy(), float(enter[b]),
                      float(leave[b])) for b in np.nonzero(keep)[0]]
