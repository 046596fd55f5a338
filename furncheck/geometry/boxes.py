"""Which plank boxes meet: pairs of axis-aligned boxes by sort and sweep.

The joint detection, the near-miss search and the interpenetration test each start from
the plank pairs whose world bounding boxes meet (or overlap) within a slack.  Comparing
all pairs costs n^2 (a 2,000-plank wall: four million pairs, 1.3 s of the geometry and
tens of MB); here the boxes are sorted by their lower end along one axis and each box is
compared only with the boxes that start before it ends along that axis (sort and sweep),
then the candidates are tested on all three axes with the same comparisons as the
all-pairs test, so the pairs found are exactly the same, in the same order (i < j,
row-major).  The sweep axis is the one that leaves the fewest candidates.
"""

from __future__ import annotations

import numpy as np


def meeting_pairs(lo: np.ndarray, hi: np.ndarray, slack: float) -> np.ndarray:
    """(P, 2) int pairs (i < j, row-major order) of boxes (lower ``lo``, upper ``hi``
    corners, (n, 3) m) that meet within ``slack`` along every axis:
    lo_i <= hi_j + slack and lo_j <= hi_i + slack."""
    i, j = _candidates(lo, hi, abs(slack))
    keep = np.all((lo[i] <= hi[j] + slack) & (lo[j] <= hi[i] + slack), axis=1)
    return _ordered(i[keep], j[keep])


def overlapping_pairs(lo: np.ndarray, hi: np.ndarray, slack: float) -> np.ndarray:
    """(P, 2) int pairs (i < j, row-major order) of boxes that overlap by more than
    ``slack`` along every axis: lo_i < hi_j - slack and lo_j < hi_i - slack."""
    i, j = _candidates(lo, hi, abs(slack))
    keep = np.all((lo[i] < hi[j] - slack) & (lo[j] < hi[i] - slack), axis=1)
    return _ordered(i[keep], j[keep])


def _candidates(lo: np.ndarray, hi: np.ndarray, reach: float) -> tuple[np.ndarray, np.ndarray]:
    """Candidate pairs (i, j), each unordered pair once: along the sweep axis, j starts at
    or after i (sorted by lower end) and no farther than ``reach`` past i's upper end -- a
    superset of the pairs that meet or overlap within a slack of at most ``reach``."""
    n = len(lo)
    if n < 2:
        return np.zeros(0, dtype=int), np.zeros(0, dtype=int)
    best = None
    for axis in range(lo.shape[1]):
        order = np.argsort(lo[:, axis], kind="stable")
        starts = lo[order, axis]
        ends = np.searchsorted(starts, hi[order, axis] + reach, side="right")
        count = np.maximum(ends - np.arange(n) - 1, 0)
        if best is None or count.sum() < best[2].sum():
            best = (order, ends, count)
    order, ends, count = best
    first = np.repeat(np.arange(n), count)
    offsets = np.arange(len(first)) - np.repeat(np.cumsum(count) - count, count)
    second = first + 1 + offsets
    return order[first], order[second]


def _ordered(i: np.ndarray, j: np.ndarray) -> np.ndarray:
    """The pairs as (min, max) rows sorted row-major, as ``np.argwhere`` of an upper
    triangle gives them."""
    low, high = np.minimum(i, j), np.maximum(i, j)
    order = np.lexsort((high, low))
    return np.column_stack([low[order], high[order]]).astype(int).reshape(-1, 2)
