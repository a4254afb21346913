"""Flank modifications and deflections as normal displacements (docs/DESIGN.md principle 2).

Each modification is a drop (material removed, mm) as a function of the face position w
(mm from mid-face, positive toward end B) and the roll length s = rb·t (mm along the
transverse line of action). Amounts are measured along the flank normal in the transverse
plane, the ISO 21771 convention; on a helical flank the normal displacement is the
transverse amount times cos(beta_b). Functions use numpy only, so they run on jets and the
curvature change of a modification is exactly its second derivative.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from .jet import Jet, value, where

SHAPES = ("circular", "parabolic")


def arc_drop(offset, radius: float, shape: str):
    """Drop of a crown of `radius` at `offset` from its centre: circular R - sqrt(R² - d²),
    evaluated as d²/(R + sqrt((R - d)(R + d))) (no cancellation for a large R), parabolic
    d²/(2R); both have curvature 1/R at the centre."""
    if shape == "circular":
        return offset * offset / (radius + np.sqrt((radius - offset) * (radius + offset)))
    return offset * offset / (2.0 * radius)


def crown_radius_from_height(height: float, half_length: float, shape: str) -> float:
    """Radius of a crown that drops `height` over `half_length` from its centre:
    circular (seed 003 eq 12) R = (h² + L²)/(2h), parabolic R = L²/(2h) (mm)."""
    if not (height > 0 and half_length > 0):
        raise ValueError("crown height and half length must be > 0")
    if shape == "circular":
        return (height**2 + half_length**2) / (2.0 * height)
    return half_length**2 / (2.0 * height)


@dataclass(frozen=True)
class LeadCrown:
    """Lead crowning: a crown along the face centred `center` mm from mid-face toward end B
    (non-zero = an off-centre crown), given by radius or by height (the drop at the face
    ends of the same crown centred mid-face)."""

    radius: float | None = None
    height: float | None = None
    shape: str = "circular"
    center: float = 0.0

    def radius_for(self, face_width: float) -> float:
        if (self.radius is None) == (self.height is None):
            raise ValueError("lead crown: give exactly one of radius and height")
        if self.shape not in SHAPES:
            raise ValueError(f"lead crown shape {self.shape!r} must be one of {SHAPES}")
        if self.radius is not None:
            if not self.radius > 0.5 * face_width:
                raise ValueError("lead crown radius must exceed half the face width")
            return self.radius
        return crown_radius_from_height(self.height, 0.5 * face_width, self.shape)

    def drop(self, w, face_width: float):
        return arc_drop(w - self.center, self.radius_for(face_width), self.shape)


@dataclass(frozen=True)
class ProfileCrown:
    """Profile crowning: drop `height` at both ends of the active profile, centred mid-profile."""

    height: float
    shape: str = "parabolic"

    def drop(self, s, s_start: float, s_end: float):
        half = 0.5 * abs(s_end - s_start)
        return arc_drop(s - 0.5 * (s_start + s_end),
                         crown_radius_from_height(self.height, half, self.shape), self.shape)


#: a linear relief's start is blended over this share of its length by default (a
#: ground relief's transition; a kink would make the loaded pressure there singular)
RELIEF_BLEND = 0.2


def relief_ramp(x, shape: str, blend: float = 0.0):
    """A relief's drop over its amount at x, the distance from its start over its length
    (0 before the start, 1 at its end): linear x or parabolic x², none before the start. A
    linear ramp's start is blended over `blend` of the length, centred on the start: the
    parabola (x + h)²/(4h), h = blend/2, joins none and the line with their slopes (C1), so
    the drop at the relief's end is the amount as given. Jet-friendly."""
    if shape != "linear":
        return where(value(x) > 0, x * x, 0.0 * x)
    h = 0.5 * min(blend, 1.0)
    if h <= 0.0:
        return where(value(x) > 0, x, 0.0 * x)
    return where(value(x) >= h, x,
                 where(value(x) > -h, (x + h) * (x + h) / (4.0 * h), 0.0 * x))


