"""Case files: TOML in, validated models out. The only module that reads input.

Every quantity is text with a unit ("1.44 in", "3600 lbf", "-50 degC"); it is converted to
the core units (mm, N, MPa, N·mm, rad) by `units.parse` as the model is validated. Any
problem becomes one `CaseError` whose message names the field, the value and what is allowed.
"""

from __future__ import annotations

import math
import re
import tomllib
from pathlib import Path
from typing import Annotated, Any, Literal, get_args

from pydantic import (
    AfterValidator,
    BaseModel,
    BeforeValidator,
    ConfigDict,
    Field,
    ValidationError,
    field_validator,
    model_validator,
)

from . import units


class CaseError(Exception):
    """Bad input: the message names the field, the value and what is allowed."""


#: absolute zero, °C
ABSOLUTE_ZERO = -273.15


def quantity(kind: str, *, positive: bool = False, nonzero: bool = False,
             allow_inf: bool = False, low: float | None = None, high: float | None = None):
    """The validator of a float field (Annotated[float, quantity(...)]) given as text with a
    unit of `kind` (see units.KINDS), within the
    kind's physical range: finite (unless `allow_inf`), at most `largest` in magnitude (or
    `high`, core units), at least `smallest` in magnitude if `positive` or `nonzero`, and
    at least `low` (core units)."""
    spec = units.KINDS[kind]

    def convert(value: Any) -> float:
        number = units.parse(value, kind)
        if math.isinf(number):
            if allow_inf:
                return number
            raise ValueError(f"{value!r} must be finite")
        if positive and not number > 0:
            raise ValueError(f"{value!r} must be greater than zero")
        if (positive or nonzero) and abs(number) < spec.smallest:
            raise ValueError(f"{value!r} is {units.show(number, kind)}: its size must be at "
                             f"least {units.show(spec.smallest, kind)}")
        if high is None and abs(number) > spec.largest:
            raise ValueError(f"{value!r} is {units.show(number, kind)}: its size must be at "
                             f"most {units.show(spec.largest, kind)}")
        if high is not None and number > high:
            raise ValueError(f"{value!r} must be at most {units.show(high, kind)}")
        if low is not None and number < low:
            raise ValueError(f"{value!r} must be at least {units.show(low, kind)}")
        return number

    return BeforeValidator(convert)


Length = Annotated[float, quantity("length", positive=True)]
SignedLength = Annotated[float, quantity("length")]
SignedTorque = Annotated[float, quantity("torque")]
Radius = Annotated[float, quantity("length", nonzero=True, allow_inf=True)]
#: a lead crown's radius: up to 1e9 mm (1 µm over a 100 mm face is 1.25e6 mm)
CrownRadius = Annotated[float, quantity("length", positive=True, high=1e9)]
Force = Annotated[float, quantity("force", positive=True)]
Modulus = Annotated[float, quantity("stress", positive=True)]
Torque = Annotated[float, quantity("torque", positive=True)]
Angle = Annotated[float, quantity("angle")]
Slope = Annotated[float, quantity("slope")]
InverseLength = Annotated[float, quantity("inverse_length", positive=True)]
Viscosity = Annotated[float, quantity("viscosity", positive=True)]
Temperature = Annotated[float, quantity("temperature", low=ABSOLUTE_ZERO + 1e-9)]
Stiffness = Annotated[float, quantity("stiffness", positive=True)]
Poisson = Annotated[float, Field(gt=-1.0, lt=0.5, description="Poisson's ratio in (-1, 0.5)")]
Factor = Annotated[float, Field(gt=0.0, le=1e6, description="a positive number")]
Friction = Annotated[float, Field(gt=0.0, lt=1.0, description="a friction coefficient in (0, 1)")]
Efficiency = Annotated[float, Field(gt=0.0, le=1.0, description="an efficiency in (0, 1]")]


class Model(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)

    @field_validator("*", mode="before")
    @classmethod
    def _no_switch_for_a_number(cls, value: Any, info) -> Any:
        """A switch (TOML's true or false) is refused where the field takes no switch:
        pydantic would read it as 1 or 0."""
        if _holds_switch(value) and not _takes_switch(cls.model_fields[info.field_name]
                                                      .annotation):
            raise ValueError(f"{value!r} {'holds' if isinstance(value, (list, tuple)) else 'is'}"
                             " a switch (true or false) where a number or a name is expected")
        return value


def _holds_switch(value: Any) -> bool:
    """Whether `value` is a bool or a list (at any depth) holding one."""
    if isinstance(value, (list, tuple)):
        return any(_holds_switch(v) for v in value)
    return isinstance(value, bool)


def _takes_switch(annotation: Any) -> bool:
    """Whether a field's type admits a bool anywhere in it."""
    return annotation is bool or any(_takes_switch(a) for a in get_args(annotation))


class CaseInfo(Model):
    """Fields every case may carry: where it comes from and what had to be assumed."""

    kind: str
    title: str = ""
    source: str = ""
    assumptions: list[str] = []

    @model_validator(mode="before")
    @classmethod
    def _kind_analysis_defaults(cls, data):
        """A partial [analysis] table keeps the kind's own defaults for the keys it leaves
        out (a spline's 3 positions, a worm set's 7), not the generic ones."""
        field = cls.model_fields.get("analysis")
        if isinstance(data, dict) and field is not None and isinstance(data.get("analysis"), dict):
            own = field.default
            kept = {k: getattr(own, k) for k in own.model_fields_set if k not in data["analysis"]}
            data = {**data, "analysis": {**kept, **data["analysis"]}}
        return data


#: a flank's thermal contact coefficient sqrt(λρc), W·s^0.5/(m²·K) (the flash temperature)
ThermalCoefficient = Annotated[float, quantity("thermal_contact_coefficient", positive=True)]
THERMAL_DESCRIPTION = ("sqrt(λρc) for the flash temperature, e.g. '12.7 kW*s^0.5/(m^2*K)' "
                       "(default: steel's)")


class Material(Model):
    E: Modulus = Field(description="Young's modulus, e.g. '206 GPa'")
    nu: Poisson = Field(description="Poisson's ratio, e.g. 0.3")
    yield_strength: Modulus | None = Field(
        None, description="0.2 % proof stress, e.g. '150 MPa' (a cast tin bronze's): the "
                          "stresses below the contact are checked against it")
    temperature_limit: Temperature | None = Field(
        None, description="the highest contact temperature the material (or its lubricant) "
                          "takes, e.g. '150 degC' (a polyamide's): the flash temperature's "
                          "peak is checked against it")
    thermal_contact_coefficient: ThermalCoefficient | None = Field(
        None, description=THERMAL_DESCRIPTION)


STEEL = {"E": "206 GPa", "nu": 0.3}
#: the heat treatments a gear material may name (rating.life.TREATMENTS: the groups of
#: ISO 6336's life factors); listed here so that reading a case does not import the ratings
TREATMENT_NAMES = ("structural", "through_hardened", "case_carburized", "induction_hardened",
                   "flame_hardened", "nitrided", "nitrided_through_hardening_steel",
                   "nitrocarburized", "nodular_cast_iron", "malleable_cast_iron",
                   "grey_cast_iron")
#: treatments whose E and ν are not steel's: given with the material, never defaulted
CAST_IRONS = ("nodular_cast_iron", "malleable_cast_iron", "grey_cast_iron")


def hardness_on(*scales: str):
    """A hardness field: text with its scale, e.g. '650 HV' (units.parse_hardness), kept as
    (number, scale)."""
    def convert(value: Any) -> tuple[float, str]:
        if isinstance(value, tuple):
            return value
        return units.parse_hardness(value, scales)

    return Annotated[tuple[float, str], BeforeValidator(convert)]


#: the quality grades of ISO 6336-5 (the demands on the material and its heat treatment)
QUALITY_GRADES = ("ML", "MQ", "ME")


