"""Design files -> frozen ``Design`` values (SI units inside), and back."""

from furncheck.design.load import load_design, parse_design
from furncheck.design.model import Design, JointSpec, Load, LoadCase, Material, Plank

__all__ = ["Design", "JointSpec", "Load", "LoadCase", "Material", "Plank",
           "design_to_document", "load_design", "parse_design", "write_design"]


def __getattr__(name: str):
    """The writer's names, imported on first use: a plain validate writes no design."""
    if name in ("design_to_document", "write_design"):
        from furncheck.design import write

        return getattr(write, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
