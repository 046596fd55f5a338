"""Design files -> frozen ``Design`` values (SI units inside), and back."""

from furncheck.design.load import load_design, parse_design
from furncheck.design.model import Design, JointSpec, Load, LoadCase, Material, Plank
from furncheck.design.write import design_to_document, write_design

__all__ = ["Design", "JointSpec", "Load", "LoadCase", "Material", "Plank",
           "design_to_document", "load_design", "parse_design", "write_design"]
