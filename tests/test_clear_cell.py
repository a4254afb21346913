"""The cell along a contact line (issue 32): a contact whose pattern stays clear of every
edge and modification kink its line crosses, and off the tip roundings, is solved on cells
twice as long along it (contact.loaded.CLEAR_CELL), one that comes near them on the short
cells (CELL). Checked against the same analyses with every field on the short cells, the
reference the edge strips' convergence tests were measured on (test_chamfer, test_tip_edge,
test_end_load_ratio)."""

import numpy as np
import pytest

from toothcontact.analyses import analyse
from toothcontact.case import parse_case
from toothcontact.contact import loaded as loaded_module

#: per-row agreement asked of the longer cells (measured on the bundled spur cases:
#: pressures 7e-4, the stresses below the contacts 2.3e-3; summaries 1.2e-4)
RTOL = 3e-3
ROW_KEYS = ("bem_p_max_MPa", "flank_p_max_MPa", "bem_load_N", "bem_approach_mm",
            "loaded_transmission_error_urad", "subsurface_shear_max_MPa",
            "subsurface_von_mises_max_MPa")
SUMMARY_KEYS = ("bem_max_p_max_MPa", "sigma_H_MPa", "K_H_beta", "max_end_load_ratio",
                "loaded_transmission_error_peak_to_peak_um", "mesh_stiffness_N_per_mm_um",
                "subsurface_shear_max_MPa", "subsurface_von_mises_max_MPa")


def spur(**changes) -> dict:
    case = {"kind": "spur", "teeth": [20, 60], "module": "3 mm", "pressure_angle": "20 deg",
            "face_width": "30 mm", "pinion": {"crown": {"radius": "4000 mm"}},
            "load": {"tangential_load": "8000 N"},
            "analysis": {"positions": 5, "interference": False, "positions_check": False,
                         "subsurface": False}}
    case.update(changes)
    return case


def both(raw: dict, monkeypatch):
    """The analysis as it runs, and with every field on the short cells."""
    case = parse_case(raw)
    found = analyse(case)
    with monkeypatch.context() as patch:
        patch.setattr(loaded_module, "CLEAR_CELL", loaded_module.CELL)
        reference = analyse(case)
    return found, reference


def agree(found, reference) -> None:
    for row, ref in zip(found.sections["positions"], reference.sections["positions"]):
        for key in ROW_KEYS:
            if ref.get(key) is not None:
                assert row[key] == pytest.approx(ref[key], rel=RTOL, abs=1e-9), \
                    (row["roll_deg"], key)
    for key in SUMMARY_KEYS:
        if key not in reference.sections["summary"]:
            continue
        assert found.sections["summary"][key] == pytest.approx(
            reference.sections["summary"][key], rel=RTOL, abs=1e-9), key


def longer(found, reference) -> list[bool]:
    """Per loaded contact, whether its cells along its field's longer axis are longer than
    the reference's (about twice)."""
    out = []
    for contact, ref in zip(found.loaded, reference.loaded):
        if contact is not None:
            axis = int(np.argmax(ref.field.gap.shape))
            out.append(contact.field.spacing[axis] > 1.5 * ref.field.spacing[axis])
    return out


def test_a_crowned_spur_contact_clear_of_its_ends_is_solved_on_longer_cells_alike(monkeypatch):
    """An aligned crowned spur pair: its lines stay clear of the face ends, and its tip
    roundings run along them. Most contacts take the longer cells, on half the grid, at
    the short cells' answers to RTOL, the stresses below them included."""
    raw = spur()
    raw["analysis"]["subsurface"] = True
    found, reference = both(raw, monkeypatch)
    assert sum(longer(found, reference)) >= 0.5 * len(longer(found, reference))
    agree(found, reference)


def test_a_contact_near_an_edge_or_kink_keeps_the_short_cells(monkeypatch):
    """A misaligned, relieved pair (contacts reaching toward end B, relief starts, tip
    roundings): every contact on the longer cells has its loaded pressure CLEAR_REACH or
    more from every crossing along its line and is off the roundings (those found
    otherwise after the coarse solve are put back on the short cells), and the answers
    are the short cells' to RTOL."""
    raw = spur(misalignment={"slope": "0.0008"},
               pinion={"crown": {"radius": "4000 mm"},
                       "tip_relief": {"amount": "30 um", "start_diameter": "63.0 mm"}},
               gear={"tip_relief": {"amount": "30 um", "start_diameter": "183.0 mm"}})
    raw["analysis"]["positions"] = 7
    found, reference = both(raw, monkeypatch)
    breaks = loaded_module.edge_breaks(found.cycle)
    on_longer = longer(found, reference)
    assert any(on_longer) and not all(on_longer)
    for contact, long in zip([c for c in found.loaded if c is not None], on_longer):
        near = loaded_module.near_crossing(contact.field, breaks,
                                           contact.solution.pressure_MPa > 0,
                                           loaded_module.CLEAR_REACH)
        rounded = any((contact.solution.pressure_MPa > 0)[on].any() for on in
                      loaded_module.tip_roundings(contact.field, breaks.roundings).values())
        assert not (long and (near or rounded))
    agree(found, reference)


def test_an_end_loaded_uncrowned_pair_keeps_the_short_cells(monkeypatch):
    """Uncrowned and tilted onto end B: every contact reaches the end, so every field keeps
    the short cells and the answer is the reference's exactly."""
    found, reference = both(spur(pinion={}, misalignment={"slope": "0.0005"}), monkeypatch)
    assert not any(longer(found, reference))
    for row, ref in zip(found.sections["positions"], reference.sections["positions"]):
        assert row["bem_grid"] == ref["bem_grid"]
        assert row["bem_p_max_MPa"] == ref["bem_p_max_MPa"]
