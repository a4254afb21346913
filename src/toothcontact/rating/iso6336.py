"""The ISO 6336 Method B rating of a cylindrical gear pair: pitting (ISO 6336-2) and tooth
bending (ISO 6336-3) with ISO 6336-1's load factors and ISO 6336-5's allowables, each
factor computed by the standard, supplied by the loaded contact where ISO allows a more
exact method (Method A: the face load factor K_Hβ), or given in the case, and named with
its source. What the case does not say is taken as ISO's neutral value and listed among the
rating's assumptions.

A pure function of plain inputs (RatedPair, Duty, the given factors, the loaded contact's
figures); analyses.rating builds them from a case. Units: mm, N, N·mm, MPa, µm for
deviations and roughness, rpm, m/s, mm²/s, kg/mm³.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..analytic.stiffness import E_STEEL, mesh_stiffness, single_stiffness
from ..surfaces.involute import CylindricalGear
from . import bending, load_factors, pitting
from .life import TREATMENTS, contact_life_factor, root_life_factor
from .root import helix_factor

#: ISO 6336-3's stress correction factor of the reference test gear (σ_FE = σ_Flim·Y_ST)
Y_ST = 2.0
#: ISO 6336-1's mesh stiffness for the face load factor, c_γβ = 0.85·c_γα
C_GAMMA_BETA_PER_ALPHA = 0.85


@dataclass(frozen=True)
class Figure:
    """One figure of the rating: its result key, ISO's symbol, value (None: not rated) and
    where it comes from (an ISO clause, the loaded contact, or 'given')."""

    key: str
    symbol: str
    value: float | None
    source: str


@dataclass(frozen=True)
class Allowable:
    """An allowable stress number (MPa) and where it comes from."""

    value: float
    source: str


@dataclass(frozen=True)
class RatedMember:
    """One gear as ISO rates it: its geometry, elastic constants, density (kg/mm³), heat
    treatment (rating.life.TREATMENTS), allowables, flank roughness Ra and root Rz (µm),
    yield strength (MPa), tip relief C_a (µm) and load cycles."""

    gear: CylindricalGear
    E: float
    nu: float
    density: float
    treatment: str | None = None
    sigma_Hlim: Allowable | None = None
    sigma_Flim: Allowable | None = None
    roughness_Ra: float | None = None
    root_roughness_Rz: float | None = None
    yield_strength: float | None = None
    tip_relief: float = 0.0
    cycles: float | None = None


@dataclass(frozen=True)
class RatedPair:
    """The pair: its members, operating centre distance (mm) and pressure angle (rad) and
    transverse contact ratio ε_α."""

    pinion: RatedMember
    gear: RatedMember
    center_distance: float
    working_pressure_angle: float
    transverse_ratio: float


@dataclass(frozen=True)
class Duty:
    """How the pair runs: the pinion's torque (N·mm) and speed (rpm; None: not given), the
    oil's viscosity at 40 °C (mm²/s), the ISO 1328-1:2013 flank tolerance class, the mesh
    misalignment f_ma and the shafts' and bodies' deflection f_sh over the face (µm, as
    ISO 6336-1 Method C takes them), whether limited pitting is accepted, the least safety
    factors."""

    torque: float
    speed: float | None = None
    viscosity_40: float | None = None
    accuracy_grade: int | None = None
    misalignment: float = 0.0
    deflection: float = 0.0
    limited_pitting: bool = False
    S_Hmin: float = 1.0
    S_Fmin: float = 1.0


@dataclass(frozen=True)
class ContactFigures:
    """What the loaded contact supplies: its face load factor K_Hβ (ISO 6336-1 Method A)
    and its mesh stiffness c_γα (N/(mm·µm)); None where it was not solved."""

    K_H_beta: float | None = None
    mesh_stiffness: float | None = None


@dataclass(frozen=True)
class Rating:
    """The rating: every figure with its source, and the assumptions it rests on."""

    figures: tuple[Figure, ...]
    assumptions: tuple[str, ...]

    def __getitem__(self, key: str) -> float | None:
        return next(f.value for f in self.figures if f.key == key)

    def values(self) -> dict[str, float | None]:
        """The figures by result key."""
        return {f.key: f.value for f in self.figures}


class _Book:
    """The figures and assumptions as the rating takes them: a given factor wins over the
    computed one and is named 'given'."""

    def __init__(self, given: dict[str, float]):
        self.given, self.figures, self.assumptions = given, [], []

    def factor(self, key: str, symbol: str, computed, source: str, default_note: str = "",
               given_as: str | None = None):
        """The factor `key`: given (as `given_as`, default `key`), else `computed()` (a
        value, or None for the neutral 1 with `default_note` among the assumptions)."""
        if (given_as or key) in self.given:
            return self.add(key, symbol, self.given[given_as or key], "given")
        value = computed() if callable(computed) else computed
        if value is None:
            self.assumptions.append(f"{symbol} = 1: {default_note}")
            return self.add(key, symbol, 1.0, f"taken as 1 ({default_note})")
        return self.add(key, symbol, value, source)

    def add(self, key: str, symbol: str, value, source: str):
        self.figures.append(Figure(key, symbol, None if value is None else float(value), source))
        return value


@dataclass(frozen=True)
class _Mesh:
    """What every part of the rating reads of the pair and its duty: signed tooth numbers
    (z2 < 0 internal), the common face width b (mm), angles (rad), contact ratios, the
    pinion's reference diameter d1 (mm), the nominal tangential load F_t there (N), the
    pitch line velocity v (m/s, None without a speed), the softer member's σ_Hlim (MPa, None
    without one), each member's running-in group and its ISO 1328 tolerances."""

    z1: int
    z2: int
    width: float
    alpha_t: float
    alpha_wt: float
    beta_b: float
    eps_a: float
    eps_b: float
    d1: float
    F_t: float
    velocity: float | None
    softer: float | None
    groups: dict
    tolerances: _Tolerances

    @property
    def eps_g(self) -> float:
        return self.eps_a + self.eps_b