class GearMaterial(Model):
    """A gear's material: E and ν (steel's where not given, unless a cast iron), the density
    (ISO 6336-1's dynamic factor), and for its safety factors the heat treatment (the life
    factors' group) and the allowable stress numbers of ISO 6336-5: σ_Hlim (contact) and
    σ_Flim (root, the nominal stress number of the unnotched reference; ISO 6336-3 multiplies
    it by Y_ST = 2), given, or from the surface hardness and quality grade by ISO 6336-5
    Table 1 (rating.allowables)."""

    E: Modulus | None = Field(None, description="Young's modulus, e.g. '206 GPa' (default "
                                                "steel's)")
    nu: Poisson | None = Field(None, description="Poisson's ratio (default 0.3)")
    density: Annotated[float, quantity("density", positive=True)] | None = Field(
        None, description="e.g. '7830 kg/m^3' (default: steel's 7830, a cast iron's 7200): "
                          "the gears' masses in ISO 6336-1's dynamic factor")
    treatment: Literal[TREATMENT_NAMES] | None = Field(
        None, description="heat treatment: the group of ISO 6336's life factors and of "
                          "ISO 6336-5's allowable stress numbers")
    sigma_Hlim: Modulus | None = Field(None, description="ISO 6336-5 contact stress number, "
                                                         "e.g. '1500 MPa'")
    sigma_Flim: Modulus | None = Field(None, description="ISO 6336-5 bending stress number, "
                                                         "e.g. '500 MPa'")
    hardness: hardness_on("HV", "HBW") | None = Field(
        None, description="surface hardness, e.g. '680 HV' or '260 HBW': with quality, "
                          "sigma_Hlim and sigma_Flim from ISO 6336-5 Table 1 (a given one "
                          "overrides)")
    quality: Literal[QUALITY_GRADES] | None = Field(
        None, description="ISO 6336-5 material quality grade: ML, MQ or ME")
    cast: bool = Field(False, description="a cast steel (structural or through-hardened): "
                                          "Table 1's cast rows")
    alloy: bool | None = Field(None, description="a through-hardened steel: an alloy "
                                                 "(true) or a carbon (false) steel")
    core_hardness: hardness_on("HRC") | None = Field(
        None, description="a case-carburized tooth's core hardness, e.g. '32 HRC': 30 HRC "
                          "or more takes Table 1's MQ root value 500 MPa, else 425")
    yield_strength: Modulus | None = Field(
        None, description="0.2 % proof stress (through-hardened steels, pearlitic cast "
                          "irons) or yield stress (structural steels): ISO 6336-3's notch "
                          "sensitivity Y_δrelT")
    thermal_contact_coefficient: ThermalCoefficient | None = Field(
        None, description=THERMAL_DESCRIPTION)

    @model_validator(mode="before")
    @classmethod
    def _steel(cls, raw: Any) -> Any:
        """Steel's E and ν where not given, unless the treatment names a cast iron."""
        if not isinstance(raw, dict) or raw.get("treatment") in CAST_IRONS:
            return raw
        return {"E": STEEL["E"], "nu": STEEL["nu"], **raw}

    @model_validator(mode="after")
    def _given(self):
        if self.E is None or self.nu is None:
            raise ValueError(f"E / nu: give both for a {self.treatment.replace('_', ' ')} "
                             "(steel's are the default only for steels)")
        rated = [name for name in ("sigma_Hlim", "sigma_Flim", "hardness")
                 if getattr(self, name) is not None]
        if rated and self.treatment is None:
            raise ValueError(f"treatment: give the heat treatment with {' / '.join(rated)} "
                             f"(one of {', '.join(TREATMENT_NAMES)}): it sets the life factors "
                             "and ISO 6336-5's rows")
        if (self.hardness is None) != (self.quality is None):
            given, missing = (("hardness", "quality") if self.quality is None
                              else ("quality", "hardness"))
            raise ValueError(f"{missing}: give it with {given} (ISO 6336-5 Table 1 rates a "
                             "material by its surface hardness and quality grade ML, MQ or ME)")
        if self.cast and self.treatment not in ("structural", "through_hardened"):
            raise ValueError(f"cast: ISO 6336-5 has cast rows for structural and through-"
                             f"hardened steels only, not {self.treatment}")
        if self.alloy is not None and self.treatment != "through_hardened":
            raise ValueError("alloy: only a through-hardened steel is rated as alloy or carbon")
        if (self.hardness is not None and self.treatment == "through_hardened"
                and self.alloy is None):
            raise ValueError("alloy: say whether the through-hardened steel is an alloy (true) "
                             "or a carbon steel (false): ISO 6336-5 rates them apart")
        if self.core_hardness is not None and self.treatment != "case_carburized":
            raise ValueError("core_hardness: only a case-carburized tooth's core is rated")
        return self


#: the most load cycles a case may give (a tooth at 30 000 rpm for 500 000 h meets 9e11)
MOST_CYCLES = 1e13


def _whole(value: float) -> float:
    if value != math.floor(value):
        raise ValueError(f"{value!r} is no whole number of cycles")
    return value


#: load cycles: a count, finite and whole, from 1 to MOST_CYCLES
Cycles = Annotated[float, Field(ge=1.0, le=MOST_CYCLES, allow_inf_nan=False),
                   AfterValidator(_whole)]


#: a load factor of ISO 6336-1 given instead of computed: at least 1 (ISO's load factors
#: raise the nominal load), at most 20
LoadFactor = Annotated[float, Field(ge=1.0, le=20.0, description="a load factor in [1, 20]")]
#: a strength factor of ISO 6336-2/-3 given instead of computed (Z_L, Y_X, ...): in (0, 3]
StrengthFactor = Annotated[float, Field(gt=0.0, le=3.0,
                                        description="an influence factor in (0, 3]")]
#: the factors a [rating] may give, by field: (the result key, ISO's symbol)
GIVEN_FACTORS = {
    "application_factor": ("K_A", "K_A"), "dynamic_factor": ("K_v", "K_v"),
    "face_load_factor": ("K_H_beta_rating", "K_Hβ"), "transverse_load_factor": ("K_H_alpha", "K_Hα"),
    "root_face_load_factor": ("K_F_beta", "K_Fβ"),
    "root_transverse_load_factor": ("K_F_alpha", "K_Fα"),
    "lubricant_factor": ("Z_L", "Z_L"), "velocity_factor": ("Z_v", "Z_v"),
    "roughness_factor": ("Z_R", "Z_R"), "work_hardening_factor": ("Z_W", "Z_W"),
    "size_factor": ("Z_X", "Z_X"), "notch_sensitivity_factor": ("Y_delta_rel_T", "Y_δrelT"),
    "root_surface_factor": ("Y_R_rel_T", "Y_RrelT"), "root_size_factor": ("Y_X", "Y_X")}


