"""The shop's score of a suggestion: which fix a maker would rather take.

Every suggestion, continuous or discrete, is scored from its cut list (``cutlist``) and its
design, and ranked by ``ShopScore.key`` (smaller first), lexicographically:

1. ``implausible``: proportions a maker would not build, that the input did not have
   already -- a plank too big to cut from one stock board (``tolerances.STOCK_BOARD``,
   2440 x 1220 mm MDF), a plank whose end is nailed to another plank's face and that is
   wider there than that plank (a 594 mm leg under a 350 mm seat) or, moved or
   widened, hangs past the faces it is nailed to by more than HANG_SHARE of its end (a
   cabinet's back slat moved 76 mm along the cap it hangs from, most of it past the
   cabinet's side), or a level plank
   (seat, top, shelf) that overhangs its supports by more than OVERHANG_SHARE of its
   length at one end (legs moved 267 mm in under a 900 mm bench seat: whoever sits at
   its end tips it, whatever the load cases say; an input's overhang past that share may
   not grow either; under it, a grown overhang where the plank's largest point load moved
   to its end tips the piece, ``_tips_at_an_end``), or a loaded level plank cut by more
   than SHRINK_SHARE of its length or
   width (a top cut to a strip under its pot) or turned out of level by more than
   TILT_LIMIT degrees (a desk's top sloping 10.5 degrees), or (elastic model) a plank resized past
   square, whose one beam then runs the other way (contract 3a: along the longer side; a
   stool's seat widened past its length bends the other way, and holds by that alone),
   or the highest loaded level plank (a
   seat, a top) raised or lowered by more than HEIGHT_SHARE of its height (a chair's seat
   lowered to 80 mm: another piece), or a push at the top carried down with its plank
   below the rest of the piece by more than PUSH_DROP_SHARE of its height (a bookcase's
   top lowered under a child's pull, its sides as tall as before), or an
   upright plank turned in plan by more than TURN_LIMIT degrees (a leg out of square), or
   a plank added standing on the floor under a piece that hangs on a wall (a floor unit);
2. ``broken``: mirror relations the edit breaks (``symmetry.broken_pairs``: a pair of
   mirror planks no longer mirrored, a plank on the mirror plane no longer symmetric, or
   an added plank without a mirror image among the added ones)
   -- on a symmetric design a symmetric fix comes first where one works;
3. ``cost``: the sum over the planks touched of each one's largest *relative* change --
   a size change over the size it had, a move over the design's size (its largest
   dimension), a turn in radians (none for a quarter turn about the plank's length: a
   leg so turned, ``discrete.turns``, is the same board standing square), a plank's own
   material value over its old value, an
   added or removed plank 1 -- plus PLANK_COST per plank touched (a change of one plank
   is easier to make than the same change spread over five);
4. the smaller change of the suggestion's own DOFs (``step``), then its rank as found.

The score is documented in the README's ``suggest`` section.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from furncheck.design.model import Design, Plank
from furncheck.dofs import design_size
from furncheck.geometry import Geometry, analyze
from furncheck.plain import plain_load
from furncheck.statics.elastic import BeamLayout, beam_layout, plank_geometry
from furncheck.suggest.cutlist import (
    ANGLE_FIELDS,
    POSITION_FIELDS,
    SIZE_FIELDS,
    PlankEdit,
)
from furncheck.suggest.discrete.common import amount, level, names, upright
from furncheck.suggest.symmetry import MirrorPlane, broken_pairs
from furncheck.tolerances import GRAVITY, ON_PLANK_EPS, STOCK_BOARD

PLANK_COST = 0.05
"""Cost of each plank touched, on top of its relative change (twenty planks touched cost
as much as doubling one plank's length)."""

WHOLE_PLANK = 1.0
"""The relative change of a plank added or taken away."""

OVERHANG_SHARE = 1.0 / 3.0
"""A level plank may reach past its outermost support at one end by at most this share of
its length (or width, across) before a suggestion reads as implausible (a table top's or
bench seat's overhang is commonly kept to a quarter or a third of its length)."""

END_LOAD_INSET = 0.05
"""m: where a level plank's largest point load is moved to find whether it tips the piece
(``_tips_at_an_end``): this far in from the plank's end, as the stability tests of
tables put their vertical force, its centre 50 mm from the top's outer edge (ISO
7172:1988, section 5; EN 1730)."""

OVERHANG_GROWTH = 0.05
"""... and only when the suggestion adds at least this share to the input's overhang (a
leg thickened 10 mm inward under a top at 32.9 % is no new overhang); the same for an end
hanging past the face it is nailed to (HANG_SHARE)."""

HEIGHT_SHARE = 0.2
"""The highest level plank that carries a load (a seat, a table's top: ``_working_heights``)
may rise or sink by at most this share of its height above the floor before a suggestion
reads as implausible: a seat's or a top's height is what the piece is for (a 750 mm bar
stool cut to 581 mm is a kitchen stool, a 738 mm desk lowered to 496 mm a coffee table,
a chair's seat lowered from 450 to 80 mm no chair); a shelf, which the rule cannot tell
from a top, may move more than a seat would (a cantilever shelf lowered 100 mm of its
606, 16.5 %, or a wall shelf 250 of its 1478, 17 %, is still the maker's shelf).  (A third,
before, let a desk lowered by 33 % pass as a fix.)"""

SHRINK_SHARE = 0.5
"""A level plank that a load case loads (a pot on a plant stand's top, books on a shelf) may
lose at most this share of its length or width before a suggestion reads as implausible:
a 400 mm top cut down to a 16 mm strip under its 25 kg pot, or a 1000 mm shelf cut to 304
mm under the same 35 kg of books, holds in the model, but the maker drew a top and a
shelf (an overloaded 400 mm cantilever shelf shortened to 220 mm is still a shelf).  The
loads ride with the plank (README "suggest")."""

TILT_LIMIT = 5.0
"""Degrees: a level plank that a load case loads (a desk's top, a shelf, a seat) may be
turned out of level by at most this before a suggestion reads as implausible: what stands
on a top sloping 10 degrees slides off it, whatever the load cases say (a chair's seat
is commonly sloped back by 3 to 5 degrees)."""

TURN_LIMIT = 5.0
"""Degrees: an upright plank (a leg, a side, a back rest) may be turned about the vertical,
out of square with the piece, by at most this before a suggestion reads as implausible
(a stool's leg turned 8.5 degrees in plan to hold a push, where a brace does it
square)."""

QUARTER_SLACK = 1e-4
"""Degrees: a plank's turn counts as a quarter turn about its length where it is within
this of 90 degrees, about an axis within this of its length (``_quarter_turned``)."""

PUSH_DROP_SHARE = 0.1
"""A push (a load with a force and no mass: a child's pull, a shove) at the top of the
piece (within this share of its height) that a suggestion carries down with its plank by
more than this share, below what then stands highest, reads as implausible: a push at the
top acts where hands reach, and a fix that lowers the plank it acts on under the rest may
hold only because the push moved (a bookcase's top lowered 261 mm under a child's pull at
1800 mm, its sides still 1800 mm tall: the child pulls at their tops).  A seat or a back
rest lowered whole, still the highest part, takes its push down with it, as the sitter
goes."""

HANG_SHARE = 0.25
"""A plank's end nailed to another plank's face may reach past that face's edge by at
most this share of the end's width before a suggestion reads as implausible, where the
input's did not: the nails then sit at the face's edge, and the part beyond sticks out
of the piece (a shelf a few millimetres proud of its sides is trimmed flush; a slat
three quarters past the cap it hangs from is not what the maker drew).  An end that
already reached past (a shelf's back edge on a narrow back slat) is left to the others."""


@dataclass(frozen=True)
class ShopScore:
    """A suggestion's score (module docstring); ``key`` orders suggestions, best first."""

    implausible: tuple[str, ...]
    broken: int
    cost: float
    touched: int

    def key(self) -> tuple:
        return (len(self.implausible), self.broken > 0, round(self.cost, 9))


def shop_score(original: Design, geometry: Geometry, planes: tuple[MirrorPlane, ...],
               edited: Design, edits: tuple[PlankEdit, ...],
               layout: BeamLayout | None = None) -> ShopScore:
    """The score of the suggestion whose design is ``edited`` and cut list ``edits``;
    ``geometry`` is the original's, ``planes`` its mirror planes, ``layout`` its
    ``elastic.beam_layout`` where the caller scores many suggestions of it (None: made
    here when needed)."""
    size = design_size(original)
    cost = sum(_relative(edit, size, _quarter_turned(original, edited, edit.plank))
               for edit in edits) + PLANK_COST * len(edits)
    broken = broken_pairs(edited, planes, frozenset(original.plank_index))
    return ShopScore(implausible(original, geometry, edited, layout), broken, cost,
                     len(edits))


def _turned_beams(original: Design, geometry: Geometry, edited: Design,
                  changed: set[str], layout: BeamLayout | None
                  ) -> tuple[list[str], list[str]]:
    """The planks whose one beam the elastic model lays the other way in ``edited`` than
    in ``original`` (``elastic.beam_layout``, in each plank's own frame) where that may
    be the model's doing, in the order of the design's planks: (those among ``changed``
    resized past square, beyond the design's tolerance, turned to run along joint lines
    that hold them all along, ``BeamLayout.held_along``, or no longer spanning across,
    ``BeamLayout.across``; the other planks so turned).  A plank nailed along both edges
    (``BeamLayout.candidates``, in either design) spans across or not as an edit moves
    what holds it: turned across, between panels that now hold its edges (a table's top
    between two panels added along its sides), it bends as the shop's plank does; turned
    back to its length, the lines along it hold its beam where they reach, and it reads
    little of its bending (a nightstand's sides cut shallower than three quarters of its
    top's depth, a top nailed all round once a front is added).  ``layout``: the
    original's ``beam_layout``, or None to make it."""
    if not edited.elastic:
        return [], []
    squared = []
    for plank_id in changed:
        before_plank, after_plank = original.plank(plank_id), edited.plank(plank_id)
        before = before_plank.length - before_plank.width
        after = after_plank.length - after_plank.width
        if before * after < 0.0 and min(abs(before), abs(after)) > original.tolerance:
            squared.append(plank_id)
    before = beam_layout(original, geometry) if layout is None else layout
    added = any(plank.id not in original.plank_index for plank in edited.planks)
    if not squared and not before.candidates and not added:
        return [], []   # nothing nailed along both edges before, nor a plank added to be
    if added:           # (an edit of the planks there that comes to nail one along both
        after = beam_layout(edited, analyze(edited))  # edges, joints new, is not looked for)
    else:               # the same joints: followed onto the edit, for the planks in
        asked = sorted(set(squared) | before.candidates, key=original.plank_index.get)
        after = beam_layout(edited, plank_geometry(geometry, edited, asked), asked)
    candidates = before.candidates | after.candidates
    turned = [p for p in sorted((set(squared) | candidates) & set(before.crosswise)
                                & set(after.crosswise), key=original.plank_index.get)
              if before.crosswise[p] != after.crosswise[p]
              and (p in squared or p in after.held_along
                   or (p in before.across and p not in after.across))]
    return [p for p in turned if p in changed], [p for p in turned if p not in changed]


def implausible(original: Design, geometry: Geometry, edited: Design,
                layout: BeamLayout | None = None) -> tuple[str, ...]:
    """Why ``edited`` has proportions a maker would not build that ``original`` did not
    have: planks too big for a stock board, planks wider than the face they are nailed
    to (the original's joints; a plank ``edited`` adds is checked for the board only)."""
    reasons = []
    changed = {plank.id for plank in edited.planks          # what an unchanged plank
               if plank.id in original.plank_index          # had, it still has
               and plank != original.plank(plank.id)}
    for plank in edited.planks:
        before = original.plank_index.get(plank.id)
        if (before is None or plank.id in changed) and not _fits_board(plank) and \
                (before is None or _fits_board(original.planks[before])):
            reasons.append(f"{plank.id} is larger than a stock board")
    faces: dict[tuple, list[str]] = {}          # per end (plank, edge_face): what holds it
    for joint in geometry.joints:
        faces.setdefault((joint.edge, tuple(joint.edge_face)), []).append(joint.face)
    for joint in geometry.joints:
        if joint.edge not in edited.plank_index or joint.face not in edited.plank_index \
                or not {joint.edge, joint.face} & changed:
            continue
        if _overhangs(edited, joint) and not _overhangs(original, joint):
            reasons.append(f"{joint.edge} is wider than {joint.face}, which it is nailed to")
            continue
        held_by = faces[(joint.edge, tuple(joint.edge_face))]
        before, after = _hanging(original, joint, held_by), _hanging(edited, joint, held_by)
        if before <= HANG_SHARE < after and after - before >= OVERHANG_GROWTH:
            reasons.append(f"{joint.edge} hangs {_percent(after)} % of its end past the "
                           f"edge of {joint.face}, which it is nailed to")
    supports = _supports(geometry)
    for plank_id in _level_planks(original, supports, changed):
        before = _overhang_share(original, plank_id, supports[plank_id])
        after = _overhang_share(edited, plank_id, supports[plank_id])
        if before is None or after is None:
            continue
        if after[0] > OVERHANG_SHARE and after[0] - before[0] >= OVERHANG_GROWTH:
            was = f" (it was {round(100 * before[0])} %)" if before[0] > OVERHANG_SHARE else ""
            reasons.append(f"{plank_id} overhangs its supports by {round(100 * after[0])} % "
                           f"of its {after[1]}{was}")
        elif after[0] > before[0] and _tips_at_an_end(original, plank_id) is None:
            tips = _tips_at_an_end(edited, plank_id)
            if tips is not None:
                load, past, weight = tips
                reasons.append(
                    f"the {amount(load / GRAVITY)} kg on {plank_id}, moved to its end "
                    f"({amount(past / original.unit_scale)} {original.units} past what "
                    f"the piece stands on), tips it over: its own "
                    f"{amount(weight / GRAVITY)} kg cannot hold it back (before the change "
                    "it could)")
    scale, unit = original.unit_scale, original.units
    turned: dict[tuple, list[str]] = {}         # planks alike, named together
    resized, others = _turned_beams(original, geometry, edited, changed, layout)
    for plank_id in resized:
        after_plank = edited.plank(plank_id)
        size = (amount(after_plank.length / scale), amount(after_plank.width / scale))
        turned.setdefault(size, []).append(plank_id)
    for (length, width), planks in turned.items():
        reasons.append(f"{names(planks)} {'is' if len(planks) == 1 else 'are'} {length} x "
                       f"{width} {unit} now, and the elastic model turns the beam with it "
                       "(one beam along the longer side, or across between panels nailed "
                       "along both edges), so the fix may be the model's")
    if others:
        reasons.append(f"the elastic model turns the beam of {names(others)} with the edit "
                       "(one beam along the longer side, or across between panels nailed "
                       "along both edges), so the fix may be the model's")
    loaded = {load.plank for case in original.load_cases for load in case.loads
              if level(original.plank(load.plank))}    # what the loads stand on
    cut: dict[tuple, list[str]] = {}
    for plank_id in sorted(loaded & changed, key=original.plank_index.get):
        before_plank, after_plank = original.plank(plank_id), edited.plank(plank_id)
        for name, old_size, new_size in (("length", before_plank.length, after_plank.length),
                                         ("width", before_plank.width, after_plank.width)):
            if new_size < (1.0 - SHRINK_SHARE) * old_size:
                key = (amount(new_size / scale), amount(old_size / scale), name)
                cut.setdefault(key, []).append(plank_id)
    for (new_size, old_size, name), planks in cut.items():
        several = len(planks) > 1
        reasons.append(f"{names(planks)} {'are' if several else 'is'} cut to {new_size} "
                       f"{unit} of {'their' if several else 'its'} {old_size} {unit} {name} "
                       f"under {'their loads' if several else 'its load'}")
    reasons += _sloped(original, edited, loaded & changed)
    reasons += _turned_in_plan(original, edited, changed)
    reasons += _pushes_lowered(original, edited)
    for plank_id in _working_heights(original):
        if plank_id not in changed:
            continue
        before = float(original.plank(plank_id).corners[:, 2].max())
        after = float(edited.plank(plank_id).corners[:, 2].max())
        if abs(after - before) > HEIGHT_SHARE * before:
            reasons.append(f"{plank_id} ends {amount(after / scale)} {unit} above the floor "
                           f"(it was {amount(before / scale)} {unit}: another piece)")
    reasons += _stood_on_the_floor(original, edited)
    return tuple(reasons)


def _stood_on_the_floor(original: Design, edited: Design) -> list[str]:
    """A piece that hangs on a wall (held by its anchors, no plank within the tolerance
    of the floor) given an added plank that stands on the floor: a floor unit, another
    piece (a wall shelf 1.4 m up offered a 1.46 m panel under it, where a maker adds a
    cleat or a stronger fixing)."""
    def on_floor(plank: Plank) -> bool:
        return float(plank.corners[:, 2].min()) <= original.tolerance

    if not original.anchors or any(on_floor(plank) for plank in original.planks):
        return []
    standing = [plank.id for plank in edited.planks
                if plank.id not in original.plank_index and on_floor(plank)]
    if not standing:
        return []
    return [f"{names(standing)} {'stands' if len(standing) == 1 else 'stand'} on the floor "
            f"under a piece that hangs on the wall: a floor unit, another piece"]


def _sloped(original: Design, edited: Design, planks: set[str]) -> list[str]:
    """TILT_LIMIT: the loaded level ``planks`` that the edit turns from within TILT_LIMIT
    of level to beyond it (a plank drawn sloping more, a drafting table's top, may turn
    further), planks alike named together."""
    sloped: dict[str, list[str]] = {}
    for plank_id in sorted(planks, key=original.plank_index.get):
        slope = _slope(edited.plank(plank_id))
        if slope > TILT_LIMIT >= _slope(original.plank(plank_id)):
            sloped.setdefault(amount(slope), []).append(plank_id)
    reasons = []
    for slope, ids in sloped.items():
        several = len(ids) > 1
        reasons.append(f"{names(ids)} {'slope' if several else 'slopes'} {slope} degrees "
                       f"under {'their loads' if several else 'its load'}: what stands on "
                       f"{'them' if several else 'it'} slides off")
    return reasons


def _turned_in_plan(original: Design, edited: Design, changed: set[str]) -> list[str]:
    """TURN_LIMIT: the upright planks (``discrete.common.upright``: a leg, a side, a back
    rest standing square) among ``changed`` turned about the vertical past it."""
    turned: dict[str, list[str]] = {}
    for plank_id in sorted(changed, key=original.plank_index.get):
        before = original.plank(plank_id)
        if not upright(before):
            continue
        turn = _plan_turn(before, edited.plank(plank_id))
        if turn > TURN_LIMIT:
            turned.setdefault(amount(turn), []).append(plank_id)
    return [f"{names(ids)} {'are' if len(ids) > 1 else 'is'} turned {turn} degrees in plan, "
            f"out of square with the piece" for turn, ids in turned.items()]


def _pushes_lowered(original: Design, edited: Design) -> list[str]:
    """PUSH_DROP_SHARE: the pushes (a force, mostly sideways, no mass) at the top of the
    piece that the edit carries down with their planks below what then stands highest
    (a push without ``at`` acts at its plank's centre, as the statics applies it)."""
    lowered: dict[tuple, list[str]] = {}
    top_before = max(float(p.corners[:, 2].max()) for p in original.planks)
    top_after = max(float(p.corners[:, 2].max()) for p in edited.planks)
    edited_cases = {case.name: case for case in edited.load_cases}
    for case in original.load_cases:
        other = edited_cases.get(case.name)
        if other is None or len(other.loads) != len(case.loads):
            continue        # (no edit changes a case's loads but by moving them)
        for old, new in zip(case.loads, other.loads):
            if old.mass is not None or old.plank not in edited.plank_index \
                    or math.hypot(old.force[0], old.force[1]) <= abs(old.force[2]):
                continue
            height = old.point[2] if old.point is not None else \
                original.plank(old.plank).center[2]
            now = new.point[2] if new.point is not None else \
                edited.plank(new.plank).center[2]
            drop, share = height - now, PUSH_DROP_SHARE * height
            if top_before - height <= share < drop and top_after - now > share:
                key = (plain_load(old.mass, old.force), old.plank,
                       amount(drop / original.unit_scale))
                lowered.setdefault(key, [])
                if case.name not in lowered[key]:
                    lowered[key].append(case.name)
    return [f"the {what} push on {plank_id} moves {drop} {original.units} lower with it "
            f"(case {', '.join(repr(c) for c in cases)}): it may hold only because the push "
            f"moved" for (what, plank_id, drop), cases in lowered.items()]


def _plan_turn(before: Plank, after: Plank) -> float:
    """Degrees a plank standing square (its face normal level) is turned about the
    vertical, out of square: between the horizontal parts of its face normal before and
    after (a tilt in its own plane or across it leaves their direction alone), or to the
    quarter turn, whichever is nearer (a leg given a quarter turn, ``discrete.turns``,
    stands square with the piece)."""
    old, new = before.rotation_matrix[:, 2], after.rotation_matrix[:, 2]
    if not np.linalg.norm(new[:2]):
        return 0.0          # turned to lie flat: the other rules judge it
    a, b = old[:2] / np.linalg.norm(old[:2]), new[:2] / np.linalg.norm(new[:2])
    cosine = abs(float(a @ b))          # a face turned 180 degrees is the same face plane
    turn = math.degrees(math.acos(min(1.0, cosine)))
    return min(turn, 90.0 - turn)       # a quarter turn stands square again


def _slope(plank: Plank) -> float:
    """Degrees between the plank's broad face and level."""
    return math.degrees(math.acos(min(1.0, abs(float(plank.rotation_matrix[2, 2])))))


def _working_heights(design: Design) -> list[str]:
    """The planks whose height is the piece's (in plank order): the highest level planks
    that carry a load in some case (a seat, a table's top: what it is for stands or sits
    on them; a bookcase's lower shelves may move), clear of the floor (a board lying on
    it is thickened upward, not raised)."""
    loaded = {load.plank for case in design.load_cases for load in case.loads}
    slack = design.tolerance + ON_PLANK_EPS
    levels = [plank for plank in design.planks if level(plank)]
    if not levels:
        return []
    top = max(float(plank.corners[:, 2].max()) for plank in levels)
    return [plank.id for plank in levels if plank.id in loaded
            and float(plank.corners[:, 2].max()) >= top - slack
            and float(plank.corners[:, 2].min()) > slack]


def _supports(geometry: Geometry) -> dict[str, list[tuple[str, bool]]]:
    """Per plank id, the planks jointed to it that may hold it: (the other plank, whether
    the plank is the joint's edge plank, its end resting on the other's face)."""
    held: dict[str, list[tuple[str, bool]]] = {}
    for joint in geometry.joints:
        held.setdefault(joint.edge, []).append((joint.face, True))
        held.setdefault(joint.face, []).append((joint.edge, False))
    return held


def _level_planks(design: Design, supports: dict[str, list[tuple[str, bool]]],
                  changed: set[str]) -> list[str]:
    """The level planks (``discrete.common.level``) held by joints whose overhang an edit
    may change: the plank or one of its jointed planks is among ``changed``."""
    return [plank.id for plank in design.planks if plank.id in supports and level(plank)
            and (plank.id in changed or any(other in changed
                                             for other, _ in supports[plank.id]))]


def _tips_at_an_end(design: Design, plank_id: str) -> tuple[float, float, float] | None:
    """(N, m, N): where the largest point load that any load case puts on the level plank
    (a sitter, a leaning person), moved to one of its ends (END_LOAD_INSET in from it,
    along its middle), tips the piece over the edge of what it stands on: that load, how
    far past that edge it is (the farthest such end), and the planks' weight that holds
    the piece back; None where no end tips it, and for a piece that a wall fixing holds
    or that stands on no floor.  Moments about that edge, along each of the plank's axes
    laid level: P a > W d (a: the load past the edge, d: the planks' centre of mass
    inside it; the other loads left out).  The overhang rule's reason (a bench's legs
    moved in under its seat: whoever sits at its end tips it, whatever the load cases
    say), for a piece too light for its overhang's share."""
    if design.anchors:
        return None
    loads = [-load.force[2] for case in design.load_cases for load in case.loads
             if load.plank == plank_id and not load.spread and load.force[2] < 0.0]
    if not loads:
        return None
    corners = np.concatenate([plank.corners for plank in design.planks])
    feet = corners[corners[:, 2] <= design.tolerance][:, :2]
    if len(feet) == 0:
        return None
    masses = np.array([design.plank_mass(plank) for plank in design.planks])
    centre = masses @ np.array([plank.center_array[:2] for plank in design.planks]) \
        / masses.sum()
    weight = float(masses.sum()) * GRAVITY
    plank = design.plank(plank_id)
    tips = []
    for axis, half in ((0, max(plank.length / 2.0 - END_LOAD_INSET, 0.0)),
                       (1, max(plank.width / 2.0 - END_LOAD_INSET, 0.0))):
        direction = plank.rotation_matrix[:2, axis]
        norm = float(np.hypot(*direction))
        if norm <= 0.5:
            continue
        direction = direction / norm
        reach = feet @ direction
        for sign, edge in ((1.0, float(reach.max())), (-1.0, float(reach.min()))):
            end = float(plank.center_array[:2] @ direction) + sign * half * norm
            past, inside = sign * (end - edge), sign * (edge - float(centre @ direction))
            if past > 0.0 and max(loads) * past > weight * inside:
                tips.append((max(loads), past, weight))
    return max(tips, key=lambda tip: tip[1], default=None)     # the farthest: a mirror
    # image's words are the design's


def _overhang_share(design: Design, plank_id: str,
                    jointed: list[tuple[str, bool]]) -> tuple[float, str] | None:
    """How far the level plank reaches past its supports at either end, along either of
    its in-plane axes, as a share of its size along that axis (0 where a support reaches
    its end), the larger of the two with its axis ('length' or 'width'); None without
    supports.  Its supports, among the planks ``jointed`` to it in the original (placed
    on ``design``'s planks): the planks below it whose ends are nailed to its face, and
    the faces its own ends are nailed to, each covering what its corners span along the
    axis (a side under a chair seat covers the seat's whole depth, and only its own
    thickness across)."""
    if plank_id not in design.plank_index:
        return None
    plank = design.plank(plank_id)
    holding = []
    for other, rests_on_it in jointed:
        if other not in design.plank_index:
            continue
        support = design.plank(other)
        if rests_on_it or support.center_array[2] < plank.center_array[2]:
            holding.append(support)
    if not holding:
        return None
    corners = np.concatenate([support.corners for support in holding]) - plank.center_array
    shares = []
    for axis, size, name in ((0, plank.length, "length"), (1, plank.width, "width")):
        along = corners @ plank.rotation_matrix[:, axis]
        reach = max(0.5 * size - float(along.max()), float(along.min()) + 0.5 * size, 0.0)
        shares.append((reach / size, name))
    return max(shares, key=lambda item: item[0])


def _relative(edit: PlankEdit, size: float, square: bool = False) -> float:
    """The plank's largest relative change (module docstring, item 3); its turn counts
    nothing where it is ``square``: given a quarter turn (``_quarter_turned``)."""
    if edit.action != "change":
        return WHOLE_PLANK
    largest = 0.0
    for field in edit.fields:
        if field.before is None or field.after is None:
            largest = max(largest, WHOLE_PLANK)
        elif field.field in POSITION_FIELDS:
            largest = max(largest, abs(field.change) / size)
        elif field.field in ANGLE_FIELDS:
            if not square:
                largest = max(largest, math.radians(abs(field.change)))
        elif field.field in SIZE_FIELDS or field.before != 0.0:
            largest = max(largest, abs(field.change) / abs(field.before))
    return largest


def _quarter_turned(original: Design, edited: Design, plank_id: str) -> bool:
    """Whether the plank is given a quarter turn about its length (its longer side: the
    same board standing square, a leg so turned by ``discrete.turns``): the rotation
    from its old frame to its new one is 90 degrees about an axis along that side, each
    within QUARTER_SLACK."""
    if plank_id not in original.plank_index or plank_id not in edited.plank_index:
        return False
    before = original.plank(plank_id).rotation_matrix
    after = edited.plank(plank_id).rotation_matrix
    relative = after @ before.T
    cosine = min(1.0, max(-1.0, 0.5 * (float(np.trace(relative)) - 1.0)))
    if abs(math.degrees(math.acos(cosine)) - 90.0) > QUARTER_SLACK:
        return False
    axis = np.array([relative[2, 1] - relative[1, 2], relative[0, 2] - relative[2, 0],
                     relative[1, 0] - relative[0, 1]])
    axis /= float(np.linalg.norm(axis))
    plank = original.plank(plank_id)
    length = before[:, 0 if plank.length >= plank.width else 1]
    return abs(float(length @ axis)) >= math.cos(math.radians(QUARTER_SLACK))


def _fits_board(plank: Plank) -> bool:
    long_side, short_side = sorted((plank.length, plank.width), reverse=True)
    return long_side <= STOCK_BOARD[0] and short_side <= STOCK_BOARD[1]


def _end_side(edge: Plank, joint) -> tuple[np.ndarray, float]:
    """(unit vector, length) of the long side of the edge plank's end that the joint
    nails to its face plank (the end face's other side is the plank's thickness)."""
    across = 1 - joint.edge_face[0]
    return edge.rotation_matrix[:, across], (edge.length, edge.width)[across]


def _hanging(design: Design, joint, faces: list[str]) -> float:
    """The share of the joint's edge plank's end (its narrow face on the face plank, a
    segment along that face's long side) that none of ``faces`` covers (the face planks
    that end is nailed to, counted together: an end under the seam of two boards is
    covered by both): the segment is clipped to each face plank's outline in the face's
    own axes."""
    edge = design.plank(joint.edge)
    axis, sign = joint.edge_face
    direction, width = _end_side(edge, joint)
    if width <= 0.0:
        return 0.0
    end = edge.center_array + sign * 0.5 * (edge.length, edge.width)[axis] \
        * edge.rotation_matrix[:, axis]
    covered = []
    for face in faces:
        if face not in design.plank_index:
            continue
        low, high = _clipped(end, direction, 0.5 * width, design.plank(face),
                             design.tolerance)
        if low < high:
            covered.append((low, high))
    reach, length = -0.5 * width, 0.0
    for low, high in sorted(covered):         # the union of the covered pieces
        low = max(low, reach)
        if high > low:
            length, reach = length + high - low, high
    return max(width - length, 0.0) / width


def _percent(share: float) -> int:
    """A share over HANG_SHARE in whole per cent, never rounded down to the threshold."""
    return max(round(100 * share), math.floor(100 * HANG_SHARE) + 1)


def _clipped(end: np.ndarray, direction: np.ndarray, half: float, face: Plank,
             slack: float) -> tuple[float, float]:
    """(low, high): the part of the segment end + s direction, |s| <= half, that lies
    within the face plank's outline widened by ``slack`` (the design's tolerance: an end
    flush with the face's edge is on it) (|offset . e_a| <= its half size along each
    in-plane axis e_a); low >= high where none does."""
    low, high = -half, half
    offset = end - face.center_array
    for a, size in ((0, face.length), (1, face.width)):
        axis = face.rotation_matrix[:, a]
        start, slope = float(offset @ axis), float(direction @ axis)
        bound = 0.5 * size + slack
        if abs(slope) <= 1e-12:
            if abs(start) > bound:
                return 0.0, 0.0
            continue
        first, second = sorted(((-bound - start) / slope, (bound - start) / slope))
        low, high = max(low, first), min(high, second)
    return low, high


def _overhangs(design: Design, joint) -> bool:
    """Whether the joint's edge plank is wider, along its end face, than its face plank
    reaches in that direction (beyond the tolerance)."""
    face = design.plank(joint.face)
    direction, width = _end_side(design.plank(joint.edge), joint)
    reach = float(np.abs(face.rotation_matrix[:, :2].T @ direction) @
                  np.array([face.length, face.width]))
    return width > reach + design.tolerance
