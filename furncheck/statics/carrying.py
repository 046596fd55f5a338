"""What carries each plank of an elastic model, and so where its sag is measured from
(contract section 3a: the line through its two outermost supports).

A plank is carried by the jointed planks that still reach the ground when it is taken
away (``carrying_neighbours``: a shelf's sides, not a lip hanging under it; one
articulation-point search, ``carriers``), by its holding ground contacts and by the
resting joints it lies on; a plank lying flat on the floor or against a wall is held along
its face and given no sag (``lying_on_floor``).  ``outermost_supports`` gives each plank's
supports nearest its two ends.  What depends on the model alone is kept in
``model.plank_cache`` (and shared by the models built on it).
"""

from __future__ import annotations

import bisect

import numpy as np

from furncheck.statics.model import StaticsModel


def plank_supports(model: StaticsModel, grounded: frozenset[int] | None = None) -> tuple:
    """(the nodes where a joint carries its plank (``carrying_neighbours``), whether each
    plank's sag is read (not lying on the floor, ``lying_on_floor``), where resting joints
    carry either plank (``resting_supports``)): which planks are
    jointed and which contacts stand decide them, so they are kept per model and shared
    by the models built on it (``templated.TOPOLOGY_CACHE``).  ``grounded``: the local
    planks whose contacts hold in a case, where that is fewer than all that have
    contacts (a bench that see-saws, one end leg lifted off the floor: that leg hangs
    from the seat and carries nothing); None for all."""
    cached = model.plank_cache.get("supports")
    if cached is None:
        measured = np.ones(len(model.planks), dtype=bool)
        measured[sorted(lying_on_floor(model))] = False
        cached = (_joint_supports(model, carrying_neighbours(model)), measured,
                  resting_supports(model))
        model.plank_cache["supports"] = cached
    if grounded is None or grounded == _grounded(model):
        return cached
    lifted = model.plank_cache.setdefault("supports_lifted", {})
    if grounded not in lifted:
        lifted[grounded] = (_joint_supports(model, _carried_by(model, grounded)),
                            *cached[1:])
    return lifted[grounded]


def _grounded(model: StaticsModel, holding: np.ndarray | None = None) -> frozenset[int]:
    """The local planks with contacts (``holding`` (nK,) bool: those of the contacts that
    hold; None: every contact), what ``carriers`` takes as grounded."""
    planks = model.contact_plank if holding is None else model.contact_plank[holding]
    return frozenset(int(k) for k in planks)


def _joint_supports(model: StaticsModel, carried_by: list[set[int]]) -> np.ndarray:
    """The nodes where a joint carries its plank, given each plank's carriers."""
    joint_supports = []
    for nodes in model.joint_nodes:
        a, b = (int(model.node_plank[node]) for node in nodes)
        for node, plank, other in ((nodes[0], a, b), (nodes[1], b, a)):
            if other in carried_by[plank]:
                joint_supports.append(int(node))
    return np.array(joint_supports, dtype=int)


END_ON_COSINE = 0.7
"""A resting corner's plank bears on the other plank end on (a leg under a loose top) when
its beam axis lies within 45 degrees of that plank's face normal."""


def resting_supports(model: StaticsModel) -> tuple[np.ndarray, np.ndarray]:
    """Per contact (nK,) bool: (a resting corner's own plank is carried there, the plank
    it rests against is carried there); False for the ground's and walls' contacts.

    Of the two planks of a resting joint, the one lying on top is carried (the other
    pushes it up).  The one below is carried too where its end bears on the one above
    (its beam axis along that plank's normal, END_ON_COSINE) and the one above reaches
    the ground without it (the rule of nailed joints, ``carrying_neighbours``, with the
    resting joints as edges and only the ground and walls as ground): a top lying loose
    on four legs holds each leg's end by friction, as a nailed top does, so a leg's sag is
    measured from the line through its foot and the top (a leg bowed by a squeeze reads
    1.01 mm between them, not 0.733 mm as a cantilever from its foot).  A board lying on
    a bracket's arm or a pin pushes it down along its bending, and holds nothing: the arm
    stays a cantilever from its nail."""
    count = len(model.contacts)
    corner_carried, face_carried = np.zeros(count, dtype=bool), np.zeros(count, dtype=bool)
    rows = model.rest_rows
    if not len(rows):
        return corner_carried, face_carried
    above = model.rest_face_above[rows]
    face_carried[rows] = above
    corner_carried[rows] = ~above
    corner_plank = model.contact_plank[rows]
    face_plank = model.node_plank[model.rest_node[rows]]
    frames = model.beams.plank_frames
    axes = frames[corner_plank][:, :, 0]                                # corner's beam
    normals = frames[face_plank][:, :, 2]                               # face's normal
    end_on = above & (np.abs(np.einsum("ij,ij->i", axes, normals)) >= END_ON_COSINE)
    if not end_on.any():
        return corner_carried, face_carried
    on_ground = np.ones(count, dtype=bool)
    on_ground[rows] = False
    pairs = model.node_plank[model.joint_nodes].reshape(-1, 2).tolist() \
        + np.column_stack([corner_plank, face_plank]).tolist()
    carried_by = carriers(len(model.planks), pairs,
                          {int(k) for k in model.contact_plank[on_ground]})
    corner_carried[rows[end_on]] = [int(b) in carried_by[int(a)] for a, b in
                                    zip(corner_plank[end_on], face_plank[end_on])]
    return corner_carried, face_carried


