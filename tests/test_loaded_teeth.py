"""The loaded contact with the teeth's bending along the face (contact.compliance) against
ISO 6336-1: the mesh stiffness of standard pairs (c', c_γα) and the face load factor K_Hβ
of an uncrowned pair under a slope."""

from __future__ import annotations

import math

import numpy as np
import pytest

from toothcontact.analyses import analyse
from toothcontact.rating.load_factors import face_load_factor
from toothcontact.case import parse_case


def spur(teeth, module, face, helix=0.0, slope=0.0, line_load=300.0, positions=9):
    """An uncrowned steel pair at line_load N/mm of tangential load."""
    return analyse(parse_case({
        "kind": "spur", "title": "stiffness check", "teeth": list(teeth),
        "module": f"{module} mm", "pressure_angle": "20 deg", "helix_angle": f"{helix} deg",
        "face_width": f"{face} mm", "misalignment": {"slope": f"{slope}"},
        "load": {"tangential_load": f"{line_load * face} N"},
        "analysis": {"positions": positions, "interference": False, "positions_check": False}}))


@pytest.fixture(scope="module")
def aligned():
    return spur((20, 60), 3, 20)


@pytest.mark.parametrize("teeth, module, face, helix, within", [
    ((20, 60), 3, 20, 0.0, 0.12), ((17, 80), 4, 30, 0.0, 0.12), ((25, 75), 3, 20, 15.0, 0.23)])
def test_the_mesh_stiffness_of_standard_pairs_is_isos(teeth, module, face, helix, within,
                                                      aligned):
    """The model's mean mesh stiffness against ISO 6336-1's c_γα and its single-pair
    stiffness against c' (Method B, solid blanks), the teeth corrected to 3D finite
    elements (compliance.SLICE_FACTOR). ISO's c' includes its basic rack factor C_B = 0.975
    of ISO 53 profile A (h_fP 1.25 m_n; taken as 1 before issue 50, which read 2.5 % higher
    ISO values). Spur pairs within 12 %: measured c_γα +10.5 % and +5.9 %, c' +8.8 % and
    +5.5 % (the 2D FE of the 20/60 pair itself, 13.84, lies +5.2 % above ISO's c' 13.15:
    tests/test_fe_mesh_stiffness.py; the 3D FE of a 25/75 pair's single-pair stiffness
    13.81 against the model's 14.21: tests/test_face_load_fe.py). The helical pair within
    23 %: measured +21.1 % (the coupling faded at the free ends, structure.end_layer,
    changed it by 0.1 %). Its contact lines cross the face obliquely, so each loads a short
    stretch of many slices, which the FE-fitted coupling (0.74 of the root chord) spreads
    along the face further than Vlasov's did (+8 % before the correction); ISO's helical
    c' is the spur value times cos β with no such term. The 3D FE of this very pair
    (tests/test_helical_stiffness_fe.py) puts its c_γα at 15.31 N/(mm·µm), ISO's 19.82 29 %
    and the model's 24.01 57 % above it: agreeing with ISO here is agreeing with a figure
    the FE does not support (the teeth's coupling through the bodies, which neither has)."""
    result = aligned if (teeth, face, helix) == ((20, 60), 20, 0.0) else spur(teeth, module, face, helix)
    s = result.sections["summary"]
    assert s["mesh_stiffness_N_per_mm_um"] == pytest.approx(s["iso_mesh_stiffness_N_per_mm_um"],
                                                            rel=within)
    if s["single_stiffness_N_per_mm_um"] is not None:       # a helical pair never has one
        assert s["single_stiffness_N_per_mm_um"] == pytest.approx(
            s["iso_single_stiffness_N_per_mm_um"], rel=within)


def test_an_aligned_uncrowned_pair_loads_its_face_evenly(aligned):
    """No slope, no crown: inside the end strips the line load of every position is its
    mean W/b within 4 % (measured: 3.8 % where a second pair enters with 2.7 µm of
    separation, elsewhere within 1.5 %)."""
    section = aligned.sections["load_distribution"]
    width = 20.0
    for line, roll in zip(section["line_load_N_per_mm"], section["roll_deg"]):
        inner = np.asarray(line)[2:-2]
        load = sum(r["bem_load_N"] for r in aligned.sections["positions"] if r["roll_deg"] == roll)
        assert np.allclose(inner, load / width, rtol=0.04)


