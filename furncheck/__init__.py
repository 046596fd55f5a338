"""furncheck: physical validity of nail-jointed plank furniture.

The package follows the pipeline a design takes:

    design    load + check a design file -> a frozen Design (SI units inside)
    geometry  joints, ground contacts, connectivity
    statics   sparse mixed-formulation solve -> joint wrenches, contact forces
    validity  durability and stability verdicts -> DesignReport
    report    text / json / junit / github / sarif reporters

Command-line code lives in ``furncheck.cli`` (the ``cli/`` folder of the source tree).
"""

__version__ = "0.1.0"
