"""Exports: coloured plank meshes (GLB, OBJ + MTL), design views and the force-space plot.

Meshes are loaded back with trimesh and checked against hand-computed boxes (the stool's
bounding box, a plank's volume length x width x thickness), glTF's metres and Y-up, and
the colour scale; pictures are decoded and checked as real images whose pixels say
valid or invalid; the plot through its figure (what is drawn, from which numbers).
"""

from __future__ import annotations

import dataclasses
import io
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from furncheck.check import check_design
from furncheck.design import Design, load_design, parse_design
from furncheck.design.model import with_model
from furncheck.export import ExportUnavailable, force_space_picture, plot_force_space
from furncheck.export.colours import UTILIZATION_STOPS, utilization_rgb
from furncheck.export.deflection import axis_curves, deflected_shape
from furncheck.export.errors import EXPORT_HINT
from furncheck.export.findings import changed_planks, plank_utilization
from furncheck.export.meshes import srgb_to_linear, write_meshes
from furncheck.result import CaseResult, DesignReport
from furncheck.tolerances import GRAVITY

trimesh = pytest.importorskip("trimesh")
pytest.importorskip("matplotlib")
Image = pytest.importorskip("PIL.Image")

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


def y_up(bounds) -> np.ndarray:
    """glTF's frame from the design's: x stays, y = design z, z = -design y (so the
    design's low and high y swap ends)."""
    (x0, y0, z0), (x1, y1, z1) = bounds
    return np.array([[x0, z0, -y1], [x1, z1, -y0]])


def plank_geometries(scene) -> dict:
    """The plank boxes of a loaded scene (outlines are paths), by name."""
    return {name: geometry for name, geometry in scene.geometry.items()
            if isinstance(geometry, trimesh.Trimesh)}


def mesh_bounds(scene) -> np.ndarray:
    """Bounds of the plank boxes in the scene frame (outlines left out)."""
    corners = []
    for node in scene.graph.nodes_geometry:
        transform, name = scene.graph[node]
        geometry = scene.geometry[name]
        if isinstance(geometry, trimesh.Trimesh):
            corners.append(trimesh.transform_points(geometry.vertices, transform))
    corners = np.concatenate(corners)
    return np.array([corners.min(axis=0), corners.max(axis=0)])


# --- the colour scale -------------------------------------------------------------------

def test_colour_scale_by_hand() -> None:
    """Linear in RGB between the stops: 0.25 is halfway from green (0.16, 0.62, 0.24) to
    yellow (0.96, 0.80, 0.14), i.e. (0.56, 0.71, 0.19); past 1.5 the darkest red stays;
    no utilization is grey."""
    assert utilization_rgb(0.25) == pytest.approx((0.56, 0.71, 0.19))
    assert utilization_rgb(1.0) == pytest.approx(UTILIZATION_STOPS[2][1])
    assert utilization_rgb(7.0) == utilization_rgb(1.5) == UTILIZATION_STOPS[-1][1]
    assert utilization_rgb(None) == (0.72, 0.72, 0.72)
    # sRGB 0.5 -> linear ((0.5 + 0.055) / 1.055) ** 2.4 = 0.2140; 0.04 -> 0.04 / 12.92
    assert srgb_to_linear([0.5, 0.04]) == pytest.approx([0.214041, 0.003096], abs=1e-6)


# --- meshes -----------------------------------------------------------------------------

