"""Independent check of the elastic statics model (contract section 3a) against PyNite.

For three structures (a table pushed sideways, a bookcase with books and a push, a two-bay
wall of shelves with a long shelf continuous over its middle upright) the script builds the
furncheck design (YAML text, ``model: elastic``), runs ``check_design``, builds the same
structure in PyNite (``pip install furncheck[compare]``) and prints a markdown table of
every joint's force and moment (what the first listed plank exerts on the second, world
frame, moment about the joint point) from both, with their relative difference.

    python benchmarks/compare_pynite.py [--euler-bernoulli] [--bilateral]

How the structure is modelled in PyNite (SI units throughout):

- Planks: a chain of PyNite members along the plank's longer in-plane axis (the same axis
  furncheck uses), through its centre, with nodes at its ends, its centre and where a
  joint, ground contact or point load projects onto the axis.  Section b x t, A = b t,
  I about the width axis b t^3 / 12, about the face normal t b^3 / 12, the torsion constant
  J = a c^3 (1/3 - 0.21 (c/a) (1 - c^4 / (12 a^4))), E = elastic_modulus,
  G = shear_modulus.  PyNite's ``Member3D`` is an Euler-Bernoulli element; furncheck's
  beams are Timoshenko beams (shear area 5/6 A).  ``TimoshenkoMember`` adds the shear
  flexibility to PyNite's own element matrix (Phi = 12 E I / (k G A L^2) per bending
  plane); ``--euler-bernoulli`` runs the plain PyNite element instead, to show how much the
  shear deformation matters.
- Joints: PyNite has no zero-length 6-DOF spring, so each nail joint is three short
  members through the joint point P, one along each axis e of the joint frame (x, y, n),
  from P - l/2 e (tied to the first plank) to P + l/2 e (tied to the second), l = 5 mm,
  with both bending moments released at both ends (no transverse stiffness), E A / l =
  the joint's translational stiffness along e and G J / l = its rotational stiffness about
  e.  An axial force through P and a torque have no moment about P, so the three members
  together are exactly the diagonal spring W = diag(n k_s, n k_s, n k_w; k_w S,
  n k_w (t/2)^2, k_s S) in the joint frame, centred at P.
- Rigid arms (beam node -> joint-member end, beam node -> contact corner): very stiff
  members, 1e12 N/m axially and in shear (shear-flexible, so that a 2.5 mm arm is not
  1e15 N/m stiff and the conditioning stays sound) and >= 1e9 N m/rad in bending and
  torsion, section chosen per arm length.  Results move by < 1e-4 relative when these
  change ten-fold either way.
- Ground contacts: a node at every ground corner, tied to its plank's axis node by a rigid
  arm.  PyNite's supports are bilateral; furncheck's contacts are unilateral with Coulomb
  friction.  So the corners furncheck finds holding get support springs of 1e10 N/m in X,
  Y and Z (furncheck's contact and anchor stiffness), the corners it lifts get none, and
  the script checks the contact state independently in the PyNite solution: every held
  corner presses, its friction stays inside the cone (no furncheck contact slips in these
  cases), and every free corner rises.  ``--bilateral`` holds every corner instead, to
  show what the unilateral contacts change.
- Loads: self-weight and ``spread`` loads as uniform member loads (global FZ) along the
  plank's beam; point loads at the axis node of their point with their moment about it.

PyNite is a benchmark extra only (``compare`` in pyproject.toml), never a runtime
dependency of furncheck.
"""

from __future__ import annotations

import argparse
import math
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import yaml

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

try:
    from Pynite import FEModel3D
    from Pynite.Member3D import Member3D
    from Pynite.PhysMember import PhysMember
except ImportError:
    raise SystemExit("compare_pynite.py needs PyNite: pip install -e '.[compare]'") from None

from furncheck.check import check_design  # noqa: E402
from furncheck.design import parse_design  # noqa: E402
from furncheck.geometry import analyze  # noqa: E402
from furncheck.statics import build_model, solve_load_case  # noqa: E402

