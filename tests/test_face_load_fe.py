"""The model's load distribution along the face where one pair carries, against the 3D
finite-element reference of benchmarks/fe_face_load.py (stored in
benchmarks/fe_face_load.json; issue 50 item 6).

The pair: benchmarks/cases/spur_uncrowned_25_75.toml (z = 25/75, m = 3 mm, b = 40 mm, flush
ends, uncrowned, 6000 N tangential), at 0, 0.22 and 0.9 mrad in the plane of action, at the
model's single-pair position, roll -3.93 deg of the case's 11 positions over a pitch (pinion
contact radius 37.43 mm, inside the single-contact zone). The model runs here as the case
file has it, with the interference check and the positions check off (they do not touch
the loaded contact): three analyses, about 15 s. The comparison is on the model's 20
load_distribution strips (1.99 mm, between 0.1 mm from each face end).

The FE reference (tests/fe_pair_face.py): each member's 3D tooth on its whole gear (P2
tetrahedra), strip compliances read at the teeth's centre lines, plus Weber's plane-strain
flattening from the flanks to the centre lines, solved for non-negative line loads with the
misalignment's gap; its medium mesh. Convergence (the benchmark's table): from the coarse to
the medium section K_Hβ moves by -0.2 and -0.3 %, the line loads by at most 2 N/mm, the
stiffness by -0.5 % (13.88 to 13.81 N/(mm·µm); plane strain of the same sections puts the
medium one 0.6 % stiffer than converged); halving the strips (and z-layers) moves K_Hβ by
-0.1 and -0.2 %, the line loads by at most 2 N/mm but for the strip where the contact ends
at 0.9 mrad (0 to 4 N/mm). The plane-strain FE of the whole pair in contact
(tests/fe_mesh_stiffness.py) gives 13.70 at this position. A smoke check below runs the FE
tooling on coarse one-tooth sectors.
"""

from __future__ import annotations

import json
import tomllib
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
STORED = json.loads((ROOT / "benchmarks" / "fe_face_load.json").read_text())
CASE = ROOT / STORED["case"]
FE = STORED["fe"][STORED["reference"]]["results"]


def run(slope: float) -> dict:
    """The model's line loads (N/mm, on its 20 strips), K_H_beta and stiffness at the
    reference's position."""
    from toothcontact.analyses import analyse
    from toothcontact.case import parse_case

    raw = tomllib.loads(CASE.read_text())
    raw["misalignment"]["slope"] = f"{slope}"
    raw["analysis"].update(interference=False, positions_check=False)
    section = analyse(parse_case(raw)).sections["load_distribution"]
    k = int(np.argmin(np.abs(np.asarray(section["roll_deg"]) - STORED["roll_deg"])))
    assert section["roll_deg"][k] == pytest.approx(STORED["roll_deg"], abs=1e-3)
    return dict(line=np.asarray(section["line_load_N_per_mm"][k]), K=section["K_H_beta"][k],
                stiffness=section["mesh_stiffness_N_per_mm_um"][k])


@pytest.fixture(scope="module")
def model():
    return {f"{slope:g}": run(slope) for slope in STORED["slopes"]}


def test_the_single_position_K_H_beta_is_the_fes_within_8_percent(model):
    """K_Hβ at the position (the largest strip over F_n/b): FE 1.533 and 3.023 at 0.22 and
    0.9 mrad, the model 1.518 and 3.054 (-1.0 %, +1.0 %; before its coupling faded at the
    free ends, 1.531 and 3.124: -0.1 %, +3.3 %)."""
    for key in ("0.00022", "0.0009"):
        assert model[key]["K"] == pytest.approx(FE[key]["K_H_beta"], rel=0.08), key


def test_the_line_loads_are_the_fes_within_10_percent_strip_by_strip(model):
    """Strip by strip away from the last 2 mm of each face end (the 18 inner strips) within
    10 % of FE's line load, on every strip at 0.22 mrad (measured -1.4 % to +4.8 %, the
    most at end A's second and third strips) and at 0.9 mrad on the strips where FE's
    contact carries (measured -2.6 % to +8.6 %). Not met at the two strips where FE's
    contact ends (see the next test); strips FE leaves unloaded carry nothing."""
    for key in ("0.00022", "0.0009"):
        fe, mine = np.asarray(FE[key]["line_load"])[1:-1], model[key]["line"][1:-1]
        tail = _tail(fe)
        assert np.all(np.abs(mine - fe)[~tail & (fe > 0)] <= 0.10 * fe[~tail & (fe > 0)]), key
        assert np.all(mine[fe == 0] == 0.0), key


def _tail(fe: np.ndarray) -> np.ndarray:
    """The strips where FE's contact ends, mid-face: the first two loaded beyond an
    unloaded strip."""
    first = np.flatnonzero(fe > 0)[0]
    tail = np.zeros(len(fe), bool)
    if first > 0:
        tail[first:first + 2] = True
    return tail


