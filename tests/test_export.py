"""Exports: plank meshes (trimesh) and the force-space plot (matplotlib).

Meshes are checked against hand-computed boxes (the stool's bounding box, a plank's volume
length x width x thickness in the file's unit) and as closed, consistently wound boxes for
every catalog design; files must re-load, name their planks and be byte-identical when
written twice.  The plot is checked through its figure (what is drawn, from which numbers)
and as a deterministic PNG.
"""

from __future__ import annotations

import dataclasses
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from furncheck.check import check_design
from furncheck.design import Design, load_design, parse_design
from furncheck.export import (
    ExportUnavailable,
    design_mesh,
    design_scene,
    force_space_figure,
    plot_force_space,
    write_meshes,
)
from furncheck.export.errors import EXPORT_HINT
from furncheck.result import CaseResult, DesignReport

trimesh = pytest.importorskip("trimesh")
pytest.importorskip("matplotlib")

DESIGNS = Path(__file__).resolve().parents[1] / "designs"
CATALOG = sorted(DESIGNS.glob("*.yaml"))
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"

METRE_TABLE = """
furncheck: 1
name: metre-table
units: m
planks:
  - {id: top, size: [0.6, 0.4], center: [0, 0, 0.5]}
  - {id: leg, size: [0.494, 0.4], center: [0.25, 0, 0.247], rotation: [0, 90, 0]}
"""
"""A top 0.6 x 0.4 x 0.012 m at z = 0.5 on one leg stood on end at x = 0.25 (rotated 90
degrees about y: its length runs along z from 0 to 0.494, its thickness along x from
0.244 to 0.256): bounds (-0.3, -0.2, 0) .. (0.3, 0.2, 0.506) m."""


def metre_table() -> Design:
    return parse_design(METRE_TABLE, "metre-table.yaml", "yaml")


def box_volumes(design: Design) -> list[float]:
    """length x width x thickness of each plank, in the file's unit cubed."""
    return [p.length * p.width * p.thickness / design.unit_scale ** 3 for p in design.planks]


# --- meshes -----------------------------------------------------------------------------

@pytest.mark.parametrize("path", CATALOG, ids=lambda path: path.stem)
def test_every_plank_is_a_closed_outward_box(path: Path) -> None:
    """8 vertices and 12 triangles per plank, watertight and consistently wound, with
    positive volume length x width x thickness (file units): the normals point outward."""
    design = load_design(str(path))
    mesh = design_mesh(design)
    count = len(design.planks)
    assert mesh.vertices.shape == (8 * count, 3) and mesh.faces.shape == (12 * count, 3)
    assert mesh.metadata["planks"] == [p.id for p in design.planks]
    scene = design_scene(design)
    assert list(scene.geometry) == [p.id for p in design.planks]
    for box, volume in zip(scene.geometry.values(), box_volumes(design)):
        assert box.is_watertight and box.is_winding_consistent
        assert box.volume == pytest.approx(volume, rel=1e-9)
    assert mesh.volume == pytest.approx(sum(box_volumes(design)), rel=1e-9)


@pytest.mark.parametrize("path", CATALOG, ids=lambda path: path.stem)
def test_mesh_bounds_are_the_plank_corners_in_file_units(path: Path) -> None:
    design = load_design(str(path))
    corners = np.concatenate([p.corners for p in design.planks]) / design.unit_scale
    bounds = design_mesh(design).bounds
    np.testing.assert_allclose(bounds, [corners.min(axis=0), corners.max(axis=0)],
                               rtol=0, atol=1e-9)


@pytest.mark.parametrize(("design", "expected"), [
    # seat 400 x 300 with its top at 450 mm; panels and rung inside it, feet at z = 0
    (load_design(str(DESIGNS / "stool.yaml")), [[-200, -150, 0], [200, 150, 450]]),
    (metre_table(), [[-0.3, -0.2, 0], [0.3, 0.2, 0.506]]),
], ids=["stool-mm", "table-m"])
def test_mesh_bounds_by_hand(design: Design, expected: list[list[float]]) -> None:
    np.testing.assert_allclose(design_mesh(design).bounds, expected, rtol=0, atol=1e-9)


