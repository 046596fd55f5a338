"""Warm-cache throughput of ``furncheck validate`` on a generated catalog.

Writes ``--designs`` (default 1,000) shelving-wall designs of 5 to 28 planks (different
loads, so every file's content differs) into a temporary folder, then times whole commands
(``python -m furncheck.cli.main validate FOLDER --format F``, start-up included, run from
the temporary folder) alternately:

- old (``--old PYTHON``): an interpreter where another furncheck is installed, e.g. a
  version before the cache (it checks every design on every run);
- new, empty cache: this interpreter's furncheck, every design checked, results stored;
- new, warm cache: the same command again, every result read back.

Prints one row per format: median seconds and designs per second of each, and whether the
warm output was byte-identical to the cold one.  BLAS runs on one thread, as the command
line sets it.  ``--jobs`` is passed to every command (default 1).
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from shelving import shelving_wall  # noqa: E402

from furncheck.design.write import write_design  # noqa: E402

# (columns, rows): planks = columns + 1 + columns * rows, from 5 to 28
SHAPES = ((1, 3), (1, 6), (2, 2), (2, 4), (2, 6), (3, 3), (2, 9), (3, 5), (3, 8))


def write_catalog(folder: Path, count: int) -> None:
    """``count`` designs in ``folder``: shelving walls of the SHAPES in turn, books from
    2 to 12 kg in 0.01 kg steps (no two files alike)."""
    for index in range(count):
        columns, rows = SHAPES[index % len(SHAPES)]
        design = shelving_wall(columns, rows, books_kg=2.0 + (index % 1000) * 0.01)
        write_design(design, str(folder / f"wall-{index:05d}.yaml"))


def run(python: str, catalog: Path, fmt: str, jobs: int, cache: Path | None
        ) -> tuple[float, float, bytes]:
    """(wall seconds, CPU seconds, stdout) of one ``validate`` command run by ``python``
    (CPU: user + system time of the command and its worker processes)."""
    environment = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1",
                       MKL_NUM_THREADS="1")
    environment.pop("PYTHONPATH", None)
    environment.pop("FURNCHECK_CACHE_DIR", None)
    command = [python, "-m", "furncheck.cli.main", "validate", catalog.name, "--format", fmt,
               "--jobs", str(jobs)]
    if cache is not None:
        command += ["--cache-dir", str(cache)]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, env=environment, check=False,
                          cwd=catalog.parent)
    seconds = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode not in (0, 1):
        raise SystemExit(f"validate failed ({done.returncode}): {done.stderr.decode()[-500:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return seconds, cpu, done.stdout


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--designs", type=int, default=1000)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--formats", default="text,json")
    parser.add_argument("--old", default=None, metavar="PYTHON",
                        help="an interpreter with another furncheck installed, to time "
                             "alongside (it has no cache)")
    arguments = parser.parse_args()
    new = sys.executable
    with tempfile.TemporaryDirectory() as scratch:
        catalog = Path(scratch) / "catalog"
        catalog.mkdir()
        write_catalog(catalog, arguments.designs)
        rows = []
        for fmt in arguments.formats.split(","):
            times: dict[str, list[tuple[float, float]]] = {"old": [], "cold": [], "warm": []}
            identical = True
            for repeat in range(arguments.repeat):
                cache = Path(scratch) / f"cache-{fmt}-{repeat}"
                if arguments.old is not None:
                    times["old"].append(run(arguments.old, catalog, fmt, arguments.jobs,
                                            None)[:2])
                *measured, cold = run(new, catalog, fmt, arguments.jobs, cache)
                times["cold"].append(tuple(measured))
                *measured, warm = run(new, catalog, fmt, arguments.jobs, cache)
                times["warm"].append(tuple(measured))
                identical = identical and warm == cold
                shutil.rmtree(cache)
            rows.append((fmt, times, identical))
    count = arguments.designs
    print(f"{count} designs of 5-28 planks, --jobs {arguments.jobs}, medians of "
          f"{arguments.repeat} runs (whole command, start-up included; CPU: user + system "
          f"time of the command and its workers)\n")
    print("| format | run | wall (s) | designs/s | CPU (s) | designs per CPU s | "
          "output = cold output |")
    print("|--------|-----|---------:|----------:|--------:|------------------:|"
          ":--------------------:|")
    labels = {"old": "old, no cache", "cold": "new, empty cache", "warm": "new, warm cache"}
    for fmt, times, identical in rows:
        for run_name, measured in times.items():
            if not measured:
                continue
            wall = statistics.median(value[0] for value in measured)
            cpu = statistics.median(value[1] for value in measured)
            same = "-" if run_name != "warm" else ("yes" if identical else "NO")
            print(f"| {fmt} | {labels[run_name]} | {wall:.3f} | {count / wall:.0f} | "
                  f"{cpu:.3f} | {count / cpu:.0f} | {same} |")


if __name__ == "__main__":
    main()