def position_stiffness(result, width):
    """Each position's mesh stiffness (N/(mm·µm), spur): its load over the approach that
    closes its first-touching pair (the lead pair's approach, measured on its gap field
    which holds its separation, less the least separation), per mm of face."""
    rows = result.sections["positions"]
    out = {}
    for roll in {r["roll_deg"] for r in rows}:
        pairs = [r for r in rows if r["roll_deg"] == roll]
        lead = max(pairs, key=lambda r: r["bem_load_N"])
        closing = lead["bem_approach_mm"] - min(r["separation_mm"] for r in pairs)
        out[roll] = sum(r["bem_load_N"] for r in pairs) / closing / width * 1e-3
    return out


def test_a_slope_loads_the_face_as_isos_linear_misalignment(aligned):
    """An uncrowned 20/60 pair under a slope of 0.5 mrad (F_βy = 10 µm over b = 20 mm):
    at every position the line load, fitted by a line inside the end strips and taken to
    the face ends, gives K_Hβ against ISO 6336-1's 1 + F_βy·c/(2·F_m/b) with the same
    stiffness c, the position's own from the aligned pair: one pair (c ≈ 14.3) gives 1.24,
    two (c ≈ 18-21) 1.30-1.35. ISO's formula takes the slices as independent springs; the
    teeth, coupled along the face over 0.74 of the root chord (5.3 mm here, fitted to 3D
    FE: compliance.COUPLING_PER_ROOT_CHORD), resist the tilt by their twist, which takes
    load off end A and puts it on end B (a Pasternak line held to a linear deflection
    needs end forces ±λ²w'/c; the contact's own compliance spreads them over a few mm,
    into the fitted stretch; the coupling fades at the free ends over Reissner's layer,
    structure.end_layer, which softens them). So the fit lies above ISO's: measured +8.5 %
    (one pair) to +19.2 % (two pairs); asserted 0 to +21 %. The gear bodies' coupling of
    the two pairs' teeth (analytic.gear_body), nearly even along the face, softens a
    two-pair position (c ≈ 22 before it) without resisting the tilt, so ISO's formula with
    that softer c reads lower: +15.6 % before it, +8.0 % to +15.1 % before the end layer. (Before the FE correction, with Vlasov's
    2.9 mm, the fit was ISO's within 2 %.) The face ends depart from the line further: end
    A 10-26 % below it, end B 4-9 % above it (15-34 % and 6-12 % before the end layer)."""
    slope, width, line_load = 0.0005, 20.0, 300.0
    tilted = spur((20, 60), 3, width, slope=slope, line_load=line_load)
    stiffness = position_stiffness(aligned, width)
    section = tilted.sections["load_distribution"]
    face = np.asarray(section["face_mm"])
    rows = tilted.sections["positions"]
    assert set(section["roll_deg"]) == set(stiffness)
    for i, roll in enumerate(section["roll_deg"]):
        line = np.asarray(section["line_load_N_per_mm"][i])
        mean = sum(r["bem_load_N"] for r in rows if r["roll_deg"] == roll) / width
        gradient, level = np.polyfit(face[2:-2], line[2:-2], 1)
        trend = (level + gradient * 0.5 * width) / mean
        iso = face_load_factor(slope * width * 1e3, stiffness[roll], line_load)
        assert 1.0 < trend / iso < 1.21
        assert section["K_H_beta"][i] == pytest.approx(line.max() / mean, rel=1e-4)
        if sum(r["roll_deg"] == roll and r["bem_load_N"] > 0 for r in rows) == 1:
            assert line[0] < level + gradient * face[0]          # end A: softer
            assert line[-1] > level + gradient * face[-1]        # end B: the edge peak
    summary = tilted.sections["summary"]
    assert summary["K_H_beta_instantaneous"] == max(section["K_H_beta"])
    # ISO's K_Hβ: the cycle's mean line load, largest over mean (the positions' mean load)
    mean_line = np.mean(section["line_load_N_per_mm"], axis=0)
    assert section["mean_line_load_N_per_mm"] == pytest.approx(mean_line, abs=1e-3)
    assert summary["K_H_beta"] == pytest.approx(mean_line.max() / (summary["normal_load_N"] / width),
                                                rel=1e-3)
    assert summary["K_H_beta"] <= summary["K_H_beta_instantaneous"]
    assert math.isfinite(tilted.sections["summary"]["K_H_beta_iso_C"])
