"""A member's flank modifications as its case gives them (crowns, reliefs, slopes, twist,
measured topography and K-charts, tip edges and end chamfers), built on its gear and
checked against it: each a drop along the normal (surfaces.modify). Units: mm, rad."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .case import CrownSpec, EndChamferSpec, Member, TipEdgeSpec
from .surfaces.involute import CylindricalGear, inv
from .surfaces.modify import (
    RELIEF_BLEND,
    EndChamfer,
    EndRelief,
    FlankModifications,
    HelixSlope,
    LeadCrown,
    ProfileCrown,
    ProfileSlope,
    RootRelief,
    TipEdge,
    TipRelief,
    Topography,
    Twist,
)


def check_crown_span(crown: CrownSpec, face_width: float, field: str) -> None:
    """Refuse a crown whose arc does not reach the farther face end from its centre, or
    whose centre lies off the face."""
    if not abs(crown.center) < 0.5 * face_width:
        raise ValueError(f"{field}.center: {crown.center:.4g} mm must lie on the face, within "
                         f"±{0.5 * face_width:.4g} mm of mid-face")
    reach = 0.5 * face_width + abs(crown.center)
    if crown.radius is not None and not crown.radius > reach:
        raise ValueError(f"{field}.radius: {crown.radius:.4g} mm must exceed {reach:.4g} mm, "
                         "the distance from the crown's centre to the farther face end (a "
                         "smaller arc does not span the face)")


def tip_thickness(gear: CylindricalGear) -> float:
    """Transverse tooth thickness (arc, mm) on the tip circle: 2·r_a·(s/(2r) ± inv(alpha_t)
    ∓ inv(alpha_a)), cos(alpha_a) = r_b/r_a (ISO 21771; lower signs for a ring, whose tooth
    widens outward). NaN for a ring whose tip circle lies inside its base circle."""
    ra, rb = gear.tip_radius, gear.base_radius
    if ra < rb:
        return math.nan
    half = gear.tooth_thickness / (2 * gear.pitch_radius)
    sign = -1.0 if gear.internal else 1.0
    return 2 * ra * (half + sign * (inv(gear.transverse_pressure_angle)
                                    - inv(math.acos(rb / ra))))


def modifications(member: Member, gear: CylindricalGear, name: str) -> FlankModifications:
    """The member's modifications, with diameters turned into roll lengths rb·t."""
    crown = member.crown
    if crown is not None:
        check_crown_span(crown, gear.face_width, f"{name}.crown")
    lo, hi = sorted((2 * gear.base_radius, 2 * gear.tip_radius))
    tip, root = member.tip_relief, member.root_relief
    for key, relief in (("tip_relief", tip), ("root_relief", root)):
        if relief is not None and not lo < relief.start_diameter < hi:
            raise ValueError(f"{name}.{key}.start_diameter: {relief.start_diameter:.4g} mm "
                             f"must lie between the base diameter {lo:.4g} mm and the tip "
                             f"{hi:.4g} mm")
    if tip is not None and root is not None and \
            (root.start_diameter >= tip.start_diameter) != gear.internal:
        raise ValueError(f"{name}.root_relief.start_diameter: {root.start_diameter:.4g} mm must "
                         "lie between the form circle and the tip relief's start "
                         f"({tip.start_diameter:.4g} mm)")

    def roll(diameter: float) -> float:
        """The roll length (mm) at a diameter of the flank."""
        return float(gear.base_radius * gear.roll_angle(0.5 * diameter))

    def blend(relief, length: float | None = None) -> float:
        """A relief's blend as a share of its length (mm; `length` for a root relief, the
        start's distance to the form circle): the case's, else RELIEF_BLEND."""
        if relief.blend is None:
            return RELIEF_BLEND
        if length is None:
            length = abs(roll(2.0 * gear.tip_radius) - roll(relief.start_diameter))
        return relief.blend / length

    mods = FlankModifications(
        tip_edge=tip_edge(member.tip_edge, gear, f"{name}.tip_edge"),
        lead_crown=None if crown is None else LeadCrown(crown.radius, crown.height, crown.shape,
                                                        crown.center),
        profile_crown=None if member.profile_crown is None else ProfileCrown(
            member.profile_crown.height, member.profile_crown.shape),
        tip_relief=None if tip is None else TipRelief(tip.amount, roll(tip.start_diameter),
                                                      tip.shape, blend(tip)),
        root_relief=None if root is None else RootRelief(
            root.amount, roll(root.start_diameter), root.shape,
            blend(root, None if root.blend is None else abs(
                roll(root.start_diameter) - _form_roll(gear)))),
        helix_slope=None if member.helix_slope is None else HelixSlope(member.helix_slope.amount),
        profile_slope=None if member.profile_slope is None else ProfileSlope(
            member.profile_slope.amount),
        twist=None if member.twist is None else Twist(member.twist.amount),
        topography=(k_chart(member.k_chart, gear, f"{name}.k_chart")
                    if member.k_chart is not None
                    else topography(member.topography, gear, f"{name}.topography")),
        end_relief=None if member.end_relief is None else EndRelief(
            member.end_relief.amount, member.end_relief.length, member.end_relief.shape,
            RELIEF_BLEND if member.end_relief.blend is None
            else member.end_relief.blend / member.end_relief.length),
        end_chamfer=end_chamfer(member.end_chamfer, gear.normal_module, gear.face_width,
                                f"{name}.end_chamfer"))
    check_slopes(mods, gear, name, "k_chart" if member.k_chart is not None else "topography")
    return mods


