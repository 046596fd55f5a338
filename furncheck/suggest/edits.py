"""Moving a design along a direction of several DOFs, and deciding whether the result is a
design the suggestion may offer (paper sections 6.1 and 6.4).

A direction is a unit vector ``s`` over m DOFs in *scaled* units (paper 6.1): a length DOF
is divided by the design's size (its largest bounding-box edge), a rotation is in radians,
so a step ``t`` along ``s`` changes DOF k by ``t s_k`` of its scale.  The DOFs are applied
one after the other with the geometric constraints of ``dofs`` (neighbours follow); between
them the constraint structure is carried along (``_carried``), so a turned face plank keeps
its edge planks' ends on its turned face.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from furncheck.design.model import Design
from furncheck.dofs import (
    Blocked,
    Dof,
    End,
    OutOfReach,
    Structure,
    apply_dof,
    design_size,
    dof_value,
)
from furncheck.edit_check import design_problem
from furncheck.geometry import (
    Geometry,
    analyze,
    cut_in_pairs,
    drawn_through_closing,
    interpenetrations,
)
from furncheck.result import DesignReport
from furncheck.statics import CaseStatics, LineStarts, build_model, solve_load_case
from furncheck.validity import case_margin

MARGIN_EPS = 1e-12
"""The margin of an invalid design is at most -MARGIN_EPS (a joint within the capacity's
round-off slack of failing still counts as failing when the verdict says so)."""

LOCK_EPS = 1e-9
"""A locked DOF counts as changed when it moves by more than this (its unit)."""


def dof_scale(design: Design, dof: Dof) -> float:
    """The DOF's change (file unit or degrees) per scaled unit: the design's size for
    lengths, 180 / pi for rotations (paper 6.1: dimensionless like radians)."""
    return math.degrees(1.0) if dof.is_rotation else design_size(design)


class Editor:
    """Designs along directions from one design: ``moved`` applies DOF changes, ``keeps``
    and ``margin_at`` say whether a moved design may be suggested."""

    def __init__(self, design: Design, geometry: Geometry, frame: Structure,
                 locked: tuple[Dof, ...] = (), starts: tuple[CaseStatics, ...] | None = None):
        """``starts``: the design's load cases solved (``check.case_statics``), where the
        contact iterations of the moved designs start (``margin_at``), if the caller
        has them."""
        self.design = design
        self.starts = starts
        self._line: tuple[tuple, LineStarts] | None = None   # the last direction's
        self.geometry = geometry
        self.frame = frame
        self.locked = locked
        self.scales: dict[Dof, float] = {}
        self._joints = _joint_set(geometry)
        self._closing = {miss.planks for miss in geometry.near_misses if len(miss.planks) == 2} \
            | cut_in_pairs(design, geometry) | drawn_through_closing(design, geometry)
        self.checks = 0

    def scale(self, dof: Dof) -> float:
        if dof not in self.scales:
            self.scales[dof] = dof_scale(self.design, dof)
        return self.scales[dof]

    def changes(self, dofs: tuple[Dof, ...], direction: np.ndarray,
                step: float) -> tuple[float, ...]:
        """Each DOF's change (its unit) at ``step`` along ``direction``."""
        return tuple(float(step * s * self.scale(dof)) for dof, s in zip(dofs, direction))

    def moved(self, dofs: tuple[Dof, ...], changes: tuple[float, ...]) -> Design:
        """The design with each DOF changed by its amount, in order, neighbours following.
        Raises Blocked or OutOfReach when a change cannot be made, and Blocked when it
        would move a locked DOF."""
        design, frame = self.design, self.frame
        for dof, change in zip(dofs, changes):
            if change == 0.0:
                continue
            edited = apply_dof(design, frame, dof, change)
            frame = _carried(frame, design, edited)
            design = edited
        moved_lock = self.moved_lock(design)
        if moved_lock is not None:
            raise Blocked(f"it would change the locked {moved_lock}")
        return design

    def moved_lock(self, edited: Design) -> str | None:
        """The first locked DOF that ``edited`` changes, or None."""
        for lock in self.locked:
            if abs(dof_value(edited, lock) - dof_value(self.design, lock)) > LOCK_EPS:
                return lock.name
        return None

    def keeps(self, edited: Design) -> Geometry | None:
        """The geometry of ``edited`` if it has no geometric violation, keeps the joints of
        the design (none lost; none added unless the joints are listed in the file, or
        the design missed that joint narrowly, or a plank joined to nothing, or drawn
        through the other, cut its end into that face (``geometry.cut_in_pairs``,
        ``drawn_through_closing``): closing it is the point) and no two
        planks cut into each other; else None.  Ground contacts may change: standing a
        hovering leg on the floor is the point of some suggestions.  A plank shrunk to no
        length or width, or an anchor moved off its wall, is refused too
        (``edit_check.design_problem``)."""
        self.checks += 1
        if design_problem(edited) is not None:
            return None
        geometry = analyze(edited, (self.design, self.geometry))
        if geometry.violations:
            return None
        joints = _joint_set(geometry)
        added = {(face, edge) for face, edge, _ in joints - self._joints}
        if not self._joints <= joints or \
                (self.design.joints is None and not added <= self._closing):
            return None
        if interpenetrations(edited):
            return None
        return geometry

    def margin_at(self, dofs: tuple[Dof, ...], direction: np.ndarray, step: float) -> float:
        """How valid the design ``step`` along ``direction`` is: >= 0 exactly when it is
        valid and keeps the design's joints (``keeps``).  Where only joints (and, elastic
        model, planks' sag and stress) fail, or none, it is the smallest 1 - utilization over
        all of them and all cases, continuous in the step, so that a line search can
        interpolate; every other failure (a step that
        cannot be made, a geometric problem, a case that topples or slides) is -inf.
        The same verdict as ``utilization_margin(check_design(...))``, without building
        the report; each case's contact iterations start where the case settled in the
        nearest step along the direction checked so far, or in the design itself
        (``statics.LineStarts``, from ``starts``: the same equilibrium, sooner)."""
        try:
            edited = self.moved(dofs, self.changes(dofs, direction, step))
        except (Blocked, OutOfReach):
            return -math.inf
        geometry = self.keeps(edited)
        if geometry is None:
            return -math.inf
        model = build_model(edited, geometry)
        line = self._line_starts(dofs, direction)
        starts = None if line is None else line.near(step)
        solved: dict = {}
        worst, holds = 1.0, True
        for k, case in enumerate(edited.load_cases):
            solved[k] = solve_load_case(model, case, None if starts is None else starts[k])
            margin, case_ok = case_margin(edited, geometry, model, solved[k])
            worst, holds = min(worst, margin), holds and case_ok
            if margin == -math.inf:
                break
        if line is not None:
            line.keep(step, solved)
        return -math.inf if worst == -math.inf else signed_margin(worst, holds)

    def _line_starts(self, dofs: tuple[Dof, ...], direction: np.ndarray) -> LineStarts | None:
        """The ``LineStarts`` of the direction (the last one asked for: a line search
        probes one direction at a time), None without the design's own ``starts``."""
        if self.starts is None:
            return None
        key = (dofs, direction.tobytes())
        if self._line is None or self._line[0] != key:
            self._line = (key, LineStarts(self.starts))
        return self._line[1]


