"""A generated catalog of small shelving designs (5 to 30 planks), for throughput benchmarks.

    python benchmarks/catalog.py DIR [--count N] [--seed S]

writes N design files ``DIR/shelf-00000.yaml`` ... (default 1,000), the same files for the
same seed.  Each is a wall of 1 to 3 bays (``shelving.shelving_wall``'s layout: sides
standing on the ground, shelves nailed between them) of a random size: bay width, depth,
shelf pitch and plank thickness vary, about half have a top plank across the sides, the
shelves carry books (at their centres, spread, or off centre), and a third have a second
load case that pushes the top sideways, so the catalog holds valid designs and invalid
ones of several kinds (sagging, non-durable joints, toppling, sliding).
"""

from __future__ import annotations

import argparse
import random
from pathlib import Path

from furncheck.design.model import Design, Load, LoadCase, Material, Plank

MIN_PLANKS, MAX_PLANKS = 5, 30


def random_shelving(rng: random.Random, name: str) -> Design:
    """One design of MIN_PLANKS to MAX_PLANKS planks drawn from ``rng`` (see the module
    docstring)."""
    while True:
        columns, rows = rng.randint(1, 3), rng.randint(1, 9)
        top = rng.random() < 0.5
        count = columns + 1 + columns * rows + top
        if MIN_PLANKS <= count <= MAX_PLANKS:
            break
    bay = rng.choice((0.30, 0.40, 0.50, 0.60, 0.80))          # m, between two sides
    depth = rng.choice((0.20, 0.25, 0.30, 0.40))
    pitch = rng.choice((0.20, 0.25, 0.30, 0.35))
    thickness = rng.choice((0.012, 0.016, 0.018, 0.025))
    height = pitch * (rows + 1)
    planks = [Plank(f"side{c}", height, depth, thickness,
                    (c * (bay + thickness), 0.0, height / 2), (0.0, 90.0, 0.0))
              for c in range(columns + 1)]
    books = []
    for c in range(columns):
        x = c * (bay + thickness) + thickness / 2 + bay / 2
        for r in range(rows):
            shelf = f"shelf{c}_{r}"
            planks.append(Plank(shelf, bay, depth, thickness, (x, 0.0, pitch * (r + 1))))
            mass = rng.choice((2.0, 5.0, 8.0, 12.0, 20.0))
            where = rng.random()
            if where < 0.4:
                books.append(Load.of_mass(shelf, mass))
            elif where < 0.8:
                books.append(Load.of_mass(shelf, mass, spread=True))
            else:   # off centre, on the shelf's top face
                off = rng.choice((-0.3, -0.15, 0.15, 0.3)) * bay
                books.append(Load.of_mass(shelf, mass,
                                          (x + off, 0.0, pitch * (r + 1) + thickness / 2)))
    if top:
        width = columns * (bay + thickness) + thickness
        planks.append(Plank("top", width, depth, thickness,
                            (width / 2 - thickness / 2, 0.0, height + thickness / 2)))
    cases = [LoadCase("default", tuple(books))]
    if rng.random() < 0.35:
        highest = planks[-1]
        push = rng.choice((20.0, 60.0, 150.0))
        cases.append(LoadCase("push", tuple(books) + (
            Load(highest.id, (push, 0.0, 0.0), highest.center),),
            includes=("default",), origins=("default",) * len(books) + ("push",)))
    return Design(name, tuple(planks), tuple(cases), Material(thickness=thickness),
                  model=rng.choice(("elastic", "elastic", "rigid")))


def write_catalog(directory: str | Path, count: int, seed: int = 16) -> list[Path]:
    """Write ``count`` designs into ``directory`` (created); the paths, in order."""
    from furncheck.design import write_design

    folder = Path(directory)
    folder.mkdir(parents=True, exist_ok=True)
    rng = random.Random(seed)
    paths = []
    for k in range(count):
        path = folder / f"shelf-{k:05d}.yaml"
        write_design(random_shelving(rng, f"shelf-{k:05d}"), str(path))
        paths.append(path)
    return paths


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("directory")
    parser.add_argument("--count", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=16)
    args = parser.parse_args()
    paths = write_catalog(args.directory, args.count, args.seed)
    print(f"{len(paths)} designs in {args.directory}")


if __name__ == "__main__":
    main()