class RatingSpec(Model):
    """What ISO 6336 needs beyond the loaded contact for the ratings: the accuracy grade,
    the load cycles (or the life at the case's speed), whether limited pitting is accepted,
    the least safety factors, and any influence factor known from measurement or a more
    exact method (ISO allows it), by its name in words; a factor not given is computed
    (ISO 6336-1/-2/-3 Method B; K_Hβ from the loaded contact) or, where the case lacks what
    it needs, taken as 1 and listed among the rating's assumptions."""

    application_factor: LoadFactor = Field(1.0, description="K_A (default 1: uniform driver "
                                                            "and driven machine)")
    dynamic_factor: LoadFactor | None = Field(None, description="K_v (default: ISO 6336-1 "
                                                                "Method B)")
    face_load_factor: LoadFactor | None = Field(
        None, description="K_Hβ (default: the loaded contact's, ISO 6336-1 Method A)")
    transverse_load_factor: LoadFactor | None = Field(
        None, description="K_Hα (default: ISO 6336-1 Method B)")
    root_face_load_factor: LoadFactor | None = Field(
        None, description="K_Fβ (default: K_Hβ^N_F, ISO 6336-1)")
    root_transverse_load_factor: LoadFactor | None = Field(
        None, description="K_Fα (default: ISO 6336-1 Method B)")
    lubricant_factor: StrengthFactor | None = Field(None, description="Z_L (default: ISO "
                                                                      "6336-2 from the oil)")
    velocity_factor: StrengthFactor | None = Field(None, description="Z_v (default: ISO "
                                                                     "6336-2 from the speed)")
    roughness_factor: StrengthFactor | None = Field(
        None, description="Z_R (default: ISO 6336-2 from the flanks' roughness)")
    work_hardening_factor: StrengthFactor | None = Field(None, description="Z_W (default 1)")
    size_factor: StrengthFactor | None = Field(None, description="Z_X (default 1)")
    notch_sensitivity_factor: StrengthFactor | None = Field(
        None, description="Y_δrelT (default: ISO 6336-3 from the material)")
    root_surface_factor: StrengthFactor | None = Field(
        None, description="Y_RrelT (default: ISO 6336-3 from the root roughness)")
    root_size_factor: StrengthFactor | None = Field(
        None, description="Y_X (default: ISO 6336-3 from the module)")
    accuracy_grade: Annotated[int, Field(ge=1, le=11)] | None = Field(
        None, description="ISO 1328-1:2013 flank tolerance class 1-11 of both members: the "
                          "pitch and profile deviations of K_v, K_Hα and K_Hβ's Method C "
                          "(default: none, deviations taken as zero)")
    pinion_cycles: Cycles | None = Field(
        None, description="load cycles of each pinion tooth, e.g. 1e9 (default: from life "
                          "and the speed, else the endurance limit, Z_NT = Y_NT = 1)")
    life: Annotated[float, quantity("time", positive=True)] | None = Field(
        None, description="required life at the case's speed, e.g. '20000 h': the load "
                          "cycles N_L = 60·n·L_h")
    limited_pitting: bool = Field(False, description="some pitting accepted (ISO 6336-2 "
                                                     "Table 2's second steel line)")
    S_Hmin: Factor = Field(1.0, description="least contact safety factor")
    S_Fmin: Factor = Field(1.0, description="least root safety factor")
    flank_pressure_limit: Modulus | None = Field(
        None, description="a limit on the loaded contact's largest flank pressure, checked "
                          "beside ISO's S_H (off by default)")

    @model_validator(mode="after")
    def _cycles_once(self):
        if self.pinion_cycles is not None and self.life is not None:
            raise ValueError("pinion_cycles / life: give the load cycles or the life, not both")
        return self


#: a flank's arithmetic mean roughness Ra (mm), given with [operation]
Roughness = Annotated[float, quantity("length", positive=True, high=0.1)]
ROUGHNESS_FIELD = Field(None, description="the flanks' arithmetic mean roughness, e.g. "
                                          "'0.4 um' (with [operation]: the friction "
                                          "coefficient and the specific film)")
#: the oil families a lubricant may name (analytic.lubricant.FAMILIES: their defaults);
#: listed here so that reading a case does not import the analysis
LUBRICANT_FAMILIES = ("mineral", "pao", "pag")


class Running(Model):
    """How a mesh runs, beside its driver's speed: the oil's temperature, and, where known,
    the teeth's bulk temperature and how the mesh is lubricated."""

    oil_temperature: Temperature = Field(description="oil sump or inlet temperature, e.g. "
                                                     "'90 degC'")
    bulk_temperature: Temperature | None = Field(
        None, description="the teeth's bulk temperature (default: oil temperature + "
                          "0.47·X_S·mean flash temperature, ISO/TS 6336-20)")
    lubrication: Literal["splash", "spray"] = Field(
        "splash", description="X_S = 1.2 (splash) or 1.0 (spray) in the bulk temperature")


class OperationSpec(Running):
    """How a gear pair runs: the pinion's speed, the oil's temperature, the teeth's bulk
    temperature where known (default: ISO/TS 6336-20's estimate from the flash temperature)
    and how the mesh is lubricated (its factor X_S in that estimate)."""

    pinion_speed: Annotated[float, quantity("rotational_speed", positive=True)] = Field(
        description="the pinion's speed, e.g. '3000 rpm'")


class WormOperationSpec(Running):
    """How a worm set runs: the worm's speed, the oil's temperature and the teeth's bulk
    temperature where known (default: the oil's)."""

    worm_speed: Annotated[float, quantity("rotational_speed", positive=True)] = Field(
        description="the worm's speed, e.g. '1450 rpm'")


#: E (MPa) within which a flank is taken as steel for its thermal contact coefficient
STEEL_LIKE = (170e3, 240e3)


def lubricated_pair(case, members: dict, friction_needed: bool) -> None:
    """What a case's [operation] needs (raising ValueError naming the field): its
    [lubricant], a load, each member's roughness_Ra, a friction coefficient where the
    mesh has no friction law of its own, and a non-steel member's thermal contact
    coefficient. `members`: name -> (its spec, its material)."""
    if (case.operation is None) != (case.lubricant is None):
        given, missing = (("operation", "lubricant") if case.lubricant is None
                          else ("lubricant", "operation"))
        raise ValueError(f"{missing}: [{given}] needs a [{missing}] table (the lubricated "
                         "contact needs the speed and the oil)")
    if case.operation is None:
        return
    if case.load is None:
        raise ValueError("load: [operation] needs a [load] (the lubricated contact is the "
                         "loaded one)")
    for name, (spec, material) in members.items():
        if spec.roughness_Ra is None:
            raise ValueError(f"{name}.roughness_Ra: give the flanks' roughness Ra (e.g. "
                             "'0.4 um') with [operation]: the friction coefficient and the "
                             "specific film thickness need it")
        if (material.thermal_contact_coefficient is None
                and not STEEL_LIKE[0] <= material.E <= STEEL_LIKE[1]):
            raise ValueError(f"{name} material: thermal_contact_coefficient: give sqrt(λρc) of "
                             f"this E = {material.E / 1e3:.4g} GPa material with [operation] "
                             "(steel's is the default only for steels)")
    if friction_needed and case.lubricant.friction_coefficient is None:
        raise ValueError("lubricant.friction_coefficient: give a worm set's mean friction "
                         "(e.g. DIN 3996's mu_zm from the worm_efficiency kind): ISO/TR "
                         "14179-2's is for cylindrical gears")
    _temperatures(case.operation, case.lubricant)


def _temperatures(op: Running, oil: LubricantSpec) -> None:
    """The oil, bulk and scuffing temperatures where their formulas hold (ValueError naming
    the field): the oil at or above its pour point (analytic.lubricant.POUR_POINTS where not
    given) and within ASTM D341's viscosities there; the teeth's bulk at or above the oil
    that cools them; the scuffing temperature above the oil's (S_B's margin)."""
    from .analytic import lubricant

    theta = op.oil_temperature
    pour = oil.pour_point if oil.pour_point is not None else lubricant.POUR_POINTS[oil.family]
    whose = ("the lubricant.pour_point given" if oil.pour_point is not None else
             f"the {oil.family} family's default pour point; give lubricant.pour_point for "
             "this oil's")
    if theta < pour:
        raise ValueError(f"operation.oil_temperature: {theta:.4g} degC lies below the oil's "
                         f"pour point {pour:.4g} degC ({whose}): ASTM D341's viscosity line "
                         "holds only for a liquid oil")
    nu = lubricant.kinematic_viscosity(oil.viscosity_40, oil.viscosity_100, theta)
    largest = units.KINDS["viscosity"].largest
    if not lubricant.WALTHER_LEAST <= nu <= largest:
        raise ValueError(f"operation.oil_temperature: {theta:.4g} degC gives the oil a "
                         f"viscosity of {nu:.4g} mm^2/s on ASTM D341's line, outside the "
                         f"{lubricant.WALTHER_LEAST:g} to {largest:.4g} mm^2/s it is taken "
                         "over")
    if op.bulk_temperature is not None and not op.bulk_temperature >= theta:
        raise ValueError(f"operation.bulk_temperature: {op.bulk_temperature:.4g} degC must be "
                         f"at least the oil temperature {theta:.4g} degC: the teeth run at "
                         "or above the oil that cools them (ISO/TS 6336-20)")
    if oil.scuffing_temperature is not None and not oil.scuffing_temperature > theta:
        raise ValueError(f"lubricant.scuffing_temperature: {oil.scuffing_temperature:.4g} degC "
                         f"must exceed the oil temperature {theta:.4g} degC: S_B = (θ_S - "
                         "θ_oil)/(θ_B,max - θ_oil) measures the margin above the oil")


