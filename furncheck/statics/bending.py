"""A solved elastic case's planks: their sag and bending stress (contract section 3a).

``plank_results`` reads, per plank, the largest deflection of its own bending (between
nodes too, ``_profile``) from the line through its outermost carrying supports or, beyond
them, from the tangent at the support (``sag.plank_sags``), and the largest bending plus axial
stress along it, at its elements' ends, points inside and the moments' peaks
(``_stress_along``).  A sensitivity's stepped designs are read only at the points where
the design's own largest sag and stress lie (``bending_points``).

Every step works on all nodes, elements and sample points of the model at once; the
per-plank results are reductions over them (``np.maximum.at`` by plank).  What depends on
the model alone (the beam axes at each node, the sections; the joints that carry a plank,
``carrying``) is read once per model (``_layout``, kept in ``model.plank_cache``).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import LoadCase
from furncheck.statics.beams import (
    SHEAR_FACTOR,
    element_end_moment,
    element_interior,
    section_properties,
)
from furncheck.statics.carrying import outermost_supports
from furncheck.statics.elements import (
    Beams,
    case_line_loads,
    element_end_forces,
    element_loads_local,
)
from furncheck.statics.model import StaticsModel
from furncheck.statics.sag import plank_sags


@dataclass(frozen=True, eq=False)    # holds arrays: no == by value
class PlankStatics:
    """Per local plank of an elastic model, for one load case (SI).

    sag    : (nP,) m, the largest deflection of its own bending (contract section 3a)
    span   : (nP,) m, between its outermost supports (twice the overhang of a cantilever);
             0 when it has no support to measure from
    stress : (nP,) Pa, the largest |M_2| / (b t^2 / 6) + |M_3| / (t b^2 / 6) + |N| / (b t)
    overhang : (nP,) bool, whether the sag is an overhang's (its span twice the overhang),
             for the messages; None where it was not read (the sensitivity's steps)
    sideways : plank index -> bool, whether the sag's deflection points more across than
             up or down (a rail bent by a push, not sagging under weight), for the
             messages; None where it cannot be read
    """

    sag: np.ndarray
    span: np.ndarray
    stress: np.ndarray
    overhang: np.ndarray | None = None
    sideways: Callable[[int], bool] | None = None


@dataclass(frozen=True, eq=False)    # holds arrays: no == by value
class _Layout:
    """The load-independent facts ``plank_results`` reads, once per model.

    node_frame : (nN, 3, 3) the beam axes e1, e2, e3 (columns, world) of each node's plank
    inertia    : (nE, 2) m^4, I_3 and I_2 of each element: bending along e2 and along e3
    area       : (nE,) m^2, b t
    bending, in_plane : (nE,) m^3, the section moduli b t^2 / 6 and t b^2 / 6
    """

    node_frame: np.ndarray
    inertia: np.ndarray
    area: np.ndarray
    bending: np.ndarray
    in_plane: np.ndarray


def plank_results(model: StaticsModel, case: LoadCase, q: np.ndarray,
                  holding: np.ndarray | None = None) -> PlankStatics:
    """Sag, span and stress of every plank for node displacements ``q`` (6 nN,) of the
    case; ``holding`` (nK,) bool: the contacts that carry (all when None)."""
    layout = _layout(model)
    displacement = q.reshape(-1, 6)
    line_loads = case_line_loads(model, case)
    w, slope = _transverse(displacement, layout.node_frame)
    stress = _stress(model, layout, displacement, w, slope, line_loads)
    s, deflection, sample_plank = _profile(model, layout, w, slope, line_loads)
    low, high = outermost_supports(model, holding)
    sag, span, overhang, sideways = plank_sags(model, s, deflection, sample_plank, w, slope, low,
                                         high, node_frame=layout.node_frame)
    return PlankStatics(sag, span, stress, overhang, sideways)


@dataclass(frozen=True, eq=False)    # holds arrays: no == by value
class _Stacked:
    """Several models' elements, nodes and planks numbered one after another, with what
    the reading functions below take of a model (``plank_results_many``)."""

    beams: Beams
    planks: range
    node_plank: np.ndarray

    @property
    def n_nodes(self) -> int:
        return len(self.node_plank)


class PlankPart(NamedTuple):
    """What ``plank_results_of`` reads of one (model, case) besides its displacements: the
    model (or a ``_Stacked`` cut of some of its planks), its ``_Layout``, line loads
    (nE, 3) N/m, outermost supports (low, high), and for a cut the model's nodes it keeps
    (None: all of them)."""

    model: object
    layout: _Layout
    line_loads: np.ndarray
    low: np.ndarray
    high: np.ndarray
    nodes: np.ndarray | None = None


def plank_part(model: StaticsModel, case: LoadCase, holding: np.ndarray | None = None,
               planks: np.ndarray | None = None,
               supports: tuple[np.ndarray, np.ndarray] | None = None) -> PlankPart:
    """The ``PlankPart`` of a model and case: of all its planks, or cut down to the local
    ``planks`` (sorted; a cut keeps only their elements and nodes, renumbered, not the
    model).  ``supports``: the outermost supports (low, high) of all its planks, where
    they are known (a stepped design's are its template's: the same nodes, ordered alike
    along each plank, a hair apart), else found (``carrying.outermost_supports``)."""
    layout = _layout(model)
    low, high = supports if supports is not None else outermost_supports(model, holding)
    part = PlankPart(model, layout, case_line_loads(model, case), low, high)
    return part if planks is None else _only(part, planks)


def plank_results_many(runs: list[tuple[StaticsModel, LoadCase, np.ndarray]],
                       holding: np.ndarray | None = None,
                       planks: np.ndarray | None = None) -> list[PlankStatics]:
    """``plank_results`` of several (model, case, q) at once: their elements, nodes and
    planks stacked into one set (each model's numbered after the previous ones'), so that
    the array operations run once for all, not once per model (a sensitivity reads the
    planks of every stepped design).  The same numbers as one call each: every step is
    element by element, sample by sample, or a maximum per plank.  ``planks``: read only
    these local planks (sorted) of each model; the results are theirs, in that order."""
    return plank_results_of([plank_part(model, case, holding, planks)
                             for model, case, _ in runs], [q for *_, q in runs])


def plank_results_of(prepared: list[PlankPart],
                     displacements: list[np.ndarray]) -> list[PlankStatics]:
    """``plank_results_many`` of parts made beforehand (``plank_part``) at the node
    displacements (6 nN,) of each part's model."""
    stack = _stacked(prepared, displacements)
    model, layout, displacement, line_loads = stack.model, stack.layout, stack.displacement, \
        stack.line_loads
    w, slope = _transverse(displacement, layout.node_frame)
    stress = _stress(model, layout, displacement, w, slope, line_loads)
    s, deflection, sample_plank = _profile(model, layout, w, slope, line_loads)
    sag, span, overhang, sideways = plank_sags(model, s, deflection, sample_plank, w, slope,
                                         stack.low, stack.high, node_frame=layout.node_frame)
    offsets = stack.plank_offsets
    return [PlankStatics(sag[a:b], span[a:b], stress[a:b], overhang[a:b],
                         lambda k, a=a: sideways(a + k))
            for a, b in zip(offsets[:-1], offsets[1:])]


class _Stack(NamedTuple):
    """Parts stacked into one model (``_stacked``): the ``_Stacked`` model and its
    ``_Layout``, the nodes' displacements (nN, 6), line loads (nE, 3), outermost supports
    (low, high) and each part's first plank (plank_offsets, one more at the end)."""

    model: _Stacked
    layout: _Layout
    displacement: np.ndarray
    line_loads: np.ndarray
    low: np.ndarray
    high: np.ndarray
    plank_offsets: np.ndarray


_ELEMENT_FIELDS = ("length", "frames", "local_stiffness", "width", "thickness",
                   "elastic_modulus", "shear_modulus")
"""A ``Beams``' arrays of one entry per element, besides its planks and nodes."""

_SECTION_FIELDS = ("inertia", "area", "bending", "in_plane")
"""A ``_Layout``'s arrays of one entry per element."""


def _stacked(prepared: list[PlankPart], displacements: list[np.ndarray],
             elements: np.ndarray | None = None) -> _Stack:
    """The parts' elements, nodes and planks numbered one after another (each part's
    after the previous ones'), with their displacements (6 nN,) each; with ``elements``
    (local, the same in each part) only those elements of each part, all their nodes and
    planks."""
    node_offsets = np.cumsum([0] + [part.model.n_nodes for part in prepared])
    plank_offsets = np.cumsum([0] + [len(part.low) for part in prepared])
    chosen = slice(None) if elements is None else elements

    def cut(read) -> np.ndarray:
        return np.concatenate([read(part)[chosen] for part in prepared])

    def whole(read, offsets=None) -> np.ndarray:
        if offsets is None:
            return np.concatenate([read(part) for part in prepared])
        return np.concatenate([read(part) + offset for part, offset in zip(prepared, offsets)])

    beams = Beams(plank=np.concatenate([part.model.beams.plank[chosen] + offset
                                        for part, offset in zip(prepared, plank_offsets)]),
                  nodes=np.concatenate([part.model.beams.nodes[chosen] + offset
                                        for part, offset in zip(prepared, node_offsets)]),
                  node_s=whole(lambda p: p.model.beams.node_s),
                  plank_half=whole(lambda p: p.model.beams.plank_half),
                  **{name: cut(lambda p, n=name: getattr(p.model.beams, n))
                     for name in _ELEMENT_FIELDS})
    layout = _Layout(node_frame=whole(lambda p: p.layout.node_frame),
                     **{name: cut(lambda p, n=name: getattr(p.layout, n))
                        for name in _SECTION_FIELDS})
    displacement = np.concatenate([
        q.reshape(-1, 6) if part.nodes is None else q.reshape(-1, 6)[part.nodes]
        for part, q in zip(prepared, displacements)])
    model = _Stacked(beams, range(int(plank_offsets[-1])),
                     whole(lambda p: p.model.node_plank, plank_offsets))
    shift = np.repeat(node_offsets[:-1], np.diff(plank_offsets))
    low, high = (np.where(ends >= 0, ends + shift, -1)
                 for ends in (whole(lambda p: p.low), whole(lambda p: p.high)))
    return _Stack(model, layout, displacement, cut(lambda p: p.line_loads), low, high,
                  plank_offsets)


def _element_cut(beams: Beams, layout: _Layout, elements: np.ndarray, **kept) -> tuple:
    """(``Beams``, ``_Layout``) of ``elements`` alone, in that order: their per-element
    arrays taken, the rest (plank, nodes, node_s, plank_half, node_frame) from
    ``kept``."""
    beam_keys = ("plank", "nodes", "node_s", "plank_half")
    cut_beams = Beams(**{key: kept[key] for key in beam_keys},
                      **{name: getattr(beams, name)[elements] for name in _ELEMENT_FIELDS})
    cut_layout = _Layout(**{key: value for key, value in kept.items() if key not in beam_keys},
                         **{name: getattr(layout, name)[elements] for name in _SECTION_FIELDS})
    return cut_beams, cut_layout


def _only(part: PlankPart, planks: np.ndarray) -> PlankPart:
    """A part cut down to the local ``planks`` (sorted): their elements and nodes in order,
    renumbered, as a ``_Stacked`` model of their own."""
    model, layout = part.model, part.layout
    beams = model.beams
    kept = np.zeros(len(model.planks), dtype=bool)
    kept[planks] = True
    elements = np.flatnonzero(kept[beams.plank])
    nodes = np.flatnonzero(kept[model.node_plank])
    node_number = np.full(model.n_nodes, -1)
    node_number[nodes] = np.arange(len(nodes))
    plank_number = np.full(len(model.planks), -1)
    plank_number[planks] = np.arange(len(planks))
    cut, cut_layout = _element_cut(
        beams, layout, elements, plank=plank_number[beams.plank[elements]],
        nodes=node_number[beams.nodes[elements]], node_s=beams.node_s[nodes],
        plank_half=beams.plank_half[planks], node_frame=layout.node_frame[nodes])

    def supports(values: np.ndarray) -> np.ndarray:
        mine = values[planks]
        return np.where(mine >= 0, node_number[mine], -1)

    return PlankPart(_Stacked(cut, range(len(planks)), plank_number[model.node_plank[nodes]]),
                     cut_layout, part.line_loads[elements], supports(part.low),
                     supports(part.high), nodes)


def _layout(model: StaticsModel) -> _Layout:
    """The model's ``_Layout``, built on first use and kept in ``model.plank_cache``."""
    cached = model.plank_cache.get("layout")
    if cached is not None:
        return cached
    beams = model.beams
    frames = beams.plank_frames
    section = section_properties(beams.width, beams.thickness)
    layout = _Layout(node_frame=frames[model.node_plank],
                     inertia=np.column_stack([section["I3"], section["I2"]]),
                     area=section["A"],
                     bending=beams.width * beams.thickness ** 2 / 6.0,
                     in_plane=beams.thickness * beams.width ** 2 / 6.0)
    model.plank_cache["layout"] = layout
    return layout


def _stress(model: StaticsModel, layout: _Layout, displacement: np.ndarray, w: np.ndarray,
            slope: np.ndarray, line_loads: np.ndarray) -> np.ndarray:
    """(nP,) Pa: each plank's largest stress along its elements (``_stress_along``)."""
    return _largest_stress(model, _stress_along(model, layout, displacement, w, slope,
                                                line_loads))


def _largest_stress(model: StaticsModel | _Stacked, along: np.ndarray) -> np.ndarray:
    """(nP,) Pa: the largest of ``_stress_along`` (nE, m) per plank."""
    stress = np.zeros(len(model.planks))
    np.maximum.at(stress, model.beams.plank, along.max(axis=1))
    return stress


def _stress_along(model: StaticsModel, layout: _Layout, displacement: np.ndarray,
                  w: np.ndarray, slope: np.ndarray, line_loads: np.ndarray,
                  elements: np.ndarray | None = None,
                  columns: np.ndarray | None = None) -> np.ndarray:
    """(nE, m) Pa: |M_2| / (b t^2 / 6) + |M_3| / (t b^2 / 6) + |N| / (b t) along each
    element (``_stress`` takes each plank's largest): at their ends, SAG_SAMPLES points
    inside (columns 0 .. SAG_SAMPLES + 1) and, the last two columns, wherever either
    bending moment peaks inside (each moment is a parabola along an element under its own
    uniform load, M(s) = M_0 + V_0 s + q s^2 / 2, ``beams.element_end_moment``; the peak
    is its vertex, s = -V_0 / q).  The normal force N comes from
    the element end forces K_local T u - f_local (T u: each end's displacement and
    rotation in the element's axes, R^T u; f_local: the consistent loads of its own
    uniform load ``line_loads`` (nE, 3) N/m), linear in between.  With ``elements`` and
    ``columns`` (k,) each: only those entries, (k,) (each entry is computed alone: the
    same number as in the whole table)."""
    model, layout, line_loads = _cut_to(model, layout, line_loads, elements)
    beams = model.beams
    forces = element_end_forces(beams, displacement.ravel()) \
        - element_loads_local(beams, line_loads)
    # each plane's moment as M(xi) = c0 + c1 xi + c2 xi^2 along the element, (2, nE) each
    c0, V0, q = _moment_lines(model, layout, w, slope, line_loads)
    c1, c2 = V0 * beams.length, 0.5 * q * beams.length ** 2
    with np.errstate(over="ignore"):    # a curvature of a denormal load: past 1, clipped
        vertex = np.divide(-c1, 2.0 * c2, out=np.zeros_like(c1), where=c2 != 0.0)
    xi = np.concatenate([np.broadcast_to(np.linspace(0.0, 1.0, tol.SAG_SAMPLES + 2),
                                         (len(beams.plank), tol.SAG_SAMPLES + 2)),
                         np.clip(vertex, 0.0, 1.0).T], axis=1)          # (nE, m)
    if columns is not None:
        xi = xi[np.arange(len(xi)), columns][:, None]                   # (k, 1)
    moments = c0[:, :, None] + c1[:, :, None] * xi + c2[:, :, None] * xi * xi   # (2, nE, m)
    normal = (1.0 - xi) * -forces[:, :1] + xi * forces[:, 6:7]          # tension > 0
    along = (np.abs(moments[0]) / layout.in_plane[:, None]
             + np.abs(moments[1]) / layout.bending[:, None]
             + np.abs(normal) / layout.area[:, None])
    return along if columns is None else along[:, 0]


def _cut_to(model, layout: _Layout, line_loads: np.ndarray,
            elements: np.ndarray | None) -> tuple:
    """The model (its beams), layout and line loads of ``elements`` alone, in that order
    (repeats allowed; the nodes and their arrays kept whole); all of them for None."""
    if elements is None:
        return model, layout, line_loads
    beams = model.beams
    cut, cut_layout = _element_cut(
        beams, layout, elements, plank=beams.plank[elements], nodes=beams.nodes[elements],
        node_s=beams.node_s, plank_half=beams.plank_half, node_frame=layout.node_frame)
    return _Stacked(cut, model.planks, model.node_plank), cut_layout, line_loads[elements]


def _transverse(displacement: np.ndarray,
                node_frame: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(w, slope) at every node: its deflection across its beam's axis (2, nN) m, along e2
    (row 0) and e3 (row 1), and its section's rotation in those planes (2, nN), theta . e3
    and -theta . e2 (the axis's slope dw/ds where shear strain is negligible; a Timoshenko
    beam's axis slopes by theta - V / k G A, see ``beams.element_interior``)
    (``displacement`` (nN, 6): u, theta per node; ``node_frame`` (nN, 3, 3): e1, e2, e3)."""
    across = node_frame[:, :, 1:]
    w = np.einsum("ni,nij->jn", displacement[:, :3], across)
    turn = np.einsum("ni,nij->jn", displacement[:, 3:], across)       # theta . e2, theta . e3
    return w, np.stack([turn[1], -turn[0]])


def _profile(model: StaticsModel, layout: _Layout, w: np.ndarray, slope: np.ndarray,
             line_loads: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(s, deflection, plank) of the points where the sag is read: every node and
    SAG_SAMPLES points inside each element, nX = nN + SAG_SAMPLES nE in all: s (nX,) m
    along its plank's axis, the transverse deflection (2, nX) m along e2 and e3, and the
    local plank of each point (nX,).

    Inside an element the deflection in each bending plane is the Timoshenko beam's own
    (``beams.element_interior``: exact for what its nodes did, ``w`` and ``slope`` (2, nN)
    of ``_transverse``, and its own uniform load), so a largest sag between nodes is read
    however long the element.  Inside the elements the arrays are (2, SAG_SAMPLES, nE):
    component, sample, element."""
    beams = model.beams
    a = beams.nodes[:, 0]
    xi = np.linspace(0.0, 1.0, tol.SAG_SAMPLES + 2)[1:-1]
    inside = _interior(model, layout, w, slope, line_loads, xi)         # (2, nE, samples)
    inside = np.transpose(inside, (0, 2, 1))                            # (2, samples, nE)
    s_inside = beams.node_s[a] + xi[:, None] * beams.length             # (samples, nE)
    return (np.concatenate([beams.node_s, s_inside.ravel()]),
            np.concatenate([w, inside.reshape(2, -1)], axis=1),
            np.concatenate([model.node_plank, np.tile(beams.plank, len(xi))]))


def _plane_arguments(model: StaticsModel, layout: _Layout, w: np.ndarray, slope: np.ndarray,
                     line_loads: np.ndarray, j: int) -> tuple:
    """(L, E I, k G A, ends, q) of every element in bending plane j (0: along e2, about e3,
    in the plank's plane; 1: along e3, about e2, the sag of a shelf), as
    ``beams.element_interior`` takes them: its nodes' deflections and section rotations
    (``_transverse``) and its own uniform load from ``line_loads`` (nE, 3) N/m."""
    beams = model.beams
    a, b = beams.nodes[:, 0], beams.nodes[:, 1]
    q = np.einsum("ei,ei->e", line_loads, beams.frames[:, :, 1 + j])
    return (beams.length, beams.elastic_modulus * layout.inertia[:, j],
            SHEAR_FACTOR * beams.shear_modulus * layout.area,
            np.column_stack([w[j, a], slope[j, a], w[j, b], slope[j, b]]), q)


def _interior(model: StaticsModel, layout: _Layout, w: np.ndarray, slope: np.ndarray,
              line_loads: np.ndarray, xi: np.ndarray,
              elements: np.ndarray | None = None) -> np.ndarray:
    """(2, nE, m): the deflection in both bending planes at the fractions ``xi`` (m,) of
    each element (``element_interior``, ``_plane_arguments``); with ``elements`` (k,) of
    those alone, and ``xi`` may be (k, 1), one fraction each."""
    model, layout, line_loads = _cut_to(model, layout, line_loads, elements)
    return np.stack([element_interior(*_plane_arguments(model, layout, w, slope,
                                                        line_loads, j), xi)[0]
                     for j in (0, 1)])


def _moment_lines(model: StaticsModel, layout: _Layout, w: np.ndarray, slope: np.ndarray,
                  line_loads: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(M_0, V_0, q), each (2, nE): the moment line M(s) = M_0 + V_0 s + q s^2 / 2 of each
    element in both bending planes (``element_end_moment``)."""
    parts = [_plane_arguments(model, layout, w, slope, line_loads, j) for j in (0, 1)]
    ends = [element_end_moment(*part) for part in parts]
    return (np.stack([end[0] for end in ends]), np.stack([end[1] for end in ends]),
            np.stack([part[4] for part in parts]))
