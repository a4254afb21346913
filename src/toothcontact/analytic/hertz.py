"""Hertz contact of two elastic bodies: point contact (exact and Roark's form) and line contact.

Conventions: curvature is positive for a body convex toward the other, negative for a concave
one; the gap between the undeformed surfaces near the first touching point is
h = A·x² + B·y² with A <= B, so the long semi-axis a lies along x. Units: mm, N, MPa.

Sources:
- Johnson, K.L., *Contact Mechanics*, Cambridge University Press 1985, §4.2, eqs (4.36)-(4.39)
  (exact ellipse from the complete elliptic integrals) and §4.1, eq (4.45) (line contact).
- Young, W.C., *Roark's Formulas for Stress and Strain*, 6th ed. 1989, Table 33 case 4
  (Table 14.1 in the 7th ed.), as quoted in seed 003 (Wang & El-Bayoumy 2009) eqs (6)-(11).
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class RelativeCurvature:
    """Gap h = A x² + B y² (1/mm), A <= B; `angle` (rad) from body 1's first principal
    direction to the x axis (the direction of A, along which the long semi-axis a lies)."""

    A: float
    B: float
    angle: float


@dataclass(frozen=True)
class PointContact:
    """Loaded Hertz ellipse: semi-axes a >= b (mm), peak pressure p0 (MPa), approach (mm)."""

    a: float
    b: float
    p0: float
    approach: float
    A: float
    B: float

    @property
    def mean_pressure(self) -> float:
        return 2.0 * self.p0 / 3.0


def compliance(E1: float, nu1: float, E2: float, nu2: float) -> float:
    """Combined elastic compliance C_E = (1-nu1²)/E1 + (1-nu2²)/E2 (1/MPa).

    Seed 003 eq (11); its inverse is Johnson's contact modulus E* (Johnson eq 4.22)."""
    for name, E in (("E1", E1), ("E2", E2)):
        if not E > 0:
            raise ValueError(f"{name} must be > 0 MPa, got {E}")
    for name, nu in (("nu1", nu1), ("nu2", nu2)):
        if not -1.0 < nu < 0.5:
            raise ValueError(f"{name} must lie in (-1, 0.5), got {nu}")
    return (1.0 - nu1**2) / E1 + (1.0 - nu2**2) / E2


def curvatures_from_radii(radii: tuple[float, float]) -> tuple[float, float]:
    """Principal curvatures 1/R (1/mm) from principal radii; an infinite radius is flat."""
    return tuple(0.0 if math.isinf(r) else 1.0 / r for r in radii)  # type: ignore[return-value]


def relative_curvature(k1: tuple[float, float], k2: tuple[float, float],
                       angle: float = 0.0, point_contact: bool = True) -> RelativeCurvature:
    """A and B of the gap from the principal curvatures of both bodies.

    `angle` (rad) is between body 1's first and body 2's first principal direction. The gap
    is half the sum of the two curvature tensors, which gives Johnson §4.2's
    A + B = (k11+k12+k21+k22)/2 and B - A = ½·sqrt((k11-k12)² + (k21-k22)²
    + 2(k11-k12)(k21-k22)·cos 2ψ) (Roark Table 33 case 4, the root in cos theta).
    Raises ValueError when the gap is not positive definite (conforming or separating bodies),
    unless point_contact is False (line contact, A = 0, is then returned as computed).
    """
    c, s = math.cos(angle), math.sin(angle)
    t11 = k1[0] + k2[0] * c * c + k2[1] * s * s
    t22 = k1[1] + k2[0] * s * s + k2[1] * c * c
    t12 = (k2[0] - k2[1]) * c * s
    mean, half_diff = 0.5 * (t11 + t22), math.hypot(0.5 * (t11 - t22), t12)
    lo, hi = mean - half_diff, mean + half_diff
    if point_contact and not lo > 0.0:
        raise ValueError(
            "the bodies do not make point contact: the relative curvature "
            f"({lo:.4g}, {hi:.4g}) 1/mm must be positive in every direction "
            "(a concave body must be less curved than the convex one it holds)")
    direction = 0.5 * math.atan2(-2.0 * t12, t22 - t11) if half_diff > 0 else 0.0
    return RelativeCurvature(A=0.5 * lo, B=0.5 * hi, angle=direction)


def _aspect_from_curvature_ratio(ratio: float) -> float:
    """k = b/a of the Hertz ellipse for B/A = ratio >= 1 (Johnson eq 4.39a):
    B/A = ((a/b)² E(e) - K(e)) / (K(e) - E(e)), e² = 1 - k²."""
    from scipy.optimize import brentq

    if ratio < 1.0:
        raise ValueError(f"B/A must be >= 1, got {ratio}")
    if ratio - 1.0 < 1e-8:
        # near-circular: B/A = 1 + (3/4)·e² + O(e⁴), exact to rounding here
        return math.sqrt(1.0 - 4.0 / 3.0 * (ratio - 1.0))

    def excess(log_k: float) -> float:
        k2 = math.exp(2.0 * log_k)
        K, E = _complete_integrals(k2)
        return (E / k2 - K) - ratio * (K - E)

    log_k = brentq(excess, math.log(1e-12), math.log(1.0 - 1e-9), xtol=1e-15, rtol=1e-15,
                   maxiter=200)
    return math.exp(log_k)


