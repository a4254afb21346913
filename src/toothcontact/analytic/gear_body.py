"""The gear body's coupling of its teeth: how far a tooth moves when another tooth of the same
gear is loaded (the teeth of different pairs in contact are not independent springs: the
load one pair puts into the body turns and strains the rim under the others).

The body is the annulus between the bore (radius r_i, held) and the root circle (r_o), in
generalized plane stress over the face width (the gear's face no wider than its body is
deep; a load anywhere along the face moves the whole rim alike: in the 3D finite elements of
tests/fe_pair_helical.py, the compliance between different teeth smeared evenly along the
face changed the pair's mesh stiffness by 0.03 %). Each tooth is rigid on its root chord (the
arc |θ - θ_k| <= θ_f of the root circle): its load (a force along the flank's normal at the
contact) reaches the body as the force and the moment about the chord's middle, spread over
the chord (the forces evenly, the moment as a linear radial stress), and a tooth with no load
moves as its chord does: the chord's mean radial and tangential displacement and its
rotation, each the work-conjugate of one of those three spreads (so the coupling is
reciprocal, Maxwell-Betti).

The annulus is solved exactly by Fourier series in θ (Michell's solution, J. H. Michell,
Proc. London Math. Soc. 31 (1899) 100-124; S. P. Timoshenko & J. N. Goodier, *Theory of
Elasticity*, 3rd ed. 1970, §43): for each harmonic n >= 2 of the rim's traction the
displacements u_r = U(r) cos nθ, u_θ = V(r) sin nθ are sums of the four powers r^(n+1),
r^(n-1), r^(1-n), r^(-1-n) (Navier's equations in polar coordinates, each power with its
own ratio V/U), fixed by u = 0 at the bore and the traction at the rim (a 4 × 4 system per
harmonic); n = 0 (the body's radial and torsional modes) and n = 1 (a repeated power, whose
solution carries a logarithm) are solved by Chebyshev collocation of the same equations,
which the tests check against the powers for n = 2...8. Not a fit: nothing in it is tuned
to a finite-element result (tests/test_gear_body.py holds it to the 3D FE).

The body also bends out of its plane (flexure_green): a helical tooth's load has an axial
part (sin β_b of it), and any tooth's load sits at a face position z off the body's mid-plane
(the moments z·F_r and z·F_t), which the generalized plane stress leaves out. The same
annulus as a Mindlin plate as thick as the face (R. D. Mindlin, J. Appl. Mech. 18 (1951)
31-38: deflection w and the normal's rotations ψ_r, ψ_θ, shear correction 5/6), held at the
bore, its rim loaded by the teeth's axial force and their moments about the rim's tangent
and its radius over each root chord; the harmonics by Chebyshev collocation of the plate's
three equations, checked against the thin (Kirchhoff) plate and the closed-form shear of
its n = 0 mode. Against the 3D FE of tests/fe_pair_helical.py the load's axial part moves
the lines on the teeth one and two pitches away 0.073/0.098 µm/kN (pinion; FE 0.064, 0.099)
and 0.418/0.493 (gear; FE 0.386, 0.477) (tests/test_gear_body.py); the tooth's own
give under it is not the plate's but its wall's (analytic.tooth_wall: a line on itself
0.136 and 0.476 with it, 0.092 and 0.433 without, against the FE's 0.218 and 0.528).

Units: mm, N, MPa; compliance per unit thickness (mm per N/mm) in plane, mm/N (and rad per
N·mm) out of plane.
"""

from __future__ import annotations

import functools
import math

import numpy as np

#: harmonics per tooth of the Fourier series (the chord Green's matrix between different
#: teeth changes by under 1e-4 from 8 to 32 per tooth: tests/test_gear_body.py)
HARMONICS_PER_TOOTH = 8
#: Chebyshev collocation points across the rim for n = 0 and 1
COLLOCATION_POINTS = 48
#: Gauss points along a root chord for its read-outs
CHORD_POINTS = 24
#: harmonics per tooth of the plate's (flexure_green's) series: a tooth's own chord's
#: terms within 0.09 % of 32 per tooth, the helical reference pair's mesh stiffness 1e-4
#: (tests/test_gear_body.py)
FLEXURE_HARMONICS_PER_TOOTH = 4
#: the shear correction factor of the Mindlin plate (Mindlin 1951: 5/6 as Reissner's)
PLATE_SHEAR_FACTOR = 5.0 / 6.0


def _chebyshev(points: int) -> tuple[np.ndarray, np.ndarray]:
    """Chebyshev-Gauss-Lobatto points on [-1, 1] (from 1 down) and their differentiation
    matrix (L. N. Trefethen, *Spectral Methods in MATLAB*, 2000, cheb.m)."""
    x = np.cos(np.pi * np.arange(points + 1) / points)
    c = np.hstack([2.0, np.ones(points - 1), 2.0]) * (-1.0) ** np.arange(points + 1)
    dx = x[:, None] - x[None, :]
    D = np.outer(c, 1.0 / c) / (dx + np.eye(points + 1))
    return x, D - np.diag(D.sum(axis=1))


