"""What a suggestion has to restore: the design's validity margins and their rates.

Every check of contract section 3 that can fail by degrees becomes a *margin*, a
dimensionless number that is >= 0 exactly where the design passes it, with its derivative
(``rates``) with respect to each free DOF in scaled units (``edits``):

* durability (paper eq. 7, our eq. 4/5 per nail), per joint and stable load case:
  ``1 - pull / pull capacity`` and ``1 - shear / shear capacity``; rates from the force
  sensitivity (eq. 6) of the solved case;
* stability, for a case that topples (paper eq. 8): each ground contact's normal force in
  the case's *bolted* state (every contact held), over the case's weight -- all of them
  non-negative means the load's line of action is back inside the support; rates from eq. 6
  of the bolted state;
* stability, for a case that slides: ``(mu W - H) / W`` per grounded component, W the
  weight it stands on, H the sideways load it must resist (nothing else can change what
  friction gives: only W does, through the planks' own weight);
* geometry, for a design whose joints or ground contacts are wrong: ``(tolerance -
  distance) / size`` for the gap of a listed joint, the depth of a corner in the ground and
  the height of a hovering plank above it; rates by central differences of the geometry.

The paper approximates the durable region by a cuboid in joint-bending space; these margins
are its faces (one per nail force and joint), so the ray test of eq. 10 is a slab test on
them (``candidates``).  The margins of each physical kind are built in ``margin_kinds``.
"""

from __future__ import annotations

import copy

import numpy as np

from furncheck.design.model import Design
from furncheck.dofs import Blocked, Dof, OutOfReach, design_size
from furncheck.geometry import Geometry, box_neighbours, cut_ins, end_depth, end_gap
from furncheck.geometry.near import carried_groups, hovering_ends
from furncheck.geometry.support import convex_hull, outside, pressure_centre
from furncheck.result import DesignReport
from furncheck.sensitivity import Linearization
from furncheck.statics import StaticsModel, build_model
from furncheck.suggest.edits import Editor
from furncheck.suggest.margin_kinds import (
    Margin,
    anchor_margins,
    bending_margins,
    component_loads,
    cone_margins,
    durability_margins,
    toppling_margins,
)

GEOMETRY_STEP = 1e-4
"""Central-difference step of the geometric margins, in scaled DOF units."""

HOVER_BAND = 0.02
"""A hovering plank counts as one that should reach the floor when its lowest corner is
within this fraction of the design's size above the component's lowest corner."""

HOVER_REACH = 0.5
"""A design that topples may be stood on a leg drawn short: planks standing on an end
that hang at most this fraction of the design's size above the floor (as far as the
candidates' search reaches, ``candidates.MAX_STEP``) are brought down to it
(``Margins.alternatives``)."""