@dataclass(frozen=True)
class _Loads:
    """The load factors the rating applies."""

    K_A: float
    K_v: float
    K_H_beta: float
    K_H_alpha: float
    K_F_beta: float
    K_F_alpha: float


def rate(pair: RatedPair, duty: Duty, given: dict[str, float],
         contact: ContactFigures = ContactFigures()) -> Rating:
    """The pitting and bending ratings of the pair (see the module); `given` holds factors by
    result key (case.GIVEN_FACTORS' keys)."""
    p, g = pair.pinion.gear, pair.gear.gear
    width = min(p.face_width, g.face_width)
    hlim = [m.sigma_Hlim.value for m in (pair.pinion, pair.gear) if m.sigma_Hlim is not None]
    mesh = _Mesh(p.teeth, -g.teeth if g.internal else g.teeth, width,
                 p.transverse_pressure_angle, pair.working_pressure_angle, p.base_helix_angle,
                 pair.transverse_ratio,
                 width * math.sin(p.helix_angle) / (math.pi * p.normal_module),
                 2.0 * p.pitch_radius, duty.torque / p.pitch_radius,
                 None if duty.speed is None else math.pi * 2.0 * p.pitch_radius * duty.speed
                 / 60000.0, min(hlim) if hlim else None,
                 {name: load_factors.RUNNING_IN_GROUPS[TREATMENTS[m.treatment]]
                  if m.treatment else "steel"
                  for name, m in (("pinion", pair.pinion), ("gear", pair.gear))},
                 _tolerances(pair, duty.accuracy_grade))
    book = _Book(given)
    book.add("F_t_N", "F_t", mesh.F_t, "ISO 6336-1: 2·T1/d1 at the reference circle")
    book.add("pitch_line_velocity_m_per_s", "v", mesh.velocity,
             "π·d1·n1 at the reference circle" if mesh.velocity else "no speed given")
    if duty.accuracy_grade is None:
        book.assumptions.append("no accuracy_grade: pitch, profile and helix deviations taken "
                                "as 0 in K_v, K_Hα and K_Hβ's Method C (a perfectly made pair)")
    loads = _load_factors(book, pair, duty, mesh, contact)
    _pitting(book, pair, duty, mesh, loads)
    _bending(book, pair, duty, mesh, loads)
    return Rating(tuple(book.figures), tuple(book.assumptions))