def collocated_harmonic(n: int, bore: float, rim: float, nu: float,
                        points: int = COLLOCATION_POINTS) -> np.ndarray:
    """The rim's displacement of harmonic n under unit traction (shear modulus 1): [[U, U],
    [V, V]] at r = rim for σ_rr = cos nθ (first column) and τ_rθ = sin nθ (second), with
    u_r = U cos nθ, u_θ = V sin nθ and u = 0 at the bore; plane stress. By Chebyshev
    collocation of Navier's equations: κ ∂e/∂r - (2/r) ∂ω/∂θ = 0, (κ/r) ∂e/∂θ + 2 ∂ω/∂r = 0
    (e the dilatation, ω the rotation, κ = 2/(1 - ν) in plane stress)."""
    kappa, lam = 2.0 / (1.0 - nu), 2.0 / (1.0 - nu) - 2.0
    x, D = _chebyshev(points)
    r = bore + 0.5 * (x + 1.0) * (rim - bore)
    D = D * 2.0 / (rim - bore)
    R, eye = np.diag(1.0 / r), np.eye(points + 1)
    e_U, e_V = D + R, n * R                     # e = e_U·U + e_V·V (times cos nθ)
    w_U, w_V = n * R, D + R                     # 2ω = w_U·U + w_V·V (times sin nθ)
    A = np.block([[kappa * D @ e_U - n * R @ w_U, kappa * D @ e_V - n * R @ w_V],
                  [-kappa * n * R @ e_U + D @ w_U, -kappa * n * R @ e_V + D @ w_V]])
    rhs = np.zeros((2 * points + 2, 2))
    outer, inner, rows = 0, points, points + 1
    A[outer] = np.hstack([kappa * D[outer] + lam * eye[outer] / r[outer],
                          lam * n * eye[outer] / r[outer]])            # σ_rr
    A[rows + outer] = np.hstack([-n * eye[outer] / r[outer],
                                 D[outer] - eye[outer] / r[outer]])   # τ_rθ
    A[inner] = np.hstack([eye[inner], 0.0 * eye[inner]])                 # U = 0
    A[rows + inner] = np.hstack([0.0 * eye[inner], eye[inner]])          # V = 0
    rhs[outer, 0] = rhs[rows + outer, 1] = 1.0
    solution = np.linalg.solve(A, rhs)
    return solution[[outer, rows + outer]]


def power_harmonics(n: np.ndarray, bore: float, rim: float, nu: float) -> np.ndarray:
    """As collocated_harmonic for every n >= 2 of `n` at once ((len(n), 2, 2)), from the
    four powers of Michell's solution (see the module), each scaled to at most 1 over the
    annulus so that high harmonics stay well conditioned."""
    n = np.asarray(n, float)
    kappa, lam = 2.0 / (1.0 - nu), 2.0 / (1.0 - nu) - 2.0
    powers = np.stack([n + 1.0, n - 1.0, 1.0 - n, -1.0 - n], axis=-1)       # (N, 4)
    nn = n[:, None]
    # V/U of each power from the first equation, or the second where its factor vanishes
    a1, b1 = kappa * nn * (powers - 1.0) - nn * (powers + 1.0), nn ** 2 - kappa * (powers ** 2 - 1.0)
    a2, b2 = (powers ** 2 - 1.0) - kappa * nn ** 2, kappa * nn * (powers + 1.0) - nn * (powers - 1.0)
    first = np.abs(a1) >= np.abs(a2)
    ratio = np.where(first, b1 / np.where(first, a1, 1.0), b2 / np.where(first, 1.0, a2))
    scale = np.where(powers > 0.0, rim, bore)
    at_rim, at_bore = (rim / scale) ** powers, (bore / scale) ** powers
    M = np.stack([
        (kappa * powers + lam * (1.0 + nn * ratio)) * at_rim / rim,         # σ_rr at the rim
        (-nn + ratio * (powers - 1.0)) * at_rim / rim,                       # τ_rθ at the rim
        at_bore,                                                             # U at the bore
        ratio * at_bore], axis=1)                                            # V at the bore
    rhs = np.zeros((len(n), 4, 2))
    rhs[:, 0, 0] = rhs[:, 1, 1] = 1.0
    c = np.linalg.solve(M, rhs)                                              # (N, 4, 2)
    U = np.einsum("nk,nkj->nj", at_rim, c)
    V = np.einsum("nk,nkj->nj", ratio * at_rim, c)
    return np.stack([U, V], axis=1)


