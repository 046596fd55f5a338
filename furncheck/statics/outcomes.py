"""What a load case's contact solver reports (``contacts._ActiveSet``'s verdicts): a stable
case's forces, a case that slides or lifts off with the forces it would need and why, and
the feasibility programs' verdict with the forces they fix where the iterations could not
settle (``from_programs``, ``prescribed``); the friction cones' tests the phases share.

``_Outcomes`` is the part of ``contacts._ActiveSet`` that builds them, apart from the
contact iterations themselves; it reads the solver's model, loads, tolerances and
``solve``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from furncheck import tolerances as tol
from furncheck.geometry.loose import loose_parts
from furncheck.geometry.support import (
    Tipping,
    convex_hull,
    nearest_edge,
    outside,
    tipping_on_plane,
)
from furncheck.plain import article, plain_compared, plain_list, plain_number
from furncheck.statics.model import CaseStatics, StaticsModel

if TYPE_CHECKING:   # the programs are imported where a case needs them
    from furncheck.statics.contacts import _Solution
    from furncheck.statics.feasibility import Feasibility

STICK, LIFT = 0, 2
FEEBLE_SCALES = (1e-9, 1e-12, 1e-15)
"""The feeble springs' stiffness, as fractions of the contacts', tried in turn where a
program's contact forces are imposed (``_ActiveSet.prescribed``)."""
_LINE_DETAIL = ("all its ground contacts lie on one line: it can at best balance on that "
                "edge, and the least push about it tips the design over")
_LINE_SLIDING = ("no equilibrium within the friction cones, and its ground contacts lie on "
                 "one line: no forces to show")
_MECHANISM_DETAIL = ("held down at all its contacts it would still move (a mechanism): no "
                     "forces to show")