def _load_factors(book: _Book, pair: RatedPair, duty: Duty, mesh: _Mesh,
                  contact: ContactFigures) -> _Loads:
    """ISO 6336-1's K_A, K_v (Method B), K_Hβ (the loaded contact's, Method A; Method C
    beside it), K_Hα and K_Fα (Method B), K_Fβ, with ISO's stiffness c' and c_γα."""
    p, g = pair.pinion.gear, pair.gear.gear
    members = (pair.pinion, pair.gear)
    K_A = book.factor("K_A", "K_A", None, "",
                      "the application factor of uniform driving and driven machines")
    line = mesh.F_t * K_A / mesh.width
    E_pair = 2.0 * pair.pinion.E * pair.gear.E / (pair.pinion.E + pair.gear.E)
    c_single = book.add("iso_single_stiffness_N_per_mm_um", "c'", single_stiffness(
        mesh.z1, mesh.z2, p.profile_shift, g.profile_shift, p.helix_angle, p.pressure_angle,
        p.dedendum, line) * E_pair / E_STEEL, "ISO 6336-1 Method B (§9), E/E_st")
    c_mesh = book.add("iso_mesh_stiffness_N_per_mm_um", "c_γα",
                      mesh_stiffness(c_single, mesh.eps_a), "ISO 6336-1 Method B (§9)")
    velocity = mesh.velocity or 0.0
    tolerances = mesh.tolerances

    def dynamic():
        if mesh.velocity is None:
            return None
        y_p = _running_in(mesh, members, tolerances.single_pitch, velocity)
        y_f = _running_in(mesh, members, tolerances.profile_form, velocity)
        relief = _tip_relief(members, mesh.softer)
        masses = tuple(load_factors.gear_mass(
            m.gear.tip_radius + m.gear.root_radius_value, 2.0 * m.gear.base_radius,
            m.gear.root_radius_value, m.density) for m in members)
        found = load_factors.dynamic_factor(
            mesh.z1, duty.speed, masses[0] if g.internal else load_factors.reduced_mass(masses),
            c_single, c_mesh, mesh.eps_g, line, max(tolerances.single_pitch - y_p, 0.0),
            max(tolerances.profile_form - y_f, 0.0), relief)
        book.add("resonance_ratio", "N", found.resonance_ratio,
                 f"ISO 6336-1 Method B: n1/n_E1, n_E1 {found.resonance_speed:.0f} rpm "
                 f"({found.regime}; C_a {relief:.3g} µm)")
        return found.value

    K_v = book.factor("K_v", "K_v", dynamic, "ISO 6336-1 Method B (6.5)",
                      "no speed given ([operation] pinion_speed)")
    K_H_beta_C = book.add("K_H_beta_iso_C", "K_Hβ (ISO C)", _face_load_factor_C(
        pair, duty, mesh, C_GAMMA_BETA_PER_ALPHA * c_mesh, mesh.F_t * K_A * K_v / mesh.width),
        "ISO 6336-1 Method C (7.6): F_βx = 1.33·f_sh + f_ma from the case's misalignment, "
        "deflection and helix tolerances (its lead modifications not credited), y_β, c_γβ = "
        "0.85·c_γα (ISO's)")
    K_H_beta = book.factor(
        "K_H_beta_rating", "K_Hβ",
        contact.K_H_beta if contact.K_H_beta is not None else K_H_beta_C,
        "the loaded contact (ISO 6336-1 Method A: the mesh cycle's largest over mean line "
        "load)" if contact.K_H_beta is not None else "ISO 6336-1 Method C (no loaded contact)")
    Z_eps = pitting.contact_ratio_factor(mesh.eps_a, mesh.eps_b)
    deviation = max(tolerances.single_pitch
                    - _running_in(mesh, members, tolerances.single_pitch, velocity), 0.0)
    F_tH = mesh.F_t * K_A * K_v * K_H_beta / mesh.width
    K_H_alpha, K_F_alpha = load_factors.transverse_load_factors(
        mesh.eps_g, mesh.eps_a, Z_eps, contact.mesh_stiffness or c_mesh, deviation, F_tH)
    alpha_source = ("ISO 6336-1 Method B (8.3) with the loaded contact's c_γα"
                    if contact.mesh_stiffness else "ISO 6336-1 Method B (8.3)")
    K_H_alpha = book.factor("K_H_alpha", "K_Hα", K_H_alpha, alpha_source)
    book.add("K_H_alpha_iso_B", "K_Hα (ISO B)", load_factors.transverse_load_factors(
        mesh.eps_g, mesh.eps_a, Z_eps, c_mesh, deviation, F_tH)[0],
        "ISO 6336-1 Method B (8.3) with ISO's c_γα")
    depth = max(m.gear.tip_radius - m.gear.root_radius_value for m in members)
    K_F_beta = book.factor("K_F_beta", "K_Fβ", load_factors.root_face_load_factor(
        K_H_beta, mesh.width, depth), "ISO 6336-1 (7.6.6): K_Hβ^N_F")
    K_F_alpha = book.factor("K_F_alpha", "K_Fα", K_F_alpha, alpha_source)
    return _Loads(K_A, K_v, K_H_beta, K_H_alpha, K_F_beta, K_F_alpha)


