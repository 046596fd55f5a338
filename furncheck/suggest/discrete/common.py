"""What every discrete rule shares: ``Fix`` (a checked fix with its advice), ``Search``
(the invalid design, its geometry and report, and the one validation every candidate
passes), and the geometry of planks a woodworker reads off a design: legs (planks
standing on the floor), parallel and facing planks, level planks, new plank names."""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass, field, replace

import numpy as np

from furncheck.check import check_design, is_valid
from furncheck.design.model import Design, JointSpec, Plank
from furncheck.dofs import Dof, dof_value, euler_degrees
from furncheck.geometry import Geometry, analyze, interpenetrations
from furncheck.plain import plain_list, plain_number
from furncheck.result import DesignReport
from furncheck.suggest.tried import FAILED, FOUND, NOT_APPLICABLE, Trial
from furncheck.tolerances import REPORT_DECIMALS

PARALLEL_COS = 0.95
"""Two planks count as parallel when their face normals' cosine is at least this (and a
plank as level, or upright, when its normal is this close to vertical, or horizontal)."""

ADVICE_DIGITS = 3
"""Significant digits of the sizes and positions in the advice (whole units at least)."""

RESTORES = {"non-durable": "durability", "lift-off": "stability", "sliding": "stability",
            "sagging": "stiffness", "overstressed": "strength", "disconnected": "geometry",
            "floating": "geometry", "penetration": "geometry"}
"""What a fix restores, by the kind of violation it removes (as the continuous
suggestions name it)."""

MAX_CANDIDATES = 12
"""Candidates checked in full per rule at most (each is a full check of every load case):
the rules list their likeliest candidates first."""

BOARD_DIGITS = 12
"""Decimals (m^3) to which the board a finished candidate adds is compared: equal
boards summed in another order are a tie, not one ulp more."""

MAX_RULED_OUT = 48
"""Candidates ruled out before a check (by their geometry: a part that would cut into
another, float, or miss what it is nailed to; or a locked DOF: one analysis each, no
full check) per rule at most, beyond MAX_CANDIDATES checked in full: on a design of
many failing planks each brings its own, and the analysis of a big design takes a
second."""

LOCK_SLACK = 1e-9
"""A locked DOF counts as unchanged within this (file unit or degrees: round-off)."""

FINISHED = 4
"""Candidates of a rule that fail only by bending (elastic model) that are finished with
thicker planks at most: those whose planks bend least (``_nearest``), of which the one
that needs the least extra board is kept (a 96 mm rail under a table top may spare the
top that a 48 mm one leaves sagging).  (Three left out the table's 72 mm rail under its
top's middle once the rails under its overhanging edges met its legs, and offered a
96 mm one for the same thicker legs.)"""

BENDING = ("sagging", "overstressed")
"""The violations a thicker plank repairs (``thicker.finish``)."""


@dataclass(frozen=True)
class Fix:
    """A discrete fix whose design is valid.

    rule     : the rule that made it ('support', 'rail', 'apron', 'stretcher', 'back panel',
               'brace', 'outrigger', 'anchor', 'thicker', 'reconnect', 'nails', 'fixings',
               'pads', 'bracket')
    advice   : the sentence a maker acts on (``Add ...``, ``Make ... thick``), ending in '.'
    design   : the design with the fix; ``report`` its validation (valid)
    adds     : planks added; ``between`` the planks a support joins ((P_i, P_j or 'the
               floor'), a rail: (bent plank, its ends); the planks nailed to, else)
    restores : the kinds of violation it removes (set by ``Search.restores``)
    thickened: {plank id: new thickness m} of the planks it makes thicker
    """

    rule: str
    advice: str
    design: Design
    report: DesignReport
    adds: tuple[Plank, ...] = ()
    between: tuple[str, ...] = ()
    restores: tuple[str, ...] = ()
    thickened: dict = field(default_factory=dict)


