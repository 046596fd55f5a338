"""A sensitivity's stepped designs read only where the design's own planks sag and
stress most (``plank_results_where`` on the design, ``plank_results_at`` on each stepped
design): the same numbers as reading every point (``bending.plank_results_of``) wherever
every plank's largest lies among those points, as it does for a small enough step, at a
fraction of the cost.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from furncheck import tolerances as tol
from furncheck.statics.bending import (
    PlankPart,
    PlankStatics,
    _interior,
    _largest_stress,
    _profile,
    _stacked,
    _stress_along,
    _transverse,
)
from furncheck.statics.sag import chosen_measure, deviation_size, plank_sags, reference_lines


class PlankWhere(NamedTuple):
    """Where a design's planks' largest sag and stress may lie in a stepped design
    (``plank_results_where``): the sample points whose value is within NEAR_LARGEST of the
    plank's largest, or NEAR_DESIGN of the design's largest where that is more (a plank
    that does not bend keeps all its points), as flat lists.  For the sag, per point its
    local plank, measure (0 between the plank's outermost supports, 1 beyond the low one, 2
    beyond the high one) and sample (an index of ``_profile``'s points: a node, or
    nN + j nE + e for the j-th interior point of element e), for every measure the plank
    has; for the stress, per point its plank, element and column (of
    ``_stress_along``'s).  A symmetric shelf's two halves, or an element's end and the
    next one's start at one node, tie: both are kept, and a stepped design's largest is
    the larger of them, as reading every point would find."""

    sag_plank: np.ndarray
    sag_measure: np.ndarray
    sag_sample: np.ndarray
    stress_plank: np.ndarray
    stress_element: np.ndarray
    stress_column: np.ndarray


def plank_results_where(part: PlankPart, q: np.ndarray) -> tuple[PlankStatics, PlankWhere]:
    """``plank_results_of([part], [q])[0]`` and where its largest sag and stress lie
    (``PlankWhere``)."""
    stack = _stacked([part], [q])
    model, layout, displacement, line_loads = stack.model, stack.layout, stack.displacement, \
        stack.line_loads
    w, slope = _transverse(displacement, layout.node_frame)
    along = _stress_along(model, layout, displacement, w, slope, line_loads)
    stress = _largest_stress(model, along)
    plank = model.beams.plank
    band = np.maximum(tol.NEAR_LARGEST * stress, tol.NEAR_DESIGN * stress.max(initial=0.0))
    element, column = np.nonzero(along >= (stress - band)[plank][:, None])
    s, deflection, sample_plank = _profile(model, layout, w, slope, line_loads)
    sag, span, measure, sample = plank_sags(model, s, deflection, sample_plank, w, slope,
                                      stack.low, stack.high, where=True)
    return PlankStatics(sag, span, stress), PlankWhere(
        sample_plank[sample], measure, sample, plank[element], element, column)


def plank_results_at(prepared: list[PlankPart], displacements: list[np.ndarray],
                     where: PlankWhere) -> list[PlankStatics]:
    """Each part's planks read at the sample points ``where`` alone (``plank_results_where``
    of a part of a model with the same nodes, elements and supports: a stepped design of
    a sensitivity): each plank's sag the largest of its measure's points, the measure
    chosen as ``plank_sags`` chooses it, its span that measure's, its stress the largest of its
    points, each point computed as ``plank_results_of`` computes it (entry by entry: the
    same numbers).  Where every plank's largest lies among those points, as it does for a
    small enough step, these are ``plank_results_of``'s numbers, at a fraction of its
    cost."""
    count = len(prepared)
    n_planks = len(prepared[0].low)
    n_nodes, n_elements = len(prepared[0].layout.node_frame), len(prepared[0].line_loads)
    parts = np.arange(count)
    sample, measure = where.sag_sample, where.sag_measure
    inside = sample >= n_nodes
    j, e = np.divmod(sample[inside] - n_nodes, n_elements)
    kept = np.unique(np.concatenate([where.stress_element, e]))      # the elements read
    stack = _stacked(prepared, displacements, kept)
    model, layout, line_loads, displacement, low, high = stack.model, stack.layout, \
        stack.line_loads, stack.displacement, stack.low, stack.high
    beams = model.beams
    w, slope = _transverse(displacement, layout.node_frame)

    def rows(local: np.ndarray) -> np.ndarray:
        """Each part's rows of the gathered elements for local elements ``local``."""
        at = np.searchsorted(kept, local)
        return (at[None, :] + len(kept) * parts[:, None]).ravel()

    def per_part(values: np.ndarray, size: int) -> np.ndarray:
        return (values[None, :] + size * parts[:, None]).ravel()

    # the stress: the largest at each plank's points
    columns = np.tile(where.stress_column, count)
    along = _stress_along(model, layout, displacement, w, slope, line_loads,
                          rows(where.stress_element), columns)
    stress = np.zeros(count * n_planks)
    np.maximum.at(stress, per_part(where.stress_plank, n_planks), along)
    # the sag: each point's deviation from the line of its measure
    plank = per_part(where.sag_plank, n_planks)
    measure = np.tile(measure, count)
    at_node = np.tile(~inside, count)
    point_s = np.zeros(len(plank))
    deflection = np.zeros((2, len(plank)))
    nodes = per_part(sample[~inside], n_nodes)
    point_s[at_node] = beams.node_s[nodes]
    deflection[:, at_node] = w[:, nodes]
    if inside.any():
        xi = np.linspace(0.0, 1.0, tol.SAG_SAMPLES + 2)[1:-1][np.tile(j, count)]
        chosen = rows(e)
        interior = _interior(model, layout, w, slope, line_loads, xi[:, None], chosen)
        deflection[:, ~at_node] = interior[:, :, 0]
        point_s[~at_node] = beams.node_s[beams.nodes[chosen, 0]] + xi * beams.length[chosen]
    low_p, high_p = low[plank], high[plank]
    sa, sb = beams.node_s[low_p], beams.node_s[high_p]
    line, tangent_low, tangent_high = reference_lines(
        point_s, sa, sb, np.where(measure == 0, sb - sa, 1.0), w[:, low_p], w[:, high_p],
        slope[:, low_p], slope[:, high_p])
    reference = np.where(measure == 0, line, np.where(measure == 1, tangent_low, tangent_high))
    distance = deviation_size(deflection, reference)
    deviation = np.full((count * n_planks, 3), -1.0)
    np.maximum.at(deviation, (plank, measure), distance)
    sa, sb = beams.node_s[low], beams.node_s[high]
    half = beams.plank_half
    spans = np.column_stack([sb - sa, 2.0 * (sa + half), 2.0 * (half - sb)])
    sag, span, _ = chosen_measure(deviation, spans)
    return [PlankStatics(sag[k * n_planks:(k + 1) * n_planks],
                         span[k * n_planks:(k + 1) * n_planks],
                         stress[k * n_planks:(k + 1) * n_planks]) for k in range(count)]
