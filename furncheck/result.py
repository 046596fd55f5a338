"""Result values: what validating a design produces, independent of any output format.

Positions are in the design file's length unit; forces in N, moments in N m, world frame.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from furncheck import exitcodes

VIOLATION_KINDS = ("disconnected", "penetration", "floating", "non-durable", "lift-off", "sliding",
                   "sagging", "overstressed")


@dataclass(frozen=True)
class Violation:
    """One reason a design is invalid.

    kind    : one of VIOLATION_KINDS
    where   : 'a/b' for a joint, a plank id, or a list of plank ids joined by ','
    case    : load case name, or None for geometric violations that hold in every case
    message : the numbers, in words
    line    : source line of the offending key (for annotations), or None
    """

    kind: str
    where: str
    case: str | None
    message: str
    line: int | None = field(default=None, compare=False)


@dataclass(frozen=True)
class JointResult:
    """A joint's wrench and durability in one load case.

    planks   : (first, second) as listed; force/moment are what the first exerts on the second
    point    : joint point, file length unit
    force    : (3,) N, world frame
    moment   : (3,) N m, world frame, about ``point``
    pull, shear : N per nail (contract section 3)
    """

    planks: tuple[str, str]
    point: tuple[float, float, float]
    nails: int
    force: tuple[float, float, float]
    moment: tuple[float, float, float]
    pull: float
    shear: float
    pull_capacity: float
    shear_capacity: float
    utilization: float
    durable: bool


@dataclass(frozen=True)
class ContactResult:
    """The ground's (or wall ``wall``'s, or for a resting joint's corner the plank ``on``'s)
    force on a plank at one contact corner (N, world; for the ground z is normal)."""

    plank: str
    point: tuple[float, float, float]
    force: tuple[float, float, float]
    wall: int | None = None
    normal: float | None = None      # N pressing on the ground or wall (force . its normal)
    on: str | None = None            # a resting joint's corner: the plank pressing on it

    @property
    def pressing(self) -> float:
        """N: the normal force, pressing > 0 (``force[2]`` on the ground)."""
        return self.force[2] if self.normal is None else self.normal


@dataclass(frozen=True)
class AnchorResult:
    """An anchor in one load case: the wall's force on its plank (N, world) at ``point``
    (file unit: its ``at`` on the plank's mid-plane, where it holds:
    ``geometry.model.anchor_tie``), its size, the capacity (N, / safety factor) and their
    ratio; ``index`` is its place in the design's ``anchors``."""

    plank: str
    wall: int
    point: tuple[float, float, float]
    force: tuple[float, float, float]
    size: float
    capacity: float
    utilization: float
    index: int


@dataclass(frozen=True)
class PlankResult:
    """A plank's bending in one load case (elastic model, contract section 3a).

    sag, sag_allowed : file length unit; sag_allowed = span / sag_limit
    stress, strength : N/mm^2; strength = bending_strength / safety_factor
    utilization : max(sag (1 + creep) / sag_allowed, stress / strength)
    """

    id: str
    sag: float
    sag_allowed: float
    stress: float
    strength: float
    utilization: float


NOT_SOLVED = "not solved"
"""``CaseResult.stability`` of a case whose statics were not solved (``check.check_design``)."""


@dataclass(frozen=True)
class LoadResult:
    """A load acting in a case, as the design file gives it (self-weight is none: it acts
    in every case).

    mass   : kg when the file gave a mass, else None
    force  : (3,) N, world frame, when the file gave a force, else None
    at     : file length unit, the world point it acts at; None at the plank centre (and
             for a spread load)
    spread : spread evenly along the plank's length
    origin : the case it comes from through ``include``; None for the case's own
    """

    plank: str
    mass: float | None
    force: tuple[float, float, float] | None
    at: tuple[float, float, float] | None
    spread: bool = False
    origin: str | None = None


@dataclass(frozen=True)
class CaseResult:
    """One load case.  ``stability`` is 'stable', 'lift-off', 'sliding' or 'mechanism'
    (no equilibrium and no force state: the planks rest on one line of ground points), or
    NOT_SOLVED for a design that does not stand as drawn (no statics: no joints, contacts
    or planks; ``durable`` and ``stable`` then read False, nothing having been shown to
    hold, and the geometric violations say why the design is invalid)."""

    name: str
    durable: bool
    stable: bool
    joints: tuple[JointResult, ...]
    contacts: tuple[ContactResult, ...]
    stability: str = "stable"
    planks: tuple[PlankResult, ...] | None = None    # elastic model only
    loads: tuple[LoadResult, ...] = ()                # the loads acting, after include
    anchors: tuple[AnchorResult, ...] = ()            # designs with anchors only

    @property
    def worst_joint(self) -> JointResult | None:
        """The joint with the highest utilization (first listed on ties)."""
        best = None
        for joint in self.joints:
            if best is None or joint.utilization > best.utilization:
                best = joint
        return best


@dataclass(frozen=True)
class DesignReport:
    """The verdict on one input file.  ``error`` set means it could not be read or checked;
    then ``valid`` is None and there are no cases."""

    design: str
    name: str
    valid: bool | None
    violations: tuple[Violation, ...] = ()
    cases: tuple[CaseResult, ...] = ()
    error: str | None = None
    units: str = "mm"
    more_errors: tuple[str, ...] = ()     # the file's other problems, a line each

    @property
    def errors(self) -> tuple[str, ...]:
        """Every problem of an errored report, a line each (``error`` first)."""
        return () if self.error is None else (self.error, *self.more_errors)


@dataclass(frozen=True)
class BatchReport:
    """Reports of a whole ``validate`` run, in input order."""

    reports: tuple[DesignReport, ...]

    @property
    def summary(self) -> dict[str, int]:
        return {
            "designs": len(self.reports),
            "valid": sum(1 for r in self.reports if r.valid is True),
            "invalid": sum(1 for r in self.reports if r.valid is False),
            "errors": sum(1 for r in self.reports if r.error is not None),
        }

    @property
    def return_code(self) -> int:
        """The exit code of ``furncheck validate`` for this batch (see ``exitcodes``)."""
        summary = self.summary
        return exitcodes.validate_code(summary["errors"] > 0, summary["invalid"] > 0)
