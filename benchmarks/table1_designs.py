"""Benchmark designs shaped like the paper's Table 1, for the suggestion generator.

Table 1 of Umetani, Igarashi and Mitra (SIGGRAPH 2012, section 7) times suggestion
generation on four designs of 9, 10, 20 and 28 planks with 13, 13, 33 and 49 nail joints.
The paper's designs themselves are not published, so ``table1_design(planks)`` builds, in
code, a piece of furniture of the same size: exactly that many 12 mm MDF planks and
exactly that many joints as furncheck detects them from the geometry (no listed joints).

Every design is shelving furniture standing on the floor, built from these parts (the
number in brackets is how many joints each part adds):

* sides and dividers standing on the floor (0 each), with a top cap on them (1 per side);
* shelves and bottoms nailed between two sides (2), kick boards under a bottom, nailed to
  both sides and to the bottom resting on them (3), cubby partitions standing on one shelf
  under the next (2);
* parts nailed by one end only (1): a gallery rail standing on the cap, bookends standing
  on a shelf, and a ledge (or desk leaf) nailed by its end to the outer face of a side.

Planks minus joints fixes the mix of parts, so the counts match Table 1 exactly:

=======  ======  ==================================================================
planks   joints  design
=======  ======  ==================================================================
9        13      one-bay bookcase on a kick board, gallery rail, plant ledge
10       13      two-bay low bookshelf, a bookend, a side shelf of books
20       33      three-bay bookshelf with fourteen shelves, a side ledge
28       49      three-bay cabinet on kick boards, cubbies, bookends, gallery rail,
                 a desk leaf
=======  ======  ==================================================================

Each design is invalid in exactly one way, as the paper's sessions start: its one-end
ledge (or desk leaf) is overloaded, so that joint's nail pull is about 1.4 times the nail
capacity (one ``non-durable`` violation), while everything else holds with margin (every
other joint below 80 % utilization, grounded, stable).  Small continuous changes restore
validity -- a shorter ledge (its load rides on it, nearer the side), a wider ledge (more
nails), a lighter load -- so suggestions have something to find.

    python benchmarks/table1_designs.py [--write DIR]

prints one line per design (planks, joints, violations, worst and next-worst joint
utilization) and, with ``--write``, writes ``DIR/table1-<planks>-<kind>.yaml`` for each
and checks that the written file gives the same verdict.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from pathlib import Path

from furncheck.check import check_design
from furncheck.design.load import load_design
from furncheck.design.model import Design, Load, LoadCase, Plank
from furncheck.design.write import write_design
from furncheck.geometry import analyze
from furncheck.result import DesignReport

TABLE1 = {9: (13, 110), 10: (13, 123), 20: (33, 880), 28: (49, 2420)}
"""Paper's Table 1: planks -> (joints, total suggestion time in ms)."""

MM = 0.001          # m per mm: the builders below work in mm, the model in metres
T = 12.0            # mm, plank thickness (12 mm MDF)

Span = tuple[float, float]


def _board(plank_id: str, xs: Span, ys: Span, zs: Span) -> Plank:
    """An axis-aligned plank filling the box ``xs x ys x zs`` (mm intervals).

    The box's thin extent (exactly ``T``) is the plank's thickness: a horizontal board
    (thin in z), a side standing in the y-z plane (thin in x, rotated -90 degrees about y,
    so its length is its height) or a board standing in the x-z plane (thin in y, rotated
    90 degrees about x, length along x).
    """
    dx, dy, dz = (hi - lo for lo, hi in (xs, ys, zs))
    centre = tuple(MM * (lo + hi) / 2 for lo, hi in (xs, ys, zs))
    if dz == T:
        length, width, rotation = dx, dy, (0.0, 0.0, 0.0)
    elif dx == T:
        length, width, rotation = dz, dy, (0.0, -90.0, 0.0)
    elif dy == T:
        length, width, rotation = dx, dz, (90.0, 0.0, 0.0)
    else:
        raise ValueError(f"{plank_id}: no extent of {T} mm in {(dx, dy, dz)}")
    return Plank(plank_id, MM * length, MM * width, MM * T, centre, rotation)


def _on(plank: Plank, x: float, y: float) -> tuple[float, float, float]:
    """The world point (m) at (x, y) mm on the top face of horizontal ``plank``."""
    return (MM * x, MM * y, plank.center[2] + plank.thickness / 2)


class _Builder:
    """Collects planks and the default load case of a design, in mm and kg."""

    def __init__(self) -> None:
        self.planks: list[Plank] = []
        self.loads: list[Load] = []

    def board(self, plank_id: str, xs: Span, ys: Span, zs: Span) -> Plank:
        """Add an axis-aligned plank (see ``_board``)."""
        plank = _board(plank_id, xs, ys, zs)
        self.planks.append(plank)
        return plank

    def books(self, plank: Plank, kg: float, at: tuple[float, float] | None = None) -> None:
        """Put ``kg`` on ``plank``: at its centre, or at (x, y) mm on its top face."""
        point = None if at is None else _on(plank, *at)
        self.loads.append(Load.of_mass(plank.id, kg, point))

    def design(self, name: str) -> Design:
        """The design built so far, its joints detected from the geometry."""
        return Design(name, tuple(self.planks), (LoadCase("default", tuple(self.loads)),))