GRAVITY = 9.81
SHEAR_FACTOR = 5.0 / 6.0
CONTACT_STIFFNESS = 1e10          # N/m, furncheck's ELASTIC_CONTACT_STIFFNESS
SPRING_LENGTH = 0.005             # m, the joint members' length
RIGID_TRANSLATION = 1e12          # N/m, target stiffness of a rigid arm
RIGID_ROTATION = 1e9              # N m/rad
RIGID_E = 1e12                    # Pa, the arms' (fictitious) material
UPRIGHT = [0, -90, 0]


# --- PyNite element with Timoshenko shear flexibility ------------------------------------------

class TimoshenkoMember(Member3D):
    """PyNite's member with shear deformation: its Euler-Bernoulli matrix, with the bending
    terms of each plane scaled as Timoshenko's (Przemieniecki): 12 and 6 terms by
    1 / (1 + Phi), the 4 terms by (4 + Phi) / (4 (1 + Phi)), the 2 terms by
    (2 - Phi) / (2 (1 + Phi)), Phi = 12 E I / (k G A L^2)."""

    shear_area: float = 0.0

    def _ke_unc(self):
        ke = np.array(super()._ke_unc(), dtype=float)
        E, G, L = self.material.E, self.material.G, self.L()
        # plane x-y: v (1, 7), theta_z (5, 11), inertia Iz; plane x-z: w (2, 8), theta_y (4, 10)
        for (v1, v2), (r1, r2), inertia in (((1, 7), (5, 11), self.section.Iz),
                                            ((2, 8), (4, 10), self.section.Iy)):
            phi = 12.0 * E * inertia / (G * self.shear_area * L * L)
            scale = np.ones((12, 12))
            for i in (v1, v2):
                for j in (v1, v2, r1, r2):
                    scale[i, j] = scale[j, i] = 1.0 / (1.0 + phi)
            for r in (r1, r2):
                scale[r, r] = (4.0 + phi) / (4.0 * (1.0 + phi))
            scale[r1, r2] = scale[r2, r1] = (2.0 - phi) / (2.0 * (1.0 + phi))
            ke *= scale
        return ke


class WholeMember(PhysMember):
    """A physical member that PyNite does not split at other nodes lying on its line (a
    joint's spring members pass through the node of a plank ending at the joint point; they
    must not connect to it): it is discretized with only its two end nodes in view."""

    def descritize(self) -> None:
        nodes = self.model.nodes
        self.model.nodes = {self.i_node.name: self.i_node, self.j_node.name: self.j_node}
        try:
            super().descritize()
        finally:
            self.model.nodes = nodes


class TimoshenkoPhysMember(WholeMember):
    """A ``WholeMember`` whose sub-member is a ``TimoshenkoMember``."""

    shear_area: float = 0.0

    def descritize(self) -> None:
        super().descritize()
        for member in self.sub_members.values():
            member.__class__ = TimoshenkoMember
            member.shear_area = self.shear_area


# --- the designs -----------------------------------------------------------------------------

def table_design() -> dict:
    """physics_designs.table with 700 mm legs: top 1000 x 600 on four 60 mm legs at
    (+-444, +-270); a 30 kg load off centre and a sideways push at the top's end; a second
    case with 40 kg near one corner (twists the top)."""
    h = 700.0
    planks = [{"id": "top", "size": [1000, 600], "center": [0, 0, h + 6]}]
    for name, (x, y) in {"leg_pp": (444, 270), "leg_mp": (-444, 270),
                         "leg_pm": (444, -270), "leg_mm": (-444, -270)}.items():
        planks.append({"id": name, "size": [h, 60], "center": [x, y, h / 2],
                       "rotation": list(UPRIGHT)})
    return {"furncheck": 1, "name": "table", "model": "elastic", "planks": planks,
            "loads": [{"plank": "top", "mass": 30, "at": [200, 100, h + 12]},
                      {"plank": "top", "force": [40, 15, 0], "at": [500, 0, h + 6]}],
            "load_cases": {"corner": [{"plank": "top", "mass": 40,
                                       "at": [420, 250, h + 12]}]}}