class LubricantSpec(Model):
    """The oil: its kinematic viscosity at 40 and 100 °C (ASTM D341 between them), density
    at 15 °C and pressure-viscosity coefficient (the family's typical values where not
    given), and, where known, a fixed friction coefficient, the scuffing temperature and
    the permissible specific film thickness for the safety factors."""

    family: Literal[LUBRICANT_FAMILIES] = Field(
        "mineral", description="mineral, pao (polyalphaolefin) or pag (polyglycol)")
    viscosity_40: Viscosity = Field(description="kinematic viscosity at 40 °C, e.g. "
                                                "'220 mm^2/s'")
    viscosity_100: Viscosity = Field(description="kinematic viscosity at 100 °C, e.g. "
                                                 "'19 mm^2/s'")
    density: Annotated[float, quantity("density", positive=True)] | None = Field(
        None, description="at 15 °C, e.g. '890 kg/m^3' (default: the family's)")
    pressure_viscosity: Annotated[float, quantity("pressure_viscosity", positive=True)] | None = Field(
        None, description="α, e.g. '1.8e-8 1/Pa' (default: the family's typical)")
    friction_coefficient: Friction | None = Field(
        None, description="a fixed mesh friction coefficient (default: ISO/TR 14179-2's, "
                          "at each contact)")
    scuffing_temperature: Temperature | None = Field(
        None, description="θ_S of the oil and flanks (e.g. from an FZG test): the scuffing "
                          "safety S_B")
    permissible_specific_film: Factor | None = Field(
        None, description="λ_GFP of ISO/TR 15144-1 (from a micropitting test): the "
                          "micropitting safety S_lambda")
    pour_point: Temperature | None = Field(
        None, description="the oil's pour point, e.g. '-27 degC': no oil temperature below "
                          "it is taken (default: the family's, mineral -15, pao -45, pag -30 "
                          "degC)")

    @model_validator(mode="after")
    def _thinner_when_hot(self):
        from .analytic.lubricant import WALTHER_LEAST

        for name in ("viscosity_40", "viscosity_100"):
            if not getattr(self, name) >= WALTHER_LEAST:
                raise ValueError(f"{name}: {getattr(self, name):.4g} mm^2/s must be at least "
                                 f"{WALTHER_LEAST:g} mm^2/s, the least ASTM D341's Walther "
                                 "line log log(ν + 0.7) holds for")
        if not self.viscosity_100 < self.viscosity_40:
            raise ValueError(f"viscosity_100: {self.viscosity_100:.4g} mm^2/s must be below "
                             f"viscosity_40 ({self.viscosity_40:.4g} mm^2/s): an oil thins as "
                             "it warms")
        return self


class Body(Material):
    radii: tuple[Radius, Radius] = Field(
        description="two principal radii, e.g. ['12.7 mm', 'inf']; negative = concave")


class HertzCase(CaseInfo):
    kind: Literal["hertz"]
    load: Force = Field(description="normal load, e.g. '1000 N'")
    angle: Angle = Field(0.0, description="angle between the bodies' first principal planes")
    body1: Body
    body2: Body


class ModuleOrPitch(Model):
    """A tooth size given as a module or as a diametral pitch (the module is its inverse)."""

    module: Length | None = Field(None, description="module, e.g. '3 mm'")
    diametral_pitch: InverseLength | None = Field(None, description="e.g. '10 1/in'")

    @property
    def module_mm(self) -> float:
        return self.module if self.module is not None else 1.0 / self.diametral_pitch


#: pressure angles of a gear pair (deg): 14.5 to 25 in practice, 30 and more for some
#: high-load and actuator gears
PAIR_PRESSURE_ANGLE = (10.0, 40.0)


def _check_pair_pressure_angle(angle: float) -> None:
    low, high = PAIR_PRESSURE_ANGLE
    if not low <= math.degrees(angle) <= high:
        raise ValueError(f"pressure_angle: {math.degrees(angle):.4g} deg must lie between "
                         f"{low:g} and {high:g} deg")


class GearPairGeometry(CaseInfo, ModuleOrPitch):
    """Teeth and module of a spur pair; the gear's count is negative for an internal gear."""

    teeth: tuple[int, int] = Field(description="[pinion, gear] teeth, gear < 0 = internal")
    pressure_angle: Angle = Field(description="e.g. '20 deg' (crown_design: operating; "
                                              "spur: normal, of the rack)")

    @model_validator(mode="after")
    def _one_size(self):
        if (self.module is None) == (self.diametral_pitch is None):
            raise ValueError("module / diametral_pitch: give exactly one of them")
        z1, z2 = self.teeth
        if z1 < 5 or abs(z2) < 5:
            raise ValueError(f"teeth: {list(self.teeth)} needs at least 5 teeth on each member")
        if z2 < 0 and abs(z2) <= z1:
            raise ValueError(f"teeth: internal gear {z2} must have more teeth than the pinion {z1}")
        _check_pair_pressure_angle(self.pressure_angle)
        return self


class CrownDesignCase(GearPairGeometry):
    kind: Literal["crown_design"]
    crown: Literal["full", "bias"]
    face_width: Length = Field(description="face width, e.g. '30 mm'")
    outside_radius_pinion: Length | None = None
    outside_radius_gear: Length | None = Field(
        None, description="gear tip radius (inside radius for an internal gear)")
    center_distance: Length | None = None
    profile_radii: tuple[Length, Length] | None = Field(
        None, description="[rho1, rho2] at the contact, overriding the LPSTC; rho2 > 0 also "
                          "for an internal gear's concave flank")
    tangential_load: Force = Field(description="e.g. '8000 N'")
    slope_A: Slope = Field(description="total slope at end A in rad, e.g. '0.0015'")
    slope_B: Slope | None = Field(None, description="total slope at end B (an off-centre crown only)")
    radius: CrownRadius | None = Field(None, description="check this crown radius instead of designing")
    center_from_B: Length | None = Field(None, description="crown centre of a checked crown")
    edge_clearance: SignedLength = Field(0.0, description="margin kept to each end")
    allowable_stress: Modulus | None = None
    material: Material
    gear_material: Material | None = None

    @model_validator(mode="after")
    def _slopes(self):
        if self.crown == "full" and self.slope_B is not None:
            raise ValueError("slope_B: a full crown takes one slope (slope_A); "
                             "use crown = 'bias' for two")
        if self.crown == "bias" and self.slope_B is None:
            raise ValueError("slope_B: missing; an off-centre (bias) crown needs the slope at end B")
        if self.center_from_B is not None and self.radius is None:
            raise ValueError("center_from_B: only with radius (checking a given crown)")
        return self


class Rack(Model):
    """Basic rack of the generating cutter, in multiples of the normal module (ISO 53 A)."""

    addendum: Factor = Field(1.0, description="tooth-tip height of the gear, × m_n")
    dedendum: Factor = Field(1.25, description="root depth of the gear, × m_n")
    root_radius: Annotated[float, Field(ge=0.0)] = Field(0.38, description="× m_n")


class CrownSpec(Model):
    """Lead crown: radius or height (drop at the face ends when centred), shape, centre."""

    radius: CrownRadius | None = None
    height: Length | None = None
    shape: Literal["circular", "parabolic"] = "circular"
    center: SignedLength = Field(0.0, description="from mid-face toward end B")

    @model_validator(mode="after")
    def _one(self):
        if (self.radius is None) == (self.height is None):
            raise ValueError("radius / height: give exactly one of them")
        return self


class ProfileCrownSpec(Model):
    height: Length = Field(description="drop at both ends of the active profile, e.g. '4 um'")
    shape: Literal["circular", "parabolic"] = "parabolic"


class ReliefSpec(Model):
    """A tip relief, or a root relief: a drop growing from its start toward the tip (the
    form circle)."""

    amount: Annotated[float, quantity("length", low=0.0)] = Field(
        description="drop at the tip (a root relief's: at the form circle), e.g. '10 um'; "
                    "'0 um' for none (a sweep's baseline)")
    start_diameter: Length = Field(description="diameter where the relief begins")
    shape: Literal["linear", "parabolic"] = "linear"
    blend: Annotated[float, quantity("length", low=0.0)] | None = Field(
        None, description="a linear relief's start blended over this length of the profile "
                          "(roll length), e.g. '0.5 mm'; default 0.2 of the relief's length; "
                          "'0 mm' for a sharp kink")


