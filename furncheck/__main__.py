"""``python -m furncheck``: the ``furncheck`` command."""

from furncheck.cli.main import main

if __name__ == "__main__":
    main(prog_name="furncheck")
