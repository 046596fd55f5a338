"""Design files (YAML or JSON, contract section 1) -> a checked, frozen ``Design`` in SI.

Reading goes in three steps:

1. bytes -> text (``load_design``): the file must exist, be a regular file of at most
   ``MAX_FILE_BYTES``, hold no NUL bytes and be UTF-8;
2. text -> a plain tree of dicts, lists and scalars, with the line of every key path;
3. tree -> ``Design`` (``_design`` and the helpers below it, key by key as in the contract),
   converting lengths to metres.

Steps 1 and 2 are in ``furncheck.design.source`` (which refuses YAML aliases before anything
is expanded and duplicate keys, and keeps YAML scalars as ``_Scalar`` until the schema knows
whether a number or a text belongs there); ``furncheck.design.values`` reads typed values
from the tree (``_Doc``); this module is step 3, the schema.

Every problem raises ``DesignError(file, key path, line, message)``.  Key paths read
``planks[1].size``, ``load_cases.sit[0].mass``; '' is the whole file.  For JSON, the line of
a key path is looked up only when an error is raised (by reading the text as YAML).
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design, JointSpec, Load, LoadCase, Material, Plank
from furncheck.design.source import (
    _NO_DOCUMENT,
    _PATH_SAFE_KEY,
    FORMATS,  # noqa: F401  (re-exported: still importable from here)
    _check_regular_file,
    _checked_text,
    _child,
    _decode,
    _format_of,
    _quote,
    _read_json,
    _read_yaml,
    _too_large,
)
from furncheck.design.values import _describe, _Doc, _resolved
from furncheck.errors import DesignError
from furncheck.plain import plain_number

UNIT_SCALES = {"mm": 0.001, "m": 1.0}
"""Length unit -> metres per unit."""

TOP_KEYS = ("furncheck", "name", "units", "model", "material", "planks", "joints", "loads",
            "load_cases", "safety_factor", "tolerance")
MATERIAL_KEYS = ("thickness", "density", "nail_spacing", "nail_pull", "nail_shear", "friction",
                 "elastic_modulus", "shear_modulus", "bending_strength", "creep", "sag_limit",
                 "nail_slip", "nail_withdrawal")
PLANK_KEYS = ("id", "size", "center", "rotation", "thickness")
JOINT_KEYS = ("planks", "nails")
LOAD_KEYS = ("plank", "mass", "force", "at", "spread")

_IDENTIFIER = _PATH_SAFE_KEY   # plank ids and case names: what a key path shows bare
_AXES = ("length", "width", "thickness")


# --- public -------------------------------------------------------------------------------------

def load_design(path: str) -> Design:
    """Read and check the design file at ``path`` (format from its extension).

    Raises ``DesignError`` (file = ``path`` as given) for a missing, unreadable, binary,
    empty, oversized or ill-formed file.
    """
    _check_regular_file(path)
    fmt = _format_of(path)
    return parse_design(_decode(_read_bytes(path), path), path, fmt)


def parse_design(text: str, source: str, fmt: str) -> Design:
    """Check the design document ``text`` ('yaml' or 'json'); ``source`` names it in errors
    and becomes ``Design.source``.  Returns the ``Design`` in SI units."""
    if fmt not in ("yaml", "json"):
        raise DesignError(source, "", None, f"unknown format {_quote(str(fmt))}; use yaml or json")
    text = _checked_text(text, source)
    if fmt == "yaml":
        tree, lines = _read_yaml(text, source)
        doc = _Doc(source, fmt, text, lines)
    else:
        tree = _read_json(text, source)
        doc = _Doc(source, fmt, text, None)
    return _design(doc, tree)


# --- step 1: the file's bytes (the rest of steps 1-2 is in source.py) ---------------------------

def _read_bytes(path: str) -> bytes:
    """The file's bytes, at most ``MAX_FILE_BYTES`` of them.  (Kept here, where the file is
    opened, so that a test can replace this module's ``open``.)"""
    try:
        with open(path, "rb") as handle:
            data = handle.read(tol.MAX_FILE_BYTES + 1)
    except OSError as error:
        raise DesignError(path, "", None, f"cannot read file: {error.strerror}") from None
    if len(data) > tol.MAX_FILE_BYTES:
        raise _too_large(path, len(data))
    return data