#: each modification (their tables in a case) checked by check_slopes; the tip edge and
#: the end chamfer are the flank's edges, drawn, not deviations of it
SLOPED = {"lead_crown": "crown", "profile_crown": "profile_crown", "tip_relief": "tip_relief",
          "root_relief": "root_relief", "helix_slope": "helix_slope",
          "profile_slope": "profile_slope", "twist": "twist", "end_relief": "end_relief",
          "topography": "topography"}
#: samples per side of the flank on which check_slopes measures each modification
SLOPE_SAMPLES = 81
#: the largest drop (either sign, in normal modules) of the modifications that tilt the
#: whole flank (a helix or profile slope, a twist): they correct a lead or profile
#: deviation of the size ISO 1328's tolerances give (tens of µm), and half of one adds
#: material; a twentieth of a module (150 µm at m_n = 3 mm, twice ISO 1328-1 class 11's
#: profile slope tolerance there) is taken as the most, an assumed bound: a twist of 1 mm
#: on a 3 mm module put whole positions' contacts off both flanks
TILT_MODULES = 0.05
TILTS = ("helix_slope", "profile_slope", "twist")


def check_slopes(mods: FlankModifications, gear: CylindricalGear, name: str,
                 measured: str = "topography") -> None:
    """Refuse (ValueError naming the table) a modification whose drop turns the flank by
    more than a misalignment may (units' slope limit, 0.1 rad) anywhere on its face and
    active profile, or a slope or twist whose drop reaches beyond TILT_MODULES of the
    normal module: a modification is a small deviation from the involute and the helix
    (DESIGN principle 2: a displacement along the normal), and a larger one moves the
    contact onto an edge or off the flank. `measured`: the table a topography came from."""
    from . import units

    present = [field for field in SLOPED if getattr(mods, field) is not None]
    if not present:
        return
    limit = units.KINDS["slope"].largest
    s_tip = float(gear.base_radius * gear.roll_angle(gear.tip_radius))
    s_form = _form_roll(gear)
    w = np.linspace(-0.5 * gear.face_width, 0.5 * gear.face_width, SLOPE_SAMPLES)
    s = np.linspace(min(s_form, s_tip), max(s_form, s_tip), SLOPE_SAMPLES)
    W, S = np.meshgrid(w, s, indexing="ij")
    for modification in present:
        drop = FlankModifications(**{modification: getattr(mods, modification)}).drop(
            W, S, gear.face_width, s_form, s_tip)
        along_face, along_profile = np.gradient(drop, w, s)
        steepest = float(np.max(np.hypot(along_face, along_profile)))
        table = measured if modification == "topography" else SLOPED[modification]
        if not steepest <= limit:
            raise ValueError(f"{name}.{table}: its drop turns the flank by up to "
                             f"{steepest:.3g} rad over the {gear.face_width:.4g} mm face and "
                             f"{abs(s_tip - s_form):.4g} mm of active profile (roll length); "
                             f"at most {limit:g} rad, as a misalignment: a modification is a "
                             "small deviation from the involute and the helix")
        largest, most = float(np.max(np.abs(drop))), TILT_MODULES * gear.normal_module
        if modification in TILTS and not largest <= most:
            raise ValueError(f"{name}.{table}: its drop reaches ±{largest:.4g} mm over the "
                             f"flank, beyond {TILT_MODULES:g} of the normal module "
                             f"({most:.4g} mm): a slope or twist corrects deviations of tens "
                             "of µm")


