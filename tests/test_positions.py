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
    both = np.concatenate([phis, mesh_positions(pitch, count, 0.5)])
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


def test_the_positions_check_is_the_analysis_at_twice_the_positions():
    """The check's answer at twice the positions is what an analysis at twice the positions
    finds (the same places of the cycle, solved on their own): its largest loaded pressure
    and loaded transmission error peak to peak to the solver's tolerance (0.5 %). The case's
    own figures stay as they were without the check."""
    checked = analyse(parse_case(spur(4, True))).sections["summary"]
    plain = analyse(parse_case(spur(4, False))).sections["summary"]
    doubled = analyse(parse_case(spur(8, False))).sections["summary"]
    check = checked["positions_check"]
    assert "positions_check" not in plain and check["checked"]
    assert checked["bem_max_p_max_MPa"] == plain["bem_max_p_max_MPa"]
    assert check["positions"] == 4 and check["doubled_positions"] == 8
    assert check["doubled_bem_max_p_max_MPa"] == pytest.approx(doubled["bem_max_p_max_MPa"],
                                                                rel=0.005)
    assert check["doubled_loaded_transmission_error_peak_to_peak_um"] == pytest.approx(
        doubled["loaded_transmission_error_peak_to_peak_um"], rel=0.005)
    assert check["bem_max_p_max_change_percent"] == pytest.approx(
        100 * (check["doubled_bem_max_p_max_MPa"] / checked["bem_max_p_max_MPa"] - 1))
    assert check["converged"] == (check["bem_max_p_max_change_percent"] <= 5.0)


def test_a_peak_between_the_positions_is_named():
    """One position (mid-mesh) misses the tip corner's contact at the cycle's end (measured
    1752 against 3102 MPa there): the check says so and the notes ask for more positions."""
    result = analyse(parse_case(spur(1, True)))
    check = result.sections["summary"]["positions_check"]
    assert not check["converged"] and check["bem_max_p_max_change_percent"] > 50.0
    assert any(note.startswith("positions: the largest loaded pressure rises")
               and "[analysis] positions = 4" in note for note in result.notes)


def test_a_transmission_error_between_the_positions_is_named():
    """Two positions (roll -9° and 0°) see a loaded TE peak to peak of 0.38 µm; with twice
    the positions it is 9.90 µm (measured): the check says the TE has not converged and a
    note asks for more positions for it. At six positions it has (9.97 against 9.98 µm)."""
    coarse = analyse(parse_case(spur(2, True)))
    check = coarse.sections["summary"]["positions_check"]
    assert check["doubled_loaded_transmission_error_peak_to_peak_um"] > \
        10 * check["loaded_transmission_error_peak_to_peak_um"]
    assert check["transmission_error_converged"] is False
    assert any("for the transmission error" in note for note in coarse.notes)
    fine = analyse(parse_case(spur(6, True))).sections["summary"]["positions_check"]
    assert fine["transmission_error_converged"] is True
