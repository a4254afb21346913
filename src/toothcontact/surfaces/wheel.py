"""Worm-wheel tooth flank: the envelope of the hob thread in the generating motion.

Theory: Litvin & Fuentes, *Gear Geometry and Applied Theory*, 2nd ed. (2004). The wheel flank
is the envelope of the family of hob thread surfaces in the relative motion of hob and wheel
(§6.1: theory of envelopes, equation of meshing n·v^(12) = 0; ch. 19: generation of the
worm-gear by a hob identical to the worm or by an oversized hob). The hob thread is a helicoid
(§19.10: the generalized helicoid and its unit normal in two-parameter form, Eqs. 19.10.4
and 19.10.8), given as a `WormFlank` r_h(u, v) = (u cos θ, u sin θ, p·v), θ = v - f(u)/p.
(Section numbers as cited; the equation numbers inside ch. 19 for the meshing of worm and
worm-gear and for the oversized hob were not checked against the book.)

Generating motion (the hobbing machine; units mm, rad):
  hob frame S_h: hob axis = z_h, through the origin; the hob turns by φ1 about +z_h.
  wheel centre C = (a0, 0, 0) in S_h: the common perpendicular of the axes is the x_h axis,
  a0 = r_hob + r2 + x2·mx (generating centre distance; r2 = z2·mx/2 with the WORM's axial
  module, x2 the profile shift, 0 by default).
  wheel axis k2 = (0, -s·sin Σ, cos Σ), s = sign(p) (+1 right-hand), Σ the crossing angle =
  angle between +z_h and k2; the wheel turns by φ2 = φ1·z1/z2 about +k2. For Σ = 90° this is
  the kinematically exact rolling: the hob's apparent axial motion -p·φ1 equals the wheel's
  pitch-circle motion r2·φ2 (same lead).
  Setting angle (option `align_hob_thread`): the hob axis is turned about the common
  perpendicular so that the hob's thread at its pitch point is parallel to the worm's thread
  at the worm's pitch point: Σ = 90° + Δγ, Δγ = γ_hob - γ_worm (γ the lead angles at the
  reference cylinders). This is exactly what is implemented; the kinematics stay
  φ2 = φ1·z1/z2 and nothing else is changed. Note: a tilted hob is only pitch-consistent
  (relative velocity at the pitch point tangent to both threads) when it has the worm's
  NORMAL pitch, p_hob·cos γ_hob = p_worm·cos γ_worm; with the same lead the small pitch
  mismatch moves the contact away from the pitch point (the envelope stays exact).
Wheel frame S2 (attached to the wheel): origin at the wheel centre, z2 = k2 (wheel axis),
  wheel mid-plane z2 = 0 through the hob axis; x2 is the direction from the wheel centre to
  the hob axis turned back by the wheel rotation φ2 and by a half pitch σ·s·π/z2 (σ = +1
  for the left, -1 for the right flank), so that tooth 0 of the wheel is centred on the +x2
  axis: for a symmetric hob at Σ = 90° the right flank is the left one turned by π about
  x2. (At φ1 = 0 the hob thread centred on +x_h at z_h = 0 sits in the space that is then
  centred on the line from C to the hob axis.) A point Y = X - C (X in the hob's fixed
  frame) has the wheel-housing coordinates (a_, b_, ζ) = (Y·x_w, Y·y_w, Y·k2), x_w = -e_x,
  y_w = k2 × x_w, and the wheel-frame coordinates R_z(-Φ)·(a_, b_, ζ), Φ = φ2 + σ·s·π/z2.
The same transform with a0 -> a and Σ -> 90° places the wheel in mesh with the worm: worm
angle φ1, wheel angle φ1·z1/z2 (`wheel_from_hob(phi1, centre_distance=a,
crossing_angle=pi/2)`).

Parameterisation (u, v), solving the meshing equation in closed form:
  v = axial coordinate z2 of the wheel point (mm): v = ±b2/2 are exactly the wheel faces;
  u in [0, 1] = depth: the generating hob point has radius rho = rho_tip(v) + u·(r_a,hob -
  rho_tip(v)) (`hob_radius(u, v)`), u = 1 on the hob's tip edge (the wheel's root edge),
  u = 0 on the fitted tip edge rho_tip(v) (see Trim).
Because the hob is a helicoid, its normal at the point of radius rho and polar angle ψ in the
machine frame is N = -rho·f'(rho) e_r - p e_t + rho e_z (= r_u × r_v in the local
cylindrical basis at ψ: a helicoid's normal only turns with the polar angle), independent of
the axial position z of the point, and the relative velocity
v^(12) = e_z × X - (z1/z2)·k2 × (X - C) (hob turning at ω1 = 1) is affine in X. The
equation of meshing N·v^(12) = 0 is therefore LINEAR in z on the line
X = (rho cos ψ, rho sin ψ, z): z = -A(rho, ψ)/B(rho, ψ), in closed form. Then ψ follows
from the wheel-axial coordinate ζ(rho, ψ) = (X - C)·k2 = v (float Newton, then two Newton
steps in jet arithmetic: exact first and second derivatives), and the generating angle is
φ1 = ψ - z/p + f(rho)/p (hob parameters (rho, z/p)). The meshing equation needs f'(rho) as a
jet, i.e. the third derivative of the hob's axial profile f: it comes from running the
hob's own `axial_profile` on a univariate third-order Taylor number (`_Taylor3`), so every
worm form (ZA, ZN, ZI, ZK) works without form-specific code.

Trim (the wheel blank, DIN 3975 proportions, x2 = profile shift coefficient, c* = 0.2):
  d2 = z2·mx, a = d1/2 + d2/2 + x2·mx, d_a2 = d2 + 2·mx·(1 + x2) (tip diameter at the throat),
  d_f2 = d2 - 2·mx·(1.2 - x2), throat radius r_k = a - d_a2/2 (the blank's tip surface is the
  torus of tube radius r_k about the circle of radius a in the mid-plane), outside diameter
  d_e2 = d_a2 + min(mx, r_k) (default; d_a2 + mx is a guideline value, lowered on a worm of
  q < 4 so that the rim keeps a throat of depth r_k/2 at least; `outside_diameter`
  overrides), face width b2 = 2·sqrt(r_a1² - r1²) = 2·mx·sqrt(q + 1), q = d1/mx (default:
  the chord of the worm's tip circle at its reference circle, R. L. Mott, *Machine Elements
  in Mechanical Design*, worm-gear geometry, F_G = sqrt(D_oW² - D_W²) (equation number not
  checked): at the faces the worm's tip still reaches the wheel's reference circle;
  `face_width` overrides). A face width must stay within the worm's reach,
  b2 < 2·sqrt(r_a1² - (a - d_e2/2)²): beyond it the worm's tip circle (in the wheel's axial
  section, about the worm axis) no longer reaches the blank's outside cylinder, so the teeth
  at the faces would neither be cut by the hob nor meet the worm. The default lies inside
  for every worm (q + 1 < 2.5·q - 1.25 for q > 1.5); it may exceed 2·r_k, where the faces
  cut the outside cylinder and not the throat torus.
  Edges: "root" (u = 1, the curve generated by the hob's tip edge: exact), "end_A"/"end_B"
  (v = -b2/2, +b2/2: the face planes, exact), "tip" (u = 0: approximate). rho_tip(v) is
  found at construction: at 1025 face positions, the lowest hob radius down to which every
  hob point from the tip edge generates a point in the blank, on the root edge's side of the
  pole of the meshing equation (a scan, then bisection); a degree-12 polynomial in v/(b2/2)
  fitted to these and lowered by its largest excess, by the largest step of the samples and
  by 0.1 % of the hob depth; never below the hob root (or form) radius, nor below the
  generating floor where the hob stops generating (`_fit_tip`). So the domain holds the whole real
  flank plus a thin strip of envelope beyond the blank's tip surface (torus/outside
  cylinder); `inside_blank(points)` says which points are real (about 96-97 % of a 41 × 41
  grid for the test sets).
Orientation: normals point out of the wheel tooth (= minus the hob's outward normal at the
generating contact).
"""

