"""Case files: TOML in, validated models out. The only package that reads input.

Every quantity is text with a unit ("1.44 in", "3600 lbf", "-50 degC"); it is converted to
the core units (mm, N, MPa, N·mm, rad) by `units.parse` as the model is validated. Any
problem becomes one `CaseError` whose message names the field, the value and what is allowed.

fields: quantities, the base model, materials, rating, operation, lubricant; cylindrical and
worm: the kinds' schemas; kinds: the Hertz and imported kinds and KINDS by name; loading:
TOML read, validated, and the message a bad case gets. The names below are the package's
interface to the rest of the tool.
"""

from .cylindrical import (
    AnalysisSpec,
    CrownDesignCase,
    CrownSpec,
    EndChamferSpec,
    LoadSpec,
    Member,
    SplineCase,
    SplineCrownCase,
    SpurCase,
    TipEdgeSpec,
)
from .fields import CAST_IRONS, GIVEN_FACTORS, CaseError, CaseInfo, Model, shown
from .kinds import KINDS, SOLID_KINDS, HertzCase, ImportedCase
from .loading import describe, load_case, parse_case, read_table
from .worm import Condition, WormCase, WormEfficiencyCase

__all__ = [
    "AnalysisSpec",
    "CAST_IRONS",
    "CaseError",
    "CaseInfo",
    "Condition",
    "CrownDesignCase",
    "CrownSpec",
    "EndChamferSpec",
    "GIVEN_FACTORS",
    "HertzCase",
    "ImportedCase",
    "KINDS",
    "LoadSpec",
    "Member",
    "Model",
    "SOLID_KINDS",
    "SplineCase",
    "SplineCrownCase",
    "SpurCase",
    "TipEdgeSpec",
    "WormCase",
    "WormEfficiencyCase",
    "describe",
    "load_case",
    "parse_case",
    "read_table",
    "shown",
]