class TipEdgeSpec(Model):
    radius: Annotated[float, quantity("length", low=0.0)] | None = Field(
        None, description="radius of the rounding that breaks the tip edge, e.g. '0.3 mm'; "
                          "'0 mm' for a sharp edge; with a chamfer, the rounding of the "
                          "chamfer's edge on the flank; none given: 0.1 normal modules, or "
                          "(a rounding alone) the largest that fits the tooth")
    chamfer: Length | None = Field(
        None, description="a tip chamfer instead of a rounding: its length along the flank "
                          "from the tip circle to its edge, e.g. '0.2 mm'")
    angle: Annotated[float, quantity("angle", positive=True)] = Field(
        math.radians(30.0), description="the tip chamfer's angle to the flank, e.g. '30 deg'")

    @model_validator(mode="after")
    def _chamfer_edge(self):
        if self.chamfer is not None and self.radius == 0.0:
            raise ValueError("radius: '0 mm' with a chamfer would leave its edge on the flank "
                             "sharp: give the rounding it has, or none for 0.1 normal modules")
        return self


class EndChamferSpec(Model):
    length: Length = Field(description="length along the face from each end face to the "
                                       "chamfer's edge on the flank, e.g. '0.5 mm'")
    angle: Annotated[float, quantity("angle", positive=True)] = Field(
        math.radians(45.0), description="the chamfer's angle to the flank, e.g. '45 deg'")
    radius: Length | None = Field(
        None, description="the rounding of the chamfer's edge on the flank, e.g. '0.2 mm'; "
                          "none given: 0.1 normal modules")


class HelixSlopeSpec(Model):
    amount: SignedLength = Field(
        description="f_Hβ: material removed at end B relative to end A, e.g. '12 um'; "
                    "negative removes it at end A")


class ProfileSlopeSpec(Model):
    amount: SignedLength = Field(
        description="f_Hα: material removed at the tip relative to the form circle, e.g. "
                    "'6 um'; negative removes it toward the root")


class TwistSpec(Model):
    amount: SignedLength = Field(
        description="the profile slope's change from end A to end B (flank twist), e.g. "
                    "'8 um'")


#: the largest deviation a topography may give (µm): a millimetre is a broken tooth
TOPOGRAPHY_LIMIT_UM = 1000.0


class TopographySpec(Model):
    """A grid of normal deviations over the flank: inline (`face`, `diameter`,
    `deviation_um`) or from a CSV file (its first row the diameters after a label cell, each
    next row a face position and its deviations, µm)."""

    face: list[SignedLength] | None = Field(
        None, description="face positions from mid-face toward end B, increasing, e.g. "
                          "['-15 mm', '0 mm', '15 mm']")
    diameter: list[Length] | None = Field(None, description="diameters, increasing")
    deviation_um: list[list[float]] | None = Field(
        None, description="µm, one row per face position, one number per diameter; positive "
                          "removes material like a relief")
    file: str | None = Field(None, description="a CSV file of the grid, relative to the case")

    @model_validator(mode="before")
    @classmethod
    def _read_file(cls, raw: Any, info) -> Any:
        if not isinstance(raw, dict) or raw.get("file") is None:
            return raw
        if any(raw.get(k) is not None for k in ("face", "diameter", "deviation_um")):
            raise ValueError("file / face / diameter / deviation_um: give the grid inline or "
                             "as a file, not both")
        try:
            path = _given_file(raw["file"], info)
        except ValueError as exc:
            raise ValueError(f"file: {exc}") from None
        return {**raw, **read_topography_csv(path)}

    @model_validator(mode="after")
    def _grid(self):
        if self.face is None or self.diameter is None or self.deviation_um is None:
            raise ValueError("face / diameter / deviation_um: give all three (or a file)")
        for name, axis in (("face", self.face), ("diameter", self.diameter)):
            if len(axis) < 2 or any(b <= a for a, b in zip(axis, axis[1:])):
                raise ValueError(f"{name}: {len(axis)} values; give two or more, increasing")
        rows = self.deviation_um
        if len(rows) != len(self.face) or any(len(r) != len(self.diameter) for r in rows):
            raise ValueError(f"deviation_um: {len(rows)} rows of "
                             f"{sorted({len(r) for r in rows})} numbers; give one row per face "
                             f"position ({len(self.face)}), one number per diameter "
                             f"({len(self.diameter)})")
        worst = max((abs(v) for r in rows for v in r if math.isfinite(v)), default=0.0)
        if not all(math.isfinite(v) for r in rows for v in r) or worst > TOPOGRAPHY_LIMIT_UM:
            raise ValueError(f"deviation_um: each value must be finite and within "
                             f"±{TOPOGRAPHY_LIMIT_UM:g} µm")
        return self


#: the longest name a file system gives a file (bytes of one path component)
NAME_MAX = 255


def _given_file(name: Any, info) -> Path:
    """The file a case names (relative to the case's folder), which must exist: a
    ValueError (its message without the field) for a name that is no text, holds a control
    character, is too long for a file system or names no file."""
    if not isinstance(name, str) or not name:
        raise ValueError(f"{shown(name)} is not a file name")
    if any(ord(ch) < 32 or ord(ch) == 127 for ch in name):
        raise ValueError(f"{shown(name)} holds a control character")
    if any(len(part.encode("utf-8")) > NAME_MAX for part in Path(name).parts):
        raise ValueError(f"{shown(name)}: a file name has at most {NAME_MAX} bytes")
    path = Path(name)
    if not path.is_absolute() and info.context and info.context.get("base"):
        path = Path(info.context["base"]) / path
    try:
        found = path.is_file()
    except OSError as exc:
        raise ValueError(f"{shown(name)}: cannot be read ({exc.strerror})") from None
    if not found:
        raise ValueError(f"{shown(name)}: no such file ({_cut(str(path))})")
    return path


class KChartSpec(Model):
    """A measured K-chart: profile traces at face positions and lead traces at diameters
    (deviations in µm, positive removing material like a relief), turned into the flank's
    topography grid (Gordon's interpolation: the surface passes through every trace)."""

    profile_face: list[SignedLength] = Field(
        min_length=1, description="face positions of the profile traces, increasing")
    profile_diameter: list[Length] = Field(
        min_length=2, description="diameters along the profile traces, increasing")
    profile_um: list[list[float]] = Field(
        description="µm, one row per profile trace, one number per profile_diameter")
    lead_diameter: list[Length] = Field(
        min_length=1, description="diameters of the lead traces, increasing")
    lead_face: list[SignedLength] = Field(
        min_length=2, description="face positions along the lead traces, increasing")
    lead_um: list[list[float]] = Field(
        description="µm, one row per lead trace, one number per lead_face position")

    @model_validator(mode="after")
    def _traces(self):
        for name, axis in (("profile_face", self.profile_face),
                           ("profile_diameter", self.profile_diameter),
                           ("lead_diameter", self.lead_diameter), ("lead_face", self.lead_face)):
            if any(b <= a for a, b in zip(axis, axis[1:])):
                raise ValueError(f"{name}: the values must increase")
        for name, rows, across, along in (
                ("profile_um", self.profile_um, self.profile_face, self.profile_diameter),
                ("lead_um", self.lead_um, self.lead_diameter, self.lead_face)):
            if len(rows) != len(across) or any(len(r) != len(along) for r in rows):
                raise ValueError(f"{name}: {len(rows)} rows of {sorted({len(r) for r in rows})} "
                                 f"numbers; give one row per trace ({len(across)}), one number "
                                 f"per point along it ({len(along)})")
            if not all(math.isfinite(v) and abs(v) <= TOPOGRAPHY_LIMIT_UM for r in rows for v in r):
                raise ValueError(f"{name}: each value must be finite and within "
                                 f"±{TOPOGRAPHY_LIMIT_UM:g} µm")
        return self


