"""The frozen design model.  Everything inside is SI: metres, kilograms, newtons.

A ``Design`` is what the loader returns and what geometry, statics and validity read.
The file's own length unit is kept (``unit_scale``, metres per file unit) so reports can
print positions the way the maker wrote them.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np

from furncheck import tolerances as tol
from furncheck.tolerances import GRAVITY

Vec3 = tuple[float, float, float]


def rotation_matrix(rotation_deg: Vec3) -> np.ndarray:
    """R = Rz @ Ry @ Rx for rotations (degrees) about world x, then y, then z.

    Returns (3, 3) float; columns are the plank's local x, y, z axes in world coordinates.
    """
    return rotation_matrices([rotation_deg])[0]


def rotation_matrices(rotations: Sequence[Vec3]) -> np.ndarray:
    """(n, 3, 3): ``rotation_matrix`` of each rotation, the three factors stacked and
    multiplied together (each product the same BLAS call as one plank's, so the same
    numbers to the bit)."""
    factors = np.zeros((3, len(rotations), 3, 3))
    for i, rotation in enumerate(rotations):
        rx, ry, rz = (math.radians(float(angle)) for angle in rotation)
        cx, sx = math.cos(rx), math.sin(rx)
        cy, sy = math.cos(ry), math.sin(ry)
        cz, sz = math.cos(rz), math.sin(rz)
        factors[0, i] = ((1.0, 0.0, 0.0), (0.0, cx, -sx), (0.0, sx, cx))
        factors[1, i] = ((cy, 0.0, sy), (0.0, 1.0, 0.0), (-sy, 0.0, cy))
        factors[2, i] = ((cz, -sz, 0.0), (sz, cz, 0.0), (0.0, 0.0, 1.0))
    return factors[2] @ factors[1] @ factors[0]


CORNER_SIGNS = np.array([[sx, sy, sz] for sz in (-1, 1) for sy in (-1, 1) for sx in (-1, 1)],
                        dtype=float)
"""(8, 3) the local sign pattern of ``Plank.corners`` (corner c: bit 0 x, bit 1 y, bit 2
z; ``dofs.frame`` reads which ends a plank's touching corners share from it)."""


def tabulate_planks(planks: Sequence[Plank]) -> None:
    """Compute the cached arrays of every plank that has none yet (``rotation_matrix``,
    ``center_array``, ``half_extents``, ``corners``) for all of them at once: the same
    numbers as each plank's own (the same products, stacked), without numpy's per-call
    overhead per plank (a design's geometry reads them all first)."""
    todo = [plank for plank in planks if "corners" not in plank.__dict__]
    if len(todo) < 2:
        return
    rotations = rotation_matrices([plank.rotation for plank in todo])
    centers = np.array([plank.center for plank in todo], dtype=float)
    halves = 0.5 * np.array([(p.length, p.width, p.thickness) for p in todo])
    corners = centers[:, None, :] + (CORNER_SIGNS * halves[:, None, :]) \
        @ np.transpose(rotations, (0, 2, 1))
    for k, plank in enumerate(todo):
        cache = plank.__dict__              # what cached_property fills in, filled here
        cache.setdefault("rotation_matrix", rotations[k])
        cache.setdefault("center_array", centers[k])
        cache.setdefault("half_extents", halves[k])
        cache["corners"] = corners[k]


@dataclass(frozen=True)
class Material:
    """Plank material and nail properties (SI; defaults and their sources: ``tolerances``
    and the README)."""

    thickness: float = 0.012      # m, default plank thickness
    density: float = 750.0        # kg/m^3
    nail_spacing: float = 0.020   # m between nails along a joint
    nail_pull: float = 700.0      # N per nail
    nail_shear: float = 190.0     # N per nail
    friction: float = 0.5         # static Coulomb coefficient with the ground
    # the elastic model (contract section 3a)
    elastic_modulus: float = tol.DEFAULT_ELASTIC_MODULUS    # Pa
    shear_modulus: float = tol.DEFAULT_SHEAR_MODULUS        # Pa
    bending_strength: float = tol.DEFAULT_BENDING_STRENGTH  # Pa
    creep: float = tol.DEFAULT_CREEP          # long-term sag factor: final = sag (1 + creep)
    sag_limit: float = tol.DEFAULT_SAG_LIMIT  # allowed sag = span / sag_limit
    nail_slip: float = tol.DEFAULT_NAIL_SLIP                # N/m per nail, across the nail
    nail_withdrawal: float = tol.DEFAULT_NAIL_WITHDRAWAL    # N/m per nail, along the nail


@dataclass(frozen=True)
class Plank:
    """A rigid box.  Local x = length, y = width, z = thickness (the face normal).

    center   : world position of the box centre, m
    rotation : degrees about world x, then y, then z (R = Rz @ Ry @ Rx)
    material : the plank's own material values, ((key, SI value), ...) in
               ``PLANK_MATERIAL_KEYS`` order (density, elastic and strength values; its
               thickness is ``thickness``); the design's material gives the rest
               (``Design.material_of``)
    """

    id: str
    length: float
    width: float
    thickness: float
    center: Vec3
    rotation: Vec3 = (0.0, 0.0, 0.0)
    material: tuple[tuple[str, float], ...] = ()

    @cached_property
    def rotation_matrix(self) -> np.ndarray:
        """(3, 3): columns are local x, y, z in world coordinates."""
        return rotation_matrix(self.rotation)

    @cached_property
    def center_array(self) -> np.ndarray:
        """(3,) float, m."""
        return np.asarray(self.center, dtype=float)

    @cached_property
    def half_extents(self) -> np.ndarray:
        """(3,) float, m: half length, half width, half thickness."""
        return 0.5 * np.array([self.length, self.width, self.thickness])

    # Plain-float views of the same numbers, for code that does a few scalar operations per
    # plank many times over (``furncheck.dofs``): on 3-vectors numpy's per-call overhead is
    # far larger than the arithmetic.

    @cached_property
    def axes(self) -> tuple[Vec3, Vec3, Vec3]:
        """The local x, y, z axes in world coordinates (the columns of ``rotation_matrix``)
        as tuples of floats."""
        x_axis, y_axis, z_axis = self.rotation_matrix.T.tolist()
        return tuple(x_axis), tuple(y_axis), tuple(z_axis)

    @property
    def half_sizes(self) -> Vec3:
        """m: half length, half width, half thickness as floats (= ``half_extents``; not
        cached: planks edited in a loop are mostly read once)."""
        return 0.5 * self.length, 0.5 * self.width, 0.5 * self.thickness

    @property
    def volume(self) -> float:
        """m^3."""
        return self.length * self.width * self.thickness

    @cached_property
    def corners(self) -> np.ndarray:
        """(8, 3) float, m: world positions of the box corners (sign pattern of local axes
        in the order ---, +--, -+-, ++-, --+, +-+, -++, +++)."""
        return self.center_array + (CORNER_SIGNS * self.half_extents) @ self.rotation_matrix.T

    def to_local(self, points: np.ndarray) -> np.ndarray:
        """World points (n, 3) -> plank-local coordinates (n, 3)."""
        return (np.asarray(points, dtype=float) - self.center_array) @ self.rotation_matrix


@dataclass(frozen=True)
class Load:
    """One applied load (SI, world frame).

    force : N; a mass m becomes (0, 0, -m g)
    point : m, world point where it acts, or None for the plank centre
    mass  : kg when the file gave a mass (kept for writing the file back), else None
    spread : spread evenly along the plank's length (books on a shelf); no point.  The
             rigid model takes its resultant at the plank centre.
    """

    plank: str
    force: Vec3
    point: Vec3 | None = None
    mass: float | None = None
    spread: bool = False

    @staticmethod
    def of_mass(plank: str, mass: float, point: Vec3 | None = None,
                spread: bool = False) -> Load:
        return Load(plank, (0.0, 0.0, -mass * GRAVITY), point, mass, spread)


@dataclass(frozen=True)
class LoadCase:
    """A named load case; self-weight is always added on top of ``loads``.

    loads    : every load that acts in the case: those of the cases it includes first (in
               include order, each case once; ``furncheck.design.cases``), then its own
    includes : the case names its ``include`` gives, as written; () for none
    origins  : per load of ``loads``, the case whose file entry gives it; () when every
               load is the case's own
    """

    name: str
    loads: tuple[Load, ...] = ()
    includes: tuple[str, ...] = ()
    origins: tuple[str, ...] = ()

    def origin(self, index: int) -> str:
        """The case whose file entry gives ``loads[index]`` (this case's name for its own)."""
        return self.origins[index] if self.origins else self.name

    @property
    def own_loads(self) -> tuple[Load, ...]:
        """The loads the case's own entry lists (what a design file writes back)."""
        if not self.origins:
            return self.loads
        return tuple(load for load, origin in zip(self.loads, self.origins)
                     if origin == self.name)


@dataclass(frozen=True)
class JointSpec:
    """A joint listed in the file: two plank ids, optional explicit nail count; ``rests``:
    a ``type: rests`` joint, no nails, one plank resting on the other (contract
    section 2)."""

    planks: tuple[str, str]
    nails: int | None = None
    rests: bool = False


@dataclass(frozen=True)
class Wall:
    """A vertical plane the design may lean on (contract section 2), SI.

    point  : m, a world point of the plane
    normal : unit, horizontal, pointing away from the wall into the room
    """

    point: Vec3
    normal: Vec3

    def distance(self, points: np.ndarray) -> np.ndarray:
        """m: signed distance of world points (..., 3) in front of the plane (< 0 behind)."""
        return (np.asarray(points) - np.asarray(self.point)) @ np.asarray(self.normal)


@dataclass(frozen=True)
class Anchor:
    """A screw or bracket tying ``plank`` to wall ``wall`` (index into ``Design.walls``) at
    the world point ``point`` (m, on the plank), both ways, up to ``capacity`` N; ``gap``
    (m): how far in front of its wall the point was drawn (an edit that moves the point
    off by more than the tolerance would need another bracket)."""

    plank: str
    point: Vec3
    wall: int
    capacity: float
    gap: float = 0.0


@dataclass(frozen=True)
class Design:
    """A checked design, SI inside.

    source      : path as given by the user ('' when built in memory)
    units       : the file's length unit, 'mm' or 'm'
    unit_scale  : metres per file length unit (0.001 or 1.0)
    joints      : listed joints, or None when they are detected from geometry
    load_cases  : 'default' (from ``loads``) first, then ``load_cases`` in file order
    tolerance   : m, geometric tolerance
    model       : 'elastic' (planks bend, contract section 3a) or 'rigid' (the paper's)
    walls       : vertical planes the design may lean on (contract section 2)
    anchors     : ties of planks to walls (contract section 2)
    lines       : key path -> 1-based line in the source file, for annotations (a JSON
                  file's looked up when first asked for: ``json_source.JsonLines``)
    """

    name: str
    planks: tuple[Plank, ...]
    load_cases: tuple[LoadCase, ...] = (LoadCase("default"),)
    material: Material = Material()
    joints: tuple[JointSpec, ...] | None = None
    safety_factor: float = 1.0
    tolerance: float = 0.0005
    units: str = "mm"
    unit_scale: float = 0.001
    source: str = ""
    model: str = tol.DEFAULT_MODEL
    walls: tuple[Wall, ...] = ()
    anchors: tuple[Anchor, ...] = ()
    lines: dict[str, int] = field(default_factory=dict, compare=False, repr=False)

    def plank(self, plank_id: str) -> Plank:
        """The plank of that id (KeyError if there is none), by ``plank_index``: a lookup
        that model builds make for every joint of a 2,000-plank design."""
        return self.planks[self.plank_index[plank_id]]

    @cached_property
    def plank_index(self) -> dict[str, int]:
        """plank id -> position in ``planks``."""
        return {p.id: i for i, p in enumerate(self.planks)}

    def plank_mass(self, plank: Plank) -> float:
        """kg: the plank's density x its volume."""
        return self.material_of(plank).density * plank.volume

    @property
    def elastic(self) -> bool:
        """Whether its planks bend (``model: elastic``, contract section 3a): the one test
        of the model's name."""
        return self.model == "elastic"

    def material_of(self, plank: Plank) -> Material:
        """The plank's material: the design's, with the plank's own values
        (``Plank.material``) in their place.  (Its thickness is ``plank.thickness``; the
        nails' values and the friction are always the design's.)"""
        if not plank.material:
            return self.material
        materials = self._plank_materials
        if plank.material not in materials:
            materials[plank.material] = replace(self.material, **dict(plank.material))
        return materials[plank.material]

    @cached_property
    def _plank_materials(self) -> dict[tuple, Material]:
        """A plank's own values -> its material, filled by ``material_of``."""
        return {}

    def line_of(self, key: str) -> int | None:
        """Source line of a key path, falling back to its closest recorded parent."""
        while key:
            if key in self.lines:
                return self.lines[key]
            cut = max(key.rfind("."), key.rfind("["))
            key = key[:cut] if cut > 0 else ""
        return None


def with_model(design: Design, model: str | None) -> Design:
    """The design in ``model`` ('elastic' or 'rigid'; the command line's ``--model``), or
    as it is when None.  Any other name is a ValueError (the file's ``model`` key and
    ``--model`` are checked where they are read; this guards the library's callers)."""
    if model is not None and model not in tol.MODELS:
        raise ValueError(f"unknown statics model {model!r} (one of {', '.join(tol.MODELS)})")
    return design if model is None or model == design.model else replace(design, model=model)
