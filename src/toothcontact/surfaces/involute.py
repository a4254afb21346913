"""Involute spur and helical gears: the gear's basic geometry and its exact flanks.

Frame: gear axis = z, face from z = -b/2 (end A) to z = +b/2 (end B); tooth 0 centred on
the +x axis. Flank side +1 faces increasing polar angle, side -1 decreasing. A flank is the
involute helicoid r(t, z) with t the roll angle (tan of the transverse profile angle).
Units: mm, rad.

Sources: ISO 21771:2007 (cylindrical involute gears: mt = mn/cos beta, tan alpha_t =
tan alpha_n / cos beta, tan beta_b = tan beta·cos alpha_t, transverse tooth thickness
s_t = m_t(π/2 + 2·x·tan alpha_n)); Litvin & Fuentes, Gear Geometry and Applied Theory,
2nd ed. 2004, §10.2 (involute curve) and §14.3 (involute helicoid).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from .base import Flank
from .jet import cos_sin


def inv(alpha: float) -> float:
    """Involute function tan(alpha) - alpha."""
    return math.tan(alpha) - alpha


@dataclass(frozen=True)
class CylindricalGear:
    """Basic data of an involute cylindrical gear (ISO 21771 conventions).

    teeth: |z|; internal: an internal (ring) gear; normal_module, pressure_angle (normal, rad),
    helix_angle (rad, 0 = spur), hand "right"/"left", profile_shift x (for an internal gear
    positive x moves the profile away from the axis, thinning the tooth), addendum,
    dedendum and root_radius coefficients of the basic rack (× m_n), face_width (mm),
    thinning: the transverse tooth-thickness allowance on the reference circle (arc mm, taken
    off both flanks alike; the gear's share of a pair's backlash), tip_diameter: the tip
    circle's diameter d_a as drawn (mm; a ring's inner diameter), or None for the rack's:
    d ± 2·(h_a ∓ x)·m_n."""

    teeth: int
    normal_module: float
    pressure_angle: float
    face_width: float
    helix_angle: float = 0.0
    hand: str = "right"
    profile_shift: float = 0.0
    addendum: float = 1.0
    dedendum: float = 1.25
    root_radius: float = 0.38
    internal: bool = False
    thinning: float = 0.0
    tip_diameter: float | None = None

    def __post_init__(self):
        problems = []
        if self.teeth < 3:
            problems.append(f"teeth {self.teeth} must be at least 3")
        if not self.normal_module > 0:
            problems.append(f"module {self.normal_module} must be > 0")
        if not 0 < self.pressure_angle <= math.radians(45) * (1 + 1e-12):   # 45°: splines
            problems.append("pressure angle must lie in (0, 45] deg")
        if not 0 <= self.helix_angle < math.radians(60):
            problems.append("helix angle must lie in [0, 60) deg")
        if self.hand not in ("right", "left"):
            problems.append(f"hand {self.hand!r} must be 'right' or 'left'")
        if not self.face_width > 0:
            problems.append(f"face width {self.face_width} must be > 0")
        if not 0 <= self.root_radius < self.dedendum:
            problems.append("root radius coefficient must lie in [0, dedendum)")
        if not self.thinning >= 0:
            problems.append(f"thinning {self.thinning} must be >= 0")
        if self.tip_diameter is not None and not (math.isfinite(self.tip_diameter)
                                                  and self.tip_diameter > 0):
            problems.append(f"tip diameter {self.tip_diameter} must be > 0")
        if problems:
            raise ValueError("; ".join(problems))

    # --- transverse data ---------------------------------------------------------------
    @property
    def transverse_module(self) -> float:
        return self.normal_module / math.cos(self.helix_angle)

    @property
    def transverse_pressure_angle(self) -> float:
        return math.atan(math.tan(self.pressure_angle) / math.cos(self.helix_angle))

    @property
    def pitch_radius(self) -> float:
        return 0.5 * self.teeth * self.transverse_module

    @property
    def base_radius(self) -> float:
        return self.pitch_radius * math.cos(self.transverse_pressure_angle)

    @property
    def base_helix_angle(self) -> float:
        return math.atan(math.tan(self.helix_angle) * math.cos(self.transverse_pressure_angle))

    @property
    def hand_sign(self) -> float:
        return 1.0 if self.hand == "right" else -1.0

    @property
    def twist_per_length(self) -> float:
        """Rotation of the transverse section per mm along z (rad/mm): tan(beta)/r."""
        return self.hand_sign * math.tan(self.helix_angle) / self.pitch_radius

    @property
    def base_pitch(self) -> float:
        """Transverse base pitch 2π·rb/z (mm)."""
        return 2.0 * math.pi * self.base_radius / self.teeth

    @property
    def tooth_thickness(self) -> float:
        """Transverse tooth thickness on the reference circle (arc, mm), less the thinning."""
        sign = -1.0 if self.internal else 1.0
        return self.transverse_module * (0.5 * math.pi
                                         + 2.0 * sign * self.profile_shift * math.tan(self.pressure_angle)
                                         ) - self.thinning

    @property
    def tip_radius(self) -> float:
        """Radius of the tip circle (mm): half the given tip_diameter, else from the rack's
        addendum and the profile shift, r ± (h_a ∓ x)·m_n (a ring's: its inner radius)."""
        if self.tip_diameter is not None:
            return 0.5 * self.tip_diameter
        m, x = self.normal_module, self.profile_shift
        if self.internal:
            return self.pitch_radius - (self.addendum - x) * m
        return self.pitch_radius + (self.addendum + x) * m

    @property
    def root_radius_value(self) -> float:
        """Radius of the root circle (mm): inside the teeth, or outside them for a ring."""
        m, x = self.normal_module, self.profile_shift
        if self.internal:
            return self.pitch_radius + (self.dedendum + x) * m
        return self.pitch_radius - (self.dedendum - x) * m

    @property
    def base_half_angle(self) -> float:
        """psi_b: polar half-angle of the tooth where its flanks leave the base circle
        (rad). External: s/(2r) + inv(alpha_t), and the flank's polar angle is
        psi_b - inv(alpha). Internal: the flank's polar angle is psi_b + inv(alpha), with
        psi_b = s/(2r) - inv(alpha_t)."""
        half = self.tooth_thickness / (2.0 * self.pitch_radius)
        return half - inv(self.transverse_pressure_angle) if self.internal else \
            half + inv(self.transverse_pressure_angle)

    def roll_angle(self, radius):
        """Roll angle t = sqrt(r²/rb² - 1) of the involute point at `radius`."""
        return np.sqrt(np.asarray(radius, float) ** 2 / self.base_radius**2 - 1.0)

    def flank(self, side: int, form_radius: float | None = None) -> InvoluteFlank:
        """The exact flank of tooth 0 on `side` (+1 or -1), from the form radius (default
        the base circle, or the root for a ring) to the tip."""
        return InvoluteFlank(self, side, form_radius)


class InvoluteFlank(Flank):
    """Involute helicoid: u = roll angle t, v = axial position z (mm from mid-face).

    point = Rot(twist·z) · rb·(cos(psi - t) - t·sin(psi - t), s·(sin(psi - t) + t·cos(psi - t)))
    with s = side for an external gear (mirror for side -1) and psi = psi_b; an internal
    gear's flank is the mirror image with psi = -psi_b (its tooth widens outward)."""

    straight_contact_lines = True

    def __init__(self, gear: CylindricalGear, side: int, form_radius: float | None = None):
        if side not in (1, -1):
            raise ValueError("side must be +1 or -1")
        self.gear, self.side = gear, side
        rb = gear.base_radius
        inner, outer = sorted((gear.tip_radius,
                               form_radius or (gear.root_radius_value if gear.internal else rb)))
        inner = max(inner, rb)
        if outer <= inner:
            raise ValueError(f"the tip radius {gear.tip_radius:.4g} mm does not clear the base "
                             f"circle {rb:.4g} mm: no involute flank")
        self.domain = ((float(gear.roll_angle(inner)), float(gear.roll_angle(outer))),
                       (-0.5 * gear.face_width, 0.5 * gear.face_width))
        if gear.internal:
            self.edges = {"u0": "tip", "u1": "root", "v0": "end_A", "v1": "end_B"}
        else:
            self.edges = {"u0": "form", "u1": "tip", "v0": "end_A", "v1": "end_B"}
        self._mirror = -side if gear.internal else side
        self._psi = -gear.base_half_angle if gear.internal else gear.base_half_angle
        self.orientation = self._orientation()

    def point(self, u, v):
        return self.point_and_normal(u, v)[0]

    def unit_normal(self, u, v):
        """Closed-form unit normal out of the material (jet-friendly)."""
        return self.point_and_normal(u, v)[1]

    def point_and_normal(self, u, v):
        """The point and its unit normal out of the material, sharing their trigonometry:
        n = orientation·(Rot(twist·z)·(m·sin(a), -cos(a)), twist·rb) / sqrt(1 + (twist·rb)²),
        a = psi - t, m the mirror sign; |twist·rb| = tan(beta_b)."""
        rb, m = self.gear.base_radius, self._mirror
        cos_a, sin_a = cos_sin(self._psi - u)
        x = rb * (cos_a - u * sin_a)
        y = m * rb * (sin_a + u * cos_a)
        k = self.gear.twist_per_length * rb
        scale = self.orientation / math.sqrt(1.0 + k * k)
        nx, ny = scale * m * sin_a, -scale * cos_a
        z, nz = v + 0.0 * u, scale * k + 0.0 * u
        if self.gear.twist_per_length == 0.0:
            return (x, y, z), (nx, ny, nz)
        c, s = cos_sin(self.gear.twist_per_length * v)
        return (x * c - y * s, x * s + y * c, z), (nx * c - ny * s, nx * s + ny * c, nz)

    @property
    def tip_roll(self) -> float:
        """Roll length rb·t at the tip circle (mm)."""
        return float(self.gear.base_radius * self.gear.roll_angle(self.gear.tip_radius))

    @property
    def form_roll(self) -> float:
        """Roll length rb·t at the other end of the active flank (form or root circle, mm)."""
        (u0, u1), _ = self.domain
        return self.gear.base_radius * (u1 if self.gear.internal else u0)

    def parameters_near(self, points):
        """Starting parameters (u, v) for points near the flank (own frame): the roll angle
        of their radius (at least 0.05) and their z."""
        r = np.hypot(points[..., 0], points[..., 1])
        t = np.sqrt(np.maximum(r * r / self.gear.base_radius**2 - 1.0, 0.0))
        # never start at the involute's cusp on the base circle (t = 0), where r_u vanishes
        return np.maximum(t, 0.05), points[..., 2].copy()

    def transverse_point(self, t):
        """The flank's transverse profile at z = 0: arrays x, y (mm) at roll angles t."""
        x, y, _ = self.point(np.asarray(t, float), 0.0)
        return x, y

    def _orientation(self) -> float:
        """+1 or -1 so that the normal leaves the material. The tooth's material lies between
        its two flanks (for a ring gear too), so the normal points away from tooth 0's centre
        line: toward increasing polar angle on side +1."""
        (u0, u1), _ = self.domain
        s = self.evaluate(np.array([0.5 * (u0 + u1)]), np.array([0.0]))
        p, n = s.points[0], np.cross(s.r_u[0], s.r_v[0])
        angular = np.array([-p[1], p[0], 0.0])  # direction of increasing polar angle
        return float(np.sign(np.dot(n, angular)) * self.side)

    @cached_property
    def form_radius(self) -> float:
        return float(self.gear.base_radius * math.sqrt(1 + self.domain[0][0] ** 2))
