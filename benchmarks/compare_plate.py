"""Comparison: furncheck's one beam per plank against a plate, for tops held on their edges.

A 388 x 400 x 12 mm MDF top (E = 3000 N/mm^2, nu = 0.25) between two 550 mm high sides,
40 kg at its centre, the sides and top of ``designs/nightstand-deep.yaml`` (no shelf):
open (held on its two 400 mm edges), with a back panel (three edges) and with a back
and a front panel (four edges); and the load 10 mm inside the free front edge.  The
load presses on a 50 mm square (furncheck's PLATE_LOAD_PATCH; at the front edge, the
square from the edge inwards).
furncheck reads each design in the elastic model twice: with its beams alone
(``statics.elastic``: a beam along the top's shorter side where it spans between
panels, ``_spans_across``; the plate check switched off) and as it reports it, the top
also checked as a plate where panels hold it along lines (``statics.plates``: simply
supported on the lines, the nail rows' grip as springs).  This benchmark's plate is a
Mindlin plate of its own, 40 x 40 bilinear elements with selectively reduced shear
integration (exact enough at this mesh: the check below), its held edges either simply
supported or clamped, the two limits of the nail rows' grip.  Self-weight is left out
of all (the designs give the top a density of 0.001 kg/m^3).  Prints the table of the
README's "The one beam per plank against a plate".

    python benchmarks/compare_plate.py

The plate code is checked first against the one-way strip: a plate simply supported on
two opposite edges, free on the others, under a uniform load, bends as a strip,
5 q L^4 / 384 D (D = E t^3 / 12 (1 - nu^2)), to well within 1 %.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

E, NU, T = 3000.0, 0.25, 12.0           # N/mm^2, -, mm
A, B = 388.0, 400.0                     # mm: between the sides (x), deep (y)
P = 40 * 9.81                           # N at the centre
CELLS = 40
PATCH = 50.0                            # mm: the square a point load presses on

DESIGN = """furncheck: 1
name: top
units: mm
planks:
  - {id: side_l, size: [550, 400], center: [-200, 0, 275], rotation: [0, -90, 0]}
  - {id: side_r, size: [550, 400], center: [200, 0, 275], rotation: [0, -90, 0]}
  - {id: top, size: [388, 400], center: [0, 0, 544], material: {density: 0.001}}
@PANELS
loads:
  - {plank: top, force: [0, 0, -392.4], at: [0, 0, 550]}