def _pitting(book: _Book, pair: RatedPair, duty: Duty, mesh: _Mesh, K: _Loads) -> None:
    """ISO 6336-2: the Z factors, σ_H0, each member's σ_H, σ_HP and S_H, and S_H."""
    p, g = pair.pinion.gear, pair.gear.gear
    Z_H = book.add("Z_H", "Z_H", pitting.zone_factor(mesh.beta_b, mesh.alpha_t, mesh.alpha_wt),
                   "ISO 6336-2 (zone factor)")
    Z_E = book.add("Z_E", "Z_E", pitting.elasticity_factor(pair.pinion.E, pair.pinion.nu,
                                                           pair.gear.E, pair.gear.nu),
                   "ISO 6336-2 (elasticity factor), sqrt(MPa)")
    Z_eps = book.add("Z_epsilon", "Z_ε", pitting.contact_ratio_factor(mesh.eps_a, mesh.eps_b),
                     "ISO 6336-2 (contact ratio factor)")
    Z_beta = book.add("Z_beta", "Z_β", pitting.helix_angle_factor(p.helix_angle),
                      "ISO 6336-2 (helix angle factor)")
    single = pitting.single_pair_factors(
        mesh.z1, mesh.z2, (2.0 * p.tip_radius, 2.0 * g.tip_radius),
        (2.0 * p.base_radius, 2.0 * g.base_radius), mesh.alpha_wt, mesh.eps_a, mesh.eps_b)
    book.add("Z_B", "Z_B", single[0], "ISO 6336-2 (single pair contact factor, pinion)")
    book.add("Z_D", "Z_D", single[1], "ISO 6336-2 (single pair contact factor, gear)")
    sigma_H0 = book.add("sigma_H0_MPa", "σ_H0", pitting.nominal_contact_stress(
        Z_H, Z_E, Z_eps, Z_beta, mesh.F_t, mesh.d1, mesh.width, mesh.z2 / mesh.z1),
        "ISO 6336-2 (nominal contact stress at the pitch point)")
    sigma_H = [Z * sigma_H0 * math.sqrt(K.K_A * K.K_v * K.K_H_beta * K.K_H_alpha)
               for Z in single]
    for (name, number, Z), stress in zip((("pinion", "1", "Z_B"), ("gear", "2", "Z_D")),
                                         sigma_H):
        book.add(f"sigma_H_{name}_MPa", "σ_H" + number, stress,
                 f"ISO 6336-2: {Z}·σ_H0·sqrt(K_A·K_v·K_Hβ·K_Hα)")
    book.add("sigma_H_MPa", "σ_H", max(sigma_H), "ISO 6336-2: the larger member's")
    strength = _contact_strength(book, pair, duty, mesh)
    safeties = []
    for (name, number, member), stress in zip(
            (("pinion", "1", pair.pinion), ("gear", "2", pair.gear)), sigma_H):
        if member.sigma_Hlim is None:
            for key, symbol, unit in (("sigma_Hlim", "σ_Hlim", "_MPa"), ("Z_NT", "Z_NT", ""),
                                      ("sigma_HP", "σ_HP", "_MPa"), ("S_H", "S_H", "")):
                book.add(f"{key}_{name}{unit}", symbol + number, None,
                         f"no sigma_Hlim (or hardness and quality) for the {name}'s material")
            continue
        book.add(f"sigma_Hlim_{name}_MPa", "σ_Hlim" + number, member.sigma_Hlim.value,
                 member.sigma_Hlim.source)
        Z_NT = book.add(f"Z_NT_{name}", "Z_NT" + number, 1.0 if member.cycles is None else
                        contact_life_factor(member.treatment, member.cycles,
                                            duty.limited_pitting),
                        "ISO 6336-2 Table 2" + ("" if member.cycles is None else
                                                f" at {member.cycles:.4g} load cycles"))
        limit = member.sigma_Hlim.value * Z_NT * strength
        book.add(f"sigma_HP_{name}_MPa", "σ_HP" + number, limit / duty.S_Hmin,
                 "ISO 6336-2: σ_Hlim·Z_NT·Z_L·Z_v·Z_R·Z_W·Z_X/S_Hmin")
        safeties.append(book.add(f"S_H_{name}", "S_H" + number, limit / stress,
                                 "ISO 6336-2: σ_HG/σ_H"))
    book.add("S_H", "S_H", min(safeties) if safeties else None, "the lesser member's")
    if any(m.cycles is None and (m.sigma_Hlim or m.sigma_Flim)
           for m in (pair.pinion, pair.gear)):
        book.assumptions.append("no load cycles (rating.pinion_cycles or life): the "
                                "endurance limit, Z_NT = Y_NT = 1")


