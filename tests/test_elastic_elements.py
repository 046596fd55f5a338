"""The elastic model's elements, one by one, against closed forms (contract section 3a).

A Timoshenko beam element (``beam_stiffness_local``), a nail row's spring
(``joint_springs``) and the consistent loads of a uniform load (``uniform_load_local``),
each a pure function of geometry and material, as scikit-fem and PyNite test theirs.
"""

from __future__ import annotations

import numpy as np
import pytest

from furncheck.design.load import parse_design
from furncheck.geometry import Joint
from furncheck.statics.beams import (
    SHEAR_FACTOR,
    beam_stiffness_local,
    joint_springs,
    nail_row_spread,
    section_properties,
    uniform_load_local,
)

E, G = 3.0e9, 0.8e9            # Pa, the MDF defaults
L, B, T = 0.3, 0.2, 0.012      # m: element length, section width and thickness


def _cantilever(K: np.ndarray, load: np.ndarray) -> np.ndarray:
    """Displacements of node 2 of an element fixed at node 1 under a load at node 2."""
    return np.linalg.solve(K[6:, 6:], load)


def test_tip_deflection_in_both_bending_planes():
    """Cantilever of one element, P = 10 N at the tip: deflection P L^3 / 3EI + P L / kGA
    and tip rotation P L^2 / 2EI, about e2 (out of the plank's plane, I = b t^3 / 12) and
    about e3 (in its plane, I = t b^3 / 12); the element is exact for end loads."""
    K = beam_stiffness_local(L, B, T, E, G)
    shear = SHEAR_FACTOR * G * B * T
    for axis, rotation, inertia, sign in ((2, 4, B * T ** 3 / 12, -1.0),
                                          (1, 5, T * B ** 3 / 12, 1.0)):
        load = np.zeros(6)
        load[axis] = 10.0
        u = _cantilever(K, load)
        assert u[axis] == pytest.approx(10 * L ** 3 / (3 * E * inertia) + 10 * L / shear,
                                        rel=1e-12)
        assert u[rotation] == pytest.approx(sign * 10 * L ** 2 / (2 * E * inertia), rel=1e-12)


def test_axial_and_torsion():
    """An end force N stretches the element by N L / EA; a torque by T L / GJ, J of the
    rectangle b x t (Roark: b t^3 (1/3 - 0.21 (t/b)(1 - t^4 / 12 b^4)))."""
    K = beam_stiffness_local(L, B, T, E, G)
    u = _cantilever(K, np.array([100.0, 0, 0, 2.0, 0, 0]))
    J = B * T ** 3 * (1 / 3 - 0.21 * (T / B) * (1 - T ** 4 / (12 * B ** 4)))
    assert section_properties(B, T)["J"] == pytest.approx(J)
    assert u[0] == pytest.approx(100 * L / (E * B * T), rel=1e-12)
    assert u[3] == pytest.approx(2.0 * L / (G * J), rel=1e-12)


def test_rigid_motions_cost_nothing():
    """Symmetric, positive semi-definite, with exactly six zero eigenvalues: the three
    translations and the three rotations of the element (a rotation theta about e3 moves
    node 2 by theta L along e2)."""
    K = beam_stiffness_local(L, B, T, E, G)
    assert np.abs(K - K.T).max() == 0.0
    eigenvalues = np.linalg.eigvalsh(K)
    assert np.sum(np.abs(eigenvalues) < 1e-6 * eigenvalues.max()) == 6
    assert eigenvalues.min() > -1e-6 * eigenvalues.max()
    turn = np.zeros(12)
    turn[[5, 11]] = 1e-3
    turn[7] = 1e-3 * L
    assert np.abs(K @ turn).max() <= 1e-9 * np.abs(K).max() * 1e-3


def test_uniform_load_is_equivalent():
    """The consistent loads of q = (1, 2, 3) N/m sum to q L and their moments about node 1
    are those of the load at mid-length: sum of forces x s + end moments = q L^2 / 2."""
    q = np.array([1.0, 2.0, 3.0])
    f = uniform_load_local(L, q)
    assert f[[0, 6]].sum() == pytest.approx(q[0] * L)
    assert f[[1, 7]].sum() == pytest.approx(q[1] * L)
    assert f[[2, 8]].sum() == pytest.approx(q[2] * L)
    # moment about e3 at node 1 (theta3 = du2/ds): node 2's force x L plus both moments
    assert f[7] * L + f[5] + f[11] == pytest.approx(q[1] * L ** 2 / 2)
    # about e2 (theta2 = -du3/ds): -(node 2's force x L) plus both moments
    assert -f[8] * L + f[4] + f[10] == pytest.approx(-q[2] * L ** 2 / 2)