# --- step 3: tree -> Design ---------------------------------------------------------------------

@dataclass(frozen=True)
class _Units:
    """The file's length unit: ``name`` ('mm' or 'm'), ``scale`` metres per unit."""

    name: str
    scale: float


def _design(doc: _Doc, tree: Any) -> Design:
    top = _top_level(doc, tree)
    units = _units(doc, top)
    tolerance = (_quantity(doc, top["tolerance"], "tolerance", 0.0, tol.MAX_LENGTH,
                           units.scale, units.name)
                 if "tolerance" in top else tol.DEFAULT_TOLERANCE)
    material = _material(doc, top, units)
    planks = _planks(doc, top["planks"], material, units)
    by_id = {plank.id: plank for plank in planks}
    safety_factor = (_quantity(doc, top["safety_factor"], "safety_factor",
                               tol.MIN_SAFETY_FACTOR, tol.MAX_SAFETY_FACTOR, positive=True)
                     if "safety_factor" in top else tol.DEFAULT_SAFETY_FACTOR)
    return Design(
        name=_name(doc, top),
        planks=planks,
        load_cases=_load_cases(doc, top, by_id, units, tolerance),
        material=material,
        joints=_joints(doc, top["joints"], by_id) if "joints" in top else None,
        safety_factor=safety_factor,
        tolerance=tolerance,
        units=units.name,
        unit_scale=units.scale,
        source=doc.source,
        model=_model(doc, top),
        lines=doc.design_lines(),
    )


def _top_level(doc: _Doc, tree: Any) -> dict:
    """The top mapping, its format version checked before its keys (a newer version may
    have keys this one does not know)."""
    if tree is _NO_DOCUMENT:
        doc.fail("", "empty file")
    if not isinstance(tree, dict):
        doc.fail("", f"the top level must be a mapping, got {_describe(tree)}")
    if "furncheck" not in tree:
        doc.fail("furncheck", 'missing required key "furncheck" (the format version: '
                              "write furncheck: 1)")
    version = doc.number(tree["furncheck"], "furncheck")
    if version != 1:
        doc.fail("furncheck", f"unsupported format version {plain_number(version, 6)}; this "
                              "furncheck reads "
                              "version 1")
    return doc.mapping(tree, "", TOP_KEYS, required=("planks",))


def _name(doc: _Doc, top: dict) -> str:
    if "name" not in top:
        return Path(doc.source).stem or "design"
    name = doc.text(top["name"], "name")
    if not name.strip() or not name.isprintable():
        doc.fail("name", "must be printable text on one line")
    return name


def _units(doc: _Doc, top: dict) -> _Units:
    name = doc.text(top["units"], "units") if "units" in top else "mm"
    if name not in UNIT_SCALES:
        doc.fail("units", f"unknown unit {_quote(name)}; use mm or m")
    return _Units(name, UNIT_SCALES[name])


def _model(doc: _Doc, top: dict) -> str:
    if "model" not in top:
        return tol.DEFAULT_MODEL
    name = doc.text(top["model"], "model")
    if name not in tol.MODELS:
        doc.fail("model", f"unknown model {_quote(name)}; use elastic or rigid")
    return name


def _quantity(doc: _Doc, node: Any, key: str, low: float, high: float, scale: float = 1.0,
              unit: str = "", positive: bool = False) -> float:
    """A number written in ``unit`` (``scale`` SI units each), checked to lie in
    [low, high] (SI) and, if ``positive``, to be > 0.  Returns it in SI."""
    value = doc.number(node, key)
    shown = f" {unit}" if unit else ""
    if positive and value <= 0:
        doc.fail(key, f"must be positive, got {plain_number(value, 6)}{shown}")
    if not low <= value * scale <= high:
        doc.fail(key, f"out of range: {plain_number(value, 6)}{shown}; allowed "
                      f"{plain_number(low / scale, 6)} to {plain_number(high / scale, 6)}{shown}")
    return value * scale


