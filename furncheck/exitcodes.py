"""Exit codes of every furncheck command (contract section 4), decided in one place."""

OK = 0
"""Every design valid (validate), or the command did its job (suggest, range)."""
INVALID = 1
"""At least one design is physically or geometrically invalid (validate only)."""
BAD_INPUT = 2
"""Some input was unreadable or ill-formed, or the command line was wrong."""


def validate_code(any_error: bool, any_invalid: bool) -> int:
    """Exit code of ``furncheck validate``: an input error outranks an invalid design."""
    if any_error:
        return BAD_INPUT
    if any_invalid:
        return INVALID
    return OK