def read_topography_csv(path: Path) -> dict:
    """A topography CSV as TopographySpec's fields: the first row a label cell and the
    diameters (mm, increasing), each next row a face position (mm from mid-face toward end
    B, increasing) and its deviations (µm, one per diameter, within ±TOPOGRAPHY_LIMIT_UM).
    Units are those; a problem is a ValueError naming the file, the row and the column as
    a spreadsheet counts them (blank lines counted)."""
    import csv

    try:
        text = path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError as exc:
        raise ValueError(f"file: {path.name}: not UTF-8 text (byte 0x{exc.object[exc.start]:02x} "
                         f"at position {exc.start}); save the CSV as UTF-8") from None
    except OSError as exc:
        raise ValueError(f"file: {path.name}: cannot be read ({exc.strerror})") from None
    rows = [(i, r) for i, r in enumerate(csv.reader(text.splitlines()), start=1)
            if any(cell.strip() for cell in r)]

    def where(line: int, column: int | None = None) -> str:
        return f"file: {path.name} row {line}" + ("" if column is None else f", column {column}")

    def number(cell: str, line: int, column: int) -> float:
        try:
            value = float(cell)
        except ValueError:
            raise ValueError(f"{where(line, column)}: {shown(cell)} is not a number") from None
        if not math.isfinite(value):
            raise ValueError(f"{where(line, column)}: {shown(cell)} is not a finite number")
        return value

    def increasing(values: list[float], places: list[tuple[int, int]], what: str) -> None:
        for (a, b), place in zip(zip(values, values[1:]), places[1:]):
            if not b > a:
                raise ValueError(f"{where(*place)}: the {what} {b:g} does not exceed the one "
                                 f"before it, {a:g}: they must increase")

    if len(rows) < 3:
        raise ValueError(f"file: {path.name}: a header row of diameters and at least two rows "
                         "of face positions are needed")
    (head, header), body = rows[0], rows[1:]
    if len(header) < 3:
        raise ValueError(f"{where(head)}: a label cell and at least two diameters (mm) are "
                         "needed")
    diameters = [number(c, head, k) for k, c in enumerate(header[1:], start=2)]
    increasing(diameters, [(head, k) for k in range(2, len(header) + 1)], "diameter")
    face, deviation = [], []
    for line, row in body:
        if len(row) - 1 != len(diameters):
            raise ValueError(f"{where(line)}: {len(row) - 1} deviations after the face "
                             f"position; the header gives {len(diameters)} diameters")
        face.append(number(row[0], line, 1))
        values = [number(c, line, k) for k, c in enumerate(row[1:], start=2)]
        for k, v in enumerate(values, start=2):
            if abs(v) > TOPOGRAPHY_LIMIT_UM:
                raise ValueError(f"{where(line, k)}: {v:g} µm lies beyond "
                                 f"±{TOPOGRAPHY_LIMIT_UM:g} µm")
        deviation.append(values)
    increasing(face, [(line, 1) for line, _ in body], "face position")
    return {"face": [f"{f!r} mm" for f in face], "diameter": [f"{d!r} mm" for d in diameters],
            "deviation_um": deviation, "file": str(path)}


class EndReliefSpec(Model):
    amount: Length = Field(description="drop at each face end, e.g. '8 um'")
    length: Length = Field(description="length from each end, e.g. '3 mm'")
    shape: Literal["linear", "parabolic"] = "linear"
    blend: Annotated[float, quantity("length", low=0.0)] | None = Field(
        None, description="a linear relief's starts blended over this length of the face, "
                          "e.g. '1 mm'; default 0.2 of `length`; '0 mm' for a sharp kink")


class ShaftSpec(Model):
    """The member's shaft (shaft.py): bearings and diameters, positions along the axis from
    mid-face toward end B; the mesh force bends it and the body twists over the face."""

    bearings: tuple[SignedLength, SignedLength] = Field(
        description="the two bearing positions from mid-face, e.g. ['-80 mm', '40 mm']")
    diameter: Length | None = Field(None, description="one diameter everywhere, e.g. '40 mm'")
    sections: list[tuple[SignedLength, SignedLength, Length]] = Field(
        [], description="a stepped shaft: [[from, to, diameter], ...] covering the bearings "
                        "and the face (the gear body a section of its own)")
    E: Modulus | None = Field(None, description="default: the member's material")
    nu: Poisson | None = None
    torque_side: Literal["A", "B"] = Field(
        "A", description="the face end the torque comes in (or goes out) at")
    bearing_stiffness: list[Stiffness] = Field(
        [], description="the bearings' radial stiffness: one for both or one each, in the "
                        "order of `bearings`, e.g. ['400 N/um']; none: rigid bearings")

    @model_validator(mode="after")
    def _layout(self):
        if (self.diameter is None) == (not self.sections):
            raise ValueError("give either diameter or sections (not both, not neither)")
        if len(self.bearing_stiffness) > 2:
            raise ValueError(f"bearing_stiffness: {len(self.bearing_stiffness)} values: give "
                             "one for both bearings or one each")
        if self.bearings[0] == self.bearings[1]:
            raise ValueError(f"bearings: {self.bearings[0]} mm twice: two distinct positions")
        for start, end, _ in self.sections:
            if not end > start:
                raise ValueError(f"sections: [{start}, {end}] mm must run from a smaller "
                                 "position to a larger one")
        return self


class Member(Model):
    """One gear of the pair: its shift, face width, tip diameter and flank modifications (both
    flanks)."""

    profile_shift: float = Field(0.0, ge=-1.5, le=1.5, description="x, in [-1.5, 1.5]")
    face_width: Length | None = None
    tip_diameter: Length | None = Field(
        None, description="the tip diameter d_a as drawn, e.g. '82.46 mm' (a ring's: its "
                          "inner diameter); default from rack.addendum and the profile shift")
    crown: CrownSpec | None = None
    profile_crown: ProfileCrownSpec | None = None
    tip_relief: ReliefSpec | None = None
    root_relief: ReliefSpec | None = None
    helix_slope: HelixSlopeSpec | None = None
    profile_slope: ProfileSlopeSpec | None = None
    twist: TwistSpec | None = None
    topography: TopographySpec | None = None
    k_chart: KChartSpec | None = None
    tip_edge: TipEdgeSpec | None = None
    end_relief: EndReliefSpec | None = None
    end_chamfer: EndChamferSpec | None = None
    shaft: ShaftSpec | None = None
    roughness_Ra: Roughness | None = ROUGHNESS_FIELD
    root_roughness_Rz: Roughness | None = Field(
        None, description="the tooth root's mean peak-to-valley roughness Rz, e.g. '10 um' "
                          "(ISO 6336-3's Y_RrelT; default: Y_RrelT = 1, the reference test "
                          "gear's Rz of about 10 um)")

    @model_validator(mode="after")
    def _one_measurement(self):
        if self.topography is not None and self.k_chart is not None:
            raise ValueError("topography / k_chart: give the measured flank one way, as a grid "
                             "or as a K-chart")
        return self


class ExportSpec(Model):
    teeth: int | None = Field(None, ge=1, description="export a sector of this many teeth")
    stl_tolerance: Length = Field(0.01, description="chordal deviation of the STL, e.g. '0.01 mm'")


class MisalignmentSpec(Model):
    slope: Slope = Field(0.0, description="tilt in the plane of action, rad; + closes end B")
    slope_normal: Slope = Field(0.0, description="tilt normal to the plane of action, rad")
    center_distance_error: SignedLength = Field(0.0, description="e.g. '0.02 mm'")
    axial_shift: SignedLength = Field(0.0, description="of the gear, e.g. '0.5 mm'")


class DeflectionSpec(Model):
    """Pinion deflection along the face, toward the gear (positive closes the gap)."""

    slope: Slope = Field(0.0, description="linear: equivalent slope, rad")
    bending: SignedLength = Field(0.0, description="parabolic: value at the face ends")
    table: list[tuple[SignedLength, SignedLength]] = Field(
        [], description="[[face position, deflection], ...], e.g. [['-15 mm', '0 um']]")


class LoadLevel(Model):
    """One level of a duty cycle: its load on the pinion and the load cycles of each pinion
    tooth at it."""

    tangential_load: Force | None = Field(None, description="at the pinion's operating pitch circle")
    torque: Torque | None = Field(None, description="on the pinion, e.g. '240 N*m'")
    cycles: Cycles = Field(
        description="load cycles of each pinion tooth at this level, e.g. 2e8")

    @model_validator(mode="after")
    def _one(self):
        if (self.tangential_load is None) == (self.torque is None):
            raise ValueError("tangential_load / torque: give exactly one of them")
        return self


