"""Elastohydrodynamic film thickness of a lubricated contact (isothermal, fully flooded).

Dimensionless groups (Dowson & Higginson; Hamrock & Dowson): speed U = η0·u/(E'·R_x),
materials G = α·E', load W = w/(E'·R_x) per unit length (line) or W = F/(E'·R_x²) (point),
with u the mean entraining speed (u1 + u2)/2 across the contact, R_x the relative radius
of curvature along it, E' = 2/((1 - ν1²)/E1 + (1 - ν2²)/E2).

* Line contact: minimum film H_min = 2.65·U^0.70·G^0.54·W^-0.13 (Dowson & Higginson,
  Elasto-Hydrodynamic Lubrication, SI ed. 1977) and central film H_c = 3.06·U^0.69·G^0.56·
  W^-0.10 (Dowson & Toyoda, Proc. 5th Leeds-Lyon Symposium, 1979): one family, H_min about
  0.75 of H_c at gear conditions (Pan & Hamrock's central film, paired with it before, came
  out equal to or below Dowson-Higginson's minimum).
* Elliptical contact: H_c = 2.69·U^0.67·G^0.53·W^-0.067·(1 - 0.61·exp(-0.73·k)) and
  H_min = 3.63·U^0.68·G^0.49·W^-0.073·(1 - exp(-0.68·k)), k = 1.0339·(R_y/R_x)^0.636
  (Hamrock & Dowson, ASME J. Lubr. Technol. 99 (1977) 264-276).

Units in and out: Pa·s, m/s, mm, N/mm or N, MPa, 1/MPa; films in µm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class Film:
    """Central and minimum film thickness (µm)."""

    central_um: float
    minimum_um: float


def reduced_modulus(E1: float, nu1: float, E2: float, nu2: float) -> float:
    """E' = 2/((1 - ν1²)/E1 + (1 - ν2²)/E2) (MPa), the EHL literature's reduced modulus."""
    return 2.0 / ((1.0 - nu1 ** 2) / E1 + (1.0 - nu2 ** 2) / E2)


def _groups(eta: float, u: float, R_mm: float, E_reduced: float, alpha: float):
    """U and G (SI inside: E' in Pa, R in m)."""
    E = E_reduced * 1e6
    return eta * u / (E * R_mm * 1e-3), alpha * E_reduced


def line_film(eta: float, u: float, R_mm: float, w: float, E_reduced: float,
              alpha: float) -> Film:
    """A line contact's film: η (Pa·s), mean entraining speed u (m/s), relative radius R
    (mm), load per unit length w (N/mm), E' (MPa), α (1/MPa)."""
    U, G = _groups(eta, u, R_mm, E_reduced, alpha)
    W = w / (E_reduced * R_mm)
    R_um = R_mm * 1e3
    return Film(3.06 * U ** 0.69 * G ** 0.56 * W ** -0.10 * R_um,
                2.65 * U ** 0.70 * G ** 0.54 * W ** -0.13 * R_um)


def point_film(eta: float, u: float, R_x: float, R_y: float, F: float, E_reduced: float,
               alpha: float) -> Film:
    """An elliptical contact's film: R_x (mm) along the entraining direction, R_y across
    it, normal load F (N); as line_film otherwise."""
    U, G = _groups(eta, u, R_x, E_reduced, alpha)
    W = F / (E_reduced * R_x ** 2)
    k = 1.0339 * (R_y / R_x) ** 0.636
    R_um = R_x * 1e3
    return Film(2.69 * U ** 0.67 * G ** 0.53 * W ** -0.067 * (1.0 - 0.61 * math.exp(-0.73 * k)) * R_um,
                3.63 * U ** 0.68 * G ** 0.49 * W ** -0.073 * (1.0 - math.exp(-0.68 * k)) * R_um)
