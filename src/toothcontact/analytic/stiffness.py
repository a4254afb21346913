"""Tooth stiffness of a spur or helical pair, for sharing the load between tooth pairs.

ISO 6336-1:2006 §9 (Method B, solid gears): the theoretical single stiffness of a tooth
pair is c'_th = 1/q' with the flexibility q' = C1 + C2/zn1 + C3/zn2 + C4·x1 + C5·x1/zn1
+ C6·x2 + C7·x2/zn2 + C8·x1² + C9·x2² (mm·µm/N; Table 9: C1..C9 below; zn the virtual
tooth numbers, negative for an internal gear); the single stiffness is
c' = c'_th · C_M · C_R · C_B · cos β with C_M = 0.8 (the standard's correction of the
theoretical value), C_R = 1 (solid gear blanks) and C_B = 1 (basic rack per ISO 53:
h_fP = 1.25 m, h_aP = 1.0 m). Units: N/(mm·µm) per mm of face; the pair's stiffness is
c'·b (N/µm).
"""

from __future__ import annotations

import math

#: ISO 6336-1:2006 Table 9, constants of the flexibility q'
C = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182)
#: ISO 6336-1:2006 §9.3.2: the correction factor of the theoretical single stiffness
C_M = 0.8


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