def test_metre_box_volume_is_in_cubic_metres() -> None:
    """The top: 0.6 x 0.4 x 0.012 = 0.00288 m^3 (a mm design would say 2.88e6 mm^3)."""
    scene = design_scene(metre_table())
    assert scene.geometry["top"].volume == pytest.approx(0.00288, rel=1e-9)
    assert scene.metadata == {"design": "metre-table", "units": "m"}


def test_written_meshes_reload_with_named_planks(tmp_path: Path) -> None:
    """GLB in metres (glTF's unit), OBJ in the file's unit (mm here)."""
    design = load_design(str(DESIGNS / "stool.yaml"))
    written = write_meshes(design, tmp_path / "stool")
    assert written == [str(tmp_path / "stool.glb"), str(tmp_path / "stool.obj")]

    glb = trimesh.load(written[0], file_type="glb")
    assert isinstance(glb, trimesh.Scene)
    assert list(glb.geometry) == ["seat", "leg_l", "leg_r", "rung"]
    for plank, box in zip(design.planks, glb.geometry.values()):
        assert box.vertices.shape == (8, 3) and box.faces.shape == (12, 3)
        np.testing.assert_allclose(box.vertices, plank.corners, atol=1e-7)  # float32, m
    np.testing.assert_allclose(glb.bounds, [[-0.2, -0.15, 0], [0.2, 0.15, 0.45]], atol=1e-7)
    assert glb.metadata["units"] == "mm"

    text = Path(written[1]).read_text(encoding="utf-8")
    lines = text.splitlines()
    assert lines[0] == "# furncheck plank mesh, lengths in mm"
    assert [line[2:] for line in lines if line.startswith("o ")] == \
        ["seat", "leg_l", "leg_r", "rung"]
    assert sum(line.startswith("v ") for line in lines) == 32
    assert sum(line.startswith("f ") for line in lines) == 48
    obj = trimesh.load(written[1], file_type="obj", process=False)
    assert obj.is_watertight and obj.volume == pytest.approx(sum(box_volumes(design)))


def test_a_plank_named_like_the_scene_root_keeps_its_name(tmp_path: Path) -> None:
    """trimesh calls a scene's root 'world' unless told otherwise; a plank may too."""
    stool = load_design(str(DESIGNS / "stool.yaml"))
    world = dataclasses.replace(stool.planks[0], id="world")
    design = dataclasses.replace(stool, planks=(world, *stool.planks[1:]))
    glb = trimesh.load(write_meshes(design, tmp_path / "stool")[0], file_type="glb")
    assert list(glb.geometry) == ["world", "leg_l", "leg_r", "rung"]


def test_written_meshes_are_byte_identical(tmp_path: Path) -> None:
    design = load_design(str(DESIGNS / "chair-tilted.yaml"))
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    first = write_meshes(design, tmp_path / "a" / "chair")
    second = write_meshes(design, tmp_path / "b" / "chair")
    for one, other in zip(first, second):
        assert Path(one).read_bytes() == Path(other).read_bytes()


def test_meshes_without_trimesh_raise_export_unavailable(monkeypatch: pytest.MonkeyPatch,
                                                         tmp_path: Path) -> None:
    monkeypatch.setitem(sys.modules, "trimesh", None)   # makes ``import trimesh`` fail
    design = metre_table()
    for export in (lambda: design_mesh(design), lambda: write_meshes(design, tmp_path / "x")):
        with pytest.raises(ExportUnavailable) as caught:
            export()
        assert str(caught.value) == EXPORT_HINT == \
            "meshes and plots need the export extra: pip install 'furncheck[export]'"
        assert caught.value.module == "trimesh"
    assert list(tmp_path.iterdir()) == []


