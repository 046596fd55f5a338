"""The elastic model's elements, pure functions of geometry and material (contract 3a).

A plank as a Timoshenko beam along its longer in-plane axis e1, with e2 the other in-plane
axis (the section's width b) and e3 its face normal (the thickness t): its section
(``section_properties``), the element stiffness (``beam_stiffness_local``: local axes,
displacements u and rotations theta per node, theta_3 = du_2/ds, theta_2 = -du_3/ds;
axial E A / L, torsion G J / L with J of a rectangle (Roark), and in each bending plane
the Timoshenko element with Phi = 12 E I / (k G A L^2), k = 5/6 (Przemieniecki), exact at
its nodes for end loads and, with the consistent nodal loads of ``uniform_load_local``,
for a uniform load along it), the beam's axes (``beam_frame``), and a nail joint's spring
from its nail row (``joint_springs``).
"""

from __future__ import annotations

import numpy as np

from furncheck.design.model import Plank
from furncheck.geometry import Joint

SHEAR_FACTOR = 5.0 / 6.0
"""Timoshenko's shear correction of a rectangular section."""


def section_properties(width, thickness) -> dict:
    """Section of a plank as a beam (floats or arrays): area A, I_2 = b t^3 / 12 (bending
    out of its plane, about e2: the sag of a shelf), I_3 = t b^3 / 12 (in its plane, about
    e3) and the torsion constant of a rectangle, J = a c^3 (1/3 - 0.21 (c/a) (1 - c^4 /
    (12 a^4))), a >= c its sides (Roark, Formulas for Stress and Strain, table 10.7)."""
    a, c = np.maximum(width, thickness), np.minimum(width, thickness)
    return {"A": width * thickness,
            "I2": width * thickness ** 3 / 12.0,
            "I3": thickness * width ** 3 / 12.0,
            "J": a * c ** 3 * (1.0 / 3.0 - 0.21 * (c / a) * (1.0 - c ** 4 / (12.0 * a ** 4)))}


def beam_stiffness_local(length, width, thickness, elastic_modulus,
                         shear_modulus) -> np.ndarray:
    """(12, 12) stiffness of a Timoshenko beam element in its local axes, DOFs per node
    (u1, u2, u3, theta1, theta2, theta3), node 1 then node 2 (N/m, N, N m); (n, 12, 12)
    for arrays of n lengths, widths and thicknesses (and moduli, Pa: one for all or n)."""
    L, b, t = (np.atleast_1d(np.asarray(v, dtype=float)) for v in (length, width, thickness))
    section = section_properties(b, t)
    E, G = elastic_modulus, shear_modulus
    shear_area = SHEAR_FACTOR * section["A"]
    K = np.zeros((len(L), 12, 12))

    def put(i: int, j: int, value: np.ndarray) -> None:
        K[:, i, j] = value
        K[:, j, i] = value

    axial, torsion = E * section["A"] / L, G * section["J"] / L
    for i, j, value in ((0, 0, axial), (6, 6, axial), (0, 6, -axial),
                        (3, 3, torsion), (9, 9, torsion), (3, 9, -torsion)):
        put(i, j, value)
    # (deflection, rotation, sign of the coupling): plane 1-2 (u2, theta3), plane 1-3 (u3,
    # theta2), where theta3 = du2/ds but theta2 = -du3/ds
    for w, r, inertia, sign in ((1, 5, section["I3"], 1.0), (2, 4, section["I2"], -1.0)):
        phi = 12.0 * E * inertia / (shear_modulus * shear_area * L * L)
        c = E * inertia / (L ** 3 * (1.0 + phi))
        for i, j, value in ((w, w, 12.0), (w + 6, w + 6, 12.0), (w, w + 6, -12.0),
                            (w, r, sign * 6.0 * L), (w, r + 6, sign * 6.0 * L),
                            (w + 6, r, -sign * 6.0 * L), (w + 6, r + 6, -sign * 6.0 * L),
                            (r, r, (4.0 + phi) * L * L), (r + 6, r + 6, (4.0 + phi) * L * L),
                            (r, r + 6, (2.0 - phi) * L * L)):
            put(i, j, value * c)
    return K[0] if np.ndim(length) == 0 else K


