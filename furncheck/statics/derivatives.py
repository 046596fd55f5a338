"""How a solved case's equations change with a design edit: the right-hand sides of the
force sensitivity (paper eq. 6), for either model.

At a solved state x = [q; h] the statics is A(g) x = b(g).  For the designs of a DOF
stepped to either side (``AssemblySide``: the design, and its joints and contacts followed
through the step), ``assembly_differences`` gives the differences of b - A x (x held),
of the contact maps and of the joint lengths; ``rates = A^-1 (their residual)`` is eq. 6.

* Rigid planks: only the terms a step changes are evaluated (the joints and contacts of
  the planks it moves, their weights and loads), so a DOF costs about as much as its few
  moved planks.
* Elastic planks: the stepped design's model is built again on the same nodes
  (``elastic.build_elastic_model(..., template=model)``: every node at the new place of
  what it serves) and b - A x evaluated whole (the stepped models' residuals and loads
  made together, ``_residuals``); the planks' sag, span and stress at the stepped state
  x + dx give their rates (``AssemblyDifferences.plank_rates``: each stepped model read
  only at the points where the design's own largest sag and stress may lie, in stacked
  passes, ``bending_points.plank_results_at``).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design
from furncheck.geometry import Contact, Joint
from furncheck.statics.contact_law import ContactLaw
from furncheck.statics.elements import elastic_forces_many
from furncheck.statics.model import StaticsModel, block_sums, external_forces
from furncheck.statics.offsets import point_maps
from furncheck.tolerances import GRAVITY

if TYPE_CHECKING:
    from furncheck.statics.bending import PlankPart


@dataclass(frozen=True)
class AssemblySide:
    """One side of a difference: DOF ``column``, its ``weight`` (+-1 / 2h, or +-1 / h),
    how far the DOF is from the design (``offset``, DOF unit), the design planks it
    changes and the geometry joints and contacts on them, and the stepped design with
    those joints and contacts followed."""

    column: int
    weight: float
    offset: float
    changed: tuple[int, ...]
    joints: tuple[int, ...]
    contacts: tuple[int, ...]
    design: Design
    followed_joints: tuple[Joint, ...]
    followed_contacts: tuple[Contact, ...]


@dataclass
class AssemblyDifferences:
    """The differences over the sides: ``residual`` (N, D) of b - A x, ``maps``
    (D, nK, 3, 6) of the contact maps (and ``rest_maps`` of the resting corners' other
    planks' maps, when the model has them; ``arms`` of the arms of joints cut into parts,
    ``StaticsModel.part_arms``), ``lengths`` (D, nJ) of the joint lengths (m),
    per DOF unit; for the planks' rates (elastic model only), ``sides``: per side (column,
    weight, offset, the stepped model's ``bending.PlankPart``, its case), the state's
    displacements ``q`` and holding contacts, the local ``planks`` read (None: all;
    ``n_planks`` in the model) and the ``PlankPart`` of the model itself (``base``); of
    the planks checked as plates too (``statics.plates``), their plates' (sag, span,
    stress) in the model itself (``plate_base``, local plank -> reading), whether their
    sag and their stress are the plate's (``plate_governs``) and per side
    (``plate_sides``: (column, weight, readings), ``_plate_sides``)."""

    residual: np.ndarray
    maps: np.ndarray
    lengths: np.ndarray
    sides: list = field(default_factory=list)
    rest_maps: np.ndarray | None = None
    q: np.ndarray | None = None
    holding: np.ndarray | None = None
    planks: np.ndarray | None = None
    n_planks: int = 0
    base: PlankPart | None = None
    arms: np.ndarray | None = None      # (D, nS, 3) of the joint parts' arms (m), if any
    shares: np.ndarray | None = None    # (D, nSt) of the support stations' shares, if any
    plate_base: dict = field(default_factory=dict)
    plate_governs: dict = field(default_factory=dict)   # local plank -> (sag, stress)
    plate_sides: list = field(default_factory=list)
    at_rest: tuple | None = None        # the base's planks and where their largest lie

    def plank_rates(self, dq: np.ndarray) -> tuple[np.ndarray, ...]:
        """(D, nP) each: d sag (m), d span (m), d stress (Pa) per DOF unit, from the
        stepped models at x + offset dx (dq: (6 nN, D), the displacement rates); (D, 0)
        each for rigid planks.  With ``planks`` only those local planks' rates are read
        (the others' are 0).

        Each stepped model's planks are read only at the points where the design's own
        largest sag and stress may lie (``bending_points.plank_results_where`` of ``base``, the
        model itself: those within NEAR_LARGEST of the largest, ties kept): at a step this
        small a stepped design's largest lie among them, so reading them alone
        (``bending_points.plank_results_at``) gives the numbers reading every point would, at a
        fraction of the cost."""
        n_dofs = self.residual.shape[1]
        if not self.sides:
            empty = np.zeros((n_dofs, 0))
            return empty, empty.copy(), empty.copy()
        from furncheck.statics.bending_points import plank_results_where

        n_planks = self.n_planks
        read = slice(None) if self.planks is None else self.planks
        sag, span, stress = (np.zeros((n_dofs, n_planks)) for _ in range(3))
        at_rest, where = self.at_rest or plank_results_where(self.base, self.q)
        stepped = [(part, column, offset)
                   for column, _, offset, part, _ in self.sides if offset != 0.0]
        moved = _plank_results_batched(stepped, self.q, dq, where)
        for column, weight, offset, *_ in self.sides:
            result = at_rest if offset == 0.0 else next(moved)
            sag[column, read] += weight * result.sag
            span[column, read] += weight * result.span
            stress[column, read] += weight * result.stress
        if self.plate_base:
            self._plate_rates(sag, span, stress)
        return sag, span, stress

    def _plate_rates(self, sag: np.ndarray, span: np.ndarray, stress: np.ndarray) -> None:
        """Where a plank's plate reading is its plank's (``plates.plate_governs``: its sag
        over its span above its beam's, its stress above its beam's), its rates (in
        place) are the plate's, differenced over the sides as the beams' are: a shelf
        held on three edges sags as its plate says, and a step that moves what holds it
        changes that sag, not its beam's (``plate_sides``).  A DOF whose stepped design
        has no plate there, or one on another grid (``plates.same_grid``), keeps its
        beam's rates."""
        for k, (sags, stresses) in self.plate_governs.items():
            rates = np.zeros((sag.shape[0], 3))
            kept = np.ones(sag.shape[0], dtype=bool)
            for column, weight, readings in self.plate_sides:
                stepped = readings.get(k)
                if stepped is None:
                    kept[column] = False
                else:
                    rates[column] += weight * np.asarray(stepped[:3])
            if sags:
                sag[kept, k], span[kept, k] = rates[kept, 0], rates[kept, 1]
            if stresses:
                stress[kept, k] = rates[kept, 2]


def _plank_results_batched(stepped: list, q: np.ndarray, dq: np.ndarray, where):
    """The planks of each stepped (part, column, offset) at q + offset dq[:, column], read
    at ``where`` (``bending_points.plank_results_at``), in order, at most PLANK_BATCH planks at a
    time (its numbers are those of one call each, so the batches change nothing but the
    memory)."""
    from furncheck.statics.bending_points import plank_results_at

    batch: list = []
    displacements: list = []
    count = 0
    for part, column, offset in stepped:
        if batch and count + len(part.model.planks) > tol.PLANK_BATCH:
            yield from plank_results_at(batch, displacements, where)
            batch, displacements, count = [], [], 0
        batch.append(part)
        displacements.append(q + offset * dq[:, column])
        count += len(part.model.planks)
    if batch:
        yield from plank_results_at(batch, displacements, where)


def assembly_steps(model: StaticsModel) -> tuple[float, float]:
    """(length step as a fraction of the design's size, rotation step in degrees) of the
    assembly's central differences for this model (tolerances: ASSEMBLY_STEP in the rigid
    model, ELASTIC_ASSEMBLY_STEP and ELASTIC_ANGLE_STEP in the elastic one)."""
    if model.beams is None:
        return tol.ASSEMBLY_STEP, tol.ASSEMBLY_STEP
    return tol.ELASTIC_ASSEMBLY_STEP, tol.ELASTIC_ANGLE_STEP


def assembly_differences(model: StaticsModel, state: np.ndarray, law: ContactLaw,
                         case_name: str, sides: list[AssemblySide], n_dofs: int,
                         planks: np.ndarray | None = None) -> AssemblyDifferences:
    """The differences of b - A x over ``sides`` (see the module docstring); the contacts
    push as ``law`` says (springs where they stick, mu N where they slipped).  ``planks``:
    the local planks whose rates ``plank_rates`` reads (None: all)."""
    if model.beams is not None:
        return _rebuilt(model, state, law, case_name, sides, n_dofs, planks)
    return _local(model, state, law, case_name, sides, n_dofs)


def _rebuilt(model: StaticsModel, state: np.ndarray, law: ContactLaw, case_name: str,
             sides: list[AssemblySide], n_dofs: int,
             planks: np.ndarray | None) -> AssemblyDifferences:
    """Elastic model: each side's model built on the same nodes, b - A x evaluated whole;
    of each stepped model only what its planks' rates read is kept (``bending.plank_part``:
    with ``planks``, a cut of those planks, so the stepped models themselves are let go)."""
    from furncheck.statics.bending import plank_part

    n = model.n_dof
    q, h = state[:n], state[n:]
    out = AssemblyDifferences(np.zeros((len(state), n_dofs)),
                              np.zeros((n_dofs, *model.contact_maps.shape)),
                              np.zeros((n_dofs, len(model.joints))), q=q,
                              holding=law.holding, planks=planks, n_planks=len(model.planks))
    if model.rest_maps is not None:
        out.rest_maps = np.zeros((n_dofs, *model.rest_maps.shape))
    if model.part_arms is not None:
        out.arms = np.zeros((n_dofs, *model.part_arms.shape))
    if model.station_shares is not None:
        out.shares = np.zeros((n_dofs, len(model.station_shares)))
    geometry = model.geometry
    own_case = next(c for c in model.design.load_cases if c.name == case_name)
    whole = plank_part(model, own_case, law.holding)
    supports = (whole.low, whole.high)      # a stepped model's too (``plank_part``)
    out.base = whole if planks is None else \
        plank_part(model, own_case, law.holding, planks, supports)
    unchanged = {}                  # case name -> b - A x of the model itself
    plates = _plate_sides(model, own_case, planks, out)
    own = [side.design is model.design and _followed_as_is(geometry, side) for side in sides]
    built = _stepped_models(model, [side for side, itself in zip(sides, own) if not itself],
                            case_name, q, h, law)
    for side, itself in zip(sides, own):
        case = next(c for c in side.design.load_cases if c.name == case_name)
        if itself:
            # the design itself (the base of a one-sided difference): its model is
            # ``model`` (built on itself, a template gives the same model bit for bit)
            stepped, stepped_geometry = model, geometry
            if case.name not in unchanged:
                unchanged[case.name] = _residual(model, case, q, h, law)
            residual, part = unchanged[case.name], out.base
        else:       # each stepped model is let go once its residual and part are made
            stepped, stepped_geometry, residual = next(built)
            part = plank_part(stepped, case, law.holding, planks, supports)
        out.residual[:, side.column] += side.weight * residual
        out.maps[side.column] += side.weight * stepped.contact_maps
        if stepped.rest_maps is not None:
            out.rest_maps[side.column] += side.weight * stepped.rest_maps
        if stepped.part_arms is not None:
            out.arms[side.column] += side.weight * stepped.part_arms
        if stepped.station_shares is not None:
            out.shares[side.column] += side.weight * stepped.station_shares
        out.lengths[side.column] += side.weight * np.array(
            [stepped_geometry.joints[j].length for j in model.joints])
        out.sides.append((side.column, side.weight, side.offset, part, case))
        if plates is not None and side.offset > 0.0:    # forward differences
            out.plate_sides += [(side.column, 1.0 / side.offset,
                                 plates(side, stepped, case, itself)),
                                (side.column, -1.0 / side.offset, out.plate_base)]
    return out


def _plate_sides(model: StaticsModel, case, planks: np.ndarray | None,
                 out: AssemblyDifferences):
    """For the planks read (``planks``, None: all) that the model checks as plates too:
    their plates' readings in the model itself (kept in ``out.plate_base``), and a
    function of a side (side, its stepped model, its case, whether it is the design
    itself) that gives theirs in its stepped design: read again for the planks whose
    plate the step may change (the plank, or a plank nailed to it, among those it
    changes: its size, its supports or its loads), the design's for the others, None
    where the stepped design has no plate there or one on another grid
    (``plates.same_grid``).  None where no plank read is a plate whose reading is its
    plank's (its sag over its span, or its stress, above its beam's: the beams' rates
    hold) and uses PLATE_RATES_FROM of its allowance or more by that reading.  The
    plates' rates are forward differences, from the side a step ahead and the design,
    where the sides are a step either way (each stepped plate is factored anew: the
    cabinet's linearizations in its four cases meet 452 new plates, about a second)."""
    from furncheck.statics.bending_points import plank_results_where
    from furncheck.statics.plates import (
        plate_governs,
        plate_planks,
        plate_readings,
        same_grid,
        whole_rows_hung,
    )
    from furncheck.validity import bending_use, plank_limits

    locals_ = {plate.local for plate in plate_planks(model)}
    if planks is not None:
        locals_ &= {int(k) for k in planks}
    if not locals_:
        return None
    readings = plate_readings(model, case, locals_)
    out.at_rest = plank_results_where(out.base, out.q)  # the planks read, in order
    beams = out.at_rest[0]
    read = list(range(len(model.planks))) if planks is None else [int(k) for k in planks]
    place = {k: i for i, k in enumerate(read)}
    sag_limit, creep, strength = plank_limits(model.design, model)
    for k, reading in readings.items():
        i = place[k]
        governs = plate_governs(reading, float(beams.sag[i]), float(beams.span[i]),
                                float(beams.stress[i]), k in whole_rows_hung(model))
        used = bending_use(reading.sag, reading.span, reading.stress, sag_limit[k],
                           creep[k], strength[k])
        if any(g and float(u) >= tol.PLATE_RATES_FROM for g, u in zip(governs, used)):
            out.plate_base[k], out.plate_governs[k] = reading, governs
    if not out.plate_base:
        return None
    design, geometry = model.design, model.geometry
    near: dict[int, set[int]] = {k: {model.planks[k]} for k in out.plate_base}
    by_id = {design.planks[model.planks[k]].id: k for k in out.plate_base}
    for joint in geometry.joints:
        first, second = joint.planks
        for one, other in ((first, second), (second, first)):
            if one in by_id:
                near[by_id[one]].add(design.plank_index[other])

    def readings_of(side: AssemblySide, stepped: StaticsModel, stepped_case,
                    itself: bool) -> dict:
        changed = set(side.changed)
        moved = {k for k, around in near.items() if around & changed}
        if itself or not moved:
            return out.plate_base
        found = plate_readings(stepped, stepped_case, moved)
        return {k: (found[k] if k in found and same_grid(found[k], reading) else None)
                if k in moved else reading for k, reading in out.plate_base.items()}
    return readings_of


def _stepped_models(model: StaticsModel, sides: list[AssemblySide], case_name: str,
                    q: np.ndarray, h: np.ndarray, law: ContactLaw):
    """(stepped model, its geometry, its b - A x) of each side in order, the models built
    on ``model`` a batch at a time (``templated.build_elastic_model_batches``) and each
    batch's residuals computed together (``_residuals``)."""
    from furncheck.statics.templated import build_elastic_model_batches

    geometries = [_stepped_geometry(model.geometry, side) for side in sides]
    done = 0
    for batch in build_elastic_model_batches([side.design for side in sides], geometries,
                                             model):
        cases = [next(c for c in side.design.load_cases if c.name == case_name)
                 for side in sides[done:done + len(batch)]]
        yield from zip(batch, geometries[done:done + len(batch)],
                       _residuals(batch, cases, q, h, law))
        done += len(batch)


def _residuals(models: list[StaticsModel], cases: list, q: np.ndarray, h: np.ndarray,
               law: ContactLaw) -> list[np.ndarray]:
    """``_residual`` of several models of one topology (built on one template) at the same
    q and h: each contact's, element's and joint's terms computed for all the models in
    one pass, and summed at each model's nodes in the same order as ``_residual`` does,
    so the numbers are its own.  One model at a time where resting corners are."""
    first = models[0]
    if len(models) == 1 or first.rest_node is not None or not first.n_springs \
            or not len(first.contacts):
        return [_residual(m, c, q, h, law) for m, c in zip(models, cases)]
    count, n_nodes = len(models), first.n_nodes
    nodes_q = q[:first.n_dof].reshape(-1, 6)
    maps = np.concatenate([m.contact_maps for m in models])                   # (S nK, 3, 6)
    contact_q = np.tile(nodes_q[first.contact_node], (count, 1))
    w = (maps @ contact_q[:, :, None])[:, :, 0]
    forces = law.forces(w, np.tile(np.arange(len(first.contacts)), count))
    per_contact = (np.transpose(maps, (0, 2, 1)) @ forces[:, :, None])[:, :, 0]
    generalized = _summed(first.contact_node, per_contact, n_nodes, count)
    beams = first.beams
    u = np.tile(nodes_q[beams.nodes].reshape(-1, 4, 3), (count, 1, 1))
    frames = np.concatenate([m.beams.frames for m in models])
    stiffness = np.concatenate([m.beams.local_stiffness for m in models])
    local = np.einsum("eab,eb->ea", stiffness, (u @ frames).reshape(-1, 12))
    world = local.reshape(-1, 4, 3) @ np.transpose(frames, (0, 2, 1))
    beam = _summed(beams.nodes.ravel(), world.reshape(-1, 6), n_nodes, count)
    wrench = np.tile(h.reshape(-1, 6), (count, 1))
    per_joint = np.einsum("jsab,ja...->jsb...", np.concatenate([m.joint_blocks for m in models]),
                          wrench)
    reactions = _summed(first.joint_nodes.ravel(), per_joint.reshape(-1, 6), n_nodes, count)
    top = beam + reactions - generalized                                       # (S, 6 nN)
    compliance = (np.concatenate([m.joint_compliance for m in models])
                  @ wrench.reshape(-1, 6, 1)).reshape(count, -1)
    columns = np.tile(nodes_q[first.joint_nodes].reshape(first.n_springs, 12, 1),
                      (count, 1, 1))
    deviations = (np.concatenate([m.joint_rows for m in models]) @ columns).reshape(count, -1)
    bottom = deviations - compliance
    loads = elastic_forces_many(models, cases) if first.beams is not None else \
        [external_forces(m, c) for m, c in zip(models, cases)]
    return [np.concatenate([loads[k] - top[k], -bottom[k]]) for k in range(count)]


def _summed(index: np.ndarray, values: np.ndarray, n_nodes: int, count: int) -> np.ndarray:
    """(count, 6 nN): ``model.block_sums`` of each model's rows of ``values`` (count x
    len(index), 6) by ``index``, each model's nodes numbered after the previous one's (a
    node's terms are summed in the same order as one model at a time)."""
    shifted = (np.asarray(index)[None, :] + n_nodes * np.arange(count)[:, None]).ravel()
    return block_sums(shifted, values, count * n_nodes).reshape(count, -1)


def _stepped_geometry(geometry, side: AssemblySide):
    """The geometry with the side's joints and contacts followed (each joint keeping the
    nails it has)."""
    joints = list(geometry.joints)
    for j, joint in zip(side.joints, side.followed_joints):
        nails = geometry.joints[j].nails                         # nails held
        joints[j] = joint if joint.nails == nails else replace(joint, nails=nails)
    contacts = list(geometry.contacts)
    for k, contact in zip(side.contacts, side.followed_contacts):
        contacts[k] = contact
    return replace(geometry, joints=tuple(joints), contacts=tuple(contacts))


def _followed_as_is(geometry, side: AssemblySide) -> bool:
    """Whether the side's followed joints and contacts are the geometry's own."""
    return all(followed is geometry.joints[j]
               for j, followed in zip(side.joints, side.followed_joints)) \
        and all(followed is geometry.contacts[k]
                for k, followed in zip(side.contacts, side.followed_contacts))


def _residual(model: StaticsModel, case, q: np.ndarray, h: np.ndarray,
              law: ContactLaw) -> np.ndarray:
    """b - A x of the mixed system [[K_b, G^T], [G, -E]] [q; h] = [f + M^T f_c; 0], the
    contact forces f_c as ``law`` gives them for the contact displacements M q."""
    w = model.contact_displacements(q)
    top = model.beam_forces(q) + model.reactions(h) - model.contact_generalized(law.forces(w))
    compliance = (model.joint_compliance @ h.reshape(-1, 6, 1)).ravel()
    bottom = model.deviations(q) - compliance
    return np.concatenate([external_forces(model, case) - top, -bottom])


def _local(model: StaticsModel, state: np.ndarray, law: ContactLaw, case_name: str,
           sides: list[AssemblySide], n_dofs: int) -> AssemblyDifferences:
    """Rigid model: the differences of the parts of b - A x that the steps change (every
    other entry is the same on both sides of a difference).

    With r = joint point - plank centre, a joint enters A x through its deviation rows
    (theta_a x r_a - theta_b x r_b) and its planks' moment rows (+-r x h^t); a contact
    through M^T f_c(M q) (M = [I, -[r]x], r = contact point - centre, f_c its force by the
    contact law); a plank through its weight and its loads' moments about its centre.
    """
    n = model.n_dof
    q = state[:n].reshape(-1, 6)
    wrench = state[n:].reshape(-1, 6)
    residual = np.zeros((len(state), n_dofs))
    maps = np.zeros((n_dofs, *model.contact_maps.shape))
    lengths = np.zeros((n_dofs, len(model.joints)))
    local_plank = {plank: k for k, plank in enumerate(model.planks)}
    joint_row = {j: row for row, j in enumerate(model.joints)}
    contact_row = {k: row for row, k in enumerate(model.contacts)}
    joint_rows, contact_rows, plank_rows, rest_rows = [], [], [], []
    rest_maps = None if model.rest_maps is None else np.zeros((n_dofs, *model.rest_maps.shape))
    for side in sides:
        column, weight, design = side.column, side.weight, side.design
        index = design.plank_index
        for j, joint in zip(side.joints, side.followed_joints):
            row = joint_row.get(j)
            if row is None:
                continue
            a, b = (local_plank[index[plank]] for plank in joint.planks)
            joint_rows.append((column, weight, row, a, b, *joint.point,
                               *design.planks[model.planks[a]].center_array,
                               *design.planks[model.planks[b]].center_array, joint.length))
        for k, contact in zip(side.contacts, side.followed_contacts):
            row = contact_row.get(k)
            if row is None:
                continue
            a = model.contact_node[row]
            if model.rest_node is not None and model.rest_node[row] >= 0:
                b = model.rest_node[row]        # its frame turns with the face plank
                rest_rows.append((column, weight, row, a, b, *(
                    contact.point - design.planks[model.planks[a]].center_array), *(
                    contact.point - design.planks[model.planks[b]].center_array),
                    *np.asarray(contact.frame, dtype=float).ravel()))
                continue
            contact_rows.append((column, weight, row, a, *(
                contact.point - design.planks[model.planks[a]].center_array)))
        case = next(c for c in design.load_cases if c.name == case_name)
        for i in side.changed:
            a = local_plank.get(i)
            if a is None:
                continue
            plank = design.planks[i]
            moment = np.zeros(3)
            for load in case.loads:
                if load.plank == plank.id and load.point is not None and not load.spread:
                    moment += _cross(np.asarray(load.point) - plank.center_array, load.force)
            plank_rows.append((column, weight, a, -design.plank_mass(plank) * GRAVITY, *moment))
    if joint_rows:
        table = np.array(joint_rows)
        column, weight = table[:, 0].astype(int), table[:, 1:2]
        row, a, b = (table[:, k].astype(int) for k in (2, 3, 4))
        point, centre_a, centre_b = table[:, 5:8], table[:, 8:11], table[:, 11:14]
        r_a, r_b = point - centre_a, point - centre_b
        force = wrench[row, :3]
        deviation = -(np.cross(q[a, 3:], r_a) - np.cross(q[b, 3:], r_b)) * weight
        _add(residual, n + 6 * row, column, deviation)
        _add(residual, 6 * a + 3, column, -np.cross(r_a, force) * weight)
        _add(residual, 6 * b + 3, column, np.cross(r_b, force) * weight)
        np.add.at(lengths, (column, row), table[:, 14] * weight[:, 0])
    if contact_rows:
        table = np.array(contact_rows)
        column, weight = table[:, 0].astype(int), table[:, 1]
        row, a = table[:, 2].astype(int), table[:, 3].astype(int)
        stepped_maps = point_maps(table[:, 4:7])                         # (E, 3, 6)
        if model.contact_frames is not None:                             # wall contacts
            stepped_maps = model.contact_frames[row] @ stepped_maps
        w = np.einsum("ebd,ed->eb", stepped_maps, q[a])
        force = np.einsum("eba,eb->ea", stepped_maps, law.forces(w, row))
        _add(residual, 6 * a, column, force * weight[:, None])
        np.add.at(maps, (column, row), stepped_maps * weight[:, None, None])
    if rest_rows:           # a resting corner: its force on both planks, against each other
        table = np.array(rest_rows)
        column, weight = table[:, 0].astype(int), table[:, 1]
        row, a, b = (table[:, k].astype(int) for k in (2, 3, 4))
        frames = table[:, 11:20].reshape(-1, 3, 3)
        maps_a = frames @ point_maps(table[:, 5:8])
        maps_b = frames @ point_maps(table[:, 8:11])
        w = np.einsum("ebd,ed->eb", maps_a, q[a]) - np.einsum("ebd,ed->eb", maps_b, q[b])
        forces = law.forces(w, row)
        _add(residual, 6 * a, column, np.einsum("eba,eb->ea", maps_a, forces) * weight[:, None])
        _add(residual, 6 * b, column, -np.einsum("eba,eb->ea", maps_b, forces)
             * weight[:, None])
        np.add.at(maps, (column, row), maps_a * weight[:, None, None])
        np.add.at(rest_maps, (column, row), maps_b * weight[:, None, None])
    if plank_rows:
        table = np.array(plank_rows)
        column, weight = table[:, 0].astype(int), table[:, 1]
        a = table[:, 2].astype(int)
        np.add.at(residual, (6 * a + 2, column), table[:, 3] * weight)
        _add(residual, 6 * a + 3, column, table[:, 4:7] * weight[:, None])
    return AssemblyDifferences(residual, maps, lengths, rest_maps=rest_maps)


def _add(matrix: np.ndarray, first_row: np.ndarray, column: np.ndarray,
         values: np.ndarray) -> None:
    """matrix[first_row + i, column] += values[:, i] for each entry (repeats add up)."""
    width = values.shape[1]
    rows = first_row[:, None] + np.arange(width)[None, :]
    np.add.at(matrix, (rows, np.broadcast_to(column[:, None], rows.shape)), values)


def _cross(u, v) -> np.ndarray:
    """u x v of two 3-vectors (np.cross costs ~50 times more on single vectors)."""
    return np.array([u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                     u[0] * v[1] - u[1] * v[0]])