def test_nail_row_spring_gives_the_rows_moments():
    """A 15-nail, 300 mm joint (S = L^2 (n^2 - 1) / 12 n = 0.112 m^2) in a turned frame:
    a unit rotation about the joint line takes n k_w (t/2)^2, about x k_w S, about the
    nail axis k_s S; a unit slip across takes n k_s, along the nails n k_w."""
    frame, _ = np.linalg.qr(np.random.default_rng(1).normal(size=(3, 3)))
    joint = Joint(("f", "e"), "f", "e", np.zeros(3), 0.3, 15, frame, 0.012)
    k_s, k_w = 1.2e6, 1.0e6
    S = 0.3 ** 2 * (15 ** 2 - 1) / (12 * 15)
    assert nail_row_spread(0.3, 15) == pytest.approx(S)
    assert nail_row_spread(0.3, 1) == pytest.approx(0.3 ** 2 / 12)
    W = joint_springs(joint, k_s, k_w)
    x, y, n = frame.T
    assert y @ W[3:, 3:] @ y == pytest.approx(15 * k_w * 0.006 ** 2)
    assert x @ W[3:, 3:] @ x == pytest.approx(k_w * S)
    assert n @ W[3:, 3:] @ n == pytest.approx(k_s * S)
    assert x @ W[:3, :3] @ x == pytest.approx(15 * k_s)
    assert n @ W[:3, :3] @ n == pytest.approx(15 * k_w)
    assert np.abs(W[:3, 3:]).max() == 0.0


def test_material_keys_are_read_in_file_units():
    """elastic_modulus, shear_modulus, bending_strength in N/mm^2, nail_slip and
    nail_withdrawal in N/mm per nail; ``model`` and ``spread`` as written."""
    design = parse_design("""\
furncheck: 1
model: elastic
material: {elastic_modulus: 3500, shear_modulus: 900, bending_strength: 25, creep: 2.25,
           sag_limit: 300, nail_slip: 800, nail_withdrawal: 600}
planks: [{id: a, size: [400, 300], center: [0, 0, 6]}]
loads: [{plank: a, mass: 5, spread: true}]
""", "m.yaml", "yaml")
    m = design.material
    assert design.model == "elastic"
    assert (m.elastic_modulus, m.shear_modulus, m.bending_strength) == (3.5e9, 0.9e9, 25e6)
    assert (m.creep, m.sag_limit, m.nail_slip, m.nail_withdrawal) == (2.25, 300, 8e5, 6e5)
    assert design.load_cases[0].loads[0].spread is True


@pytest.mark.parametrize("text, message", [
    ("model: stiff\n", 'model: unknown model "stiff"; use elastic or rigid'),
    ("loads: [{plank: a, mass: 5, spread: yes, at: [0, 0, 12]}]\n",
     "a spread load acts along the whole plank: give no point"),
    ("loads: [{plank: a, mass: 5, spread: 3}]\n", "expected true or false"),
    ("material: {elastic_modulus: -3}\n", "must be positive"),
])
def test_bad_elastic_keys_are_one_line(text, message):
    from furncheck.errors import DesignError

    with pytest.raises(DesignError) as error:
        parse_design("furncheck: 1\nplanks: [{id: a, size: [400, 300], center: [0, 0, 6]}]\n"
                     + text, "bad.yaml", "yaml")
    assert message in str(error.value)


def test_model_option_overrides_the_file():
    """``--model`` on every command: designs/bookcase-sagging.yaml says ``model: elastic``
    and its middle shelf sags (exit 1); as rigid planks it holds (exit 0); the JSON of the
    elastic case lists its planks' sag and stress, the rigid one none."""
    import json
    from pathlib import Path

    from click.testing import CliRunner

    from furncheck.cli.main import main

    path = str(Path(__file__).resolve().parents[1] / "designs" / "bookcase-sagging.yaml")
    runner = CliRunner()
    elastic = runner.invoke(main, ["validate", path, "--format", "json"])
    rigid = runner.invoke(main, ["validate", path, "--model", "rigid", "--format", "json"])
    assert (elastic.exit_code, rigid.exit_code) == (1, 0)
    planks = json.loads(elastic.output)["reports"][0]["cases"][0]["planks"]
    assert [p["id"] for p in planks] == ["side_l", "side_r", "bottom", "middle", "top"]
    assert "planks" not in json.loads(rigid.output)["reports"][0]["cases"][0]
    for command in (["suggest", path], ["range", path, "middle.z"]):
        result = runner.invoke(main, [*command, "--model", "rigid"])
        assert result.exit_code == 0, result.output
    assert runner.invoke(main, ["validate", path, "--model", "soft"]).exit_code == 2