def uniform_load_local(length, load: np.ndarray) -> np.ndarray:
    """(12,) consistent nodal loads of a uniform load ``load`` (3,) N/m along a beam element,
    in its local axes: q L / 2 at each node and end moments q L^2 / 12 (signs of theta_3 =
    du2/ds, theta_2 = -du3/ds); (n, 12) for n lengths and loads (n, 3)."""
    L = np.atleast_1d(np.asarray(length, dtype=float))
    q = np.asarray(load, dtype=float).reshape(-1, 3)
    f = np.zeros((len(L), 12))
    f[:, 0] = f[:, 6] = q[:, 0] * L / 2.0
    f[:, 1] = f[:, 7] = q[:, 1] * L / 2.0
    f[:, 5], f[:, 11] = q[:, 1] * L * L / 12.0, -q[:, 1] * L * L / 12.0
    f[:, 2] = f[:, 8] = q[:, 2] * L / 2.0
    f[:, 4], f[:, 10] = -q[:, 2] * L * L / 12.0, q[:, 2] * L * L / 12.0
    return f[0] if np.ndim(length) == 0 else f


def element_interior(length, bending_stiffness, shear_stiffness, ends: np.ndarray,
                     load, xi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Deflection w and bending moment M inside Timoshenko elements, exactly, in one bending
    plane: (n, m) each at the fractions ``xi`` (m,) of n elements of lengths L (n,),
    E I (n,) N m^2, k G A (n,) N, with ``ends`` (n, 4) = (w_0, theta_0, w_L, theta_L) (m and
    rad: theta the section's rotation, dw/ds where shear is negligible) and a uniform
    load q (n,) N/m along +w.

    With V = dM/ds, dV/ds = q, M = E I dtheta/ds and dw/ds = theta - V / k G A:

        M(s) = M_0 + V_0 s + q s^2 / 2
        w(s) = w_0 + theta_0 s + (M_0 s^2 / 2 + V_0 s^3 / 6 + q s^4 / 24) / E I
               - (V_0 s + q s^2 / 2) / k G A

    and M_0, V_0 follow from theta and w at s = L (two linear equations): the element's
    deflection between its nodes and its moment, which can peak between them, for what its
    nodes did and its own load."""
    L = np.asarray(length, dtype=float)
    EI = np.asarray(bending_stiffness, dtype=float)
    kGA = np.asarray(shear_stiffness, dtype=float)
    q = np.asarray(load, dtype=float)
    w0, th0 = ends[:, 0], ends[:, 1]
    M0, V0 = element_end_moment(L, EI, kGA, ends, q)
    s = L[:, None] * np.asarray(xi, dtype=float)
    M0, V0, q, EI, kGA = (v[:, None] for v in (M0, V0, q, EI, kGA))
    moment = M0 + V0 * s + 0.5 * q * s * s
    w = (w0[:, None] + th0[:, None] * s
         + (0.5 * M0 * s * s + V0 * s ** 3 / 6.0 + q * s ** 4 / 24.0) / EI
         - (V0 * s + 0.5 * q * s * s) / kGA)
    return w, moment


def element_end_moment(length, bending_stiffness, shear_stiffness, ends: np.ndarray,
                       load) -> tuple[np.ndarray, np.ndarray]:
    """(M_0, V_0), each (n,): the moment and its slope V = dM/ds at the start of n
    Timoshenko elements (``element_interior``'s arguments but ``xi``), from theta and w at
    s = L, two linear equations: M(s) = M_0 + V_0 s + q s^2 / 2 along each."""
    L, EI, kGA, q = length, bending_stiffness, shear_stiffness, load
    w0, th0, wL, thL = (ends[:, i] for i in range(4))
    # [L / EI, L^2 / 2 EI; L^2 / 2 EI, L^3 / 6 EI - L / kGA] [M_0, V_0] = [rotation, deflection]
    rotation = thL - th0 - q * L ** 3 / (6.0 * EI)
    deflection = wL - w0 - th0 * L - q * L ** 4 / (24.0 * EI) + q * L * L / (2.0 * kGA)
    a, b, d = L / EI, L * L / (2.0 * EI), L ** 3 / (6.0 * EI) - L / kGA
    determinant = a * d - b * b            # = -L^4 / 12 EI^2 - L^2 / EI kGA < 0
    return ((d * rotation - b * deflection) / determinant,
            (a * deflection - b * rotation) / determinant)


def nail_row_spread(length, nails):
    """m^2: S = sum y_i^2 = L^2 (n^2 - 1) / 12 n of a joint's n nails at y_i = (i + 1/2)
    L / n - L / 2 (contract section 3), for floats or arrays; a one-nail joint's spring
    uses S = L^2 / 12 of its contact region (contract section 3a: never zero)."""
    length, nails = np.asarray(length, dtype=float), np.asarray(nails, dtype=float)
    return np.where(nails <= 1.0, length * length / 12.0,
                    length * length * (nails * nails - 1.0) / (12.0 * np.maximum(nails, 1.0)))


def joint_springs(joint: Joint, nail_slip: float, nail_withdrawal: float) -> np.ndarray:
    """(6, 6) world-frame stiffness W of a nail joint (wrench = W deviation), from its n
    nails in the joint frame (x, y the joint line, n the nail axis; contract 3a): along n
    n k_w, across it n k_s; rotation about y n k_w (t/2)^2, about x k_w S, about n k_s S."""
    return nail_row_springs([joint], nail_slip, nail_withdrawal)[0]


def nail_row_springs(joints, nail_slip: float, nail_withdrawal: float) -> np.ndarray:
    """(nJ, 6, 6): ``joint_springs`` of each of ``joints``, all at once."""
    frames = np.array([joint.frame for joint in joints], dtype=float).reshape(-1, 3, 3)
    n = np.array([joint.nails for joint in joints], dtype=float)
    spread = nail_row_spread(np.array([joint.length for joint in joints], dtype=float), n)
    half = 0.5 * np.array([joint.edge_thickness for joint in joints], dtype=float)
    return _in_world(frames, n, spread, half, nail_slip, nail_withdrawal)


def nail_row_parts(joints, counts, nail_slip: float,
                   nail_withdrawal: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The springs of ``joints`` cut into parts along their nail rows (``counts`` (nJ,):
    parts per joint, 1 for a joint left whole): (W (nS, 6, 6), each spring's joint
    (nS,), where it sits along its joint line in lengths L from the middle (nS,),
    ``part_fractions``).

    Part g of m holds n / m of the joint's n nails, centred at y_g = ((g + 1/2) / m -
    1/2) L: along n (n / m) k_w, across it (n / m) k_s, about the joint line (n / m) k_w
    (t/2)^2, about x k_w S_m and about n k_s S_m with S_m = (S - (n / m) sum_g y_g^2) / m
    = L^2 (n / m^2 - 1 / n) / 12 m, so that the parts together, on planks that do not
    bend, are the whole row's spring of ``joint_springs``: their translations add up, and
    their turns add up with the parallel-axis terms (n / m) k y_g^2 (contract 3a's S =
    L^2 (n^2 - 1) / 12 n for n >= 2 nails).  m <= n / 2 keeps S_m > 0.  A joint left
    whole (m = 1) gets ``nail_row_springs``' own numbers."""
    counts = np.asarray(counts, dtype=int)
    whole = nail_row_springs(joints, nail_slip, nail_withdrawal)
    rows = np.repeat(np.arange(len(counts)), counts)
    if not (counts > 1).any():
        return whole, rows, np.zeros(len(rows))
    springs = whole[rows]
    parted = np.flatnonzero(counts[rows] > 1)
    picked = [joints[row] for row in rows[parted]]
    frames = np.array([joint.frame for joint in picked], dtype=float).reshape(-1, 3, 3)
    n = np.array([joint.nails for joint in picked], dtype=float)
    length = np.array([joint.length for joint in picked], dtype=float)
    m = counts[rows[parted]].astype(float)
    spread = length * length * (n / (m * m) - 1.0 / n) / (12.0 * m)
    half = 0.5 * np.array([joint.edge_thickness for joint in picked], dtype=float)
    springs[parted] = _in_world(frames, n / m, spread, half, nail_slip, nail_withdrawal)
    return springs, rows, part_fractions(counts)


def part_fractions(counts) -> np.ndarray:
    """(sum counts,) where each part of a joint cut into ``counts`` parts sits along its
    joint line, in joint lengths from its middle: (g + 1/2) / m - 1/2, g = 0 .. m - 1."""
    return np.concatenate([(np.arange(m) + 0.5) / m - 0.5 for m in np.asarray(counts)]) \
        if len(counts) else np.zeros(0)


def part_points(joints, counts) -> tuple[np.ndarray, np.ndarray]:
    """(points (nS, 3), arms (nS, 3)) m of the springs of ``joints`` cut into ``counts``
    parts (``nail_row_parts``): each part's point on its joint line, and that point less
    its joint's point (a whole joint's spring sits at the joint's point, its arm 0)."""
    counts = np.asarray(counts, dtype=int)
    centres = np.array([joint.point for joint in joints], dtype=float).reshape(-1, 3)
    rows = np.repeat(np.arange(len(counts)), counts)
    lines = np.array([joint.length * joint.frame[:, 1] for joint in joints],
                     dtype=float).reshape(-1, 3)
    arms = part_fractions(counts)[:, None] * lines[rows]
    return centres[rows] + arms, arms


def _in_world(frames: np.ndarray, nails: np.ndarray, spread: np.ndarray, half: np.ndarray,
              nail_slip: float, nail_withdrawal: float) -> np.ndarray:
    """(k, 6, 6) world-frame springs of k nail rows of ``nails`` nails (floats: a part's
    share), S = ``spread`` and half edge thickness ``half``, in their joint frames
    (``joint_springs``)."""
    translation = np.column_stack([nails * nail_slip, nails * nail_slip,
                                   nails * nail_withdrawal])
    rotation = np.column_stack([nail_withdrawal * spread, nails * nail_withdrawal * half * half,
                                nail_slip * spread])
    W = np.zeros((len(nails), 6, 6))
    transposed = np.transpose(frames, (0, 2, 1))
    W[:, :3, :3] = (frames * translation[:, None, :]) @ transposed
    W[:, 3:, 3:] = (frames * rotation[:, None, :]) @ transposed
    return W


def along_width(plank: Plank) -> bool:
    """Whether the plank's beam runs along its local y (its width is the longer side; on a
    tie it runs along local x)."""
    return plank.width > plank.length


def beam_frame(plank: Plank, crosswise: bool | None = None) -> np.ndarray:
    """(3, 3) columns e1 (the beam axis: the plank's longer in-plane axis, or local y when
    ``crosswise``), e2 (the other in-plane axis), e3 (the face normal), world frame."""
    axes = plank.rotation_matrix
    if not (along_width(plank) if crosswise is None else crosswise):
        return axes.copy()
    return np.column_stack([axes[:, 1], -axes[:, 0], axes[:, 2]])


def beam_length_width(plank: Plank, crosswise: bool | None = None) -> tuple[float, float]:
    """(beam length, section width) of the plank (m), as ``beam_frame``."""
    if not (along_width(plank) if crosswise is None else crosswise):
        return plank.length, plank.width
    return plank.width, plank.length