_UTILIZATION_KINDS = frozenset({"non-durable", "sagging", "overstressed"})
"""The violations measured by a utilization (joints, and planks in the elastic model): a
margin through them is continuous in an edit."""


def utilization_margin(report: DesignReport) -> float:
    """>= 0 exactly when the report is valid: the smallest 1 - utilization of its joints,
    anchors and (elastic model) planks where at most those fail, else -inf (the same as
    ``Editor.margin_at``, through ``validity.case_margin``)."""
    if any(v.kind not in _UTILIZATION_KINDS for v in report.violations):
        return -math.inf
    used = [joint.utilization for case in report.cases for joint in case.joints]
    used += [plank.utilization for case in report.cases for plank in case.planks or ()]
    used += [anchor.utilization for case in report.cases for anchor in case.anchors]
    return signed_margin(min((1.0 - u for u in used), default=1.0), report.valid)


def signed_margin(worst: float, holds: bool) -> float:
    """The margin of a design whose smallest 1 - utilization is ``worst``: >= 0 exactly
    when it ``holds`` (a utilization at its capacity to round-off still holds)."""
    return max(worst, 0.0) if holds else min(worst, -MARGIN_EPS)


def _joint_set(geometry: Geometry) -> set[tuple]:
    return {(j.face, j.edge, j.edge_face) for j in geometry.joints}


def _carried(frame: Structure, before: Design, after: Design) -> Structure:
    """The constraint structure after an edit: the supporting-face normal of every held
    end turns with the plank it rests on (ground ends keep the vertical)."""
    turns = {}
    for old, new in zip(before.planks, after.planks):
        if old.rotation != new.rotation:
            turns[old.id] = new.rotation_matrix @ old.rotation_matrix.T
    if not turns:
        return frame

    def turned(end: End) -> End:
        if end.on not in turns:
            return end
        return replace(end, normal=turns[end.on] @ end.normal)

    ends = {plank: tuple(turned(end) for end in held) for plank, held in frame.ends.items()}
    attached = {plank: tuple((edge, turned(end)) for edge, end in items)
                for plank, items in frame.attached.items()}
    return replace(frame, ends=ends, attached=attached)
