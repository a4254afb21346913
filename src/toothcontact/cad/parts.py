"""The solids of a case, by part name: what `export` writes."""

from __future__ import annotations

from .. import gearset, worm_gearset
from ..case import SOLID_KINDS
from .gear import build_gear
from .wheel import build_wheel
from .worm import build_worm


def build_parts(case) -> dict:
    """Bodies (with .solid, .description, .flank_deviation()) of a spur, spline or worm case.
    Gears may be exported as a sector (`[export] teeth`)."""
    if case.kind == "worm":
        parts = worm_gearset.worm_set(case)
        n = case.export.teeth
        sector = n if n is not None and n < case.wheel.teeth else None
        return {"worm": build_worm(parts.worm["left"], parts.worm["right"]),
                "wheel": build_wheel(parts.wheel["left"], parts.wheel["right"], teeth=sector)}
    if case.kind == "spur":
        pair = gearset.gear_pair(case)
        gears = {"pinion": (pair.pinion, pair.pinion_modifications),
                 "gear": (pair.gear, pair.gear_modifications)}
    elif case.kind == "spline":
        pair = gearset.spline_pair(case)
        gears = {"hub": (pair.hub, pair.hub_modifications),
                 "sleeve": (pair.sleeve, pair.sleeve_modifications)}
    else:
        raise ValueError(f"kind {case.kind!r} has no solids; solids exist for {SOLID_KINDS}")
    return {name: build_gear(gear, mods, teeth=_sector(case, gear)) for name, (gear, mods) in gears.items()}


def _sector(case, gear) -> int | None:
    """Teeth to build: the case's sector size, for external gears with more teeth."""
    n = case.export.teeth
    return n if n is not None and not gear.internal and n < gear.teeth else None