class LoadSpec(Model):
    tangential_load: Force | None = Field(None, description="at the pinion's operating pitch circle")
    torque: Torque | None = Field(None, description="on the pinion, e.g. '240 N*m'")
    spectrum: list[LoadLevel] = Field(
        [], description="a duty cycle: [[load.spectrum]] levels, each analysed; Miner's sums "
                        "against ISO 6336-6's S-N curves")

    @model_validator(mode="after")
    def _one(self):
        if (self.tangential_load is None) == (self.torque is None):
            raise ValueError("load.tangential_load / load.torque: give exactly one of them")
        return self


#: the search grid's bounds: points per side, and points in all
SEARCH_GRID_SIDE, SEARCH_GRID_POINTS = (3, 1001), 100_000


class AnalysisSpec(Model):
    positions: int = Field(21, ge=1, le=401, description="mesh positions over one pitch")
    grid: tuple[int, int] = Field((25, 41), description="[profile, face] search grid")

    @field_validator("field_grid", "pressure_grid")
    @classmethod
    def _off_or_enough(cls, value: int, info) -> int:
        least = {"field_grid": 11, "pressure_grid": 8}[info.field_name]
        if 0 < value < least:
            raise ValueError(f"{value}: 0 (none) or at least {least} points a side")
        return value

    @field_validator("grid")
    @classmethod
    def _grid(cls, value: tuple[int, int]) -> tuple[int, int]:
        low, high = SEARCH_GRID_SIDE
        if not all(low <= n <= high for n in value):
            raise ValueError(f"{list(value)}: each side must have {low} to {high} points")
        if value[0] * value[1] > SEARCH_GRID_POINTS:
            raise ValueError(f"{list(value)}: at most {SEARCH_GRID_POINTS} points in all")
        return value

    approach: Length = Field(0.00632, description="rigid approach for the pattern")
    field_grid: int = Field(201, ge=0, le=1001,
                            description="points per side of each contact's separation field in "
                                        "the common tangent plane, on which the rigid pattern "
                                        "is measured; 0 = none")
    interference: bool = Field(True, description="collide the bodies (python-fcl)")
    pressure_grid: int = Field(128, ge=0, le=1024,
                               description="n: the loaded-contact (half-space) grid of each "
                                           "contact has about n² cells, as square as the "
                                           "contact's box allows; 0 = Hertz only")
    positions_check: bool = Field(
        True, description="solve the loaded contact again midway between the positions (twice "
                          "as many in all) and report how far the largest loaded pressure "
                          "moves (summary positions_check)")
    subsurface: bool | None = Field(
        None, description="the stresses below each loaded contact (largest principal shear "
                          "and von Mises stress and their depths); default: in a run, not "
                          "in a sweep's samples")
    rigid_patterns: bool | None = Field(
        None, description="measure each contact's rigid pattern on its separation field "
                          "(the rows' rigid_pattern_* keys); default: in a run, and in a "
                          "sweep's samples only where their rows are kept")
    ease_off: bool | None = Field(
        None, description="map the ease-off of the flank over the cycle (the result's "
                          "ease_off section and picture, and the rendered pattern and "
                          "pressure, which are painted on it); default: in a run, not in a "
                          "sweep's samples")


#: the default material, steel, in core units (MPa); built without parsing its units, so
#: that importing the schema does not build the unit registry (a test checks it is STEEL)
DEFAULT_STEEL = Material.model_construct(E=206000.0, nu=0.3)
#: the same for a gear pair's members (GearMaterial), built the same way
DEFAULT_GEAR_STEEL = GearMaterial.model_construct(E=206000.0, nu=0.3)


class SpurCase(GearPairGeometry):
    """A parallel-axis pair, spur or helical (helix_angle), external or internal."""

    kind: Literal["spur"]
    helix_angle: Angle = Field(0.0, description="e.g. '15 deg'; 0 for spur")
    hand: Literal["right", "left"] = Field("right", description="the pinion's hand")
    face_width: Length = Field(description="e.g. '30 mm'")
    center_distance: Length | None = None
    backlash: Annotated[float, quantity("length", low=0.0)] | None = Field(
        None, description="normal backlash j_bn the teeth are thinned for, half on each "
                          "member, e.g. '0.1 mm'; default ISO/TR 10064-2's least recommended "
                          "(2/3)(0.06 + 0.0005·a + 0.03·m_n) mm; '0 mm' for teeth as the rack "
                          "gives them (both flanks touch)")
    rack: Rack = Rack()
    pinion: Member = Member()
    gear: Member = Member()
    material: GearMaterial = Field(DEFAULT_GEAR_STEEL, description="default steel")
    gear_material: GearMaterial | None = None
    misalignment: MisalignmentSpec = MisalignmentSpec()
    deflection: DeflectionSpec | None = None
    load: LoadSpec | None = Field(None, description="with a load, run analyses the contact")
    rating: RatingSpec = RatingSpec()
    operation: OperationSpec | None = Field(
        None, description="speed and oil temperature: with [lubricant], the lubricated "
                          "contact (sliding, film, flash temperature, losses)")
    lubricant: LubricantSpec | None = None
    analysis: AnalysisSpec = AnalysisSpec()
    export: ExportSpec = ExportSpec()

    @model_validator(mode="after")
    def _lubricated(self):
        lubricated_pair(self, {"pinion": (self.pinion, self.material),
                               "gear": (self.gear, self.gear_material or self.material)},
                        friction_needed=False)
        if self.rating.life is not None and self.operation is None:
            raise ValueError("rating.life: the load cycles follow from the life and the "
                             "speed: give [operation] pinion_speed, or rating.pinion_cycles")
        return self

    @model_validator(mode="after")
    def _helix(self):
        if not 0 <= self.helix_angle < math.radians(45):
            raise ValueError(f"helix_angle: {math.degrees(self.helix_angle):.4g} deg must lie "
                             "in [0, 45) deg")
        if self.rack.root_radius >= self.rack.dedendum:
            raise ValueError("rack.root_radius: must be smaller than rack.dedendum")
        return self


class SplineCase(CaseInfo, ModuleOrPitch):
    """An involute spline (hub and sleeve) with an optional lead crown on the hub teeth."""

    kind: Literal["spline"]
    teeth: int = Field(ge=6, description="spline teeth (>= 6)")
    pressure_angle: Angle = Field(description="30, 37.5 or 45 deg")
    root: Literal["flat", "fillet"] = "fillet"
    engaged_length: Length
    tooth_thickness: Length = Field(description="hub tooth thickness T_mod at the crown centre")
    clearance: SignedLength = Field(description="dT: sleeve space width minus T_mod")
    tip_edge: TipEdgeSpec | None = Field(
        None, description="the rounding of the hub's and the sleeve's tooth tips (radius); "
                          "none given: sharp tips")
    crown: CrownSpec | None = Field(None, description="lead crown of the hub teeth, measured in "
                                                      "the tooth-thickness direction (seed 003)")
    material: Material = Field(DEFAULT_STEEL, description="default steel")
    misalignment: Slope = Field(0.0, description="angular misalignment of the sleeve, rad")
    torque: Torque | None = Field(None, description="with a torque, run analyses the contact")
    analysis: AnalysisSpec = Field(AnalysisSpec(positions=3, grid=(9, 41)),
                                   description="positions over one tooth pitch, grid")
    export: ExportSpec = ExportSpec()

    @model_validator(mode="after")
    def _size(self):
        if (self.module is None) == (self.diametral_pitch is None):
            raise ValueError("module / diametral_pitch: give exactly one of them")
        return self


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