@dataclass(frozen=True)
class TipRelief:
    """Tip relief of `amount` at the tip, starting at roll length `start` (mm) and growing
    linearly or parabolically toward the tip, a linear one's start blended over `blend` of
    its length (relief_ramp)."""

    amount: float
    start: float
    shape: str = "linear"
    blend: float = RELIEF_BLEND

    def drop(self, s, s_tip: float):
        length = s_tip - self.start
        if abs(length) < 1e-12:
            raise ValueError("tip relief starts at the tip")
        x = (s - self.start) / length
        return self.amount * relief_ramp(x, self.shape, self.blend)


@dataclass(frozen=True)
class RootRelief:
    """Root relief of `amount` at the form circle (the active profile's root end), starting
    at roll length `start` (mm) and growing linearly or parabolically toward the form
    circle, a linear one's start blended over `blend` of its length: the tip relief's
    counterpart."""

    amount: float
    start: float
    shape: str = "linear"
    blend: float = RELIEF_BLEND

    def drop(self, s, s_form: float):
        length = self.start - s_form
        if abs(length) < 1e-12:
            raise ValueError("root relief starts at the form circle")
        x = (self.start - s) / length
        return self.amount * relief_ramp(x, self.shape, self.blend)


@dataclass(frozen=True)
class HelixSlope:
    """Helix slope modification f_Hβ (ISO 21771, ISO 1328-1): `amount` (mm, transverse) of
    material removed at end B relative to end A, linear along the face and none at
    mid-face; negative removes it at end A. A slope of f_Hβ/b turns the lead as a
    misalignment of that slope does, the other way."""

    amount: float

    def drop(self, w, face_width: float):
        return self.amount * w / face_width


@dataclass(frozen=True)
class ProfileSlope:
    """Profile slope modification f_Hα (ISO 21771, ISO 1328-1): `amount` (mm, transverse)
    of material removed at the tip relative to the form circle, linear in the roll length
    between them and none mid-profile; negative removes it toward the root."""

    amount: float

    def drop(self, s, s_form: float, s_tip: float):
        return self.amount * (s - 0.5 * (s_form + s_tip)) / (s_tip - s_form)


@dataclass(frozen=True)
class Twist:
    """Flank twist (ISO 21771's profile twist, the "bias" of grinding): the profile slope
    (material removed at the tip relative to the form circle, mm) grows linearly along the
    face by `amount` from end A to end B: -amount/2 at end A, +amount/2 at end B, none at
    mid-face. Its drop is a saddle, amount·(w/b)·(s - s_mid)/(s_tip - s_form)."""

    amount: float

    def drop(self, w, s, face_width: float, s_form: float, s_tip: float):
        return (self.amount * (w / face_width) * (s - 0.5 * (s_form + s_tip))
                / (s_tip - s_form))


class Topography:
    """A grid of normal deviations over the flank (a measured or ordered topography): at face
    positions `face` (mm from mid-face toward end B, increasing) and roll lengths `roll`
    (mm, increasing: the grid's diameters on this flank), `deviation` (mm, one row per face
    position, positive removing material like a relief), interpolated by a tensor-product
    cubic spline (not-a-knot along each axis: C2 inside the grid, exact for a quadratic or
    cubic crown; two points give a line, three a parabola) and held at its edge value
    beyond the grid. Jet-friendly: the patch's polynomial is evaluated on the jet, so the
    surface's derivatives and curvatures are the spline's."""

    def __init__(self, face, roll, deviation):
        from scipy.interpolate import CubicSpline

        self.face = np.asarray(face, float)
        self.roll = np.asarray(roll, float)
        self.deviation = np.asarray(deviation, float)
        along = CubicSpline(self.face, self.deviation, axis=0).c     # (4, nf - 1, ns)
        # each power's coefficient along the face, splined across the profile
        self._c = np.stack([CubicSpline(self.roll, along[k], axis=1).c for k in range(4)])
        # (4 face powers, 4 roll powers, ns - 1, nf - 1)

    def drop(self, w, s):
        def held(x, nodes):
            x = where(value(x) < nodes[0], 0.0 * x + nodes[0], x)
            return where(value(x) > nodes[-1], 0.0 * x + nodes[-1], x)

        w, s = held(w, self.face), held(s, self.roll)
        i = np.clip(np.searchsorted(self.face, value(w), side="right") - 1, 0,
                    len(self.face) - 2)
        j = np.clip(np.searchsorted(self.roll, value(s), side="right") - 1, 0,
                    len(self.roll) - 2)
        dw, ds = w - self.face[i], s - self.roll[j]
        total = 0.0 * dw * ds
        for k in range(4):
            row = 0.0 * ds
            for m in range(4):
                row = row * ds + self._c[k, m, j, i]
            total = total * dw + row
        return total