def _length(doc: _Doc, node: Any, key: str, units: _Units) -> float:
    """m: a size, thickness or spacing in [MIN_LENGTH, MAX_LENGTH]."""
    return _quantity(doc, node, key, tol.MIN_LENGTH, tol.MAX_LENGTH, units.scale, units.name,
                     positive=True)


def _vector(doc: _Doc, node: Any, key: str, count: int, low: float, high: float,
            scale: float = 1.0, unit: str = "", positive: bool = False) -> tuple[float, ...]:
    """``count`` numbers, each as ``_quantity``; SI."""
    items = doc.sequence(node, key)
    if len(items) != count:
        doc.fail(key, f"expected {count} numbers, got {len(items)}")
    return tuple(_quantity(doc, item, f"{key}[{i}]", low, high, scale, unit, positive)
                 for i, item in enumerate(items))


def _point(doc: _Doc, node: Any, key: str, units: _Units) -> tuple[float, float, float]:
    """m: a world point, every |coordinate| <= MAX_COORDINATE."""
    return _vector(doc, node, key, 3, -tol.MAX_COORDINATE, tol.MAX_COORDINATE,
                   units.scale, units.name)


def _identifier(doc: _Doc, node: Any, key: str, what: str) -> str:
    name = doc.text(node, key)
    if not _IDENTIFIER.fullmatch(name):
        doc.fail(key, f"invalid {what} {_quote(name)}: use letters, digits, '_', '.' and '-'")
    return name


def _material(doc: _Doc, top: dict, units: _Units) -> Material:
    """Material; lengths in the file unit, defaults (SI) from ``tolerances``."""
    if "material" not in top:
        return Material()
    fields = doc.mapping(top["material"], "material", MATERIAL_KEYS)

    def read(name: str, default: float, low: float, high: float, scale: float = 1.0,
             unit: str = "", positive: bool = True) -> float:
        if name not in fields:
            return default
        return _quantity(doc, fields[name], f"material.{name}", low, high, scale, unit, positive)

    return Material(
        thickness=read("thickness", tol.DEFAULT_THICKNESS, tol.MIN_LENGTH, tol.MAX_LENGTH,
                       units.scale, units.name),
        density=read("density", tol.DEFAULT_DENSITY, 0.0, tol.MAX_DENSITY, unit="kg/m^3"),
        nail_spacing=read("nail_spacing", tol.DEFAULT_NAIL_SPACING, tol.MIN_LENGTH,
                          tol.MAX_LENGTH, units.scale, units.name),
        nail_pull=read("nail_pull", tol.DEFAULT_NAIL_PULL, 0.0, tol.MAX_NAIL_CAPACITY,
                       unit="N"),
        nail_shear=read("nail_shear", tol.DEFAULT_NAIL_SHEAR, 0.0, tol.MAX_NAIL_CAPACITY,
                        unit="N"),
        friction=read("friction", tol.DEFAULT_FRICTION, 0.0, tol.MAX_FRICTION,
                      positive=False),
        elastic_modulus=read("elastic_modulus", tol.DEFAULT_ELASTIC_MODULUS, 0.0,
                             tol.MAX_MODULUS, 1e6, "N/mm^2"),
        shear_modulus=read("shear_modulus", tol.DEFAULT_SHEAR_MODULUS, 0.0, tol.MAX_MODULUS,
                           1e6, "N/mm^2"),
        bending_strength=read("bending_strength", tol.DEFAULT_BENDING_STRENGTH, 0.0,
                              tol.MAX_MODULUS, 1e6, "N/mm^2"),
        creep=read("creep", tol.DEFAULT_CREEP, 0.0, tol.MAX_CREEP, positive=False),
        sag_limit=read("sag_limit", tol.DEFAULT_SAG_LIMIT, 0.0, tol.MAX_SAG_LIMIT),
        nail_slip=read("nail_slip", tol.DEFAULT_NAIL_SLIP, 0.0, tol.MAX_NAIL_STIFFNESS, 1e3,
                       "N/mm"),
        nail_withdrawal=read("nail_withdrawal", tol.DEFAULT_NAIL_WITHDRAWAL, 0.0,
                             tol.MAX_NAIL_STIFFNESS, 1e3, "N/mm"),
    )