class SplineCrownCase(CaseInfo, ModuleOrPitch):
    kind: Literal["spline_crown"]
    teeth: int = Field(ge=6, description="spline teeth (>= 6)")
    pitch_diameter: Length | None = None
    pressure_angle: Angle = Field(description="30, 37.5 or 45 deg")
    torque: Torque
    misalignment: Angle = Field(description="angular misalignment, e.g. '0.1 deg'")
    engaged_length: Length
    working_depth: Length
    tooth_thickness: Length = Field(description="T_mod at the crown centre")
    clearance: Length = Field(description="dT, space width minus tooth thickness")
    material: Material
    sleeve_material: Material | None = None

    @model_validator(mode="after")
    def _size(self):
        given = [n for n in ("pitch_diameter", "module", "diametral_pitch")
                 if getattr(self, n) is not None]
        if len(given) != 1:
            raise ValueError("pitch_diameter / module / diametral_pitch: give exactly one")
        if not 0 < self.misalignment < math.radians(10):
            raise ValueError(f"misalignment: {math.degrees(self.misalignment):.4g} deg must "
                             "lie between 0 and 10 deg")
        return self

    @property
    def pitch_diameter_mm(self) -> float:
        if self.pitch_diameter is not None:
            return self.pitch_diameter
        return self.module_mm * self.teeth


class ImportedBody(Model):
    """A body from a file, in its own frame: its axis is the file's z axis."""

    file: str = Field(description="an .stl, .step or .stp file, relative to the case file")
    teeth: int = Field(ge=3, description="number of teeth of the whole gear (>= 3)")
    form_diameter: Length | None = Field(None, gt=0, description="where the active flank "
                                         "starts; the form edge is checked only when given")

    @field_validator("file")
    @classmethod
    def _exists(cls, value: str, info) -> str:
        if Path(value).suffix.lower() not in (".stl", ".step", ".stp"):
            raise ValueError(f"{shown(value)}: must be an .stl, .step or .stp file")
        return str(_given_file(value, info).resolve())


class ImportedCase(CaseInfo):
    """A parallel-axis pair from a user's STL or STEP bodies, analysed on their meshes."""

    kind: Literal["imported"]
    pinion: ImportedBody
    gear: ImportedBody
    center_distance: Length
    pressure_angle: Angle = Field(math.radians(20.0),
                                  description="working transverse pressure angle (the plane "
                                              "of action the slopes refer to), default 20 deg")
    base_helix_angle: Annotated[float, quantity("angle", low=0.0, high=math.radians(60.0))] = Field(
        0.0, description="for the normal load, 0 to 60 deg; 0 for spur")
    pinion_phase: Angle = Field(0.0, description="the pinion's turn from its file's position "
                                                 "at the start (default 0: a tooth on the "
                                                 "file's +x axis faces the gear)")
    gear_phase: Angle = Field(math.pi, description="the gear's turn from its file's position "
                                                   "at the start; the mesh is sought within two "
                                                   "pitches of it (default 180 deg: a tooth on "
                                                   "the file's +x axis faces the pinion)")
    step_tolerance: Length = Field(0.002, description="chordal tolerance to tessellate STEP")
    material: Material = Field(DEFAULT_STEEL, description="default steel")
    gear_material: Material | None = None
    misalignment: MisalignmentSpec = MisalignmentSpec()
    load: LoadSpec
    analysis: AnalysisSpec = AnalysisSpec(positions=11)

    @model_validator(mode="after")
    def _angles(self):
        _check_pair_pressure_angle(self.pressure_angle)
        return self


KINDS: dict[str, type[CaseInfo]] = {
    "hertz": HertzCase,
    "crown_design": CrownDesignCase,
    "worm_efficiency": WormEfficiencyCase,
    "spline_crown": SplineCrownCase,
    "spur": SpurCase,
    "spline": SplineCase,
    "worm": WormCase,
    "imported": ImportedCase,
}
#: the case kinds whose members are generated as solids (export, STEP/STL)
SOLID_KINDS = ("spur", "spline", "worm")


def read_table(path: str | Path) -> dict:
    """A TOML file's table; a CaseError names the file where it cannot be read."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise CaseError(f"{path}: no such case file") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise CaseError(f"{path}: cannot read it ({exc})") from None
    try:
        table = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise CaseError(f"{path}: not valid TOML ({_toml_problem(exc, text)})") from None
    except RecursionError:
        raise CaseError(f"{path}: {TOO_DEEP}") from None
    if _depth(table) > MAX_DEPTH:
        raise CaseError(f"{path}: {TOO_DEEP}")
    return table


#: the deepest nesting of arrays and tables a case file may have (a case needs 4)
MAX_DEPTH = 16
TOO_DEEP = f"arrays or tables nested more than {MAX_DEPTH} deep (a case needs 4)"


def _depth(value, level: int = 0) -> int:
    """How deep arrays and tables nest in `value` (stops counting past MAX_DEPTH)."""
    if level > MAX_DEPTH or not isinstance(value, (dict, list)):
        return level
    children = value.values() if isinstance(value, dict) else value
    return max((_depth(v, level + 1) for v in children), default=level + 1)


def _toml_problem(exc: tomllib.TOMLDecodeError, text: str) -> str:
    """tomllib's message, with the key named where it says a value is given twice."""
    message = str(exc)
    at = re.search(r"at line (\d+)", message)
    if "Cannot overwrite" in message and at:
        key = text.splitlines()[int(at.group(1)) - 1].split("=", 1)[0].strip()
        return f"{key!r} is given twice ({message})"
    return message


def load_case(path: str | Path) -> tuple[CaseInfo, dict]:
    """Read and validate a case file; returns the model and the raw table (units as given)."""
    raw = read_table(path)
    return parse_case(raw, source=str(path), base=Path(path).parent), raw


def parse_case(raw: dict, source: str = "case", base: Path | None = None) -> CaseInfo:
    """Validate a case table (as read from TOML) into its kind's model; files it names are
    found relative to `base` (the case file's folder)."""
    if _depth(raw) > MAX_DEPTH:
        raise CaseError(f"{source}: {TOO_DEEP}")
    kind = raw.get("kind")
    allowed = ", ".join(KINDS)
    if kind is None:
        raise CaseError(f"{source}: kind: missing; allowed: {allowed}")
    if not isinstance(kind, str) or kind not in KINDS:
        raise CaseError(f"{source}: kind: {shown(kind)} is not a known kind; allowed: {allowed}")
    model = KINDS[kind]
    try:
        return model.model_validate(raw, context={"base": base})
    except ValidationError as exc:
        raise CaseError(f"{source}: {describe(exc, model)}") from None


def describe(exc: ValidationError, model: type[BaseModel]) -> str:
    """One line for the first validation error: field, value, what is allowed."""
    error = exc.errors(include_url=False)[0]
    field = _dotted(error["loc"])
    message = error["msg"].removeprefix("Value error, ")
    if error["type"] == "missing":
        hint = _field_description(model, error["loc"])
        return f"{field}: missing" + (f"; expected {hint}" if hint else "")
    if error["type"] == "extra_forbidden":
        return f"{field}: unknown field (check the spelling; see the README for each kind)"
    if not field:
        return message
    if error["type"] in ("value_error", "assertion_error") and (
            repr(error["input"]) in message or isinstance(error["input"], dict)):
        # a table's own check names its fields: the table itself is not repeated
        return f"{field}: {_shortened(message)}"
    return f"{field}: {shown(error['input'])}: {_shortened(message)}"


#: the most characters of a given value a message repeats
SHOWN = 60


def shown(value) -> str:
    """A given value as a message shows it: its repr, cut to SHOWN characters."""
    return _cut(repr(value))


def _cut(text: str) -> str:
    return text if len(text) <= SHOWN else f"{text[:SHOWN]}… ({len(text)} characters)"


def _shortened(message: str) -> str:
    """A message with every long quoted value in it cut (see shown)."""
    return re.sub(rf"'[^']{{{SHOWN},}}'", lambda m: _cut(m.group(0)), message)


def _dotted(loc: tuple) -> str:
    out = ""
    for part in loc:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else str(part))
    return out


def _field_description(model: type[BaseModel], loc: tuple) -> str:
    current: Any = model
    info = None
    for part in loc:
        if isinstance(part, int) or not (isinstance(current, type) and issubclass(current, BaseModel)):
            continue
        info = current.model_fields.get(part)
        if info is None:
            return ""
        current = info.annotation
        args = getattr(current, "__args__", ())
        current = next((a for a in args if isinstance(a, type) and issubclass(a, BaseModel)), current)
    return (info.description or "") if info else ""