def k_chart_grid(profile_face, profile_roll, profile, lead_roll, lead_face, lead):
    """A K-chart (profile traces at face positions, lead traces at roll lengths) as a
    topography grid over lead_face × profile_roll: Gordon's transfinite interpolation
    (W. J. Gordon, SIAM J. Numer. Anal. 8 (1971) 158-177, the Boolean sum of the two
    families' blends) with cubic-spline cardinal functions, so that the surface passes
    through every trace. `profile` holds one row per profile trace (at `profile_face`) over
    `profile_roll`, `lead` one row per lead trace (at `lead_roll`) over `lead_face`. Where
    the traces cross, each family gives a value; the two may differ by a measurement's
    scatter: the surface takes their mean there. Returns the grid and the largest
    difference at a crossing (same unit as the traces)."""
    from scipy.interpolate import CubicSpline

    profile_face, profile_roll = np.asarray(profile_face, float), np.asarray(profile_roll, float)
    lead_roll, lead_face = np.asarray(lead_roll, float), np.asarray(lead_face, float)
    profile, lead = np.asarray(profile, float), np.asarray(lead, float)

    def cardinal(nodes, at):
        """The cardinal functions of the nodes (each 1 at its node, 0 at the others) at `at`:
        (len(at), len(nodes)); one node: 1 everywhere."""
        if len(nodes) == 1:
            return np.ones((len(at), 1))
        return CubicSpline(nodes, np.eye(len(nodes)))(at)

    def along(nodes, rows, at):
        return CubicSpline(nodes, rows, axis=1)(at)    # each trace at the points `at`

    profiles = along(profile_roll, profile, profile_roll)          # (np, nr)
    leads = along(lead_face, lead, lead_face)                      # (nl, nf)
    by_profile = along(profile_roll, profile, lead_roll)           # (np, nl): P_i(s_j)
    by_lead = along(lead_face, lead, profile_face)                 # (nl, np): L_j(w_i)
    crossing = 0.5 * (by_profile + by_lead.T)
    phi = cardinal(profile_face, lead_face)                        # (nf, np)
    psi = cardinal(lead_roll, profile_roll)                        # (nr, nl)
    grid = phi @ profiles + (psi @ leads).T - phi @ crossing @ psi.T
    return grid, float(np.max(np.abs(by_profile - by_lead.T)))


def broken_edge_drop(run, radius: float, angle: float, bend: float = 0.0):
    """The drop (mm) of an edge broken by a chamfer at `angle` (rad) to the surface, its
    start rounded by `radius` (mm, the curvature the drop adds), at `run` (mm, >= 0) past
    where the rounding starts: the circle until its slope reaches tan(angle), then the
    straight chamfer, plus bend·run²/2 from there on (a curved surface's own curvature taken
    back, so that the chamfer is straight in space). C1, exact for jets."""
    turn_run = radius * math.sin(angle)
    on_circle = value(run) < turn_run
    circle = arc_drop(where(on_circle, run, 0.0 * run + turn_run), radius, "circular")
    past = where(on_circle, 0.0 * run, run - turn_run)
    return circle + math.tan(angle) * past + 0.5 * bend * past * past