from __future__ import annotations

import math

import numpy as np

from .base import Flank
from .jet import ARITHMETIC, Jet, cos_sin, dispatch_ufunc, value, where
from .worm import WormFlank


# --- univariate third-order Taylor numbers ---------------------------------------------------
class _Taylor3:
    """g(t) with dg/dt, d²g/dt², d³g/dt³ (numpy arrays): enough to run a hob's axial profile
    f(r) and read f, f', f'', f''' exactly (f' is needed as a second-order jet)."""

    __slots__ = ("d",)
    __array_priority__ = 200

    def __init__(self, d0, d1=0.0, d2=0.0, d3=0.0):
        self.d = tuple(np.asarray(x, dtype=float) for x in (d0, d1, d2, d3))

    def __array__(self, dtype=None, copy=None):  # value(), np.asarray: the plain value
        return np.asarray(self.d[0], dtype=dtype)

    def _chain(self, p0, p1, p2, p3):
        _, g1, g2, g3 = self.d
        return _Taylor3(p0, p1 * g1, p2 * g1 * g1 + p1 * g2,
                        p3 * g1 ** 3 + 3 * p2 * g1 * g2 + p1 * g3)

    def cos_sin(self):
        c, s = np.cos(self.d[0]), np.sin(self.d[0])
        return self._chain(c, -s, -c, s), self._chain(s, c, -s, -c)

    def __add__(self, other):
        o = _lift3(other)
        return _Taylor3(*(a + b for a, b in zip(self.d, o.d)))

    __radd__ = __add__

    def __neg__(self):
        return _Taylor3(*(-a for a in self.d))

    def __sub__(self, other):
        return self + (-_lift3(other))

    def __rsub__(self, other):
        return _lift3(other) + (-self)

    def __mul__(self, other):
        a0, a1, a2, a3 = self.d
        b0, b1, b2, b3 = _lift3(other).d
        return _Taylor3(a0 * b0, a1 * b0 + a0 * b1, a2 * b0 + 2 * a1 * b1 + a0 * b2,
                        a3 * b0 + 3 * a2 * b1 + 3 * a1 * b2 + a0 * b3)

    __rmul__ = __mul__

    def reciprocal(self):
        r = 1.0 / self.d[0]
        return self._chain(r, -r * r, 2 * r ** 3, -6 * r ** 4)

    def __truediv__(self, other):
        return self * _lift3(other).reciprocal()

    def __rtruediv__(self, other):
        return _lift3(other) * self.reciprocal()

    def __pow__(self, exponent):
        q, x = float(exponent), self.d[0]
        return self._chain(x ** q, q * x ** (q - 1), q * (q - 1) * x ** (q - 2),
                           q * (q - 1) * (q - 2) * x ** (q - 3))

    def __array_ufunc__(self, ufunc, method, *inputs, **kwargs):
        return dispatch_ufunc(ufunc, method, inputs, kwargs, _UNARY3, _BINARY3, _lift3)