def _bending(book: _Book, pair: RatedPair, duty: Duty, mesh: _Mesh, K: _Loads) -> None:
    """ISO 6336-3: Y_β, Y_B, Y_DT, Y_ST and each member's root figures."""
    p = pair.pinion.gear
    Y_beta = book.add("Y_beta", "Y_β", helix_factor(p, mesh.eps_b),
                      "ISO 6336-3:2006 (helix angle factor)")
    book.add("Y_B", "Y_B", 1.0, "ISO 6336-3 (rim factor): solid gear blanks")
    Y_DT = book.add("Y_DT", "Y_DT", bending.deep_tooth_factor(
        mesh.eps_a / math.cos(mesh.beta_b) ** 2, duty.accuracy_grade),
        "ISO 6336-3 (deep tooth factor)")
    book.add("Y_ST", "Y_ST", Y_ST, "ISO 6336-3: the reference test gear's")
    load = K.K_A * K.K_v * K.K_F_beta * K.K_F_alpha
    for name, member in (("pinion", pair.pinion), ("gear", pair.gear)):
        _root_rating(book, name, member, mesh, Y_beta, Y_DT, load, duty)


@dataclass(frozen=True)
class _Tolerances:
    """The pair's deviations as ISO 6336-1 takes them (µm): the base pitch deviation f_pb,
    the profile form deviation f_fα and the helix slope deviation f_Hβ, each the larger
    member's tolerance of the accuracy grade (0 without one)."""

    single_pitch: float = 0.0
    profile_form: float = 0.0
    helix_slope: float = 0.0


def _tolerances(pair: RatedPair, grade: int | None) -> _Tolerances:
    """The larger member's ISO 1328-1:2013 tolerances of class `grade` (analytic.iso1328):
    f_pb = f_pT·cos α_t, f_fα = f_fαT, f_Hβ = f_HβT."""
    from ..analytic.iso1328 import flank_tolerances

    if grade is None:
        return _Tolerances()
    each = [flank_tolerances(grade, 2.0 * m.gear.pitch_radius, m.gear.normal_module,
                             m.gear.face_width) for m in (pair.pinion, pair.gear)]
    cos_alpha = math.cos(pair.pinion.gear.transverse_pressure_angle)
    return _Tolerances(max(t.single_pitch for t in each) * cos_alpha,
                       max(t.profile_form for t in each), max(t.helix_slope for t in each))


def _running_in(mesh: _Mesh, members, deviation: float, velocity: float,
                allowance=load_factors.profile_running_in) -> float:
    """The pair's running-in allowance (µm) of a deviation: the mean of the members' (ISO
    6336-1, 8.3.3 and 7.6.3), each with its own σ_Hlim (the softer one's where not given;
    neither: no allowance for a steel)."""
    each = []
    for name, member in zip(("pinion", "gear"), members):
        sigma = member.sigma_Hlim.value if member.sigma_Hlim else mesh.softer
        group = mesh.groups[name]
        each.append(0.0 if group == "steel" and sigma is None else
                    allowance(group, deviation, sigma or 1.0, velocity))
    return sum(each) / len(each)


