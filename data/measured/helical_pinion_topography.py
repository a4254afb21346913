"""Writes cases/helical_measured_topography.csv: a measured-style flank topography of the
bundled automotive helical pinion (z = 27, m_n = 2.25 mm, α_n = 18°, β = 27°, x = 0.25,
b = 20 mm; base diameter 64.055 mm), as a gear measuring machine reports it over its
evaluation range: 11 face positions (-9 to 9 mm from mid-face toward end B: the 20 mm
face less 1 mm at each end, as a lead evaluation range leaves out) × 9 diameters (65.6 to
73.6 mm), normal deviations in µm, positive removing material.

What the grid holds, each term by its ISO 21771 meaning:
- a parabolic lead crown C_β = 8 µm (its drop at the face ends; 6.5 µm at the grid's ±9 mm);
- a profile slope f_Hα = 5 µm (material removed at the tip end of the evaluation range
  relative to its root end, linear in the roll length, none mid-profile);
- a twist of 6 µm (the profile slope -3 µm at end A, +3 µm at end B: the "bias" of
  generating grinding);
- a linear tip relief C_a = 12 µm from 71.6 mm to the tip diameter 73.81 mm (12 µm there,
  9.5 µm at 73.6 mm);
- measurement noise, normal with σ = 0.3 µm (numpy's generator, seed 2026).

Run from the repository root: python data/measured/helical_pinion_topography.py
"""

from __future__ import annotations

import csv
import math
import sys
from pathlib import Path

import numpy as np

BASE_DIAMETER = 64.05514857    # mm: 27 × 2.25 / cos 27° × cos α_t, tan α_t = tan 18°/cos 27°
FACE_WIDTH = 20.0              # mm
FACE = np.linspace(-9.0, 9.0, 11)
DIAMETER = np.linspace(65.6, 73.6, 9)
CROWN, PROFILE_SLOPE, TWIST, TIP_RELIEF, NOISE = 8.0, 5.0, 6.0, 12.0, 0.3     # µm
RELIEF_START, TIP = 71.6, 73.80631894                                        # mm
SEED = 2026


def deviation_um() -> np.ndarray:
    """The grid (µm), one row per face position."""
    roll = np.sqrt((DIAMETER / 2) ** 2 - (BASE_DIAMETER / 2) ** 2)
    along_profile = (roll - 0.5 * (roll[0] + roll[-1])) / (roll[-1] - roll[0])   # -1/2..1/2
    along_face = FACE / FACE_WIDTH                                               # -1/2..1/2
    crown = CROWN * (2.0 * along_face[:, None]) ** 2
    slope = (PROFILE_SLOPE + TWIST * along_face[:, None]) * along_profile[None, :]
    start, tip = (np.sqrt((d / 2) ** 2 - (BASE_DIAMETER / 2) ** 2) for d in (RELIEF_START, TIP))
    relief = TIP_RELIEF * np.clip((roll - start) / (tip - start), 0.0, None)[None, :]
    noise = np.random.default_rng(SEED).normal(0.0, NOISE, (len(FACE), len(DIAMETER)))
    return crown + slope + relief + noise


def write(path: Path) -> None:
    rows = [["face mm \\ diameter mm", *(f"{d:.1f}" for d in DIAMETER)]]
    rows += [[f"{f:.1f}", *(f"{v:.2f}" for v in row)] for f, row in zip(FACE, deviation_um())]
    with path.open("w", newline="", encoding="utf-8") as out:
        csv.writer(out, lineterminator="\n").writerows(rows)


if __name__ == "__main__":
    write(Path(sys.argv[1] if len(sys.argv) > 1 else "cases/helical_measured_topography.csv"))
