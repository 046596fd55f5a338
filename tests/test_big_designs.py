"""Big designs: the parts that replace all-pairs and all-planks loops by near-linear ones
give exactly what the quadratic definitions give (box pairs by sort and sweep, the planks
that carry each plank), and the size guard of the commands."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from furncheck.geometry.boxes import meeting_pairs, overlapping_pairs


def _all_pairs(lo, hi, slack, strict):
    """The definition: every pair i < j compared on every axis, row-major."""
    if strict:
        meet = np.all((lo[:, None, :] < hi[None, :, :] - slack)
                      & (lo[None, :, :] < hi[:, None, :] - slack), axis=2)
    else:
        meet = np.all((lo[:, None, :] <= hi[None, :, :] + slack)
                      & (lo[None, :, :] <= hi[:, None, :] + slack), axis=2)
    return np.argwhere(np.triu(meet, k=1))


_coordinate = st.integers(0, 12).map(lambda k: 0.25 * k)     # ties and touching faces


@settings(max_examples=150, deadline=None)
@given(st.lists(st.tuples(_coordinate, _coordinate, _coordinate,
                          _coordinate, _coordinate, _coordinate), min_size=0, max_size=30),
       st.sampled_from([0.0, 0.001, 0.25, 0.5]))
def test_box_pairs_are_the_all_pairs_ones(boxes, slack):
    """Sort and sweep finds exactly the pairs of the all-pairs comparison, in the same
    order, for meeting (<= with + slack) and overlapping (< with - slack) boxes; the
    coordinates are on a 0.25 grid, so boxes tie, touch, and meet exactly at the slack."""
    corners = np.array(boxes, dtype=float).reshape(-1, 2, 3)
    lo, hi = corners.min(axis=1), corners.max(axis=1)
    assert np.array_equal(meeting_pairs(lo, hi, slack), _all_pairs(lo, hi, slack, False))
    assert np.array_equal(overlapping_pairs(lo, hi, slack), _all_pairs(lo, hi, slack, True))


def test_box_pairs_of_a_row_of_touching_boxes():
    """Five unit cubes in a row along x, each touching the next: with no slack the
    neighbours meet (4 pairs), none overlap; a slack of 1.0 reaches the next but one too
    (4 + 3 pairs: 2 <= 1 + 1); "overlapping by more than -1.0" holds for the neighbours
    only (the next but one starts at 2, not below 1 + 1)."""
    lo = np.array([[k, 0.0, 0.0] for k in range(5)])
    hi = lo + 1.0
    assert meeting_pairs(lo, hi, 0.0).tolist() == [[0, 1], [1, 2], [2, 3], [3, 4]]
    assert overlapping_pairs(lo, hi, 0.0).tolist() == []
    assert len(meeting_pairs(lo, hi, 1.0)) == 7
    assert overlapping_pairs(lo, hi, -1.0).tolist() == [[0, 1], [1, 2], [2, 3], [3, 4]]


def _carriers_by_definition(n, pairs, grounded):
    """Per plank: take it away, search from the other grounded planks, keep the
    neighbours reached (one search per plank)."""
    neighbours = [set() for _ in range(n)]
    for a, b in pairs:
        neighbours[a].add(b)
        neighbours[b].add(a)
    out = []
    for removed in range(n):
        reached = {k for k in grounded if k != removed}
        frontier = list(reached)
        while frontier:
            k = frontier.pop()
            for other in neighbours[k] - reached - {removed}:
                reached.add(other)
                frontier.append(other)
        out.append(neighbours[removed] & reached)
    return out


@settings(max_examples=200, deadline=None)
@given(st.integers(1, 14).flatmap(lambda n: st.tuples(
    st.just(n),
    st.lists(st.tuples(st.integers(0, n - 1), st.integers(0, n - 1))
             .filter(lambda p: p[0] != p[1]), max_size=3 * n),
    st.sets(st.integers(0, n - 1), max_size=n))))
def test_carriers_match_the_definition(graph):
    """The one-search answer equals the one-search-per-plank definition on random joint
    graphs: repeated joints, planks on nothing, several grounded planks, cycles."""
    from furncheck.statics.bending import carriers

    n, pairs, grounded = graph
    assert carriers(n, pairs, grounded) == _carriers_by_definition(n, pairs, grounded)


def test_carriers_of_a_shelf_and_a_hanging_lip():
    """Two sides (0, 1) on the floor with a shelf (2) nailed between them, a lip (3) nailed
    under the shelf only: the sides carry the shelf and the shelf braces each side (it
    still reaches the other side's floor), the lip carries nothing and the shelf is the
    lip's only carrier."""
    from furncheck.statics.bending import carriers

    assert carriers(4, [(0, 2), (1, 2), (2, 3)], {0, 1}) == [{2}, {2}, {0, 1}, {2}]


def _shelving(columns, rows, model, heavy_kg=None):
    import sys
    from pathlib import Path

    from furncheck.design.model import with_model

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
    from shelving import shelving_wall

    return with_model(shelving_wall(columns, rows, heavy_kg=heavy_kg), model)


@pytest.mark.parametrize("model", ["elastic", "rigid"])
def test_implicit_condensation_solves_as_the_stored_one(model, monkeypatch):
    """A condensation too large to keep X = A_ii^-1 A_ig (forced here by a limit of 0
    bytes) sums S0 a few columns at a time and solves for X x_g: the same statics as the
    stored X up to round-off, in both large paths (a 73-plank wall: 438 rigid plank
    displacements, above DENSE_PLANKS_MAX, and its elastic model's beams), for the
    case's solve and for the sensitivity's many right-hand sides."""
    from furncheck import tolerances as tol
    from furncheck.geometry import analyze
    from furncheck.statics import build_model, solve_load_case, solve_system

    design = _shelving(8, 8, model)
    geometry = analyze(design)
    results = []
    for limit in (tol.CONDENSED_DENSE_BYTES, 0):
        monkeypatch.setattr(tol, "CONDENSED_DENSE_BYTES", limit)
        statics_model = build_model(design, geometry)
        assert (statics_model.condensation.reduced is None) == (limit == 0)
        statics = solve_load_case(statics_model, design.load_cases[0])
        rhs = np.random.default_rng(1).normal(size=(len(statics.state), 3))
        results.append((statics.joint_wrenches, statics.contact_forces,
                        solve_system(statics_model, statics.holding, rhs)))
    for stored, implicit in zip(*results):
        assert np.allclose(implicit, stored, rtol=1e-9, atol=1e-9 * np.abs(stored).max())
