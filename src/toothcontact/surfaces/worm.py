"""Cylindrical worm thread flanks ZA, ZN, ZI and ZK as exact helicoids.

Flank forms after DIN 3975 (1976) §3.6.4-3.6.7 / ISO/TR 10828 and Litvin & Fuentes, *Gear
Geometry and Applied Theory*, 2nd ed. (2004), ch. 19. Every cylindrical worm flank is a
helicoid (Litvin §19.10, Eqs. 19.10.1-19.10.4: a plane curve performing the screw motion
about the worm axis with screw parameter p, p > 0 for a right-hand worm), so one flank is
fixed by its axial profile z = f(r) in the half-plane y = 0, x > 0; only f differs between
the forms:

- ZA: straight line in the axial section, axial profile angle alpha_x.
- ZN: straight line in the normal section of the thread space (DIN 3975 §3.1.2: the plane
  through the radial line at the middle of the space on the reference cylinder, normal to the
  reference helix there), normal profile angle alpha_n.
- ZI: involute helicoid; transverse profile an involute of the base circle r_b, with
  tan(alpha_t) = tan(alpha_n)/sin(gamma), r_b = r1·cos(alpha_t), equivalently
  cos(gamma_b) = cos(gamma)·cos(alpha_n), tan(gamma_b) = |p|/r_b (helical-gear relations with
  helix angle beta = pi/2 - gamma).
- ZK (ZK1): envelope of a straight-sided double-cone grinding wheel whose axis is crossed with
  the worm axis at the lead angle gamma, centre distance a = D/2 + d1/2, wheel axial-section
  profile angle alpha_0 = pressure_angle; contact line from the equation of meshing
  n·v12 = 0 (Litvin ch. 6; v12 = the screw velocity field of the worm, e_z × r + p e_z).
  The wheel's tip grinds the root cylinder (its cone sides end at rho_t = a - r_f from its
  axis, or at the apex where they meet, if that comes first).

Form circle: the flank exists down to a form radius r_form, and the domain starts at
max(r_f, r_form) (edge "form" when r_form > r_f, else "root"; a form edge lies FORM_OFFSET
of the depth outside the form circle, where the profile is regular); below it the thread is
undercut, bounded by a surface the flank's model does not hold. ZA: r_form = 0; ZN: the
radius below which the normal-section line has no point of that radius; ZI: the base
radius r_b (no involute inside it); ZK: along the contact line the worm radius R(rho) falls
as rho grows to a least value (an edge of regression of the envelope, where the profile
turns back) or to the wheel's tip edge rho_t; beyond, the tip edge's circle cuts into the
flank (the undercut, as a rack's tip rounding cuts into an involute): r_form is the radius
where the screw-projected tip-edge circle, or the contact line's far branch, leaves the
flank's axial profile.

Frame and conventions (mm, rad): worm axis = z, worm centred at z = 0. One thread is centred
on the +x axis at z = 0 with axial thickness s = pi·mx/2 at d1; its "left" flank faces -z
(z = -s/2 at d1), its "right" flank faces +z (z = +s/2). The right flank is the left one
turned by pi about the x axis (f_right = -f_left). A left-hand worm is the mirror image
(y -> -y) of the right-hand one; here it follows from the sign of p, not from mirroring.

Parameterisation of every flank:  r(u, v) = (u cos(theta), u sin(theta), p·v),
theta = v - f(u)/p, with
  u = distance from the worm axis (mm), u in [max(root, form) radius, tip radius],
  v = screw-motion angle (rad): the point is the transverse (z = 0) profile screwed by v, so
      z = p·v exactly and a screw motion by phi maps (u, v) to (u, v + phi).
The domain u in [max(r_f, r_form), r_a], v in [-L/(2|p|), L/(2|p|)] is therefore exactly the
flank between the root (or form) and tip cylinders and the end planes z = ±L/2 (edges "root"
or "form", "tip", "end_A" at z = -L/2, "end_B" at z = +L/2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from .base import Flank
from .jet import cos_sin, value

FORMS = ("ZA", "ZN", "ZI", "ZK")

#: a flank that ends on its form circle starts this fraction of its depth outside it: the
#: parameterisation by radius is singular on a ZI base circle, a ZN line's limit and a ZK
#: edge of regression (infinite slope or curvature of the axial profile)
FORM_OFFSET = 1e-4


@dataclass(frozen=True)
class GrindingWheel:
    """The ZK tool side that generates one flank (mm, rad).

    A point X of the wheel has axial coordinate zeta = (X - centre)·axis and distance rho from
    the axis; the generating cone side is zeta = half_width + (radius - rho)·tan(profile_angle).
    """

    centre: np.ndarray  # wheel centre (mm): (a, 0, z of the space centre), a = radius + d1/2
    axis: np.ndarray  # unit wheel axis, crossed with the worm axis at the lead angle
    radius: float  # reference radius D/2 (mm): the profile point on the worm reference cylinder
    profile_angle: float  # alpha_0 (rad): wheel profile to the wheel's radial direction
    half_width: float  # zeta of the cone side at rho = radius (mm), solved for s = pi·mx/2

    @property
    def centre_distance(self) -> float:
        """Distance between the worm axis and the wheel axis (mm)."""
        return float(self.centre[0])


class WormFlank(Flank):
    """One flank of a cylindrical worm thread (ZA, ZN, ZI or ZK), see the module docstring.

    form: "ZA", "ZN", "ZI" or "ZK"; starts: z1 >= 1; axial_module: mx (mm);
    pitch_diameter: reference diameter d1 (mm); length: axial length L of the threaded part
    (mm), centred at z = 0; hand: "right" or "left"; pressure_angle (rad): axial profile angle
    alpha_x for ZA, normal profile angle alpha_n for ZN and ZI, wheel profile angle alpha_0 for
    ZK; side: "left" (faces -z) or "right" (faces +z); tip_diameter, root_diameter (mm):
    default d1 + 2 mx and d1 - 2.4 mx; wheel_diameter: ZK grinding-wheel diameter D (mm).
    """

    def __init__(self, form: str, starts: int, axial_module: float, pitch_diameter: float, *,
                 length: float, hand: str = "right", pressure_angle: float = math.radians(20.0),
                 side: str = "left", tip_diameter: float | None = None,
                 root_diameter: float | None = None, wheel_diameter: float = 250.0):
        form = str(form).upper()
        if form not in FORMS:
            raise ValueError(f"form must be one of {FORMS}, got {form!r}")
        if hand not in ("right", "left"):
            raise ValueError(f"hand must be 'right' or 'left', got {hand!r}")
        if side not in ("left", "right"):
            raise ValueError(f"side must be 'left' or 'right', got {side!r}")
        if int(starts) != starts or starts < 1:
            raise ValueError(f"starts must be an integer >= 1, got {starts}")
        if not (axial_module > 0 and pitch_diameter > 0 and length > 0):
            raise ValueError("axial_module, pitch_diameter and length must be > 0 mm")
        if not 0 < pressure_angle < math.pi / 2:
            raise ValueError(f"pressure_angle must lie in (0, pi/2) rad, got {pressure_angle}")
        self.form, self.starts, self.hand, self.side = form, int(starts), hand, side
        self.axial_module, self.pitch_diameter = float(axial_module), float(pitch_diameter)
        self.pressure_angle, self.length = float(pressure_angle), float(length)
        self.tip_diameter = float(pitch_diameter + 2 * axial_module if tip_diameter is None
                                  else tip_diameter)
        self.root_diameter = float(pitch_diameter - 2.4 * axial_module if root_diameter is None
                                   else root_diameter)
        if not 0 < self.root_diameter < self.pitch_diameter < self.tip_diameter:
            raise ValueError("need 0 < root_diameter < pitch_diameter < tip_diameter")
        self.wheel_diameter = float(wheel_diameter)

        mx = self.axial_module
        self._p = (1.0 if hand == "right" else -1.0) * self.starts * mx / 2  # = ±r1·tan(gamma)
        gamma = self.lead_angle
        self._sg, self._cg = math.copysign(math.sin(gamma), self._p), math.cos(gamma)
        self._zq = -self.axial_pitch / 2  # centre of the space in front of the left flank
        self._tau = math.tan(self.pressure_angle)
        self._half_s = math.pi * mx / 4
        self._left_profile = getattr(self, f"_left_{form.lower()}")
        #: form radius r_form (mm): the flank exists from here outward (module docstring)
        self.form_radius = float(getattr(self, f"_init_{form.lower()}")())
        if self.form_radius >= self.tip_diameter / 2:
            raise ValueError(f"the {form} flank exists only beyond radius {self.form_radius:.4g}"
                             f" mm, outside the tip radius {self.tip_diameter / 2:.4g} mm")

        half = self.length / (2 * abs(self._p))
        root, tip = self.root_diameter / 2, self.tip_diameter / 2
        start = root if self.form_radius <= root else \
            self.form_radius + FORM_OFFSET * (tip - self.form_radius)
        self.domain = ((start, tip), (-half, half))
        ends = ("end_A", "end_B") if self._p > 0 else ("end_B", "end_A")
        self.edges = {"u0": "form" if self.form_radius > root else "root", "u1": "tip",
                      "v0": ends[0], "v1": ends[1]}
        # (r_u × r_v)_z = u > 0 everywhere, and the left flank faces -z
        self.orientation = -1.0 if side == "left" else 1.0
        self._side_sign = 1.0 if side == "left" else -1.0

    @classmethod
    def from_lead_angle(cls, form: str, starts: int, lead_angle: float, *,
                        axial_module: float | None = None, normal_module: float | None = None,
                        **kwargs) -> WormFlank:
        """Build from the lead angle gamma (rad) at d1 and mx (mm) or mn = mx·cos(gamma) (mm):
        d1 = z1·mx / tan(gamma). Other keywords as in the constructor."""
        if (axial_module is None) == (normal_module is None):
            raise ValueError("give exactly one of axial_module and normal_module")
        mx = axial_module if axial_module is not None else normal_module / math.cos(lead_angle)
        return cls(form, starts, mx, starts * mx / math.tan(lead_angle), **kwargs)

    # --- worm data -------------------------------------------------------------------------
    @property
    def reference_radius(self) -> float:
        """r1 = d1/2 (mm)."""
        return self.pitch_diameter / 2

    @property
    def axial_pitch(self) -> float:
        """px = pi·mx (mm)."""
        return math.pi * self.axial_module

    @property
    def lead(self) -> float:
        """pz = z1·pi·mx (mm), positive for either hand."""
        return self.starts * self.axial_pitch

    @property
    def lead_angle(self) -> float:
        """gamma at d1 (rad, positive): tan(gamma) = z1·mx/d1."""
        return math.atan(self.starts * self.axial_module / self.pitch_diameter)

    @property
    def normal_module(self) -> float:
        """mn = mx·cos(gamma) (mm)."""
        return self.axial_module * math.cos(self.lead_angle)

    @property
    def screw_parameter(self) -> float:
        """p = lead/(2 pi) (mm/rad), positive for a right-hand worm, negative for left-hand."""
        return self._p

    @property
    def axial_thickness(self) -> float:
        """Thread thickness in the axial section at d1 (mm): pi·mx/2."""
        return 2 * self._half_s

    @property
    def base_radius(self) -> float:
        """ZI only: r_b = r1·cos(alpha_t), tan(alpha_t) = tan(alpha_n)/sin(gamma) (mm)."""
        if self.form != "ZI":
            raise AttributeError(f"a {self.form} worm has no base cylinder")
        return self._rb

    @property
    def base_lead_angle(self) -> float:
        """ZI only: base lead angle gamma_b (rad), tan(gamma_b) = |p|/r_b; equivalently
        cos(gamma_b) = cos(gamma)·cos(alpha_n)."""
        return math.atan(abs(self._p) / self.base_radius)

    @property
    def grinding_wheel(self) -> GrindingWheel:
        """ZK only: the wheel side generating this flank, placed for the thread at z = 0."""
        if self.form != "ZK":
            raise AttributeError(f"a {self.form} worm is not ground by a ZK wheel")
        sg, cg, a = self._sg, self._cg, self._a
        centre, axis = np.array([a, 0.0, self._zq]), np.array([0.0, -sg, cg])
        if self.side == "right":  # turned by pi about the x axis
            centre, axis = centre * [1, -1, -1], axis * [1, -1, -1]
        return GrindingWheel(centre, axis, self._rw, self.pressure_angle, self._zeta_ref)

    # --- the surface -----------------------------------------------------------------------
    def point(self, u, v):
        """(x, y, z) in mm at u = radius (mm), v = screw angle (rad); numpy or jets."""
        f = self._side_sign * self._left_profile(u)
        cos_theta, sin_theta = cos_sin(v - f / self._p)
        return u * cos_theta, u * sin_theta, self._p * v

    def axial_section(self, count: int) -> tuple[np.ndarray, np.ndarray]:
        """The flank's axial section through `count` points: radii and z (mm)."""
        r = self.profile_parameters(count)
        return r, self.axial_profile(r)

    def axial_profile(self, r):
        """z (mm) of this flank in the axial half-plane y = 0, x > 0 at radius r (mm), for the
        thread centred at z = 0 (other threads and turns: + k·px)."""
        return self._side_sign * self._left_profile(r)

    # ZA: straight axial profile
    def _init_za(self):
        return 0.0

    def _left_za(self, r):
        return -self._half_s + (r - self.reference_radius) * self._tau

    # ZI: involute helicoid, f = -s/2 + |p|·(inv(alpha(r)) - inv(alpha(r1))), cos(alpha) = rb/r
    def _init_zi(self):
        alpha_t = math.atan(self._tau / math.sin(self.lead_angle))
        self._rb = self.reference_radius * math.cos(alpha_t)
        self._inv1 = math.tan(alpha_t) - alpha_t
        return self._rb

    def _left_zi(self, r):
        rb = self._rb
        inv = np.sqrt(r * r - rb * rb) / rb - np.arccos(rb / r)
        return -self._half_s + abs(self._p) * (inv - self._inv1)

    # ZN: straight line in the normal section of the space; in-plane coordinates xi (along
    # e_x) and eta (along t = (0, -sin g, cos g)) about Q = (0, 0, zq): eta = eta1 + (xi - r1)·tau
    def _init_zn(self):
        r1 = self.reference_radius
        sg, tau = self._sg, self._tau
        # the line has points of radius r1 while |sg·b| <= r1·sqrt(1 + sg²·tau²)
        top = min(self.axial_pitch, r1 * tau + r1 * math.sqrt(1 + sg * sg * tau * tau) / abs(sg))
        thickness = lambda e: self._zn(r1, e) + self._half_s  # noqa: E731
        if not thickness(0.0) * thickness(top) < 0:
            raise ValueError(f"ZN: no straight normal-section line at "
                             f"{math.degrees(self.pressure_angle):.4g} deg gives the thread "
                             f"thickness pi·mx/2 at d1 with a lead angle of "
                             f"{math.degrees(self.lead_angle):.4g} deg")
        self._eta1 = brentq(thickness, 0.0, top, xtol=1e-15, rtol=4 * np.finfo(float).eps)
        b = self._eta1 - r1 * tau
        return abs(sg * b) / math.sqrt(1 + sg * sg * tau * tau)  # where the root vanishes

    def _zn(self, r, eta1):
        sg, cg, tau = self._sg, self._cg, self._tau
        b = eta1 - self.reference_radius * tau
        k = 1 + sg * sg * tau * tau
        # r² = xi² + (eta·sin g)², a quadratic in xi
        xi = (-sg * sg * tau * b + np.sqrt(r * r * k - sg * sg * b * b)) / k
        eta = b + tau * xi
        return self._zq + eta * cg - self._p * np.arctan2(-eta * sg, xi)

    def _left_zn(self, r):
        return self._zn(r, self._eta1)

    # ZK: envelope of the wheel cone under the screw motion
    def _init_zk(self):
        self._rw = self.wheel_diameter / 2
        self._a = self._rw + self.reference_radius
        r1 = self.reference_radius
        self._zeta_ref = brentq(lambda zr: self._zk(r1, zr) + self._half_s, 0.0,
                                self.axial_pitch, xtol=1e-15, rtol=4 * np.finfo(float).eps)
        return self._zk_form_radius()

    def _zk_form_radius(self) -> float:
        """r_form of the ZK flank (mm): where the near branch of the contact line ends (the
        least worm radius R(rho), or the wheel's tip edge rho_t), raised to where the
        screw-projected tip-edge circle or the contact line's far branch stop reaching past
        the flank's axial profile into the thread (module docstring)."""
        zr, tau, p, mx = self._zeta_ref, self._tau, self._p, self.axial_module
        rho_t = min(self._a - self.root_diameter / 2, self._rw + zr / tau)
        rho = np.linspace(self._a - self.tip_diameter / 2 - mx, rho_t, 2001)
        with np.errstate(invalid="ignore"):
            dR = self._zk_contact(rho, zr)[4]
        rising = np.flatnonzero(~(dR < 0))
        rho_end = rho_t
        if rising.size:  # R(rho) has its least value (or the contact line ends) before rho_t
            i = rising[0]
            rho_end = brentq(lambda t: self._zk_contact(t, zr)[4], rho[i - 1], rho[i],
                             xtol=1e-13 * self._a) if np.isfinite(dR[i]) else rho[i - 1]
        form = float(self._zk_contact(rho_end, zr)[3])

        def projected(x, y, z):  # (R, Z) in the axial half-plane y = 0, x > 0
            return np.hypot(x, y), z - p * np.arctan2(y, x)

        def reach(t, curve):  # > 0 where the curve's point lies past the flank's profile
            R, Z = projected(*curve(t))
            with np.errstate(invalid="ignore"):
                return np.where(R > form, Z - self._zk(R, zr), -np.inf)

        sg, cg, zeta_t = self._sg, self._cg, zr + (self._rw - rho_t) * tau
        edge = lambda psi: (self._a - rho_t * np.cos(psi),  # noqa: E731  the tip-edge circle
                            -rho_t * cg * np.sin(psi) - zeta_t * sg,
                            self._zq - rho_t * sg * np.sin(psi) + zeta_t * cg)
        curves = [(edge, np.linspace(-0.5 * np.pi, 0.5 * np.pi, 4001))]
        if rho_end < rho_t:  # the far branch of the contact line
            curves.append((lambda t: self._zk_contact(t, zr)[:3],
                           np.linspace(rho_end, rho_t, 2001)[1:]))
        for curve, t in curves:
            g = reach(t, curve)
            past = np.flatnonzero(g > 0)
            if not past.size:
                continue
            R = projected(*curve(t))[0]
            i = past[np.argmax(R[past])]  # the outermost point past the profile
            j = i + 1 if i + 1 < t.size and R[i + 1] > R[i] else i - 1
            if 0 <= j < t.size and g[j] <= 0:
                t_cross = brentq(lambda s, curve=curve: float(reach(np.array(s), curve)),
                                 t[i], t[j], xtol=1e-14)
                form = max(form, float(projected(*curve(np.array(t_cross)))[0]))
            else:
                form = max(form, float(R[i]))
        return form

    def _zk_contact(self, rho, zeta_ref):
        """Contact point (x, y, z) on the left-flank wheel side at distance rho (mm) from the
        wheel axis, its worm radius R and dR/drho. Wheel frame: centre C = (a, 0, zq),
        e1 = -e_x, e2 = (0, -cos g, -sin g), e3 = axis = (0, -sin g, cos g); wheel point
        C + rho (cos psi e1 + sin psi e2) + zeta e3, normal tau·e_rho + e3. Meshing
        n·(e_z × r + p e_z) = 0 reduces to A cos psi + B sin psi = D (derived here)."""
        sg, cg, tau, p, a = self._sg, self._cg, self._tau, self._p, self._a
        zeta = zeta_ref + (self._rw - rho) * tau
        A = sg * (rho - tau * zeta)
        B = -tau * (a * cg + p * sg)
        D = a * sg - p * cg
        psi = np.arctan2(B, A) + np.arccos(D / np.sqrt(A * A + B * B))  # branch near psi = 0
        cpsi, spsi = cos_sin(psi)
        x = a - rho * cpsi
        y = -rho * cg * spsi - zeta * sg
        z = self._zq - rho * sg * spsi + zeta * cg
        dpsi = -sg * (1 + tau * tau) * cpsi / (B * cpsi - A * spsi)  # implicit d psi/d rho
        dx = -cpsi + rho * spsi * dpsi
        dy = -cg * spsi - rho * cg * cpsi * dpsi + tau * sg
        R = np.sqrt(x * x + y * y)
        return x, y, z, R, (x * dx + y * dy) / R

    def _zk(self, r, zeta_ref):
        """Axial profile z(r) (mm) of the left flank through its contact line with the
        wheel: the point of the near branch (R falls as rho grows) of worm radius r. NaN
        where that branch has no point of radius r (Newton fails, ends on the far branch or
        beyond the wheel axis): a contact search may probe far outside the worm, and NaN
        tells it there is no surface there."""
        r_f = np.asarray(value(r), float)
        rho = self._zk_start(r_f, zeta_ref).ravel()
        target = np.broadcast_to(r_f, np.shape(r_f)).ravel()
        tol = 1e-13 * self._a
        converged = np.zeros(rho.shape, bool)
        running = np.flatnonzero(np.isfinite(target))
        with np.errstate(invalid="ignore", divide="ignore"):
            for _ in range(40):      # Newton on the points still running only
                if running.size == 0:
                    break
                *_, R, dR = self._zk_contact(rho[running], zeta_ref)
                step = (R - target[running]) / dR
                rho[running] -= step
                done = np.abs(step) < tol
                converged[running[done & (dR < 0)]] = True
                running = running[~done & np.isfinite(step)]  # NaN: no contact there
            rho = np.where(converged & (rho > 0), rho, np.nan).reshape(np.shape(r_f))
            for _ in range(2):  # in jets: each step doubles the number of exact Taylor orders
                *_, R, dR = self._zk_contact(rho, zeta_ref)
                rho = rho - (R - r) / dR
            x, y, z, _, _ = self._zk_contact(rho, zeta_ref)
            return z - self._p * np.arctan2(y, x)

    def _zk_start(self, r, zeta_ref):
        """Where the Newton for R(rho) = r (mm) starts: from the wheel's outside (the worm's
        tip and beyond), where R is convex, so the steps approach the near branch's root
        from one side; inside the flank's radii, from a table of that branch's roots
        (interpolated: a step or two from the root, where each Newton solve from outside
        took about ten)."""
        outside = np.full(np.shape(r), self._a - self.tip_diameter / 2 - self.axial_module)
        if zeta_ref != getattr(self, "_zeta_ref", None):
            return outside            # the flank still being placed
        if "_zk_table" not in self.__dict__:
            radii = np.linspace(0.5 * self.root_diameter, 0.5 * self.tip_diameter, 65)
            rho = outside.flat[0] + np.zeros_like(radii)
            with np.errstate(invalid="ignore", divide="ignore"):
                for _ in range(40):
                    *_, R, dR = self._zk_contact(rho, zeta_ref)
                    rho = rho - (R - radii) / dR
            good = np.isfinite(rho) & (rho > 0)
            self._zk_table = (radii[good], rho[good])
        radii, roots = self._zk_table
        if radii.size < 2:
            return outside
        within = (r >= radii[0]) & (r <= radii[-1])
        return np.where(within, np.interp(r, radii, roots), outside)

    def _left_zk(self, r):
        return self._zk(r, self._zeta_ref)
