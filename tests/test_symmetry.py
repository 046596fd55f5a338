"""Mirror planks and symmetric suggestions (``suggest.symmetry``).

The stool (designs/stool.yaml) is symmetric about the plane x = 0: its legs at x = -170
and +170 (rotation [0, -90, 0] both: length along z, width along y) are mirror images,
the seat and the rung lie across the plane.  The catalog test checks the written files
with its own mirror test (corners mirrored about the plane x = 0 or y = 0 of the input's
bounding box), not the library's.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
import yaml
from click.testing import CliRunner

from furncheck.check import check_file
from furncheck.cli.main import main
from furncheck.design import load_design
from furncheck.design.load import parse_design
from furncheck.dofs import Dof
from furncheck.suggest.symmetry import broken_pairs, mirror_planes, mirrored_dof

CATALOG = Path(__file__).resolve().parents[1] / "designs"
MODELS = ("rigid", "elastic")


def stool():
    return load_design(str(CATALOG / "stool.yaml"))


def test_the_stool_is_symmetric_about_x_0():
    (plane,) = mirror_planes(stool())
    assert plane.axis == 0 and plane.offset == pytest.approx(0.0, abs=1e-12)
    assert plane.pairs == [("leg_l", "leg_r")]
    assert plane.partner["seat"] == "seat" and plane.partner["rung"] == "rung"
    assert plane.covers(stool())


def test_a_leg_out_of_place_breaks_the_pair():
    """leg_r 5 mm further out (10 x the 0.5 mm tolerance) is no image of leg_l: no plane
    with a pair is left."""
    text = (CATALOG / "stool.yaml").read_text().replace("center: [170, 0, 219]",
                                                        "center: [175, 0, 219]")
    assert mirror_planes(parse_design(text, "stool.yaml", "yaml")) == ()


@pytest.mark.parametrize("kind, image, sign", [
    ("x", "x", -1.0),        # across the plane: opposite (apart / closer)
    ("y", "y", 1.0),         # along the plane: the same
    ("z", "z", 1.0),
    ("rx", "rx", 1.0),       # rotations are axial vectors: about the normal the same,
    ("ry", "ry", -1.0),      # about the other axes opposite
    ("rz", "rz", -1.0),
    ("length", "length", 1.0),
    ("width", "width", 1.0),
])
def test_mirrored_dofs_of_the_legs(kind, image, sign):
    """Mirroring about x = 0 maps (x, y, z) to (-x, y, z): a move along x reverses; a
    turn's axis (an axial vector) maps to -M w = (w_x, -w_y, -w_z)."""
    design = stool()
    (plane,) = mirror_planes(design)
    assert mirrored_dof(design, plane, Dof("leg_l", kind)) == (Dof("leg_r", image), sign)


def test_broken_pairs_counts_what_an_edit_unmirrors():
    """Moving leg_r alone out by 20 mm breaks the leg pair; moving both apart by 20 mm
    (and lengthening the rung between them by 40 mm about the middle) breaks nothing."""
    design = stool()
    planes = mirror_planes(design)
    text = (CATALOG / "stool.yaml").read_text()
    one = text.replace("center: [170, 0, 219]", "center: [190, 0, 219]")
    both = one.replace("center: [-170, 0, 219]", "center: [-190, 0, 219]") \
        .replace("size: [328, 80]", "size: [368, 80]")
    assert broken_pairs(parse_design(one, "s.yaml", "yaml"), planes) == 1
    assert broken_pairs(parse_design(both, "s.yaml", "yaml"), planes) == 0
    assert broken_pairs(design, planes) == 0


def test_an_added_plank_without_a_mirror_image_breaks_the_symmetry():
    """Planks an edit adds count too: one support under the seat's end (x = 120) breaks
    the stool's symmetry, a pair of them at x = -120 and +120 does not, nor one on the
    mirror plane (x = 0); planks of the input are never counted as added."""
    design = stool()
    planes = mirror_planes(design)
    original = frozenset(design.plank_index)
    text = (CATALOG / "stool.yaml").read_text()

    def with_supports(*xs: float):
        added = "".join(f"  - {{id: support-{k}, size: [300, 80], center: [{x}, 0, 150], "
                        f"rotation: [0, -90, 0]}}\n" for k, x in enumerate(xs))
        return parse_design(text.replace("planks:\n", "planks:\n" + added, 1), "s.yaml",
                            "yaml")

    assert broken_pairs(with_supports(120), planes, original) == 1
    assert broken_pairs(with_supports(120), planes) == 0           # no input planks given
    assert broken_pairs(with_supports(-120, 120), planes, original) == 0
    assert broken_pairs(with_supports(0), planes, original) == 0
    assert broken_pairs(design, planes, original) == 0