"""
BACK = "  - {id: back, size: [412, 550], center: [0, 206, 275], rotation: [90, 0, 0]}"
FRONT = "  - {id: front, size: [412, 550], center: [0, -206, 275], rotation: [90, 0, 0]}"


def element_stiffness(hx: float, hy: float) -> np.ndarray:
    """(12, 12) of one Mindlin element, unknowns (w, beta_x, beta_y) per corner (slopes
    dw/dx = beta_x where the shear strain vanishes): bending by 2 x 2 Gauss points,
    shear by one (selective reduced integration, free of shear locking)."""
    D = E * T ** 3 / (12 * (1 - NU ** 2))
    bending = D * np.array([[1, NU, 0], [NU, 1, 0], [0, 0, (1 - NU) / 2]])
    shear = 5 / 6 * E / (2 * (1 + NU)) * T * np.eye(2)
    corners = [(-1, -1), (1, -1), (1, 1), (-1, 1)]

    def shapes(xi: float, eta: float):
        n = np.array([(1 + a * xi) * (1 + b * eta) / 4 for a, b in corners])
        dx = np.array([a * (1 + b * eta) / 4 for a, b in corners]) * 2 / hx
        dy = np.array([b * (1 + a * xi) / 4 for a, b in corners]) * 2 / hy
        return n, dx, dy

    K = np.zeros((12, 12))
    g = 1 / np.sqrt(3)
    for xi in (-g, g):
        for eta in (-g, g):
            _, dx, dy = shapes(xi, eta)
            Bb = np.zeros((3, 12))
            Bb[0, 1::3], Bb[1, 2::3] = dx, dy
            Bb[2, 1::3], Bb[2, 2::3] = dy, dx
            K += Bb.T @ bending @ Bb * hx * hy / 4
    n, dx, dy = shapes(0.0, 0.0)
    Bs = np.zeros((2, 12))
    Bs[0, 0::3], Bs[0, 1::3] = dx, -n
    Bs[1, 0::3], Bs[1, 2::3] = dy, -n
    return K + Bs.T @ shear @ Bs * hx * hy


def plate_deflection(held: str, clamped: bool, point: float = 0.0,
                     pressure: float = 0.0, front: bool = False,
                     centre: bool = False) -> float:
    """mm: the largest deflection (or, ``centre``, the centre's) of the A x B plate held
    on the edges ``held`` (of 'LRBT': x = 0, x = A, y = 0, y = B), simply supported or
    ``clamped``, under a ``point`` load (N) pressing on a 50 mm square midway between x =
    0 and A, about the centre or (``front``) from the edge y = 0 to 50 mm inside it, as
    furncheck presses a point load on a plate (``tolerances.PLATE_LOAD_PATCH``; the cells
    whose centres lie in the square share it), and a uniform ``pressure`` (N/mm^2)."""
    n = CELLS + 1
    hx, hy = A / CELLS, B / CELLS
    Ke = element_stiffness(hx, hy)
    y0 = 0.0 if front else B / 2 - PATCH / 2
    rows, cols, values = [], [], []
    f = np.zeros(3 * n * n)
    loaded = []
    for j in range(CELLS):
        for i in range(CELLS):
            nodes = [j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i]
            dofs = np.array([[3 * k, 3 * k + 1, 3 * k + 2] for k in nodes]).ravel()
            rows.append(np.repeat(dofs, 12))
            cols.append(np.tile(dofs, 12))
            values.append(Ke.ravel())
            f[dofs[0::3]] += pressure * hx * hy / 4
            if abs((i + 0.5) * hx - A / 2) < PATCH / 2 and y0 < (j + 0.5) * hy < y0 + PATCH:
                loaded.append(dofs[0::3])
    for corners in loaded:
        f[corners] += point / (4 * len(loaded))
    K = sp.csr_matrix((np.concatenate(values), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(3 * n * n, 3 * n * n))
    edges = {"L": [j * n for j in range(n)], "R": [j * n + CELLS for j in range(n)],
             "B": list(range(n)), "T": [CELLS * n + i for i in range(n)]}
    fixed = set()
    for edge in held:
        for k in edges[edge]:
            fixed.update([3 * k, 3 * k + 1, 3 * k + 2] if clamped else [3 * k])
    free = np.array(sorted(set(range(3 * n * n)) - fixed))
    u = np.zeros(3 * n * n)
    u[free] = spla.spsolve(K[free][:, free].tocsc(), f[free])
    if centre:
        return float(u[3 * ((CELLS // 2) * n + CELLS // 2)])
    return float(np.abs(u[0::3]).max())


def furncheck_sag(panels: list[str], front: bool = False, beams_only: bool = False) -> float:
    from furncheck import tolerances as tol
    from furncheck.check import check_design
    from furncheck.design import parse_design

    text = DESIGN.replace("@PANELS", "\n".join(panels))
    if front:                   # the load 10 mm inside the top's free front edge
        text = text.replace("at: [0, 0, 550]", "at: [0, -190, 550]")
    share = tol.PLATE_HELD_SHARE
    tol.PLATE_HELD_SHARE = float("inf") if beams_only else share   # no plank a plate
    try:
        report = check_design(parse_design(text, "top.yaml", "yaml"))
    finally:
        tol.PLATE_HELD_SHARE = share
    (case,) = report.cases
    return next(float(p.sag) for p in case.planks if p.id == "top")


def main() -> None:
    q = 1e-3
    strip = 5 * q * A ** 4 / (384 * E * T ** 3 / (12 * (1 - NU ** 2)))
    plate = plate_deflection("LR", False, pressure=q, centre=True)
    print(f"check: two edges simply supported, uniform {q} N/mm^2: plate centre {plate:.4f} mm, "
          f"strip 5 q L^4 / 384 D {strip:.4f} mm ({100 * (plate / strip - 1):+.2f} %)")
    print()
    print("| top held on | plate, simply supported (mm) | plate, clamped (mm) "
          "| furncheck, beams alone (mm) | furncheck (mm) |")
    print("|---|---:|---:|---:|---:|")
    for name, held, panels, front in (
            ("two edges (sides)", "LR", [], False),
            ("three edges (sides, back)", "LRT", [BACK], False),
            ("four edges (sides, back, front)", "LRTB", [BACK, FRONT], False),
            ("two edges, the load 10 mm inside the front edge", "LR", [], True),
            ("three edges, the load 10 mm inside the front edge", "LRT", [BACK], True)):
        simply = plate_deflection(held, False, point=P, front=front)
        clamped = plate_deflection(held, True, point=P, front=front)
        print(f"| {name} | {simply:.2f} | {clamped:.2f} | "
              f"{furncheck_sag(panels, front, beams_only=True):.2f} | "
              f"{furncheck_sag(panels, front):.2f} |")


if __name__ == "__main__":
    main()
