"""A lubricant at its operating temperature: kinematic viscosity through two measured points
(ASTM D341, Walther's equation), density with thermal expansion, dynamic viscosity, and the
stated defaults of the oil families (density, pressure-viscosity coefficient, ISO/TR
14179-2's lubricant factor X_L). Units: mm²/s, kg/m³, degC, Pa·s, 1/MPa."""

from __future__ import annotations

import math
from dataclasses import dataclass

#: ASTM D341's Walther offset: log log(ν + 0.7) is linear in log T (ν in mm²/s, T in K)
WALTHER_OFFSET = 0.7
#: the least kinematic viscosity (mm²/s) the equation holds for with the offset 0.7 alone:
#: below 2.0 mm²/s ASTM D341 adds exponential terms (Z = ν + 0.7 + exp(-1.47 - 1.84ν -
#: 0.51ν²) ...) that this module does not carry, so the oil is held at or above it, given
#: and at its temperature (ASTM D341-20 §5, as Technical Toolboxes' guide to it states)
WALTHER_LEAST = 2.0
#: the two temperatures (degC) the case gives the oil's viscosity at: outside them the
#: line is extrapolated
MEASURED = (40.0, 100.0)
KELVIN = 273.15
#: the volumetric thermal expansion of the oil's density (1/K), a mineral oil's typical
#: value (density falls by about 0.064 % per kelvin), assumed for every family
EXPANSION = 6.4e-4


@dataclass(frozen=True)
class Family:
    """An oil family's defaults where the case gives none: density at 15 °C (kg/m³), the
    pressure-viscosity coefficient (1/MPa, typical at 40-100 °C, taken constant) and ISO/TR
    14179-2's lubricant factor X_L of the mesh friction coefficient."""

    density_15: float
    pressure_viscosity: float
    X_L: float


#: typical values (a measured density and pressure-viscosity coefficient should be given
#: where known: the film thickness goes with α^0.5); X_L: ISO/TR 14179-2 (mineral oil 1.0,
#: polyalphaolefin 0.8, non-water-soluble polyglycol 0.7)
FAMILIES = {"mineral": Family(890.0, 0.020, 1.0),
            "pao": Family(850.0, 0.016, 0.8),
            "pag": Family(1010.0, 0.013, 0.7)}

#: the pour point (degC) taken for a family's oil where the case gives none: ASTM D341's
#: line holds only where the oil is a homogeneous liquid ("between the cloud point at low
#: temperatures and the initial boiling point", D341 §3.1), so no oil or bulk temperature
#: below it is taken. Mineral: -15 degC, an ISO VG 460 mineral oil's (a mineral oil's pour
#: point rises with its grade, ISO VG 46 about -39 degC: Panther Lubes, "Pour point"; the
#: heaviest gear grade's is taken, a lighter oil gives its own); PAO: -45 degC (an ISO VG 32
#: polyalphaolefin pours below -50 degF: Efficient Plant, "Introduction to synthetic
#: lubricants", 2007; a gear grade's lies higher); PAG: -30 degC, assumed (no public figure
#: found; polyglycols are said to have good low-temperature properties: Beatty & Greaves,
#: Machinery Lubrication, "Polyalkylene glycol synthetic PAG oil explained")
POUR_POINTS = {"mineral": -15.0, "pao": -45.0, "pag": -30.0}


def kinematic_viscosity(nu_40: float, nu_100: float, temperature: float) -> float:
    """ν (mm²/s) at `temperature` (degC, above absolute zero) on the straight line of ASTM
    D341 through ν at 40 and 100 °C (each at least WALTHER_LEAST): log10 log10(ν + 0.7) =
    A - B·log10(T/K); inf where the line runs past the largest float (far below any
    oil's pour point)."""
    def walther(nu):
        return math.log10(math.log10(nu + WALTHER_OFFSET))

    t40, t100, t = (math.log10(x + KELVIN) for x in (*MEASURED, temperature))
    slope = (walther(nu_100) - walther(nu_40)) / (t100 - t40)
    try:
        return 10.0 ** 10.0 ** (walther(nu_40) + slope * (t - t40)) - WALTHER_OFFSET
    except OverflowError:
        return math.inf


def extrapolated(temperature: float) -> bool:
    """Whether ν at `temperature` (degC) lies off the measured span of ASTM D341's line."""
    return not MEASURED[0] <= temperature <= MEASURED[1]


def density(density_15: float, temperature: float) -> float:
    """ρ (kg/m³) at `temperature` (degC) from ρ at 15 °C (EXPANSION)."""
    return density_15 * (1.0 - EXPANSION * (temperature - 15.0))


def dynamic_viscosity(nu_40: float, nu_100: float, density_15: float,
                      temperature: float) -> float:
    """η (Pa·s) = ν·ρ at `temperature` (degC)."""
    return kinematic_viscosity(nu_40, nu_100, temperature) * 1e-6 * density(density_15,
                                                                            temperature)
