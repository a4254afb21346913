"""Lead-crown design of a spur pair against misalignment (Wang & El-Bayoumy, seed 003).

The crown is a circular arc of radius R along the face, centred a distance c from end B.
Under a total slope theta (misalignment plus deflection) the contact moves R·theta from the
crown centre, and its ellipse must stay inside the face: R·theta + a <= L (eq 13), a being
the contact semi-axis along the face. A full crown is centred mid-face; an off-centre crown
(seed 003's "bias" crown) is placed so that both ends reach their limit together:
    R·theta_A + a = F - c,   R·theta_B + a = c   =>   R·(theta_A + theta_B) + 2a = F.
Units: mm, N, MPa, rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .hertz import PointContact, relative_curvature, roark_point, semi_axis_along


def radius_from_drop(drop: float, length: float) -> float:
    """Seed 003 eq (12): R² = (R - drop)² + L²  =>  R = (drop² + L²) / (2·drop) (mm)."""
    if not (drop > 0 and length > 0):
        raise ValueError(f"drop and length must be > 0, got {drop}, {length}")
    return (drop**2 + length**2) / (2.0 * drop)


def drop_from_radius(radius: float, length: float) -> float:
    """Inverse of seed 003 eq (12): drop = R - sqrt(R² - L²) over a distance L from the
    crown centre (mm)."""
    if abs(length) > radius:
        raise ValueError(f"a crown of radius {radius:.4g} mm cannot span {length:.4g} mm")
    if math.isinf(radius):
        return 0.0
    # L²/(R + sqrt(R² - L²)), written without R² (no cancellation, no overflow)
    ratio = length / radius
    return length * ratio / (1.0 + math.sqrt((1.0 - ratio) * (1.0 + ratio)))


def normal_load(tangential_load: float, pressure_angle: float) -> float:
    """Seed 003 eq (7): P = Wt / cos(phi_op) (N)."""
    return tangential_load / math.cos(pressure_angle)


@dataclass(frozen=True)
class CrownedContact:
    """The crowned contact: Hertz ellipse and its semi-axis along the face (mm)."""

    ellipse: PointContact
    semi_axis_face: float


def crowned_contact(crown_radius: float, profile_curvature: float, load: float,
                    C_E: float, mating_crown_radius: float = math.inf) -> CrownedContact:
    """Hertz contact of a crowned pinion on its mate (seed 003 eqs (6)-(11)).

    profile_curvature: 1/rho1 ± 1/rho2 (1/mm, + external, - internal); crown radii in mm.
    Principal planes of both bodies coincide (lead and profile directions)."""
    lead = 1.0 / crown_radius + (0.0 if math.isinf(mating_crown_radius) else 1.0 / mating_crown_radius)
    rc = relative_curvature((lead, profile_curvature), (0.0, 0.0))
    total = 2.0 * (rc.A + rc.B)
    ellipse = roark_point(total, 2.0 * (rc.B - rc.A), load, C_E)
    return CrownedContact(ellipse, semi_axis_along(ellipse, rc, 0.0))


@dataclass(frozen=True)
class Crown:
    """A crown and how its contact sits on the face under the two limiting slopes."""

    radius: float
    center_from_B: float
    face_width: float
    slope_A: float
    slope_B: float
    contact: CrownedContact

    @property
    def drop_A(self) -> float:
        return drop_from_radius(self.radius, self.face_width - self.center_from_B)

    @property
    def drop_B(self) -> float:
        return drop_from_radius(self.radius, self.center_from_B)

    @property
    def edge_margin_A(self) -> float:
        """Seed 003 eq (13) at end A: (F - c) - (R·theta_A + a) (mm); negative = edge loading."""
        return self.face_width - self.center_from_B - (self.radius * self.slope_A
                                                       + self.contact.semi_axis_face)

    @property
    def edge_margin_B(self) -> float:
        """Seed 003 eq (13) at end B: c - (R·theta_B + a) (mm); negative = edge loading."""
        return self.center_from_B - (self.radius * self.slope_B + self.contact.semi_axis_face)


class CrownDesignError(ValueError):
    """A crown that cannot be designed, and the input fields that cause it."""

    def __init__(self, fields: str, message: str):
        super().__init__(message)
        self.fields = fields


def design_crown(face_width: float, slope_A: float, slope_B: float, profile_curvature: float,
                 load: float, C_E: float, edge_clearance: float = 0.0) -> Crown:
    """The largest crown radius that keeps the ellipse `edge_clearance` inside both face ends.

    Solves R·(theta_A + theta_B) + 2·a(R) + 2·clearance = F for R (a from Hertz), then
    c = R·theta_B + a + clearance. A full crown is the case theta_B = theta_A (c = F/2)."""
    from scipy.optimize import brentq

    usable = face_width - 2.0 * edge_clearance
    if usable <= 0:
        raise CrownDesignError("edge_clearance / face_width",
                               f"an edge clearance of {edge_clearance:.4g} mm leaves nothing "
                               f"of the {face_width:.4g} mm face")

    def spread(log_R: float) -> float:
        R = math.exp(log_R)
        return R * (slope_A + slope_B) + 2.0 * crowned_contact(
            R, profile_curvature, load, C_E).semi_axis_face - usable

    lo, hi = math.log(1e-3 * face_width), math.log(10.0 * face_width)
    if spread(lo) >= 0:
        raise CrownDesignError("tangential_load / face_width / material",
                               f"the load spreads the contact over the whole {face_width:.4g} "
                               "mm face even with a very small crown radius: the face is too "
                               "narrow for the load (or the material too soft)")
    while spread(hi) < 0:
        hi += math.log(10.0)
        if hi > math.log(1e12):
            raise CrownDesignError("slope_A / slope_B",
                                   "the slopes are too small for any crown radius below "
                                   "1e12 mm to bring the contact to the face ends: no crown "
                                   "is needed")
    R = math.exp(brentq(spread, lo, hi, xtol=1e-12, rtol=1e-13))
    contact = crowned_contact(R, profile_curvature, load, C_E)
    center = R * slope_B + contact.semi_axis_face + edge_clearance
    return Crown(R, center, face_width, slope_A, slope_B, contact)


def check_crown(radius: float, center_from_B: float, face_width: float, slope_A: float,
                slope_B: float, profile_curvature: float, load: float, C_E: float) -> Crown:
    """An existing crown of `radius` centred `center_from_B`: its contact and edge margins."""
    contact = crowned_contact(radius, profile_curvature, load, C_E)
    return Crown(radius, center_from_B, face_width, slope_A, slope_B, contact)


@dataclass(frozen=True)
class DesignChart:
    """Seed 003's two rules over a range of slopes (the crown design chart): per slope
    `theta` (rad) and face end ("A"; "B" too for an off-centre crown) the edge rule's largest
    radius (mm, NaN where no crown fits), the stress rule's least radius (mm, NaN where no
    crown gets under the reference), the reference stress (MPa) and whether it is the
    case's allowable ("allowable") or the chosen design's own ("design")."""

    theta: np.ndarray
    edge_radius: dict
    stress_radius: float
    reference_stress: float
    reference: str
    design_stress: float


def design_chart(design: Crown, full: bool, profile_curvature: float, load: float, C_E: float,
                 edge_clearance: float = 0.0, allowable: float | None = None,
                 points: int = 80) -> DesignChart:
    """The chart of a chosen crown (`design`, from design_crown or check_crown).

    Edge rule (eq 13): for each slope theta up to 2.5 times the larger design slope, the
    largest radius whose ellipse stays inside the room on that side of the crown's centre
    (F - c toward end A, c toward end B, less the edge clearance): design_crown of a face
    twice that room with slope theta at both ends. Stress rule: the least radius whose
    crowned Hertz stress (crowned_contact, eqs 6-11) is at most the allowable, or the
    chosen design's stress where none is given; in this model the stress does not depend
    on theta, so that rule is one radius."""
    from scipy.optimize import brentq

    F, c = design.face_width, design.center_from_B
    rooms = {"A": F - c} if full else {"A": F - c, "B": c}
    theta = np.linspace(0.0, 2.5 * max(design.slope_A, design.slope_B), points + 1)
    edge = {}
    for end, room in rooms.items():
        radii = []
        for t in theta:
            try:
                radii.append(design_crown(2.0 * room, t, t, profile_curvature, load, C_E,
                                          edge_clearance).radius)
            except ValueError:
                radii.append(math.nan)
        edge[end] = np.array(radii)

    def stress(radius: float) -> float:
        return crowned_contact(radius, profile_curvature, load, C_E).ellipse.p0

    design_stress = stress(design.radius)
    if allowable is None:
        return DesignChart(theta, edge, design.radius, design_stress, "design", design_stress)
    lo, hi = math.log(1e-3 * F), math.log(1e6 * F)
    if stress(math.exp(lo)) <= allowable:
        least = math.exp(lo)
    elif stress(math.exp(hi)) > allowable:
        least = math.nan             # no crown this flat gets under the allowable
    else:
        least = math.exp(brentq(lambda s: stress(math.exp(s)) - allowable, lo, hi, xtol=1e-10))
    return DesignChart(theta, edge, least, allowable, "allowable", design_stress)
