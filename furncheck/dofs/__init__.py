"""Design degrees of freedom and the geometric constraints that go with them (paper 6.1).

Every plank has eight DOFs, named ``<plank>.x|y|z`` (translation along world axes, file
length unit), ``<plank>.rx|ry|rz`` (rotation about world axes through the plank centre,
degrees) and ``<plank>.length|width`` (file length unit).  Changing one DOF keeps the
design's joints and ground contacts by adjusting the planks next to it, as in the paper:

* a plank whose end rests on the moved plank's face (it is the *edge plank* of that joint)
  follows by changing its length at that end, its other end staying where it is; a plank
  held by nothing else (no other joint, no ground) moves along rigidly instead;
* a plank's own jointed ends (and an end standing on the ground) stay where they are:
  lengthening a plank that is jointed at one end moves its free end, a rotation lengthens
  or shortens its jointed ends so that they stay on their faces;
* a change that would pull a jointed end off its face, lift a plank off the ground or push
  it in, cannot be compensated by these rules: the DOF is *blocked*, with the reason;
* loads ride on their planks (see ``_carried``).

The rules are applied exactly (not linearized), so ``apply_dof`` gives the edited design
for any step; whether the result still has the same joints and contacts is checked by the
full geometry (``furncheck.edit_check``).

Its modules: ``names`` (the DOFs, their values and the two refusals),
``frame`` (the constraint structure of a design), ``apply`` (``apply_dof``) and
``plank_edits`` (the plank arithmetic it uses, all SI).
"""

from furncheck.dofs.apply import apply_dof, carried_point, with_planks_carried
from furncheck.dofs.frame import End, Structure, structure
from furncheck.dofs.names import (
    DOF_KINDS,
    Blocked,
    Dof,
    OutOfReach,
    all_dofs,
    design_size,
    dof_value,
    parse_dof,
)
from furncheck.dofs.plank_edits import axis_rotation, euler_degrees

__all__ = ["DOF_KINDS", "Blocked", "Dof", "End", "OutOfReach", "Structure", "all_dofs",
           "apply_dof", "axis_rotation", "carried_point", "design_size", "dof_value",
           "euler_degrees", "parse_dof", "structure", "with_planks_carried"]
