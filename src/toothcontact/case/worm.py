"""The worm kinds' case schemas: a worm set (worm, wheel, hob, misalignment, load, spring)
and the worm-gear efficiency case (conditions, the published figures it checks)."""

from __future__ import annotations

import math
from typing import Literal

from pydantic import (
    Field,
    model_validator,
)

from .cylindrical import DEFAULT_STEEL, AnalysisSpec, EndChamferSpec, ExportSpec, ShaftSpec, TipEdgeSpec
from .fields import (
    ROUGHNESS_FIELD,
    Angle,
    CaseInfo,
    Efficiency,
    Factor,
    Friction,
    Length,
    LubricantSpec,
    Material,
    Model,
    Modulus,
    Roughness,
    SignedLength,
    SignedTorque,
    Slope,
    Stiffness,
    Temperature,
    Torque,
    Viscosity,
    WormOperationSpec,
    lubricated_pair,
)

#: DIN 3975 worm root depth below the pitch diameter, in axial modules (d_f1 = d1 - 2.4·mx)
ROOT_DEPTH = 2.4


#: a worm's profile angle (deg): 20 in most sets, 15 to 30 in practice
WORM_PRESSURE_ANGLE = (10.0, 40.0)


class WormSpec(Model):
    """The worm: flank form, starts, module and lead, hand, profile angle, length."""

    form: Literal["ZA", "ZN", "ZI", "ZK"] = "ZI"
    starts: int = Field(ge=1, le=12, description="worm starts z1 (1..12)")
    normal_module: Length | None = None
    axial_module: Length | None = None
    lead_angle: Angle | None = None
    pitch_diameter: Length | None = None
    hand: Literal["right", "left"] = "right"
    pressure_angle: Angle = Field(description="axial angle for ZA, normal for ZN/ZI, grinding-"
                                              "wheel angle for ZK, e.g. '20 deg'")
    length: Length = Field(description="threaded length, e.g. '30 mm'")
    grinding_wheel_diameter: Length = Field(250.0, description="ZK only")
    tip_edge: TipEdgeSpec | None = Field(
        None, description="the thread's tip edges as made: a rounding (radius) or a rounded "
                          "chamfer; none given: rounded by 0.1 normal modules")
    shaft: ShaftSpec | None = Field(
        None, description="the worm shaft: bearings and diameters along the worm axis from "
                          "the mesh (the worm's middle); the mesh force bends it, and its "
                          "deflection at the mesh moves the worm against the wheel")
    roughness_Ra: Roughness | None = ROUGHNESS_FIELD

    @model_validator(mode="after")
    def _choices(self):
        if (self.normal_module is None) == (self.axial_module is None):
            raise ValueError("worm.normal_module / worm.axial_module: give exactly one of them")
        if (self.lead_angle is None) == (self.pitch_diameter is None):
            raise ValueError("worm.lead_angle / worm.pitch_diameter: give exactly one of them")
        if self.lead_angle is not None and not 0 < self.lead_angle < math.radians(45):
            raise ValueError("worm.lead_angle: must lie between 0 and 45 deg")
        low, high = WORM_PRESSURE_ANGLE
        if not low <= math.degrees(self.pressure_angle) <= high:
            raise ValueError(f"worm.pressure_angle: {math.degrees(self.pressure_angle):.4g} deg "
                             f"must lie between {low:g} and {high:g} deg")
        return self

    def axial_module_and_pitch_diameter(self) -> tuple[float, float]:
        """(mx, d1) in mm from the given module and lead angle or pitch diameter (DIN 3975:
        mx = mn/cos(gamma), tan(gamma) = z1·mx/d1, sin(gamma) = z1·mn/d1)."""
        if self.lead_angle is not None:
            mx = self.axial_module or self.normal_module / math.cos(self.lead_angle)
            return mx, self.starts * mx / math.tan(self.lead_angle)
        d1 = self.pitch_diameter
        if self.axial_module is not None:
            return self.axial_module, d1
        return self.normal_module / math.cos(math.asin(self.starts * self.normal_module / d1)), d1


class WheelSpec(Model):
    """The worm wheel and the hob that cuts it (identical to the worm, or oversized)."""

    teeth: int = Field(ge=10, description="wheel teeth z2 (>= 10)")
    face_width: Length | None = None
    profile_shift: float = Field(0.0, ge=-1.0, le=1.0, description="x2, in [-1, 1]")
    hob_pitch_diameter: Length | None = Field(
        None, description="pitch diameter of an oversized hob with the worm's lead; "
                          "default: the worm's (line contact)")
    align_hob_thread: bool = Field(False, description="tilt an oversized hob to the worm's thread")
    tip_edge: TipEdgeSpec | None = Field(
        None, description="the teeth's tip edges on the throat as made: a rounding (radius) "
                          "or a rounded chamfer; none given: rounded by 0.1 normal modules")
    rim_chamfer: EndChamferSpec | None = Field(
        None, description="a chamfer where the teeth's flanks meet the rim's faces (length "
                          "along the face, angle, the rounding of its edge); none given: flush "
                          "faces")
    roughness_Ra: Roughness | None = ROUGHNESS_FIELD


