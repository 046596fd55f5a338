"""Benchmark designs shaped like the paper's Table 1, for the suggestion generator.

Table 1 of Umetani, Igarashi and Mitra (SIGGRAPH 2012, section 7) times suggestion
generation on four designs of 9, 10, 20 and 28 planks with 13, 13, 33 and 49 nail joints.
The paper's designs themselves are not published, so ``table1_design(planks)`` builds, in
code, a piece of furniture of the same size: exactly that many MDF planks and exactly that
many joints as furncheck detects them from the geometry.  The joints are listed in the
design (the detected ones, in their order) only so that the ledge's joint can have an
explicit nail count; every other joint has one nail per 20 mm as detection gives it.

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

Each design is invalid in exactly one way, in both statics models (``model: rigid``, the
paper's, and ``model: elastic``, the default), as the paper's sessions start: its one-end
ledge (or desk leaf) is nailed with too few nails for its load, so that joint's nail pull
is about 1.4 times the nail capacity (one ``non-durable`` violation), while everything
else holds with margin (every other joint below 80 % utilization, stable; in the elastic
model no plank sagging or overstressed, every plank below 75 % of its sag or stress
limit).  Small continuous changes restore validity -- a shorter ledge (its load rides on
it, nearer the side), a lighter load -- so suggestions have something to find.

Materials and the physics that fixes them (MDF, E = 3000 N/mm^2, creep 0.5: a plank sags
when 1.5 x sag > span / 400; nail pull 700 N, shear 190 N).  The carcass -- sides,
dividers, caps, bottoms and shelves -- is 19 mm MDF, the kick boards, gallery rails,
bookends and cubby partitions 12 mm, the ledges 25 mm and the desk leaf 30 mm; books are
spread along their shelves.  A ledge nailed by its end fails by pull = (2 |M| / t) / n per
nail (contract section 3, t the ledge's thickness, n its nails), so breaking it at
1.4 x 700 N takes a root moment M = 490 t n N mm.  A tip load giving that moment bends the
ledge by M L^2 / 3EI, L its overhang, which must stay within (2 L / 400) / 1.5: with
I = b t^3 / 12 that allows L <= E (b / n) t^2 / 588000 mm.  With one nail per 20 mm
(b / n = 20) a 12 mm ledge could overhang at most 15 mm and even a 25 mm one 64 mm; so
each ledge is nailed with few nails -- two in a 200-240 mm wide ledge (b / n = 100-120),
three in the 400 mm desk leaf -- which is the builder's real mistake, and is listed as
such.  The first version of these designs (all 12 mm, ledges 350-600 mm long nailed every
20 mm, books as point loads) failed only the ledge joint in the rigid model but sagged in
7 to 19 further places in the elastic one; ``sagging_bookshelf_20`` keeps its 20-plank
design for tests that want many failures.

    python benchmarks/table1_designs.py [--write DIR]

prints one line per design and model (planks, joints, violations, worst and next-worst
joint utilization, worst plank utilization) and, with ``--write``, writes
``DIR/table1-<planks>-<kind>.yaml`` for each and checks that the written file gives the
same verdict in both models.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from pathlib import Path

from furncheck.check import check_design
from furncheck.design.load import load_design
from furncheck.design.model import Design, JointSpec, Load, LoadCase, Plank, with_model
from furncheck.design.write import write_design
from furncheck.geometry import analyze
from furncheck.result import DesignReport

TABLE1 = {9: (13, 110), 10: (13, 123), 20: (33, 880), 28: (49, 2420)}
"""Paper's Table 1: planks -> (joints, total suggestion time in ms)."""

MODELS = ("rigid", "elastic")
"""The statics models each design is invalid in exactly one way in."""

MM = 0.001          # m per mm: the builders below work in mm, the model in metres
T = 12.0            # mm, the thin parts (kick boards, gallery rails, bookends, partitions)
BOARD = 19.0        # mm, the carcass: sides, dividers, caps, bottoms and shelves
LEDGE = 25.0        # mm, the ledges (30 mm for the desk leaf)
LEDGE_NAILS = 2     # nails in a ledge's joint (3 in the desk leaf's), listed explicitly

Span = tuple[float, float]


