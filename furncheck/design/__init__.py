"""Design files -> frozen ``Design`` values (SI units inside)."""

from furncheck.design.model import Design, JointSpec, Load, LoadCase, Material, Plank

__all__ = ["Design", "JointSpec", "Load", "LoadCase", "Material", "Plank"]
