"""Benchmark: `suggest` on designs shaped like the paper's Table 1, in-process.

The designs (``table1_designs``: 9 planks/13 joints, 10/13, 20/33, 28/49, each with one
failing joint) go through ``suggest_design``.  The *suggestion step* is what the paper's
Table 1 times: candidates (margins and sensitivities of every DOF, directions of one to
three DOFs), line searches with the full statics, and discrete suggestions (support
planks); it is compared with the paper's totals (a 2.8 GHz Core i7 laptop, 2012).  The
*total* adds what furncheck does on top: validating the input design first, and writing
every suggestion's design file and validating it again from its text.  Medians of
``--repeat`` runs (default 11); the machine's speed varies by 20-30 % between runs.  Both
statics models run in the same process, one row each, so they meet the same speed phase.

    python benchmarks/bench_suggest.py [--repeat N]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import furncheck.cli  # noqa: F401  (first: one BLAS thread, as the command line runs)
from furncheck.design.model import with_model
from furncheck.dofs import all_dofs
from furncheck.geometry import analyze
from furncheck.suggest import suggest_design

sys.path.insert(0, str(Path(__file__).resolve().parent))
from table1_designs import TABLE1, table1_design  # noqa: E402


def main(repeat: int) -> None:
    print("| model | planks | joints | DOFs | continuous | discrete | line searches | "
          "full checks | candidates (ms) | line search (ms) | discrete (ms) | step (ms) | "
          "paper (ms) | faster | total (ms) |")
    print("|-------|-------:|-------:|-----:|-----------:|---------:|--------------:|"
          "------------:|----------------:|-----------------:|--------------:|----------:|"
          "-----------:|-------:|-----------:|")
    for (planks, (_, paper_ms)), model in ((item, model) for item in TABLE1.items()
                                           for model in ("rigid", "elastic")):
        design = with_model(table1_design(planks), model)
        runs = []
        for _ in range(repeat):
            start = time.perf_counter()
            result = suggest_design(design)
            runs.append((time.perf_counter() - start, result))
        total = statistics.median(seconds for seconds, _ in runs)
        phases = {name: 1000 * statistics.median(r.seconds[name] for _, r in runs)
                  for name in ("candidates", "line search", "discrete")}
        step = 1000 * statistics.median(sum(r.seconds.values()) for _, r in runs)
        result = runs[0][1]
        kinds = [s.kind for s in result.suggestions]
        print(f"| {model:<7} | {planks:>6} | {len(analyze(design).joints):>6} | "
              f"{len(all_dofs(design)):>4} | "
              f"{kinds.count('continuous'):>10} | {kinds.count('discrete'):>8} | "
              f"{result.searched:>13} | {result.checks:>11} | "
              f"{phases['candidates']:>15.0f} | {phases['line search']:>16.0f} | "
              f"{phases['discrete']:>13.0f} | {step:>9.0f} | {paper_ms:>10} | "
              f"{paper_ms / step:>5.1f}x | {1000 * total:>10.0f} |")

if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=11)
    main(parser.parse_args().repeat)