def _bookcase_9() -> Design:
    """9 planks, 13 joints: a 1.5 m one-bay bookcase (two sides, a cap with a gallery rail
    standing on its back edge, two shelves, a bottom on a kick board) and a 350 x 160 mm
    plant ledge nailed (8 nails) to the outside of the right side, a 16 kg planter near its
    tip: the ledge joint fails (cap 2 + kick 3 + bottom 2 + shelves 4 + gallery 1 + ledge 1).
    """
    b = _Builder()
    depth, height = (-150.0, 150.0), (0.0, 1500.0)
    b.board("side_l", (-312, -300), depth, height)
    side_r = b.board("side_r", (300, 312), depth, height)
    cap = b.board("cap", (-322, 322), (-160, 160), (1500, 1512))
    b.board("gallery", (-300, 300), (136, 148), (1512, 1592))
    b.board("kick", (-300, 300), (-130, -118), (0, 60))
    bottom = b.board("bottom", (-300, 300), depth, (60, 72))
    shelf_1 = b.board("shelf_1", (-300, 300), depth, (520, 532))
    shelf_2 = b.board("shelf_2", (-300, 300), depth, (980, 992))
    x0 = side_r.center[0] / MM + T / 2
    ledge = b.board("ledge", (x0, x0 + 350), (-80, 80), (1100, 1112))
    for plank in (bottom, shelf_1, shelf_2):
        b.books(plank, 15.0)
    b.books(cap, 4.0)
    b.books(ledge, 16.0, (x0 + 300, 0))
    return b.design("table1-9-bookcase")


def _bookshelf_10() -> Design:
    """10 planks, 13 joints: a 0.9 m two-bay low bookshelf (three sides, a cap, a bottom and
    a shelf in each bay, a bookend standing on the left shelf) and a 350 x 240 mm side shelf
    nailed (12 nails) to the outside of the right side, 24 kg of books at its far end: the
    side shelf's joint fails (cap 3 + bottoms and shelves 8 + bookend 1 + side shelf 1).
    """
    b = _Builder()
    depth, height = (-150.0, 150.0), (0.0, 900.0)
    b.board("side_l", (-612, -600), depth, height)
    b.board("side_m", (-6, 6), depth, height)
    side_r = b.board("side_r", (600, 612), depth, height)
    cap = b.board("cap", (-622, 622), (-160, 160), (900, 912))
    shelves = []
    for bay, xs in (("a", (-600.0, -6.0)), ("b", (6.0, 600.0))):
        shelves.append(b.board(f"bottom_{bay}", xs, depth, (60, 72)))
        shelves.append(b.board(f"shelf_{bay}", xs, depth, (480, 492)))
    b.board("bookend", (-220, -208), (-100, 100), (492, 692))
    x0 = side_r.center[0] / MM + T / 2
    side_shelf = b.board("side_shelf", (x0, x0 + 350), (-120, 120), (640, 652))
    for plank in shelves:
        b.books(plank, 15.0)
    b.books(cap, 5.0)
    b.books(side_shelf, 24.0, (x0 + 300, 0))
    return b.design("table1-10-bookshelf")


def _bookshelf_20() -> Design:
    """20 planks, 33 joints: a 1.8 m three-bay bookshelf (two sides and two dividers on the
    floor, a cap on all four, five, four and five shelves in the bays, the lowest 60 mm
    above the floor) and a 400 x 200 mm ledge nailed (10 nails) to the outside of the right
    side, 17 kg on its far end: the ledge joint fails (cap 4 + shelves 28 + ledge 1).
    """
    b = _Builder()
    depth, height = (-150.0, 150.0), (0.0, 1800.0)
    b.board("side_l", (-774, -762), depth, height)
    b.board("divider_l", (-262, -250), depth, height)
    b.board("divider_r", (250, 262), depth, height)
    side_r = b.board("side_r", (762, 774), depth, height)
    cap = b.board("cap", (-784, 784), (-160, 160), (1800, 1812))
    levels = {"a": (60, 400, 740, 1080, 1420), "b": (60, 480, 900, 1320),
              "c": (60, 400, 740, 1080, 1420)}
    bays = {"a": (-762.0, -262.0), "b": (-250.0, 250.0), "c": (262.0, 762.0)}
    for bay, xs in bays.items():
        for level, z in enumerate(levels[bay]):
            b.books(b.board(f"shelf_{bay}{level}", xs, depth, (z, z + T)), 12.0)
    b.books(cap, 5.0)
    x0 = side_r.center[0] / MM + T / 2
    ledge = b.board("ledge", (x0, x0 + 400), (-100, 100), (1200, 1212))
    b.books(ledge, 17.0, (x0 + 350, 0))
    return b.design("table1-20-bookshelf")


