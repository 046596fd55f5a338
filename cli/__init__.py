"""furncheck's command line (installed as the package ``furncheck.cli``).

Only click commands live here: parse the arguments, call the library, pick a reporter,
write, exit.  Nothing heavy (numpy, scipy) is imported at module level, so ``--help`` and
``--version`` start fast; the checker is imported inside the command that needs it.
"""