#: points along each trace of a K-chart
K_CHART_SAMPLES = 61


def k_chart_traces(mods: FlankModifications, gear: CylindricalGear) -> dict:
    """A member's modifications as a K-chart shows them, as made (crowns, slopes, twist,
    reliefs, topography and the tip edge together): the profile trace at mid-face over the
    active profile (form to tip diameter) and the lead trace at mid-profile over the face;
    drops in µm along the flank's normal, positive where material is removed."""
    s_tip = float(gear.base_radius * gear.roll_angle(gear.tip_radius))
    s_form = _form_roll(gear)
    s = np.linspace(min(s_form, s_tip), max(s_form, s_tip), K_CHART_SAMPLES)
    w = np.linspace(-0.5 * gear.face_width, 0.5 * gear.face_width, K_CHART_SAMPLES)
    s_mid = 0.5 * (s_form + s_tip)
    profile = mods.drop(np.zeros_like(s), s, gear.face_width, s_form, s_tip)
    lead = mods.drop(w, np.full_like(w, s_mid), gear.face_width, s_form, s_tip)
    return {"profile_diameter_mm": (2.0 * np.hypot(gear.base_radius, s)).tolist(),
            "profile_um": (1e3 * np.broadcast_to(profile, s.shape)).tolist(),
            "lead_face_mm": w.tolist(),
            "lead_um": (1e3 * np.broadcast_to(lead, w.shape)).tolist(),
            "lead_diameter_mm": float(2.0 * np.hypot(gear.base_radius, s_mid))}


def _form_roll(gear: CylindricalGear) -> float:
    """The roll length (mm) of a member's generated form circle."""
    from .surfaces.generation import generate_ring_side, generate_side

    form = (generate_ring_side(gear) if gear.internal else generate_side(gear)).form_radius
    return float(gear.base_radius * gear.roll_angle(form))


def _rolls(diameters, gear: CylindricalGear, field: str) -> list[float]:
    """Roll lengths (mm) of a member's diameters, which must lie on the involute."""
    base = 2 * gear.base_radius
    if not diameters[0] > base:
        raise ValueError(f"{field}: {diameters[0]:.4g} mm must lie above the base diameter "
                         f"{base:.4g} mm (the involute starts there)")
    return [float(gear.base_radius * gear.roll_angle(0.5 * d)) for d in diameters]


def topography(spec, gear: CylindricalGear, field: str) -> Topography | None:
    """A member's topography grid on its flank: diameters turned into roll lengths, µm into
    mm."""
    if spec is None:
        return None
    where = (f"{field}.diameter" if spec.file is None else
             f"{field}.file: {Path(spec.file).name} row 1 (the diameters)")
    return Topography(spec.face, _rolls(spec.diameter, gear, where),
                      np.asarray(spec.deviation_um) * 1e-3)


#: traces of a K-chart that disagree by more than this (µm) where they cross get a note
K_CHART_CROSSING_UM = 1.0