def _cabinet_28() -> Design:
    """28 planks, 49 joints: a 1.6 m three-bay cabinet, 400 mm deep (two sides and two
    dividers on the floor, a cap with a gallery rail, in each bay a bottom on a kick board
    and three shelves, two cubby partitions under each of the middle bay's two lower
    shelves, a bookend on the first shelf of each outer bay) and a 600 x 400 mm desk leaf
    nailed (20 nails) to the outside of the right side at desk height, 25 kg of monitor
    and printer near its tip: the desk leaf's joint fails (cap 4 + kicks 9 + bottoms and
    shelves 24 + partitions 8 + gallery 1 + bookends 2 + desk leaf 1).
    """
    b = _Builder()
    depth, height = (-200.0, 200.0), (0.0, 1600.0)
    b.board("side_l", (-774, -762), depth, height)
    b.board("divider_l", (-262, -250), depth, height)
    b.board("divider_r", (250, 262), depth, height)
    side_r = b.board("side_r", (762, 774), depth, height)
    cap = b.board("cap", (-784, 784), (-210, 210), (1600, 1612))
    b.board("gallery", (-700, 700), (180, 192), (1612, 1692))
    bays = {"a": (-762.0, -262.0), "b": (-250.0, 250.0), "c": (262.0, 762.0)}
    shelf_z = (420, 800, 1180)
    for bay, xs in bays.items():
        b.board(f"kick_{bay}", xs, (-180, -168), (0, 80))
        b.books(b.board(f"bottom_{bay}", xs, depth, (80, 92)), 20.0)
        for level, z in enumerate(shelf_z, start=1):
            b.books(b.board(f"shelf_{bay}{level}", xs, depth, (z, z + T)), 15.0)
    for level, (z0, z1) in enumerate(((92, 420), (432, 800))):
        for k, x in enumerate((-90.0, 78.0)):
            b.board(f"cubby_{level}{k}", (x, x + T), depth, (z0, z1))
    b.board("bookend_a", (-420, -408), (-120, 120), (432, 632))
    b.board("bookend_c", (408, 420), (-120, 120), (432, 632))
    b.books(cap, 10.0)
    x0 = side_r.center[0] / MM + T / 2
    leaf = b.board("desk_leaf", (x0, x0 + 600), depth, (740, 752))
    b.books(leaf, 25.0, (x0 + 480, 0))
    return b.design("table1-28-cabinet")


_BUILDERS: dict[int, Callable[[], Design]] = {
    9: _bookcase_9, 10: _bookshelf_10, 20: _bookshelf_20, 28: _cabinet_28}


def table1_design(planks: int) -> Design:
    """The benchmark design with ``planks`` planks (9, 10, 20 or 28) and Table 1's number
    of joints, invalid by exactly one non-durable joint (see the module docstring)."""
    try:
        builder = _BUILDERS[planks]
    except KeyError:
        raise ValueError(f"Table 1 has designs of {sorted(TABLE1)} planks, not {planks}") \
            from None
    return builder()


def utilizations(report: DesignReport) -> list[float]:
    """Every joint's utilization in every load case of ``report``, largest first."""
    return sorted((j.utilization for case in report.cases for j in case.joints), reverse=True)


def verdict(report: DesignReport) -> tuple:
    """What a round trip through a file must keep: validity and the violations (kind,
    where, case)."""
    return report.valid, tuple((v.kind, v.where, v.case) for v in report.violations)


def _row(cells: list[str], widths: list[int]) -> str:
    return " | ".join(cell.rjust(w) if i else cell.ljust(w)
                      for i, (cell, w) in enumerate(zip(cells, widths)))


def main(argv: list[str] | None = None) -> int:
    """Print the table of the four designs; with ``--write DIR`` also write them as YAML
    and check that each written file gives the same verdict.  Returns the exit code."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", metavar="DIR", help="write each design as DIR/<name>.yaml")
    args = parser.parse_args(argv)
    header = ["design", "planks", "joints", "paper joints", "paper ms", "violations",
              "worst util.", "next util.", "failing joint"]
    rows = []
    mismatches = 0
    for planks, (paper_joints, paper_ms) in TABLE1.items():
        design = table1_design(planks)
        geometry = analyze(design)
        report = check_design(design, geometry)
        util = utilizations(report)
        rows.append([design.name, str(len(design.planks)), str(len(geometry.joints)),
                     str(paper_joints), str(paper_ms), str(len(report.violations)),
                     f"{util[0]:.2f}", f"{util[1]:.2f}",
                     ", ".join(f"{v.kind} {v.where}" for v in report.violations)])
        if args.write:
            path = Path(args.write) / f"{design.name}.yaml"
            path.parent.mkdir(parents=True, exist_ok=True)
            write_design(design, str(path))
            if verdict(check_design(load_design(str(path)))) != verdict(report):
                print(f"{path}: written file gives another verdict", file=sys.stderr)
                mismatches += 1
            else:
                print(f"wrote {path}")
    widths = [max(len(r[i]) for r in [header, *rows]) for i in range(len(header))]
    print(_row(header, widths))
    print("-+-".join("-" * w for w in widths))
    for cells in rows:
        print(_row(cells, widths))
    return 1 if mismatches else 0


if __name__ == "__main__":
    sys.exit(main())
