"""The transmission error's mesh harmonics (analyses.contact.mesh_harmonics): the amplitudes
of a Fourier series sampled at positions spread evenly over one mesh cycle, and on an
analysed pair their sum of squares is the TE's variance (Parseval) where all orders are
resolved."""

import numpy as np
import pytest

from toothcontact.analyses.contact import mesh_harmonics


def test_a_sampled_series_gives_its_amplitudes_back():
    """1.5 sin θ + 0.4 cos 2θ + 0.1 sin(3θ + 1) + 7 at 12 positions of one cycle: orders 1-5
    are 1.5, 0.4, 0.1, 0, 0 (the mean left out); at 5 positions only orders 1 and 2 are
    resolved; the start of the cycle (a phase) changes nothing."""
    for start in (0.0, 0.37):
        theta = start + 2 * np.pi * np.arange(12) / 12
        te = 1.5 * np.sin(theta) + 0.4 * np.cos(2 * theta) + 0.1 * np.sin(3 * theta + 1) + 7
        assert mesh_harmonics(te.tolist()) == pytest.approx([1.5, 0.4, 0.1, 0.0, 0.0], abs=1e-12)
    theta = 2 * np.pi * np.arange(5) / 5
    assert mesh_harmonics((np.sin(theta) + 0.2 * np.cos(2 * theta)).tolist()) \
        == pytest.approx([1.0, 0.2], abs=1e-12)


def test_an_analysed_pairs_harmonics_hold_its_variance():
    """The crowned 20/60 pair at 11 positions: the loaded TE's harmonics 1-5 are all its
    orders, so Σ A_k²/2 is its variance over the positions (Parseval), to 1e-9."""
    from test_subsurface import spur_case

    from toothcontact.analyses import analyse
    from toothcontact.case import parse_case

    raw = spur_case(positions=11, subsurface=False)
    result = analyse(parse_case(raw))
    summary, rows = result.sections["summary"], result.sections["positions"]
    te = {r["roll_deg"]: r["loaded_transmission_error_um"] for r in rows}
    values = np.array([te[k] for k in sorted(te)])
    amplitudes = np.array(summary["te_harmonics_um"])
    assert len(amplitudes) == 5
    assert (amplitudes ** 2).sum() / 2 == pytest.approx(values.var(), rel=1e-9)
    assert max(amplitudes) <= summary["loaded_transmission_error_peak_to_peak_um"]