class Margins:
    """The margins of an invalid design over its free DOFs.

    dofs    : the free DOFs (not locked, able to move), in design order
    blocked : DOF name -> why it cannot be part of a suggestion
    margins : every margin; ``violated`` those below zero
    alternatives : other margin sets that restore the design another way, each searched
              for directions of its own (``with_margins``): for a design that topples
              and has legs drawn short, the margins with the toppling cases' stability
              margins replaced by those legs' heights above the floor (``_short_legs``,
              ``_standing``)
    """

    def __init__(self, design: Design, geometry: Geometry, report: DesignReport,
                 editor: Editor, dofs: list[Dof], model: StaticsModel | None = None,
                 solved: dict | None = None):
        """``model``, ``solved``: the design's statics model and its cases' statics by
        name (``check.check_design``), if the caller has them: not solved again."""
        self.design = design
        self.report = report
        self._model, self._solved = model, solved or {}
        self.geometry = geometry
        self.editor = editor
        self.size = design_size(design)
        self.blocked: dict[str, str] = {}
        self._edited: dict[Dof, tuple[float, Design, Design]] = {}   # (step apart, +, -)
        self.alternatives: list[list[Margin]] = []
        if geometry.violations or any(v.kind == "disconnected" for v in report.violations):
            # (the report's: two planks drawn through each other are told by the check,
            # ``geometry.drawn_through``, not by the geometry: a leg drawn too long, up
            # through the seat, is repaired by drawing it back before its statics count)
            self.dofs = [dof for dof in dofs if self._movable(dof)]
            self.margins = self._geometric(report)
        else:
            self.margins = self._physical(dofs)

    @property
    def violated(self) -> list[Margin]:
        return [m for m in self.margins if m.value < 0.0]

    def with_margins(self, margins: list[Margin]) -> Margins:
        """These margins over the same DOFs (``alternatives``: what ``candidates`` reads)."""
        other = copy.copy(self)
        other.margins, other.alternatives = margins, []
        return other

    # -- DOFs ------------------------------------------------------------------------------
    def _movable(self, dof: Dof) -> bool:
        """Whether the DOF can move both ways by a small step (locked DOFs unchanged);
        the edited designs are kept for the differences."""
        step = GEOMETRY_STEP * self.editor.scale(dof)
        try:
            plus = self.editor.moved((dof,), (step,))
            minus = self.editor.moved((dof,), (-step,))
        except (Blocked, OutOfReach) as why:
            self.blocked[dof.name] = getattr(why, "reason", str(why))
            return False
        self._edited[dof] = (2.0 * step, plus, minus)
        return True

    def _difference(self, measure) -> np.ndarray:
        """Central differences of ``measure(design) -> (k,) array`` over the free DOFs:
        (k, n_free), per scaled unit; 0 where a measure is not finite on a side (an end that
        no longer faces its face: that DOF gives it no usable rate)."""
        columns = []
        for dof in self.dofs:
            span, plus, minus = self._edited[dof]
            with np.errstate(invalid="ignore"):
                change = measure(plus) - measure(minus)
            columns.append(np.where(np.isfinite(change), change, 0.0) / span
                           * self.editor.scale(dof))
        if not columns:
            return np.zeros((len(measure(self.design)), 0))
        return np.column_stack(columns)

    # -- physics ---------------------------------------------------------------------------
    def _physical(self, dofs: list[Dof]) -> list[Margin]:
        """The margins of every load case that has a state to linearize (its own, or the
        bolted one when it topples or slides); sets ``dofs`` to the free ones."""
        shared: dict = {}
        linears = []
        model = self._model or build_model(self.design, self.geometry)  # one for all cases
        for case in self.design.load_cases:
            try:
                linears.append(Linearization(self.design, case, self.geometry,
                                             self.editor.frame, shared, bolted=True,
                                             one_sided=True, model=model,
                                             statics=self._solved.get(case.name)))
            except ValueError:
                continue
        if not linears:             # every case a mechanism even held down
            legs = self._short_legs({v.case for v in self.report.violations
                                     if v.kind == "lift-off"})
            self.dofs = [dof for dof in dofs if self._movable(dof)] if legs else []
            return self._standing(legs)
        first = linears[0].derivatives(dofs)
        self.blocked.update(first.blocked)
        free = []
        for dof in first.dofs:
            stepped = shared[dof]
            lock = self.editor.moved_lock(stepped.plus[0]) or \
                self.editor.moved_lock(stepped.minus[0])
            if lock is not None:
                self.blocked[dof.name] = f"it would change the locked {lock}"
                continue
            self._edited[dof] = (stepped.h, stepped.plus[0], stepped.minus[0])  # one-sided
            free.append(dof)
        self.dofs = free
        if not free:
            return []
        scales = np.array([self.editor.scale(dof) for dof in free])
        margins = []
        for linear in linears:
            if linear.statics.stability == "sliding" and not self.design.walls:
                margins.extend(self._sliding(linear))
                continue
            sens = first if linear is linears[0] and len(free) == len(first.dofs) \
                else linear.derivatives(free)
            if linear.statics.stability == "lift-off":
                margins.extend(toppling_margins(linear, sens.contact_forces, scales))
            elif linear.statics.stability == "sliding":     # leaning on walls too
                margins.extend(cone_margins(linear, sens.contact_forces, scales))
            else:       # stable (bolted only when its forces came from the feasibility LP)
                margins.extend(durability_margins(linear, sens, scales))
                margins.extend(anchor_margins(linear, sens.contact_forces, scales))
                margins.extend(bending_margins(linear, sens, scales))
        toppled = {linear.case.name for linear in linears
                   if linear.statics.stability == "lift-off"}
        standing = self._standing(self._short_legs(toppled))
        if standing:
            self.alternatives.append([m for m in margins if not (
                m.restores == "stability" and m.case in toppled)] + standing)
        return margins

    def _short_legs(self, toppled: set[str]) -> list[int]:
        """For a design that topples in the cases ``toppled``: its legs drawn short, the
        lowest (within HOVER_BAND of the design's size of each other) of the planks of its
        grounded groups standing on an end above the floor (``geometry.near.
        hovering_ends``, within HOVER_REACH of its size) whose foot on the floor would
        widen its support toward where it tips (``_widens``); their indices."""
        if not toppled:
            return []
        design = self.design
        scale = self.size * design.unit_scale
        hovering = [(i, height) for i, height in hovering_ends(design, self.geometry,
                                                               HOVER_REACH * scale)
                    if self._widens(design.planks[i], toppled)]
        if not hovering:
            return []
        lowest = min(height for _, height in hovering)
        return [i for i, height in hovering if height <= lowest + HOVER_BAND * scale]

    def _standing(self, legs: list[int]) -> list[Margin]:
        """The margins of the legs drawn short ``legs`` (``_short_legs``): each one's
        ``(tolerance - height) / size``, restoring stability in every toppling case
        (``case`` None).  The toppling margins, the forces of the contacts the design has,
        cannot tell that a leg that touches nothing helps: rates by differences of the
        geometry (as a floating plank's, ``_geometric``); the full checks of the line
        search decide."""
        if not legs or not self.dofs:
            return []
        design = self.design
        scale = self.size * design.unit_scale

        def heights(edited: Design) -> np.ndarray:
            return np.array([_height(i)(edited) for i in legs])

        values = (design.tolerance - heights(design)) / scale
        rates = -self._difference(heights) / scale
        return [Margin("stability", design.planks[i].id, None, float(values[k]), rates[k],
                       design.tolerance / scale) for k, i in enumerate(legs)]

    def _widens(self, plank, toppled: set[str]) -> bool:
        """Whether the plank's foot (its corners within the tolerance of its lowest),
        standing on the floor, would bring the support polygon of the design's floor
        contacts nearer, by more than the tolerance, to where the loads' line of action
        meets the floor (``geometry.support.pressure_centre``) in some toppling case of
        ``toppled``: a stretcher on edge between the legs, or a leg short on the side the
        design does not tip to, holds nothing that topples."""
        design = self.design
        points = [c.point[:2] for c in self.geometry.contacts if c.on_floor]
        if not points:
            return False
        corners = plank.corners
        foot = [p for p in corners[corners[:, 2] <= corners[:, 2].min() + design.tolerance,
                                   :2]]
        hull = np.array(points, dtype=float)[convex_hull(points)]
        widened = np.array(points + foot, dtype=float)[convex_hull(points + foot)]
        for case in (case for case in design.load_cases if case.name in toppled):
            centre = pressure_centre(design, case)
            if centre is not None and \
                    outside(widened, centre)[0] < outside(hull, centre)[0] - design.tolerance:
                return True
        return False

    def _sliding(self, linear: Linearization) -> list[Margin]:
        """``(mu W - H) / W0`` per grounded component: W the downward load on it, H the
        sideways load (the ground must supply minus both), W0 the case's whole weight."""
        model, mu = linear.model, self.design.material.friction
        components = [[model.planks[k] for k in component] for component in model.components]

        def margins(totals: np.ndarray) -> np.ndarray:
            return mu * -totals[:, 2] - np.hypot(totals[:, 0], totals[:, 1])

        def loads(design: Design) -> np.ndarray:
            return component_loads(design, components, linear.case.name)

        totals = loads(self.design)
        weight = max(float(-totals[:, 2].sum()), 1e-12)
        values = margins(totals)
        rates = self._difference(lambda design: margins(loads(design)))
        return [Margin("stability", ",".join(self.design.planks[i].id for i in component),
                       linear.case.name, float(values[c] / weight), rates[c] / weight, 0.0)
                for c, component in enumerate(components)]

    # -- geometry --------------------------------------------------------------------------
    def _geometric(self, report: DesignReport) -> list[Margin]:
        """Margins of the geometric violations: a listed joint's gap, a corner in the
        ground, a hovering component (its lowest planks, but those whose foot stands on
        another of them, ``_standing_on_others``; not one that hangs on joints it misses,
        ``near.carried_groups``: closing them carries it), and for a plank joined
        to nothing the depth to which its end cuts into each face (``geometry.cut_ins``:
        resting on the face, within the tolerance, joins it)."""
        design, tolerance = self.design, self.design.tolerance
        measures: list[tuple[str, object]] = []
        carried = carried_groups(design, self.geometry)
        neighbours = None               # whose boxes meet each plank's, where one needs them
        for violation in report.violations:
            if violation.kind == "penetration":
                plank = design.plank_index[violation.where]
                measures.append((violation.where, _depth(plank)))
            elif violation.kind == "floating" and violation.where not in carried:
                ids = violation.where.split(",")
                lows = {i: float(design.planks[design.plank_index[i]].corners[:, 2].min())
                        for i in ids}
                lowest = min(lows.values())
                for plank_id in _standing_on_others(design, self.geometry, lows, tolerance):
                    del lows[plank_id]
                ids = [i for i in ids if i in lows]
                for plank_id in ids:
                    if lows[plank_id] <= lowest + HOVER_BAND * self.size * design.unit_scale:
                        measures.append((plank_id, _height(design.plank_index[plank_id])))
            elif violation.kind == "disconnected" and "/" in violation.where:
                a, b = violation.where.split("/", 1)
                pair = (design.plank_index[a], design.plank_index[b])
                if end_gap(design, *pair) is not None:
                    measures.append((violation.where, _gap_measure(pair)))
            elif violation.kind == "disconnected":      # its end cut into faces: rest on them
                edge = design.plank_index[violation.where]
                if neighbours is None:
                    neighbours = box_neighbours(design)
                for _, face in cut_ins(design, edge, neighbours[edge]):
                    measures.append((f"{design.planks[face].id}/{violation.where}",
                                     _depth_measure(face, edge)))
        if not measures:
            return []

        def distances(edited: Design) -> np.ndarray:
            return np.array([measure(edited) for _, measure in measures])

        scale = self.size * design.unit_scale
        values = (tolerance - distances(design)) / scale
        rates = -self._difference(distances) / scale
        return [Margin("geometry", where, None, float(values[k]), rates[k],
                       tolerance / scale) for k, (where, _) in enumerate(measures)]


