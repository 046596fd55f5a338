"""The ``material`` of a design file and a plank's own ``material`` (contract section 1),
part of step 3 of reading a design: file units -> SI, each value range-checked.

Top level: every key of ``MATERIAL_KEYS``; the defaults (SI) are ``Material``'s, with their
sources in ``tolerances`` and the README.  A plank's ``material`` sets the keys that are
properties of the plank (``PLANK_MATERIAL_KEYS``: thickness, density, the elastic and
strength values); the nails' keys and the friction with the ground belong to the
top-level ``material`` and are refused there with a line saying so.

Units are the same in both places: lengths in the file's unit, density kg/m^3, moduli and
strength N/mm^2, nail stiffnesses N/mm per nail, the rest plain numbers.
"""

from __future__ import annotations

from typing import Any

from furncheck import tolerances as tol
from furncheck.design.model import Material
from furncheck.design.source import _child, _quote
from furncheck.design.values import _Doc, _quantity, _Units, _unknown_key_message
from furncheck.errors import DesignError

MATERIAL_KEYS = ("thickness", "density", "nail_spacing", "nail_pull", "nail_shear", "friction",
                 "elastic_modulus", "shear_modulus", "bending_strength", "creep", "sag_limit",
                 "nail_slip", "nail_withdrawal")
PLANK_MATERIAL_KEYS = ("thickness", "density", "elastic_modulus", "shear_modulus",
                       "bending_strength", "creep", "sag_limit")
"""The material keys that are properties of a plank, which a plank may set itself."""

_SIGNIFICANT_DIGITS = 12
"""Digits a value keeps when written back in file units (as ``write`` does for lengths)."""
_LENGTH = None
"""``_RANGES`` scale of a length: the file's unit."""
_RANGES: dict[str, tuple[float, float, float | None, str, bool]] = {
    # key: (low SI, high SI, SI per file unit (_LENGTH: the file's length unit), unit shown,
    #       must be > 0)
    "thickness": (tol.MIN_LENGTH, tol.MAX_LENGTH, _LENGTH, "", True),
    "density": (0.0, tol.MAX_DENSITY, 1.0, "kg/m^3", True),
    "nail_spacing": (tol.MIN_LENGTH, tol.MAX_LENGTH, _LENGTH, "", True),
    "nail_pull": (0.0, tol.MAX_NAIL_CAPACITY, 1.0, "N", True),
    "nail_shear": (0.0, tol.MAX_NAIL_CAPACITY, 1.0, "N", True),
    "friction": (0.0, tol.MAX_FRICTION, 1.0, "", False),
    "elastic_modulus": (0.0, tol.MAX_MODULUS, 1e6, "N/mm^2", True),
    "shear_modulus": (0.0, tol.MAX_MODULUS, 1e6, "N/mm^2", True),
    "bending_strength": (0.0, tol.MAX_MODULUS, 1e6, "N/mm^2", True),
    "creep": (0.0, tol.MAX_CREEP, 1.0, "", False),
    "sag_limit": (0.0, tol.MAX_SAG_LIMIT, 1.0, "", True),
    "nail_slip": (0.0, tol.MAX_NAIL_STIFFNESS, 1e3, "N/mm", True),
    "nail_withdrawal": (0.0, tol.MAX_NAIL_STIFFNESS, 1e3, "N/mm", True),
}


def design_material(doc: _Doc, top: dict, units: _Units) -> Material:
    """The top-level ``material``; ``Material``'s defaults for the keys it does not give."""
    if "material" not in top:
        return Material()
    fields = doc.mapping(top["material"], "material")
    return Material(**_values(doc, fields, "material", MATERIAL_KEYS, units))


def plank_material(doc: _Doc, node: Any, key: str, units: _Units) -> dict[str, float]:
    """A plank's ``material`` at key path ``key``: {key: SI value} in ``PLANK_MATERIAL_KEYS``
    order.  A nail key or friction is refused: it is not a property of one plank."""
    fields = doc.mapping(node, key)
    if not fields:
        doc.fail(key, "an empty material: give the plank's own values, e.g. "
                      "{elastic_modulus: 11000, density: 600}, or leave it out")
    return _values(doc, fields, key, PLANK_MATERIAL_KEYS, units)


def _values(doc: _Doc, fields: dict, parent: str, names: tuple[str, ...],
            units: _Units) -> dict[str, float]:
    """{name: SI value} of each of ``names`` that ``fields`` gives (``_value``), in that
    order.  Every problem of ``fields``, in the order they are written (a key that is
    not one of ``names``: the nails' and the ground's keys in a plank's material refused
    with a line saying where they belong, any other unknown; a value out of range, or no
    number), is raised together, the first with the others as its ``more``: a material
    written with several mistakes is told of all of them at once."""
    problems, values = [], {}
    for name, node in fields.items():
        where = _child(parent, name)
        if name in MATERIAL_KEYS and name not in names:
            what = "the ground's friction" if name == "friction" else "a property of the nails"
            problems.append(doc.error(where, f"{_quote(name)} is {what}, not of one plank: "
                                             f"set it in the top-level material"))
        elif name not in names:
            problems.append(doc.error(where, _unknown_key_message(name, names)))
        else:
            try:
                values[name] = _value(doc, node, parent, name, units)
            except DesignError as error:
                problems.extend((error, *error.more))
    if problems:
        first, *rest = problems
        first.more = tuple(rest)
        raise first
    return {name: values[name] for name in names if name in values}


def material_entry(values: dict[str, float], scale: float) -> dict[str, float]:
    """Material values (SI) as a design file writes them: lengths in the file's unit
    (``scale`` m each), moduli N/mm^2, nail stiffnesses N/mm, rounded to 12 significant
    digits (a unit conversion's round-off dropped); the inverse of ``_value``."""
    entry = {}
    for name, value in values.items():
        per_unit = _RANGES[name][2]
        if per_unit is _LENGTH or per_unit != 1.0:
            per_unit = scale if per_unit is _LENGTH else per_unit
            value = float(f"{value / per_unit:.{_SIGNIFICANT_DIGITS}g}")
        entry[name] = value
    return entry


def _value(doc: _Doc, node: Any, parent: str, name: str, units: _Units) -> float:
    low, high, scale, unit, positive = _RANGES[name]
    if scale is _LENGTH:
        scale, unit = units.scale, units.name
    return _quantity(doc, node, f"{parent}.{name}", low, high, scale, unit, positive)