@pytest.mark.parametrize("path", CATALOG, ids=lambda path: path.stem)
def test_every_catalog_mesh_loads_back_with_planks_bounds_and_colours(path: Path,
                                                                      tmp_path: Path) -> None:
    """GLB: one closed outward box per plank, named by its id, volume length x width x
    thickness in m^3, bounds the corners in metres turned Y-up, base colour the linear
    form of the plank's utilization colour.  OBJ: the same boxes in the file's unit, z up,
    each with the material of its id, Kd the sRGB colour."""
    design = load_design(str(path))
    report = check_design(design)
    glb, obj, mtl = write_meshes(design, tmp_path / path.stem, report)
    assert [Path(glb).suffix, Path(obj).suffix, Path(mtl).suffix] == [".glb", ".obj", ".mtl"]
    used = plank_utilization(report, design.planks)
    corners = np.concatenate([p.corners for p in design.planks])
    box = [corners.min(axis=0), corners.max(axis=0)]

    scene = trimesh.load(glb, file_type="glb")
    boxes = plank_geometries(scene)
    assert list(boxes) == [p.id for p in design.planks]
    for plank in design.planks:
        mesh = boxes[plank.id]
        assert mesh.vertices.shape == (8, 3) and mesh.faces.shape == (12, 3)
        assert mesh.is_watertight and mesh.is_winding_consistent
        assert mesh.volume == pytest.approx(plank.volume, rel=1e-5)        # float32
        expected = np.round(255 * np.array(srgb_to_linear(utilization_rgb(used[plank.id]))))
        np.testing.assert_allclose(mesh.visual.material.baseColorFactor[:3], expected, atol=1)
    np.testing.assert_allclose(mesh_bounds(scene), y_up(box), atol=1e-6)
    assert scene.metadata["units"] == design.units

    loaded = trimesh.load(obj, file_type="obj", process=False, split_object=True,
                          group_material=False)
    objects = plank_geometries(loaded)
    assert len(objects) == len(design.planks)
    np.testing.assert_allclose(mesh_bounds(loaded), np.array(box) / design.unit_scale,
                               atol=1e-6)
    for plank in design.planks:
        colour = next(m for m in objects.values()
                      if m.visual.material.name == plank.id).visual.material.diffuse
        expected = np.round(255 * np.array(utilization_rgb(used[plank.id])))
        np.testing.assert_allclose(colour[:3], expected, atol=1)


def test_stool_and_metre_table_bounds_by_hand(tmp_path: Path) -> None:
    """The stool: seat 400 x 300 with its top at 450 mm, feet at z = 0; the metre table:
    (-0.3, -0.2, 0) .. (0.3, 0.2, 0.506) m.  GLB in metres Y-up, OBJ in the file unit."""
    stool = load_design(str(DESIGNS / "stool.yaml"))
    for design, file_box, metres in [
            (stool, [[-200, -150, 0], [200, 150, 450]], [[-0.2, -0.15, 0], [0.2, 0.15, 0.45]]),
            (metre_table(), [[-0.3, -0.2, 0], [0.3, 0.2, 0.506]],
             [[-0.3, -0.2, 0], [0.3, 0.2, 0.506]])]:
        glb, obj, _ = write_meshes(design, tmp_path / design.name)
        np.testing.assert_allclose(mesh_bounds(trimesh.load(glb, file_type="glb")),
                                   y_up(metres), atol=1e-6)
        np.testing.assert_allclose(mesh_bounds(trimesh.load(obj, file_type="obj",
                                                            process=False)),
                                   file_box, atol=1e-9)


def test_marked_planks_carry_their_mark(tmp_path: Path) -> None:
    """Moving the stool's rung and adding a plank: the rung is 'changed', the new plank
    'added' (``changed_planks``); the GLB nodes say so in their extras and carry an
    outline (a path), the OBJ says so and lists the 12 box edges of each as lines."""
    stool = load_design(str(DESIGNS / "stool.yaml"))
    rung = dataclasses.replace(stool.planks[3], center=(0.0, 0.0, 0.2))
    extra = dataclasses.replace(stool.planks[3], id="brace", center=(0.0, 0.0, 0.3))
    moved = dataclasses.replace(stool, planks=(*stool.planks[:3], rung, extra))
    marks = changed_planks(stool, moved)
    assert marks == {"rung": "changed", "brace": "added"}
    glb, obj, mtl = write_meshes(moved, tmp_path / "moved", check_design(moved), marks)
    scene = trimesh.load(glb, file_type="glb")
    assert len(plank_geometries(scene)) == 5
    paths = [g for g in scene.geometry.values() if not isinstance(g, trimesh.Trimesh)]
    assert len(paths) == 2
    text = Path(obj).read_text()
    assert "# rung: changed" in text and "# brace: added" in text
    assert sum(line.startswith("l ") for line in text.splitlines()) == 24
    assert "changed" in Path(mtl).read_text()
    import json
    import struct

    data = Path(glb).read_bytes()
    (length,) = struct.unpack("<I", data[12:16])
    nodes = {node["name"]: node for node in json.loads(data[20:20 + length])["nodes"]}
    assert nodes["rung"]["extras"]["mark"] == "changed"
    assert nodes["brace"]["extras"]["mark"] == "added"
    assert "mark" not in nodes["seat"]["extras"]


