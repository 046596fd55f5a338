"""furncheck's command line (installed as the package ``furncheck.cli``).

Only click commands live here: parse the arguments, call the library, pick a reporter,
write, exit.  Nothing heavy (numpy, scipy) is imported at module level, so ``--help`` and
``--version`` start fast; the checker is imported inside the command that needs it.
"""

import os

for _threads in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    # The statics solves many small dense systems: a multi-threaded BLAS gains nothing on
    # them, its threads spin on the cores that --jobs worker processes need (measured:
    # the same wall time on twice the CPU).  Set before numpy is first imported; a value
    # the user set wins.
    os.environ.setdefault(_threads, "1")