def _standing_on_others(design: Design, geometry: Geometry, lows: dict[str, float],
                        tolerance: float) -> list[str]:
    """The planks of a group (``lows``: id -> its lowest corner's height, m) that stand on
    another plank of the group: the edge plank of a joint with it, the joint in the lower
    half of the plank's height, its lowest corner above the group's lowest by more than
    the tolerance (a post standing on a 12 mm base is carried by the base: it need not
    reach the floor too; a leg under a top is jointed at its upper end)."""
    lowest = min(lows.values())
    found = []
    for joint in geometry.joints:
        edge, face = joint.edge, joint.face
        if edge not in lows or face not in lows or edge in found \
                or lows[edge] <= lowest + tolerance:
            continue
        top = float(design.plank(edge).corners[:, 2].max())
        if float(joint.point[2]) <= 0.5 * (lows[edge] + top):
            found.append(edge)
    return found


def _depth(plank: int):
    """How deep (m) the plank's lowest corner is below the ground."""
    return lambda design: -float(design.planks[plank].corners[:, 2].min())


def _height(plank: int):
    """How high (m) the plank's lowest corner is above the ground."""
    return lambda design: float(design.planks[plank].corners[:, 2].min())


def _depth_measure(face: int, edge: int):
    """How far (m) the end of plank ``edge`` is from the face of plank ``face``, above it
    or sunk into it (inf where no end of it faces that face)."""
    def measure(design: Design) -> float:
        gap = end_depth(design, face, edge)
        return np.inf if gap is None else abs(gap)
    return measure


def _gap_measure(pair: tuple[int, int]):
    def measure(design: Design) -> float:
        gap = end_gap(design, *pair)
        return np.inf if gap is None else gap
    return measure
