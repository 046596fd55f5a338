"""Force sensitivity (paper section 5.2, eq. 6) against finite differences of the full solve.

``sensitivity(design, dofs, case)`` gives d(joint force N, moment N m)/d(DOF unit) and
d(ground force N)/d(DOF unit) with the contact states held.  The reference here is the
central difference of the complete pipeline, ``check_design(apply_dof(design, frame, dof,
+-h))``, which re-detects the geometry and re-solves the statics from scratch.

Step h (measured on these designs, see ``test_the_difference_step_is_in_the_flat_region``):
the full solve's forces carry round-off of ~1e-11 of the total load W (bookshelf-20: W =
1826 N, ~5e-9 N), so the central difference's round-off error is ~1e-11 W / h; its
truncation error is ~h^2 |f'''| / 6.  For lengths, h = 1e-3 mm leaves round-off errors up
to 2.4e-4 (relative to the DOF's largest derivative) on bookshelf-20 (cap.length), h = 1e-2
mm <= 2e-5 and h = 1e-1 mm <= 2e-6 with truncation still invisible: h = 1e-2 file units.
For rotations h = 1e-3 degrees (errors <= 2e-5 on the differentiable DOFs; 1e-5 degrees
already shows round-off of 5e-4).

Non-differentiable DOFs: the geometric rules of ``dofs`` keep a plank's end on its face by
its *lowest* corner and joints measure the *overlap* of faces, so where two faces are flush
(a panel's end exactly under a top, a shelf's edge flush with a side's edge) a DOF has
different one-sided slopes (table top.rx: -0.133 and -0.168 N m/deg on its largest
component), and a central difference over h differs from the mean slope by O(h) (table
apron.ry: 2e-4 at h = 1e-3 degrees).  There is no derivative to compare with there; the
sensitivity (itself a central difference of the assembly over ``ASSEMBLY_STEP``) must lie
within the spread of the one-sided slopes around the central difference.  On these designs
it does with a wide margin (closest: stool leg_l.ry, error 1e-5 against a spread of
1.8e-3, both relative to the largest derivative).

Models: every test names the model it runs in.  The step choice above was measured in the
rigid model; the elastic model's assembly step is smaller (``ELASTIC_ASSEMBLY_STEP``: its
short beam elements bend the assembly on a millimetre scale), and its contacts that slipped
keep slipping (``ContactLaw``): before both, its sensitivity missed these checks by up to
a factor of 18 (the cantilever's base, whose two far corners slip against the near ones
as it bends).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import range_designs as rd

from furncheck.check import check_design
from furncheck.design import load_design
from furncheck.design.model import with_model
from furncheck.dofs import Blocked, all_dofs, apply_dof, parse_dof, structure
from furncheck.edit_check import check_edit
from furncheck.geometry import analyze
from furncheck.sensitivity import sensitivity

DESIGNS = Path(__file__).resolve().parent.parent / "designs"
G = rd.G

H_LENGTH = 1e-2     # file length unit
H_ANGLE = 1e-3      # degrees
AGREEMENT = 1e-4    # relative to the DOF's largest derivative magnitude
TINY = 1e-6         # derivatives below TINY x W per DOF unit are round-off
KINK = 1e-3         # one-sided slopes differing by more than this (relative): no derivative
ACTIVE = 1e-9       # a contact holds if its normal force exceeds ACTIVE x W


def forces(case) -> np.ndarray:
    """All joint wrenches (force, moment) and ground forces of a CaseResult, flattened."""
    joints = np.array([list(j.force) + list(j.moment) for j in case.joints],
                      dtype=float).reshape(-1, 6)
    contacts = np.array([c.force for c in case.contacts], dtype=float).reshape(-1, 3)
    return np.concatenate([joints.ravel(), contacts.ravel()])


def active(case, weight: float) -> tuple[bool, ...]:
    return tuple(c.force[2] > ACTIVE * weight for c in case.contacts)


def first_stable_case(report) -> int:
    return next(i for i, case in enumerate(report.cases) if case.stability == "stable")


class Differences:
    """Finite differences of the full solve of one load case of a design."""

    def __init__(self, design, index: int):
        self.design = design
        self.index = index
        self.geometry = analyze(design)
        self.frame = structure(design, self.geometry)
        self.case = check_design(design).cases[index]
        self.weight = sum(c.force[2] for c in self.case.contacts)
        self.base = forces(self.case)
        self.active = active(self.case, self.weight)

    def at(self, dof, h: float):
        """(central, forward, backward) differences with step h, or None when the step
        changes the joints, contacts or the active contact set (or loses stability)."""
        plus = apply_dof(self.design, self.frame, dof, h)
        minus = apply_dof(self.design, self.frame, dof, -h)
        if check_edit(self.geometry, plus)[0] or check_edit(self.geometry, minus)[0]:
            return None
        case_plus = check_design(plus).cases[self.index]
        case_minus = check_design(minus).cases[self.index]
        if case_plus.stability != "stable" or case_minus.stability != "stable":
            return None
        if not (active(case_plus, self.weight) == active(case_minus, self.weight)
                == self.active):
            return None
        f_plus, f_minus = forces(case_plus), forces(case_minus)
        return ((f_plus - f_minus) / (2 * h), (f_plus - self.base) / h,
                (self.base - f_minus) / h)


@pytest.mark.parametrize("name, model", [
    ("shelf-cantilever", "rigid"), ("table", "rigid"), ("stool", "rigid"),
    ("chair-upright", "rigid"), ("bookshelf-20", "rigid"),
    ("shelf-cantilever", "elastic"), ("table", "elastic"),
    ("stool", "elastic"),
    ("chair-upright", "elastic")])
def test_sensitivity_matches_finite_differences_of_the_full_solve(name, model):
    """For every DOF of the design's first stable case: blocked DOFs are exactly those
    apply_dof refuses; for the others, with the same joints, contacts and active contact set
    at +-h (h = H_LENGTH or H_ANGLE), the sensitivity equals (F(+h) - F(-h)) / 2h to 1e-4 of
    the DOF's largest derivative magnitude ("scale").  For a non-differentiable DOF (one-sided
    slopes (F(h) - F(0)) / h and (F(0) - F(-h)) / h differing by more than 1e-3 of the scale,
    module docstring) the allowance grows by half that difference: the sensitivity must lie
    within the one-sided slopes' spread around the central difference.  DOFs whose
    derivatives are all below 1e-6 W per unit are round-off and skipped.  The catalog
    design in ``model`` (the rigid cases are the paper's model, the elastic ones the
    default)."""
    design = with_model(load_design(str(DESIGNS / f"{name}.yaml")), model)
    report = check_design(design)
    index = first_stable_case(report)
    case = report.cases[index]
    diff = Differences(design, index)
    dofs = all_dofs(design)
    sens = sensitivity(design, dofs, design.load_cases[index].name)

    assert sens.case == case.name
    assert {d.name for d in sens.dofs} | set(sens.blocked) == {d.name for d in dofs}
    assert not {d.name for d in sens.dofs} & set(sens.blocked)
    assert sens.joint_wrenches.shape == (len(sens.dofs), len(case.joints), 6)
    assert sens.contact_forces.shape == (len(sens.dofs), len(case.contacts), 3)
    for dof in dofs:
        if dof.name in sens.blocked:
            with pytest.raises(Blocked):
                apply_dof(design, diff.frame, dof, H_ANGLE if dof.is_rotation else H_LENGTH)

    compared, kinked, failures = [], [], []
    for row, dof in enumerate(sens.dofs):
        analytic = np.concatenate([sens.joint_wrenches[row].ravel(),
                                   sens.contact_forces[row].ravel()])
        found = diff.at(dof, H_ANGLE if dof.is_rotation else H_LENGTH)
        if found is None:
            continue
        central, forward, backward = found
        scale = max(np.abs(central).max(initial=0.0), np.abs(analytic).max(initial=0.0))
        if scale < TINY * diff.weight:
            continue
        kink = np.abs(forward - backward).max()
        if kink > KINK * scale:
            kinked.append(dof.name)
            allowed = AGREEMENT * scale + 0.5 * kink
        else:
            compared.append(dof.name)
            allowed = AGREEMENT * scale
        error = np.abs(analytic - central).max()
        if error > allowed:
            k = int(np.argmax(np.abs(analytic - central)))
            failures.append(f"{dof.name}: error {error / scale:.2e} of the scale {scale:.3g} "
                            f"> {allowed / scale:.2e} (component {k}: {analytic[k]:.6g} vs "
                            f"{central[k]:.6g}; one-sided {forward[k]:.6g}, {backward[k]:.6g})")
    assert not failures, "\n".join(failures)
    assert len(compared) >= 5, (compared, kinked)


def test_the_difference_step_is_in_the_flat_region():
    """The step choice (module docstring), checked where round-off is largest (bookshelf-20,
    W = 1826 N) and on a rotation: the central differences at h and 3h agree to 2e-5 of the
    DOF's largest derivative (truncation is negligible at h; at h / 10 round-off is not:
    2.4e-4 for cap.length).  What differs at h is the solve's round-off, about 3e-9 N,
    eps x joint stiffness x the planks' 1e-3 m motion on their contact springs: measured
    1.4e-5 for cap.length through the sparse mixed system, 1.3e-5 through the plank
    condensation that designs of up to 60 planks use.  Measured in the rigid model, whose
    rigid cases of the test above use this step."""
    design = with_model(load_design(str(DESIGNS / "bookshelf-20.yaml")), "rigid")
    frame = structure(design, analyze(design))

    def central(name, h):
        dof = parse_dof(design, name)
        plus = forces(check_design(apply_dof(design, frame, dof, h)).cases[0])
        minus = forces(check_design(apply_dof(design, frame, dof, -h)).cases[0])
        return (plus - minus) / (2 * h)

    for name, h in (("cap.length", H_LENGTH), ("shelf_a3.width", H_LENGTH),
                    ("side_l.ry", H_ANGLE), ("shelf_a2.ry", H_ANGLE)):
        at_h, at_3h = central(name, h), central(name, 3 * h)
        scale = np.abs(at_h).max()
        assert np.abs(at_h - at_3h).max() <= 2e-5 * scale, name


def _joint_index(case, first: str, second: str) -> int:
    return next(k for k, j in enumerate(case.joints) if tuple(j.planks) == (first, second))


@pytest.mark.parametrize("model", [
    "rigid", "elastic"])
def test_cantilever_moment_rate_by_hand(model):
    """designs/shelf-cantilever.yaml, default case: m = 15 kg at x = 0 on the shelf that spans
    x -144..156 (L = 0.3 m) from the post face, so the load rides at f = 144 / 300 = 0.48.
    The shelf hangs on the post joint only, so the post's moment on the shelf about the
    joint line (world y) balances the loads: M(L) = m g f L + rho t w g L^2 / 2 and

        dM/dL = m g f + rho t w g L = 15 x 9.81 x 0.48 + 750 x 0.012 x 0.3 x 9.81 x 0.3
              = 70.632 + 7.946 = 78.578 N m/m = 0.078578 N m per mm.

    The post/base joint (point x = -150, 6 mm behind the post face) carries the same loads
    with 6 mm more arm: dM_base/dL = m g f + rho t w g (L + 0.006) = 78.737 N m/m, and the
    ground's total vertical force grows by the shelf's weight per length, rho t w g =
    26.487 N/m = 0.026487 N per mm.  Statics alone fixes these (the shelf and the post are a
    tree on the base): the same in both models."""
    design = with_model(load_design(str(DESIGNS / "shelf-cantilever.yaml")), model)
    case = check_design(design).cases[0]
    sens = sensitivity(design, [parse_dof(design, "shelf.length")], "default")
    rates = sens.joint_wrenches[0]
    shelf_joint = _joint_index(case, "post", "shelf")
    base_joint = _joint_index(case, "base", "post")
    strip = 750 * 0.012 * 0.3 * G                  # N/m, shelf weight per length
    mgf = 15 * G * 0.48
    moment = case.joints[shelf_joint].moment[1]
    # the magnitude of the moment grows: d|M_y|/dL = sign(M_y) dM_y/dL
    assert np.sign(moment) * rates[shelf_joint, 4] == pytest.approx(
        (mgf + strip * 0.3) / 1000.0, rel=1e-5)
    assert np.sign(case.joints[base_joint].moment[1]) * rates[base_joint, 4] == pytest.approx(
        (mgf + strip * 0.306) / 1000.0, rel=1e-5)
    # no twist or sideways bending: the other moment components do not change
    assert np.abs(rates[shelf_joint, [3, 5]]).max() <= 1e-9
    assert sens.contact_forces[0][:, 2].sum() == pytest.approx(strip / 1000.0, rel=1e-5)


@pytest.mark.parametrize("model", [
    "rigid", "elastic"])
def test_range_cantilever_moment_rate_by_hand(model):
    """range_designs.cantilever (m = 10 kg riding at f = 0.75, shelf L = 0.3 m, 300 wide):
    dM/dL = m g f + rho t w g L = 73.575 + 26.487 x 0.3 = 81.521 N m/m; the nail pull
    2 M / t / 15 then grows at 2 x 81.521 / 0.012 / 15 = 905.8 N per m (0.9058 N per mm).
    Determinate: the same in both models."""
    design = with_model(rd.parse(rd.cantilever(mass=10.0, fraction=0.75)), model)
    case = check_design(design).cases[0]
    sens = sensitivity(design, [parse_dof(design, "shelf.length")])
    joint = _joint_index(case, "post", "shelf")
    rate = np.sign(case.joints[joint].moment[1]) * sens.joint_wrenches[0][joint, 4]
    expected = (10 * G * 0.75 + 750 * 0.012 * 0.3 * G * 0.3) / 1000.0
    assert expected == pytest.approx(0.081521, rel=1e-4)
    assert rate == pytest.approx(expected, rel=1e-5)
    assert 2 * rate * 1000.0 / 0.012 / 15 == pytest.approx(905.8, rel=1e-3)
