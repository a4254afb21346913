"""The case kinds: the Hertz contact of two bodies, an imported pair (STL/STEP bodies), and
KINDS, every kind's schema by its name in a case file."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated, Literal

from pydantic import (
    Field,
    field_validator,
    model_validator,
)

from .cylindrical import (
    DEFAULT_STEEL,
    AnalysisSpec,
    CrownDesignCase,
    LoadSpec,
    MisalignmentSpec,
    SplineCase,
    SplineCrownCase,
    SpurCase,
    check_pair_pressure_angle,
    given_file,
)
from .fields import Angle, Body, CaseInfo, Force, Length, Material, Model, quantity, shown
from .worm import WormCase, WormEfficiencyCase


class HertzCase(CaseInfo):
    kind: Literal["hertz"]
    load: Force = Field(description="normal load, e.g. '1000 N'")
    angle: Angle = Field(0.0, description="angle between the bodies' first principal planes")
    body1: Body
    body2: Body


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
        return str(given_file(value, info).resolve())


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
        check_pair_pressure_angle(self.pressure_angle)
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
