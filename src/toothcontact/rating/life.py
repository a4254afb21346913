"""Life factors: how much more than its endurance limit a flank (Z_NT, ISO 6336-2:2006
Table 2) or a tooth root (Y_NT, ISO 6336-3:2006 Table 1) carries for a limited number of
load cycles, and how much less for more: straight lines in log-log between the tables'
points (static, the reference at the knee, 0.85 at 10¹⁰ cycles: the long-life value
without optimum lubrication, material and manufacturing).

The materials' groups (ISO 6336-5 abbreviations): St structural steel, V through-hardened,
GGG nodular and GTS malleable cast iron (pearlitic, bainitic), Eh case-carburized, IF
flame or induction hardened, GG grey and GGG ferritic cast iron, NT nitriding steel
nitrided, NV through-hardening steel nitrided or nitrocarburized.
"""

from __future__ import annotations

import math

#: the treatments a material may name, and their group in the tables below
TREATMENTS = {
    "structural": "St", "through_hardened": "V", "case_carburized": "Eh",
    "induction_hardened": "IF", "flame_hardened": "IF", "nitrided": "NT",
    "nitrided_through_hardening_steel": "NV", "nitrocarburized": "NV(nitrocar)",
    "nodular_cast_iron": "GGG", "malleable_cast_iron": "GTS", "grey_cast_iron": "GG",
}

#: Z_NT's points (load cycles, factor) by group (ISO 6336-2:2006 Table 2): steels and
#: pearlitic cast irons where no pitting is permitted (the default), where some is
#: (`limited_pitting`), nitrided steels and grey cast iron, nitrocarburized steel
Z_NT_POINTS = {
    "steel": ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85)),
    "steel_limited_pitting": ((6e5, 1.6), (1e7, 1.3), (1e9, 1.0), (1e10, 0.85)),
    "nitrided": ((1e5, 1.3), (2e6, 1.0), (1e10, 0.85)),
    "nitrocarburized": ((1e5, 1.1), (2e6, 1.0), (1e10, 0.85)),
}

#: Y_NT's points by group (ISO 6336-3:2006 Table 1)
Y_NT_POINTS = {
    "through": ((1e4, 2.5), (3e6, 1.0), (1e10, 0.85)),       # St, V, GGG, GTS
    "surface": ((1e3, 2.5), (3e6, 1.0), (1e10, 0.85)),       # Eh, IF (root)
    "nitrided": ((1e3, 1.6), (3e6, 1.0), (1e10, 0.85)),      # GG, GGG (ferr.), NT, NV
    "nitrocarburized": ((1e3, 1.1), (3e6, 1.0), (1e10, 0.85)),
}


def _log_line(points, cycles: float) -> float:
    """The factor at `cycles`: held at the first point below it, straight in log-log
    between the points, held at the last beyond it."""
    if cycles <= points[0][0]:
        return points[0][1]
    for (n0, f0), (n1, f1) in zip(points, points[1:]):
        if cycles <= n1:
            t = math.log(cycles / n0) / math.log(n1 / n0)
            return math.exp(math.log(f0) + t * (math.log(f1) - math.log(f0)))
    return points[-1][1]


def _flank_group(treatment: str, limited_pitting: bool) -> str:
    group = TREATMENTS[treatment]
    if group in ("GG", "NT", "NV"):
        return "nitrided"
    if group == "NV(nitrocar)":
        return "nitrocarburized"
    return "steel_limited_pitting" if limited_pitting else "steel"


def _root_group(treatment: str) -> str:
    group = TREATMENTS[treatment]
    if group in ("Eh", "IF"):
        return "surface"
    if group in ("GG", "NT", "NV"):
        return "nitrided"
    if group == "NV(nitrocar)":
        return "nitrocarburized"
    return "through"


def contact_life_factor(treatment: str, cycles: float, limited_pitting: bool = False) -> float:
    """Z_NT (ISO 6336-2:2006 Table 2) of a flank of that treatment after `cycles` loads."""
    return _log_line(Z_NT_POINTS[_flank_group(treatment, limited_pitting)], cycles)


def root_life_factor(treatment: str, cycles: float) -> float:
    """Y_NT (ISO 6336-3:2006 Table 1) of a tooth root of that treatment after `cycles`."""
    return _log_line(Y_NT_POINTS[_root_group(treatment)], cycles)


def _log_line_cycles(points, factor: float) -> float:
    """The load cycles at which the line reaches `factor` (_log_line's inverse): the static
    point's cycles at or above its factor, continued past the last point with the last
    segment's slope (no endurance limit: Miner's elementary rule)."""
    if factor >= points[0][1]:
        return points[0][0]
    for (n0, f0), (n1, f1) in zip(points, points[1:]):
        if factor >= f1:
            t = math.log(factor / f0) / math.log(f1 / f0)
            return math.exp(math.log(n0) + t * math.log(n1 / n0))
    (n0, f0), (n1, f1) = points[-2:]
    t = math.log(factor / f0) / math.log(f1 / f0)
    return math.exp(math.log(n0) + t * math.log(n1 / n0))


def contact_cycles(treatment: str, factor: float, limited_pitting: bool = False) -> float:
    """The load cycles a flank endures at the stress σ_Hlim·factor: the S-N curve of Z_NT
    (ISO 6336-6's for pitting, Z_NT's line continued past 10¹⁰)."""
    return _log_line_cycles(Z_NT_POINTS[_flank_group(treatment, limited_pitting)], factor)


def root_cycles(treatment: str, factor: float) -> float:
    """The load cycles a tooth root endures at the stress σ_Flim·Y_ST·factor (Y_NT's line)."""
    return _log_line_cycles(Y_NT_POINTS[_root_group(treatment)], factor)