class WormMisalignmentSpec(Model):
    center_distance_error: SignedLength = Field(0.0, description="e.g. '0.05 mm'")
    shaft_angle_error: Slope = Field(0.0, description="crossing angle - 90 deg, rad")
    wheel_axial_shift: SignedLength = Field(0.0, description="along the wheel axis")
    worm_tilt: Slope = Field(0.0, description="worm shaft tilt about its mount, rad")
    mount: SignedLength = Field(0.0, description="the mount's axial position on the "
                                                         "worm, from the mesh")


class WormLoadSpec(Model):
    output_torque: Torque = Field(description="on the wheel, e.g. '20 N*m'")
    flank: Literal["left", "right"] = Field(
        "left", description="the loaded worm flank: 'left' faces -z, 'right' faces +z")


class SpringSpec(Model):
    """Seed 001's anti-rattle spring: it tilts the worm shaft by its force (eqs 20-21)."""

    stiffness: Stiffness = Field(description="spring rate, e.g. '30 N/mm'")
    d1: Length = Field(description="mesh to spring, along the worm shaft")
    d2: Length = Field(description="mount to mesh, along the worm shaft")
    mount_moment: SignedTorque = Field(description="moment held at the mount")


class WormCase(CaseInfo):
    """A worm set: the worm's flanks and the wheel enveloped by the hob; with a load, the
    contact over the mesh cycle."""

    kind: Literal["worm"]
    worm: WormSpec
    wheel: WheelSpec
    material: Material = Field(DEFAULT_STEEL, description="worm, default steel")
    wheel_material: Material | None = None
    misalignment: WormMisalignmentSpec = WormMisalignmentSpec()
    anti_rattle_spring: SpringSpec | None = None
    load: WormLoadSpec | None = None
    operation: WormOperationSpec | None = Field(
        None, description="worm speed and oil temperature: with [lubricant], the lubricated "
                          "contact (sliding, film, flash temperature, losses)")
    lubricant: LubricantSpec | None = None
    analysis: AnalysisSpec = Field(AnalysisSpec(positions=7, grid=(11, 121)),
                                   description="positions per worm turn/start, grid")
    export: ExportSpec = ExportSpec()

    @model_validator(mode="after")
    def _lubricated(self):
        lubricated_pair(self, {"worm": (self.worm, self.material),
                               "wheel": (self.wheel, self.wheel_material or self.material)},
                        friction_needed=True)
        return self

    @model_validator(mode="after")
    def _proportions(self):
        """The worm's pitch diameter clears its thread depth; the hob is not smaller."""
        w = self.worm
        if w.pitch_diameter is not None and w.normal_module is not None and \
                not w.starts * w.normal_module < w.pitch_diameter:
            raise ValueError(f"worm.pitch_diameter: {w.pitch_diameter:.4g} mm must exceed "
                             f"z1·m_n = {w.starts * w.normal_module:.4g} mm "
                             "(sin(lead angle) = z1·m_n/d1)")
        mx, d1 = w.axial_module_and_pitch_diameter()
        if not d1 > ROOT_DEPTH * mx:  # the DIN 3975 root diameter d1 - 2.4·mx must be > 0
            field = "lead_angle" if w.lead_angle is not None else "pitch_diameter"
            given = (f"{math.degrees(w.lead_angle):.4g} deg" if w.lead_angle is not None
                     else f"{d1:.4g} mm")
            limit = (f"below {math.degrees(math.atan(w.starts / ROOT_DEPTH)):.4g} deg for "
                     f"{w.starts} start(s)" if w.lead_angle is not None
                     else f"above {ROOT_DEPTH * mx:.4g} mm")
            raise ValueError(f"worm.{field}: {given} gives a pitch diameter d1 = {d1:.4g} mm "
                             f"within the thread depth: the root diameter d1 - 2.4·mx must be "
                             f"> 0, so the {field.replace('_', ' ')} must lie {limit}")
        hob = self.wheel.hob_pitch_diameter
        if hob is not None and not hob >= d1:
            raise ValueError(f"wheel.hob_pitch_diameter: {hob:.4g} mm must be at least the "
                             f"worm's pitch diameter {d1:.4g} mm (a hob smaller than the worm "
                             "cuts a wheel the worm does not fit)")
        return self


class Condition(Model):
    temperature: Temperature = Field(description="e.g. '-50 degC'")
    viscosity: Viscosity = Field(description="kinematic viscosity, e.g. '30000 mm^2/s'")
    eta_spindle: Efficiency | None = Field(None, description="efficiency of what follows the worm set")
    published_eta_total: Efficiency | None = None
    published_eta_z: Efficiency | None = None
    published_mu_zm: Friction | None = None