def _board(plank_id: str, xs: Span, ys: Span, zs: Span, t: float = T) -> Plank:
    """An axis-aligned plank ``t`` mm thick filling the box ``xs x ys x zs`` (mm intervals).

    The box's extent equal to ``t`` is the plank's thickness: a horizontal board (thin in
    z), a side standing in the y-z plane (thin in x, rotated -90 degrees about y, so its
    length is its height) or a board standing in the x-z plane (thin in y, rotated 90
    degrees about x, length along x).
    """
    dx, dy, dz = (hi - lo for lo, hi in (xs, ys, zs))
    centre = tuple(MM * (lo + hi) / 2 for lo, hi in (xs, ys, zs))
    if dz == t:
        length, width, rotation = dx, dy, (0.0, 0.0, 0.0)
    elif dx == t:
        length, width, rotation = dz, dy, (0.0, -90.0, 0.0)
    elif dy == t:
        length, width, rotation = dx, dz, (90.0, 0.0, 0.0)
    else:
        raise ValueError(f"{plank_id}: no extent of {t} mm in {(dx, dy, dz)}")
    return Plank(plank_id, MM * length, MM * width, MM * t, centre, rotation)


def _on(plank: Plank, x: float, y: float) -> tuple[float, float, float]:
    """The world point (m) at (x, y) mm on the top face of horizontal ``plank``."""
    return (MM * x, MM * y, plank.center[2] + plank.thickness / 2)


class _Builder:
    """Collects planks and the default load case of a design, in mm and kg."""

    def __init__(self) -> None:
        self.planks: list[Plank] = []
        self.loads: list[Load] = []

    def board(self, plank_id: str, xs: Span, ys: Span, zs: Span, t: float = T) -> Plank:
        """Add an axis-aligned plank ``t`` mm thick (see ``_board``)."""
        plank = _board(plank_id, xs, ys, zs, t)
        self.planks.append(plank)
        return plank

    def books(self, plank: Plank, kg: float, at: tuple[float, float] | None = None) -> None:
        """Put ``kg`` on ``plank``: spread along it (books), or at (x, y) mm on its top
        face (a planter, a monitor)."""
        if at is None:
            self.loads.append(Load.of_mass(plank.id, kg, spread=True))
        else:
            self.loads.append(Load.of_mass(plank.id, kg, _on(plank, *at)))

    def design(self, name: str, nails: dict[str, int]) -> Design:
        """The design built so far.  Its joints are the ones detected from the geometry,
        listed so that the joint of each plank in ``nails`` (plank id -> count) gets that
        many nails instead of one per 20 mm; every other joint keeps the spacing rule."""
        cases = (LoadCase("default", tuple(self.loads)),)
        if not nails:
            return Design(name, tuple(self.planks), cases)
        detected = analyze(Design(name, tuple(self.planks), cases)).joints
        joints = tuple(JointSpec(j.planks, next((n for p, n in nails.items() if p in j.planks),
                                                None))
                       for j in detected)
        return Design(name, tuple(self.planks), cases, joints=joints)


def _ledge(b: _Builder, side: Plank, plank_id: str, length: float, width: float, z: float,
           t: float = LEDGE) -> tuple[Plank, float]:
    """A ledge ``length`` x ``width`` mm, ``t`` thick, its end on the outer (+x) face of
    ``side`` with its underside at ``z``; returns it and the x of that face."""
    x0 = side.center[0] / MM + side.thickness / MM / 2
    return b.board(plank_id, (x0, x0 + length), (-width / 2, width / 2), (z, z + t), t), x0


def _bookcase_9() -> Design:
    """9 planks, 13 joints: a 1.5 m one-bay bookcase (two sides, a cap with a gallery rail
    standing on its back edge, two shelves, a bottom on a kick board) and a plant ledge
    nailed to the outside of the right side: the ledge joint fails (cap 2 + kick 3 +
    bottom 2 + shelves 4 + gallery 1 + ledge 1).

    The ledge, 200 x 200 x 25 mm, nailed with 2 nails, carries a 14 kg planter 170 mm
    out: M = 137 N x 0.17 m + its own 0.75 kg at 0.1 m = 24.1 N m, pull = 2 M / t / n =
    2 x 24.1 / 0.025 / 2 = 963 N = 1.38 x 700 N (shear 72 N per nail, 0.38).  Its
    deflection P a^2 (3L - a) / 6EI = 137 x 170^2 x 430 / (6 x 3000 x 260417) = 0.36 mm
    (+0.01 own weight), 1.5 x 0.37 = 0.56 mm against span / 400 = 2 x 200 / 400 = 1.0 mm.
    The shelves, 600 x 300 x 19 mm with 12 kg of books (143 N with their own weight),
    sag between 0.16 mm (wL^4/384EI, fixed ends) and 0.78 mm (5wL^4/384EI, pinned)
    against 1.5 / 1.5 = 1.0 mm; the elastic model finds 0.54 mm (semi-rigid nails).
    """
    b = _Builder()
    depth, height, t = (-150.0, 150.0), (0.0, 1500.0), BOARD
    b.board("side_l", (-300 - t, -300), depth, height, t)
    side_r = b.board("side_r", (300, 300 + t), depth, height, t)
    cap = b.board("cap", (-310 - t, 310 + t), (-160, 160), (1500, 1500 + t), t)
    b.board("gallery", (-300, 300), (136, 148), (1500 + t, 1580 + t))
    b.board("kick", (-300, 300), (-130, -118), (0, 60))
    bottom = b.board("bottom", (-300, 300), depth, (60, 60 + t), t)
    shelf_1 = b.board("shelf_1", (-300, 300), depth, (520, 520 + t), t)
    shelf_2 = b.board("shelf_2", (-300, 300), depth, (980, 980 + t), t)
    ledge, x0 = _ledge(b, side_r, "ledge", 200, 200, 1100)
    for plank in (bottom, shelf_1, shelf_2):
        b.books(plank, 12.0)
    b.books(cap, 4.0, (0, 0))
    b.books(ledge, 14.0, (x0 + 170, 0))
    return b.design("table1-9-bookcase", {"ledge": LEDGE_NAILS})