def test_a_plank_named_like_the_scene_root_keeps_its_name(tmp_path: Path) -> None:
    """trimesh calls a scene's root 'world'; a plank may be called that too."""
    stool = load_design(str(DESIGNS / "stool.yaml"))
    world = dataclasses.replace(stool.planks[0], id="world")
    design = dataclasses.replace(stool, planks=(world, *stool.planks[1:]))
    glb = trimesh.load(write_meshes(design, tmp_path / "stool")[0], file_type="glb")
    assert list(plank_geometries(glb)) == ["world", "leg_l", "leg_r", "rung"]


def test_written_meshes_are_byte_identical(tmp_path: Path) -> None:
    design = load_design(str(DESIGNS / "chair-tilted.yaml"))
    report = check_design(design)
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    first = write_meshes(design, tmp_path / "a" / "chair", report)
    second = write_meshes(design, tmp_path / "b" / "chair", report)
    for one, other in zip(first, second):
        assert Path(one).read_bytes() == Path(other).read_bytes()


def test_importing_the_package_loads_no_heavy_module() -> None:
    code = ("import sys, furncheck.export, furncheck.export.suggestions; "
            "print(sorted(m for m in ('trimesh', 'matplotlib') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == "[]"


# --- deflection -------------------------------------------------------------------------

def test_hermite_midpoint_by_hand() -> None:
    """One element 1 m along x, ends displaced (0, 0, -1) and (0, 0, -3) mm, turned
    theta_a = (0, 0.01, 0) and theta_b = (0, -0.01, 0) rad.  The slopes du/ds = theta x e
    are (0, 0, -0.01) and (0, 0, 0.01); at the middle the Hermite weights are 1/2, 1/8,
    1/2, -1/8: w = -0.5 - 1.5 + (1/8)(-10) - (1/8)(10) = -4.5 mm (design in mm)."""
    design = SimpleNamespace(unit_scale=0.001,
                             planks=[SimpleNamespace(id="shelf")])
    beams = SimpleNamespace(nodes=np.array([[0, 1]]), plank=np.array([0]),
                            node_s=np.array([-0.5, 0.5]))
    model = SimpleNamespace(beams=beams, node_points=np.array([[0.0, 0, 0], [1.0, 0, 0]]),
                            planks=(0,))
    q = np.array([0, 0, -0.001, 0, 0.01, 0, 0, 0, -0.003, 0, -0.01, 0])
    shape = axis_curves(design, model, "default", q)
    (plank, points, moves), = shape.curves
    middle = len(points) // 2                     # an odd number of samples: the middle
    xi = (points[:, 0] + 0.0) / 1000.0
    expected = -1 * (1 - 3 * xi ** 2 + 2 * xi ** 3) - 3 * (3 * xi ** 2 - 2 * xi ** 3) \
        - 10 * (xi - 2 * xi ** 2 + xi ** 3) + 10 * (xi ** 3 - xi ** 2)
    np.testing.assert_allclose(moves[:, 2], expected, atol=1e-9)
    assert xi[middle] == pytest.approx(0.5) and moves[middle, 2] == pytest.approx(-4.5)
    assert shape.where == "shelf" and shape.largest == pytest.approx(abs(moves[:, 2]).max())


def test_stool_seat_deflects_by_its_sag() -> None:
    """The elastic stool's seat sags 3.67 mm (README, measured from the line through its
    supports); its largest displacement adds what its supports move, which on two stiff
    legs is a few percent at most: sag <= largest <= 1.1 sag.  Rigid planks have none."""
    stool = load_design(str(DESIGNS / "stool.yaml"))
    report = check_design(stool)
    sag = next(p.sag for p in report.cases[0].planks if p.id == "seat")
    shape = deflected_shape(stool, "default")
    assert shape.where == "seat" and sag <= shape.largest <= 1.1 * sag
    assert deflected_shape(with_model(stool, "rigid"), "default") is None


# --- design views -----------------------------------------------------------------------

def decoded(data: bytes) -> np.ndarray:
    assert data.startswith(PNG_MAGIC)
    image = Image.open(io.BytesIO(data))
    assert 400 <= image.width <= 2400 and 300 <= image.height <= 1200
    return np.asarray(image.convert("RGB"), dtype=int)


def reddish(pixels: np.ndarray) -> int:
    """Pixels of the failing end of the scale (red, dark red), not of green or yellow."""
    red, green, blue = pixels[..., 0], pixels[..., 1], pixels[..., 2]
    return int(np.sum((red > 60) & (red > 2.5 * green) & (red > 2.5 * blue)))


def test_views_of_a_valid_and_an_invalid_stool_differ_where_it_fails() -> None:
    """The rigid stool (worst joint 23 %: all green to yellow) and the same stool with
    ten times the load (its joints fail): the same planks, the same view, but the
    invalid one is red (planks past capacity, failing joints marked) where the valid one
    has no red at all (the colour bar below the drawing left out)."""
    from furncheck.export.views import PANEL_SIZE, design_view_png

    stool = with_model(load_design(str(DESIGNS / "stool.yaml")), "rigid")
    heavy_cases = tuple(dataclasses.replace(case, loads=tuple(
        dataclasses.replace(load, force=tuple(10 * f for f in load.force),
                            mass=10 * load.mass if load.mass else None)
        for load in case.loads)) for case in stool.load_cases)
    heavy = dataclasses.replace(stool, load_cases=heavy_cases)
    valid, invalid = check_design(stool), check_design(heavy)
    assert valid.valid and not invalid.valid
    pictures = [decoded(design_view_png(design, report))
                for design, report in ((stool, valid), (heavy, invalid))]
    assert pictures[0].shape == pictures[1].shape
    drawing = int(pictures[0].shape[0] * PANEL_SIZE[1] / (PANEL_SIZE[1] + 0.55))
    assert reddish(pictures[0][:drawing]) == 0
    assert reddish(pictures[1][:drawing]) > 2000
    assert np.mean(np.any(pictures[0] != pictures[1], axis=2)) > 0.02


@pytest.mark.parametrize("path", CATALOG, ids=lambda path: path.stem)
def test_every_catalog_view_is_an_image(path: Path) -> None:
    """A real picture of sensible size that is not blank: the planks cover part of it."""
    from furncheck.export.views import design_view_png

    design = load_design(str(path))
    pixels = decoded(design_view_png(design, check_design(design)))
    not_white = np.mean(np.any(pixels < 235, axis=2))
    assert 0.03 < not_white < 0.9


def test_suggestion_view_has_two_panels_and_the_change_outlined() -> None:
    """Before | after, twice as wide as one design's view; the moved rung is outlined in
    the 'changed' blue in both panels."""
    from furncheck.export.colours import MARK_RGB
    from furncheck.export.views import design_view_png, suggestion_view_png

    stool = with_model(load_design(str(DESIGNS / "stool.yaml")), "rigid")
    rung = dataclasses.replace(stool.planks[3], center=(0.0, 0.0, 0.2))
    moved = dataclasses.replace(stool, planks=(*stool.planks[:3], rung))
    one = decoded(design_view_png(stool, check_design(stool)))
    both = decoded(suggestion_view_png(stool, check_design(stool), moved, check_design(moved),
                                       "stool, suggestion 1: raise rung", {"rung": "changed"}))
    assert both.shape[1] == 2 * one.shape[1]
    blue = np.round(255 * np.array(MARK_RGB["changed"])).astype(int)
    near = np.all(np.abs(both - blue) <= 40, axis=2)
    half = both.shape[1] // 2
    assert near[:, :half].sum() > 50 and near[:, half:].sum() > 50


def test_a_hidden_added_part_is_drawn_in_hidden_lines() -> None:
    """A rail added right under the stool's seat is hidden by it in the oblique view: its
    box edges are drawn dashed over everything in the 'added' purple, so the after panel
    has purple pixels (the before panel, without it, has none).  A box has 12 edges, each
    joining two corners that differ in one sign."""
    from furncheck.export.colours import MARK_RGB
    from furncheck.export.projection import BOX_EDGES
    from furncheck.export.views import suggestion_view_png

    assert len(BOX_EDGES) == 12 and all(bin(a ^ b).count("1") == 1 for a, b in BOX_EDGES)
    stool = with_model(load_design(str(DESIGNS / "stool.yaml")), "rigid")
    seat = stool.plank("seat")
    rail = dataclasses.replace(seat, id="rail", width=0.05, center=(
        seat.center[0], seat.center[1], seat.center[2] - 0.5 * seat.thickness - 0.026),
        rotation=(90.0, 0.0, 0.0))
    added = dataclasses.replace(stool, planks=(*stool.planks, rail))
    both = decoded(suggestion_view_png(stool, check_design(stool), added,
                                       check_design(added), "stool: add a rail",
                                       {"rail": "added"}))
    purple = np.round(255 * np.array(MARK_RGB["added"])).astype(int)
    near = np.all(np.abs(both - purple) <= 30, axis=2)
    half = both.shape[1] // 2
    assert near[:, half:].sum() > 30 and near[:, :half].sum() == 0


def test_before_and_after_share_the_deflection_scale() -> None:
    """The deflected shapes of both panels are magnified alike (one factor from the
    larger deflection), so a suggestion that halves the sag reads as half."""
    from furncheck.export.deflection import Deflection
    from furncheck.export.views import Panel, _magnification, _shared_magnification

    stool = load_design(str(DESIGNS / "stool.yaml"))
    big = Panel(stool, None, Deflection("default", (), 2.0, "seat"), {}, "before")
    small = Panel(stool, None, Deflection("default", (), 0.2, "seat"), {}, "after")
    shared = _shared_magnification([big, small])
    extent = float(np.ptp(np.concatenate([p.corners for p in stool.planks]), axis=0).max())
    assert shared == _magnification(2.0, extent / stool.unit_scale)
    assert shared == _shared_magnification([big])
    assert _shared_magnification([small]) > shared


# --- force-space plot -------------------------------------------------------------------

@pytest.fixture(scope="module")
def tipping_change() -> tuple[DesignReport, DesignReport]:
    """bench-tips (a person on the overhanging end: it lifts off its left panel) and the
    same load on the bench with its panels moved out to x = +-520 (stable); rigid."""
    tips = with_model(load_design(str(DESIGNS / "bench-tips.yaml")), "rigid")
    bench = with_model(load_design(str(DESIGNS / "bench.yaml")), "rigid")
    fixed = dataclasses.replace(bench, name=tips.name, load_cases=tips.load_cases)
    return check_design(tips), check_design(fixed)


def test_plot_draws_joints_and_contacts_once_each(tipping_change) -> None:
    """Two panels; the heading names the change and the verdicts; before (lift-off) the
    joints do not count, so no rings; after, one dot per joint at (pull / capacity,
    shear / capacity); contacts: rings before at their (N, |T|) (the left panel's four
    feet would pull: N < 0), dots after (none pulls)."""
    before, after = tipping_change
    picture = force_space_picture(before, after, 0.5, "suggestion 1: move leg_r")
    joints, contacts = "joints", "contacts"
    texts = picture.texts
    assert texts[0] == "bench-tips: suggestion 1: move leg_r"
    assert texts[1].startswith("before: INVALID (lift-off in 'default')  ->  after: valid.")

    def points(panel: str, filled: bool) -> np.ndarray:
        """The markers of a panel (its artists' gid), rings or dots, in data units."""
        lines = [line for line in picture.figure.artists if line.get_gid() == panel
                 and getattr(line, "get_marker", lambda: None)() == "o"
                 and (line.get_markerfacecolor() != "none") == filled]
        return np.concatenate([line.get_xydata() for line in lines]) if lines else \
            np.zeros((0, 2))

    after_joints = after.cases[0].joints
    assert len(points(joints, filled=False)) == 0
    np.testing.assert_allclose(
        sorted(map(tuple, points(joints, filled=True))),
        sorted((max(j.pull / j.pull_capacity, -1.0), j.shear / j.shear_capacity)
               for j in after_joints))
    rings = points(contacts, filled=False)
    normals = sorted(c.pressing for c in before.cases[0].contacts)
    assert sorted(rings[:, 0]) == pytest.approx(normals)
    assert np.sum(rings[:, 0] < 0) == 4
    assert np.all(points(contacts, filled=True)[:, 0] >= 0)    # pressing or lifted a hair


def test_plot_labels_only_the_worst_of_many() -> None:
    """The cabinet: 88 joints and 60 contacts, at most 3 of each labelled."""
    design = load_design(str(DESIGNS / "cabinet-28.yaml"))
    report = check_design(design)
    assert sum(len(c.contacts) for c in report.cases[:1]) >= 50
    picture = force_space_picture(report, report)
    labelled = [text for text in picture.texts if ("% ('" in text or "of mu N" in text)
                and not text.startswith("contacts:")]
    joints = [text for text in labelled if "/" in text.split()[0]]
    assert len(joints) == 3 and len(labelled) - len(joints) == 3


def test_friction_budget_by_hand(tipping_change) -> None:
    """table-slides (rigid), case shove: 110 N sideways on a table of weight W (its
    planks' masses x g; nothing else on it): the ground's friction must sum to 110 N and
    its normal forces to W, so the budget is 110 / (0.5 W), beyond 100 %: it slides."""
    design = with_model(load_design(str(DESIGNS / "table-slides.yaml")), "rigid")
    report = check_design(design)
    weight = sum(design.plank_mass(p) for p in design.planks) * GRAVITY
    budget = 100 * 110.0 / (0.5 * weight)
    assert budget > 100
    picture = force_space_picture(report, report, 0.5)
    title = next(text for text in picture.texts if text.startswith("contacts:"))
    assert title.endswith(f"friction used {budget:.1f} % -> {budget:.1f} % ('shove')")


def test_plot_png_is_deterministic(tipping_change, tmp_path: Path) -> None:
    before, after = tipping_change
    first = plot_force_space(before, after, tmp_path / "one.png")
    second = plot_force_space(before, after, tmp_path / "two.png")
    assert first == str(tmp_path / "one.png")
    data = Path(first).read_bytes()
    decoded(data)
    assert b"Software" not in data and b"matplotlib" not in data
    assert data == Path(second).read_bytes()


def test_plot_of_a_case_without_forces(tipping_change) -> None:
    """Reports with only a mechanism case (no joint or contact forces) say so."""
    loose = CaseResult("loose", durable=True, stable=False, joints=(), contacts=(),
                       stability="mechanism")
    report = dataclasses.replace(tipping_change[0], cases=(loose,))
    texts = force_space_picture(report, report).texts
    assert texts.index("no joint forces") < texts.index("no contact forces (no equilibrium)")


def test_plot_of_non_slip_pads_reads_each_report_by_its_own_friction() -> None:
    """A bench sliding on tiles (mu 0.15) and the same with non-slip pads (mu 0.2): the
    contacts panel judges the after report by 0.2 (its heading says 'mu 0.15 -> 0.2'),
    so the friction it uses reads less of its budget than before."""
    from shop_designs import TILE_BENCH

    before = parse_design(TILE_BENCH, "bench.yaml", "yaml")
    after = dataclasses.replace(before, material=dataclasses.replace(before.material,
                                                                     friction=0.2))
    texts = force_space_picture(check_design(before), check_design(after), 0.15,
                                "suggestion 1: pads", 0.2).texts
    heading = next(t for t in texts if t.startswith("contacts: shaded"))
    assert "mu 0.15 -> 0.2;" in heading


def test_plot_needs_load_cases() -> None:
    unreadable = DesignReport(design="broken.yaml", name="broken", valid=None, error="line 1")
    with pytest.raises(ValueError, match="no load case results"):
        force_space_picture(unreadable, unreadable)


def test_pictures_without_matplotlib_raise_export_unavailable(tipping_change,
                                                              monkeypatch: pytest.MonkeyPatch,
                                                              tmp_path: Path) -> None:
    from furncheck.export.views import design_view_png

    monkeypatch.setitem(sys.modules, "matplotlib.figure", None)
    with pytest.raises(ExportUnavailable, match="pip install matplotlib") as caught:
        plot_force_space(*tipping_change, tmp_path / "plot.png")
    assert str(caught.value) == EXPORT_HINT
    with pytest.raises(ExportUnavailable):
        design_view_png(metre_table(), None)
    assert not (tmp_path / "plot.png").exists()
