"""A plank's own ``material`` (contract section 1): its density, elastic and strength values
reach the self-weight, the beam's stiffness, the sag and stress checks, the reports and the
written design; bad values are one line at the command line.

Hand calculations in the docstrings (g = 9.81 m/s^2, tolerance 2 %); the designs come from
``elastic_designs`` and ``physics_designs`` (geometry described there).
"""

from __future__ import annotations

from dataclasses import replace

import elastic_designs as ed
import physics_designs as pd
import pytest
import yaml
from click.testing import CliRunner

from furncheck.check import check_design
from furncheck.cli.main import main
from furncheck.design import parse_design
from furncheck.design.model import with_model
from furncheck.design.write import design_text
from furncheck.dofs import apply_dof, parse_dof, structure
from furncheck.geometry import analyze

G = pd.G
REL = 0.02
K_SHEAR = 5.0 / 6.0
FLAT_L, FLAT_B, FLAT_T, FLAT_MASS = 800.0, 200.0, 12.0, 10.0


def parsed(design: dict):
    return parse_design(pd.to_text(design), f"{design['name']}.yaml", "yaml")


def plank_of(report, plank: str, case: str = "default"):
    (found,) = [p for p in pd.case_of(report, case).planks if p.id == plank]
    return found


def flat_shelf(shelf_material: dict | None = None, **material_keys) -> dict:
    """``elastic_designs.flat_shelf`` (span 800 mm, 200 x 12, 10 kg spread, pinned on two
    fins; top-level E = 3000, G = 800 N/mm^2) with the shelf's own ``material``."""
    design = ed.flat_shelf(mass=FLAT_MASS, length=FLAT_L, width=FLAT_B, **material_keys)
    if shelf_material:
        design["planks"][0]["material"] = shelf_material
    return design


def flat_sag(elastic_modulus: float) -> float:
    """mm: 5 w L^4 / 384 E I + w L^2 / 8 k G A, w = 98.1 N / 812 mm = 0.120813 N/mm,
    I = 200 x 12^3 / 12 = 28,800 mm^4, k G A = 5/6 x 800 x 2400 = 1.6e6 N:
    E = 3000: 7.4576 + 0.0060 = 7.4636 mm; E = 11000: 2.0339 + 0.0060 = 2.0399 mm."""
    w = FLAT_MASS * G / (FLAT_L + ed.FLAT_FIN_T)
    inertia = FLAT_B * FLAT_T ** 3 / 12.0
    return (5 * w * FLAT_L ** 4 / (384 * elastic_modulus * inertia)
            + w * FLAT_L ** 2 / (8 * K_SHEAR * ed.G_MOD * FLAT_B * FLAT_T))


FLAT_STRESS = (FLAT_MASS * G / (FLAT_L + ed.FLAT_FIN_T) * FLAT_L ** 2 / 8
               / (FLAT_B * FLAT_T ** 2 / 6))
"""N/mm^2: (w L^2 / 8) / (b t^2 / 6) = 9665.0 N mm / 4800 mm^3 = 2.0135, whatever E."""


# --- the model ----------------------------------------------------------------------------------