def _bookshelf_10() -> Design:
    """10 planks, 13 joints: a 0.9 m two-bay low bookshelf (three sides, a cap, a bottom and
    a shelf in each bay, a bookend standing on the left shelf) and a side shelf nailed to
    the outside of the right side: the side shelf's joint fails (cap 3 + bottoms and
    shelves 8 + bookend 1 + side shelf 1).

    The side shelf, 250 x 240 x 25 mm, nailed with 2 nails, carries 11.5 kg of books
    200 mm out: M = 113 N x 0.2 m + its own 1.1 kg at 0.125 m = 23.9 N m, pull =
    2 x 23.9 / 0.025 / 2 = 958 N = 1.37 x 700 N (shear 62 N per nail, 0.33).  Deflection
    113 x 200^2 x 550 / (6 x 3000 x 312500) = 0.44 mm (+0.02 own weight), 1.5 x 0.46 =
    0.70 mm against 2 x 250 / 400 = 1.25 mm.  The 590 x 300 x 19 mm shelves and bottoms
    with 12 kg (142 N) sag between 0.15 mm fixed and 0.74 mm pinned against 0.98 mm;
    the elastic model finds 0.49-0.52 mm.
    """
    b = _Builder()
    depth, height, t = (-150.0, 150.0), (0.0, 900.0), BOARD
    b.board("side_l", (-600 - t, -600), depth, height, t)
    b.board("side_m", (-t / 2, t / 2), depth, height, t)
    side_r = b.board("side_r", (600, 600 + t), depth, height, t)
    cap = b.board("cap", (-610 - t, 610 + t), (-160, 160), (900, 900 + t), t)
    shelves = []
    for bay, xs in (("a", (-600.0, -t / 2)), ("b", (t / 2, 600.0))):
        shelves.append(b.board(f"bottom_{bay}", xs, depth, (60, 60 + t), t))
        shelves.append(b.board(f"shelf_{bay}", xs, depth, (480, 480 + t), t))
    b.board("bookend", (-220, -208), (-100, 100), (480 + t, 680 + t))
    side_shelf, x0 = _ledge(b, side_r, "side_shelf", 250, 240, 640)
    for plank in shelves:
        b.books(plank, 12.0)
    b.books(cap, 5.0, (0, 0))
    b.books(side_shelf, 11.5, (x0 + 200, 0))
    return b.design("table1-10-bookshelf", {"side_shelf": LEDGE_NAILS})


def _bookshelf_20_carcass(t: float) -> tuple[_Builder, Plank]:
    """The 20-plank bookshelf but its ledge, boards ``t`` mm thick, with the books on its
    shelves and cap; returns the builder and the right side (for ``_bookshelf_20`` and
    ``sagging_bookshelf_20``)."""
    b = _Builder()
    depth, height = (-150.0, 150.0), (0.0, 1800.0)
    inner = 250 + t + 500                           # x of the right side's inner face
    bays = {"a": (-inner, -250 - t), "b": (-250.0, 250.0), "c": (250 + t, inner)}
    b.board("side_l", (-inner - t, -inner), depth, height, t)
    b.board("divider_l", (-250 - t, -250), depth, height, t)
    b.board("divider_r", (250, 250 + t), depth, height, t)
    side_r = b.board("side_r", (inner, inner + t), depth, height, t)
    cap = b.board("cap", (-inner - t - 10, inner + t + 10), (-160, 160), (1800, 1800 + t), t)
    levels = {"a": (60, 400, 740, 1080, 1420), "b": (60, 480, 900, 1320),
              "c": (60, 400, 740, 1080, 1420)}
    for bay, xs in bays.items():
        for level, z in enumerate(levels[bay]):
            b.books(b.board(f"shelf_{bay}{level}", xs, depth, (z, z + t), t), 12.0)
    b.books(cap, 5.0, (0, 0))
    return b, side_r


