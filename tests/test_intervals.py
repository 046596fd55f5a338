"""Honest intervals: a continuous suggestion's ``range`` is the valid interval along its
direction, and ``range`` of a DOF agrees with ``suggest``.

* Both ends of every interval are valid, and a step one resolution beyond each is not
  (the lower end is closed to LOWER_RESOLUTION of itself, the upper end to
  UPPER_RESOLUTION of the lower end); an upper end that is the search limit says so
  (``limited``) and is MAX_STEP itself.
* For every one-DOF suggestion, ``range`` of that DOF contains its change.
* The advice quotes magnitudes: the amount of its first phrase lies in the interval it
  quotes, whatever the sign of the change.

Over every invalid catalog design in both models (the suggestions are shared with
``test_cutlist``, ``conftest.catalog_suggestions``).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

from furncheck.check import check_file
from furncheck.dofs import dof_value, parse_dof, structure
from furncheck.edit_check import standing_geometry
from furncheck.geometry import analyze
from furncheck.ranges import RangeFinder
from furncheck.report.suggestions import advice
from furncheck.suggest.candidates import MAX_STEP
from furncheck.suggest.edits import Editor
from furncheck.suggest.line_search import LOWER_RESOLUTION, MIN_RESOLUTION, UPPER_RESOLUTION

CATALOG = Path(__file__).resolve().parents[1] / "designs"
MODELS = ("rigid", "elastic")
INVALID = [(path.name, model) for path in sorted(CATALOG.glob("*.yaml")) for model in MODELS
           if not check_file(str(path), model).valid]


def continuous(result):
    return [s for s in result.suggestions if s.kind == "continuous"]


@pytest.mark.parametrize("name, model", INVALID)
def test_interval_ends_are_checked(catalog_suggestions, name, model):
    """Each end valid, one resolution beyond it invalid (or the search limit)."""
    design, result = catalog_suggestions(name, model)
    suggestions = continuous(result)
    if not suggestions:
        return
    geometry = analyze(design)
    editor = Editor(design, geometry, structure(design, standing_geometry(geometry)))
    for s in suggestions:
        dofs = tuple(parse_dof(design, n) for n in s.dofs)
        direction = np.array(s.direction)
        low, high = s.range

        def margin(step, dofs=dofs, direction=direction):
            return editor.margin_at(dofs, direction, step)

        assert margin(low) >= 0.0 and margin(high) >= 0.0, (name, s.rank)
        assert margin(low - max(LOWER_RESOLUTION * low, MIN_RESOLUTION)) < 0.0, (name, s.rank)
        if s.limited:
            assert high == MAX_STEP
        else:
            beyond = high + max(UPPER_RESOLUTION * low, MIN_RESOLUTION)
            assert margin(beyond) < 0.0, (name, s.rank, s.range)


@pytest.mark.parametrize("name, model", INVALID)
def test_range_contains_every_one_dof_change(catalog_suggestions, name, model):
    """``range`` of the DOF of every one-DOF suggestion contains the suggested value (the
    current value plus its change)."""
    design, result = catalog_suggestions(name, model)
    single = [s for s in continuous(result) if len(s.dofs) == 1]
    if not single:
        return
    ranges = RangeFinder(design).ranges([s.dofs[0] for s in single])
    for s, found in zip(single, ranges):
        value = dof_value(design, parse_dof(design, s.dofs[0]))
        assert found.valid is not None, (name, s.dofs, found.reason)
        lower, upper = found.valid
        assert lower <= value + s.changes[0] <= upper, (name, s.dofs, s.changes, found)


_NUMBER = r"(\d+(?:\.\d+)?)"


@pytest.mark.parametrize("name, model", INVALID)
def test_advice_amount_lies_in_its_quoted_interval(catalog_suggestions, name, model):
    """'Move leg_r 260 mm ... (valid for 220-301 mm)': 220 <= 260 <= 301, no minus sign
    in the amount or the interval (rounded to the advice's three digits)."""
    design, result = catalog_suggestions(name, model)
    for s in continuous(result):
        text = advice(s, design)
        quoted = re.search(rf"valid for {_NUMBER}-{_NUMBER} ", text)
        amount = re.search(rf" {_NUMBER} (mm|degrees)", text)
        assert quoted and amount, text
        low, high = float(quoted.group(1)), float(quoted.group(2))
        first = float(amount.group(1))
        assert low <= first * (1 + 5e-3) and first <= high * (1 + 5e-3), text
        assert not re.search(r"[ (]-\d", text), text
        assert math.isclose(first, abs(s.changes[0]), rel_tol=5e-3), text