def test_a_shelf_of_its_own_modulus_sags_by_it():
    """The shelf's own E = 11000 N/mm^2 over fins of the top-level 3000: its sag is
    ``flat_sag(11000)`` = 2.0399 mm, against 7.4636 mm for the MDF shelf (bending part
    3000 / 11000 of it); the same as a design made all of E = 11000 (the pinned fins'
    stiffness does not enter), and the stress is unchanged."""
    mdf = check_design(parsed(flat_shelf()))
    own = check_design(parsed(flat_shelf({"elastic_modulus": 11000})))
    everywhere = check_design(parsed(flat_shelf(elastic_modulus=11000.0)))
    mdf_shelf, own_shelf = plank_of(mdf, "shelf"), plank_of(own, "shelf")
    assert mdf_shelf.sag == pytest.approx(flat_sag(3000.0), rel=REL)
    assert own_shelf.sag == pytest.approx(flat_sag(11000.0), rel=REL)
    assert own_shelf.sag == pytest.approx(plank_of(everywhere, "shelf").sag, rel=1e-3)
    bending_ratio = (own_shelf.sag - 0.0060) / (mdf_shelf.sag - 0.0060)
    assert bending_ratio == pytest.approx(3000.0 / 11000.0, rel=REL)
    assert own_shelf.stress == pytest.approx(FLAT_STRESS, rel=REL)


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_a_plank_of_its_own_density_weighs_by_it(model):
    """The bench, unloaded: seat 800 x 300 x 12 of density 600 (its own), legs 450 x 300 x
    12 of the top-level 750.  Ground reaction = g (600 x 2.88e-3 + 2 x 750 x 1.62e-3) =
    9.81 x (1.728 + 2.430) kg = 40.79 N, where an all-750 bench weighs 9.81 x 4.59 = 45.03 N."""
    design = pd.bench(mass=0.0)
    design["planks"][0]["material"] = {"density": 600}
    report = check_design(with_model(parsed(design), model))
    total = sum(c.force[2] for c in pd.case_of(report).contacts)
    assert total == pytest.approx(40.79, rel=1e-3)
    assert parsed(design).plank_mass(parsed(design).planks[0]) == pytest.approx(1.728)


def test_a_plank_of_lower_strength_is_overstressed():
    """The flat shelf's stress 2.0135 N/mm^2 (``FLAT_STRESS``) against its own bending
    strength 1.8 N/mm^2: utilization 2.0135 / 1.8 = 1.119, overstressed; with the top-level
    22 N/mm^2 it holds (0.092).  The fins report the top-level strength.  (sag_limit 1:
    nothing sags.)"""
    weak = check_design(parsed(flat_shelf({"bending_strength": 1.8}, sag_limit=1.0)))
    strong = check_design(parsed(flat_shelf(sag_limit=1.0)))
    shelf = plank_of(weak, "shelf")
    assert shelf.strength == pytest.approx(1.8)
    assert plank_of(weak, "fin_l").strength == pytest.approx(ed.STRENGTH)
    assert shelf.utilization == pytest.approx(FLAT_STRESS / 1.8, rel=REL)
    assert [(v.kind, v.where) for v in weak.violations] == [("overstressed", "shelf")]
    assert "exceeds its strength 1.8 N/mm^2" in weak.violations[0].message
    assert strong.valid and plank_of(strong, "shelf").utilization == \
        pytest.approx(FLAT_STRESS / ed.STRENGTH, rel=REL)


def test_a_plank_of_its_own_sag_limit_and_creep():
    """The flat shelf (sag 7.4636 mm over 800 mm) with its own sag_limit 200 and creep 0.1:
    allowed 800 / 200 = 4 mm, 7.4636 x 1.1 = 8.21 mm > 4 mm: utilization 2.05, sagging, and
    the message says span / 200 and x 1.1; the fins keep the top-level limit 400."""
    report = check_design(parsed(flat_shelf({"sag_limit": 200, "creep": 0.1},
                                            bending_strength=1000.0)))
    plain = check_design(parsed(flat_shelf(bending_strength=1000.0)))
    shelf = plank_of(report, "shelf")
    assert shelf.sag_allowed == pytest.approx(4.0)
    assert plank_of(plain, "shelf").sag_allowed == pytest.approx(2.0)
    assert plank_of(report, "fin_r").sag_allowed == plank_of(plain, "fin_r").sag_allowed
    assert shelf.utilization == pytest.approx(flat_sag(3000.0) * 1.1 / 4.0, rel=REL)
    (sagging,) = [v for v in report.violations if v.where == "shelf"]
    assert "(x 1.1)" in sagging.message and "(span / 200)" in sagging.message


def test_thickness_in_a_planks_material_is_its_thickness():
    design = flat_shelf()
    own = flat_shelf({"thickness": 18})
    design["planks"][0]["thickness"] = 18
    del own["planks"][0]["thickness"]
    assert parsed(own).planks == parsed(design).planks
    both = flat_shelf({"thickness": 18})
    both["planks"][0]["thickness"] = 18
    assert parsed(both).planks[0].thickness == pytest.approx(0.018)