@dataclass
class Search:
    """One invalid design's discrete search: the design, its geometry and report, the
    DOFs that must not change (``--lock``: a fix that moves or resizes a plank so that
    one of them changes is not offered; added planks change none), what the rules tried
    (``trials``, ``tried.Trial`` values for ``explain``) and the count of candidate
    designs checked in full (``checks``)."""

    design: Design
    geometry: Geometry
    report: DesignReport
    locked: tuple[Dof, ...] = ()
    trials: list[Trial] = field(default_factory=list)
    checks: int = 0
    _neighbours: dict[str, list[str]] | None = field(default=None, repr=False)

    @property
    def restores(self) -> tuple[str, ...]:
        return tuple(sorted({RESTORES[v.kind] for v in self.report.violations}))

    @property
    def elastic(self) -> bool:
        return self.design.elastic

    @property
    def neighbours(self) -> dict[str, list[str]]:
        """plank id -> the planks jointed to it, in joint order."""
        if self._neighbours is None:
            found: dict[str, list[str]] = {p.id: [] for p in self.design.planks}
            found.update(self.geometry.jointed())
            self._neighbours = found
        return self._neighbours

    def kinds(self) -> set[str]:
        return {v.kind for v in self.report.violations}

    def repairs(self, rule: str, kinds: tuple[str, ...]) -> bool:
        """Whether ``rule`` (its name in the reports) applies: the design stands as drawn,
        some violation is of ``kinds`` and every other one bends a plank too much in the
        elastic model (its candidates are then finished with thicker boards: an anchor
        against toppling, and a thicker bottom for its sag); if not, that is recorded,
        with why."""
        if self.geometry.violations:
            self.not_applicable(rule, "the geometry is repaired first")
            return False
        finished = set(BENDING) if self.elastic else set()
        unrepaired = sorted(self.kinds() - set(kinds) - finished)
        if not self.kinds() & set(kinds):
            unrepaired = sorted(self.kinds())
        if unrepaired or not self.report.violations:
            self.not_applicable(rule, f"it does not repair {' or '.join(unrepaired)}")
            return False
        return True

    def not_applicable(self, rule: str, reason: str, target: str = "") -> None:
        """Record that ``rule`` (its name in the reports) does not apply, and why."""
        self.trials.append(Trial(rule, target, NOT_APPLICABLE, reason))

    def failed(self, rule: str, reason: str, target: str = "") -> None:
        """Record a candidate of ``rule`` ruled out before any check, and why."""
        self.trials.append(Trial(rule, target, FAILED, reason))

    def first_valid(self, candidates: Iterable[Candidate]) -> Fix | None:
        """The Fix of the first candidate that is valid (``verdict``), checking at most
        MAX_CANDIDATES of them in full (those ruled out before any check, by their
        geometry or a locked DOF, do not count; at most MAX_RULED_OUT of those); when
        none is, but some failed only by planks that bend too much (elastic model), the
        FINISHED of those whose planks bend least past their limits (``_nearest``; on a
        tie the later, as the rules list their smallest parts first) with those planks
        thickened (``thicker.finish``): of the ones that are then valid, the one that adds
        the least board (``_added_board``; on a tie, a preferred one, then the one whose
        added parts are smaller: a 48 mm rail where a 96 mm one needs the same boards);
        else None.  Every candidate checked is recorded in ``trials`` (``tried.Trial``:
        found, or failed and why)."""
        bent: list[tuple] = []
        count = ruled_out = 0               # checked in full; ruled out before a check
        for candidate in candidates:
            if count >= MAX_CANDIDATES or ruled_out >= MAX_RULED_OUT:
                self.failed(candidate.trial_rule or candidate.rule, f"the rule checks "
                            f"{MAX_CANDIDATES} candidates at most" if count >= MAX_CANDIDATES
                            else f"the rule rules out {MAX_RULED_OUT} candidates before a "
                            "check at most", candidate.target)
                break
            outcome = self.verdict(candidate.design, candidate.new_joints, full=self.elastic)
            if isinstance(outcome, str):
                self._record(candidate, FAILED, outcome)
                ruled_out += 1
                continue
            count += 1
            edited, after, report = outcome
            if report.valid:
                self._record(candidate, FOUND)
                return Fix(candidate.rule, candidate.advice, edited, report, candidate.adds,
                           candidate.between)
            self._record(candidate, FAILED, "the design with it is still not valid", edited)
            if report.violations and all(v.kind in BENDING for v in report.violations):
                bent.append((candidate, edited, after, report))
        from furncheck.suggest.discrete.growth import cut_phrase
        from furncheck.suggest.discrete.thicker import boards_alone, finish, thickness_phrase

        best = None
        for candidate, edited, after, report in reversed(_nearest(bent)):
            finished = finish(self, edited, after, report)
            if finished is None:
                self._record(candidate, FAILED, "no thicker boards (up to 44 mm) make the "
                             "design with it valid", thickening=True)
                continue
            key = (round(_added_board(edited, finished[2]), BOARD_DIGITS),
                   not candidate.preferred, _part_volume(candidate))
            if best is not None and key >= best[0]:
                self._record(candidate, FAILED, f"valid, but {_worse(key, best[0])} "
                             f"{best[1].place}", thickening=True)
                continue
            if best is not None:
                self._record(best[1], FAILED, f"valid, but {_worse(best[0], key)} "
                             f"{candidate.place}", thickening=True)
            best = (key, candidate, finished, edited)
        if best is None:
            return None
        _, candidate, (design, report, thickened), unfinished = best
        bare = boards_alone(self, thickened, candidate.trial_rule or candidate.rule)
        if bare is not None:
            self._record(candidate, FAILED, "valid, but the thicker boards alone make the "
                         "design valid: left out", thickening=True)
            return bare
        self._record(candidate, FOUND, thickening=True)
        advice = candidate.advice
        adds = tuple(design.plank(plank.id) for plank in candidate.adds)   # as finished
        units = self.design.units
        for old, plank in zip(candidate.adds, adds):    # a part it adds: said as it is cut
            if plank == old:
                continue            # (thickened, or lengthened to cover a thickened edge)
            size = size_of(plank, self.design)
            if plank.id in thickened:
                size = f"{size[:-len(units) - 1]} x " \
                       f"{amount(plank.thickness / self.design.unit_scale)} {units}"
            advice = advice.replace(
                f"{plank.id} ({size_of(old, self.design)})", f"{plank.id} ({size})", 1).replace(
                point_of(old.center, self.design), point_of(plank.center, self.design), 1)
        existing = {p: v for p, v in thickened.items() if p in self.design.plank_index}
        if existing:
            advice = (f"{advice[:-1]}, and {thickness_phrase(existing, self.design)}"
                      f"{cut_phrase(unfinished, design)}.")
        return Fix(candidate.rule, advice, design, report, adds, candidate.between,
                   thickened={p: new for p, (_, new) in thickened.items()})

    def _record(self, candidate: Candidate, outcome: str, reason: str = "",
                design: Design | None = None, thickening: bool = False) -> None:
        """A Trial of ``candidate``: its place and the reason ('place: reason')."""
        place = candidate.place + (" with thicker planks" if thickening else "")
        self.trials.append(Trial(candidate.trial_rule or candidate.rule, candidate.target,
                                 outcome,
                                 f"{place}: {reason}" if reason else "",
                                 candidate.plank, design))

    def keeps_locks(self, edited: Design) -> bool:
        """Whether every locked DOF has the same value in ``edited``."""
        return all(abs(dof_value(edited, dof) - dof_value(self.design, dof)) <= LOCK_SLACK
                   for dof in self.locked)

    def verdict(self, edited: Design, new_joints: tuple[tuple[str, str], ...] = (),
                full: bool = False) -> tuple[Design, Geometry, DesignReport] | str:
        """(the design, its geometry, its report) when ``edited`` keeps every joint of the
        design, adds exactly ``new_joints`` (plank id pairs, also listed when the design
        lists its joints) and no other, and no plank cuts into another; else why not, in
        words.  The report is the full one when the design is valid or ``full`` is asked
        for (a candidate that fails by bending alone may be finished); else an invalid
        candidate's report is cut short (``is_valid`` stops at its first failing case)
        and says only that it is invalid.  (With one load case there is nothing to cut
        short: the full check is made at once, and a valid candidate is solved once.)"""
        if edited.joints is not None and new_joints:
            listed = {frozenset(spec.planks) for spec in edited.joints}
            edited = replace(edited, joints=(*edited.joints, *(
                JointSpec(pair) for pair in new_joints if frozenset(pair) not in listed)))
        if not self.keeps_locks(edited):
            return "it would change a locked DOF"
        after = analyze(edited)
        if after.violations:
            first = after.violations[0]
            return f"with it, {first.kind}: {first.where}: {first.message}"
        before = {frozenset(j.planks) for j in self.geometry.joints}
        wanted = before | {frozenset(pair) for pair in new_joints}
        found = {frozenset(j.planks) for j in after.joints}
        if found - wanted:
            others = sorted({p for pair in found - wanted for p in pair}
                            - {p for pair in new_joints for p in pair})
            return f"it would also meet {', '.join(others)}" if others else \
                "it would change the design's other joints"
        if wanted - found or len(after.joints) != len(self.geometry.joints) + len(new_joints):
            return "it would not be nailed to every plank it should be" if wanted - found - \
                before else "it would change the design's other joints"
        cuts = interpenetrations(edited)
        if cuts:
            added = set(edited.plank_index) - set(self.design.plank_index)
            crossed = sorted({p for pair in cuts for p in pair[:2]} - added) or \
                sorted({p for pair in cuts for p in pair[:2]})      # (added cut each other)
            return f"it would cut into {', '.join(crossed)}"
        self.checks += 1
        if not full and len(edited.load_cases) > 1 and not is_valid(edited, after):
            return edited, after, DesignReport(edited.source, edited.name, False)
        return edited, after, check_design(edited, after)