@functools.lru_cache(maxsize=64)
def chord_green(bore: float, rim: float, half_angle: float, teeth: int, offset: int,
                E: float, nu: float) -> np.ndarray:
    """The body's compliance between two teeth's root chords (3 × 3, per unit thickness):
    [i, j] the displacement of kind i (the chord's mean radial displacement, mm; its mean
    tangential displacement, mm, counter-clockwise; its rotation, rad, counter-clockwise) of
    the tooth `offset` pitches counter-clockwise of a tooth loaded by a unit load of kind j
    (radial force outward, tangential force counter-clockwise, N/mm; moment, N·mm/mm,
    counter-clockwise). bore, rim: the annulus's radii (mm); half_angle: the half angle a
    root chord subtends (rad); a gear of `teeth` teeth; E (MPa), nu. chord_green(offset)
    is chord_green(-offset) transposed (reciprocity)."""
    mu = E / (2.0 * (1.0 + nu))
    a = half_angle * rim                                  # the chord's half length (mm)
    turn = 2.0 * math.pi * offset / teeth
    xg, wg = np.polynomial.legendre.leggauss(CHORD_POINTS)
    theta, weight = half_angle * xg, half_angle * wg       # along the read chord, about its middle
    read = turn + theta
    # read-outs: the chord's mean u_r, mean u_θ, and ∫ u_r·(-3x/(2a³)) dx (its rotation)
    spread = -3.0 * rim * theta / (2.0 * a ** 3)
    reads = np.stack([weight / (2.0 * half_angle), weight / (2.0 * half_angle),
                      weight * rim * spread])
    n = np.arange(2, HARMONICS_PER_TOOTH * teeth + 1)
    H = np.concatenate([np.stack([collocated_harmonic(k, bore, rim, nu) for k in (0, 1)]),
                        power_harmonics(n, bore, rim, nu)]) / mu
    n = np.arange(0, len(H)).astype(float)
    # the loads' Fourier coefficients: the forces' even block (cos), the moment's odd ramp (sin)
    na = np.maximum(n, 1.0) * half_angle
    block = np.where(n == 0, 1.0 / (2.0 * math.pi * rim),
                     np.sin(na) / (math.pi * rim * na))
    ramp = np.where(n == 0, 0.0, -3.0 / (a ** 3 * math.pi) * rim
                    * (np.sin(na) / np.maximum(n, 1.0) ** 2
                       - half_angle * np.cos(na) / np.maximum(n, 1.0)))
    cos, sin = np.cos(np.outer(n, read)), np.sin(np.outer(n, read))
    # each load's rim traction in the two families of a harmonic (H maps the traction's
    # (σ_rr, τ_rθ) amplitudes to the rim's (U, V)): the radial force σ_rr = Σ block·cos nθ
    # gives u_r = Σ H00·block cos nθ, u_θ = Σ H10·block sin nθ; the tangential force
    # τ_rθ = Σ block·cos nθ gives u_r = -Σ H01·block sin nθ, u_θ = Σ H11·block cos nθ (n = 0:
    # the body's torsion); the moment σ_rr = Σ ramp·sin nθ gives u_r = Σ H00·ramp sin nθ,
    # u_θ = -Σ H10·ramp cos nθ
    displacements = [
        ((H[:, 0, 0] * block) @ cos, (H[:, 1, 0] * block) @ sin),
        (-(H[:, 0, 1] * block) @ sin, (H[:, 1, 1] * block) @ cos),
        ((H[:, 0, 0] * ramp) @ sin, -(H[:, 1, 0] * ramp) @ cos),
    ]
    return np.array([[reads[0] @ u_r, reads[1] @ u_t, reads[2] @ u_r]
                     for u_r, u_t in displacements]).T