def bookcase_design() -> dict:
    """Two sides 1200 x 300 at x = +-306, four shelves 600 x 300 between them (the top one
    flush with the sides' tops); books on every shelf, then the books and a 30 N push at
    the top of the left side."""
    planks = [{"id": "side_l", "size": [1200, 300], "center": [-306, 0, 600],
               "rotation": list(UPRIGHT)},
              {"id": "side_r", "size": [1200, 300], "center": [306, 0, 600],
               "rotation": list(UPRIGHT)}]
    books = []
    for k, z in enumerate((56, 420, 800, 1194)):
        planks.append({"id": f"shelf{k}", "size": [600, 300], "center": [0, 0, z]})
        books.append({"plank": f"shelf{k}", "mass": 15 if k < 3 else 5, "spread": True})
    return {"furncheck": 1, "name": "bookcase", "model": "elastic", "planks": planks,
            "loads": books,
            "load_cases": {"push": books + [{"plank": "side_l", "force": [30, 0, 0],
                                             "at": [-312, 0, 1150]}]}}


def chair_design() -> dict:
    """A chair-like frame with a plank out of the world's axes: two 900 x 420 sides
    standing on the floor 462 mm apart, a 450 x 380 seat nailed between them by its ends
    and a 450 x 300 back rest between them raked back 10 degrees (turned 80 degrees about
    x), its joint lines tilted with it; 60 kg on the seat, then that and 100 N pushing the
    back rest backwards at its centre (a structural engineer's cross-check, session 18:
    each member's section turned to the plank's width, where a test of PyNite's default
    local y against the width had laid the back rest's section 10 degrees off)."""
    planks = [{"id": "side_l", "size": [900, 420], "center": [-231, 0, 450],
               "rotation": list(UPRIGHT)},
              {"id": "side_r", "size": [900, 420], "center": [231, 0, 450],
               "rotation": list(UPRIGHT)},
              {"id": "seat", "size": [450, 380], "center": [0, -10, 450]},
              {"id": "back", "size": [450, 300], "center": [0, 150, 700],
               "rotation": [80, 0, 0]}]
    seat = [{"plank": "seat", "mass": 60, "at": [0, -10, 456]}]
    return {"furncheck": 1, "name": "chair", "model": "elastic", "planks": planks,
            "loads": seat,
            "load_cases": {"push": seat + [{"plank": "back", "force": [0, 100, 0],
                                            "at": [0, 144.091139, 701.041889]}]}}


def two_bay_design() -> dict:
    """Three uprights 1000 x 250 at x = -606, 0, 606; in each bay two shelves 594 x 250
    (z = 300 and 650) nailed between the uprights; a long top shelf 1224 x 250 on the
    uprights' top ends, continuous over the middle one.  Books on all shelves and 10 kg
    off-centre on the long shelf; then the same with a 25 N push along the wall."""
    planks = [{"id": f"up{k}", "size": [1000, 250], "center": [x, 0, 500],
               "rotation": list(UPRIGHT)} for k, x in enumerate((-606, 0, 606))]
    books = []
    for bay, x in (("l", -303), ("r", 303)):
        for level, z in ((0, 300), (1, 650)):
            name = f"shelf_{bay}{level}"
            planks.append({"id": name, "size": [594, 250], "center": [x, 0, z]})
            books.append({"plank": name, "mass": 12, "spread": True})
    planks.append({"id": "long", "size": [1224, 250], "center": [0, 0, 1006]})
    books += [{"plank": "long", "mass": 20, "spread": True},
              {"plank": "long", "mass": 10, "at": [300, 80, 1012]}]
    return {"furncheck": 1, "name": "two-bay", "model": "elastic", "planks": planks,
            "loads": books,
            "load_cases": {"push": books + [{"plank": "long", "force": [25, 0, 0],
                                             "at": [-612, 0, 1006]}]}}