class _Outcomes:
    """The verdicts and reports of ``contacts._ActiveSet`` (a mixin: it reads the solver's
    ``model``, ``f``, ``scale``, ``force_tol``, ``mu`` and ``anchored``, calls its
    ``solve`` and ``by_newton``, and ``prescribed`` builds another solver of its class,
    ``type(self)(model, f, scale)``)."""

    # -- results -------------------------------------------------------------------------------
    def stable(self, solution: _Solution, status: np.ndarray) -> CaseStatics:
        return CaseStatics("stable", _wrenches(self.model, solution.h),
                           solution.contact_forces,
                           state=np.concatenate([solution.q, solution.h]),
                           holding=status != LIFT, displacements=solution.q,
                           ground=solution.ground, part_wrenches=_parts(self.model, solution.h))

    def sliding(self, solution: _Solution) -> CaseStatics:
        """Report a case that slides, with the forces it would need if friction were endless."""
        model = self.model
        forces = solution.contact_forces
        over = self._outside_cones(forces)
        if model.contact_frames is not None:        # walls too: the friction each needs
            resting = self._rests_phrase(over, "slides on")
            if resting:                             # what the resting joints must hold
                needed, capacity = self._rests_friction(forces, over)
            else:                                   # the ground's and walls' corners
                surface, needed, capacity = self._surface_friction(forces)
            needs, gives = plain_compared(needed, capacity)
            if resting:
                what = (f"{resting}: a resting joint must pass on {needs} N along its faces, "
                        f"its friction gives at most {gives} N")
            else:
                faces = "their faces" if surface.endswith("walls") else "its face"
                what = f"{surface} must hold {needs} N along {faces}, friction gives at most " \
                       f"{gives} N"
            detail = (f"no equilibrium within the friction cones (mu = "
                      f"{plain_number(self.mu, 6)}): {what}")
            return CaseStatics("sliding", _wrenches(self.model, solution.h), forces,
                               self._plank_ids(over), detail, displacements=solution.q,
                               part_wrenches=_parts(self.model, solution.h))
        sideways = float(np.hypot(*forces[:, :2].sum(axis=0)))
        capacity = self.mu * float(forces[:, 2].sum())
        centre = (forces[:, 2] @ model.contact_points) / max(float(forces[:, 2].sum()), 1e-300)
        arms = model.contact_points - centre
        twist = abs(float((arms[:, 0] * forces[:, 1] - arms[:, 1] * forces[:, 0]).sum()))
        radius = float(np.sqrt(forces[:, 2] @ (arms ** 2).sum(axis=1)
                               / max(float(forces[:, 2].sum()), 1e-300)))
        significant = twist > 0.05 * sideways * radius + self.force_tol
        turning = plain_number(twist, 3)
        twist_text = f" and {article(turning)} {turning} N m twist" if significant else ""
        needs, gives = plain_compared(sideways, capacity)
        detail = (f"no equilibrium within the friction cones (mu = {plain_number(self.mu, 6)}): "
                  f"the ground must resist {needs} N sideways{twist_text}, "
                  f"friction gives at most {gives} N")
        if sideways > capacity + self.force_tol:    # it slides as a whole: all its feet
            over = forces[:, 2] > self.force_tol
        return CaseStatics("sliding", _wrenches(self.model, solution.h), forces,
                           self._plank_ids(over), detail, displacements=solution.q,
                           part_wrenches=_parts(self.model, solution.h))

    def unstable(self, stability: str, program: Feasibility | None = None) -> CaseStatics:
        """Report a case without admissible equilibrium: forces as if bolted to the ground
        (none when even bolted down the contacts cannot hold it: all on one line, or the
        design a mechanism on them)."""
        from furncheck.statics.feasibility import UNDECIDED

        bolted = self.solve(np.full(len(self.model.contacts), STICK))
        undecided = "" if program is None or program.status != UNDECIDED else (
            f"; the solver could not prove it either way ({program.message}), so the "
            "case is not passed")
        if bolted is None:
            detail = _MECHANISM_DETAIL if not _on_one_line(self.model.contact_points) else \
                _LINE_DETAIL if stability == "lift-off" else _LINE_SLIDING
            return CaseStatics(stability, None, None, (), detail + undecided)
        pulling = bolted.contact_forces[:, 2] < -self.force_tol
        if self.anchored is not None:
            pulling &= ~self.anchored
        least = self._hold_down() if stability == "lift-off" else None
        pulling[self.model.rest_rows] = False   # the ground's pulls; resting corners below
        resting, pulled = "", -float(bolted.contact_forces[pulling, 2].sum())
        rests_held = None
        if self.model.rest_node is not None and least is None:  # resting joints that open
            forces = bolted.contact_forces
            lifting = self._lifting_rests(forces)
            pulled = -float(forces[pulling, 2].sum()) + sum(lifting.values())
            by_statics = self._opening_by_statics(lifting)
            if by_statics is not None:          # the loose parts that tip, by statics:
                lifting, rests_held = by_statics    # the planks named are theirs alone
                pulling = np.zeros(len(forces), dtype=bool)
            corners = np.zeros(len(forces), dtype=bool)
            for rest, rows in self._rest_corners().items():
                corners[rows] = rest in lifting
            resting = self._rests_phrase(corners, "lifts off")
            pulling = pulling | corners         # the planks named: those that lift
        if stability == "lift-off" and resting:
            held = rests_held or f"held down, the {self._supports()} would have to pull " \
                f"{plain_number(pulled)} N"
            detail = (f"no equilibrium with the {self._supports()} only pushing: {resting} "
                      f"({held})")
        elif stability == "lift-off":
            held = f"held down, the {self._supports()} would have to pull " \
                f"{plain_number(pulled)} N" if least is None else \
                f"held down at {least[1]}, the ground would have to pull at least " \
                f"{plain_number(least[0])} N there"
            detail = (f"no equilibrium with the {self._supports()} only pushing: the line of "
                      "action of its weight and loads together falls outside the support "
                      f"polygon, the design topples ({held})")
            if least is not None and self.model.rest_node is not None:
                detail += self._parts_also()
        else:
            detail = (f"no equilibrium within the friction cones "
                      f"(mu = {plain_number(self.mu, 6)}); forces shown as if the design were "
                      f"bolted to the {self._supports()}")
        return CaseStatics(stability, _wrenches(self.model, bolted.h), bolted.contact_forces,
                           self._plank_ids(pulling), detail + undecided,
                           displacements=bolted.q, part_wrenches=_parts(self.model, bolted.h))

    def from_programs(self, target: np.ndarray, on_failure: _Solution | None,
                      bolted: _Solution | None = None) -> CaseStatics:
        """The verdict of the friction program when the iterations could not settle:
        'sliding' when it finds no equilibrium inside the friction cones (with the forces
        of ``on_failure`` if given); else stable, with the equilibrium of the contact law
        that Newton's method (``by_newton``) reaches from ``bolted`` (every contact
        sticking) where it reaches one, or the admissible contact forces closest to
        ``target`` (the elastic forces).  The program goes first: a design that slides,
        the usual reason the iterations fail, costs no Newton steps (where the program
        cannot decide, an equilibrium that Newton's method finds decides it)."""
        from furncheck.statics.feasibility import (
            INFEASIBLE,
            UNDECIDED,
            closest_admissible,
            cone_solution,
        )

        cone = cone_solution(self.model, self.f)
        settled = None
        if bolted is not None and (cone.exists or cone.status == UNDECIDED):
            settled = self.by_newton(bolted.ground)     # an equilibrium it finds exists
        if settled is not None:
            return settled
        if not cone.exists:
            if on_failure is not None and cone.status == INFEASIBLE:
                return self.sliding(on_failure)
            return self.unstable("sliding", cone)
        closest = closest_admissible(self.model, self.f, target)
        return self.prescribed(closest if self._admissible(closest) else cone.forces)

    def _admissible(self, forces: np.ndarray) -> bool:
        """Whether contact forces (nK, 3) press (N >= 0) and stay inside the friction
        cones, to the force tolerance (the exact balance of ``closest_admissible`` moves
        them by round-off; should it ever move them out, the program's own are used); an
        anchor's tie may pull."""
        pressing = forces[:, 2] >= -self.force_tol
        if self.anchored is not None:
            pressing |= self.anchored
        return bool(np.all(pressing) and not self._outside_cones(forces).any())

    def prescribed(self, contact_forces: np.ndarray) -> CaseStatics:
        """Joint wrenches for contact forces fixed by a feasibility program.

        The contact forces enter as loads; feeble springs (the contact stiffness times
        FEEBLE_SCALES, the first whose forces stay within the force tolerance) only remove
        the rigid motions and carry no force since the loads balance (the solve is judged
        against the loads' scale: its own right-hand side is round-off).  An elastic frame
        loaded by forces far from its own equilibrium ones can deform by centimetres
        (a racking table's feet, the program's friction fixed at them): 1e-9 of the
        stiffness then held 0.2 N per corner, so that its planks' wrenches missed balance
        by that much; the next scale holds a thousandth of it.
        """
        model = self.model
        f = self.f + model.contact_generalized(contact_forces)
        feeble = type(self)(model, f, self.scale)
        all_stick = np.full(len(model.contacts), STICK)
        solution = None
        for scale in FEEBLE_SCALES:
            found = feeble.solve(all_stick, stiffness_scale=scale, load_scale=self.scale)
            if found is None:
                break
            solution = found
            if np.abs(found.contact_forces).max(initial=0.0) <= self.force_tol:
                break
        if solution is None:
            return CaseStatics("lift-off", None, None, (), _LINE_DETAIL)
        return CaseStatics("stable", _wrenches(self.model, solution.h), contact_forces.copy(),
                           holding=self._pressing(contact_forces),
                           displacements=solution.q,
                           part_wrenches=_parts(self.model, solution.h))

    def _hold_down(self) -> tuple[float, str] | None:
        """(N, planks): the least pull at one ground contact that would hold a toppling
        design down, and the planks of the contacts where it is least ('leg_l or leg_r'
        where several tie: at either), by statics alone: the loads' resultant (weights
        included), V down, meets the floor outside the support polygon, and a pull P at
        hull point q holds it once the resultant of both meets the floor inside
        (``geometry.support.tipping_on_plane``, ``hold_down_ratios``: V d / a where it
        lies d beyond one edge and q a inside it; more beyond a corner), what ballast
        there would have to weigh (``suggest.needs``).  The bolted solve's pulls are no
        measure of it in the elastic model: a narrow foot's corners carry its plank's
        bending as a pair of large opposite forces (a sawhorse 3 % past its tipping push:
        901.9 N bolted, 3.804 N needed; a frame under a loose top, pushed over: 956.3 N at
        the top's resting corners bolted, 5.82 N needed at its front feet).  Resting
        joints count as part of the body: the whole design cannot stand once the
        resultant of all its loads meets the floor outside its ground contacts, whatever
        its resting joints do.  None where this does not apply (walls or anchors; grounded
        parts that no resting joint joins into one; contacts on a line; the resultant
        inside)."""
        model = self.model
        if model.contact_anchored is not None or not self._one_body():
            return None
        if any(model.geometry.contacts[c].wall is not None for c in model.contacts):
            return None
        rows = np.ones(len(model.contacts), dtype=bool)
        rows[model.rest_rows] = False
        rows = np.flatnonzero(rows)
        loads = self.f.reshape(-1, 6)
        tipping = tipping_on_plane(*_resultant(model.node_points, loads),
                                   model.contact_points[rows], np.array([0.0, 0.0, 1.0]))
        held = None if tipping is None else tipping.least_pull()
        if held is None:
            return None
        pull, tied = held
        planks = sorted(set(model.contact_plank[rows[tied]].tolist()))
        return pull, " or ".join(model.design.planks[model.planks[k]].id for k in planks)

    def _opening_by_statics(self, lifting) -> tuple[set[int], str] | None:
        """(the resting joints that open, the hold-down's words) by the statics of the
        loose parts that carry the joints the bolted solve finds opening (``lifting``):
        the parts that tip off their rests by ``tipping_on_plane`` (or that their loads
        lift), each opening every rest but those along the edge it tips over, with the
        least pull that would hold each down (``_hold_words``: 'held down at end_l or
        end_r, its rests would have to pull at least 28.84 N there').  The bolted solve
        is no measure of either in the elastic model: a plank's bending between its
        resting corners shows as couples at them, at an empty shelf on pins that lifts
        off nothing, or at the edge a loose desk top tips over (15,400 N of them where
        28.8 N holds it).  None where statics cannot say (a joint of no loose part, by
        ``geometry.loose``: a group that stands on its own too, carries what stands
        elsewhere, or rests on faces that push it different ways) or no part tips."""
        model = self.model
        parts = [part for part in loose_parts(model.design, model.geometry)
                 if part.rests & set(lifting)]
        if not parts or not set(lifting) <= {r for part in parts for r in part.rests}:
            return None
        holds = [(part, hold) for part in parts if (hold := self._part_hold(part)) is not None]
        if not holds:
            return None
        opening = set()
        for part, (_, _, tipping) in holds:     # a part lifted bodily opens every rest
            opening |= part.rests if tipping is None else \
                part.rests - _pivot_rests(model.design, model.geometry, part, tipping)
        return opening, self._hold_words(holds)

    def _parts_also(self) -> str:
        """'; top also lifts off its rests (held down at ...)' for the loose parts that tip
        by statics while the whole topples, or that their loads lift ('' for none):
        holding the whole down does not hold them."""
        model = self.model
        holds = [(part, hold) for part in loose_parts(model.design, model.geometry)
                 if (hold := self._part_hold(part)) is not None]
        if not holds:
            return ""
        names = plain_list([part.names(model.design).replace(",", " and ")
                            for part, _ in holds])
        one = len(holds) == 1
        return (f"; {names} {'also lifts' if one else 'also lift'} off "
                f"{'its' if one else 'their'} rests ({self._hold_words(holds)})")

    def _part_resultant(self, part) -> tuple[np.ndarray, np.ndarray]:
        """(force, moment about the origin) of the node loads on a loose part's planks."""
        model = self.model
        nodes = np.isin(np.asarray(model.planks)[model.node_plank], list(part.planks))
        return _resultant(model.node_points[nodes], self.f.reshape(-1, 6)[nodes])

    def _part_hold(self, part) -> tuple[float, str, Tipping | None] | None:
        """(N, where, tipping) of a loose ``part``: the least pull at one of its resting
        corners that would hold it down and the planks under the corners where it is
        least ('end_l or end_r'), by ``tipping_on_plane``; where its loads lift it, their
        upward part, at the planks it rests on ('end_l and end_r'; tipping None).  None
        where it stands (its loads' line meets its rests' plane inside them)."""
        design = self.model.design
        force, moment = self._part_resultant(part)
        lift = float(force @ part.push)
        if lift > 0.0:
            return lift, plain_list(sorted(set(part.under), key=design.plank_index.get)), None
        tipping = tipping_on_plane(force, moment, part.points, part.push)
        held = None if tipping is None else tipping.least_pull()
        if held is None:
            return None
        return held[0], " or ".join(sorted({part.under[k] for k in held[1]},
                                           key=design.plank_index.__getitem__)), tipping

    def _hold_words(self, holds: list) -> str:
        """'held down at end_l or end_r, its rests would have to pull at least 28.84 N
        there' ('in all' for a part lifted bodily), or for several parts each with its own
        pull and their sum, of (part, ``_part_hold``) pairs."""
        if len(holds) == 1:
            (_, (pull, place, tipping)), = holds
            return (f"held down at {place}, its rests would have to pull at least "
                    f"{plain_number(pull)} N {'in all' if tipping is None else 'there'}")
        design = self.model.design
        each = " and ".join(f"{part.names(design)} at {place} ({plain_number(pull)} N)"
                            for part, (pull, place, _) in holds)
        total = sum(pull for _, (pull, _, _) in holds)
        return (f"held down, {each}, their rests would have to pull at least "
                f"{plain_number(total)} N in all")

    def _one_body(self) -> bool:
        """Whether the grounded components, joined where one rests on another, are one."""
        model = self.model
        group = list(range(len(model.components)))

        def root(c: int) -> int:
            while group[c] != c:
                c = group[c]
            return c

        for k in model.rest_rows:
            a, b = root(int(model.contact_component[k])), root(int(model.rest_component[k]))
            group[a] = b
        return len({root(c) for c in range(len(group))}) == 1

    def _supports(self) -> str:
        """What the contacts stand on, for messages: 'ground', 'ground and walls', or
        'supports' where planks rest on others."""
        if self.model.rest_node is not None:
            return "supports"
        return "ground" if self.model.contact_frames is None else "ground and walls"

    def _rest_corners(self) -> dict[int, list[int]]:
        """Per resting joint (its index in ``Design.joints``), its corners' contact rows."""
        model, corners = self.model, {}
        for k in model.rest_rows:
            corners.setdefault(model.geometry.contacts[model.contacts[k]].rest, []).append(k)
        return corners

    def _rest_totals(self, forces: np.ndarray) -> dict[int, np.ndarray]:
        """Per resting joint, its corners' forces (nK, 3) summed (one after the other):
        what the corners push against each other cancels."""
        totals = {}
        for rest, rows in self._rest_corners().items():
            total = np.zeros(3)
            for k in rows:
                total = total + forces[k]
            totals[rest] = total
        return totals

    def _surface_friction(self, forces: np.ndarray) -> tuple[str, float, float]:
        """('the ground', 'the wall' or 'wall N', N, N): the support surface that needs
        the most friction for what it gives, with the sideways force its corners must hold
        (their forces summed, each grounded component's apart: what they pull against
        each other along the face, as an elastic board's corners do, cancels) and the
        friction mu N they give; where every such sum is within its friction (a twist, or
        corners that slide against each other), the sum of every corner's sideways force
        instead."""
        model = self.model
        rows: dict[tuple[int, int], list[int]] = {}     # (surface, component) -> corners
        for k, c in enumerate(model.contacts):
            contact = model.geometry.contacts[c]
            if contact.rest is None and (self.anchored is None or not self.anchored[k]):
                surface = -1 if contact.wall is None else contact.wall
                rows.setdefault((surface, int(model.contact_component[k])), []).append(k)
        worst = None
        for (wall, _), ks in sorted(rows.items()):
            needed = float(np.hypot(*forces[ks, :2].sum(axis=0)))
            capacity = self.mu * float(np.maximum(forces[ks, 2], 0.0).sum())
            if worst is None or needed - capacity > worst[1] - worst[2]:
                name = "the ground" if wall < 0 else \
                    "the wall" if len(model.design.walls) == 1 else f"wall {wall}"
                worst = (name, needed, capacity)
        if worst is not None and worst[1] - worst[2] > self.force_tol:
            return worst
        own = [k for ks in rows.values() for k in ks]    # each nets out: its corners' sum
        walls = any(model.geometry.contacts[c].wall is not None for c in model.contacts)
        return ("the ground and walls" if walls else "the ground",
                float(np.hypot(forces[own, 0], forces[own, 1]).sum()),
                self.mu * float(np.maximum(forces[own, 2], 0.0).sum()))

    def _lifting_rests(self, forces: np.ndarray) -> dict[int, float]:
        """The resting joints that cannot pass on their corners' forces (nK, 3) by pushing
        alone, each with the pull it would need (N): one whose corners' forces add up to
        a pull (that sum), and one that presses as a whole but whose centre of pressure
        lies outside the polygon of its corners, so that it tips about an edge (the
        pull of its corners that pull: a loose block pushed over on its base)."""
        model, found = self.model, {}
        for rest, ks in self._rest_corners().items():
            normal = forces[ks, 2]
            total = float(normal.sum())
            if total < -self.force_tol:
                found[rest] = -total
                continue
            pulls = -float(np.minimum(normal, 0.0).sum())
            if pulls <= self.force_tol:
                continue
            if total <= self.force_tol:         # a couple alone: no centre of pressure
                found[rest] = pulls
                continue
            frame = model.contact_frames[ks[0]]
            flat = model.contact_points[ks] @ frame[:2].T           # in the rest's plane
            centre = normal @ flat / total
            hull = flat[convex_hull(flat)]
            if outside(hull, centre)[0] > model.design.tolerance:     # it tips
                found[rest] = pulls
        return found

    def _rests_friction(self, forces: np.ndarray, over: np.ndarray) -> tuple[float, float]:
        """(N, N) of the resting joint that needs the most friction for what it gives
        (among those with a corner in ``over``): the sideways force it must pass on, its
        corners' forces summed, and the friction mu N it gives."""
        model = self.model
        sliding = {model.geometry.contacts[model.contacts[k]].rest
                   for k in model.rest_rows if over[k]}
        worst = (0.0, 0.0)
        for rest, total in self._rest_totals(forces).items():
            if rest not in sliding:
                continue
            needed, capacity = float(np.hypot(total[0], total[1])), \
                self.mu * max(float(total[2]), 0.0)
            if needed - capacity > worst[0] - worst[1]:
                worst = (needed, capacity)
        return worst

    def _rests_phrase(self, mask: np.ndarray, verb: str) -> str:
        """'top lifts off side_l; ...' for the resting joints with a corner in ``mask``:
        the upper plank (the face plank when its face looks down onto the edge plank)
        first; '' for none."""
        model, phrases = self.model, []
        for k in model.rest_rows:
            if not mask[k]:
                continue
            contact = model.geometry.contacts[model.contacts[k]]
            upper, lower = contact.resting
            phrase = f"{upper} {verb} {lower}"
            if phrase not in phrases:
                phrases.append(phrase)
        return "; ".join(phrases)

    def _pressing(self, forces: np.ndarray) -> np.ndarray:
        """(nK,) bool: the contacts that hold with forces (nK, 3): those that press, and
        the anchors' ties whatever they do."""
        pressing = forces[:, 2] > self.force_tol
        return pressing if self.anchored is None else pressing | self.anchored

    def within_cones(self, solution: _Solution) -> bool:
        return not self._outside_cones(solution.contact_forces).any()

    def _outside_cones(self, forces: np.ndarray) -> np.ndarray:
        """(nK,) bool: contact forces (nK, 3) whose sideways part exceeds mu N (beyond the
        force tolerance); never an anchor's tie."""
        outside = np.hypot(forces[:, 0], forces[:, 1]) > self.mu * forces[:, 2] + self.force_tol
        return outside if self.anchored is None else outside & ~self.anchored

    def _plank_ids(self, mask: np.ndarray) -> tuple[str, ...]:
        """The planks of the contacts in ``mask`` (both planks of a resting corner)."""
        design, model = self.model.design, self.model
        ids = {design.planks[model.planks[model.contact_plank[k]]].id
               for k in np.nonzero(mask)[0]}
        if model.rest_node is not None:
            ids |= {model.geometry.contacts[model.contacts[k]].on
                    for k in np.nonzero(mask)[0] if model.rest_node[k] >= 0}
        return tuple(p.id for p in design.planks if p.id in ids)


