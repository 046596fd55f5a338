"""Benchmark: `range` for every DOF of catalog designs, in-process.

Prints, per design and statics model (rigid and elastic, one row each, in the same run):
planks, DOFs, DOFs that can move, full-check evaluations, total time and time per movable
DOF.  The targets for the ~28-plank catalog design (all DOFs) on the project's 2-core
machine: 1 s in the rigid model, 2 s in the elastic one.  The catalog's cabinet is
invalid in the elastic model (its plates sag); ``benchmarks/cabinet-28-fixed.yaml``, the
cabinet with ``suggest``'s first fix, is a valid one, the case the targets were set on.

    python benchmarks/bench_range.py [--jobs N] [DESIGN ...]   (default: a few catalog
                                                                designs, one process)

With ``--jobs 2`` the DOFs are searched in two worker processes.  Like the command line
(``furncheck.cli``), the benchmark runs numpy with one BLAS thread (see
``RangeFinder.ranges``).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import furncheck.cli  # noqa: F401  (first: one BLAS thread, as the command line runs)
from furncheck.design import load_design
from furncheck.design.model import with_model
from furncheck.ranges import RangeFinder

CATALOG = Path(__file__).resolve().parent.parent / "designs"
DEFAULT = ("shelf-cantilever.yaml", "stool.yaml", "table.yaml", "bookshelf-20.yaml",
           "cabinet-28.yaml")


def main(paths: list[str], jobs: int = 1) -> None:
    print("| design                  | model   | planks | DOFs | movable | evaluations |"
          " time (s) | ms per movable DOF |")
    print("|-------------------------|---------|-------:|-----:|--------:|------------:|"
          "---------:|-------------------:|")
    for path, model in ((path, model) for path in paths for model in ("rigid", "elastic")):
        design = with_model(load_design(path), model)
        start = time.perf_counter()
        finder = RangeFinder(design)
        ranges = finder.ranges(jobs=jobs)
        seconds = time.perf_counter() - start
        movable = sum(r.valid is not None or (r.reason or "").startswith("the current")
                      for r in ranges)
        # an invalid design has no valid range to move in: no time per movable DOF
        per_dof = f"{1000 * seconds / movable:.0f}" if movable else "-"
        print(f"| {Path(path).name:<23} | {model:<7} | {len(design.planks):>6} | "
              f"{len(ranges):>4} | "
              f"{movable:>7} | {finder.evaluations:>11} | {seconds:>8.2f} | "
              f"{per_dof:>18} |")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("designs", nargs="*", metavar="DESIGN",
                        help="design files (default: " + ", ".join(DEFAULT) + ")")
    parser.add_argument("--jobs", type=int, default=1,
                        help="worker processes that search the DOFs (default 1)")
    options = parser.parse_args()
    main(options.designs or [str(CATALOG / name) for name in DEFAULT], options.jobs)
