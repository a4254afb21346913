"""Transverse geometry of a spur mesh along its line of action (external or internal).

Distances are measured along the line of action from the pinion's base-circle tangency
point T1, so a point at distance s has pinion profile radius of curvature s. Units: mm, rad.

Source: AGMA 908-B89, the line-of-action distances C1..C6 used for the geometry factor I
(C1 start of active profile on the pinion, C2 = C5 - pb the pinion's lowest point of single
tooth contact (LPSTC), C4 = C1 + pb its highest (HPSTC), C5 the pinion tip, C6 = C·sin phi),
and seed 003 eqs (1)-(2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class SpurMesh:
    """A spur pair: pinion teeth z1 > 0, gear teeth z2 (negative = internal gear).

    module (mm), operating pressure angle (rad), centre distance (mm, operating), outside
    radii (mm; for an internal gear its tip radius is the inside radius)."""

    z1: int
    z2: int
    module: float
    pressure_angle: float
    center_distance: float
    outside_radius_pinion: float
    outside_radius_gear: float

    @property
    def internal(self) -> bool:
        return self.z2 < 0

    @property
    def base_radius_pinion(self) -> float:
        return 0.5 * self.module * self.z1 * math.cos(self.generating_pressure_angle)

    @property
    def base_radius_gear(self) -> float:
        return 0.5 * self.module * abs(self.z2) * math.cos(self.generating_pressure_angle)

    @property
    def generating_pressure_angle(self) -> float:
        """Reference pressure angle implied by the operating one and the centre distance."""
        standard = 0.5 * self.module * abs(self.z2 + self.z1 if not self.internal
                                           else abs(self.z2) - self.z1)
        return math.acos(min(1.0, self.center_distance * math.cos(self.pressure_angle) / standard))

    @property
    def base_pitch(self) -> float:
        """pb = 2π·rb1/z1 (mm)."""
        return 2.0 * math.pi * self.base_radius_pinion / self.z1

    @property
    def operating_pitch_diameter(self) -> float:
        """d = 2·C/(u ± 1), u = |z2|/z1 (mm)."""
        u = abs(self.z2) / self.z1
        return 2.0 * self.center_distance / (u - 1.0 if self.internal else u + 1.0)

    @property
    def line_of_action_length(self) -> float:
        """C6 = C·sin(phi_op): distance between the two tangency points T1, T2 (mm)."""
        return self.center_distance * math.sin(self.pressure_angle)

    @property
    def start_of_contact(self) -> float:
        """C1: where the gear tip meets the pinion flank (mm from T1)."""
        gear_tip = math.sqrt(self.outside_radius_gear**2 - self.base_radius_gear**2)
        C6 = self.line_of_action_length
        return gear_tip - C6 if self.internal else C6 - gear_tip

    @property
    def end_of_contact(self) -> float:
        """C5: the pinion tip, sqrt(Ro1² - Rb1²) (mm from T1)."""
        return math.sqrt(self.outside_radius_pinion**2 - self.base_radius_pinion**2)

    @property
    def contact_ratio(self) -> float:
        return (self.end_of_contact - self.start_of_contact) / self.base_pitch

    def gear_radius_of_curvature(self, s: float) -> float:
        """Seed 003 eq (2): rho2 = C·sin(phi) ∓ rho1 (external -, internal +), with rho1 = s;
        positive for the convex external gear, and reported positive (concave) for an
        internal one."""
        C6 = self.line_of_action_length
        return s + C6 if self.internal else C6 - s

    def lpstc(self) -> float:
        """Seed 003 eq (1): pinion profile radius of curvature at its lowest point of single
        tooth contact, rho1 = sqrt(Ro1² - Rb1²) - 2π·Rb1/N1 (AGMA 908 C2 = C5 - pb, mm).

        While this pair is in single contact the pair ahead has left the pinion tip (C5), so
        the single-tooth zone runs from C5 - pb up to C1 + pb (the HPSTC)."""
        return self.end_of_contact - self.base_pitch

    def hpstc(self) -> float:
        """Pinion profile radius of curvature at its highest point of single tooth contact,
        C1 + pb (AGMA 908 C4, mm)."""
        return self.start_of_contact + self.base_pitch

    def check(self) -> None:
        """Raise ValueError naming what is wrong when the pair cannot mesh as described."""
        if self.outside_radius_pinion <= self.base_radius_pinion:
            raise ValueError(f"pinion outside radius {self.outside_radius_pinion:.4g} mm must "
                             f"exceed its base radius {self.base_radius_pinion:.4g} mm")
        if self.start_of_contact < 0.0:
            raise ValueError("the gear tip reaches below the pinion base circle (interference): "
                             f"start of contact at {self.start_of_contact:.4g} mm from T1")
        if self.contact_ratio < 1.0:
            raise ValueError(f"transverse contact ratio {self.contact_ratio:.3f} is below 1: "
                             "the pair cannot carry load continuously")
