"""AGMA pitting-resistance formulas for an uncrowned spur pair (seed 003 eqs (3)-(5)).

Source: ANSI/AGMA 2001-B88 as quoted by Wang & El-Bayoumy 2009 (seed 003). Units: mm, N, MPa.
"""

from __future__ import annotations

import math


def elastic_coefficient(C_E: float) -> float:
    """Seed 003 eq (5): Cp = sqrt(1 / (π·((1-nu1²)/E1 + (1-nu2²)/E2))) (sqrt(MPa))."""
    return math.sqrt(1.0 / (math.pi * C_E))


def geometry_factor(rho1: float, rho2: float, pressure_angle: float, pitch_diameter: float,
                    internal: bool) -> float:
    """Seed 003 eq (4): I = cos(phi_op) / ((1/rho1 ± 1/rho2)·d), + external, - internal.

    rho1, rho2: profile radii of curvature (mm, both positive); d: operating pitch diameter
    of the pinion (mm). Dimensionless."""
    relative = 1.0 / rho1 - 1.0 / rho2 if internal else 1.0 / rho1 + 1.0 / rho2
    return math.cos(pressure_angle) / (relative * pitch_diameter)


def contact_stress(Cp: float, tangential_load: float, pitch_diameter: float, face_width: float,
                   I: float) -> float:
    """Seed 003 eq (3): Sc = Cp·sqrt(Wt / (d·F·I)) (MPa), uncrowned, aligned."""
    return Cp * math.sqrt(tangential_load / (pitch_diameter * face_width * I))