def _planks(doc: _Doc, node: Any, material: Material, units: _Units) -> tuple[Plank, ...]:
    items = doc.sequence(node, "planks")
    if not items:
        doc.fail("planks", "a design needs at least one plank")
    first_index: dict[str, int] = {}
    planks = []
    for index, item in enumerate(items):
        key = f"planks[{index}]"
        plank = _plank(doc, item, key, material, units)
        if plank.id in first_index:
            doc.fail(f"{key}.id", f"duplicate plank id {_quote(plank.id)} "
                                  f"(planks[{first_index[plank.id]}] and {key})")
        first_index[plank.id] = index
        planks.append(plank)
    return tuple(planks)


def _plank(doc: _Doc, node: Any, key: str, material: Material, units: _Units) -> Plank:
    fields = doc.mapping(node, key, PLANK_KEYS, required=("id", "size", "center"))
    plank_id = _identifier(doc, fields["id"], f"{key}.id", "plank id")
    length, width = _vector(doc, fields["size"], f"{key}.size", 2, tol.MIN_LENGTH,
                            tol.MAX_LENGTH, units.scale, units.name, positive=True)
    thickness = (_length(doc, fields["thickness"], f"{key}.thickness", units)
                 if "thickness" in fields else material.thickness)
    rotation = (_vector(doc, fields["rotation"], f"{key}.rotation", 3, -tol.MAX_ROTATION_DEG,
                        tol.MAX_ROTATION_DEG, unit="degrees")
                if "rotation" in fields else (0.0, 0.0, 0.0))
    center = _point(doc, fields["center"], f"{key}.center", units)
    return Plank(plank_id, length, width, thickness, center, rotation)


def _plank_ref(doc: _Doc, node: Any, key: str, by_id: dict[str, Plank]) -> Plank:
    """The plank that ``node`` names."""
    name = doc.text(node, key)
    if name not in by_id:
        close = difflib.get_close_matches(name, list(by_id), n=1)
        hint = f" (did you mean {_quote(close[0])}?)" if close else ""
        doc.fail(key, f"unknown plank {_quote(name)}{hint}")
    return by_id[name]


# --- joints -------------------------------------------------------------------------------------

def _joints(doc: _Doc, node: Any, by_id: dict[str, Plank]) -> tuple[JointSpec, ...] | None:
    """None for ``auto`` (detected from geometry), else the listed joints."""
    if isinstance(_resolved(node), str) and doc.text(node, "joints") == "auto":
        return None
    if not isinstance(node, list):
        doc.fail("joints", f'expected "auto" or a list of joints, got {_describe(node)}')
    first_index: dict[frozenset, int] = {}
    joints = []
    for index, item in enumerate(node):
        key = f"joints[{index}]"
        joint = _joint(doc, item, key, by_id)
        pair = frozenset(joint.planks)
        if pair in first_index:
            doc.fail(key, f"joint {'/'.join(joint.planks)} is listed twice "
                          f"(joints[{first_index[pair]}] and {key})")
        first_index[pair] = index
        joints.append(joint)
    return tuple(joints)


def _joint(doc: _Doc, node: Any, key: str, by_id: dict[str, Plank]) -> JointSpec:
    """``[a, b]`` or ``{planks: [a, b], nails: n}``."""
    nails = None
    if isinstance(node, dict):
        fields = doc.mapping(node, key, JOINT_KEYS, required=("planks",))
        pair_key, pair_node = f"{key}.planks", fields["planks"]
        if "nails" in fields:
            nails = _nail_count(doc, fields["nails"], f"{key}.nails")
    elif isinstance(node, list):
        pair_key, pair_node = key, node
    else:
        doc.fail(key, f"expected [plank, plank] or {{planks: [plank, plank], nails: n}}, "
                      f"got {_describe(node)}")
    items = doc.sequence(pair_node, pair_key)
    if len(items) != 2:
        doc.fail(pair_key, f"expected 2 plank ids, got {len(items)}")
    first, second = (_plank_ref(doc, item, f"{pair_key}[{i}]", by_id).id
                     for i, item in enumerate(items))
    if first == second:
        doc.fail(key, f"a joint needs two different planks, got {_quote(first)} twice")
    return JointSpec((first, second), nails)