def outermost_supports(model: StaticsModel, holding: np.ndarray | None
                       ) -> tuple[np.ndarray, np.ndarray]:
    """(low, high) per local plank (nP,) int: its carrying support nearest its -e1 end and
    nearest its +e1 end (nodes where a joint carries it, ``carrying_neighbours``, a
    holding contact stands, or a holding resting joint carries it, ``resting_supports``),
    -1 for a plank with none or lying on the floor.  A joint carries a plank through
    planks that reach the ground by contacts that hold in the case (``holding``, None:
    all): a leg lifted off the floor carries nothing."""
    beams = model.beams
    carrying = np.ones(len(model.contacts), dtype=bool) if holding is None \
        else np.asarray(holding, dtype=bool)
    joint_supports, measured, (corner_carried, face_carried) = plank_supports(
        model, _grounded(model, carrying))
    on_ground = carrying.copy()
    on_ground[model.rest_rows] = False
    nodes = [model.contact_node[on_ground]]
    if len(model.rest_rows):            # a resting joint: either plank, where carried
        nodes += [model.contact_node[carrying & corner_carried],
                  model.rest_node[carrying & face_carried]]
    supports = np.concatenate([joint_supports, *nodes])
    plank = model.node_plank[supports]
    order = np.lexsort((beams.node_s[supports], plank))      # by plank, then along it
    supports, plank = supports[order], plank[order]
    first = np.flatnonzero(np.diff(plank, prepend=-1) != 0)            # of each plank's run
    last = np.flatnonzero(np.diff(plank, append=len(model.planks)) != 0)
    low, high = np.full(len(model.planks), -1), np.full(len(model.planks), -1)
    low[plank[first]], high[plank[last]] = supports[first], supports[last]
    low[~measured] = high[~measured] = -1
    return low, high


def carrying_neighbours(model: StaticsModel) -> list[set[int]]:
    """Per local plank P, the planks jointed to it that carry it: those that still reach a
    plank on the ground when P is taken away (a shelf's sides carry it, and it braces
    them; a lip nailed under a shelf's tip, or a shelf hanging on a post, reaches the
    ground only through the plank it hangs on and carries nothing).  Kept per model."""
    cached = model.plank_cache.get("carrying")
    if cached is not None:
        return cached
    carrying = _carried_by(model, _grounded(model))
    model.plank_cache["carrying"] = carrying
    return carrying


def _carried_by(model: StaticsModel, grounded: frozenset[int]) -> list[set[int]]:
    """``carriers`` of the model's planks over its joints, ``grounded`` the planks on the
    ground."""
    pairs = model.node_plank[model.joint_nodes].reshape(-1, 2).tolist()
    return carriers(len(model.planks), pairs, set(grounded))


def carriers(n: int, pairs: list, grounded: set[int]) -> list[set[int]]:
    """Per plank P of n, its neighbours (``pairs``: jointed planks (a, b)) that still reach
    a plank of ``grounded`` other than P when P is taken away.

    That is reaching the ground node, joined to every grounded plank, in the graph without
    P, which one depth-first search from the ground node answers for every P at once
    (the articulation-point search, linear in planks and joints): a neighbour found before
    P is its ancestor and reaches the ground above P; one found after P lies in the subtree
    of a child c of P, which is cut off when nothing in it reaches above P (low[c] >=
    disc[P]).  A plank whose part stands on nothing has no carrier."""
    neighbours: list[set[int]] = [set() for _ in range(n)]
    for a, b in pairs:
        neighbours[a].add(b)
        neighbours[b].add(a)
    root = n
    adjacency = [sorted(others) for others in neighbours] + [sorted(grounded)]
    for k in grounded:
        adjacency[k].append(root)
    disc, low = [-1] * (n + 1), [0] * (n + 1)
    parent, size = [-1] * (n + 1), [1] * (n + 1)
    children: list[list[int]] = [[] for _ in range(n + 1)]
    disc[root], time = 0, 1
    stack = [(root, iter(adjacency[root]))]
    while stack:
        v, rest = stack[-1]
        for w in rest:
            if disc[w] < 0:
                parent[w] = v
                children[v].append(w)
                disc[w] = low[w] = time
                time += 1
                stack.append((w, iter(adjacency[w])))
                break
            low[v] = min(low[v], disc[w])
        else:
            stack.pop()
            if stack:
                up = parent[v]
                low[up] = min(low[up], low[v])
                size[up] += size[v]
    carrying: list[set[int]] = []
    for removed in range(n):
        found: set[int] = set()
        if disc[removed] >= 0:
            below = children[removed]                   # in order of discovery
            starts = [disc[c] for c in below]
            for other in neighbours[removed]:
                if disc[other] < disc[removed]:
                    found.add(other)
                    continue
                child = below[bisect.bisect_right(starts, disc[other]) - 1]
                if low[child] < disc[removed]:
                    found.add(other)
        carrying.append(found)
    return carrying


def lying_on_floor(model: StaticsModel) -> set[int]:
    """Local planks lying on the floor (or flat against a wall) on a broad face (all four
    corners of that face are contacts with that support): it holds them along their whole
    face, not at the corners the contacts stand for, so they are given no sag."""
    cached = model.plank_cache.get("lying")
    if cached is not None:
        return cached
    corners: dict[tuple, set[int]] = {}
    for row, c in enumerate(model.contacts):
        contact = model.geometry.contacts[c]
        if contact.on is not None:      # a resting joint's corners are not the plank's
            continue
        corners.setdefault((int(model.contact_plank[row]), contact.wall),
                           set()).add(contact.corner)
    lying = {k for (k, *_), found in corners.items()
             if {0, 1, 2, 3} <= found or {4, 5, 6, 7} <= found}
    model.plank_cache["lying"] = lying
    return lying
