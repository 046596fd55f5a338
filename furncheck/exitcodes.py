"""Exit codes of every furncheck command (contract section 4), decided in one place."""

OK = 0
"""Every design valid (validate), or the command did its job (suggest, range)."""
INVALID = 1
"""At least one design is physically or geometrically invalid (validate only)."""
BAD_INPUT = 2
"""Some input was unreadable or ill-formed, or the command line was wrong."""
SIGNALLED = 128
"""A run stopped by a signal exits with this plus the signal's number, as a shell reports
it: 130 for SIGINT (Ctrl-C; a CI's first cancel), 143 for SIGTERM (a CI's cancel or
timeout).  No finished run gives them: its report is incomplete (``-o FILE`` keeps the
old file)."""


def signalled(number: int) -> int:
    """Exit code of a run stopped by signal ``number``."""
    return SIGNALLED + number


def validate_code(any_error: bool, any_invalid: bool) -> int:
    """Exit code of ``furncheck validate``: an input error outranks an invalid design."""
    if any_error:
        return BAD_INPUT
    if any_invalid:
        return INVALID
    return OK