class Din3996(Model):
    mu_0T: Friction = Field(description="base friction of DIN 3996, e.g. 0.047")
    Y_S: Factor = 1.0
    Y_G: Factor = 1.0
    Y_W: Factor = 1.0
    Y_R: Factor = 1.0


class AntiRattleSpring(Model):
    """Seed 001 Fig. 6: the worm shaft pivots at its mount, meshes at d2 and is held by a
    spring of stiffness k at d1 + d2."""

    stiffness: Stiffness = Field(description="spring rate, e.g. '30 N/mm'")
    d1: Length = Field(description="mesh to spring, along the worm shaft")
    d2: Length = Field(description="mount to mesh, along the worm shaft")
    mount_moment: SignedTorque = Field(description="moment held at the mount, e.g. '3.3 N*m'")
    output_torques: list[SignedTorque] = Field(min_length=1,
                                                     description="wheel torques, e.g. ['0 N*m']")
    published_stiffness: Stiffness | None = Field(
        None, description="the source's spring rate, e.g. '30 N/mm'")
    published_misalignment_at_no_torque: SignedLength | None = Field(
        None, description="the source's eq (21) at no output torque, e.g. '-1.10 mm'")
    published_aligned_torque: Torque | None = Field(
        None, description="the output torque where the source's shaft is aligned, "
                          "e.g. '19.67 N*m'")


class FrictionLaw(Model):
    """Seed 001 §2.4.1: mu = c·p^n through a measured point (steel on polymer)."""

    mu_ref: Friction = Field(description="measured friction, e.g. 0.029")
    pressure_ref: Modulus = Field(description="at this contact pressure, e.g. '130 MPa'")
    exponent: float = Field(-0.9, ge=-5.0, le=0.0,
                            description="n in [-5, 0]: -0.9 sliding, -0.6 rolling")


class PublishedFriction(Model):
    """A friction coefficient a source prints at a contact pressure."""

    mu: Friction
    pressure: Modulus = Field(description="e.g. '130 MPa'")


class PublishedEfficiency(Model):
    """An efficiency a source prints (or measured) at an output torque."""

    output_torque: SignedTorque = Field(description="e.g. '36 N*m'")
    eta: Efficiency


class KimContact(Model):
    """What seed 001's contact pressure (eqs 10-19) needs beyond the worm set: a ZI worm,
    the hob that cut the wheel, the materials; and what the source prints of them, to
    check against."""

    hob_pitch_diameter: Length = Field(description="the (oversized) hob, e.g. '22 mm'")
    worm: Material = Field(DEFAULT_STEEL, description="default steel")
    wheel: Material = Field(description="e.g. nylon: E = '3 GPa', nu = 0.4")
    friction: FrictionLaw
    published_friction: PublishedFriction | None = Field(
        None, description="a measured friction, e.g. {mu = 0.029, pressure = '130 MPa'}")
    published_efficiency: list[PublishedEfficiency] = Field(
        [], description="efficiencies the source prints, e.g. [{output_torque = '36 N*m', "
                        "eta = 0.931}]")


class WormEfficiencyCase(CaseInfo):
    kind: Literal["worm_efficiency"]
    starts: int = Field(ge=1, le=12, description="worm starts z1 (1..12)")
    teeth: int = Field(ge=10, description="wheel teeth z2 (>= 10)")
    normal_module: Length
    lead_angle: Angle | None = None
    worm_pitch_diameter: Length | None = None
    normal_pressure_angle: Angle = Field(description="e.g. '20 deg'")
    mu_zm: Friction | None = Field(None, description="mean tooth friction, e.g. 0.061")
    din3996: Din3996 | None = None
    conditions: list[Condition] = []
    anti_rattle_spring: AntiRattleSpring | None = None
    contact: KimContact | None = Field(None, description="seed 001's pressure-dependent "
                                                         "friction (needs the spring)")

    @model_validator(mode="after")
    def _choices(self):
        if self.contact is not None and (self.anti_rattle_spring is None
                                         or self.worm_pitch_diameter is None):
            raise ValueError("contact: needs [anti_rattle_spring] and worm_pitch_diameter")
        if (self.lead_angle is None) == (self.worm_pitch_diameter is None):
            raise ValueError("lead_angle / worm_pitch_diameter: give exactly one of them")
        if self.lead_angle is not None and not 0 < self.lead_angle < math.radians(45):
            raise ValueError(f"lead_angle: {math.degrees(self.lead_angle):.4g} deg must lie "
                             "between 0 and 45 deg")
        if (self.mu_zm is None) == (self.din3996 is None):
            raise ValueError("mu_zm / din3996: give either mu_zm or a [din3996] table")
        if self.conditions and self.din3996 is None:
            raise ValueError("conditions: need the [din3996] chain (mu_zm is fixed)")
        if not 0 < self.normal_pressure_angle < math.radians(45):
            raise ValueError("normal_pressure_angle: must lie between 0 and 45 deg")
        return self
