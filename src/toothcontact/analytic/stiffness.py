"""Tooth stiffness of a spur or helical pair: ISO 6336-1's single and mesh stiffness (the
references the tooth-compliance model is checked against, and what ISO's load factors take),
and the gear body's compliance under a tooth (Sainsot et al. 2004) that model uses.

ISO 6336-1:2006 §9 (Method B): the theoretical single stiffness of a tooth pair is
c'_th = 1/q' with the flexibility q' = C1 + C2/zn1 + C3/zn2 + C4·x1 + C5·x1/zn1 + C6·x2 +
C7·x2/zn2 + C8·x1² + C9·x2² (mm·µm/N; Table 9: C1..C9 below; zn the virtual tooth numbers
z/(cos²β_b·cos β), negative for an internal gear: ISO/TR 6336-30 Example 1 evaluates its
c'_th = 17.85584 so, z/cos³β would give 0.16 % more); the single stiffness is
c' = c'_th·C_M·C_R·C_B·cos β with C_M = 0.8 (the standard's correction of the theoretical
value), C_R = 1 (solid gear blanks, as the tooth compliance model assumes) and the basic rack
factor C_B = [1 + 0.5·(1.2 - h_fP/m_n)]·[1 - 0.02·(20° - α_n)] (1 for h_fP = 1.2 m_n; 0.975
for ISO 53 profile A's 1.25; the TR's 0.9 for profile D's 1.4), times (F_t·K_A/b / 100)^0.25
where that line load is below 100 N/mm. Units: N/(mm·µm) per mm of face; the pair's
stiffness is c'·b (N/µm). For other materials ISO scales c' by E/E_st (§9.2,
E = 2E1E2/(E1+E2), E_st = 206 000 N/mm²).
"""

from __future__ import annotations

import math

import numpy as np

#: ISO 6336-1:2006 Table 9, constants of the flexibility q'
C = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182)
#: ISO 6336-1:2006 §9.3.2: the correction factor of the theoretical single stiffness, and
#: the rim factor of a solid gear blank
C_M, C_R = 0.8, 1.0
#: ISO 6336-1:2006 §9.2: the steel modulus (MPa) c' is given for
E_STEEL = 206000.0


def single_stiffness(z1: int, z2: int, x1: float = 0.0, x2: float = 0.0,
                     helix_angle: float = 0.0, pressure_angle: float = math.radians(20.0),
                     dedendum: float = 1.2, line_load: float | None = None) -> float:
    """Single stiffness c' (N/(mm·µm)) of a solid spur/helical pair (see the module): teeth
    z1, z2 (z2 negative for a ring gear), profile shifts x1, x2, helix angle and normal
    pressure angle (rad) of the basic rack, its dedendum h_fP/m_n and the line load
    F_t·K_A/b (N/mm; None: at least 100)."""
    transverse = math.atan(math.tan(pressure_angle) / math.cos(helix_angle))
    base_helix = math.atan(math.tan(helix_angle) * math.cos(transverse))
    virtual = math.cos(base_helix) ** 2 * math.cos(helix_angle)
    zn1, zn2 = z1 / virtual, z2 / virtual
    c1, c2, c3, c4, c5, c6, c7, c8, c9 = C
    q = (c1 + c2 / zn1 + c3 / zn2 + c4 * x1 + c5 * x1 / zn1 + c6 * x2 + c7 * x2 / zn2
         + c8 * x1 ** 2 + c9 * x2 ** 2)
    C_B = (1.0 + 0.5 * (1.2 - dedendum)) * (1.0 - 0.02 * (20.0 - math.degrees(pressure_angle)))
    low_load = 1.0 if line_load is None or line_load >= 100.0 else (line_load / 100.0) ** 0.25
    return C_M / q * C_R * C_B * math.cos(helix_angle) * low_load


def mesh_stiffness(single: float, contact_ratio: float) -> float:
    """Mesh stiffness c_γα (N/(mm·µm)) from the single stiffness c' and the transverse
    contact ratio ε_α: ISO 6336-1:2006 §9.3.3, c_γα = c'·(0.75·ε_α + 0.25)."""
    return single * (0.75 * contact_ratio + 0.25)


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