class _NoAliases(yaml.SafeDumper):
    """Design files may not use YAML aliases: write shared values out."""

    def ignore_aliases(self, data) -> bool:
        return True


# --- the PyNite model --------------------------------------------------------------------------

@dataclass
class _Beam:
    """A plank as a beam: axis e1 through its centre, e2 the section's width, e3 its normal."""

    centre: np.ndarray
    e1: np.ndarray
    e2: np.ndarray
    e3: np.ndarray
    length: float
    width: float
    thickness: float
    stations: list
    members: list = field(default_factory=list)


def _beam_of(plank) -> _Beam:
    R = plank.rotation_matrix
    if plank.width > plank.length:
        e1, e2, length, width = R[:, 1], R[:, 0], plank.width, plank.length
    else:
        e1, e2, length, width = R[:, 0], R[:, 1], plank.length, plank.width
    return _Beam(np.asarray(plank.center_array, dtype=float), e1, e2, R[:, 2], length, width,
                 plank.thickness, [-length / 2, 0.0, length / 2])


def _torsion_constant(width: float, thickness: float) -> float:
    a, c = max(width, thickness), min(width, thickness)
    return a * c ** 3 * (1.0 / 3.0 - 0.21 * (c / a) * (1.0 - c ** 4 / (12.0 * a ** 4)))


