"""Worm-gear tooth efficiency: the DIN 3996 chain with a viscosity factor, and Kim's model.

Sources:
- seed 000: KISSsoft application note "Efficiency of a worm gear flap actuator as function
  of temperature" (2007), §3.5 (DIN 3996 formulas) and Table 3.5-1 (Y_VISC).
- seed 001: Kim, S.H., "Worm gear efficiency model considering misalignment in electric
  power steering systems", Mech. Sci. 9, 201-210, 2018, eqs (2), (3), (20), (21).
Units: mm, N, N·mm, rad, mm²/s.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

#: Seed 000 Table 3.5-1: kinematic viscosity (mm²/s) and the proposed viscosity factor.
Y_VISC_TABLE = ((11.0, 1.00), (57.0, 1.00), (310.0, 1.01), (1020.0, 1.08), (5000.0, 1.31),
                (30000.0, 1.46))


def lead_angle_from_pitch_diameter(starts: int, normal_module: float, pitch_diameter: float) -> float:
    """Mean lead angle gamma_m (rad) from sin(gamma) = z1·mn / d1 (worm pitch diameter d1)."""
    ratio = starts * normal_module / pitch_diameter
    if not 0 < ratio < 1:
        raise ValueError(f"z1·mn/d1 = {ratio:.4g} must lie in (0, 1)")
    return math.asin(ratio)


def viscosity_factor(viscosity: float) -> float:
    """Seed 000 Table 3.5-1: Y_VISC at a kinematic viscosity (mm²/s).

    Linear in log(viscosity) between the table's points, 1.0 below them; above 30000 mm²/s
    it is held at 1.46 with a warning (the note gives no data there)."""
    if not viscosity > 0:
        raise ValueError(f"viscosity must be > 0 mm²/s, got {viscosity}")
    nu, y = np.array(Y_VISC_TABLE).T
    if viscosity > nu[-1]:
        warnings.warn(f"viscosity {viscosity:g} mm²/s is above seed 000's last point "
                      f"({nu[-1]:g} mm²/s): Y_VISC held at {y[-1]}", stacklevel=2)
    return float(np.interp(math.log(viscosity), np.log(nu), y, left=1.0, right=y[-1]))


def mean_friction(mu_0T: float, Y_S: float = 1.0, Y_G: float = 1.0, Y_W: float = 1.0,
                  Y_R: float = 1.0, Y_VISC: float = 1.0) -> float:
    """Seed 000 §3.5: mu_zm = mu_0T·Y_S·Y_G·Y_W·Y_R·Y_VISC (DIN 3996 with the note's Y_VISC)."""
    return mu_0T * Y_S * Y_G * Y_W * Y_R * Y_VISC


def efficiency_worm_driving(lead_angle: float, mu: float) -> float:
    """Seed 000 §3.5 (DIN 3996): eta_z = tan(gamma_m) / tan(gamma_m + atan(mu_zm))."""
    return math.tan(lead_angle) / math.tan(lead_angle + math.atan(mu))


def efficiency_wheel_driving(lead_angle: float, mu: float) -> float:
    """DIN 3996 wheel-driving tooth efficiency eta_z' = tan(gamma_m - atan(mu_zm)) / tan(gamma_m).

    Zero or below means the pair is self-locking; the value is returned as computed."""
    return math.tan(lead_angle - math.atan(mu)) / math.tan(lead_angle)


def efficiency_kim(lead_angle: float, normal_pressure_angle: float, mu: float) -> float:
    """Seed 001 eq (2): eta = (cos alpha_n - mu·tan gamma) / (cos alpha_n + mu·cot gamma).

    Identical to the DIN form with an effective friction angle atan(mu / cos alpha_n)."""
    c = math.cos(normal_pressure_angle)
    return (c - mu * math.tan(lead_angle)) / (c + mu / math.tan(lead_angle))


def normal_tooth_load(wheel_torque: float, wheel_pitch_radius: float, lead_angle: float,
                      normal_pressure_angle: float) -> float:
    """Seed 001 eq (3): F_n = (T_wh / R_p)·sqrt(1 + tan²gamma + tan²alpha) (N).

    The root equals 1/(cos alpha_n·cos gamma) exactly when alpha is the axial pressure angle,
    tan alpha_x = tan alpha_n / cos gamma; the normal angle is converted to it here."""
    tan_axial = math.tan(normal_pressure_angle) / math.cos(lead_angle)
    return wheel_torque / wheel_pitch_radius * math.sqrt(1.0 + math.tan(lead_angle)**2 + tan_axial**2)


def anti_rattle_spring_force(wheel_torque: float, mount_moment: float, d1: float, d2: float,
                             wheel_pitch_radius: float, pressure_angle: float,
                             lead_angle: float) -> float:
    """Seed 001 eq (20): F_ARS = (d2·T_wh - M·R_p·cot(alpha)·cos(gamma))
                                  / ((d1 + d2)·R_p·cot(alpha)·cos(gamma))  (N).

    d2: worm-shaft mount (pivot) to the mesh, d1: mesh to the spring (mm); M: moment held at
    the mount (N·mm). The moment balance about the mount of the radial mesh force
    T_wh·tan(alpha)/(R_p·cos(gamma)) acting at d2."""
    lever = wheel_pitch_radius * math.cos(lead_angle) / math.tan(pressure_angle)
    return (d2 * wheel_torque - mount_moment * lever) / ((d1 + d2) * lever)


def anti_rattle_misalignment(spring_force: float, stiffness: float) -> float:
    """Seed 001 eq (21): x = F_ARS / k, the worm-shaft tip height at the spring (mm)."""
    return spring_force / stiffness