@dataclass(frozen=True)
class TipEdge:
    """The tip edge broken by a rounding of `radius` (mm) tangent to the flank and to the tip
    circle, or, with a chamfer `angle` (rad, to the flank), by a chamfer whose edge on the
    flank is rounded by `radius`; as the drop it cuts from the involute run on to the tip.

    On an involute of base radius r_b the arc length from the base circle is s²/(2·r_b)
    (s = r_b·t the roll length), and the flank meets the tip circle turning by
    θ = 90° - α_a (α_a the pressure angle at the tip: the flank leans α_a off the radius,
    the tip land is square to it). A rounding tangent to both starts ρ·tan(θ/2) before the
    corner along the flank and departs from the flank's tangent there as a circle; its
    curvature relative to the involute's (1/s at roll length s, convex on an external
    gear, concave on a ring's) is what the drop adds, so that the flank's own curvature
    across the rounding is 1/ρ. The drop is taken along the flank normal (the rounding's
    departure at its start is second order: the contact, a few micrometres deep, stays
    on it); the flank ends at the tip circle, where the drop is ρ·(1 - cos(θ/2)) (tens of
    micrometres), and the rest of the rounding, turning onto the tip land, is left off.
    A chamfer of `chamfer` mm along the flank (its edge that far from the tip corner) turns
    the rounding by `angle` only and runs on straight to the tip circle: its edge's
    rounding starts ρ·tan(angle/2) before the edge."""

    radius: float
    start: float
    base_radius: float
    internal: bool = False
    angle: float | None = None

    @classmethod
    def on(cls, radius: float, base_radius: float, tip_radius: float,
           internal: bool = False, chamfer: float | None = None,
           angle: float | None = None) -> TipEdge:
        """The rounding of `radius` (mm) on a flank of base radius and tip radius (mm); on a
        ring (internal) the tip is the flank's inner end. With `chamfer` (mm along the flank
        from the tip) and `angle` (rad): a chamfer whose edge is rounded by `radius`."""
        alpha_a = math.acos(min(base_radius / tip_radius, 1.0))
        s_tip = math.sqrt(max(tip_radius**2 - base_radius**2, 0.0))
        if chamfer is None:
            back = radius * math.tan(0.5 * (0.5 * math.pi - alpha_a))
        else:
            back = chamfer + radius * math.tan(0.5 * angle)
        # the rounding's start, its tangent length back from the tip (or the chamfer's edge)
        start_arc = 0.5 * s_tip**2 / base_radius + (back if internal else -back)
        if not start_arc > 0.0:
            raise ValueError(f"tip edge radius {radius:g} mm: the rounding would start below "
                             "the base circle")
        return cls(radius, math.sqrt(2.0 * base_radius * start_arc), base_radius, internal,
                   None if chamfer is None else angle)

    @property
    def breaks(self) -> tuple[float, ...]:
        """Roll lengths (mm) where the profile's curvature jumps: the rounding's start, and
        a chamfer's where its edge's rounding runs into the straight chamfer."""
        if self.angle is None:
            return (self.start,)
        relative = 1.0 / (1.0 / self.radius + (1.0 if self.internal else -1.0) / self.start)
        arc = relative * math.sin(self.angle) * (-1.0 if self.internal else 1.0)
        return (self.start, math.sqrt(self.start**2 + 2.0 * self.base_radius * arc))

    def drop(self, s, s_tip: float):
        """The drop (mm) at roll length s (mm; s_tip the tip's). Past the tip (where a gap
        field continues the flank) the circle runs on as its own quadratic from the tip, so
        the continued surface stays smooth and finite; a chamfer runs on straight."""
        toward = 1.0 if s_tip >= self.start else -1.0
        beyond = (value(s) - self.start) * toward > 0.0
        if isinstance(s, Jet):      # held at the start short of it (no drop, no NaN there)
            held = where(beyond, s, 0.0 * s + self.start)
            return where(beyond, self._drop_beyond(held, s_tip, toward), 0.0 * s)
        # plain numbers: the drop only where the rounding is (most of a flank has none)
        s = np.asarray(s, float)
        drop = np.zeros(np.broadcast(s, beyond).shape)
        if beyond.any():
            drop[beyond] = self._drop_beyond(np.broadcast_to(s, drop.shape)[beyond], s_tip,
                                             toward)
        return drop

    def _drop_beyond(self, s, s_tip: float, toward: float):
        """The drop (mm) at roll lengths s (mm) past the rounding's start (see drop)."""
        arc = toward * (s * s - self.start**2) / (2.0 * self.base_radius)
        radius = 1.0 / (1.0 / self.radius + (1.0 if self.internal else -1.0) / self.start)
        if self.angle is not None:
            # a line's drop off a circle of radius s along its normal, at the angle γ to
            # it, curves at (1 + sin²γ)/(cos²γ·s) (d = s - p/cos(σ/s - φ0) differentiated
            # twice in the arc σ), away from the circle's centre on an external gear
            sin2 = math.sin(self.angle) ** 2
            bend = (1.0 if self.internal else -1.0) * (1.0 + sin2) / ((1.0 - sin2) * self.start)
            return broken_edge_drop(arc, radius, self.angle, bend)
        arc_tip = toward * (s_tip**2 - self.start**2) / (2.0 * self.base_radius)
        past = value(arc) > arc_tip
        circle = arc_drop(where(past, 0.0 * s + arc_tip, arc), radius, "circular")
        root = math.sqrt(radius**2 - arc_tip**2)
        run = arc - arc_tip
        continued = (radius - root + arc_tip / root * run
                     + 0.5 * radius**2 / root**3 * run * run)
        return where(past, continued, circle)