@dataclass(frozen=True)
class Candidate:
    """A fix to check: the edited design, the joints it adds, and its advice.

    trial_rule : the rule's name in ``tried.Trial`` (the reports), e.g. 'support plank'
    target     : what it is for (a failing joint or plank; '' for the whole design)
    place      : where it goes, in words, for the Trial's reason ('between shelf and base
                 at the far side')
    plank      : the plank (or fixing) it adds, as the advice names it
    preferred  : of candidates that thicker boards finish with as much board, a preferred
                 one is kept over one that is not (the anchors on a plank and its mirror
                 images over those on the plank alone); else the one whose added parts
                 are smaller
    """

    rule: str
    design: Design
    advice: str
    adds: tuple[Plank, ...] = ()
    between: tuple[str, ...] = ()
    new_joints: tuple[tuple[str, str], ...] = ()
    trial_rule: str = ""
    target: str = ""
    place: str = ""
    plank: str = ""
    preferred: bool = False


def _part_volume(candidate: Candidate) -> float:
    """m^3: the parts a candidate adds, as it adds them (before any is thickened)."""
    return sum(p.length * p.width * p.thickness for p in candidate.adds)


def _worse(key: tuple, other: tuple) -> str:
    """Why a finished candidate of ``key`` (``first_valid``'s: board added, not
    preferred, its parts' volume) loses to one of ``other`` (at least as good), in words
    ending in 'than'."""
    if key[0] > other[0]:
        return "it adds more board than"
    if key[1] > other[1]:
        return "it adds as much board as, and is not preferred to,"
    if key[2] > other[2]:
        return "it adds as much board as, and bigger parts than,"
    return "it is no better than"


