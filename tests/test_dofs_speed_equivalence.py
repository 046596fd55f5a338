"""The fast paths of ``apply_dof``: plain-float plank views and the per-design turn cache.

``Plank.axes`` and ``Plank.half_sizes`` must be the very numbers of ``rotation_matrix`` and
``half_extents``; a ``Structure`` reused across calls and designs (it remembers the
angle-independent part of each turn) must give what a fresh one gives.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from furncheck.design import load_design
from furncheck.design.model import Plank
from furncheck.dofs import Blocked, OutOfReach, all_dofs, apply_dof, parse_dof, structure
from furncheck.geometry import analyze

DESIGNS = Path(__file__).resolve().parent.parent / "designs"
CATALOG = sorted(DESIGNS.glob("*.yaml"))


def _outcome(design, frame, dof, step):
    try:
        return apply_dof(design, frame, dof, step)
    except (Blocked, OutOfReach) as error:
        return type(error).__name__, str(error)


def test_plain_float_views_are_the_numpy_numbers():
    plank = Plank("p", 0.8, 0.3, 0.018, (0.1, -0.2, 0.5), (12.5, -33.0, 171.0))
    axes = np.array(plank.axes).T
    assert np.array_equal(axes, plank.rotation_matrix)
    assert np.array_equal(np.array(plank.half_sizes), plank.half_extents)


@pytest.mark.parametrize("path", CATALOG, ids=lambda p: p.stem)
def test_reused_frame_gives_what_a_fresh_one_gives(path):
    design = load_design(str(path))
    geometry = analyze(design)
    shared = structure(design, geometry)
    rotations = [dof for dof in all_dofs(design) if dof.is_rotation]
    for dof in rotations:
        for step in (2.0, -7.5):
            assert _outcome(design, shared, dof, step) == \
                _outcome(design, structure(design, geometry), dof, step)
    # another design through the same frame: the remembered turns must not be reused
    edited = None
    for dof in all_dofs(design):
        outcome = _outcome(design, shared, dof, 1.0 if dof.is_rotation else 3.0)
        if not isinstance(outcome, tuple):
            edited = outcome
            break
    assert edited is not None
    for dof in rotations:
        assert _outcome(edited, shared, dof, 3.0) == \
            _outcome(edited, structure(design, geometry), dof, 3.0)


def test_cabinet_rotation_unchanged_by_repetition():
    design = load_design(str(DESIGNS / "cabinet-28.yaml"))
    frame = structure(design, analyze(design))
    dof = parse_dof(design, "cap.rx")
    first = apply_dof(design, frame, dof, 3.0)
    assert all(apply_dof(design, frame, dof, 3.0) == first for _ in range(3))
