"""Benchmark: ``furncheck range`` with ``--jobs 1`` and ``--jobs 2`` as fresh processes, old
and new tree side by side (medians, run alternately).

    python benchmarks/bench_range_jobs.py [--old TREE] [--repeat R] [DESIGN:MODEL ...]

Default designs: the small catalog designs (stool and table rigid, the cantilever shelf
elastic), where two worker processes used to be slower than one.  Trees run as in
``bench_catalog.py`` (this Python, one BLAS thread, bytecode written).
"""

from __future__ import annotations

import argparse
import statistics
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from bench_catalog import NEW_TREE, run, tree_command  # noqa: E402

DEFAULT = ("stool:rigid", "table:rigid", "shelf-cantilever:elastic")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--old", type=Path, default=None, help="an older furncheck tree")
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("designs", nargs="*", default=list(DEFAULT))
    args = parser.parse_args()
    trees = {"old": args.old.resolve()} if args.old else {}
    trees["new"] = NEW_TREE
    commands = {}
    for item in args.designs:
        name, model = item.split(":")
        for side, tree in trees.items():
            for jobs in (1, 2):
                commands[(name, model, side, jobs)] = tree_command(tree) + [
                    "range", str(NEW_TREE / "designs" / f"{name}.yaml"), "--model", model,
                    "--jobs", str(jobs), "--format", "json"]
    for command in commands.values():       # warm-up: bytecode
        run(command)
    samples: dict[tuple, list[float]] = {key: [] for key in commands}
    for _ in range(args.repeat):
        for key, command in commands.items():
            samples[key].append(run(command)[0])
    columns = [(side, jobs) for side in trees for jobs in (1, 2)]
    print("| design | model | " + " | ".join(f"{side} --jobs {jobs} (s)"
                                           for side, jobs in columns) + " |")
    print("|---|---|" + "---:|" * len(columns))
    for item in args.designs:
        name, model = item.split(":")
        print(f"| {name} | {model} | " + " | ".join(
            f"{statistics.median(samples[(name, model, side, jobs)]):.2f}"
            for side, jobs in columns) + " |")


if __name__ == "__main__":
    main()