def _bookshelf_20() -> Design:
    """20 planks, 33 joints: a 1.8 m three-bay bookshelf (two sides and two dividers on the
    floor, a cap on all four, five, four and five shelves in the bays, the lowest 60 mm
    above the floor) and a ledge nailed to the outside of the right side: the ledge joint
    fails (cap 4 + shelves 28 + ledge 1).

    The ledge is the 9-plank bookcase's: 200 x 200 x 25 mm, 2 nails, 14 kg 170 mm out,
    M = 24.1 N m, pull 963 N = 1.38 x 700 N, 1.5 x deflection 0.56 mm against 1.0 mm.
    The 500 x 300 x 19 mm shelves with 12 kg (139 N) sag between 0.09 mm fixed and
    0.44 mm pinned against 1.25 / 1.5 = 0.83 mm; the elastic model finds 0.29-0.33 mm.
    """
    b, side_r = _bookshelf_20_carcass(BOARD)
    ledge, x0 = _ledge(b, side_r, "ledge", 200, 200, 1200)
    b.books(ledge, 14.0, (x0 + 170, 0))
    return b.design("table1-20-bookshelf", {"ledge": LEDGE_NAILS})


def sagging_bookshelf_20() -> Design:
    """The 20-plank bookshelf as first built: all 12 mm MDF, its 400 x 200 mm ledge
    nailed by one end (10 nails by the spacing rule; joints detected, not listed), 17 kg
    on the ledge's far end.  In the rigid model only the ledge joint fails (1.42); in the
    elastic model thirteen of the fourteen 500 mm shelves (12 kg spread: up to 1.6 times
    their allowed sag), the sides, the dividers and the ledge (34 mm at its tip against
    2 x 400 / 400 / 1.5 = 1.3 mm) sag too: 19 failing places over all three bays.  For
    tests that want a design failing all over; not a Table-1 benchmark."""
    b, side_r = _bookshelf_20_carcass(T)
    ledge, x0 = _ledge(b, side_r, "ledge", 400, 200, 1200, T)
    b.books(ledge, 17.0, (x0 + 350, 0))
    return b.design("table1-20-bookshelf-12mm", {})


def _cabinet_28() -> Design:
    """28 planks, 49 joints: a 1.6 m three-bay cabinet, 400 mm deep (two sides and two
    dividers on the floor, a cap with a gallery rail, in each bay a bottom on a kick board
    and three shelves, two cubby partitions under each of the middle bay's two lower
    shelves, a bookend on the first shelf of each outer bay) and a desk leaf nailed to the
    outside of the right side at desk height: the desk leaf's joint fails (cap 4 + kicks 9
    + bottoms and shelves 24 + partitions 8 + gallery 1 + bookends 2 + desk leaf 1).

    The desk leaf, 500 x 400 x 30 mm, nailed with 3 nails, carries an 8.5 kg laptop and
    lamp 400 mm out: M = 83 N x 0.4 m + its own 4.5 kg at 0.25 m = 44.4 N m, pull =
    2 x 44.4 / 0.030 / 3 = 986 N = 1.41 x 700 N (shear 43 N per nail, 0.22).  Deflection
    83 x 400^2 x 1100 / (6 x 3000 x 900000) = 0.91 mm + wL^4/8EI = 0.26 mm of its own
    weight, 1.5 x 1.16 = 1.74 mm against 2 x 500 / 400 = 2.5 mm.  The 500 x 400 x 19 mm
    shelves with 15 kg (175 N) sag between 0.08 mm fixed and 0.42 mm pinned, the bottoms
    with 20 kg (224 N) between 0.11 and 0.53 mm, against 0.83 mm; the elastic model finds
    at most 0.32 mm.
    """
    b = _Builder()
    depth, height, t = (-200.0, 200.0), (0.0, 1600.0), BOARD
    b.board("side_l", (-769 - t, -769), depth, height, t)
    b.board("divider_l", (-250 - t, -250), depth, height, t)
    b.board("divider_r", (250, 250 + t), depth, height, t)
    side_r = b.board("side_r", (769, 769 + t), depth, height, t)
    cap = b.board("cap", (-779 - t, 779 + t), (-210, 210), (1600, 1600 + t), t)
    b.board("gallery", (-700, 700), (180, 192), (1600 + t, 1680 + t))
    bays = {"a": (-769.0, -269.0), "b": (-250.0, 250.0), "c": (269.0, 769.0)}
    shelf_z = (420, 800, 1180)
    for bay, xs in bays.items():
        b.board(f"kick_{bay}", xs, (-180, -168), (0, 80))
        b.books(b.board(f"bottom_{bay}", xs, depth, (80, 80 + t), t), 20.0)
        for level, z in enumerate(shelf_z, start=1):
            b.books(b.board(f"shelf_{bay}{level}", xs, depth, (z, z + t), t), 15.0)
    for level, (z0, z1) in enumerate(((80 + t, 420), (420 + t, 800))):
        for k, x in enumerate((-90.0, 78.0)):
            b.board(f"cubby_{level}{k}", (x, x + T), depth, (z0, z1))
    b.board("bookend_a", (-420, -408), (-120, 120), (420 + t, 620 + t))
    b.board("bookend_c", (408, 420), (-120, 120), (420 + t, 620 + t))
    b.books(cap, 10.0, (0, 0))
    leaf, x0 = _ledge(b, side_r, "desk_leaf", 500, 400, 740, 30.0)
    b.books(leaf, 8.5, (x0 + 400, 0))
    return b.design("table1-28-cabinet", {"desk_leaf": 3})