def _lift3(x) -> _Taylor3:
    return x if isinstance(x, _Taylor3) else _Taylor3(x)


def _shift(g: _Taylor3) -> _Taylor3:
    """dg/dt, exact to second order (its third derivative is not known)."""
    return _Taylor3(g.d[1], g.d[2], g.d[3], 0.0)


def _integrate(g0, dg: _Taylor3) -> _Taylor3:
    """The function with value g0 and derivative dg (dg exact to second order)."""
    return _Taylor3(g0, dg.d[0], dg.d[1], dg.d[2])


def _sqrt3(a):
    x = a.d[0]
    s = np.sqrt(x)
    return a._chain(s, 0.5 / s, -0.25 / (s * x), 0.375 / (s * x * x))


def _atan3(a):
    x = a.d[0]
    w = 1.0 / (1.0 + x * x)
    return a._chain(np.arctan(x), w, -2 * x * w * w, (6 * x * x - 2) * w ** 3)


def _asin3(a):
    x = a.d[0]
    w = 1.0 / (1.0 - x * x)
    r = np.sqrt(w)
    return a._chain(np.arcsin(x), r, x * r * w, (1 + 2 * x * x) * r * w * w)


def _tan3(a):
    t = np.tan(a.d[0])
    w = 1 + t * t
    return a._chain(t, w, 2 * t * w, 2 * w * (1 + 3 * t * t))


def _arctan2_3(y, x):
    # d atan2(y, x) = (x dy - y dx)/(x² + y²), integrated once
    return _integrate(np.arctan2(y.d[0], x.d[0]),
                      (x * _shift(y) - y * _shift(x)) / (x * x + y * y))


_UNARY3 = {
    np.negative: lambda a: -a,
    np.sin: lambda a: a.cos_sin()[1],
    np.cos: lambda a: a.cos_sin()[0],
    np.tan: lambda a: _tan3(a),
    np.arctan: _atan3,
    np.arcsin: _asin3,
    np.arccos: lambda a: math.pi / 2 - _asin3(a),
    np.sqrt: _sqrt3,
    np.exp: lambda a: a._chain(*(np.exp(a.d[0]),) * 4),
    np.log: lambda a: a._chain(np.log(a.d[0]), 1 / a.d[0], -1 / a.d[0] ** 2, 2 / a.d[0] ** 3),
    np.square: lambda a: a * a,
}

_BINARY3 = {**ARITHMETIC, np.arctan2: _arctan2_3}


def _compose(u, p0, p1, p2):
    """phi(u) for a jet u, given phi, phi', phi'' at u's value (plain arrays)."""
    return u._chain(p0, p1, p2) if isinstance(u, Jet) else p0


# --- the wheel flank --------------------------------------------------------------------------
class BlankError(ValueError):
    """The wheel cannot be made with these proportions. `parameter` names what to change:
    "face_width" (the wheel's), or "hob_length" (the hob is shorter than its generating
    zone; `needed` then holds the shortest hob length that covers it, mm)."""

    def __init__(self, message: str, parameter: str, needed: float | None = None):
        super().__init__(message)
        self.parameter, self.needed = parameter, needed