@dataclass(frozen=True)
class EndChamfer:
    """A chamfer at both face ends, `length` (mm) along the face from each end face to its
    edge on the flank, at `angle` (rad) to the flank (its drop grows tan(angle) mm, a
    transverse amount like every modification, per mm toward the end), its edge on the
    flank rounded by `radius` (mm): the rounding starts radius·tan(angle/2) before the
    edge."""

    length: float
    angle: float
    radius: float

    def start(self, face_width: float) -> float:
        """Where the edge's rounding starts (mm from mid-face, either way)."""
        return 0.5 * face_width - self.length - self.radius * math.tan(0.5 * self.angle)

    def breaks(self, face_width: float) -> tuple[float, ...]:
        """Face positions (mm from mid-face) where the lead's curvature jumps: the edge's
        rounding's start and end at both ends."""
        start = self.start(face_width)
        end = start + self.radius * math.sin(self.angle)
        return (-end, -start, start, end)

    def drop(self, w, face_width: float):
        start = self.start(face_width)
        if not start > 0.0:
            raise ValueError("end chamfer length and its edge's rounding must leave the middle "
                             "of the face")
        run = where(value(w) > 0, w, -w) - start
        inside = value(run) > 0.0
        return where(inside, broken_edge_drop(where(inside, run, 0.0 * run), self.radius,
                                               self.angle), 0.0 * w)


@dataclass(frozen=True)
class EndRelief:
    """End relief of `amount` at both face ends over `length` (mm) from each end, a linear
    one's starts blended over `blend` of its length (relief_ramp)."""

    amount: float
    length: float
    shape: str = "linear"
    blend: float = RELIEF_BLEND

    def drop(self, w, face_width: float):
        if not 0 < self.length <= 0.5 * face_width:
            raise ValueError("end relief length must lie in (0, half the face width]")
        inner = 0.5 * face_width - self.length
        x = (where(value(w) > 0, w, -w) - inner) / self.length
        return self.amount * relief_ramp(x, self.shape, self.blend)