def k_chart(spec, gear: CylindricalGear, field: str) -> Topography:
    """A member's measured K-chart as its topography (modify.k_chart_grid) over the lead
    traces' face positions × the profile traces' diameters; a note where the two families
    of traces disagree by more than K_CHART_CROSSING_UM where they cross."""
    import warnings

    from .surfaces.modify import k_chart_grid

    profile_roll = _rolls(spec.profile_diameter, gear, f"{field}.profile_diameter")
    lead_roll = _rolls(spec.lead_diameter, gear, f"{field}.lead_diameter")
    grid, crossing = k_chart_grid(spec.profile_face, profile_roll, spec.profile_um, lead_roll,
                                  spec.lead_face, spec.lead_um)
    if crossing > K_CHART_CROSSING_UM:
        warnings.warn(f"{field}: the profile and lead traces differ by up to {crossing:.2f} µm "
                      "where they cross; the topography takes their mean there", stacklevel=2)
    return Topography(spec.lead_face, profile_roll, grid * 1e-3)


#: the tip edge rounding a member gets where its case gives none, in normal modules: the
#: edge break "tip edges rounded 0.1·m_n" of a gear drawing (0.3 mm at m_n = 3, 1.4 mm at
#: 14), or the largest that fits where it does not
DEFAULT_TIP_EDGE_MODULES = 0.1


def tip_edge(spec: TipEdgeSpec | None, gear: CylindricalGear, field: str,
             default_modules: float = DEFAULT_TIP_EDGE_MODULES) -> TipEdge | None:
    """A gear's tip edge rounding: the case's `spec` at `field` ('0 mm': a sharp edge, None),
    else `default_modules`·m_n (0: sharp) or the largest that fits; checked to fit the tooth:
    it starts on the involute above the form circle (inside it on a ring), and its tangent
    length, on the flank and on the tip land alike, leaves room for the other flank's on the
    top land. A given radius that does not fit is refused, naming the largest that does."""
    from .surfaces.generation import generate_ring_side, generate_side

    given = spec.radius if spec is not None else None
    radius = default_modules * gear.normal_module if given is None else given
    if spec is not None and spec.chamfer is not None:
        return _tip_chamfer(spec, radius, gear, field)
    if radius == 0.0:
        return None
    form = (generate_ring_side(gear) if gear.internal else generate_side(gear)).form_radius
    edge = _fitting_tip_edge(gear, form, radius)
    if edge is not None:
        return edge
    largest = largest_tip_edge(gear, form)
    if given is None:
        return _fitting_tip_edge(gear, form, largest) if largest > 0.0 else None
    raise ValueError(f"{field}.radius: {radius:.4g} mm must be at most {largest:.3g} mm: "
                     "the rounding must start on the involute "
                     f"{'inside' if gear.internal else 'above'} the form diameter "
                     f"{2 * form:.4g} mm and leave room on the top land "
                     f"({tip_thickness(gear):.3g} mm) for the other flank's")


#: the longest tip chamfer, as a share of the involute's radius of curvature at its edge
CHAMFER_PER_CURVATURE_RADIUS = 0.1