def test_where_the_contact_ends_at_0_9_mrad_the_model_runs_on_further_than_fe(model):
    """The shortfall, stated: at 0.9 mrad FE's contact ends near z = -6 mm; the model's runs
    on about 0.7 mm further, so its two strips there read 16.4 and 53.3 N/mm against FE's
    4.5 and 43.7 (×3.7 and +22 %: 12 and 10 N/mm, 7.5 and 6 % of the mean line load
    F_n/b = 160 N/mm; before the end layer the same, +21 %). A
    Pasternak line cannot follow FE here: with FE's own slice compliance and the coupling
    length fitted to FE's strip compliance (both members), the line reads 25 and 60 N/mm;
    the 75-tooth gear's FE falls off faster than any one coupling length within 2-8 mm of
    a load (0.41 of the peak at 6 mm against the line's 0.44). Bands: the model minus FE
    on those strips within 4-20 N/mm, and the whole miss under 10 % of the mean."""
    fe = np.asarray(FE["0.0009"]["line_load"])[1:-1]
    mine = model["0.0009"]["line"][1:-1]
    tail = _tail(fe)
    assert tail.sum() == 2
    excess = mine[tail] - fe[tail]
    assert np.all((excess > 4.0) & (excess < 20.0))
    assert np.all(excess < 0.10 * STORED["normal_load_N"] / STORED["face_mm"])


def test_the_loaded_end_strip_is_the_fes_within_3_percent(model):
    """The end rise (issue 50 item 6): the strip at end B, left out above, was 3.3 % over
    FE's at 0.9 mrad with the Pasternak line's free ends (w' = 0: a line held to a tilt
    needs the end forces λ²w'/c; uncoupled slices give no rise at all, the half-space's
    free-end mirror takes 2 %); with the coupling fading over Reissner's free-edge layer
    (structure.end_layer) +1.0 %, and -1.2 % at 0.22 mrad. Against its own mid-face trend
    (a line fitted over z = 0-12 mm) FE's end strip rises +7.7 % and +14.2 %, the model's
    +7.9 % and +20.0 % (+9.1 % and +23.3 % before): the rest of the model's rise at 0.9
    mrad is its shallower mid-face slope (14.5 against 15.5 N/mm per mm), the previous
    test's Pasternak shape. End A's strip is at 0.22 mrad 4.1 % under FE's (6.6 %
    before)."""
    for key in ("0.00022", "0.0009"):
        fe, mine = FE[key]["line_load"], model[key]["line"]
        assert mine[-1] == pytest.approx(fe[-1], rel=0.03), key
    assert model["0.00022"]["line"][0] == pytest.approx(FE["0.00022"]["line_load"][0], rel=0.05)


def test_the_single_pair_stiffness_is_the_fes_within_5_percent(model):
    """Aligned: the model's single-pair stiffness 14.21 N/(mm·µm) against the 3D FE's 13.81
    (+2.9 %; against the converged section's, 0.6 % softer, +3.5 %) and the plane-strain FE
    of the pair in contact, 13.70; ISO 6336-1's c' is 14.06. The issue's FE read 17.75 on
    3-tooth sectors: the tooling's sectors, their cut faces held, give 16.16 here, 17 %
    stiffer than the whole gears. The load is even along the face in both (K_Hβ 1.004 and
    1.018: FE's strips at the very ends carry 2 % more)."""
    fe = FE["0"]
    assert model["0"]["stiffness"] == pytest.approx(fe["stiffness"], rel=0.05)
    assert STORED["plane_strain_pair_stiffness"]["refine 2"] == pytest.approx(
        fe["stiffness"], rel=0.02)
    assert model["0"]["K"] < 1.01 and fe["K_H_beta"] < 1.03


def test_the_fe_reference_runs_and_balances_on_a_coarse_sector():
    """Smoke check of tests/fe_pair_face.py (about 6 s): one-tooth sectors of both members
    (0.4/1.5 mm elements, 5 strips on the half face): the whole face's strip compliance
    mirrors about mid-face, the line loads carry the load, spread evenly when aligned (within
    3 %) and rise to end B at 0.9 mrad, leaving end A; the sectors' stiffness lies between
    the whole gears' (13.8) and 1.5 times it."""
    pytest.importorskip("skfem")
    import fe_pair_face as fl
    from toothcontact.case import parse_case
    from toothcontact.gearset import gear_pair

    pair = gear_pair(parse_case(tomllib.loads(CASE.read_text())))
    (r1, r2), rho = STORED["radii_mm"], STORED["curvature_mm"]
    edges = np.array([0.0, 5.97, 11.94, 17.91, 19.9, 20.0])
    members = [fl.member_compliance(gear, r, edges, 1, 0.4, 1.5, 30.0, 0.8, teeth=1,
                                    log=lambda *_: None)
               for gear, r in ((pair.pinion, r1), (pair.gear, r2))]
    A = members[0].matrix
    assert np.allclose(A, A[::-1, ::-1], rtol=1e-9)
    solver = fl.PairFaceLoad(*members, rho)
    load = STORED["normal_load_N"]
    aligned, tilted = solver.solve(load, 0.0), solver.solve(load, 0.0009)
    widths = np.diff(aligned.edges)
    for s in (aligned, tilted):
        assert widths @ s.line_load == pytest.approx(load, rel=1e-9)
    assert np.allclose(aligned.line_load, load / 40.0, rtol=0.03)
    assert np.all(np.diff(tilted.line_load[tilted.line_load > 0]) > 0)
    assert tilted.line_load[0] == 0.0 and tilted.approach > aligned.approach
    stiffness = load / 40.0 / (1e3 * aligned.approach)
    assert FE["0"]["stiffness"] < stiffness < 1.5 * FE["0"]["stiffness"]
