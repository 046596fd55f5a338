"""Static equilibrium of the planks: the paper's mixed formulation (section 5.1), for rigid
planks (the paper's) and elastic ones (contract section 3a).

Unknowns are a small displacement per node, q_i = (u_i, theta_i) (m, rad, about the node's
point: a rigid plank's centre, or a point on an elastic plank's beam axis), and the wrench
of every nail joint, h_j = (h^t, h^r) (N, N m, world frame, what the joint's first plank
exerts on its second, moment about the joint point).  With G the linearized joint
deviation map (d = G q) and E the joint compliances (W = E^-1: penalty constants for rigid
planks, the nail row's springs for elastic ones), stationarity of the potential energy
(paper eq. 3) is the sparse system

    [ K_b + K_c  G^T ] [q]   [f]
    [ G          -E  ] [h] = [0]

where f holds self-weight and loads (force, moment about each node), K_b the elastic
planks' beam stiffness (none for rigid planks) and K_c the ground contact springs.
Contacts are unilateral penalty springs with friction anchors (section 5.2): a contact is
*stick* (three springs to its anchor), *slip* (normal spring; friction mu N along a fixed
direction, i.e. the anchor relocated to the cone's edge) or *lifted* (no force).  An
active-set loop switches contacts until every force is admissible.  When that loop cannot
finish, small linear programs decide whether any admissible equilibrium exists at all, so
the verdicts 'lift-off' and 'sliding' mean exactly what contract section 3 says.

The package, by job:

    model        StaticsModel, CaseStatics; build_model (joint map G, contact maps) and
                 external_forces (self-weight and loads)
    condense     static condensation onto the grounded planks (through the planks with a
                 dense Cholesky factor up to 60 planks, else the sparse LU of the mixed
                 system)
    anchored     the contact springs on the condensed system: a contact state's matrix
                 factored once (anchored_system), the full mixed matrix (system_matrix)
                 and its solve (solve_system)
    lapack       scipy's LAPACK routines without importing scipy.linalg (cholesky)
    contacts     solve_case: the contact active set and its phases
    friction     the friction phase's energy (Tresca problems) and its line search
    outcomes     what a case reports once decided: stable, sliding, lift-off, the
                 programs' forces
    feasibility  linear programs: does any admissible equilibrium exist?
    beams        the elastic model's elements: Timoshenko beam, consistent loads, a nail
                 row's spring (pure functions)
    elastic      the elastic model (contract section 3a): the StaticsModel of beams with
                 nodes where joints, contacts and loads act, stiff contacts, loads along
                 the beams
    bending      a solved elastic case's planks: sag and stress (plank_results);
                 bending_points reads a stepped design's planks where the design's sag
                 and stress peak; carrying, what carries each plank (where its sag is
                 measured from)
    plates       a plank held along lines checked as a plate too: its loads, its
                 readings (kept by plate and loads) merged with the beams' (with_plates);
                 plate_supports, which planks and what holds them; plate_mesh, the
                 plate itself (grid, elements, banded factor, solves)
    starts       where the contact iterations of a search's edits start (LineStarts)
    derivatives  eq. 6's right-hand sides for both models (a plate's rates too)

``solve_load_case`` (``solve_load_cases`` for all of a design's cases) is what the layers
above call: the loads of a case, its equilibrium
and, in the elastic model, its planks' sag and stress, whichever model built the
``StaticsModel`` (``build_model`` chooses, from ``design.model``).
"""

from dataclasses import replace

from furncheck.design.model import LoadCase
from furncheck.statics.anchored import anchor_springs, solve_system, system_matrix
from furncheck.statics.contacts import LIFT, STICK, solve_case
from furncheck.statics.model import CaseStatics, StaticsModel, build_model, external_forces
from furncheck.statics.starts import LineStarts


def solve_load_case(model: StaticsModel, case: LoadCase,
                    near: CaseStatics | None = None) -> CaseStatics:
    """``solve_case`` of the case's loads, with the planks' sag and stress in the elastic
    model (from the displacements of the forces it reports).  ``near``: the same case
    solved on a design of which this one is a small edit, where it starts (``solve_case``)."""
    statics = solve_case(model, external_forces(model, case), near=near)
    if model.beams is None or statics.displacements is None:
        return statics
    from furncheck.statics.bending import plank_results
    from furncheck.statics.plates import with_plates

    planks = plank_results(model, case, statics.displacements, statics.holding)
    return replace(statics, planks=with_plates(model, [case], [planks])[0])


def solve_load_cases(model: StaticsModel, cases: list[LoadCase]) -> list[CaseStatics]:
    """``solve_load_case`` of each case: each case's contact iterations start from the
    contacts that held in the case before (``solve_case``'s ``start``: the same
    equilibrium, sooner; a case that is not stable passes nothing on), and the elastic
    model's sag and stress of all of them are read in one pass over their planks stacked
    (``bending.plank_results_of``: the same numbers as one case at a time, for a
    fraction of the calls)."""
    statics, start = [], None
    for case in cases:     # each case starts from the contacts that held in the one before
        statics.append(solve_case(model, external_forces(model, case), start))
        if statics[-1].holding is not None:
            start = statics[-1].holding
    solved = [k for k, one in enumerate(statics) if one.displacements is not None]
    if model.beams is None or not solved:
        return statics
    from furncheck.statics.bending import plank_part, plank_results_of
    from furncheck.statics.plates import with_plates

    parts = [plank_part(model, cases[k], statics[k].holding) for k in solved]
    results = plank_results_of(parts, [statics[k].displacements for k in solved])
    results = with_plates(model, [cases[k] for k in solved], results)
    for k, planks in zip(solved, results):
        statics[k] = replace(statics[k], planks=planks)
    return statics


__all__ = ["LIFT", "STICK", "CaseStatics", "StaticsModel", "anchor_springs", "build_model",
           "LineStarts", "external_forces", "solve_case", "solve_load_case",
           "solve_load_cases",
           "solve_system", "system_matrix"]
