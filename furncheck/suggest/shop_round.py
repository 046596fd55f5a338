"""Suggested changes in amounts a maker measures and cuts: ``rounded_changes``.

A continuous suggestion's smallest valid change plus its reserve is a number like 39.71 mm
or 1.31 mm each; in the shop a plank is shortened by 40 mm and two sides are moved 1.5 mm
closer each.  So each DOF's change is rounded to the shop's grid of its unit (GRIDS: whole
millimetres first, then half millimetres; half degrees, then tenths), each change on its
own and mirror pairs alike (the rounding is symmetric about zero).  The suggestion's design
is then made from the rounded changes and validated like any other (``ranking._written``);
the first rounding whose design is valid is the suggestion, the exact changes only when
none is.

Roundings are tried in order: to the nearest grid point, then away from zero (a little
more of a change that works), then toward zero, coarse grid before fine.  A rounding is
tried only when every DOF's change stays on the valid side of the search (the step it
implies along the direction, ``change / (direction x scale)``, within the interval whose
ends were checked) and no change is rounded to zero (that would drop a DOF from the
suggestion); at most MOST_TRIED are tried.
"""

from __future__ import annotations

import math

from furncheck import tolerances as tol

GRIDS = {"mm": (1.0, 0.5), "m": (0.001, 0.0005), "deg": (0.5, 0.1)}
"""Per unit of a DOF's change: the grids tried, coarse first (whole millimetres, the cut a
maker marks with a rule; half degrees, the mark of a protractor)."""

MOST_TRIED = 3
"""Most rounded changes validated before the exact ones are kept."""


def rounded_changes(changes: tuple[float, ...], units: tuple[str, ...],
                    rates: tuple[float, ...], low: float, high: float
                    ) -> list[tuple[float, tuple[float, ...]]]:
    """The roundings of ``changes`` (each in its unit of ``units``) worth validating,
    preferred first (module docstring), as (step, changes): ``rates`` is each DOF's change
    per unit step (direction x scale), ``low`` .. ``high`` the valid steps; the step is
    the first DOF's.  At most MOST_TRIED; none that equals ``changes``."""
    found: list[tuple[float, tuple[float, ...]]] = []
    for level in range(2):
        for rule in (_nearest, _away, _toward):
            rounded = tuple(rule(change, GRIDS.get(unit, (0.0, 0.0))[level])
                            for change, unit in zip(changes, units))
            if rounded == tuple(changes) or any(r == rounded for _, r in found):
                continue
            if any(change != 0.0 and value == 0.0 for change, value in zip(changes, rounded)):
                continue
            steps = [value / rate for value, rate in zip(rounded, rates) if rate != 0.0]
            slack = tol.STEP_ROUNDOFF * max(abs(low), abs(high))
            if not steps or not all(low - slack <= step <= high + slack for step in steps):
                continue
            found.append((steps[0], rounded))
            if len(found) == MOST_TRIED:
                return found
    return found


def _nearest(value: float, grid: float) -> float:
    return _on_grid(value, grid, lambda size: math.floor(size + 0.5))


def _away(value: float, grid: float) -> float:
    return _on_grid(value, grid, math.ceil)


def _toward(value: float, grid: float) -> float:
    return _on_grid(value, grid, math.floor)


def _on_grid(value: float, grid: float, whole) -> float:
    """``value`` on the grid, its size rounded by ``whole`` (the sign kept, so a change and
    its mirror round alike); unchanged for a grid of 0 (a unit without one)."""
    if grid <= 0.0 or value == 0.0:
        return value
    size = abs(value) / grid
    rounded = whole(round(size, 9)) * grid        # 39.999999999 mm is 40 mm, not 39
    return math.copysign(float(f"{rounded:.10g}"), value)