class WormWheelFlank(Flank):
    """One flank of the worm-wheel teeth, generated by a hob (see the module docstring).

    hob: the hob thread flank (`WormFlank`; its form, hand, side and starts are those of the
    worm; an oversized hob has a larger pitch_diameter and, normally, the worm's lead);
    teeth: z2; worm: the worm the wheel will mesh with (default: the hob itself, i.e. a hob
    identical to the worm) - it fixes mx (r2 = z2·mx/2), the nominal centre distance a and
    the blank; crossing_angle: Σ (rad) of the generating setting, default 90°;
    align_hob_thread: instead set Σ = 90° + (γ_hob - γ_worm); profile_shift: x2 (coefficient,
    the hob withdrawn by x2·mx); face_width: b2 (mm); outside_diameter: d_e2 (mm).

    Attributes (mm, rad): centre_distance a (mesh with the worm), generating_centre_distance
    a0, crossing_angle Σ, tip_diameter d_a2, root_diameter d_f2, throat_radius r_k,
    outside_diameter d_e2, face_width b2, generating_zone (min, max) of the generating hob
    points' axial position z_h over the domain (the hob must cover it, checked), side and
    hand (those of the hob; side "left" = the flank generated by the hob's left flank).
    """

    def __init__(self, hob: WormFlank, teeth: int, *, worm: WormFlank | None = None,
                 crossing_angle: float | None = None, align_hob_thread: bool = False,
                 profile_shift: float = 0.0, face_width: float | None = None,
                 outside_diameter: float | None = None):
        worm = hob if worm is None else worm
        if not isinstance(hob, WormFlank) or not isinstance(worm, WormFlank):
            raise TypeError("hob and worm must be WormFlank instances")
        if int(teeth) != teeth or teeth < 3:
            raise ValueError(f"teeth must be an integer >= 3, got {teeth}")
        for attr in ("starts", "hand", "side"):
            if getattr(hob, attr) != getattr(worm, attr):
                raise ValueError(f"hob and worm differ in {attr}: "
                                 f"{getattr(hob, attr)!r} != {getattr(worm, attr)!r}")
        if crossing_angle is not None and align_hob_thread:
            raise ValueError("give crossing_angle or align_hob_thread, not both")
        self.hob, self.worm, self.teeth = hob, worm, int(teeth)
        self.side, self.hand, self.profile_shift = hob.side, hob.hand, float(profile_shift)
        mx, x2 = worm.axial_module, self.profile_shift
        self._p = hob.screw_parameter
        self._s = 1.0 if self._p > 0 else -1.0
        self._m = hob.starts / self.teeth  # φ2/φ1
        # half a pitch: tooth 0 (not the space the hob thread sits in at φ1 = 0) on +x2
        self._offset = (1.0 if hob.side == "left" else -1.0) * self._s * math.pi / self.teeth
        if align_hob_thread:
            crossing_angle = math.pi / 2 + hob.lead_angle - worm.lead_angle
        self.crossing_angle = float(math.pi / 2 if crossing_angle is None else crossing_angle)
        if not 0 < self.crossing_angle < math.pi:
            raise ValueError("crossing_angle must lie in (0, pi) rad")
        self._ky = -self._s * math.sin(self.crossing_angle)
        self._kz = math.cos(self.crossing_angle)
        if abs(self._kz) < 1e-15:
            self._kz = 0.0
        self.generating_centre_distance = hob.reference_radius + self.reference_radius + x2 * mx
        self.centre_distance = worm.reference_radius + self.reference_radius + x2 * mx

        # DIN 3975 blank
        self.tip_diameter = 2 * self.reference_radius + 2 * mx * (1 + x2)
        self.root_diameter = 2 * self.reference_radius - 2 * mx * (1.2 - x2)
        self.throat_radius = self.centre_distance - self.tip_diameter / 2
        if not self.throat_radius > 0:
            raise ValueError(f"the wheel's tip diameter d_a2 = {self.tip_diameter:.4g} mm "
                             f"reaches the worm axis (2 a = {2 * self.centre_distance:.4g} mm)")
        self.outside_diameter = float(
            self.tip_diameter + min(mx, self.throat_radius) if outside_diameter is None
            else outside_diameter)
        if not self.tip_diameter <= self.outside_diameter < 2 * self.centre_distance:
            raise ValueError(f"outside diameter {self.outside_diameter:.4g} mm must lie in "
                             f"[d_a2, 2 a) = [{self.tip_diameter:.4g}, "
                             f"{2 * self.centre_distance:.4g}) mm")
        self.orientation = 1.0
        # hob root, or just outside its form circle (a ZI base circle or a ZK edge of
        # regression has an infinite profile slope): no flank below it
        (u0, u1), _ = hob.domain
        self._rho_root = u0 + (1e-3 * (u1 - u0) if hob.edges["u0"] == "form" else 0.0)
        self._rho_tip = hob.tip_diameter / 2  # hob tip edge: generates the wheel's root edge
        # beyond z_b along the hob axis no generated point can lie in the blank
        self._z_blank = math.sqrt(max((self.outside_diameter / 2) ** 2 - (
            self.generating_centre_distance - self._rho_tip) ** 2, 0.0))
        psi, _, _, fp = self._generate(np.array([self._rho_tip]), np.array([0.0]), strict=False)
        self._sheet = float(np.sign(self._normal_x(self._rho_tip, fp, psi))[0])

        r1, ra1 = worm.reference_radius, worm.tip_diameter / 2
        reach = ra1 * ra1 - (self.centre_distance - self.outside_diameter / 2) ** 2
        reach = 2 * math.sqrt(reach) if reach > 0 else 0.0
        root_reach = 2 * self._root_reach(reach / 2)
        if face_width is None:
            face_width = min(2 * math.sqrt(ra1 * ra1 - r1 * r1), 0.9 * root_reach)
        self.face_width = float(face_width)
        if not 0 < self.face_width < reach:
            raise BlankError(f"face width {self.face_width:.4g} mm must lie in (0, "
                             f"{reach:.4g}) mm: beyond, the worm's tip (d_a1 = "
                             f"{worm.tip_diameter:.4g} mm) no longer reaches the wheel's outside "
                             f"diameter {self.outside_diameter:.4g} mm", "face_width")
        if not self.face_width < root_reach:
            raise BlankError(f"face width {self.face_width:.4g} mm must be below "
                             f"{root_reach:.4g} mm: beyond, the hob's tip edge no longer "
                             "generates the wheel's root on its mid-face contact (the contact "
                             "runs off along the hob axis)", "face_width")
        self._tip_poly = self._fit_tip()
        self.domain = ((0.0, 1.0), (-self.face_width / 2, self.face_width / 2))
        self.edges = {"u0": "tip", "u1": "root", "v0": "end_A", "v1": "end_B"}

        # hob length: the generating region must lie on the hob
        u, v = self.grid(17, 17)
        _, hob_v, _ = self.generating_parameters(u, v)
        z = self._p * hob_v
        if np.abs(z).max() > hob.length / 2:
            raise BlankError(f"the hob is too short: generating points reach |z| = "
                             f"{np.abs(z).max():.4g} mm > L/2 = {hob.length / 2:.4g} mm",
                             "hob_length", 2 * float(np.abs(z).max()))
        self.generating_zone = (float(z.min()), float(z.max()))

        # normals out of the wheel tooth: minus the hob's outward normal at the contact
        uc, vc = np.array(0.5), np.array(0.0)
        sample = self.evaluate(uc, vc)
        raw = np.cross(sample.r_u, sample.r_v)
        self.orientation = -1.0 if float(np.dot(raw, self._hob_normal_in_wheel(uc, vc))) > 0 \
            else 1.0

    # --- data --------------------------------------------------------------------------------
    @property
    def reference_radius(self) -> float:
        """r2 = z2·mx/2 (mm), mx the worm's axial module."""
        return self.teeth * self.worm.axial_module / 2

    @property
    def ratio(self) -> float:
        """φ2/φ1 = z1/z2."""
        return self._m

    @property
    def wheel_axis(self) -> np.ndarray:
        """k2 in the hob frame (unit vector); the wheel turns by +φ1·z1/z2 about it."""
        return np.array([0.0, self._ky, self._kz])

    # --- the surface -------------------------------------------------------------------------
    def _profile(self, u):
        """f(u) and f'(u) of the hob's axial profile as jets (or plain arrays)."""
        uf = np.asarray(value(u), float)
        F = self.hob.axial_profile(_Taylor3(uf, np.ones_like(uf)))
        f0, f1, f2, f3 = (np.broadcast_to(x, uf.shape) for x in _lift3(F).d)
        return _compose(u, f0, f1, f2), _compose(u, f1, f2, f3)

    def _meshing_z(self, u, fp, c, sn):
        """z of the contact point on the line (u cos ψ, u sin ψ, z): the equation of meshing
        N·v^(12) = 0 is A + B·z = 0 (see the module docstring)."""
        p, m, a0, ky, kz = self._p, self._m, self.generating_centre_distance, self._ky, self._kz
        nx = -u * fp * c + p * sn
        ny = -u * fp * sn - p * c
        xx, xy = u * c, u * sn
        A = nx * (m * kz - 1.0) * xy + ny * (xx - m * kz * (xx - a0)) + u * m * ky * (xx - a0)
        B = -m * ky * nx
        return -A / B

    def _zeta(self, u, fp, psi):
        c, sn = cos_sin(psi)
        z = self._meshing_z(u, fp, c, sn)
        return self._ky * u * sn + self._kz * z

    def _solve_psi(self, u, v, fp, strict=True):
        """Polar angle ψ (rad) of the generating point in the hob's fixed frame. strict=False:
        NaN where Newton fails (no contact on that line), instead of an error."""
        uf, vf, fpf = np.broadcast_arrays(*(np.asarray(value(x), float) for x in (u, v, fp)))
        shape = uf.shape
        uf, vf, fpf = (x.ravel() for x in (uf, vf, fpf))
        psi = np.arcsin(np.clip(vf / (self._ky * uf), -0.95, 0.95))
        done = np.zeros(psi.shape, bool)
        active = np.arange(psi.size)
        with np.errstate(all="ignore"):
            # Newton on the points still running only: those with a contact line converge
            # in 2-4 steps; the others (no contact on their line) would run on to the end
            for _ in range(25):
                g = self._zeta(uf[active], fpf[active], Jet(psi[active], 1.0)) - vf[active]
                step = g.f / g.u
                psi[active] = np.clip(psi[active] - step, -1.5, 1.5)
                # Newton: the step just taken leaves an error of order step², so a step
                # below 1e-8 rad has converged to round-off
                converged = np.abs(step) <= 1e-8
                done[active[converged]] = True
                active = active[~converged & np.isfinite(step)]
                if active.size == 0:
                    break
        if self._kz != 0.0 and not np.all(done):
            psi[~done] = self._bracket_psi(uf[~done], vf[~done], fpf[~done])
            done = np.isfinite(psi)
        uf, vf, fpf, psi, done = (x.reshape(shape) for x in (uf, vf, fpf, psi, done))
        if not np.all(done):
            if strict:
                raise RuntimeError("worm wheel: no generating contact found (Newton failed)")
            psi = np.where(done, psi, np.nan)
        slope = self._zeta(uf, fpf, Jet(psi, 1.0)).u
        if any(isinstance(x, Jet) for x in (u, v, fp)):
            for _ in range(2):  # each step adds one exact Taylor order (slope is a float)
                psi = psi - (self._zeta(u, fp, psi) - v) / slope
        return psi

    def _normal_x(self, rho, fp, psi):
        """x-component of the hob normal N (module docstring) at radius rho, polar angle psi;
        where it vanishes, the meshing equation's z runs off to infinity."""
        return -rho * fp * np.cos(psi) + self._p * np.sin(psi)

    def _on_sheet(self, rho, v):
        """The generating contact (psi, z, phi1) at hob radius rho, wheel-axial v (plain
        arrays), and whether it is real: it exists, lies within z_b of the hob's middle, and
        on the mid-face root edge's side of the pole of z (N_x keeps the sign it has there)."""
        psi, z, phi1, fp = self._generate(rho, v, strict=False)
        with np.errstate(invalid="ignore"):
            real = (np.abs(z) <= self._z_blank) & (
                np.sign(self._normal_x(rho, fp, psi)) == self._sheet)
        return (psi, z, phi1), real

    def _root_reach(self, limit: float, samples: int = 65) -> float:
        """Largest half-width (mm, at most `limit`) up to which the hob's tip edge generates
        the wheel's root on the real sheet on both sides of the mid-plane (scan, then
        bisection)."""
        tip = self._rho_tip

        def real(v):
            v = np.atleast_1d(np.asarray(v, float))
            return (self._on_sheet(np.full_like(v, tip), v)[1]
                    & self._on_sheet(np.full_like(v, tip), -v)[1])

        v = np.linspace(0.0, limit, samples)
        good = real(v)
        if good.all():
            return limit
        k = int(np.argmin(good))
        if k == 0:
            return 0.0
        lo, hi = v[k - 1], v[k]
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if real(mid)[0] else (lo, mid)
        return lo

    def _bracket_psi(self, u, v, fp, samples=241):
        """ψ (rad) for the points Newton left (plain 1-d arrays): the root of ζ(ψ) = v in
        [-1.5, 1.5] whose generating point lies nearest the hob's middle (least |z|), by
        bisection inside a bracket of a scan; NaN where no bracket has its generating point on
        the hob (|z| <= L_hob/2). A tilted hob's z(ψ) has a pole where the hob normal's
        x-component vanishes, so ζ(ψ) is not monotonic and a start from ψ = asin(v/(k_y u))
        can fall into the wrong branch."""
        grid = np.linspace(-1.5, 1.5, samples)
        P = np.broadcast_to(grid, (u.size, samples))
        U, V, FP = (np.broadcast_to(x[:, None], P.shape) for x in (u, v, fp))
        with np.errstate(all="ignore"):
            g = self._zeta(U, FP, P) - V
            z = np.abs(self._meshing_z(U, FP, *cos_sin(P)))
            on_hob = z <= self.hob.length / 2
            bracket = (np.sign(g[:, :-1]) != np.sign(g[:, 1:])) & on_hob[:, :-1] & on_hob[:, 1:]
            cost = np.where(bracket, np.maximum(z[:, :-1], z[:, 1:]), np.inf)
            k = np.argmin(cost, axis=1)
            found = np.isfinite(cost[np.arange(u.size), k])
            lo, hi = grid[k], grid[k + 1]
            g_lo = g[np.arange(u.size), k]
            for _ in range(55):  # 3/240 rad · 2^-55: round-off
                mid = 0.5 * (lo + hi)
                g_mid = self._zeta(u, fp, mid) - v
                left = np.sign(g_mid) == np.sign(g_lo)
                lo, g_lo = np.where(left, mid, lo), np.where(left, g_mid, g_lo)
                hi = np.where(left, hi, mid)
        return np.where(found, 0.5 * (lo + hi), np.nan)

    def _generate(self, u, v, strict=True):
        """(psi, z, phi1, f') of the generating contact: hob radius u (mm), wheel axial v."""
        f, fp = self._profile(u)
        psi = self._solve_psi(u, v, fp, strict)
        z = self._meshing_z(u, fp, *cos_sin(psi))
        phi1 = psi - z / self._p + f / self._p
        return psi, z, phi1, fp

    def hob_radius(self, u, v):
        """Radius (mm) of the generating hob point at wheel parameters (u, v): linear in u
        from the fitted tip edge rho_tip(v) (u = 0) to the hob tip radius (u = 1). Beyond
        the faces (|v| > b2/2, where a gap field's lines still sample the flank continued)
        rho_tip runs on along its tangent at the face: the degree-12 fit, extrapolated,
        swung the parameter map by whole hob depths 0.3 mm past a face, and the fields'
        samples there fell on another branch of the envelope (a false gap of -1 mm next
        to the face end, ringing into its material as a dip of 2 µm: 45 GPa at the end)."""
        x = v / (self.face_width / 2)
        face = where(value(x) > 1.0, 1.0, where(value(x) < -1.0, -1.0, x))
        rho0, slope = self._tip_poly[-1], 0.0
        for c in self._tip_poly[-2::-1]:
            slope = slope * face + rho0
            rho0 = rho0 * face + c
        rho0 = rho0 + slope * (x - face)
        floor = self._floor_at(v)  # not below the hob, nor where it generates nothing
        rho0 = where(value(rho0) < value(floor), floor, rho0)
        return rho0 + u * (self._rho_tip - rho0)

    def _floor_at(self, v):
        """The generating floor at wheel-axial v (mm; array or jet): linear between its
        samples (`_fit_tip`), so its jet is that of the segment v lies on."""
        V, F = self._floor
        vf = np.asarray(value(v), float)
        i = np.clip(np.searchsorted(V, vf) - 1, 0, V.size - 2)
        slope = (F[i + 1] - F[i]) / (V[i + 1] - V[i])
        return (v - V[i]) * slope + F[i]

    def point(self, u, v):
        """(x, y, z) of the wheel flank in the wheel frame (mm) at u = depth parameter (0 on
        the tip edge, 1 on the root edge), v = wheel axial coordinate z2 (mm); arrays or jets.
        NaN where (u, v) lies beyond the region the hob generates (a contact search may probe
        there; the surface does not exist)."""
        return self._point_at_radius(self.hob_radius(u, v), v, strict=False)

    def _point_at_radius(self, rho, v, strict=True):
        """Wheel point generated by the hob point of radius rho (mm) at wheel axial v (mm)."""
        psi, z, phi1, _ = self._generate(rho, v, strict)
        return self._wheel_point(rho, psi, z, phi1)

    def _wheel_point(self, rho, psi, z, phi1):
        """The wheel-frame point of the generating contact (rho, psi, z) at hob angle phi1."""
        c, sn = cos_sin(psi)
        a_ = self.generating_centre_distance - rho * c
        b_ = -self._kz * rho * sn + self._ky * z
        zeta = self._ky * rho * sn + self._kz * z
        big_phi = self._m * phi1 + self._offset
        cp, sp = cos_sin(big_phi)
        return cp * a_ + sp * b_, -sp * a_ + cp * b_, zeta

    def generating_parameters(self, u, v):
        """(hob u, hob v, φ1): the hob point r_h(u, v) (hob u = radius, mm; hob v = screw
        angle, rad) that generates the wheel point at wheel parameters (u, v), and the hob
        angle φ1 (rad) at which it does; plain arrays."""
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        rho = self.hob_radius(u, v)
        _, z, phi1, _ = self._generate(rho, v)
        return rho, z / self._p, phi1

    def _hob_normal_in_wheel(self, u, v):
        """The hob's outward unit normal at the generating contact, in the wheel frame."""
        hu, hv, phi1 = self.generating_parameters(u, v)
        n = self.hob.evaluate(hu, hv).normals
        M = self.wheel_from_hob(phi1)
        return np.einsum("...ij,...j->...i", M[..., :3, :3], n)

    def wheel_from_hob(self, phi1, *, centre_distance: float | None = None,
                       crossing_angle: float | None = None) -> np.ndarray:
        """4×4 matrices (shape (..., 4, 4)) mapping hob-attached coordinates (hob turned by
        φ1) to wheel-attached coordinates (wheel turned by φ1·z1/z2). Defaults: the
        generating setting (a0, Σ); pass centre_distance=a, crossing_angle=pi/2 for the mesh
        with the worm."""
        a0 = self.generating_centre_distance if centre_distance is None else centre_distance
        sigma = self.crossing_angle if crossing_angle is None else crossing_angle
        ky, kz = -self._s * math.sin(sigma), math.cos(sigma)
        phi1 = np.asarray(phi1, float)
        c1, s1 = cos_sin(phi1)
        big_phi = self._m * phi1 + self._offset
        cp, sp = cos_sin(big_phi)
        W = np.array([[-1.0, 0.0, 0.0], [0.0, -kz, ky], [0.0, ky, kz]])  # rows x_w, y_w, k2
        R1 = np.zeros(phi1.shape + (3, 3))
        R1[..., 0, 0], R1[..., 0, 1], R1[..., 1, 0], R1[..., 1, 1] = c1, -s1, s1, c1
        R1[..., 2, 2] = 1.0
        R2 = np.zeros(phi1.shape + (3, 3))
        R2[..., 0, 0], R2[..., 0, 1], R2[..., 1, 0], R2[..., 1, 1] = cp, sp, -sp, cp
        R2[..., 2, 2] = 1.0
        M = np.zeros(phi1.shape + (4, 4))
        M[..., :3, :3] = R2 @ W @ R1
        M[..., :3, 3] = np.einsum("...ij,j->...i", R2 @ W, [-a0, 0.0, 0.0])
        M[..., 3, 3] = 1.0
        return M

    def inside_blank(self, points, tol: float = 1e-9) -> np.ndarray:
        """True where wheel-frame points (..., 3) (mm) lie in the DIN 3975 blank: |z2| <=
        b2/2, radius <= d_e2/2 and outside the throat torus (tube radius r_k about the circle
        of radius a in the mid-plane)."""
        P = np.asarray(points, float)
        return self._blank_margin(P) >= -tol

    def _blank_margin(self, P):
        R = np.hypot(P[..., 0], P[..., 1])
        z = P[..., 2]
        torus = np.hypot(self.centre_distance - R, z) - self.throat_radius
        return np.minimum(np.minimum(self.face_width / 2 - np.abs(z),
                                     self.outside_diameter / 2 - R), torus)

    def _fit_tip(self, samples=1025, degree=12):
        """The "tip" edge rho_tip(v): for each face position the lowest hob radius down to
        which every hob point from the hob's tip edge generates a point inside the blank (the
        real flank is the part connected to the root edge), fitted by a polynomial in
        v/(b2/2) and lowered by its largest excess over the samples plus the largest change
        of the trim curve between two samples plus 0.1 % of the hob depth, so that the domain
        contains the whole real flank. Returns the power-series coefficients.

        The lowered polynomial may pass below the hob's root (or form) radius, or below the
        floor under which the hob generates nothing near the blank at that face position: a
        hob point of radius rho reaches |z2| <= rho at most (near the faces of a wide wheel,
        and with a tilted hob, the floor rises above the hob root), and where the hob normal
        turns square to the relative motion the generating point runs off along the hob axis
        (z -> infinity; beyond the blank's reach z_b = sqrt((d_e2/2)² - (a0 - r_a,hob)²) no
        point can lie in the blank). `hob_radius` never goes below this floor, sampled here
        like the trim and kept as `_floor` (face positions, radii), raised by its largest
        second difference so that the chords between samples stay above it."""
        half = self.face_width / 2
        v = np.linspace(-half, half, samples)
        depth = self._rho_tip - self._rho_root

        def generates(rho, i):
            return self._on_sheet(rho, v[i])[1]

        def inside(rho, i):
            contact, real = self._on_sheet(rho, v[i])
            point = np.stack(self._wheel_point(rho, *contact), axis=-1)
            return real & (self._blank_margin(point) >= -1e-9)

        every = np.arange(v.size)
        tip = np.full_like(v, self._rho_tip)
        if not np.all(generates(tip, every)):
            raise BlankError(f"face width {self.face_width:.4g} mm: the hob's tip generates "
                             "no wheel root at the faces (they lie beyond the hob's reach)",
                             "face_width")
        if not np.all(inside(tip, every)):
            raise BlankError(f"face width {self.face_width:.4g} mm: the wheel's root edge "
                             "leaves the blank at the faces", "face_width")
        rho = self._lowest(inside, v)
        x = v / half
        coef = np.polynomial.polynomial.polyfit(x, rho, degree)
        fit = np.polynomial.polynomial.polyval(x, coef)
        coef[0] -= (max(float((fit - rho).max()), 0.0) + float(np.abs(np.diff(rho)).max())
                    + 1e-3 * depth)
        self._floor = (v, self._generating_floor(
            generates, np.maximum(np.polynomial.polynomial.polyval(x, coef), self._rho_root),
            rho))
        return coef

    def _generating_floor(self, generates, lowered, trim, steps=16):
        """Samples of the generating floor at the face positions of `trim` (see `_fit_tip`):
        the hob root where the whole strip between the lowered trim and the trim samples
        generates (taken as so when its lower end does: its upper end does, and a pole in
        between would flip the sheet's side), else the highest radius in that strip where it
        does not (a scan in `steps` steps, then bisection), raised where it binds by the
        largest second difference of its binding runs and 2^-30 of the hob depth."""
        root, depth = self._rho_root, self._rho_tip - self._rho_root
        every = np.arange(trim.size)
        if np.all(generates(lowered, every)):  # the same sheet at both ends of every strip
            return np.full_like(trim, root)
        failed = np.full_like(trim, np.nan)  # highest failing level
        above = trim.copy()  # the level above it (generates)
        for k in range(steps, -1, -1):
            rho = lowered + (trim - lowered) * k / steps
            bad = ~generates(rho, every) & np.isnan(failed)
            failed[bad] = rho[bad]
            if k < steps:
                above[bad] = (lowered + (trim - lowered) * (k + 1) / steps)[bad]
        binds = np.isfinite(failed)
        binding = np.flatnonzero(binds)
        floor = np.full_like(trim, root)
        if binding.size:
            lo, hi = failed[binding], above[binding]
            for _ in range(40):
                mid = 0.5 * (lo + hi)
                good = generates(mid, binding)
                hi, lo = np.where(good, mid, hi), np.where(good, lo, mid)
            floor[binding] = hi
            runs = binds[:-2] & binds[1:-1] & binds[2:]  # second differences inside runs
            curve = np.abs(np.diff(floor, 2))[runs]
            floor[binding] += (curve.max() if curve.size else 0.0) + 2.0 ** -30 * depth
        return np.minimum(floor, self._rho_tip)

    def _lowest(self, ok, v, levels=8):
        """For each face position v: the lowest hob radius r* (at least the hob root) such that
        ok(rho, i) holds for all rho in [r*, hob tip] (a scan down in `levels` steps, then
        bisection to 2^-36 of the hob depth). ok(hob tip, i) must hold; ok is evaluated only
        at the face positions i still undecided."""
        top, root = self._rho_tip, self._rho_root
        depth = top - root
        free = ok(np.full_like(v, root), np.arange(v.size))
        lo, hi = np.full_like(v, root), np.full_like(v, top)
        running = np.flatnonzero(~free)  # the positions whose scan has not failed yet
        for k in range(1, levels if running.size else 1):
            rho = np.full(running.size, top - depth * k / levels)
            good = ok(rho, running)
            hi[running[good]] = rho[good]
            lo[running[~good]] = rho[~good]
            running = running[good]
        lo[running] = root  # good down to the last level above the root: bisect to the root
        open_ = np.flatnonzero(~free)
        for _ in range(36 - int(math.log2(levels)) if open_.size else 0):
            mid = 0.5 * (lo[open_] + hi[open_])
            good = ok(mid, open_)
            hi[open_[good]], lo[open_[~good]] = mid[good], mid[~good]
        return np.where(free, root, hi)
