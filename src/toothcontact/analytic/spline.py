"""Crowned involute spline teeth under angular misalignment (seed 003 and its ref. 4).

Sources: Wang & El-Bayoumy 2009 (seed 003) eq (19); Dudley, D.W., "When splines need stress
control", Product Engineering 23, Dec. 1957 (seed 003 ref. 4). Units: mm, N, N·mm, MPa, rad.
"""

from __future__ import annotations

import math

import numpy as np


def dudley_crown(engaged_length: float, misalignment: float) -> tuple[float, float]:
    """Dudley's crown for a misaligned spline: the drop at each end of the engaged length A
    equals what the tilt takes up there, C1 = (A/2)·tan(theta), and the crown radius is
    r1 = A² / (8·C1). Returns (crown height C1, crown radius r1) in mm."""
    if not (engaged_length > 0 and 0 < misalignment < math.pi / 2):
        raise ValueError("engaged length must be > 0 and misalignment in (0, 90°)")
    height = 0.5 * engaged_length * math.tan(misalignment)
    return height, engaged_length**2 / (8.0 * height)


def dudley_contact_stress(torque: float, pitch_diameter: float, teeth: int,
                          working_depth: float, crown_radius: float, C_E: float) -> float:
    """Dudley's contact stress of a crowned spline tooth (MPa): Hertz line contact of a
    cylinder of the crown radius r1 on a flat over the working depth h, carrying the
    tangential tooth load W = 2T/(D·N):  sigma = sqrt(W / (h·r1) / (π·C_E)).

    For steel (E = 30e6 psi, nu = 0.3) 1/sqrt(π·C_E) = 2290 sqrt(psi), which is Dudley's
    sigma = 2290·sqrt(2T/(D·N·h·r1)) psi. Dudley uses the tangential, not the normal,
    tooth load; so does this function."""
    tooth_load = 2.0 * torque / (pitch_diameter * teeth)
    return math.sqrt(tooth_load / (working_depth * crown_radius) / (math.pi * C_E))


def max_crown_radius_for_fit(tooth_thickness: float, clearance: float,
                             misalignment: float) -> float:
    """Seed 003 eq (19): the largest crown radius at which the crowned tooth (thickness T_mod
    at the crown centre), tilted by theta, still fits a space T_mod + dT wide:
        R = [dT/2 + (T_mod/2)(1 - cos theta)]·(1 + cos theta) / sin² theta,
    i.e. R·(1 - cos theta) = dT/2 + (T_mod/2)(1 - cos theta) (seeds README)."""
    c, s = math.cos(misalignment), math.sin(misalignment)
    return (0.5 * clearance + 0.5 * tooth_thickness * (1.0 - c)) * (1.0 + c) / s**2


def tilted_tooth_clearance(crown_radius: float, tooth_thickness: float, clearance: float,
                           misalignment: float, half_length: float) -> float:
    """Smallest gap (mm) between a crowned tooth tilted by `misalignment` about its crown
    centre and the straight walls of a space T_mod + dT wide, over |z| <= half_length.

    Found by maximising the rotated flank arc numerically (an independent check of eq 19);
    negative means the tooth does not fit."""
    from scipy.optimize import minimize_scalar

    R, T, th = crown_radius, tooth_thickness, misalignment

    def rotated_x(z: float) -> float:
        x = 0.5 * T - (R - math.sqrt(R * R - z * z))
        return x * math.cos(th) + z * math.sin(th)

    span = min(half_length, R * (1 - 1e-12))
    grid = np.linspace(-span, span, 2001)
    best = grid[int(np.argmax([rotated_x(z) for z in grid]))]
    step = 2 * span / 2000
    res = minimize_scalar(lambda z: -rotated_x(z), bounds=(max(-span, best - step),
                                                           min(span, best + step)),
                          method="bounded", options={"xatol": 1e-12 * max(1.0, span)})
    widest = max(-res.fun, rotated_x(best))
    return 0.5 * (T + clearance) - widest
