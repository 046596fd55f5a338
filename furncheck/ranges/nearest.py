"""The range of a DOF of an *invalid* design: the valid interval nearest its value.

A valid window can be as narrow as twice the tolerance (a shelf 3 mm short of the side it
should be nailed to joins when lengthened by 2.5 to 3.5 mm), far narrower than any
sampling of the search's reach finds.  So the window is first looked for where
``suggest`` looks: at the step the linearized margins predict for this DOF alone
(``suggest.margins``, ``suggest.candidates`` with one DOF: the step at which every
violated margin is restored), probed at PREDICTED_PROBES times that step, and where the
first of them fails, at the least-squares step toward the margins' targets if it lies
before that probe (as ``suggest`` does where its first probe fails outright; a range's
probe says only valid or not: a board 94 mm above the floor is valid lowered by 93.5 to
94.5 mm, the predicted 93.5 mm is the window's near edge, and 1.05 times it is past the
far one); a valid probe is widened to the interval around it, each end closed to the
finest of the range's resolution, WINDOW_RESOLUTION of the step and, for a length found
at the aim, WINDOW_TOLERANCE of the design's tolerance.  A DOF without a
prediction, or whose probes all fail, is sampled outward from the value as before (from 1/64
of the reach out, each probe sqrt(2) times the last, both sides, the sensitivity's favoured
side first); where none is valid, the range says how it was sampled, since a window
narrower than the gap between two probes can lie between them.
``suggest`` and ``range`` see the same edits (the constraint structure of
``edit_check.standing_geometry``), so a one-DOF suggestion's change lies in the range of
its DOF.
"""

from __future__ import annotations

from furncheck import tolerances as tol
from furncheck.check import check_design
from furncheck.design.model import Design
from furncheck.dofs import Dof, Structure
from furncheck.geometry import Geometry

OUTWARD_SAMPLES = 13
"""Where the window is sampled outward from the value, the probes each way: from 1/64 of
the reach out to the reach, each sqrt(2) times the one before (doubling, 7 probes, stepped
over a 52 mm window between 95 and 190 mm of a headboard's 1524 mm reach)."""

PREDICTED_PROBES = (1.05, 1.0, 0.85, 1.5, 2.25, 3.4)
"""Multiples of the predicted step probed, in order: the first as ``suggest``'s line
search's first probe, the second the predicted step itself, which that line search
tries where its first probe fails (the window may end between the prediction and its
overshoot: bench-tips' seat, shortened, is valid from 521 to 558 mm shorter, predicted
542, first probed at 569, where its seat, now checked as a plate too, sags)."""

WINDOW_RESOLUTION = 0.02
"""The ends of a window found at a predicted step are closed to at most this fraction of
the step (a window of a few millimetres needs a finer bracket than the range's 0.1 % of
the design's size), and where the window was found at the aim (a geometric repair), for
a length, to at most WINDOW_TOLERANCE of the design's tolerance."""


def window_resolution(design: Design) -> float:
    """The length (the file's unit) to which a geometric repair's window is closed in a
    length DOF: WINDOW_TOLERANCE of the design's tolerance (``suggest.line_search`` too;
    each floors it: WINDOW_FLOOR here in ``_predicted_window``, MIN_RESOLUTION there)."""
    return tol.WINDOW_TOLERANCE * design.tolerance / design.unit_scale


def predicted_steps(design: Design, geometry: Geometry, frame: Structure,
                    locked: tuple[Dof, ...], dofs: list[Dof]
                    ) -> dict[Dof, tuple[float, float]]:
    """Per DOF of ``dofs`` (among the strongest ``suggest`` combines): the signed changes
    (its unit) at which the linearized margins of the invalid ``design`` are all restored
    when this DOF alone changes, and at which they meet their targets (``Candidate.enter``
    and ``aim``; the aim inf where unknown); DOFs with no such change are left out."""
    # suggest builds on ranges (its line search's geometric estimates): imported here
    from furncheck.suggest.candidates import every_candidate
    from furncheck.suggest.edits import Editor
    from furncheck.suggest.margins import Margins

    free = [dof for dof in dict.fromkeys(dofs) if dof not in locked]
    if not free:
        return {}
    report = check_design(design, geometry)
    editor = Editor(design, geometry, frame, locked)
    margins = Margins(design, geometry, report, editor, free)
    steps: dict[Dof, tuple[float, float]] = {}
    for candidate in every_candidate(margins, 1):
        dof = margins.dofs[candidate.dofs[0]]
        along = float(candidate.direction[0] * editor.scale(dof))
        steps.setdefault(dof, (along * candidate.enter, along * candidate.aim))
    return steps


def outward_samples(limit: float) -> list[float]:
    """The steps at which the window is sampled outward, each way (OUTWARD_SAMPLES)."""
    return [limit * 2.0 ** (-k / 2) for k in range(OUTWARD_SAMPLES - 1, -1, -1)]


def nearest_window(finder, dof: Dof, limit: float, resolution: float,
                   predicted: tuple[float, float] | None):
    """Search (a generator of ``finder``'s evaluations, ``ranges.RangeFinder``) of the
    valid window of ``dof`` of an invalid design: ((inner, outer) signed changes of its
    ends, which interval it is), or None when none is found within ``limit``."""
    if predicted is not None:
        window = yield from _predicted_window(finder, dof, predicted, limit, resolution)
        if window is not None:
            return window, "valid interval where the sensitivities point (where suggest looks)"
    samples = outward_samples(limit)
    order = (1.0, -1.0) if finder._favoured_sign(dof) > 0 else (-1.0, 1.0)
    for previous, step in zip([0.0] + samples, samples):
        for sign in order:
            if (yield from finder._valid_at(dof, sign * step)):
                inner = yield from finder._bisect(dof, sign, step, previous, resolution)
                outer = yield from finder._expand(dof, sign, step, limit, resolution)
                return (sign * inner, sign * outer), "nearest valid interval"
    return None


def _predicted_window(finder, dof: Dof, predicted: tuple[float, float], limit: float,
                      resolution: float):
    """The valid window at the ``predicted`` changes of ``dof`` (``predicted_steps``):
    (inner, outer) signed changes of its ends, nearer end first, or None when no probe is
    valid."""
    near, aim = predicted
    sign = 1.0 if near > 0.0 else -1.0
    size = abs(near)
    fine = min(resolution, WINDOW_RESOLUTION * size)
    steps = [min(size * factor, limit) for factor in PREDICTED_PROBES]
    if size <= sign * aim < steps[0]:
        steps.insert(1, sign * aim)
    invalid = [0.0]
    for step in steps:
        if (yield from finder._valid_at(dof, sign * step)):
            if step == sign * aim and not dof.is_rotation:   # a geometric repair's window
                fine = min(fine, window_resolution(finder.design))
            if not dof.is_rotation:     # no finer than this (tolerance 0, a tiny step)
                fine = max(fine, tol.WINDOW_FLOOR / finder.design.unit_scale)
            below = max(s for s in invalid if s < step)
            inner = yield from finder._bisect(dof, sign, step, below, fine)
            outer = yield from finder._expand(dof, sign, step, limit, fine)
            return sign * inner, sign * outer
        invalid.append(step)
    return None