# --- writing back, moving ----------------------------------------------------------------------

def test_written_design_keeps_a_planks_material():
    design = parsed(flat_shelf({"elastic_modulus": 11000, "density": 600,
                                "bending_strength": 40}))
    text = design_text(design, "yaml")
    entry = yaml.safe_load(text)["planks"][0]
    assert entry["material"] == {"density": 600.0, "elastic_modulus": 11000.0,
                                 "bending_strength": 40.0}
    again = parse_design(text, "again.yaml", "yaml")
    assert again.planks == design.planks
    assert again.material_of(again.planks[0]).elastic_modulus == pytest.approx(11000e6)
    assert replace(check_design(again), design="") == replace(check_design(design), design="")


@pytest.mark.parametrize("dof", ["shelf.length", "shelf.z", "shelf.ry", "fin_l.x"])
def test_an_edited_plank_keeps_its_material(dof):
    """Resized, moved or turned (and its neighbours adjusted), a plank keeps its own
    material."""
    design = parsed(flat_shelf({"elastic_modulus": 11000}))
    design = replace(design, planks=tuple(replace(p, material=(("density", 600.0),))
                                          if p.id != "shelf" else p for p in design.planks))
    moved = apply_dof(design, structure(design, analyze(design)), parse_dof(design, dof), 2.0)
    assert [p.material for p in moved.planks] == [p.material for p in design.planks]
    assert moved.planks != design.planks


# --- bad input at the command line -------------------------------------------------------------

FRAME = """\
furncheck: 1
planks:
  - {id: seat, size: [800, 300], center: [0, 0, 456]}
  - {id: leg_l, size: [450, 300], center: [-350, 0, 225], rotation: [0, -90, 0]}
  - id: leg_r
    size: [450, 300]
    center: [350, 0, 225]
    rotation: [0, -90, 0]
"""
"""A bench; the last plank's own keys go on line 9."""

BAD_MATERIALS = {
    # name -> (text at line 9, key path, message)
    "negative modulus": ("    material: {elastic_modulus: -5}",
                         "planks[2].material.elastic_modulus", "must be positive, got -5 N/mm^2"),
    "unknown key": ("    material: {densty: 600}", "planks[2].material.densty",
                    'unknown key "densty" (did you mean "density"?); allowed keys: thickness, '
                    "density, elastic_modulus, shear_modulus, bending_strength, creep, sag_limit"),
    "nail key": ("    material: {nail_pull: 500}", "planks[2].material.nail_pull",
                 '"nail_pull" is a property of the nails, not of one plank: set it in the '
                 "top-level material"),
    "friction": ("    material: {friction: 0.3}", "planks[2].material.friction",
                 '"friction" is the ground\'s friction, not of one plank'),
    "not a mapping": ("    material: mdf", "planks[2].material",
                      'expected a mapping, got text "mdf"'),
    "empty": ("    material: {}", "planks[2].material", "an empty material"),
    "two thicknesses": ("    thickness: 12\n    material: {thickness: 18}",
                        "planks[2].material.thickness",
                        "thickness 18 mm differs from the plank's thickness: 12 mm; give it once"),
    "too large": ("    material: {density: 1e9}", "planks[2].material.density",
                  "out of range: 1,000,000,000 kg/m^3"),
}


@pytest.mark.parametrize("name", sorted(BAD_MATERIALS))
def test_bad_plank_material_is_one_line_with_key_path_and_line(tmp_path, name):
    text, key, message = BAD_MATERIALS[name]
    path = tmp_path / "bad.yaml"
    path.write_text(FRAME + text + "\n", encoding="utf-8")
    result = CliRunner().invoke(main, ["validate", str(path)])
    assert result.exit_code == 2 and "Traceback" not in result.output
    lines = result.output.splitlines()
    assert len(lines) == 2 and lines[1] == "1 design: 0 valid, 0 invalid, 1 error"
    line = 10 if name == "two thicknesses" else 9
    assert lines[0].startswith(f"{path}: error: line {line}: {key}: "), lines[0]
    assert message in lines[0], lines[0]