class PyniteFrame:
    """One load case of a design as a PyNite model (see the module docstring)."""

    def __init__(self, design, geometry, case, joints, holding, timoshenko: bool):
        self.model = FEModel3D()
        self.design, self.timoshenko = design, timoshenko
        material = design.material
        self.model.add_material("mdf", material.elastic_modulus, material.shear_modulus,
                                0.3, material.density)
        self.model.add_material("rigid", RIGID_E, RIGID_E, 0.3, 0.0)
        self.model.add_material("spring", 1e9, 1e9, 0.3, 0.0)
        self.count = 0
        self.beams = {p.id: _beam_of(p) for p in design.planks}

        # where things attach along each beam
        def station(plank_id, point):
            beam = self.beams[plank_id]
            s = float((np.asarray(point, dtype=float) - beam.centre) @ beam.e1)
            beam.stations.append(min(max(s, -beam.length / 2), beam.length / 2))
            return s

        for joint in joints:
            for plank_id in joint.planks:
                station(plank_id, joint.point)
        for contact in geometry.contacts:
            station(contact.plank, contact.point)
        for load in case.loads:
            if not load.spread and load.point is not None:
                station(load.plank, load.point)

        self.nodes = {}
        self.springs = []          # per joint: (member, its start point) of its 3 members
        for plank in design.planks:
            self._add_beam(plank)
        for joint in joints:
            self._add_joint(joint)
        self.corners = []          # (node, holds) per contact of the geometry
        for contact, hold in zip(geometry.contacts, holding):
            corner = self._node(contact.point)
            self._rigid(self._axis_node(contact.plank, contact.point), corner)
            if hold:               # a lifted corner is only watched: does it rise?
                for dof in ("DX", "DY", "DZ"):
                    self.model.def_support_spring(corner, dof, CONTACT_STIFFNESS)
            self.corners.append((corner, bool(hold)))
        self._add_loads(case)
        self.joints = joints

    # -- building ---------------------------------------------------------------------------
    def _node(self, point) -> str:
        self.count += 1
        name = f"N{self.count}"
        self.model.add_node(name, *(float(v) for v in point))
        return name

    def _member(self, i: str, j: str, material: str, A: float, I_a: float, I_b: float,
                J: float, axis_a=None) -> str:
        """A member i -> j; I_a is the inertia about the axis ``axis_a`` (world), I_b about
        the third axis (when axis_a is None, both inertias are equal)."""
        self.count += 1
        name = f"M{self.count}"
        self.model.add_section(f"S{self.count}", A, 1.0, 1.0, J)
        self.model.add_member(name, i, j, material, f"S{self.count}")
        member = self.model.members[name]
        member.__class__ = WholeMember
        if axis_a is not None:      # turn the member about its axis: local y along axis_a
            x, y = member.T()[0, :3], member.T()[1, :3]
            member.rotation = math.degrees(math.atan2(float(np.cross(x, y) @ axis_a),
                                                      float(y @ axis_a)))
            assert abs(abs(float(member.T()[1, :3] @ axis_a)) - 1.0) < 1e-9
        member.section.Iy, member.section.Iz = I_a, I_b
        return name

    def _add_beam(self, plank) -> None:
        beam = self.beams[plank.id]
        stations = sorted(beam.stations)
        merged = [stations[0]]
        for s in stations[1:]:
            if s - merged[-1] > 1e-7:
                merged.append(s)
        names = [self._node(beam.centre + s * beam.e1) for s in merged]
        self.nodes[plank.id] = (np.array(merged), names)
        b, t = beam.width, beam.thickness
        weight = self.design.plank_mass(plank) * GRAVITY / beam.length
        for a, c in zip(names[:-1], names[1:]):
            name = self._member(a, c, "mdf", b * t, b * t ** 3 / 12.0, t * b ** 3 / 12.0,
                                _torsion_constant(b, t), axis_a=beam.e2)
            if self.timoshenko:
                member = self.model.members[name]
                member.__class__ = TimoshenkoPhysMember
                member.shear_area = SHEAR_FACTOR * b * t
            self.model.add_member_dist_load(name, "FZ", -weight, -weight)
            beam.members.append(name)

    def _axis_node(self, plank_id: str, point) -> str:
        beam = self.beams[plank_id]
        s = float((np.asarray(point, dtype=float) - beam.centre) @ beam.e1)
        stations, names = self.nodes[plank_id]
        return names[int(np.argmin(np.abs(stations - s)))]

    def _rigid(self, i: str, j: str) -> None:
        """A rigid arm i -> j: a member with axial and shear stiffness RIGID_TRANSLATION
        (N/m; a shear-flexible member, so that a short arm's transverse stiffness does not
        grow as 1 / L^3 and spoil the conditioning) and bending and torsional stiffness of
        at least RIGID_ROTATION (N m/rad)."""
        a, b = self.model.nodes[i], self.model.nodes[j]
        L = float(np.linalg.norm([b.X - a.X, b.Y - a.Y, b.Z - a.Z]))
        assert L > 1e-6, "a rigid arm of zero length"
        A = RIGID_TRANSLATION * L / RIGID_E
        inertia = max(RIGID_TRANSLATION * L ** 3 / 12.0, RIGID_ROTATION * L) / RIGID_E
        name = self._member(i, j, "rigid", A, inertia, inertia, RIGID_ROTATION * L / RIGID_E)
        member = self.model.members[name]
        member.__class__ = TimoshenkoPhysMember
        member.shear_area = A

    def _add_joint(self, joint) -> None:
        material = self.design.material
        n = joint.nails
        y = (np.arange(n) + 0.5) * joint.length / n - joint.length / 2
        S = float(y @ y) if n > 1 else joint.length ** 2 / 12.0
        half = joint.edge_thickness / 2
        k_s, k_w = material.nail_slip, material.nail_withdrawal
        translation = (n * k_s, n * k_s, n * k_w)
        rotation = (k_w * S, n * k_w * half * half, k_s * S)
        point = np.asarray(joint.point, dtype=float)
        node_a = self._axis_node(joint.planks[0], point)
        node_b = self._axis_node(joint.planks[1], point)
        springs = []
        for axis in range(3):
            e = np.asarray(joint.frame, dtype=float)[:, axis]
            end_a = self._node(point - 0.5 * SPRING_LENGTH * e)
            end_b = self._node(point + 0.5 * SPRING_LENGTH * e)
            self._rigid(node_a, end_a)
            self._rigid(node_b, end_b)
            name = self._member(end_a, end_b, "spring", translation[axis] * SPRING_LENGTH / 1e9,
                                1.0, 1.0, rotation[axis] * SPRING_LENGTH / 1e9)
            self.model.def_releases(name, Ryi=True, Rzi=True, Ryj=True, Rzj=True)
            springs.append((name, point - 0.5 * SPRING_LENGTH * e))
        self.springs.append(springs)

    def _add_loads(self, case) -> None:
        for load in case.loads:
            beam = self.beams[load.plank]
            force = np.asarray(load.force, dtype=float)
            if load.spread:
                for name in beam.members:
                    for k, direction in enumerate(("FX", "FY", "FZ")):
                        if force[k]:
                            self.model.add_member_dist_load(name, direction,
                                                            force[k] / beam.length,
                                                            force[k] / beam.length)
                continue
            point = beam.centre if load.point is None else np.asarray(load.point, dtype=float)
            node = self._axis_node(load.plank, point)
            where = self.model.nodes[node]
            moment = np.cross(point - np.array([where.X, where.Y, where.Z]), force)
            for k, direction in enumerate(("FX", "FY", "FZ")):
                if force[k]:
                    self.model.add_node_load(node, direction, float(force[k]))
                if moment[k]:
                    self.model.add_node_load(node, "M" + direction[1], float(moment[k]))

    # -- solving and reading ------------------------------------------------------------------
    def solve(self) -> None:
        self.model.analyze_linear(check_stability=False)
        split = [name for name, member in self.model.members.items()
                 if len(member.sub_members) != 1]
        assert not split, f"PyNite split members at nodes lying on them: {split}"

    def joint_wrenches(self) -> np.ndarray:
        """(nJ, 6): force (N) and moment about the joint point (N m) that the first plank
        exerts on the second: the sum over the joint's three members of the force the
        first plank's side applies to the member at its start, and its moment about P."""
        out = []
        for joint, springs in zip(self.joints, self.springs):
            force, moment = np.zeros(3), np.zeros(3)
            for name, start in springs:
                (member,) = self.model.members[name].sub_members.values()
                F = np.asarray(member.F("Combo 1"), dtype=float).ravel()
                force += F[:3]
                moment += F[3:6] + np.cross(start - np.asarray(joint.point), F[:3])
            out.append(np.concatenate([force, moment]))
        return np.array(out)

    def contact_forces(self) -> np.ndarray:
        """(nK, 3) N, the ground's force on each contact corner (zero where lifted)."""
        out = []
        for corner, holds in self.corners:
            node = self.model.nodes[corner]
            displacement = np.array([node.DX["Combo 1"], node.DY["Combo 1"],
                                     node.DZ["Combo 1"]])
            out.append(-CONTACT_STIFFNESS * displacement if holds else np.zeros(3))
        return np.array(out)

    def lowest_lifted(self) -> float:
        """m, the lowest vertical displacement of a corner left free (>= 0: it does lift)."""
        return min((self.model.nodes[corner].DZ["Combo 1"]
                    for corner, holds in self.corners if not holds), default=np.inf)