def flexure_harmonic(n: int, bore: float, rim: float, nu: float, thickness: float,
                     points: int = COLLOCATION_POINTS) -> np.ndarray:
    """The rim's motion of harmonic n of a Mindlin annular plate (E = 1, held at the bore,
    `thickness` mm thick) under unit edge loads: [[W], [P], [T]] (3 × 3) at r = rim for the
    shear Q_r = cos nθ, the bending moment M_r = cos nθ and the twisting moment M_rθ =
    sin nθ (columns, per unit length of rim), with w = W cos nθ, ψ_r = P cos nθ, ψ_θ = T sin
    nθ (in-plane displacement z·ψ at height z). Symmetric (the loads are the motions'
    work-conjugates). Chebyshev collocation of Mindlin's equations in polar coordinates:
    ∂M_r/∂r + ∂M_rθ/(r∂θ) + (M_r - M_θ)/r = Q_r, ∂M_rθ/∂r + ∂M_θ/(r∂θ) + 2 M_rθ/r = Q_θ,
    ∂Q_r/∂r + Q_r/r + ∂Q_θ/(r∂θ) = 0, with M from ψ (bending stiffness D) and Q = κ G t
    (∂w + ψ)."""
    shear = PLATE_SHEAR_FACTOR * thickness / (2.0 * (1.0 + nu))
    D = thickness ** 3 / (12.0 * (1.0 - nu ** 2))
    x, d = _chebyshev(points)
    r = bore + 0.5 * (x + 1.0) * (rim - bore)
    d = d * 2.0 / (rim - bore)
    size = points + 1
    eye, zero, R = np.eye(size), np.zeros((size, size)), np.diag(1.0 / r)
    W, P, T = (np.hstack([eye if k == j else zero for k in range(3)]) for j in range(3))
    M_r = D * (d @ P + nu * R @ (P + n * T))
    M_t = D * (R @ (P + n * T) + nu * d @ P)
    M_rt = 0.5 * D * (1.0 - nu) * (-n * R @ P + d @ T - R @ T)
    Q_r, Q_t = shear * (d @ W + P), shear * (-n * R @ W + T)
    A = np.vstack([d @ Q_r + n * R @ Q_t + R @ Q_r,
                   d @ M_r + n * R @ M_rt + R @ (M_r - M_t) - Q_r,
                   d @ M_rt - n * R @ M_t + 2.0 * R @ M_rt - Q_t])
    rhs = np.zeros((3 * size, 3))
    rim_rows = [0, size, 2 * size]                 # each equation's row at the rim ...
    for k, (load, held) in enumerate(((Q_r, W), (M_r, P), (M_rt, T))):
        A[rim_rows[k]] = load[0]                    # ... takes the edge load
        A[rim_rows[k] + points] = held[points]      # ... and at the bore the support
        rhs[rim_rows[k], k] = 1.0
    return np.linalg.solve(A, rhs)[rim_rows]


@functools.lru_cache(maxsize=16)
def _flexure_series(bore: float, rim: float, half_angle: float, teeth: int,
                    thickness: float, E: float, nu: float) -> tuple[np.ndarray, ...]:
    """The plate's series for flexure_green: the harmonics n, their rim responses H
    ((N, 3, 3), mm and rad per unit edge load, E applied) times the chord's block (the
    Fourier coefficient of a unit resultant spread evenly over the chord) and the chord's
    mean (sinc) of each harmonic."""
    n = np.arange(0, FLEXURE_HARMONICS_PER_TOOTH * teeth + 1)
    H = np.stack([flexure_harmonic(int(k), bore, rim, nu, thickness) for k in n]) / E
    na = np.maximum(n, 1) * half_angle
    block = np.where(n == 0, 1.0 / (2.0 * math.pi * rim), np.sin(na) / (math.pi * rim * na))
    sinc = np.where(n == 0, 1.0, np.sin(na) / na)
    return n.astype(float), H * (block * sinc)[:, None, None]


def flexure_green(bore: float, rim: float, half_angle: float, teeth: int, thickness: float,
                  angle, E: float, nu: float) -> np.ndarray:
    """The body's out-of-plane compliance between two root chords ((..., 3, 3) for an
    array of angles): [i, j] the chord's mean motion of kind i (w: axial displacement, mm;
    ψ_r: rotation about the rim's tangent, rad, the radial displacement z·ψ_r at face
    position z; ψ_θ: rotation about the radius, rad, the tangential displacement z·ψ_θ) of a
    chord `angle` rad counter-clockwise of a chord loaded by a unit resultant of kind j (the
    axial force, N; the moments, N·mm, work-conjugate to ψ_r and ψ_θ), each spread evenly
    over its chord. The annulus between `bore` (held) and `rim` (mm) as a Mindlin plate
    `thickness` mm thick (the face width); half_angle: the half angle a root chord subtends
    (rad); a gear of `teeth` teeth for the series' length; E (MPa), nu.
    flexure_green(-angle) is flexure_green(angle) transposed.

    A load family Q, M_r = cos nθ gives w, ψ_r ∝ cos nθ and ψ_θ ∝ sin nθ; the twisting
    moment's cos nθ the same turned a quarter period: w, ψ_r ∝ -sin nθ, ψ_θ ∝ cos nθ."""
    n, H = _flexure_series(bore, rim, half_angle, teeth, thickness, E, nu)
    angle = np.asarray(angle, float)
    c, s = np.cos(angle[..., None] * n), np.sin(angle[..., None] * n)
    out = np.empty(angle.shape + (3, 3))
    out[..., :2, :2] = np.einsum("nij,...n->...ij", H[:, :2, :2], c)
    out[..., 2, :2] = s @ H[:, 2, :2]
    out[..., :2, 2] = -(s @ H[:, :2, 2])
    out[..., 2, 2] = c @ H[:, 2, 2]
    return out
