"""Benchmark: `suggest` on designs shaped like the paper's Table 1, in-process.

The designs (``table1_designs``: 9 planks/13 joints, 10/13, 20/33, 28/49, each with one
failing joint) go through the whole suggestion step -- margins and sensitivities of every
DOF, directions of one to three DOFs, line searches with the full statics, support planks
(discrete suggestions), validation of each suggestion's design file -- and the table
compares the time with the paper's
Table 1 totals (a 2.8 GHz Core i7 laptop, 2012).  Median of ``--repeat`` runs (default 5).

    python benchmarks/bench_suggest.py [--repeat N]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from table1_designs import TABLE1, table1_design  # noqa: E402

from furncheck.dofs import all_dofs  # noqa: E402
from furncheck.geometry import analyze  # noqa: E402
from furncheck.suggest import suggest_design  # noqa: E402


def main(repeat: int) -> None:
    print("| planks | joints | DOFs | continuous | discrete | line searches | full checks | "
          "candidates (ms) | line search (ms) | discrete (ms) | total (ms) | paper (ms) | faster |")
    print("|-------:|-------:|-----:|-----------:|---------:|--------------:|------------:|"
          "----------------:|-----------------:|--------------:|-----------:|-----------:|"
          "-------:|")
    for planks, (_, paper_ms) in TABLE1.items():
        design = table1_design(planks)
        runs = []
        for _ in range(repeat):
            start = time.perf_counter()
            result = suggest_design(design)
            runs.append((time.perf_counter() - start, result))
        total, result = sorted(runs, key=lambda run: run[0])[len(runs) // 2]
        seconds = result.seconds
        kinds = [s.kind for s in result.suggestions]
        print(f"| {planks:>6} | {len(analyze(design).joints):>6} | {len(all_dofs(design)):>4} | "
              f"{kinds.count('continuous'):>10} | {kinds.count('discrete'):>8} | "
              f"{result.searched:>13} | {result.checks:>11} | "
              f"{1000 * seconds['candidates']:>15.0f} | {1000 * seconds['line search']:>16.0f} | "
              f"{1000 * seconds['discrete']:>13.0f} | {1000 * total:>10.0f} | {paper_ms:>10} | "
              f"{paper_ms / (1000 * total):>5.1f}x |")

if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    main(parser.parse_args().repeat)