def _nearest(bent: list[tuple]) -> list[tuple]:
    """The FINISHED (candidate, design, geometry, report) of ``bent`` that the least
    thicker board may finish: the smallest worst utilization of a plank in the report,
    in their order (a long bench's middle leg, its seat then sagging 2.7 times its
    allowance, before deep rails that leave it at 8 times: the rule lists the supports
    first and the rails last, and the last three alone were finished)."""
    def worst(report) -> float:
        return max((plank.utilization for case in report.cases for plank in case.planks or ()),
                   default=math.inf)

    kept = sorted(range(len(bent)), key=lambda k: (worst(bent[k][3]), -k))[:FINISHED]
    return [bent[k] for k in sorted(kept)]


# --- geometry a woodworker reads off a design ---------------------------------------------

def _added_board(design: Design, thickened: dict) -> float:
    """m^3 of board that thickening adds to ``design``: over the planks {id: (old, new)
    thickness m}, (new - old) x length x width."""
    return sum((new - old) * design.plank(plank).length * design.plank(plank).width
               for plank, (old, new) in thickened.items())


def normal(plank: Plank) -> np.ndarray:
    """(3,) the plank's face normal (local z) in world coordinates."""
    return plank.rotation_matrix[:, 2]


def level(plank: Plank) -> bool:
    """Whether the plank lies level (its broad faces horizontal)."""
    return abs(float(plank.rotation_matrix[2, 2])) >= PARALLEL_COS


