"""The mesh positions of a contact analysis: each place of the cycle once, and the check
that the largest loaded pressure does not hide between them (summary positions_check)."""

import math

import numpy as np
import pytest

from toothcontact.analyses import analyse
from toothcontact.case import parse_case
from toothcontact.contact.cycle import mesh_positions


@pytest.mark.parametrize("count", [1, 2, 7, 8, 21])
def test_positions_hold_each_place_of_the_cycle_once(count):
    """A cycle's positions spread over one pitch, 0 among them; its two ends are one
    position (the mesh repeats after a pitch), so none lies a whole pitch from another.
    Shifted by half a step they fall midway, and with the unshifted ones they are the
    positions of twice the count."""
    pitch = 2 * math.pi / 20
    phis = mesh_positions(pitch, count)
    assert len(phis) == count and 0.0 in phis
    assert np.all(np.diff(phis) == pytest.approx(pitch / count))
    assert np.ptp(phis) < pitch - 1e-12
    both = np.concatenate([phis, mesh_positions(pitch, count,
                                                tuple(np.arange(count) - count // 2 + 0.5))])
    doubled = mesh_positions(pitch, 2 * count)
    wrapped = np.round((both - doubled[0]) % pitch, 12)       # the same places of the cycle
    assert sorted(wrapped) == pytest.approx(sorted(np.round(doubled - doubled[0], 12)))


def spur(positions: int, check: bool) -> dict:
    """The aligned, lightly crowned spur pair 20/60 that test_loaded_contact uses."""
    return {"kind": "spur", "teeth": [20, 60], "module": "3 mm", "pressure_angle": "20 deg",
            "face_width": "30 mm", "pinion": {"crown": {"radius": "4000 mm"}},
            "load": {"tangential_load": "8000 N"},
            "analysis": {"positions": positions, "interference": False, "pressure_grid": 64,
                         "positions_check": check}}


def test_the_positions_check_refines_where_the_figures_can_hide():
    """The check's positions are places of the analysis at twice (and four times) the
    positions, solved on their own: what it finds there is what that analysis finds (its
    largest loaded pressure and loaded transmission error peak to peak to the solver's
    tolerance, 0.5 %), from fewer positions where the pressure's peak and the TE's
    extremes allow. The case's own figures stay as they were without the check."""
    checked = analyse(parse_case(spur(10, True))).sections["summary"]
    plain = analyse(parse_case(spur(10, False))).sections["summary"]
    check = checked["positions_check"]
    assert "positions_check" not in plain and check["checked"]
    assert check["method"] == "adaptive bisection"
    assert checked["bem_max_p_max_MPa"] == plain["bem_max_p_max_MPa"]
    levels = check["refinement_levels"]
    assert levels >= 1 and check["finest_step_fraction"] == 0.5 ** levels
    # measured: 10 positions, 10 added in two levels (the finer analysis has 30 more); the
    # pressure 4307 -> 5191 MPa (a tip's corner contact between), the TE 9.97 -> 10.05 µm
    assert 0 < check["refined_positions"] < 10 * (2 ** levels - 1)
    fine = analyse(parse_case(spur(10 * 2 ** levels, False))).sections["summary"]
    assert check["refined_bem_max_p_max_MPa"] == pytest.approx(fine["bem_max_p_max_MPa"],
                                                               rel=0.005)
    assert check["refined_loaded_transmission_error_peak_to_peak_um"] == pytest.approx(
        fine["loaded_transmission_error_peak_to_peak_um"], rel=0.005)
    assert check["bem_max_p_max_change_percent"] == pytest.approx(
        100 * (check["refined_bem_max_p_max_MPa"] / checked["bem_max_p_max_MPa"] - 1))
    assert check["converged"] == (check["bem_max_p_max_change_percent"] <= 5.0)


def test_bisection_picks_the_steps_about_the_peak_the_jumps_and_the_extremes():
    """_to_refine on made-up figures of 8 positions (steps -4..3, periodic): the steps with
    an end within 5 % of the largest pressure, a jump of more than 10 % of it, or an end at
    the transmission error's highest or lowest; the others are left, and so are the steps
    with an end not solved and those not of the width asked."""
    from toothcontact.analyses.contact import _to_refine

    pressure = [1000, 1010, 1005, 1003, 1500, 1480, 1002, 1001]
    te = [1.0, 1.1, 1.2, 1.15, 1.1, 1.05, 1.0, 0.9]
    known = {float(k - 4): (p, t) for k, (p, t) in enumerate(zip(pressure, te))}
    # peak 1500 at step 0 and 1480 at 1: steps (-1, 0), (0, 1), (1, 2) (the jumps too);
    # TE highest 1.2 at -2, lowest 0.9 at 3: steps (-3, -2), (-2, -1), (2, 3), (3, 4 = -4)
    assert _to_refine(known, 8, 1.0) == [-2.5, -1.5, -0.5, 0.5, 1.5, 2.5, 3.5]
    # a peak at 0, the TE highest at 1 and lowest at -3; -4 not solved: its steps are left
    other = {k: (1000.0 + 300.0 * (k == 0), 1.0 + 0.001 * k + 0.2 * (k == 1)) for k in known}
    other[-4.0] = (None, None)
    assert _to_refine(other, 8, 1.0) == [-2.5, -0.5, 0.5, 1.5]
    assert _to_refine(other, 8, 0.5) == []
    # a loaded TE flat to within TE_POSITIONS_FLOOR (0.1 µm) asks for no step of its own
    level = {k: (1000.0 + 300.0 * (k == 0), 1.0 + 0.01 * (k == 1)) for k in known}
    assert _to_refine(level, 8, 1.0) == [-0.5, 0.5]


def test_a_peak_between_the_positions_is_named():
    """One position (mid-mesh) misses the tip corner's contact at the cycle's end (measured
    1752 against 3102 MPa there): the check says so and the notes ask for more positions,
    as many as the finest step it took."""
    result = analyse(parse_case(spur(1, True)))
    check = result.sections["summary"]["positions_check"]
    assert not check["converged"] and check["bem_max_p_max_change_percent"] > 50.0
    asked = round(1 / check["finest_step_fraction"])
    assert any(note.startswith("positions: the largest loaded pressure rises")
               and f"[analysis] positions = {max(2, asked)} " in note for note in result.notes)


def test_a_transmission_error_between_the_positions_is_named():
    """Two positions (roll -9° and 0°) see a loaded TE peak to peak of 0.38 µm; with twice
    the positions it is 9.90 µm (measured): the check says the TE has not converged and a
    note asks for more positions for it. At six positions it has (9.97 against 9.98 µm)."""
    coarse = analyse(parse_case(spur(2, True)))
    check = coarse.sections["summary"]["positions_check"]
    assert check["refined_loaded_transmission_error_peak_to_peak_um"] > \
        10 * check["loaded_transmission_error_peak_to_peak_um"]
    assert check["transmission_error_converged"] is False
    assert any("for the transmission error" in note for note in coarse.notes)
    fine = analyse(parse_case(spur(6, True))).sections["summary"]["positions_check"]
    assert fine["transmission_error_converged"] is True
