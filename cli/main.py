"""The ``furncheck`` command group (console script ``furncheck = furncheck.cli.main:main``)."""

from __future__ import annotations

import click

from furncheck import __version__
from furncheck.cli.range import range_command
from furncheck.cli.suggest import suggest
from furncheck.cli.validate import validate


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, "--version", prog_name="furncheck",
                      message="%(prog)s %(version)s")
def main() -> None:
    """Check nail-jointed plank furniture designs for durability and stability.

    validate: verdicts on design files; suggest: ranked changes that make an invalid
    design valid; range: valid interval of each design DOF.
    Exit codes: 0 all designs valid (or done), 1 some design invalid (validate), 2
    unreadable or ill-formed input, or a usage error.
    """


main.add_command(validate)
main.add_command(range_command)
main.add_command(suggest)


if __name__ == "__main__":  # pragma: no cover
    main()
