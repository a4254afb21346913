"""The cylindrical kinds' case schemas: spur and helical pairs (external and ring), their
members' modifications, shafts, misalignment, deflection, load, the analysis settings; the
crown design, involute splines and the spline crown design."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated, Any, Literal

from pydantic import (
    Field,
    field_validator,
    model_validator,
)

from .fields import (
    ROUGHNESS_FIELD,
    Angle,
    CaseInfo,
    CrownRadius,
    Cycles,
    Factor,
    Force,
    GearMaterial,
    InverseLength,
    Length,
    LubricantSpec,
    Material,
    Model,
    Modulus,
    OperationSpec,
    Poisson,
    RatingSpec,
    Roughness,
    SignedLength,
    Slope,
    Stiffness,
    Torque,
    cut_shown,
    lubricated_pair,
    quantity,
    shown,
)


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


def check_pair_pressure_angle(angle: float) -> None:
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
        check_pair_pressure_angle(self.pressure_angle)
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
            path = given_file(raw["file"], info)
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


def given_file(name: Any, info) -> Path:
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
        raise ValueError(f"{shown(name)}: no such file ({cut_shown(str(path))})")
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

    @field_validator("subsurface", mode="before")
    @classmethod
    def _subsurface(cls, value: Any) -> Any:
        if value is not None and not isinstance(value, bool) and value != "all":
            raise ValueError(f"{value!r}: must be true, false or \"all\"")
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
        True, description="solve the loaded contact again between the positions where the "
                          "largest loaded pressure or the transmission error's extremes can "
                          "hide (adaptive bisection, steps down to 1/8) and report how far "
                          "they move (summary positions_check)")
    subsurface: bool | Literal["all"] | None = Field(
        None, description="the stresses below the loaded contacts that can decide (largest "
                          "principal shear and von Mises stress and their depths; the "
                          "largest few by pressure and load and every edge-loaded one), "
                          "\"all\" below every one; default: in a run, not in a sweep's "
                          "samples")
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
