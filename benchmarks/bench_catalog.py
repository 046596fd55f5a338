"""Benchmark: catalogs through the command line, and the cold start, old and new side by side.

    python benchmarks/bench_catalog.py [--old TREE] [--count N] [--repeat R] [--big M]
                                       [--skip-cold]

Prints three tables (medians of R runs; the old and new commands run alternately, so a
machine whose speed drifts slows both alike):

1. cold start: ``python -c "import numpy, yaml, click"`` (the floor), then ``furncheck
   validate designs/stool.yaml`` as a fresh process (the installed ``furncheck`` script,
   and each tree's command line), with the ratio to the floor; and what the modules that
   ``validate`` may import cost (``python -X importtime``, the new tree);
2. throughput: ``validate --format json`` of N generated designs of 5 to 30 planks
   (``benchmarks/catalog.py``) with ``--jobs 1`` and ``--jobs 2``: seconds, designs per
   second, peak RSS of the largest process, and a small catalog (10 designs) with
   ``--jobs 2`` against ``--jobs 1``;
3. memory over a large catalog: M designs (default 10,000) with ``--jobs 2``, its peak
   RSS next to the N-design run's (flat when the report is streamed).

TREE is a source tree of furncheck (e.g. a git worktree of an older commit); both trees
run under this Python, through ``TREE/cli`` as the package ``furncheck.cli``, with one
BLAS thread (as the command line sets) and bytecode written (as after a first run: this
checks out ``PYTHONDONTWRITEBYTECODE``, and one warm-up run of each command writes it).
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
NEW_TREE = HERE.parent
sys.path.insert(0, str(HERE))

LAUNCHER = """\
import importlib.util, sys
tree = sys.argv.pop(1)
sys.path.insert(0, tree)
import furncheck
spec = importlib.util.spec_from_file_location(
    "furncheck.cli", tree + "/cli/__init__.py", submodule_search_locations=[tree + "/cli"])
