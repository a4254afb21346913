"""Tooth stiffness of a spur or helical pair: ISO 6336-1's single and mesh stiffness and
its face load factor K_Hβ (the references the tooth-compliance model is checked against),
and the gear body's compliance under a tooth (Sainsot et al. 2004) that model uses.

ISO 6336-1:2006 §9 (Method B, solid gears): the theoretical single stiffness of a tooth
pair is c'_th = 1/q' with the flexibility q' = C1 + C2/zn1 + C3/zn2 + C4·x1 + C5·x1/zn1
+ C6·x2 + C7·x2/zn2 + C8·x1² + C9·x2² (mm·µm/N; Table 9: C1..C9 below; zn the virtual
tooth numbers, negative for an internal gear); the single stiffness is
c' = c'_th · C_M · C_R · C_B · cos β with C_M = 0.8 (the standard's correction of the
theoretical value), C_R = 1 (solid gear blanks) and C_B = 1 (basic rack per ISO 53:
h_fP = 1.25 m, h_aP = 1.0 m). Units: N/(mm·µm) per mm of face; the pair's stiffness is
c'·b (N/µm). For other materials ISO scales c' by E/E_st (§9.2, E = 2E1E2/(E1+E2),
E_st = 206 000 N/mm²).
"""

from __future__ import annotations

import math

import numpy as np

#: ISO 6336-1:2006 Table 9, constants of the flexibility q'
C = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182)
#: ISO 6336-1:2006 §9.3.2: the correction factor of the theoretical single stiffness
C_M = 0.8
#: ISO 6336-1:2006 §9.2: the steel modulus (MPa) c' is given for
E_STEEL = 206000.0


def single_stiffness(z1: int, z2: int, x1: float = 0.0, x2: float = 0.0,
                     helix_angle: float = 0.0) -> float:
    """Single stiffness c' (N/(mm·µm)) of a solid spur/helical pair with the ISO 53 rack:
    teeth z1, z2 (z2 negative for a ring gear), profile shifts x1, x2, helix angle (rad)."""
    zn1 = z1 / math.cos(helix_angle) ** 3
    zn2 = z2 / math.cos(helix_angle) ** 3
    c1, c2, c3, c4, c5, c6, c7, c8, c9 = C
    q = (c1 + c2 / zn1 + c3 / zn2 + c4 * x1 + c5 * x1 / zn1 + c6 * x2 + c7 * x2 / zn2
         + c8 * x1 ** 2 + c9 * x2 ** 2)
    return C_M / q * math.cos(helix_angle)


def mesh_stiffness(single: float, contact_ratio: float) -> float:
    """Mesh stiffness c_γα (N/(mm·µm)) from the single stiffness c' and the transverse
    contact ratio ε_α: ISO 6336-1:2006 §9.3.3, c_γα = c'·(0.75·ε_α + 0.25)."""
    return single * (0.75 * contact_ratio + 0.25)


def face_load_factor(misalignment_um: float, stiffness: float, line_load: float) -> float:
    """K_Hβ of ISO 6336-1:2006 §7.6 (Method C, a linear mesh misalignment) for the effective
    mesh misalignment F_βy (µm) over the face, the mesh stiffness c_γβ (N/(mm·µm)) and the
    mean line load F_m/b (N/mm): 1 + F_βy·c_γβ/(2·F_m/b) while that is at most 2 (the load
    spreads over the whole face), sqrt(2·F_βy·c_γβ/(F_m/b)) beyond (it covers part of it)."""
    ratio = misalignment_um * stiffness / line_load
    return 1.0 + 0.5 * ratio if ratio <= 2.0 else math.sqrt(2.0 * ratio)


#: Sainsot, Velex & Duverger (2004), Table 1, as reprinted by Chaari et al. (2009) Table 1:
#: the coefficients (A, B, C, D, E, F) of L*, M*, P*, Q*, each
#: X* = A/θ_f² + B·h_fi² + C·h_fi/θ_f + D/θ_f + E·h_fi + F
FOUNDATION = {"L": (-5.574e-5, -1.9986e-3, -2.3015e-4, 4.7702e-3, 0.0271, 6.8045),
              "M": (60.111e-5, 28.100e-3, -83.431e-4, -9.9256e-3, 0.1624, 0.9086),
              "P": (-50.952e-5, 185.50e-3, 0.0538e-4, 53.300e-3, 0.2895, 0.9236),
              "Q": (-6.2042e-5, 9.0889e-3, -4.0964e-4, 7.8297e-3, -0.1472, 0.6904)}


def foundation_compliance(u_f, S_f: float, theta_f: float, h_fi: float, load_angle,
                          E: float):
    """Compliance (mm²/N per unit face width) of the gear body under a tooth (the fillet
    foundation): Sainsot, Velex & Duverger, "Contribution of gear body to tooth deflections
    - a new bidimensional analytical formula", J. Mech. Des. 126 (2004) 748-752, as used by
    Chaari et al. (2009) eq (5):
    cos²α_m/E · [L*(u_f/S_f)² + M*(u_f/S_f) + P*(1 + Q*·tan²α_m)].
    u_f (mm): from the root circle along the tooth's centre line to where the load line
    crosses it; S_f (mm): the tooth's chord on the root circle; theta_f (rad): half the
    angle that chord subtends; h_fi: root radius over bore radius; load_angle α_m (rad):
    the load's angle to the perpendicular of the centre line; E (MPa).

    With arrays u_f and load_angle (n loads on one tooth) it gives the (n × n) cross
    compliance: the body's displacement along load i under load j, the fit's bracket as the
    symmetric bilinear form it is the square of (the body takes the tooth's root moment,
    its force across and its force along the centre line):
    cos α_i cos α_j/E · [L* x_i x_j + M*(x_i + x_j)/2 + P*(1 + Q* tan α_i tan α_j)],
    x = u_f/S_f; its diagonal is the fit."""
    def star(name):
        A, B, C, D, E_, F = FOUNDATION[name]
        return (A / theta_f ** 2 + B * h_fi ** 2 + C * h_fi / theta_f + D / theta_f
                + E_ * h_fi + F)

    x = np.asarray(u_f, float) / S_f
    angle = np.asarray(load_angle, float)
    outer = np.multiply.outer
    cos, tan = np.cos(angle), np.tan(angle)
    form = (outer(cos, cos) / E
            * (star("L") * outer(x, x) + 0.5 * star("M") * np.add.outer(x, x)
               + star("P") * (1.0 + star("Q") * outer(tan, tan))))
    return float(form) if np.ndim(u_f) == 0 else form