@dataclass(frozen=True)
class Deflection:
    """Deflection of a flank along the face, as a displacement toward the mating flank
    (mm, positive closes the gap): `slope`·w (rad; an equivalent misalignment), plus a
    parabolic bending whose value is `bending` at the face ends and zero mid-face, plus a
    table of (w, displacement) points interpolated linearly (held beyond its ends)."""

    slope: float = 0.0
    bending: float = 0.0
    table: tuple[tuple[float, float], ...] = ()

    def drop(self, w, face_width: float):
        x = w / (0.5 * face_width)
        d = self.slope * w + self.bending * x * x
        if self.table:
            positions, values = np.array(self.table, float).T
            order = np.argsort(positions)
            # piecewise linear in w, exact for jets as well: sum of hat functions
            d = d + _piecewise_linear(w, positions[order], values[order])
        return -d  # a drop removes material: moving toward the mate is a negative drop


def _piecewise_linear(w, xs: np.ndarray, ys: np.ndarray):
    """Linear interpolation through (xs, ys), held constant beyond the ends (jet-friendly)."""
    out = ys[0] + 0.0 * w
    for i in range(len(xs) - 1):
        slope = (ys[i + 1] - ys[i]) / (xs[i + 1] - xs[i])
        inside = (value(w) > xs[i]) & (value(w) <= xs[i + 1])
        beyond = value(w) > xs[i + 1]
        out = out + where(inside, slope * (w - xs[i]), where(beyond, ys[i + 1] - ys[i], 0.0))
    return out


@dataclass(frozen=True)
class FlankModifications:
    """All modifications of one flank; `drop` is their sum (transverse amount, mm)."""

    lead_crown: LeadCrown | None = None
    profile_crown: ProfileCrown | None = None
    tip_relief: TipRelief | None = None
    end_relief: EndRelief | None = None
    deflection: Deflection | None = None
    tip_edge: TipEdge | None = None
    end_chamfer: EndChamfer | None = None
    root_relief: RootRelief | None = None
    helix_slope: HelixSlope | None = None
    profile_slope: ProfileSlope | None = None
    twist: Twist | None = None
    topography: Topography | None = None

    def drop(self, w, s, face_width: float, s_form: float, s_tip: float):
        total = 0.0 * w + 0.0 * s
        if self.deflection is not None:
            total = total + self.deflection.drop(w, face_width)
        if self.helix_slope is not None:
            total = total + self.helix_slope.drop(w, face_width)
        if self.lead_crown is not None:
            total = total + self.lead_crown.drop(w, face_width)
        if self.end_relief is not None:
            total = total + self.end_relief.drop(w, face_width)
        if self.end_chamfer is not None:
            total = total + self.end_chamfer.drop(w, face_width)
        if self.profile_slope is not None:
            total = total + self.profile_slope.drop(s, s_form, s_tip)
        if self.twist is not None:
            total = total + self.twist.drop(w, s, face_width, s_form, s_tip)
        if self.profile_crown is not None:
            total = total + self.profile_crown.drop(s, s_form, s_tip)
        if self.tip_relief is not None:
            total = total + self.tip_relief.drop(s, s_tip)
        if self.root_relief is not None:
            total = total + self.root_relief.drop(s, s_form)
        if self.tip_edge is not None:
            total = total + self.tip_edge.drop(s, s_tip)
        if self.topography is not None:
            total = total + self.topography.drop(w, s)
        return total

    @property
    def empty(self) -> bool:
        return all(getattr(self, f.name) is None for f in fields(self))

    @property
    def profile_breaks(self) -> tuple[float, ...]:
        """Roll lengths (mm) where the profile's slope or curvature jumps: the starts of the
        tip and root reliefs and those of the tip edge (a fitted B-spline needs points close
        around them)."""
        reliefs = tuple(r.start for r in (self.tip_relief, self.root_relief) if r is not None)
        return reliefs + (() if self.tip_edge is None else self.tip_edge.breaks)

    def lead_breaks(self, face_width: float) -> tuple[float, ...]:
        """Face positions (mm from mid-face) where the lead's slope or curvature jumps: an
        end relief's starts and an end chamfer's edge roundings (sections are put there)."""
        out = ()
        if self.end_relief is not None:
            inner = 0.5 * face_width - self.end_relief.length
            out += (-inner, inner)
        if self.end_chamfer is not None:
            out += self.end_chamfer.breaks(face_width)
        return tuple(sorted(out))
