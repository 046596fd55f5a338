"""The sag of a solved elastic case's planks (contract section 3a): per plank, the largest
deflection of its own bending from the straight line through its two outermost supports,
or, beyond them, from the tangent at the support (``plank_sags``), the measure nearest its
limit chosen (``chosen_measure``), and whether that deflection points sideways
(``_sideways``: a rail bent by a push is said to bow, not to sag).  ``bending`` reads the
deflected axes it measures (``bending._profile``) and ``bending_points`` the same measures
at a few points.
"""

from __future__ import annotations

import numpy as np

from furncheck import tolerances as tol
from furncheck.statics.model import StaticsModel


def plank_sags(model: StaticsModel, s: np.ndarray, deflection: np.ndarray,
         sample_plank: np.ndarray, w: np.ndarray, slope: np.ndarray, low: np.ndarray,
         high: np.ndarray, where: bool = False, node_frame: np.ndarray | None = None
         ) -> tuple:
    """(sag, span) (nP,) m of every plank (contract 3a) from its deflected axis (``s``,
    ``deflection``, ``sample_plank``: ``_profile``) and its outermost supports ``low``,
    ``high`` (``carrying.outermost_supports``; ``w``, ``slope``: ``_transverse``): between them, the
    largest deviation from the straight line through them (span: their distance); beyond
    them, each overhang's largest deviation from the tangent at its support (span: twice
    the overhang); the one nearest its limit (the largest sag / span) is the plank's.  Held
    at one point, only the overhangs count; with no support, (0, 0).  With ``where``, also
    the points near each measure's largest (``bending_points.PlankWhere``), every measure
    the plank has (0, 1, 2 as above), as flat lists: (sag, span, measures, points).  With
    ``node_frame`` (the nodes' beam axes, ``_Layout``), also whether each plank's largest
    deviation points sideways (``_sideways``): (sag, span, overhang, sideways)."""
    beams = model.beams
    half = beams.plank_half
    supported = low >= 0
    sa, sb = beams.node_s[low], beams.node_s[high]          # read only where supported
    chord = supported & (sb - sa > tol.NODE_MERGE + tol.NODE_MERGE_ROUNDOFF)
    reach = 1e-9 + 1e-9 * half                  # a point at a support counts as between

    # per sample point, its plank's supports: which part of the plank it lies in and the
    # line (chord or tangent) its deviation is measured from
    def at_points(values: np.ndarray) -> np.ndarray:
        """(..., nX) each sample point's value of a per-plank array (..., nP)."""
        return np.take(values, sample_plank, axis=-1)

    s_low, s_high = at_points(sa), at_points(sb)
    below, above = s_low - at_points(reach), s_high + at_points(reach)
    between = at_points(chord) & (s >= below) & (s <= above)
    beyond_low = at_points(supported) & (s < below)
    beyond_high = at_points(supported) & (s > above)
    references = reference_lines(s, s_low, s_high, at_points(np.where(chord, sb - sa, 1.0)),
                                  at_points(np.take(w, low, axis=1)),
                                  at_points(np.take(w, high, axis=1)),
                                  at_points(np.take(slope, low, axis=1)),
                                  at_points(np.take(slope, high, axis=1)))
    # (3, nX) each point's distance from the line of each measure, -1 where that measure
    # does not read it: between the supports, beyond the low one, beyond the high one
    distances = np.array([np.where(points, deviation_size(deflection, reference), -1.0)
                          for points, reference in zip((between, beyond_low, beyond_high),
                                                       references)])
    deviation = np.full((len(half), 3), -1.0)                           # (nP, 3) largest
    for k in range(3):
        np.maximum.at(deviation[:, k], sample_plank, distances[k])
    spans = np.column_stack([sb - sa, 2.0 * (sa + half), 2.0 * (half - sb)])
    sag, span, overhang = chosen_measure(deviation, spans)
    if node_frame is not None:
        return sag, span, overhang, _sideways(model, node_frame, deflection, references,
                                              distances, sample_plank, deviation, spans)
    if not where:
        return sag, span, overhang
    band = np.maximum(tol.NEAR_LARGEST * deviation,
                      tol.NEAR_DESIGN * deviation.max(initial=0.0))
    measures, points = np.nonzero((distances >= 0.0)
                                  & (distances >= (deviation - band)[sample_plank].T))
    return sag, span, measures, points