def _on_one_line(points: np.ndarray) -> bool:
    """Whether the contact points (nK, 3) lie on one line (or at one point), to
    MECHANISM_RCOND of their spread."""
    if len(points) < 2:
        return True
    spread = np.linalg.svd(points - points.mean(axis=0), compute_uv=False)
    return bool(spread[1] <= tol.MECHANISM_RCOND * max(spread[0], 1e-300))


def _wrenches(model: StaticsModel, h: np.ndarray) -> np.ndarray:
    """(nJ, 6) each joint's wrench from the springs' wrenches h (``joint_totals``)."""
    return model.joint_totals(h).reshape(-1, 6).copy()


def _parts(model: StaticsModel, h: np.ndarray) -> np.ndarray | None:
    """(nS, 6) the springs' own wrenches where joints are cut into parts, else None."""
    return None if model.joint_parts is None else h.reshape(-1, 6).copy()


def _resultant(points: np.ndarray, loads: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(force, moment about the world origin) of node loads (k, 6) at ``points`` (k, 3)."""
    force = loads[:, :3].sum(axis=0)
    moment = (np.cross(points, loads[:, :3]) + loads[:, 3:]).sum(axis=0)
    return force, moment


def _pivot_rests(design, geometry, part, tipping) -> set[int]:
    """The resting joints of a loose ``part`` that lie along the edge (or at the corner)
    of its support that it tips over (``tipping``: the polygon's side or vertex nearest
    where its loads' line meets the rests' plane): each of its corners within PIVOT_SHARE
    of the farthest support's distance from it, or the design's tolerance (a front apron's
    18 mm top edge, a front pin): they stay pressed, the others open."""
    hull = part.points[tipping.hull]
    k = nearest_edge(hull, tipping.nearest_point)[0]
    a, b = hull[k], hull[(k + 1) % len(hull)]
    at_corner = min(float(np.linalg.norm(tipping.nearest_point - p)) for p in (a, b)) \
        <= design.tolerance + 1e-9 or float(np.linalg.norm(b - a)) == 0.0

    def distance(point: np.ndarray) -> float:
        if at_corner:
            return float(np.linalg.norm(point - tipping.nearest_point))
        along = (b - a) / float(np.linalg.norm(b - a))
        offset = point - a
        return float(np.linalg.norm(offset - (offset @ along) * along))

    distances = np.array([distance(point) for point in part.points])
    reach = max(PIVOT_SHARE * float(distances.max(initial=0.0)), design.tolerance) + 1e-9
    near: dict[int, list[bool]] = {}
    for k, gap in zip(part.corners, distances):
        near.setdefault(geometry.contacts[k].rest, []).append(bool(gap <= reach))
    return {rest for rest, flags in near.items() if all(flags)}


PIVOT_SHARE = 0.1
"""A loose part's resting joint whose corners all lie within this share of its support's
depth from the edge it tips over counts as that edge, which stays pressed
(``_pivot_rests``)."""
