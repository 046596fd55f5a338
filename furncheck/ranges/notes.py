"""What a range row says besides its interval (``finder.RangeFinder``): where the edit
passes a value at which the elastic model turns a plank's one beam (``turn_reasons``,
``BeamTurns``), a size's interval that ends where the plank would be gone
(``floor_reason``), and an interval that is its value alone (``pinned_reason``).
"""

from __future__ import annotations

from furncheck.design.model import Design
from furncheck.dofs import Blocked, Dof, OutOfReach, apply_dof
from furncheck.geometry import Geometry
from furncheck.plain import plain_number
from furncheck.statics.elastic import beam_layout, plank_geometry

TURN_RESOLUTION = 0.01
"""Where a resize turns a beam (``BeamTurns.first_turn``) is found to this share of the
range's resolution: about seven more bisections than the range's own resolution would
take, each the plank's joints followed onto the edited design (``BeamTurns.turned``),
on the rows that pass a turn."""


def turn_reasons(design: Design, dof: Dof, value: float, low: float, high: float,
                 unit: str, turns: BeamTurns) -> list[str]:
    """Where a row's interval, or the way to it from the current ``value``, passes a value
    at which the elastic model turns a plank's one beam: that values beyond are judged
    spanning the other way, so that a sag judged there may be the model's, not the
    shop's.  The beam runs along the longer side (contract 3a), and turns at the square
    (a seat widened past its length spans from its front edge to its back); a plank
    nailed along both edges to panels spans across between them
    (``elastic.BeamLayout.candidates``), and its beam turns where those lines stop
    covering three quarters of its edges, not at the square: resized (the stool's 400
    mm seat on its 300 mm legs, widened past 401.335 mm), or as its neighbours are (a
    nightstand's sides cut shallower than 299 mm under its 400 mm deep top; a shelf
    between two sides as deep as itself spans between them either side of the square):
    ``turns`` finds where, for the DOF's plank and the planks nailed to it.  Else
    nothing."""
    if not design.elastic:
        return []
    reasons = []
    if dof.kind in ("length", "width") and dof.plank not in turns.candidates:
        plank = design.plank(dof.plank)
        other = (plank.width if dof.kind == "length" else plank.length) / design.unit_scale
        margin = design.tolerance / design.unit_scale
        if min(low, value) + margin < other < max(high, value) - margin:
            side = "length" if dof.kind == "width" else "width"
            reasons.append(f"past {plain_number(other, 6)} {unit} (its {side}) {dof.plank} "
                           "is square and then turned: the elastic model lays its one beam "
                           "along the longer side, so values beyond are judged spanning "
                           "the other way")
    turned: dict[str, list[str]] = {}            # planks turned at one value, together
    affected = turns.affected(dof)
    ends = sorted({low, high} - {value}, key=lambda end: abs(end - value))
    at_ends = [turns.turned(dof, value, end, affected) if affected else set()
               for end in ends]
    for plank_id in affected:
        end = next((end for end, there in zip(ends, at_ends) if plank_id in there), None)
        if end is not None:
            where = turns.first_turn(dof, value, end, plank_id)
            turned.setdefault(plain_number(where, 6), []).append(plank_id)
    for where, planks in turned.items():
        whose = f"{planks[0]}'s beam is" if len(planks) == 1 else \
            f"the beams of {', '.join(planks[:-1])} and {planks[-1]} are"
        reasons.append(f"past {where} {unit} {whose} turned: the elastic model lays a "
                       "plank's one beam along the longer side, or across it between "
                       "panels nailed along both its edges, so values beyond are judged "
                       "spanning the other way")
    return reasons


class BeamTurns:
    """Where an edit turns an elastic plank's beam (``turn_reasons``), for one design: the
    planks that may span across (``elastic.BeamLayout.candidates``), which of them each
    plank is nailed to, and their beams' directions now, found once."""

    def __init__(self, design: Design, geometry: Geometry, frame, resolution: float,
                 turn_resolution: float):
        self.design, self.geometry, self.frame = design, geometry, frame
        self.resolution, self.turn_resolution = resolution, turn_resolution
        layout = beam_layout(design, geometry) if design.elastic else None
        self.candidates = layout.candidates if layout is not None else frozenset()
        self._now = layout.crosswise if layout is not None else {}
        self._nailed: dict[str, set] = {}
        for joint in geometry.joints if self.candidates else ():
            a, b = joint.planks
            for one, other in ((a, b), (b, a)):
                if other in self.candidates:
                    self._nailed.setdefault(one, set()).add(other)

    def affected(self, dof: Dof) -> list[str]:
        """The planks whose beam ``dof`` may turn other than at the square: its own plank
        if that may span across (resized, moved or turned, it comes to be held along
        more or less of its edges), and the candidates nailed to it, in the design's
        order."""
        planks = set(self._nailed.get(dof.plank, ()))
        if dof.plank in self.candidates:
            planks.add(dof.plank)
        return sorted(planks, key=self.design.plank_index.get)

    def turned(self, dof: Dof, value: float, at: float, planks: list[str]) -> set[str]:
        """Which of ``planks`` have their beam the other way with ``dof`` at ``at`` (none
        where the edit cannot be made): their joints and their neighbours' floor corners
        followed onto the edited design at once (``geometry.follow_many``: the joints
        they have now, measured again; one that the edit would open or close is not
        looked for), not the whole design analysed again."""
        try:
            edited = apply_dof(self.design, self.frame, dof, at - value)
        except (Blocked, OutOfReach):
            return set()
        after = beam_layout(edited, plank_geometry(self.geometry, edited, planks), planks)
        return {plank_id for plank_id in planks
                if after.crosswise[plank_id] != self._now[plank_id]}

    def first_turn(self, dof: Dof, value: float, end: float, plank_id: str) -> float:
        """The value nearest ``value`` past which plank ``plank_id``'s beam is turned,
        toward ``end``, where it is (to within TURN_RESOLUTION of ``resolution``, by
        bisection: the turn is where joint lines stop covering a length, which the row
        names to six figures, as the interval; one turn is assumed between the value and
        that end, a turn and a turn back between them is not seen)."""
        resolution = self.turn_resolution if dof.is_rotation else self.resolution
        near, far = value, end
        while abs(far - near) > TURN_RESOLUTION * resolution:
            middle = 0.5 * (near + far)
            near, far = (near, middle) if self.turned(dof, value, middle, [plank_id]) \
                else (middle, far)
        return far


def floor_reason(dof: Dof, low: float, resolution: float, unit: str) -> str:
    """Why a size's interval ends within a resolution of nothing: no smaller plank is
    searched (the step beyond would be no plank at all), so that end is not one past
    which the design is invalid (a shelf cut to 0.3 mm still holds: nothing rests on
    it)."""
    return (f"{dof.kind} {plain_number(low, 5)} {unit} is the least searched: one step "
            f"of {plain_number(resolution, 5)} {unit} less leaves no plank")


def pinned_reason(resolution: float, unit: str) -> str:
    """Why an interval is its value alone: either way a step of at most the range's
    resolution was found invalid (what lies closer is not searched)."""
    return (f"valid at its value only, to the range's resolution "
            f"({plain_number(resolution, 5)} {unit})")
