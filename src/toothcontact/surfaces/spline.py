"""Involute splines: hub (external) and sleeve (internal) teeth as involute gears.

A spline is an involute gear pair of ratio 1 on a common axis. Its basic proportions follow
ISO 4156-1 (ANSI B92.1 in module form): pitch diameter D = m·z; the major and minor
diameters below, in multiples of m about z. The tooth thickness of the hub (T_mod of seed
003, at the crown centre) and the space width of the sleeve (T_mod + dT) set each member's
profile shift. Units: mm, rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .involute import CylindricalGear

#: (pressure angle in deg, root) -> (hub major, hub minor, sleeve minor, sleeve major) as
#: offsets from z in multiples of m: D = m·(z + offset)  (ISO 4156-1 basic proportions)
PROPORTIONS = {
    (30.0, "flat"): (1.0, -1.5, -1.0, 1.5),
    (30.0, "fillet"): (1.0, -1.8, -1.0, 1.8),
    (37.5, "fillet"): (0.9, -1.4, -0.9, 1.4),
    (45.0, "fillet"): (0.8, -1.2, -0.8, 1.2),
}
#: root radius of a flat root, × m (a small corner radius of the hob tip)
FLAT_ROOT_RADIUS = 0.2


#: the hub tooth's share of the circular pitch a spline is built with (ISO 4156's basic
#: tooth is half; a thickness far from it is a unit slip, not a spline)
THICKNESS_SHARE = (0.3, 0.7)


@dataclass(frozen=True)
class InvoluteSpline:
    """teeth, module (mm), pressure_angle (rad), root "flat" or "fillet", hub tooth thickness
    T_mod and clearance dT (circular, on the pitch circle, mm), engaged length (mm)."""

    teeth: int
    module: float
    pressure_angle: float
    tooth_thickness: float
    clearance: float
    engaged_length: float
    root: str = "fillet"

    def __post_init__(self):
        key = (round(math.degrees(self.pressure_angle), 1), self.root)
        if key not in PROPORTIONS:
            raise ValueError(f"no ISO 4156 proportions for {key[0]} deg with a {self.root} root; "
                             f"known: {sorted(PROPORTIONS)}")
        pitch = math.pi * self.module
        low, high = (f * pitch for f in THICKNESS_SHARE)
        if not low <= self.tooth_thickness <= high:
            raise ValueError(f"tooth_thickness: {self.tooth_thickness:.4g} mm must lie between "
                             f"{low:.4g} and {high:.4g} mm, {THICKNESS_SHARE[0]:g} to "
                             f"{THICKNESS_SHARE[1]:g} of the circular pitch π·m = {pitch:.4g} mm "
                             "(the basic tooth is half of it)")
        if self.clearance < 0 or self.tooth_thickness + self.clearance >= high:
            raise ValueError(f"clearance: {self.clearance:.4g} mm must be >= 0 and leave the "
                             f"sleeve's tooth at least {1 - THICKNESS_SHARE[1]:g} of the "
                             f"circular pitch: below {high - self.tooth_thickness:.4g} mm")

    @property
    def pitch_diameter(self) -> float:
        return self.module * self.teeth

    @property
    def diameters(self) -> dict[str, float]:
        """Hub major/minor and sleeve minor/major diameters (mm)."""
        key = (round(math.degrees(self.pressure_angle), 1), self.root)
        offsets = PROPORTIONS[key]
        names = ("hub_major", "hub_minor", "sleeve_minor", "sleeve_major")
        return {n: self.module * (self.teeth + o) for n, o in zip(names, offsets)}

    def hub(self) -> CylindricalGear:
        """The external member, its tooth T_mod thick on the pitch circle."""
        m, d = self.module, self.diameters
        x = (self.tooth_thickness / m - 0.5 * math.pi) / (2.0 * math.tan(self.pressure_angle))
        dedendum = (self.pitch_diameter - d["hub_minor"]) / (2 * m) + x
        return CylindricalGear(self.teeth, m, self.pressure_angle, self.engaged_length,
                               profile_shift=x,
                               addendum=(d["hub_major"] - self.pitch_diameter) / (2 * m) - x,
                               dedendum=dedendum, root_radius=self._root_radius(dedendum - x))

    def sleeve(self) -> CylindricalGear:
        """The internal member, its space T_mod + dT wide on the pitch circle."""
        m, d = self.module, self.diameters
        thickness = math.pi * m - (self.tooth_thickness + self.clearance)
        x = (0.5 * math.pi - thickness / m) / (2.0 * math.tan(self.pressure_angle))
        return CylindricalGear(self.teeth, m, self.pressure_angle, self.engaged_length,
                               profile_shift=x, internal=True,
                               addendum=(self.pitch_diameter - d["sleeve_minor"]) / (2 * m) + x,
                               dedendum=(d["sleeve_major"] - self.pitch_diameter) / (2 * m) - x)

    def _root_radius(self, depth: float) -> float:
        """Hub root radius coefficient: a small corner for a flat root; for a fillet root 95 %
        of the full radius that fits the generating rack tooth's tip at `depth` (× m)."""
        a = self.pressure_angle
        tip_half_width = 0.25 * math.pi - depth * math.tan(a)
        full = tip_half_width * math.cos(a) / (1.0 - math.sin(a))
        return min(FLAT_ROOT_RADIUS, 0.95 * full) if self.root == "flat" else 0.95 * full