# --- the catalog: a symmetric fix among the first three where one works --------------------

def corners_of(document: dict) -> dict[str, np.ndarray]:
    """Plank id -> (8, 3) corners, from a design document (mm), R = Rz Ry Rx."""
    out = {}
    thickness = document.get("material", {}).get("thickness", 12.0)
    for entry in document["planks"]:
        rx, ry, rz = np.radians(entry.get("rotation", [0, 0, 0]))
        cx, sx, cy, sy, cz, sz = np.cos(rx), np.sin(rx), np.cos(ry), np.sin(ry), \
            np.cos(rz), np.sin(rz)
        rotation = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]]) @ \
            np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]]) @ \
            np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
        half = 0.5 * np.array([*entry["size"], entry.get("thickness", thickness)])
        signs = np.array([[i, j, k] for i in (-1, 1) for j in (-1, 1) for k in (-1, 1)])
        out[entry["id"]] = np.array(entry["center"]) + (signs * half) @ rotation.T
    return out


def symmetric_about(corners: dict[str, np.ndarray], axis: int, offset: float) -> bool:
    """Every plank's mirrored corners are the corners of some plank (to 0.5 mm)."""
    for box in corners.values():
        image = box.copy()
        image[:, axis] = 2 * offset - image[:, axis]
        if not any(np.all(np.linalg.norm(image[:, None] - other[None], axis=2).min(axis=1)
                          <= 0.5) for other in corners.values()):
            return False
    return True


def input_planes(corners: dict[str, np.ndarray]) -> list[tuple[int, float]]:
    stacked = np.vstack(list(corners.values()))
    middle = 0.5 * (stacked.min(axis=0) + stacked.max(axis=0))
    return [(axis, float(middle[axis])) for axis in (0, 1)
            if symmetric_about(corners, axis, float(middle[axis]))]


SYMMETRIC = [(path.name, model) for path in sorted(CATALOG.glob("*.yaml")) for model in MODELS
             if input_planes(corners_of(yaml.safe_load(path.read_text())))
             and not check_file(str(path), model).valid]


@pytest.mark.parametrize("name, model", SYMMETRIC)
def test_symmetric_designs_get_a_symmetric_fix_in_the_top_three(catalog_suggestions, name,
                                                                model):
    """On every invalid catalog design that is mirror-symmetric (all its planks), if any
    suggestion's written file is still symmetric about the same planes, one of the first
    three is."""
    source = corners_of(yaml.safe_load((CATALOG / name).read_text()))
    planes = input_planes(source)
    _, result = catalog_suggestions(name, model)
    keeps = [all(symmetric_about(corners_of(yaml.safe_load(s.text)), axis, offset)
                 for axis, offset in planes) for s in result.suggestions]
    if any(keeps):
        assert any(keeps[:3]), (name, model, [s.dofs or s.between for s in result.suggestions])


def test_bench_tips_is_told_to_move_both_legs_apart():
    """bench-tips (rigid): 'Move leg_l and leg_r apart by N mm each' among the first three;
    its cut list moves leg_l to -300 - N and leg_r to 300 + N and lengthens the stretcher
    between them by 2 N (its ends follow the legs), to the text's rounding."""
    output = CliRunner().invoke(main, ["suggest", str(CATALOG / "bench-tips.yaml"),
                                       "--model", "rigid"]).output
    found = re.search(r"\n  ([123])\. Move leg_l and leg_r apart by (\d+) mm each \(valid for "
                      r"(\d+)-(\d+) mm each\)", output)
    assert found, output
    amount = float(found.group(2))
    assert float(found.group(3)) <= amount <= float(found.group(4))
    block = re.split(r"\n  \d+\. ", output[found.end():])[0]
    left = float(re.search(r"leg_l: x -300 -> (-[\d.]+) mm", block).group(1))
    right = float(re.search(r"leg_r: x 300 -> ([\d.]+) mm", block).group(1))
    stretcher = float(re.search(r"stretcher: length 588 -> ([\d.]+) mm", block).group(1))
    assert left == pytest.approx(-right, abs=0.1)
    assert right - 300 == pytest.approx(amount, abs=0.5)
    assert stretcher - 588 == pytest.approx(2 * (right - 300), abs=0.2)