_BUILDERS: dict[int, Callable[[], Design]] = {
    9: _bookcase_9, 10: _bookshelf_10, 20: _bookshelf_20, 28: _cabinet_28}


def table1_design(planks: int) -> Design:
    """The benchmark design with ``planks`` planks (9, 10, 20 or 28) and Table 1's number
    of joints, invalid by exactly one non-durable joint in either model (see the module
    docstring)."""
    try:
        builder = _BUILDERS[planks]
    except KeyError:
        raise ValueError(f"Table 1 has designs of {sorted(TABLE1)} planks, not {planks}") \
            from None
    return builder()


def utilizations(report: DesignReport) -> list[float]:
    """Every joint's utilization in every load case of ``report``, largest first."""
    return sorted((j.utilization for case in report.cases for j in case.joints), reverse=True)


def plank_utilizations(report: DesignReport) -> list[float]:
    """Every plank's utilization (sag or stress, the larger) in every load case of
    ``report``, largest first; none in the rigid model."""
    return sorted((p.utilization for case in report.cases for p in case.planks or ()),
                  reverse=True)


def verdict(report: DesignReport) -> tuple:
    """What a round trip through a file must keep: validity and the violations (kind,
    where, case)."""
    return report.valid, tuple((v.kind, v.where, v.case) for v in report.violations)


def _row(cells: list[str], widths: list[int]) -> str:
    return " | ".join(cell.rjust(w) if i else cell.ljust(w)
                      for i, (cell, w) in enumerate(zip(cells, widths)))


def main(argv: list[str] | None = None) -> int:
    """Print the table of the four designs in both models; with ``--write DIR`` also write
    them as YAML and check that each written file gives the same verdict in both models.
    Returns the exit code."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", metavar="DIR", help="write each design as DIR/<name>.yaml")
    args = parser.parse_args(argv)
    header = ["design", "model", "planks", "joints", "paper joints", "paper ms",
              "violations", "worst util.", "next util.", "worst plank", "failing"]
    rows = []
    mismatches = 0
    for planks, (paper_joints, paper_ms) in TABLE1.items():
        design = table1_design(planks)
        geometry = analyze(design)
        for model in MODELS:
            report = check_design(with_model(design, model), geometry)
            util, bent = utilizations(report), plank_utilizations(report)
            rows.append([design.name, model, str(len(design.planks)),
                         str(len(geometry.joints)), str(paper_joints), str(paper_ms),
                         str(len(report.violations)), f"{util[0]:.2f}", f"{util[1]:.2f}",
                         f"{bent[0]:.2f}" if bent else "-",
                         ", ".join(f"{v.kind} {v.where}" for v in report.violations)])
        if args.write:
            path = Path(args.write) / f"{design.name}.yaml"
            path.parent.mkdir(parents=True, exist_ok=True)
            write_design(design, str(path))
            written = load_design(str(path))
            if any(verdict(check_design(with_model(written, model)))
                   != verdict(check_design(with_model(design, model))) for model in MODELS):
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