cli = importlib.util.module_from_spec(spec)
sys.modules["furncheck.cli"] = cli
spec.loader.exec_module(cli)
from furncheck.cli import main as command
sys.argv[0] = "furncheck"
getattr(command, "run", command.main)()   # the console script's entry (older trees: main)
"""


def environment() -> dict[str, str]:
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1",
               MKL_NUM_THREADS="1")
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    env.pop("PYTHONPATH", None)
    return env


def run(command: list[str]) -> tuple[float, float]:
    """(wall seconds, peak RSS MB of the largest process of the run)."""
    start = time.perf_counter()
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                               env=environment(), cwd=NEW_TREE)
    _, status, usage = os.wait4(process.pid, 0)
    seconds = time.perf_counter() - start
    if os.waitstatus_to_exitcode(status) not in (0, 1):
        raise SystemExit(f"{' '.join(command)} failed ({status})")
    return seconds, usage.ru_maxrss / 1024


def tree_command(tree: Path) -> list[str]:
    return [sys.executable, "-c", LAUNCHER, str(tree)]


def uncached(tree: Path) -> list[str]:
    """``--no-cache`` for a tree that has the result cache: every run checks every design
    (a warm cache is ``bench_cache.py``'s table)."""
    return ["--no-cache"] if (tree / "furncheck" / "cache.py").exists() else []


def medians(commands: dict[str, list[str]], repeat: int) -> dict[str, tuple[float, float]]:
    """Each command run once to warm up, then ``repeat`` times in turn: median seconds and
    the largest peak RSS."""
    for command in commands.values():
        run(command)
    samples: dict[str, list[tuple[float, float]]] = {name: [] for name in commands}
    for _ in range(repeat):
        for name, command in commands.items():
            samples[name].append(run(command))
    return {name: (statistics.median(s for s, _ in runs), max(m for _, m in runs))
            for name, runs in samples.items()}


def cold_start(trees: dict[str, Path], repeat: int) -> None:
    stool = NEW_TREE / "designs" / "stool.yaml"
    commands = {"floor: python -c \"import numpy, yaml, click\"":
                [sys.executable, "-c", "import numpy, yaml, click"]}
    script = Path(sys.executable).with_name("furncheck")
    if script.exists():
        commands["furncheck validate designs/stool.yaml (installed)"] = \
            [str(script), "validate", str(stool), *uncached(NEW_TREE)]
    for side, tree in trees.items():
        commands[f"{side}: validate designs/stool.yaml"] = \
            tree_command(tree) + ["validate", str(stool), *uncached(tree)]
    found = medians(commands, repeat)
    floor = next(iter(found.values()))[0]
    print("| cold start | median (ms) | x floor |")
    print("|---|---:|---:|")
    for name, (seconds, _) in found.items():
        print(f"| {name} | {seconds * 1000:.0f} | {seconds / floor:.2f} |")


IMPORTS = ("scipy.linalg", "scipy.sparse", "scipy.sparse.linalg", "scipy.optimize",
           "furncheck.cli.main", "furncheck.check")
"""What ``validate`` may import beyond numpy, yaml and click: each one's import time."""


def import_costs(repeat: int) -> None:
    """``python -X importtime``: each module's cumulative import time after numpy, yaml
    and click (the least of ``repeat`` runs: the machine's other load only adds)."""
    print("\n| import (after numpy, yaml, click) | ms (least of "
          f"{repeat} runs) |")
    print("|---|---:|")
    for module in ("numpy, yaml, click",) + IMPORTS:
        names = module.split(", ")
        code = "import numpy, yaml, click" if len(names) > 1 else \
            f"import numpy, yaml, click; import {module}"
        times = []
        for _ in range(repeat):
            done = subprocess.run([sys.executable, "-X", "importtime", "-c", code],
                                  capture_output=True, text=True, env=environment(),
                                  cwd=NEW_TREE)
            cumulative = {line.split("|")[2].strip(): int(line.split("|")[1])
                          for line in done.stderr.splitlines()
                          if line.startswith("import time:") and "self" not in line}
            times.append(sum(cumulative.get(name, 0) for name in names))
        print(f"| {module} | {min(times) / 1000:.0f} |")


def _validate_commands(trees: dict[str, Path], folder: Path) -> dict[str, list[str]]:
    """``validate FOLDER --format json --no-cache`` with ``--jobs`` 1 and 2, per tree."""
    return {f"{side} --jobs {jobs}": tree_command(tree) + [
                "validate", str(folder), "--format", "json", "--jobs", str(jobs),
                *uncached(tree)]
            for side, tree in trees.items() for jobs in (1, 2)}


def throughput(trees: dict[str, Path], catalog: Path, small: Path, repeat: int,
               count: int) -> dict[str, tuple[float, float]]:
    found = medians(_validate_commands(trees, catalog), repeat)
    print(f"\n| {count} designs, --format json | seconds | designs/s | peak RSS (MB) |")
    print("|---|---:|---:|---:|")
    for name, (seconds, rss) in found.items():
        print(f"| {name} | {seconds:.2f} | {count / seconds:.0f} | {rss:.0f} |")
    if "old" in trees:
        ratio = found["old --jobs 2"][0] / found["new --jobs 2"][0]
        print(f"\nnew --jobs 2 / old --jobs 2: {ratio:.2f}x the designs per second")
    found_small = medians(_validate_commands(trees, small), repeat)
    print("\n| 10 designs, --format json | seconds |")
    print("|---|---:|")
    for name, (seconds, _) in found_small.items():
        print(f"| {name} | {seconds:.2f} |")
    return found


def memory(trees: dict[str, Path], catalog: Path, count: int,
           smaller: dict[str, tuple[float, float]], smaller_count: int) -> None:
    print(f"\n| --jobs 2, --format json | peak RSS, {smaller_count} designs (MB) | "
          f"peak RSS, {count} designs (MB) | seconds, {count} designs |")
    print("|---|---:|---:|---:|")
    for side, tree in trees.items():
        seconds, rss = run(tree_command(tree) + ["validate", str(catalog), "--format", "json",
                                                 "--jobs", "2", *uncached(tree)])
        print(f"| {side} | {smaller[f'{side} --jobs 2'][1]:.0f} | {rss:.0f} | {seconds:.0f} |")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--old", type=Path, default=None, help="an older furncheck tree")
    parser.add_argument("--count", type=int, default=1000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--big", type=int, default=10000, help="0: no memory table")
    parser.add_argument("--skip-cold", action="store_true")
    args = parser.parse_args()

    from catalog import write_catalog

    trees = {"old": args.old.resolve()} if args.old else {}
    trees["new"] = NEW_TREE
    if not args.skip_cold:
        cold_start(trees, max(args.repeat, 9))
        import_costs(max(args.repeat, 7))
    with tempfile.TemporaryDirectory() as folder:
        catalog, small = Path(folder) / "catalog", Path(folder) / "small"
        paths = write_catalog(catalog, args.big or args.count)
        small.mkdir()
        for path in paths[:10]:
            shutil.copy(path, small / path.name)
        if args.big:        # the first --count of the big catalog's designs
            part = Path(folder) / "part"
            part.mkdir()
            for path in paths[:args.count]:
                os.link(path, part / path.name)
        found = throughput(trees, part if args.big else catalog, small, args.repeat,
                           args.count)
        if args.big:
            memory(trees, catalog, args.big, found, args.count)


if __name__ == "__main__":
    main()