def _complete_integrals(k2: float) -> tuple[float, float]:
    """K(e) and E(e), the complete elliptic integrals of the first and second kind, of the
    ellipse of aspect k = b/a (k2 = k², e² = 1 - k²); scipy's ellipkm1 keeps K exact as
    k -> 0 (imported here: scipy.special is slow to import)."""
    from scipy.special import ellipe, ellipkm1

    return float(ellipkm1(k2)), float(ellipe(1.0 - k2))


def hertz_point(A: float, B: float, load: float, C_E: float) -> PointContact:
    """Exact Hertz ellipse for gap h = A x² + B y² pressed by `load` (N).

    Johnson eqs (4.36)-(4.39): with k = b/a and e² = 1 - k², A + B = p0·E(e)/(E*·b),
    P = (2/3)·π·a·b·p0, approach = p0·b·K(e)/E*; hence b³ = 3·P·k·E(e)·C_E / (2π(A+B)).
    """
    A, B = min(A, B), max(A, B)
    if not (A > 0 and load > 0 and C_E > 0):
        raise ValueError(f"need A > 0, load > 0, C_E > 0; got A={A}, load={load}, C_E={C_E}")
    k = _aspect_from_curvature_ratio(B / A)
    K, E = _complete_integrals(k * k)
    b = (3.0 * load * k * E * C_E / (2.0 * math.pi * (A + B))) ** (1.0 / 3.0)
    a = b / k
    p0 = 3.0 * load / (2.0 * math.pi * a * b)
    return PointContact(a=a, b=b, p0=p0, approach=p0 * b * K * C_E, A=A, B=B)


def roark_coefficients(cos_theta: float) -> tuple[float, float, float]:
    """Roark's alpha, beta, lambda for the general two-body contact (Roark Table 33 case 4).

    cos(theta) = (B - A)/(A + B). a = alpha·(P·K_D·C_E)^(1/3), b = beta·(...)^(1/3),
    approach y = lambda·(P²·C_E²/K_D)^(1/3), with K_D = 1.5/(sum of the four principal
    curvatures). The tabulated values follow from Johnson's exact solution:
    beta = (2·k·E(e)/π)^(1/3), alpha = beta/k, lambda = 3·K(e)/(2·π·alpha).
    """
    if not 0.0 <= cos_theta < 1.0:
        raise ValueError(f"cos(theta) must lie in [0, 1), got {cos_theta}")
    k = _aspect_from_curvature_ratio((1.0 + cos_theta) / (1.0 - cos_theta))
    K, E = _complete_integrals(k * k)
    beta = (2.0 * k * E / math.pi) ** (1.0 / 3.0)
    alpha = beta / k
    return alpha, beta, 3.0 * K / (2.0 * math.pi * alpha)


def roark_point(curvature_sum: float, curvature_difference: float, load: float,
                C_E: float) -> PointContact:
    """Seed 003 eqs (6)-(11): sigma_c = 1.5 P/(π a b), a = alpha (P K_D C_E)^(1/3),
    b = beta (P K_D C_E)^(1/3), with K_D = 1.5 / (1/rho1 + 1/rho2 + 1/R1 + 1/R2).

    `curvature_sum` is the sum of the four principal curvatures (1/mm) and
    `curvature_difference` Roark's square-root term, so cos(theta) = difference / sum.
    Eq (10) as printed carries a trailing "· d" (pitch diameter); that makes a not a length,
    and Roark's own K_D has no such factor, so it is left out here (seeds README).
    """
    K_D = 1.5 / curvature_sum
    alpha, beta, lam = roark_coefficients(curvature_difference / curvature_sum)
    scale = (load * K_D * C_E) ** (1.0 / 3.0)
    a, b = alpha * scale, beta * scale
    approach = lam * (load**2 * C_E**2 / K_D) ** (1.0 / 3.0)
    A = 0.25 * (curvature_sum - curvature_difference)
    return PointContact(a=a, b=b, p0=1.5 * load / (math.pi * a * b), approach=approach,
                        A=A, B=0.5 * curvature_sum - A)


@dataclass(frozen=True)
class LineContact:
    """Hertz line contact: half-width b (mm) and peak pressure p0 (MPa)."""

    b: float
    p0: float


def hertz_line(load_per_length: float, relative_radius: float, C_E: float) -> LineContact:
    """Two parallel cylinders (Johnson eq 4.45): b = sqrt(4 w R / (π E*)),
    p0 = sqrt(w E* / (π R)), with 1/R = 1/R1 + 1/R2 and w the load per unit length (N/mm)."""
    if not (load_per_length > 0 and relative_radius > 0 and C_E > 0):
        raise ValueError("line contact needs positive load per length, radius and compliance")
    b = math.sqrt(4.0 * load_per_length * relative_radius * C_E / math.pi)
    return LineContact(b=b, p0=math.sqrt(load_per_length / (math.pi * relative_radius * C_E)))


def semi_axis_along(contact: PointContact, rc: RelativeCurvature, direction: float) -> float:
    """Half-length (mm) of the contact ellipse along `direction` (rad, same frame as rc.angle)."""
    phi = direction - rc.angle
    return 1.0 / math.sqrt((math.cos(phi) / contact.a) ** 2 + (math.sin(phi) / contact.b) ** 2)

