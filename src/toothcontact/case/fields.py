"""What every case kind is made of: quantities given as text with a unit (converted to the
core units as the model is validated), the base model that refuses unknown keys, the case's
common header, materials with their ISO 6336-5 allowables, the rating, the operation and the
lubricant. Any problem becomes one CaseError naming the field, the value and what is
allowed."""

from __future__ import annotations

import math
from typing import Annotated, Any, Literal, get_args

from pydantic import (
    AfterValidator,
    BaseModel,
    BeforeValidator,
    ConfigDict,
    Field,
    field_validator,
    model_validator,
)

from .. import units


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
    from ..analytic import lubricant

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
        from ..analytic.lubricant import WALTHER_LEAST

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


#: the most characters of a given value a message repeats
SHOWN = 60


def shown(value) -> str:
    """A given value as a message shows it: its repr, cut to SHOWN characters."""
    return cut_shown(repr(value))


def cut_shown(text: str) -> str:
    return text if len(text) <= SHOWN else f"{text[:SHOWN]}… ({len(text)} characters)"