def _tip_relief(members, softer: float | None) -> float:
    """C_a of ISO 6336-1's dynamic factor (µm): the larger member's tip relief, or without
    one the running-in tip relief C_ay, the mean of the members' (none without σ_Hlim)."""
    relief = max(m.tip_relief for m in members)
    if relief > 0.0 or softer is None:
        return relief
    return sum(load_factors.running_in_tip_relief(
        m.sigma_Hlim.value if m.sigma_Hlim else softer) for m in members) / len(members)


def _face_load_factor_C(pair: RatedPair, duty: Duty, mesh: _Mesh, c_gamma_beta: float,
                        line_load: float) -> float:
    """K_Hβ by ISO 6336-1 Method C (7.6) for what the case says: F_βx = 1.33·f_sh + f_ma,
    f_sh the case's deflection over the face (its shafts' included), f_ma the root sum of
    squares of its misalignment over the face and the members' helix slope tolerances;
    F_βy = F_βx - y_β (the members' mean running-in); K_Hβ from F_βy, c_γβ and F_m/b
    (load_factors.face_load_factor). ISO's factors crediting lead modifications (B1, B2)
    and its least F_βx are not applied: they were not at hand in a checked source."""
    helix = mesh.tolerances.helix_slope
    F_bx = 1.33 * duty.deflection + math.sqrt(duty.misalignment ** 2 + 2.0 * helix ** 2)
    y_beta = _running_in(mesh, (pair.pinion, pair.gear), F_bx, mesh.velocity or 0.0,
                         load_factors.lead_running_in)
    return load_factors.face_load_factor(max(F_bx - y_beta, 0.0), c_gamma_beta, line_load)


def _contact_strength(book: _Book, pair: RatedPair, duty: Duty, mesh: _Mesh) -> float:
    """Z_L·Z_v·Z_R·Z_W·Z_X (ISO 6336-2), each added to the book: computed from the oil, the
    speed and the flanks' roughness where the case gives them (with the softer member's
    σ_Hlim), else 1 as an assumption; Z_W 1 and Z_X 1 unless given."""
    softer = mesh.softer
    if softer is None:
        for key in ("Z_L", "Z_v", "Z_R", "Z_W", "Z_X"):
            book.add(key, key, None, "no allowable stress number: no pitting rating")
        return 1.0
    roughness = [m.roughness_Ra for m in (pair.pinion, pair.gear)]
    radius = pitting.pitch_point_relative_radius(
        (2.0 * pair.pinion.gear.base_radius, 2.0 * pair.gear.gear.base_radius),
        mesh.alpha_wt, pair.gear.gear.internal)
    Z_L = book.factor("Z_L", "Z_L", None if duty.viscosity_40 is None else
                      pitting.lubricant_factor(softer, duty.viscosity_40),
                      "ISO 6336-2 (lubricant factor) from the oil's viscosity at 40 °C",
                      "no oil given ([lubricant] viscosity_40)")
    Z_v = book.factor("Z_v", "Z_v", None if mesh.velocity is None else
                      pitting.velocity_factor(softer, mesh.velocity),
                      "ISO 6336-2 (velocity factor) at the pitch line velocity",
                      "no speed given ([operation] pinion_speed)")
    Z_R = book.factor("Z_R", "Z_R", None if None in roughness else pitting.roughness_factor(
        softer, tuple(pitting.RZ_PER_RA * r for r in roughness), radius),
        f"ISO 6336-2 (roughness factor) from the flanks' Ra (Rz = {pitting.RZ_PER_RA:g}·Ra)",
        "no flank roughness given ([pinion] / [gear] roughness_Ra)")
    Z_W = book.factor("Z_W", "Z_W", None, "", "no work hardening credited (ISO 6336-2's "
                      "Z_W >= 1 for a soft gear run with a hardened, smooth pinion)")
    Z_X = book.factor("Z_X", "Z_X", 1.0, "ISO 6336-2:2019 (size factor: 1 for through-"
                      "hardened teeth and case depths as the standard asks)")
    return Z_L * Z_v * Z_R * Z_W * Z_X


