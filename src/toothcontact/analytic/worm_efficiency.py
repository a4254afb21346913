"""Worm-gear tooth efficiency: the DIN 3996 chain with a viscosity factor, and Kim's model.

Sources:
- seed 000: KISSsoft application note "Efficiency of a worm gear flap actuator as function
  of temperature" (2007), §3.5 (DIN 3996 formulas) and Table 3.5-1 (Y_VISC).
- seed 001: Kim, S.H., "Worm gear efficiency model considering misalignment in electric
  power steering systems", Mech. Sci. 9, 201-210, 2018, eqs (2), (3), (10)-(21).
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
    lever = _anti_rattle_lever(wheel_pitch_radius, pressure_angle, lead_angle)
    return (d2 * wheel_torque - mount_moment * lever) / ((d1 + d2) * lever)


def anti_rattle_aligned_torque(mount_moment: float, d2: float, wheel_pitch_radius: float,
                               pressure_angle: float, lead_angle: float) -> float:
    """Seed 001 eq (20) solved for F_ARS = 0: the output torque
    T_wh = M·R_p·cot(alpha)·cos(gamma) / d2 (N·mm) at which the spring carries nothing and
    eq (21)'s misalignment is zero (the paper's 19.67 N·m)."""
    return mount_moment * _anti_rattle_lever(wheel_pitch_radius, pressure_angle, lead_angle) / d2


def _anti_rattle_lever(wheel_pitch_radius: float, pressure_angle: float,
                       lead_angle: float) -> float:
    """R_p·cot(alpha)·cos(gamma) of seed 001 eqs (20)-(21) (mm)."""
    return wheel_pitch_radius * math.cos(lead_angle) / math.tan(pressure_angle)


def anti_rattle_misalignment(spring_force: float, stiffness: float) -> float:
    """Seed 001 eq (21): x = F_ARS / k, the worm-shaft tip height at the spring (mm)."""
    return spring_force / stiffness


def kim_curvature_radii(worm_pitch_radius: float, base_radius: float, hob_radius: float,
                        lead_angle: float, wheel_pitch_radius: float,
                        pressure_angle: float) -> tuple[float, float, float, float]:
    """Seed 001 eqs (10)-(17): the radii of the four principal curves at the contact point of
    a ZI worm and a wheel cut by a hob of pitch radius r_h (mm):
    R1 (worm, eq 14 at u1 of eq 10), R2 = inf (the worm's straight blade, eq 15),
    R3 (wheel, eq 16 at u2 of eq 12), R4 = R_b·sqrt(R_p/R_b - 1), R_b = R_p·cos(alpha) (eq 17).
    Eqs (14)/(16) are the curvature radius of the helix-like curve x = r cos d + u cos l sin d,
    ... of eqs (4)/(7) at the given u."""
    rp, rb, rh, lam = worm_pitch_radius, base_radius, hob_radius, lead_angle
    if not rb < rp:
        raise ValueError(f"base radius {rb:.4g} mm must be below the worm pitch radius {rp:.4g} mm")
    c2 = math.cos(lam) ** 2

    def radius(r, u):   # eqs (14) and (16)
        return (r * r * c2 + u * u * c2) ** 1.5 / math.sqrt(
            r ** 4 * c2 + r * r * u * u * (1.0 + c2) + u ** 4 * c2 * c2)

    u1 = -rp * math.cos(math.asin(rb / rp)) * math.cos(lam)                       # eq (10)
    reach = rh + rp - rb
    u2 = -reach * math.cos(math.asin(rh / reach)) * math.cos(lam)                 # eq (12)
    Rb = wheel_pitch_radius * math.cos(pressure_angle)
    return radius(rb, u1), math.inf, radius(rh, u2), Rb * math.sqrt(wheel_pitch_radius / Rb - 1.0)


def kim_contact_pressure(normal_force: float, radii: tuple[float, float, float, float],
                         C_E: float) -> float:
    """Seed 001 eq (19): the mean contact pressure (MPa) of the normal force (N) on the
    contact area of eq (18), A = π·{(3/4)·C_E}^(2/3)·(R_eq1·R_eq2)^(1/3)·(F/3)^(2/3), with
    R_eq1 = R1·R3/(R3 - R1) and R_eq2 = R2·R4/(R4 + R2) (= R4 for R2 = inf):
    P = F^(1/3) / (π·{(1/4)·C_E}^(2/3)·(R_eq1·R_eq2)^(1/3))."""
    R1, R2, R3, R4 = radii
    if not R3 > R1:
        raise ValueError(f"the wheel's curve radius R3 = {R3:.4g} mm must exceed the worm's "
                         f"R1 = {R1:.4g} mm (a concave wheel holding the worm)")
    req1 = R1 * R3 / (R3 - R1)
    req2 = R4 if math.isinf(R2) else R2 * R4 / (R4 + R2)
    return normal_force ** (1.0 / 3.0) / (math.pi * (0.25 * C_E) ** (2.0 / 3.0)
                                          * (req1 * req2) ** (1.0 / 3.0))


def preloaded_normal_force(normal_force: float, spring_force: float, d1: float, d2: float,
                           pressure_angle: float) -> float:
    """Seed 001 eq (19)'s load: the tooth normal force plus the anti-rattle spring's share at
    the mesh, (d1 + d2)·|F_ARS|·sin(alpha)/d1 (N): the spring presses the worm into the
    wheel whichever way it deflects."""
    return normal_force + (d1 + d2) * abs(spring_force) * math.sin(pressure_angle) / d1


def friction_power_law(pressure: float, mu_ref: float, pressure_ref: float,
                       exponent: float) -> float:
    """Seed 001 §2.3: steel on polymer, mu = c·p^n (n = -0.9 sliding, -0.6 rolling, after
    Mowafi), with c fixed by a measured point: mu_ref at pressure_ref (the paper's 0.029 at
    130 MPa, §2.4.2)."""
    if not pressure > 0:
        raise ValueError(f"pressure must be > 0 MPa, got {pressure}")
    return mu_ref * (pressure / pressure_ref) ** exponent


def efficiency_kim_preloaded(lead_angle: float, normal_pressure_angle: float, mu: float,
                             normal_force: float, preloaded_force: float) -> float:
    """Seed 001 eq (2) with the friction force of the preloaded contact: the friction mu
    acts on the whole normal force (tooth load plus spring), while only the tooth load
    transmits torque, so the equation sees mu·F_total/F_n. Zero when nothing is
    transmitted or friction locks the mesh."""
    if not normal_force > 0:
        return 0.0
    return max(efficiency_kim(lead_angle, normal_pressure_angle,
                              mu * preloaded_force / normal_force), 0.0)