def _tip_chamfer(spec: TipEdgeSpec, radius: float, gear: CylindricalGear,
                 field: str) -> TipEdge:
    """A tip chamfer (modify.TipEdge with an angle) of the case's `spec`, its edge on the
    flank rounded by `radius` (mm); checked to turn less than the corner between flank and
    tip land, to be short against the involute's curvature, to start on the involute and
    to leave a top land."""
    from .surfaces.generation import generate_ring_side, generate_side

    rb, ra = gear.base_radius, gear.tip_radius
    corner = 0.5 * math.pi - math.acos(min(rb / ra, 1.0))
    if not spec.angle < corner:
        raise ValueError(f"{field}.angle: {math.degrees(spec.angle):.4g} deg must be less than "
                         f"{math.degrees(corner):.3g} deg, the turn from the flank onto the "
                         "tip land (90 deg less the pressure angle at the tip)")
    s_tip = math.sqrt(max(ra**2 - rb**2, 0.0))
    s_edge = math.sqrt(max(s_tip**2 + (1.0 if gear.internal else -1.0) * 2.0 * rb * spec.chamfer,
                           0.0))
    if not spec.chamfer <= CHAMFER_PER_CURVATURE_RADIUS * s_edge:
        raise ValueError(f"{field}.chamfer: {spec.chamfer:.4g} mm must be at most "
                         f"{CHAMFER_PER_CURVATURE_RADIUS * s_edge:.3g} mm, a tenth of the "
                         "involute's radius of curvature at its edge (the chamfer's drop is "
                         "straightened to second order in the involute's turn along it)")
    form = (generate_ring_side(gear) if gear.internal else generate_side(gear)).form_radius
    try:
        edge = TipEdge.on(radius, rb, ra, gear.internal, spec.chamfer, spec.angle)
        start = math.hypot(edge.start, rb)
        on_flank = start < form if gear.internal else start > form
    except ValueError:
        on_flank = False
    if not on_flank:
        raise ValueError(f"{field}.chamfer: {spec.chamfer:.4g} mm with its edge rounded by "
                         f"{radius:.4g} mm must start on the involute "
                         f"{'inside' if gear.internal else 'above'} the form diameter "
                         f"{2 * form:.4g} mm")
    land_cut = float(edge.drop(np.array(s_tip), s_tip)) / math.sin(corner)
    if not 2.0 * land_cut < tip_thickness(gear):
        raise ValueError(f"{field}.chamfer: {spec.chamfer:.4g} mm at "
                         f"{math.degrees(spec.angle):.4g} deg cuts {land_cut:.3g} mm into the "
                         f"top land from each flank: the land is {tip_thickness(gear):.3g} mm")
    return edge


def end_chamfer(spec: EndChamferSpec | None, normal_module: float, face_width: float,
                field: str) -> EndChamfer | None:
    """A member's face-end chamfer (modify.EndChamfer) of the case's `spec` at `field`, its
    edge on the flank rounded by the given radius or 0.1 normal modules (mm); checked to
    turn less than 90 deg and to leave the middle of the face (mm)."""
    if spec is None:
        return None
    if not spec.angle < 0.5 * math.pi:
        raise ValueError(f"{field}.angle: {math.degrees(spec.angle):.4g} deg must be less than "
                         "90 deg (the chamfer's angle to the flank)")
    radius = DEFAULT_TIP_EDGE_MODULES * normal_module if spec.radius is None else spec.radius
    chamfer = EndChamfer(spec.length, spec.angle, radius)
    if not chamfer.start(face_width) > 0.0:
        raise ValueError(f"{field}.length: {spec.length:.4g} mm with its edge rounded by "
                         f"{radius:.4g} mm must leave the middle of the {face_width:.4g} mm face")
    return chamfer


def largest_tip_edge(gear: CylindricalGear, form: float) -> float:
    """The largest tip edge rounding (mm, to 0.1 %, rounded down) that fits the gear (see
    tip_edge); 0 where none does."""
    lo, hi = 0.0, gear.tip_radius
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _fitting_tip_edge(gear, form, mid) else (lo, mid)
    return 0.999 * lo


def _fitting_tip_edge(gear: CylindricalGear, form: float, radius: float) -> TipEdge | None:
    """The rounding of `radius` (mm) on the gear's tip if it fits (see tip_edge), else None."""
    try:
        edge = TipEdge.on(radius, gear.base_radius, gear.tip_radius, gear.internal)
    except ValueError:
        return None
    start = math.hypot(edge.start, gear.base_radius)
    alpha_a = math.acos(min(gear.base_radius / gear.tip_radius, 1.0))
    tangent = radius * math.tan(0.5 * (0.5 * math.pi - alpha_a))
    on_flank = start < form if gear.internal else start > form
    return edge if on_flank and 2.0 * tangent <= tip_thickness(gear) else None
