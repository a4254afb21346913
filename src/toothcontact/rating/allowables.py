"""Allowable stress numbers of gear materials: ISO 6336-5:2016 Table 1, σ_Hlim (contact) and
σ_Flim (nominal bending) as σ = A·x + B of the surface hardness x (HBW or HV, by row), for
the material quality grades ML, MQ and ME, each fit valid over its row's hardness range.

The table is package data (iso6336_5_table1.csv, with its source in its header); a hardness
outside a row's range, or in the other hardness scale, is refused: the standard gives no
value there (ISO 6336-5 gives no conversion between HV and HBW either). Units: N/mm² (MPa).
"""

from __future__ import annotations

import csv
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources

from .life import TREATMENTS

GRADES = ("ML", "MQ", "ME")
#: the core hardness (HRC) from which a case-hardened MQ root takes Table 1's row 47
#: (500 N/mm²) instead of row 45 (425 N/mm², core hardness at least 25 HRC)
CORE_HRC_FOR_ROW_47 = 30.0
CORE_HRC_LEAST = 25.0


@dataclass(frozen=True)
class Row:
    """One row of Table 1."""

    number: int
    stress: str              # "contact" or "bending"
    group: str
    variant: str             # "carbon" / "alloy" (V), a case-hardened core condition, or ""
    grades: tuple[str, ...]
    A: float
    B: float
    unit: str                # "HV" or "HBW"
    low: float
    high: float

    def value(self, hardness: float) -> float:
        """σ (N/mm²) at the hardness (the row's unit)."""
        return self.A * hardness + self.B


@dataclass(frozen=True)
class Allowable:
    """An allowable stress number and the row it comes from."""

    value: float             # N/mm²
    row: Row

    @property
    def source(self) -> str:
        return (f"ISO 6336-5:2016 Table 1 row {self.row.number} "
                f"({self.row.A:g}·x + {self.row.B:g}, {self.row.low:g}-{self.row.high:g} "
                f"{self.row.unit})")


@lru_cache(maxsize=1)
def table() -> tuple[Row, ...]:
    """Table 1's 73 rows, read from the package's CSV."""
    text = resources.files(__package__).joinpath("iso6336_5_table1.csv").read_text("utf-8")
    lines = [line for line in text.splitlines() if line and not line.startswith("#")]
    return tuple(Row(int(r["row"]), r["stress"], r["group"], r["variant"],
                     tuple(r["grades"].split()), float(r["A"]), float(r["B"]), r["unit"],
                     float(r["min"]), float(r["max"]))
                 for r in csv.DictReader(lines))


def group(treatment: str, cast: bool) -> str:
    """The Table 1 group of a treatment (rating.life.TREATMENTS: ISO 6336-5's abbreviations;
    structural and through-hardened steels have cast rows of their own: 'St(cast)',
    'V(cast)')."""
    name = TREATMENTS[treatment]
    return f"{name}(cast)" if cast and name in ("St", "V") else name


def allowable(stress: str, treatment: str, hardness: float, scale: str, grade: str, *,
              cast: bool = False, alloy: bool | None = None,
              core_hrc: float | None = None) -> Allowable:
    """σ_Hlim (stress "contact") or σ_Flim ("bending") of a material: its treatment, surface
    hardness in `scale` ("HV" or "HBW"), quality grade, whether cast, whether an alloy
    steel (through-hardened steels) and the core hardness (HRC; case-hardened MQ roots).
    Raises ValueError, naming what is wrong and what is allowed, where Table 1 has no row."""
    name = group(treatment, cast)
    if cast and TREATMENTS[treatment] not in ("St", "V"):
        raise ValueError(f"cast: Table 1 has cast rows only for structural and through-"
                         f"hardened steels, not {treatment.replace('_', ' ')}")
    if grade not in GRADES:
        raise ValueError(f"quality: {grade!r}; one of {', '.join(GRADES)}")
    rows = [r for r in table() if r.stress == stress and r.group == name and grade in r.grades]
    if name.startswith("V"):
        if alloy is None:
            raise ValueError("alloy: say whether the through-hardened steel is an alloy steel "
                             "(true) or a carbon steel (false): Table 1 rates them apart")
        rows = [r for r in rows if r.variant == ("alloy" if alloy else "carbon")]
    if name == "Eh" and stress == "bending" and grade == "MQ":
        rows = [r for r in rows if r.number == _case_hardened_mq_row(core_hrc)]
    if rows[0].unit != scale:
        raise ValueError(f"hardness: Table 1 rates {treatment.replace('_', ' ')} by {rows[0].unit}, "
                         f"not {scale}; give it in {rows[0].unit} (e.g. '{rows[0].low:g} "
                         f"{rows[0].unit}')")
    inside = [r for r in rows if r.low <= hardness <= r.high]
    if not inside:
        low, high = min(r.low for r in rows), max(r.high for r in rows)
        raise ValueError(f"hardness: {hardness:g} {scale} lies outside Table 1's range for "
                         f"{treatment.replace('_', ' ')}, grade {grade} ({stress}): "
                         f"{low:g} to {high:g} {scale}")
    row = inside[0]
    return Allowable(row.value(hardness), row)


def _case_hardened_mq_row(core_hrc: float | None) -> int:
    """Row 45 (core hardness at least 25 HRC, the band's lower line) or 47 (at least 30 HRC);
    row 46, the band's upper line, needs the figure's footnotes (not at hand), so it is
    never chosen."""
    if core_hrc is None:
        return 45
    if core_hrc < CORE_HRC_LEAST:
        raise ValueError(f"core_hardness: {core_hrc:g} HRC; Table 1's case-hardened MQ rows "
                         f"need at least {CORE_HRC_LEAST:g} HRC")
    return 47 if core_hrc >= CORE_HRC_FOR_ROW_47 else 45
