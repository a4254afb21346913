"""Tooth root stress from a line load on the flank: ISO 6336-3 Method B's critical section
and factors, taken from the exact generated fillet and applied to the load where it acts.

The critical section (ISO 6336-3:2006, Method B's tooth form factor Y_F): the chord s_Fn
between the points where
tangents inclined 30° to the tooth's centre line (60° on an internal gear) touch the two
root fillets, and the fillet's radius of curvature ρ_F there: here found on the fillet the
basic rack generates (surfaces.generation), not on ISO's closed form of the trochoid. A
load w (N per mm of tooth length) on the flank at radius r, along the flank's normal,
crosses the centre line at h_F above the section at the angle α_Fen from its normal;
the nominal bending stress is 6·w·h_F·cos α_Fen / s_Fn² (Y_F's definition without the
module), times Method B's stress correction factor Y_S = (1.2 + 0.13 L)·
q_s^(1/(1.21 + 2.3/L)), L = s_Fn/h_F, q_s = s_Fn/(2ρ_F), with the actual h_F of the
load's height rather than of the outer point of single pair contact.

A helical gear is taken as ISO takes it: its virtual spur gear in the normal section
(z_n = z/(cos²β_b·cos β), m_n, α_n, the same profile shift and tip height), the load per
unit of tooth length the line load per mm of face times cos β_b, at the radius of the
virtual gear whose distance from its tip along the line of action is the transverse one
over cos β_b, and ISO's helix angle factor Y_β = 1 - ε_β·β/120° (ε_β at most 1, β at most
30°). Units: mm, N, MPa.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..surfaces.generation import generate_side
from ..surfaces.involute import CylindricalGear

#: the inclination (deg) of the tangents to the fillet that fix the critical section
TANGENT_EXTERNAL, TANGENT_INTERNAL = 30.0, 60.0
#: fillet samples the section is found on
FILLET_SAMPLES = 600


@dataclass(frozen=True)
class CriticalSection:
    """ISO 6336-3's critical section of a (virtual spur) gear's tooth: the chord s_Fn
    (mm), the fillet's radius of curvature ρ_F (mm) at its ends and the position x (mm)
    of the chord along the tooth's centre line (from the gear's centre)."""

    s_Fn: float
    rho_F: float
    x: float


def virtual_spur_gear(gear: CylindricalGear) -> CylindricalGear:
    """ISO 6336-3's virtual spur gear of a helical gear (its normal section): z_n =
    z/(cos²β_b cos β) teeth of the normal module and pressure angle, the same profile
    shift, rack and tip height (d_an = d_n + d_a - d); the gear itself if spur."""
    if gear.helix_angle == 0.0:
        return gear
    beta, beta_b = gear.helix_angle, gear.base_helix_angle
    z_n = gear.teeth / (math.cos(beta_b) ** 2 * math.cos(beta))
    d, d_n = 2.0 * gear.pitch_radius, z_n * gear.normal_module
    return CylindricalGear(z_n, gear.normal_module, gear.pressure_angle, gear.face_width,
                           profile_shift=gear.profile_shift, addendum=gear.addendum,
                           dedendum=gear.dedendum, root_radius=gear.root_radius,
                           thinning=gear.thinning * math.cos(beta),
                           tip_diameter=d_n + 2.0 * gear.tip_radius - d)


def critical_section(gear: CylindricalGear) -> CriticalSection:
    """The critical section of an external spur gear's tooth on its generated fillet (the
    tangent at 30° to the centre line, tooth 0 on +x)."""
    if gear.internal:
        raise ValueError("the root stress of an internal gear is not modelled")
    side = generate_side(gear, samples=FILLET_SAMPLES)
    points, normals = side.fillet, side.fillet_normals          # root -> form
    # the tangent's inclination to the centre line (the x axis): 90° at the root circle,
    # falling toward the flank
    inclination = np.degrees(np.arctan2(np.abs(normals[:, 0]), np.abs(normals[:, 1])))
    k = int(np.flatnonzero((inclination[:-1] >= TANGENT_EXTERNAL)
                           & (inclination[1:] < TANGENT_EXTERNAL))[0])
    t = (inclination[k] - TANGENT_EXTERNAL) / (inclination[k] - inclination[k + 1])
    x, y = points[k] + t * (points[k + 1] - points[k])
    # the radius of curvature: arc length over the normal's turn, about the section
    lo, hi = max(k - 3, 0), min(k + 4, len(points) - 1)
    arc = float(np.sum(np.hypot(*np.diff(points[lo:hi + 1], axis=0).T)))
    turn = abs(math.atan2(*normals[hi][::-1]) - math.atan2(*normals[lo][::-1]))
    return CriticalSection(s_Fn=2.0 * float(y), rho_F=arc / turn, x=float(x))


def _involute_point(gear: CylindricalGear, radius: np.ndarray):
    """Points (n, 2) of side +1's involute of tooth 0 at `radius` and the unit normals
    into the tooth there."""
    rb = gear.base_radius
    alpha = np.arccos(rb / radius)
    theta = gear.base_half_angle - (np.tan(alpha) - alpha)
    point = np.column_stack([radius * np.cos(theta), radius * np.sin(theta)])
    # the normal is the generating line, tangent to the base circle at the polar angle
    # theta - alpha (side +1 unwinds clockwise); into the tooth it points toward -y
    direction = np.column_stack([np.sin(theta - alpha), -np.cos(theta - alpha)])
    return point, direction


@dataclass(frozen=True)
class RootStress:
    """The root stress of one member per unit line load at each load radius: σ_F = w ·
    factor(r) · Y_β, w the line load per mm of face (N/mm) along the flank's normal."""

    section: CriticalSection
    radii: np.ndarray           # mm, the real gear's transverse load radii
    factors: np.ndarray         # 1/mm: 6 h_F cos α_Fen Y_S / s_Fn² × cos β_b
    Y_beta: float

    def stress(self, line_load: np.ndarray, radius: np.ndarray) -> np.ndarray:
        """σ_F (MPa) of line loads (N per mm of face) at load radii (mm)."""
        return np.asarray(line_load, float) * np.interp(radius, self.radii,
                                                        self.factors) * self.Y_beta