# --- the comparison ------------------------------------------------------------------------------

def compare(design_dict: dict, timoshenko: bool = True,
            bilateral: bool = False) -> tuple[list, list]:
    """(table rows, notes) of one design, every load case.  ``bilateral``: PyNite holds
    every ground corner, whether furncheck lifts it or not."""
    design = parse_design(yaml.dump(design_dict, Dumper=_NoAliases, sort_keys=False),
                          f"{design_dict['name']}.yaml", "yaml")
    geometry = analyze(design)
    report = check_design(design, geometry)
    model = build_model(design, geometry)
    assert not geometry.violations, geometry.violations
    assert len(model.contacts) == len(geometry.contacts)
    mu = design.material.friction
    rows, notes = [], []
    for case, result in zip(design.load_cases, report.cases):
        statics = solve_load_case(model, case)
        ours = np.asarray(statics.contact_forces, dtype=float)
        holding = np.ones(len(geometry.contacts), dtype=bool)
        if not bilateral:
            holding[list(model.contacts)] = statics.holding
        tangential = np.hypot(ours[:, 0], ours[:, 1])
        slipping = statics.holding & (tangential >= 0.999 * mu * ours[:, 2])
        joints = [geometry.joints[j] for j in model.joints]
        frame = PyniteFrame(design, geometry, case, joints, holding, timoshenko)
        frame.solve()
        pynite = frame.joint_wrenches()
        theirs = frame.contact_forces()
        pressed = theirs[holding, 2]
        pushing = pressed > 0.0
        cone = np.hypot(theirs[holding, 0], theirs[holding, 1])[pushing] / pressed[pushing]
        notes.append(
            f"{design.name}/{case.name}: furncheck {result.stability}, "
            f"{int(statics.holding.sum())} of {len(model.contacts)} corners hold, "
            f"{int(slipping.sum())} slip, {sum(j.durable for j in result.joints)}"
            f"/{len(result.joints)} joints durable.  PyNite with "
            f"{int(holding.sum())} corners held: smallest normal force "
            f"{pressed.min():.4g} N ({int((~pushing).sum())} pull), largest friction use "
            f"|F_t| / N = {cone.max(initial=0.0):.3f} "
            f"(mu = {mu:g}), lowest free corner rises {1e6 * frame.lowest_lifted():.4g} um "
            "(inf: none free); "
            f"ground forces differ by at most {np.abs(theirs - ours).max():.3g} N "
            f"(total ground force furncheck {np.round(ours.sum(axis=0), 3).tolist()}, "
            f"PyNite {np.round(theirs.sum(axis=0), 3).tolist()} N)")
        scale_f = max(np.linalg.norm(j.force) for j in result.joints)
        scale_m = max(np.linalg.norm(j.moment) for j in result.joints)
        for joint, wrench in zip(result.joints, pynite):
            force, moment = np.asarray(joint.force), np.asarray(joint.moment)
            d_force = np.linalg.norm(force - wrench[:3]) / max(np.linalg.norm(force),
                                                               0.01 * scale_f)
            d_moment = np.linalg.norm(moment - wrench[3:]) / max(np.linalg.norm(moment),
                                                                 0.01 * scale_m)
            rows.append((design.name, case.name, "/".join(joint.planks),
                         np.linalg.norm(force), np.linalg.norm(wrench[:3]),
                         np.linalg.norm(moment), np.linalg.norm(wrench[3:]),
                         d_force, d_moment))
    return rows, notes


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--euler-bernoulli", action="store_true",
                        help="PyNite's plain Euler-Bernoulli members (no shear deformation)")
    parser.add_argument("--bilateral", action="store_true",
                        help="PyNite holds every ground corner, also those furncheck lifts")
    args = parser.parse_args()
    timoshenko = not args.euler_bernoulli
    print(f"PyNite members: {'Timoshenko (shear flexible)' if timoshenko else 'Euler-Bernoulli'}"
          f"; ground corners held in PyNite: "
          f"{'all' if args.bilateral else 'those furncheck finds holding'}\n")
    print("| structure | case | joint | \\|F\\| furncheck (N) | \\|F\\| PyNite (N) "
          "| \\|M\\| furncheck (N m) | \\|M\\| PyNite (N m) | rel. diff F | rel. diff M |")
    print("| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    all_notes = []
    worst = 0.0
    for design in (table_design(), bookcase_design(), two_bay_design(), chair_design()):
        rows, notes = compare(design, timoshenko, args.bilateral)
        all_notes += notes
        for name, case, joint, f1, f2, m1, m2, df, dm in rows:
            worst = max(worst, df, dm)
            print(f"| {name} | {case} | {joint} | {f1:.4f} | {f2:.4f} | {m1:.5f} | {m2:.5f} "
                  f"| {100 * df:.3f} % | {100 * dm:.3f} % |")
    print("\nrel. diff: |vector difference| / |furncheck vector| (the floor of the "
          "denominator is 1 % of the largest joint force or moment of the structure in "
          "that case)")
    print(f"worst relative difference: {100 * worst:.4f} %\n")
    for note in all_notes:
        print(f"- {note}")


if __name__ == "__main__":
    main()