def test_importing_the_package_loads_neither_trimesh_nor_matplotlib() -> None:
    code = ("import sys, furncheck.export; "
            "print(sorted(m for m in ('trimesh', 'matplotlib') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == "[]"


# --- force-space plot -------------------------------------------------------------------

@pytest.fixture(scope="module")
def tipping_change() -> tuple[DesignReport, DesignReport]:
    """bench-tips (a person on the overhanging end: it lifts off its left panel) and the
    same load on the bench with its panels moved out to x = +-520 (stable)."""
    tips = load_design(str(DESIGNS / "bench-tips.yaml"))
    bench = load_design(str(DESIGNS / "bench.yaml"))
    fixed = dataclasses.replace(bench, name=tips.name, load_cases=tips.load_cases)
    return check_design(tips), check_design(fixed)


def test_plot_draws_both_force_spaces(tipping_change) -> None:
    before, after = tipping_change
    assert [c.stability for c in before.cases] == ["lift-off"]
    assert [c.stability for c in after.cases] == ["stable"]
    figure = force_space_figure(before, after)
    durability, stability = figure.axes[:2]
    assert "bench-tips" in figure.get_suptitle() and "'default'" in durability.get_title()
    assert stability.get_title().endswith("stability (lift-off -> stable)")

    # stability: one bar per contact before and after, heights = ground normal forces
    heights = sorted(round(bar.get_height(), 6) for bar in stability.patches)
    normals = [contact.force[2] for case in (before.cases[0], after.cases[0])
               for contact in case.contacts]
    assert heights == sorted(round(normal, 6) for normal in normals)
    assert sum(height < 0 for height in heights) == 4   # the left panel's feet lift

    # durability: an arrow per joint that moved (same plank pair), the worst 3 labelled
    arrows = [text for text in durability.texts if text.get_text() == ""]
    labels = {text.get_text() for text in durability.texts if text.get_text()}
    assert len(arrows) == 4
    assert len(labels) == 3 and all("/" in label for label in labels)


def test_plot_png_is_deterministic(tipping_change, tmp_path: Path) -> None:
    before, after = tipping_change
    first = plot_force_space(before, after, tmp_path / "one.png")
    second = plot_force_space(before, after, tmp_path / "two.png")
    assert first == str(tmp_path / "one.png")
    data = Path(first).read_bytes()
    assert data.startswith(PNG_MAGIC)
    assert b"Software" not in data and b"matplotlib" not in data
    assert data == Path(second).read_bytes()


def test_plot_of_no_change(tipping_change) -> None:
    """before == after: every joint's two markers coincide, so no arrows; the bars pair
    up with equal heights."""
    report = tipping_change[0]
    figure = force_space_figure(report, report)
    assert not [text for text in figure.axes[0].texts if text.get_text() == ""]
    heights = [bar.get_height() for bar in figure.axes[1].patches]
    assert heights[0::2] == heights[1::2] == [c.force[2] for c in report.cases[0].contacts]
    assert figure.axes[1].get_title().endswith("(lift-off -> lift-off)")


def test_plot_of_a_case_without_forces(tipping_change) -> None:
    """A case with neither joint nor contact forces (a mechanism) still gets its row,
    saying so; a case only one report has is drawn for that one alone."""
    before, after = tipping_change
    loose = CaseResult("loose", durable=True, stable=False, joints=(), contacts=(),
                       stability="mechanism")
    figure = force_space_figure(before, dataclasses.replace(after, cases=(*after.cases, loose)))
    assert len(figure.axes) == 4
    assert [text.get_text() for text in figure.axes[2].texts] == ["no joint forces"]
    assert [text.get_text() for text in figure.axes[3].texts] == \
        ["no contact forces (no equilibrium)"]
    assert figure.axes[3].get_title().endswith("'loose': stability (- -> mechanism)")


def test_plot_needs_load_cases() -> None:
    unreadable = DesignReport(design="broken.yaml", name="broken", valid=None, error="line 1")
    with pytest.raises(ValueError, match="no load case results"):
        force_space_figure(unreadable, unreadable)


def test_plot_without_matplotlib_raises_export_unavailable(tipping_change,
                                                           monkeypatch: pytest.MonkeyPatch,
                                                           tmp_path: Path) -> None:
    monkeypatch.setitem(sys.modules, "matplotlib.figure", None)
    with pytest.raises(ExportUnavailable, match="pip install 'furncheck\\[export\\]'"):
        plot_force_space(*tipping_change, tmp_path / "plot.png")
    assert not (tmp_path / "plot.png").exists()