def _nail_count(doc: _Doc, node: Any, key: str) -> int:
    value = doc.number(node, key)
    if not value.is_integer() or not 1 <= value <= tol.MAX_NAILS:
        doc.fail(key, f"must be a whole number of nails from 1 to "
                      f"{plain_number(tol.MAX_NAILS, 6)}, got {plain_number(value, 6)}")
    return int(value)


# --- loads and load cases -----------------------------------------------------------------------

def _load_cases(doc: _Doc, top: dict, by_id: dict[str, Plank], units: _Units,
                tolerance: float) -> tuple[LoadCase, ...]:
    """'default' (from ``loads``) first, then ``load_cases`` in file order; a lone
    self-weight case 'default' when the file gives neither."""
    cases = []
    if "loads" in top:
        cases.append(LoadCase("default", _loads(doc, top["loads"], "loads", by_id, units,
                                                tolerance)))
    if "load_cases" in top:
        for name, node in doc.mapping(top["load_cases"], "load_cases").items():
            key = _child("load_cases", name)
            _identifier(doc, name, key, "load case name")
            if name == "default" and "loads" in top:
                doc.fail(key, 'case "default" is already given by "loads"; rename this case '
                              'or move its loads there')
            cases.append(LoadCase(name, _loads(doc, node, key, by_id, units, tolerance)))
    return tuple(cases) or (LoadCase("default"),)


def _loads(doc: _Doc, node: Any, key: str, by_id: dict[str, Plank], units: _Units,
           tolerance: float) -> tuple[Load, ...]:
    items = doc.sequence(node, key)
    return tuple(_load(doc, item, f"{key}[{i}]", by_id, units, tolerance)
                 for i, item in enumerate(items))


def _load(doc: _Doc, node: Any, key: str, by_id: dict[str, Plank], units: _Units,
          tolerance: float) -> Load:
    """``{plank, mass | force, at? | spread?}``: mass kg, force N, ``at`` a world point on
    the plank, ``spread: true`` the load spread evenly along the plank's length."""
    fields = doc.mapping(node, key, LOAD_KEYS, required=("plank",))
    spread = "spread" in fields and doc.flag(fields["spread"], f"{key}.spread")
    if spread and "at" in fields:
        doc.fail(f"{key}.at", "a spread load acts along the whole plank: give no point")
    plank = _plank_ref(doc, fields["plank"], f"{key}.plank", by_id)
    if "mass" in fields and "force" in fields:
        doc.fail(key, "give either mass (kg) or force ([fx, fy, fz] N), not both")
    if "mass" not in fields and "force" not in fields:
        doc.fail(key, "a load needs a mass (kg) or a force ([fx, fy, fz] N)")
    point = (_point_on_plank(doc, fields["at"], f"{key}.at", plank, units, tolerance)
             if "at" in fields else None)
    if "mass" in fields:
        mass = _quantity(doc, fields["mass"], f"{key}.mass", 0.0, tol.MAX_MASS, unit="kg")
        return Load.of_mass(plank.id, mass, point, spread)
    force = _vector(doc, fields["force"], f"{key}.force", 3, -tol.MAX_FORCE, tol.MAX_FORCE,
                    unit="N")
    return Load(plank.id, force, point, spread=spread)


def _point_on_plank(doc: _Doc, node: Any, key: str, plank: Plank, units: _Units,
                    tolerance: float) -> tuple[float, float, float]:
    """m: a world point that lies on ``plank`` within ``tolerance`` (m) on every local axis."""
    point = _point(doc, node, key, units)
    local = plank.to_local(np.asarray(point, dtype=float))
    outside = np.abs(local) - plank.half_extents
    axis = int(np.argmax(outside))
    if outside[axis] > tolerance + tol.ON_PLANK_EPS:
        shown = ", ".join(plain_number(c / units.scale, 6) for c in point)
        doc.fail(key, f"point ({shown}) is not on plank {_quote(plank.id)}: "
                      f"{plain_number(outside[axis] / units.scale)} {units.name} beyond its "
                      f"{_AXES[axis]} (tolerance {plain_number(tolerance / units.scale, 6)} "
                      f"{units.name})")
    return point