def upright(plank: Plank) -> bool:
    """Whether the plank stands upright (its broad faces vertical)."""
    return abs(float(plank.rotation_matrix[2, 2])) <= 1.0 - PARALLEL_COS


def parallel(a: Plank, b: Plank) -> bool:
    return abs(float(normal(a) @ normal(b))) >= PARALLEL_COS


def legs(design: Design, geometry: Geometry) -> list[str]:
    """The upright planks standing on the floor (a ground contact), in plank order."""
    on_floor = {c.plank for c in geometry.contacts if c.on_floor}
    return [p.id for p in design.planks if p.id in on_floor and upright(p)]


def facing(a: Plank, b: Plank) -> tuple[np.ndarray, float, np.ndarray, np.ndarray] | None:
    """For parallel planks a and b whose broad faces look at each other: (the unit normal
    from a toward b, the gap between their facing faces m, and the overlap of b with a in
    a's plane as (low, high) (2,) local x-y of a); None when they are not parallel."""
    if not parallel(a, b):
        return None
    toward = normal(a).copy()
    offset = float((b.center_array - a.center_array) @ toward)
    if offset < 0:
        toward, offset = -toward, -offset
    gap = offset - a.half_extents[2] - b.half_extents[2]
    axes = a.rotation_matrix[:, :2]
    corners = (b.corners - a.center_array) @ axes
    low = np.maximum(-a.half_extents[:2], corners.min(axis=0))
    high = np.minimum(a.half_extents[:2], corners.max(axis=0))
    return toward, float(gap), low, high


def new_id(design: Design, stem: str, taken: set[str] = frozenset()) -> str:
    """``stem-1``, ``stem-2``, ...: the first not yet a plank id of the design (nor in
    ``taken``)."""
    used = {p.id for p in design.planks} | set(taken)
    return next(f"{stem}-{n}" for n in range(1, len(used) + 2) if f"{stem}-{n}" not in used)


def board(name: str, length: float, width: float, thickness: float, centre: np.ndarray,
          x_axis: np.ndarray, z_axis: np.ndarray) -> Plank:
    """A plank ``length`` along ``x_axis``, ``width`` across, its face normal ``z_axis``
    (unit, orthogonal), centred at ``centre`` (m)."""
    y_axis = np.cross(z_axis, x_axis)
    rotation = euler_degrees(np.column_stack([x_axis, y_axis, z_axis]), (0.0, 0.0, 0.0))
    return Plank(name, _clean(length), _clean(width), float(thickness),
                 tuple(_clean(v) for v in centre), tuple(float(v) for v in rotation))


def _clean(value: float) -> float:
    """``value`` (m) to the micrometre: the round-off of the geometry that placed a part
    (a rail 0.388000117481 m long) left out of its file (388 mm), far below any tolerance."""
    return round(float(value), 6) + 0.0


def with_planks(design: Design, planks: tuple[Plank, ...]) -> Design:
    """The design with ``planks`` added (after its own)."""
    return replace(design, planks=(*design.planks, *planks))


# --- words ---------------------------------------------------------------------------------

def amount(value: float) -> str:
    """ADVICE_DIGITS significant digits, but a tenth of the unit at least (443.5, not 444;
    1250, not 1.25e+03), as the cut list shows it (``report.cutlist``)."""
    value = round(float(value), REPORT_DECIMALS) + 0.0     # round-off (1e-14 mm) -> 0
    whole = len(str(int(abs(round(value)))))
    return plain_number(value, max(ADVICE_DIGITS, whole + 1))


def size_of(plank: Plank, design: Design) -> str:
    """'582 x 300 mm': the plank's length and width in the design's unit."""
    scale = design.unit_scale
    return f"{amount(plank.length / scale)} x {amount(plank.width / scale)} {design.units}"


def point_of(point, design: Design) -> str:
    """'(250, 0, 303) mm': a world point (m) in the design's unit."""
    scale = design.unit_scale
    return f"({', '.join(amount(v / scale) for v in point)}) {design.units}"


names = plain_list
"""'a', 'a and b', 'a, b and c' (``plain.plain_list``): plank ids in a fix's words."""