def _root_rating(book: _Book, name: str, member: RatedMember, mesh: _Mesh, Y_beta: float,
                 Y_DT: float, load: float, duty: Duty) -> None:
    """The member's ISO 6336-3 figures into the book: Y_F, Y_S, σ_F0 (its face width at most
    the common one and a module each side), σ_F = σ_F0·load (K_A·K_v·K_Fβ·K_Fα), and with
    its σ_Flim Y_NT, Y_δrelT, Y_RrelT, Y_X, σ_FP and S_F."""
    number = "1" if name == "pinion" else "2"
    keys = [("Y_F", "Y_F"), ("Y_S", "Y_S"), ("sigma_F0", "σ_F0"), ("sigma_F", "σ_F"),
            ("sigma_Flim", "σ_Flim"), ("Y_NT", "Y_NT"), ("Y_delta_rel_T", "Y_δrelT"),
            ("Y_R_rel_T", "Y_RrelT"), ("Y_X", "Y_X"), ("sigma_FP", "σ_FP"), ("S_F", "S_F")]

    def key(base: str) -> str:
        return f"{base}_{name}" + ("_MPa" if base.startswith("sigma") else "")

    gear = member.gear
    if gear.internal:
        for base, symbol in keys:
            book.add(key(base), symbol + number, None,
                     "an internal gear's root is not rated (ISO 6336-3's internal form "
                     "factor is not implemented)")
        return
    face = min(gear.face_width, mesh.width + 2.0 * gear.normal_module)
    form = bending.form_factors(gear, mesh.eps_a)
    book.add(key("Y_F"), "Y_F" + number, form.Y_F,
             f"ISO 6336-3 Method B at d_en = {form.d_en:.4g} mm (h_Fe {form.h_Fe:.4g}, "
             f"s_Fn {form.s_Fn:.4g} mm, α_Fen {math.degrees(form.alpha_Fen):.4g}°)")
    book.add(key("Y_S"), "Y_S" + number, form.Y_S,
             f"ISO 6336-3 Method B (ρ_F {form.rho_F:.4g} mm)")
    sigma_F0 = book.add(key("sigma_F0"), "σ_F0" + number, bending.nominal_root_stress(
        mesh.F_t, face, gear.normal_module, form.Y_F, form.Y_S, Y_beta, 1.0, Y_DT),
        f"ISO 6336-3: F_t/(b·m_n)·Y_F·Y_S·Y_β·Y_B·Y_DT, b = {face:g} mm")
    sigma_F = book.add(key("sigma_F"), "σ_F" + number, sigma_F0 * load,
                       "ISO 6336-3: σ_F0·K_A·K_v·K_Fβ·K_Fα")
    if member.sigma_Flim is None:
        for base, symbol in keys[4:]:
            book.add(key(base), symbol + number, None,
                     f"no sigma_Flim (or hardness and quality) for the {name}'s material")
        return
    book.add(key("sigma_Flim"), "σ_Flim" + number, member.sigma_Flim.value,
             member.sigma_Flim.source)
    strength = book.add(key("Y_NT"), "Y_NT" + number, 1.0 if member.cycles is None else
                        root_life_factor(member.treatment, member.cycles),
                        "ISO 6336-3 Table 1" + ("" if member.cycles is None else
                                                f" at {member.cycles:.4g} load cycles"))
    for base, symbol, value, source, neutral in bending.material_factors(
            TREATMENTS[member.treatment], form, member.yield_strength,
            member.root_roughness_Rz, gear.normal_module):
        strength *= book.factor(key(base), symbol + number, value, source,
                                f"{name}: {neutral}", given_as=base)
    limit = member.sigma_Flim.value * Y_ST * strength
    book.add(key("sigma_FP"), "σ_FP" + number, limit / duty.S_Fmin,
             "ISO 6336-3: σ_Flim·Y_ST·Y_NT·Y_δrelT·Y_RrelT·Y_X/S_Fmin")
    book.add(key("S_F"), "S_F" + number, limit / sigma_F, "ISO 6336-3: σ_FG/σ_F")