def stress_correction(s_Fn: float, h_F, rho_F: float):
    """ISO 6336-3 Method B's Y_S = (1.2 + 0.13 L) q_s^(1/(1.21 + 2.3/L))."""
    L = s_Fn / np.asarray(h_F, float)
    q_s = s_Fn / (2.0 * rho_F)
    return (1.2 + 0.13 * L) * q_s ** (1.0 / (1.21 + 2.3 / L))


def helix_factor(gear: CylindricalGear, overlap_ratio: float) -> float:
    """ISO 6336-3's Y_β = 1 - ε_β·β/120°, ε_β taken at most 1, β at most 30°."""
    beta = min(math.degrees(gear.helix_angle), 30.0)
    return 1.0 - min(overlap_ratio, 1.0) * beta / 120.0


def load_arm(virtual: CylindricalGear, section: CriticalSection, roll):
    """(h_F, cos α_F) (mm, -) of a unit load on a spur gear's flank at roll lengths (mm along
    its line of action from the base tangency point), along the flank's normal: the height
    above the critical section at which the load's line crosses the tooth's centre line,
    and the cosine of its angle to the section (ISO 6336-3's h_F and α_F)."""
    point, direction = _involute_point(virtual, np.hypot(virtual.base_radius, roll))
    along = -point[:, 1] / direction[:, 1]
    crossing = point[:, 0] + along * direction[:, 0]
    return crossing - section.x, np.abs(direction[:, 1])


def root_stress(gear: CylindricalGear, form_radius: float, overlap_ratio: float = 0.0,
                points: int = 60) -> RootStress:
    """The member's root stress per unit line load for loads between its form circle
    (mm) and its tip (see the module)."""
    virtual = virtual_spur_gear(gear)
    section = critical_section(virtual)
    radii = np.linspace(form_radius, gear.tip_radius, points)
    cos_beta_b = math.cos(gear.base_helix_angle)
    # the load's distance from the tip along the line of action, in the normal section
    from_tip = (math.sqrt(gear.tip_radius ** 2 - gear.base_radius ** 2)
                - np.sqrt(np.maximum(radii ** 2 - gear.base_radius ** 2, 0.0))) / cos_beta_b
    rb_n = virtual.base_radius
    roll = np.maximum(math.sqrt(virtual.tip_radius ** 2 - rb_n ** 2) - from_tip, 1e-9)
    h_F, cos_alpha = load_arm(virtual, section, roll)
    Y_S = stress_correction(section.s_Fn, h_F, section.rho_F)
    factors = 6.0 * h_F * cos_alpha * Y_S / section.s_Fn ** 2 * cos_beta_b
    return RootStress(section, radii, factors, helix_factor(gear, overlap_ratio))