def reference_lines(s, s_low, s_high, chord, w_low, w_high, slope_low, slope_high) -> tuple:
    """(line, tangent_low, tangent_high), each (2, n): at the points along the axis ``s``
    (n,), the straight line through the outermost supports (at ``s_low`` and ``s_high``,
    their distance ``chord``, deflections ``w_low`` and ``w_high``) and the tangents at
    either support (slopes ``slope_low``, ``slope_high``), from which the sag of each
    measure is measured (``plank_sags``, ``bending_points.plank_results_at``: one formula for
    both)."""
    line = w_low + ((s - s_low) / chord) * (w_high - w_low)
    return (line, w_low + (s - s_low) * slope_low, w_high + (s - s_high) * slope_high)


def deviation_size(deflection: np.ndarray, reference: np.ndarray) -> np.ndarray:
    """(n,) |deflection - reference| of (2, n) arrays, by rows (np.linalg.norm's own sum,
    ten times faster)."""
    offset = deflection - reference
    return np.sqrt(offset[0] * offset[0] + offset[1] * offset[1])


def _sideways(model, node_frame: np.ndarray, deflection: np.ndarray, references: tuple,
              distances: np.ndarray, sample_plank: np.ndarray, deviation: np.ndarray,
              spans: np.ndarray):
    """A function of a plank (its index here) telling whether its sag, the largest
    deviation of its chosen measure (``chosen_measure``), points more across than up or
    down (its world vertical part below cos 45 degrees of it): a rail or a stretcher bent
    by a sideways push, which a woodworker does not call a sag.  Read only for a plank
    the messages name (a sagging one: reading every plank's cost 1 to 4 % of a check).
    (The sample points are ``_profile``'s: the nodes, then each element's interior
    points, sample by sample; an interior point's axes are its element's first node's.)"""
    beams = model.beams

    def sideways(plank: int) -> bool:
        _, pick = _measure_picked(deviation[plank:plank + 1], spans[plank:plank + 1])
        measure = int(pick[0])
        points = np.flatnonzero(sample_plank == plank)
        if not points.size or deviation[plank, measure] < 0.0:
            return False
        point = int(points[np.argmax(distances[measure, points])])
        offset = deflection[:, point] - references[measure][:, point]
        node = point if point < len(node_frame) else \
            int(beams.nodes[(point - len(node_frame)) % len(beams.length), 0])
        vertical = float(offset @ node_frame[node, 2, 1:])
        return abs(vertical) < tol.UPRIGHT_SINE * float(np.hypot(*offset))

    return sideways


def _measure_picked(deviation: np.ndarray, spans: np.ndarray) -> tuple[np.ndarray, ...]:
    """(present, pick): which measures each plank has, and the one nearest its limit
    (``chosen_measure``)."""
    present = deviation >= 0.0
    ratio = np.where(present, 0.0, -np.inf)
    positive = present & (spans > 0.0) & (deviation > tol.SAG_ROUNDOFF)
    ratio[positive] = deviation[positive] / spans[positive]
    return present, np.argmax(ratio, axis=1)


def chosen_measure(deviation: np.ndarray, spans: np.ndarray) -> tuple[np.ndarray, ...]:
    """(sag, span, overhang) (nP,) of each plank's measure nearest its limit, from the
    largest deviation and the span of each measure (nP, 3; deviation -1 for a measure the
    plank does not have): the largest sag / span (0 for no span or a sag of round-off,
    SAG_ROUNDOFF; the first one on a tie), among those it has; (0, 0) for none; overhang
    where the measure is one beyond a support."""
    present, pick = _measure_picked(deviation, spans)
    rows = np.arange(len(deviation))
    chosen = present[rows, pick]
    return (np.where(chosen, deviation[rows, pick], 0.0),
            np.where(chosen, spans[rows, pick], 0.0), chosen & (pick > 0))
