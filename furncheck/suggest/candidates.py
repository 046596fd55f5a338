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
from math import comb, inf

import numpy as np

from furncheck.suggest.margins import Margins
from furncheck.suggest.tried import DirectionTally

MAX_STEP = 0.5
"""Furthest step searched along a direction, scaled units: half the design's size for
lengths, 0.5 rad (28.6 degrees) for rotations."""

MAX_RELEVANT_DOFS = 48
"""Combinations are formed from at most this many DOFs, those whose rates move the
violated margins most (a DOF that hardly moves them needs a huge step)."""

RELEVANT_RATE = 1e-3
"""A DOF is relevant when its rate on some violated margin is at least this fraction of
the largest rate of any DOF on that margin: each margin weighs its DOFs against its own
(a shelf at 11,000 % of its sag has rates a thousand times a joint's just past its
limit; measured against all rates at once, the joint's DOFs fell out of the
combinations)."""

SAME_DIRECTION = 0.999
"""Directions over the same DOFs whose cosine exceeds this are the same suggestion."""

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
    aim       : the least-squares step |y*| toward the violated margins' targets (inf if
                not known): it meets them where one margin is violated, or there are as
                many DOFs; for such a geometric repair the middle of its tolerance
                window, where ``enter`` is the window's near edge
    """

    dofs: tuple[int, ...]
    direction: np.ndarray
    enter: float
    leave: float
    units: tuple[tuple[int, ...], ...] = ()  # the DOFs of each symmetric unit it combines
    # (``unit_candidates``: a mirror pair, or a DOF its mirror keeps); () for the others
    aim: float = inf


def candidates(margins: Margins, max_dofs: int,
               tally: list[DirectionTally] | None = None) -> list[Candidate]:
    """Kept directions of 1..max_dofs DOFs, nearest (smallest predicted step) first;
    ``tally`` (when given) gets one ``DirectionTally`` per number of DOFs."""
    system = _system(margins)
    if system is None:
        return []
    rows = margins.margins
    rates, values, violated, deficit = system
    relevant = _relevant(_strength(rates[violated], deficit))
    kept: list[Candidate] = []
    found: set[tuple[int, ...]] = set()
    for m in range(1, max_dofs + 1):
        combos = _combinations(relevant, m, found)
        culled = np.zeros(3, dtype=int)
        before = len(kept)
        size = max(1, min(_CHUNK, _CHUNK_BYTES // (8 * len(rows) * m)))
        for start in range(0, len(combos), size):
            chunk = combos[start:start + size]
            chunk_kept, chunk_culled = _evaluate(rates, values, violated, deficit, chunk)
            culled += chunk_culled
            for candidate in chunk_kept:
                kept.append(candidate)
                found.add(candidate.dofs)
        if tally is not None:
            tally.append(DirectionTally(m, len(relevant), comb(len(relevant), m), len(combos),
                                        len(kept) - before, *(int(c) for c in culled)))
    kept.sort(key=lambda c: (c.enter, len(c.dofs), c.dofs))
    return kept


def every_candidate(margins: Margins, max_dofs: int,
                    tally: list[DirectionTally] | None = None) -> list[Candidate]:
    """``candidates`` of the margins and of each of their ``alternatives`` (other ways to
    restore the design, e.g. a leg drawn short brought down to the floor), each direction
    once (the margins' own where both have it), nearest first; ``tally`` counts the
    alternatives' combinations with the margins' own of as many DOFs (a direction that
    both sets keep is counted in each)."""
    found = candidates(margins, max_dofs, tally)
    for rows in margins.alternatives:
        counted: list[DirectionTally] | None = None if tally is None else []
        more = candidates(margins.with_margins(rows), max_dofs, counted)
        found += [c for c in more if not any(same_direction(c, f) for f in found)]
        if tally is not None:
            tally[:] = _added_tallies(tally, counted)
    found.sort(key=lambda c: (c.enter, len(c.dofs), c.dofs))
    return found


def same_direction(a: Candidate, b: Candidate) -> bool:
    """Whether two candidates are one direction (the same DOFs, parallel)."""
    return a.dofs == b.dofs and float(a.direction @ b.direction) > SAME_DIRECTION


def _added_tallies(first: list[DirectionTally],
                   second: list[DirectionTally]) -> list[DirectionTally]:
    """One ``DirectionTally`` per number of DOFs of both lists: their counts added, the
    relevant DOFs the larger of the two."""
    sizes = sorted({t.size for t in first} | {t.size for t in second})
    out = []
    for size in sizes:
        both = [t for t in (*first, *second) if t.size == size]
        out.append(DirectionTally(size, max(t.relevant for t in both),
                                  *(sum(getattr(t, name) for t in both) for name in (
                                      "possible", "evaluated", "kept", "facing_away",
                                      "breaks_other", "too_far"))))
    return out


def unit_candidates(margins: Margins, units: list, max_dofs: int) -> list[Candidate]:
    """Kept directions (as ``candidates``) in the span of one or two *units* -- fixed
    directions of one or two DOFs each (``symmetry.Unit``: a mirror pair changed
    symmetrically, a DOF its mirror keeps) -- with at least one unit of two DOFs, the
    units' DOFs disjoint and at most ``max_dofs`` in all; a combination containing a kept
    smaller one is skipped.  Nearest first; each direction over the DOFs of its units,
    in ascending order.  After them, nearest first, the mirror pairs changed alone that
    the slab test culled only because another margin is predicted to fail first: the
    line search's full checks decide (a bench's legs moved apart, culled in the elastic
    model where a corner's margin of the leg under the load fell in the linearization
    but not in the checks, were otherwise found only with the seat widened to 790 mm
    as ballast); ``ContinuousSearch.run`` drops a direction found that contains one of
    them found too."""
    paired = {u for u, unit in enumerate(units) if len(unit.dofs) == 2}
    system = _system(margins)
    if system is None or not paired or max_dofs < 2:
        return []
    rates, values, violated, deficit = system
    basis = np.zeros((len(margins.dofs), len(units)))
    for u, unit in enumerate(units):
        basis[list(unit.dofs), u] = unit.coefficients
    unit_rates = rates @ basis                                       # (rows, units)
    relevant = set(_relevant(_strength(unit_rates[violated], deficit)))
    kept: list[Candidate] = []
    unsure: list[Candidate] = []       # mirror pairs alone that break another margin first
    working: set[int] = set()          # units that work alone (paired or not)
    for m in (1, 2):
        combos = [c for c in combinations(sorted(relevant), m)
                  if (m == 1 or any(u in paired for u in c))
                  and sum(len(units[u].dofs) for u in c) <= max_dofs
                  and len({i for u in c for i in units[u].dofs})
                  == sum(len(units[u].dofs) for u in c)
                  and not any(u in working for u in c)]
        if not combos:
            continue
        combos_array = np.array(combos, dtype=int).reshape(-1, m)
        breaking: list[Candidate] | None = [] if m == 1 else None
        for candidate in _evaluate(unit_rates, values, violated, deficit, combos_array,
                                   breaking)[0]:
            if m == 1:
                working.add(candidate.dofs[0])
                if candidate.dofs[0] not in paired:
                    continue            # one DOF alone: an ordinary candidate
            kept.append(_in_dofs(candidate, basis))
        unsure += [_in_dofs(candidate, basis) for candidate in breaking or ()
                   if candidate.dofs[0] in paired]
    kept.sort(key=lambda c: (c.enter, len(c.dofs), c.dofs))
    unsure.sort(key=lambda c: (c.enter, len(c.dofs), c.dofs))
    return kept + unsure


def culled_singles(margins: Margins) -> list[Candidate]:
    """Each DOF changed alone that the slab test culled only because another margin is
    predicted to fail first, nearest first: ``ContinuousSearch.directions``' fallback
    where no direction was kept at all, for the line search's full checks to decide
    (a desk's side moved out under its overhanging top, culled in the elastic model
    where the span it lengthens was predicted to sag first, holds from 154 to 294 mm
    out; without it the desk got only discrete fixes)."""
    system = _system(margins)
    if system is None:
        return []
    rates, values, violated, deficit = system
    relevant = _relevant(_strength(rates[violated], deficit))
    if not relevant:
        return []
    breaking: list[Candidate] = []
    _evaluate(rates, values, violated, deficit, np.array(relevant, dtype=int)[:, None],
              breaking)
    breaking.sort(key=lambda c: (c.enter, c.dofs))
    return breaking


def _system(margins: Margins) -> tuple[np.ndarray, ...] | None:
    """(rates (rows, n), values (rows,), violated (rows,) bool, deficit (violated,)): the
    margins' linearization that the directions are formed from; None without margins,
    DOFs or a violated margin."""
    rows = margins.margins
    if not rows or not margins.dofs:
        return None
    rates = np.array([m.rates for m in rows])                        # (rows, n)
    values = np.array([m.value for m in rows])
    violated = values < 0.0
    if not violated.any():
        return None
    deficit = np.array([m.target for m in rows])[violated] - values[violated]
    return rates, values, violated, deficit


def _in_dofs(candidate: Candidate, basis: np.ndarray) -> Candidate:
    """A candidate over units (``unit_candidates``) as one over the DOFs of its units."""
    real = basis[:, list(candidate.dofs)] @ candidate.direction
    dofs = tuple(int(i) for i in np.nonzero(real)[0])
    units = tuple(tuple(int(i) for i in np.nonzero(basis[:, u])[0]) for u in candidate.dofs)
    return Candidate(dofs, real[list(dofs)], candidate.enter, candidate.leave, units,
                     candidate.aim)


def _strength(rates: np.ndarray, deficit: np.ndarray) -> np.ndarray:
    """(n,): each DOF's largest rate on a violated margin (``rates``: (violated, n)) as a
    fraction of that margin's largest (see RELEVANT_RATE).  A margin that no DOF moves
    by RELEVANT_RATE of its ``deficit`` (target - value) within MAX_STEP counts for none:
    its rates are round-off, and its largest would weigh as much as a real one's.  A rate
    that is not a number counts as none, an infinite one as the largest there is."""
    size = np.nan_to_num(np.abs(rates), nan=0.0, posinf=np.finfo(float).max)
    top = size.max(axis=1, keepdims=True, initial=0.0)
    moved = (top > 0.0) & (top * MAX_STEP >= RELEVANT_RATE * deficit[:, None])
    return np.divide(size, top, out=np.zeros_like(size), where=moved).max(axis=0, initial=0.0)


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
              deficit: np.ndarray, combos: np.ndarray,
              breaking: list[Candidate] | None = None) -> tuple[list[Candidate], np.ndarray]:
    """Least-squares directions and slab tests of a batch of combinations; and how many
    were culled because a violated margin does not grow, another margin fails first, or
    the valid region is beyond MAX_STEP (3,) (in that order of precedence).  ``breaking``
    (when given) gets those culled only because another margin is predicted to fail
    first, within MAX_STEP."""
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
    facing_away = ~usable | ~np.isfinite(enter)
    breaks_other = ~facing_away & (enter >= leave)
    too_far = ~facing_away & ~breaks_other & (enter > MAX_STEP)
    culled = np.array([facing_away.sum(), breaks_other.sum(), too_far.sum()])
    if breaking is not None:
        breaking += [Candidate(tuple(int(i) for i in combos[b]), s[b].copy(),
                               float(enter[b]), float(leave[b]), aim=float(norm[b]))
                     for b in np.nonzero(breaks_other & (enter <= MAX_STEP))[0]]
    return [Candidate(tuple(int(i) for i in combos[b]), s[b].copy(), float(enter[b]),
                      float(leave[b]), aim=float(norm[b])) for b in np.nonzero(keep)[0]], culled
