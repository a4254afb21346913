"""Elastic half-space contact solver (contact.pressure) against exact Hertz, closed-form
displacements, a direct influence sum, for masked (truncated) contacts, and on the gap
fields of the contact cycle (cut oblique ellipses, line contacts, two patches, fields dumped
from real cases in tests/data/fields)."""

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from toothcontact.analytic import hertz
from toothcontact.contact import influence
from toothcontact.contact import pressure as P

E_STAR = 1.0 / hertz.compliance(210000.0, 0.3, 210000.0, 0.3)   # steel on steel, 115385 MPa


def hertz_grid(A, B, load, n=256, margin=1.4):
    """Gap A x² + B y² on an n × n grid spanning ±margin × the Hertz semi-axes (x along
    axis 0), and the exact Hertz contact."""
    exact = hertz.hertz_point(A, B, load, 1.0 / E_STAR)
    dx, dy = 2 * margin * exact.a / n, 2 * margin * exact.b / n
    x = (np.arange(n) - (n - 1) / 2) * dx
    y = (np.arange(n) - (n - 1) / 2) * dy
    X, Y = np.meshgrid(x, y, indexing="ij")
    return A * X**2 + B * Y**2, dx, dy, x, y, exact


def contact_half_width(p_line, coords):
    """Half the contact extent along one grid line through the centre: each end is found by
    extrapolating p² linearly to zero from the last two contact cells (at a smooth contact
    edge p ~ sqrt(distance), so p² is linear in distance there), then halved."""
    idx = np.flatnonzero(p_line > 0)
    lo, hi = idx[0], idx[-1]
    step = coords[1] - coords[0]
    q = p_line**2
    end_hi = coords[hi] + step * q[hi] / (q[hi - 1] - q[hi])
    end_lo = coords[lo] - step * q[lo] / (q[lo + 1] - q[lo])
    return 0.5 * (end_hi - end_lo)


@pytest.fixture(scope="module", params=[1.0, 4.0, 40.0, 400.0, 1e4], ids=lambda r: f"B/A={r:g}")
def hertz_case(request):
    A, load = 0.02, 2500.0
    h, dx, dy, x, y, exact = hertz_grid(A, request.param * A, load)
    return P.solve_contact(h, dx, dy, load, E_STAR), h, x, y, exact


def test_whole_ellipse_matches_exact_hertz(hertz_case):
    """Issue acceptance: peak within 1 %, semi-axes within 2 %, approach within 1 % (the
    solver gives about 2e-5, 9e-4 and 4e-6 at 256²)."""
    sol, _, x, y, exact = hertz_case
    p = sol.pressure_MPa
    i, j = np.unravel_index(np.argmax(p), p.shape)
    a = contact_half_width(p[:, j], x)
    b = contact_half_width(p[i, :], y)
    assert sol.peak_pressure_MPa == pytest.approx(exact.p0, rel=0.01)
    assert a == pytest.approx(exact.a, rel=0.02)
    assert b == pytest.approx(exact.b, rel=0.02)
    assert sol.approach_mm == pytest.approx(exact.approach, rel=0.01)
    # what the solver really achieves on this grid, well inside the acceptance criteria
    assert abs(sol.peak_pressure_MPa / exact.p0 - 1) < 1e-3
    assert abs(a / exact.a - 1) < 2e-3 and abs(b / exact.b - 1) < 2e-3
    assert abs(sol.approach_mm / exact.approach - 1) < 1e-4
    assert sol.area_mm2 == pytest.approx(math.pi * exact.a * exact.b, rel=0.01)
    assert sol.mean_pressure_MPa == pytest.approx(sol.load_N / sol.area_mm2, rel=1e-12)


def assert_solved(sol, h):
    """Checks of a solution against its own gap h (mm), whatever path reached it:
    sum(p)·dx·dy = W to 1e-6; p >= 0, and 0 off the material; u the displacement of p,
    afresh; the loaded gap h - delta + u (= separation_mm on the material) within 1e-6 of
    the largest displacement of zero where p > 0 (rms within 1e-8, the solver's tol) and not
    below -1e-8 of it where p = 0 (complementarity); the reported error below tol."""
    p, u, m = sol.pressure_MPa, sol.displacement_mm, sol.mask
    assert p.sum() * sol.dx_mm * sol.dy_mm == pytest.approx(sol.load_N, rel=1e-6)
    assert p.min() >= 0.0 and np.all(p[~m] == 0)
    scale = u[m].max()
    op = influence.influence_operator(p.shape, sol.dx_mm, sol.dy_mm)
    np.testing.assert_allclose(u, op(p) / sol.E_star_MPa, rtol=0, atol=1e-12 * scale)
    gap = np.where(m, np.asarray(h, dtype=float) + u - sol.approach_mm, 0.0)
    np.testing.assert_allclose(gap, sol.separation_mm, rtol=0, atol=1e-14 * scale)
    contact = p > 0
    assert np.abs(gap[contact]).max() < 1e-6 * scale
    assert math.sqrt(np.mean(gap[contact] ** 2)) < 1e-8 * scale
    assert gap[m & ~contact].min(initial=0.0) > -1e-8 * scale
    assert sol.relative_error < 1e-8


def test_load_balance_sign_and_complementarity(hertz_case):
    sol, h, _, _, _ = hertz_case
    assert_solved(sol, h)


def test_single_precision_and_cold_start_give_the_same_pressure():
    """float32 transforms and a uniform start reach the same solution: two solutions each
    within the 1e-8 gap tolerance differ by a few 1e-6 of p0."""
    h, dx, dy, _, _, exact = hertz_grid(0.02, 0.08, 2500.0, n=128)
    double = P.solve_contact(h, dx, dy, 2500.0, E_STAR)
    single = P.solve_contact(h, dx, dy, 2500.0, E_STAR, dtype=np.float32)
    cold = P.solve_contact(h, dx, dy, 2500.0, E_STAR, warm_start=False)
    for other in (single, cold):
        assert np.abs(other.pressure_MPa - double.pressure_MPa).max() < 1e-5 * exact.p0
        assert other.relative_error < 1e-8


# --- influence operator -------------------------------------------------------------------


def test_dc_fft_equals_direct_sum_of_love_coefficients():
    """DC-FFT on a 16 × 12 grid of 0.3 × 0.7 mm cells equals the direct double sum of the
    rectangle formula (Johnson eq 3.25) over every pair of cells."""
    n0, n1, dx, dy = 16, 12, 0.3, 0.7
    rng = np.random.default_rng(7)
    p = rng.uniform(0.0, 100.0, (n0, n1))
    xi = np.arange(n0) * dx
    yj = np.arange(n1) * dy
    # coefficient of source cell (k, l) at field cell (i, j), all at once: (i, j, k, l)
    coeff = influence.rectangle_displacement(xi[:, None, None, None] - xi[None, None, :, None],
                                     yj[None, :, None, None] - yj[None, None, None, :],
                                     0.5 * dx, 0.5 * dy, E_STAR)
    direct = np.einsum("ijkl,kl->ij", coeff, p)
    fft = influence.influence_operator((n0, n1), dx, dy)(p) / E_STAR
    np.testing.assert_allclose(fft, direct, rtol=0, atol=1e-10 * np.abs(direct).max())
    single = influence.influence_operator((n0, n1), dx, dy)(p, single=True) / E_STAR
    np.testing.assert_allclose(single, direct, rtol=0, atol=1e-6 * np.abs(direct).max())


def test_uniform_square_centre_displacement_closed_form():
    """1 MPa on a square of side 2c (101 × 101 cells of a 128² grid): the centre sinks by
    u = (8/π)·ln(1 + √2)·p·c / E* (Johnson eq 3.25 at the centre), and an off-centre point by
    the rectangle formula for the whole square."""
    n, cells, step = 128, 101, 0.02
    p = np.zeros((n, n))
    p[:cells, :cells] = 1.0
    u = influence.influence_operator((n, n), step, step)(p) / E_STAR
    c = 0.5 * cells * step
    centre = cells // 2
    assert u[centre, centre] == pytest.approx(8 / math.pi * math.log(1 + math.sqrt(2)) * c / E_STAR,
                                              rel=1e-12)
    for i, j in ((0, 0), (10, 90), (120, 127), (127, 3)):
        x, y = (i - centre) * step, (j - centre) * step
        assert u[i, j] == pytest.approx(float(influence.rectangle_displacement(x, y, c, c, E_STAR)),
                                        rel=1e-10)


def test_operator_is_cached_per_grid():
    first = influence.influence_operator((32, 20), 0.1, 0.2)
    assert influence.influence_operator((32, 20), 0.1, 0.2) is first
    assert influence.influence_operator((32, 20), 0.1, 0.25) is not first


# --- masked contacts and edge loading -----------------------------------------------------


def rigid_flat_punch(n, radius=1.0, load=1000.0):
    step = 2.2 * radius / n
    x = -1.1 * radius + (np.arange(n) + 0.5) * step
    X, Y = np.meshgrid(x, x, indexing="ij")
    mask = X**2 + Y**2 <= radius**2
    return P.solve_contact(np.zeros((n, n)), step, step, load, E_STAR, mask=mask), mask


def test_flat_punch_approach_boussinesq():
    """A flat circular punch (gap 0 on a disc mask) sinks by Boussinesq's
    delta = W / (2 a E*) (Johnson 1985, ch. 3); the staircase disc converges like 1/n."""
    sol, mask = rigid_flat_punch(128)
    assert sol.approach_mm == pytest.approx(1000.0 / (2 * 1.0 * E_STAR), rel=5e-3)
    assert np.all(sol.pressure_MPa[~mask] == 0)
    assert sol.area_mm2 == pytest.approx(mask.sum() * sol.dx_mm**2)


TRUNCATED = dict(A=0.01, B=0.1, load=2000.0)


def truncated_ellipse(n):
    """The truncated_gap problem solved: (solution, mask, exact Hertz)."""
    h, dx, dy, mask, exact = truncated_gap(n)
    return P.solve_contact(h, dx, dy, TRUNCATED["load"], E_STAR, mask=mask), mask, exact


def truncated_gap(n):
    """Gap A (x - 0.6a)² + B y² cut by a face end at x = 1.125 a (mask False beyond it), a
    the Hertz semi-axis, on n × n cells: (gap, dx, dy, mask, exact Hertz); the face end
    falls on a cell boundary for every n divisible by 64."""
    A, B, load = TRUNCATED["A"], TRUNCATED["B"], TRUNCATED["load"]
    exact = hertz.hertz_point(A, B, load, 1.0 / E_STAR)
    half_x, half_y = 1.5 * exact.a, 2.0 * exact.b
    dx, dy = 2 * half_x / n, 2 * half_y / n
    x = -half_x + (np.arange(n) + 0.5) * dx
    y = -half_y + (np.arange(n) + 0.5) * dy
    X, Y = np.meshgrid(x, y, indexing="ij")
    mask = np.zeros((n, n), dtype=bool)
    mask[: n * 56 // 64, :] = True
    h = A * (X - 0.6 * exact.a) ** 2 + B * Y**2
    return h, dx, dy, mask, exact


@pytest.fixture(scope="module")
def truncated():
    return {n: truncated_ellipse(n) for n in (64, 128, 256)}


def test_truncated_ellipse_carries_the_load_on_the_material(truncated):
    sol, mask, exact = truncated[256]
    p = sol.pressure_MPa
    assert np.all(p[~mask] == 0)
    assert p.sum() * sol.dx_mm * sol.dy_mm == pytest.approx(2000.0, rel=1e-6)
    assert p.min() >= 0
    # cut short, the ellipse presses harder than the whole one, hardest at the face end
    assert sol.peak_pressure_MPa > exact.p0
    i, _ = np.unravel_index(np.argmax(p), p.shape)
    assert i == mask[:, 0].sum() - 1


def test_edge_pressure_converges_while_raw_peak_grows(truncated):
    """Strip-averaged (0.1 mm) pressure at the face end changes by < 3 % from 64 to 128 and
    < 2 % from 128 to 256 cells across; the raw peak of the edge cells grows each time by
    about √2 (the r^(-1/2) singularity of a sharp end)."""
    edges = {n: truncated[n][0].edge_loads(axis=0, width_mm=0.1) for n in truncated}
    high = {n: edges[n][1] for n in edges}
    for n in edges:
        low = edges[n][0]
        assert low.edge_pressure_MPa == 0 and low.load_N == 0   # x = -1.5a is not loaded
        assert high[n].side == "high" and high[n].width_mm == 0.1
        assert 0.05 < high[n].load_fraction < 0.2
        assert high[n].load_N == pytest.approx(high[n].load_fraction * 2000.0)
        assert high[n].edge_pressure_MPa < high[n].raw_peak_MPa
        assert high[n].line_index in (n // 2 - 1, n // 2)       # on the centre line y = 0
    q = [high[n].edge_pressure_MPa for n in (64, 128, 256)]
    raw = [high[n].raw_peak_MPa for n in (64, 128, 256)]
    assert abs(q[1] / q[0] - 1) < 0.03
    assert abs(q[2] / q[1] - 1) < 0.02
    assert abs(q[2] / q[1] - 1) < abs(q[1] / q[0] - 1)
    for coarse, fine in zip(raw, raw[1:]):
        assert 1.25 < fine / coarse < 1.5


def rotated_truncation(theta, n=256):
    """The truncated ellipse turned by theta on the grid (gap and face end together)."""
    A, B, load = TRUNCATED["A"], TRUNCATED["B"], TRUNCATED["load"]
    exact = hertz.hertz_point(A, B, load, 1.0 / E_STAR)
    half = 1.6 * exact.a
    step = 2 * half / n
    x = -half + (np.arange(n) + 0.5) * step
    X, Y = np.meshgrid(x, x, indexing="ij")
    c, s = math.cos(theta), math.sin(theta)
    along, across = c * X + s * Y, -s * X + c * Y
    mask = along < 1.125 * exact.a
    h = A * (along - 0.6 * exact.a) ** 2 + B * across**2
    return P.solve_contact(h, step, step, load, E_STAR, mask=mask)


def test_edge_pressure_does_not_depend_on_how_the_edge_lies_on_the_grid():
    """The truncated ellipse turned with its face end by 15, 30 and 45 deg on the grid (a
    helical flank's tip or a tilted face end): the 0.1 mm edge pressure stays within 3 % of
    the unturned one. Each grid line's own strip read 72 % high at 15 deg (the staircase
    edge's cell-to-cell spikes decided it, and a strip along the line is shallower across
    an oblique edge); the strip stretched to 0.1 mm across the edge and averaged over
    0.1 mm along it does not see how the edge lies."""
    def edge_pressure(theta):
        sol = rotated_truncation(math.radians(theta))
        return max(e.edge_pressure_MPa for axis in (0, 1) for e in sol.edge_loads(axis, 0.1))

    straight = edge_pressure(0.0)
    for theta in (15.0, 30.0, 45.0):
        assert edge_pressure(theta) == pytest.approx(straight, rel=0.03)


def test_edge_strip_counts_partial_cells():
    """A uniform pressure of 1 MPa on the material: every strip average is 1 MPa, and a strip
    of 2.5 cells carries 2.5 cells' load per line, partial cell included."""
    n, step = 8, 0.1
    mask = np.zeros((n, n), dtype=bool)
    mask[2:6, 1:7] = True
    p = mask.astype(float)
    sol = P.ContactSolution(
        pressure_MPa=p, displacement_mm=p, separation_mm=p, mask=mask, dx_mm=step, dy_mm=step,
        load_N=p.sum() * step**2, E_star_MPa=E_STAR, area_mm2=mask.sum() * step**2,
        peak_pressure_MPa=1.0, mean_pressure_MPa=1.0, approach_mm=0.0, iterations=0,
        relative_error=0.0)
    for axis, lines in ((0, 6), (1, 4)):
        for edge in sol.edge_loads(axis=axis, width_mm=0.25):
            assert edge.edge_pressure_MPa == pytest.approx(1.0)
            assert edge.raw_peak_MPa == 1.0
            assert edge.load_N == pytest.approx(lines * 0.25 * step)


# --- gap fields of the contact cycle ------------------------------------------------------
# Cut, oblique and elongated ellipses on anisotropic cells, line contacts, several patches:
# the solver stalled on such fields ("relative gap error 0.971 after 500 iterations") when
# its start put the whole load on one material cell (the Hertz ellipse fitted to a gap
# whose bowl lies beyond the material).


def oblique_cut_gap(n=128):
    """A helical flank's contact, made exact (helical_032 in tests/data/fields): the long
    ellipse A·ξ² + B·η² (B/A = 100, long axis 20 deg off x) on n × n cells of 7:1, cut by an
    oblique tip edge (mask: material below y = 0.02·x) that the whole gap's Hertz ellipse
    crosses by half a cell row, its centre beyond the tip. (gap, dx, dy, mask, load, centre
    of the bowl, exact Hertz of the whole gap)."""
    A, B, load, theta = 5e-4, 0.05, 2000.0, math.radians(20.0)
    exact = hertz.hertz_point(A, B, load, 1.0 / E_STAR)
    c, s = math.cos(theta), math.sin(theta)
    half_x = 2.0 * math.hypot(exact.a * c, exact.b * s)
    dx = 2 * half_x / n
    dy = dx / 7
    x = -half_x + (np.arange(n) + 0.5) * dx
    y = (np.arange(n) - n / 2 + 0.5) * dy
    X, Y = np.meshgrid(x, y, indexing="ij")
    normal = np.array([-0.02, 1.0]) / math.hypot(0.02, 1.0)           # out of the material
    rim = math.hypot(exact.a * (normal @ (c, s)), exact.b * (normal @ (-s, c)))
    yc = (rim - 0.5 * dy) / normal[1]               # the ellipse pokes dy/2 into the material
    xi, eta = c * X + s * (Y - yc), -s * X + c * (Y - yc)
    return A * xi**2 + B * eta**2, dx, dy, Y < 0.02 * X, load, (xi, eta), exact


def test_oblique_ellipse_cut_beyond_its_centre():
    """The old failure itself: the whole gap's Hertz ellipse holds one material cell, so the
    fitted start put the load there and the iteration stalled. The fit is now refused
    (hertz_start: None, less than half its load on the material), and the solution, reached
    within 40 iterations, passes assert_solved and equals the one from the uniform start."""
    h, dx, dy, mask, load, (xi, eta), exact = oblique_cut_gap()
    assert np.sum(mask & ((xi / exact.a) ** 2 + (eta / exact.b) ** 2 < 1)) == 1
    sol = P.solve_contact(h, dx, dy, load, E_STAR, mask=mask)
    assert sol.iterations <= 40
    assert_solved(sol, h)
    assert sol.peak_pressure_MPa > 5 * exact.p0          # edge-loaded along the tip
    cold = P.solve_contact(h, dx, dy, load, E_STAR, mask=mask, warm_start=False)
    assert np.abs(cold.pressure_MPa - sol.pressure_MPa).max() < 1e-5 * sol.peak_pressure_MPa
    assert P.hertz_start(h, dx, dy, mask, load, E_STAR) is None


def test_iteration_limit_raises_with_the_error_reached():
    h, dx, dy, mask, load, *_ = oblique_cut_gap()
    with pytest.raises(RuntimeError, match=r"relative gap error .* after 3 iterations"):
        P.solve_contact(h, dx, dy, load, E_STAR, mask=mask, max_iter=3)


def line_contact_gap(n=128):
    """An uncrowned spur flank under slope: gap B·y² + s·x, linear along the face (x) with no
    bowl, cut by the face end x = 0 (mask), a tenth of the field beyond it, cells 46:1.
    (gap, dx, dy, mask, load)."""
    B, slope, face, load = 0.05, 4e-4, 30.0, 4000.0
    half_width = math.sqrt(2 * load / (B * math.pi * E_STAR * face))   # Hertz line contact
    dx, dy = face / (0.9 * n), 6 * half_width / n
    x = -0.1 * n * dx + (np.arange(n) + 0.5) * dx
    y = (np.arange(n) - (n - 1) / 2) * dy
    X, Y = np.meshgrid(x, y, indexing="ij")
    return B * Y**2 + slope * X, dx, dy, X > 0, load


def test_line_contact_cut_by_a_face_end_in_any_length_unit():
    """The line contact solved in mm and with every length 1000 times larger (µm numbers)
    and the load 1e6 times (the same pressures): a dimensionally consistent iteration takes
    the same steps and gives the same pressure to rounding. The old join step gave a
    joining cell -tau·gap, a length taken for a pressure: its path changed with the unit,
    and in µm it stalled."""
    h, dx, dy, mask, load = line_contact_gap()
    sol = P.solve_contact(h, dx, dy, load, E_STAR, mask=mask)
    assert sol.iterations <= 40
    assert_solved(sol, h)
    k = 1000.0
    scaled = P.solve_contact(k * h, k * dx, k * dy, k * k * load, E_STAR, mask=mask)
    assert scaled.iterations == sol.iterations
    np.testing.assert_allclose(scaled.pressure_MPa, sol.pressure_MPa, rtol=0,
                               atol=1e-10 * sol.peak_pressure_MPa)
    assert scaled.approach_mm == pytest.approx(k * sol.approach_mm, rel=1e-10)
    # the load runs to the face end: highest on the material's first row
    assert np.unravel_index(np.argmax(sol.pressure_MPa), h.shape)[0] == np.argmax(mask[:, 0])


def test_two_patches_share_the_load_as_hertz_with_boussinesq_interaction():
    """Two bowls at the same height, 4.4 mm apart (A, B = 0.01, 0.04 and 0.02, 0.08 /mm),
    under 2000 N. Each patch is a Hertz contact for its share W_i (analytic.hertz), pushed
    down further by the other's load as by a point load, W_j/(π E* D) (Boussinesq; Johnson
    1985, §3.2); both sink by the same approach, which fixes the split. The solver agrees to
    1e-3 in the split, 2e-3 in each peak and in the approach."""
    W, d = 2000.0, 2.2
    bowls = ((0.01, 0.04, -d), (0.02, 0.08, d))
    n, half_x, half_y = 128, 3.6, 0.55
    dx, dy = 2 * half_x / n, 2 * half_y / n
    x = (np.arange(n) - (n - 1) / 2) * dx
    y = (np.arange(n) - (n - 1) / 2) * dy
    X, Y = np.meshgrid(x, y, indexing="ij")
    h = np.minimum(*(A * (X - xc) ** 2 + B * Y**2 for A, B, xc in bowls))
    sol = P.solve_contact(h, dx, dy, W, E_STAR)
    assert_solved(sol, h)

    def sink(i, w):                                   # patch i under w, the other under W - w
        A, B, _ = bowls[i]
        return (hertz.hertz_point(A, B, w, 1.0 / E_STAR).approach
                + (W - w) / (math.pi * E_STAR * 2 * d))

    W0 = brentq(lambda w: sink(0, w) - sink(1, W - w), 0.01 * W, 0.99 * W)
    shares = (W0, W - W0)
    p = sol.pressure_MPa
    for i, side in enumerate((X < 0, X > 0)):
        A, B, _ = bowls[i]
        exact = hertz.hertz_point(A, B, shares[i], 1.0 / E_STAR)
        assert p[side].sum() * dx * dy == pytest.approx(shares[i], rel=1e-3)
        assert p[side].max() == pytest.approx(exact.p0, rel=2e-3)
    assert sol.approach_mm == pytest.approx(sink(0, W0), rel=2e-3)


def test_interference_start_is_hertz_for_a_sphere():
    """interference_start's level relation is Hertz's sphere (Johnson eqs 4.22-4.23): for the
    gap r²/(2R) it gives p0·sqrt(1 - r²/a²) to the grid's resolution; for a gap flat over the
    whole material (a flat punch) it gives none."""
    h, dx, dy, _, _, exact = hertz_grid(0.02, 0.02, 2500.0, n=128)
    p = P.interference_start(h, dx, dy, np.ones(h.shape, dtype=bool), 2500.0, E_STAR)
    p *= 2500.0 / (p.sum() * dx * dy)
    sphere = exact.p0 * np.sqrt(np.clip(1.0 - h / (0.02 * exact.a**2), 0.0, None))
    assert np.abs(p - sphere).max() < 0.02 * exact.p0
    flat = np.zeros((32, 32))
    assert P.interference_start(flat, 0.1, 0.1, flat == 0, 1000.0, E_STAR) is None


FIELDS = sorted((Path(__file__).parent / "data" / "fields").glob("*.npz"))


@pytest.mark.parametrize("path", FIELDS, ids=lambda path: path.stem)
def test_gap_fields_dumped_from_the_cycle(path):
    """Real fields (tests/data/fields/README.md): each converges within 40 iterations (the
    *_stall ones stalled at 500 before), passes assert_solved and agrees with the solution
    from the uniform start; an *_edge field is still reported as reaching the grid's edge
    (the caller widens the field)."""
    with np.load(path) as f:
        gap, mask = f["gap"], f["mask"]
        dx, dy, load, E_star = (float(f[k]) for k in ("dx", "dy", "load", "E_star"))
    if path.stem.endswith("_edge"):
        with pytest.raises(ValueError, match="reaches the grid's edge"):
            P.solve_contact(gap, dx, dy, load, E_star, mask=mask)
        return
    sol = P.solve_contact(gap, dx, dy, load, E_star, mask=mask)
    assert sol.iterations <= 40
    assert_solved(sol, gap)
    cold = P.solve_contact(gap, dx, dy, load, E_star, mask=mask, warm_start=False)
    assert np.abs(cold.pressure_MPa - sol.pressure_MPa).max() < 1e-5 * sol.peak_pressure_MPa


# --- bad input ----------------------------------------------------------------------------


@pytest.fixture(scope="module")
def small_gap():
    h, dx, dy, *_ = hertz_grid(0.02, 0.08, 2500.0, n=32)
    return h, dx, dy


@pytest.mark.parametrize("change, field", [
    (dict(load_N=-100.0), "load_N"),
    (dict(load_N=0.0), "load_N"),
    (dict(load_N=float("nan")), "load_N"),
    (dict(E_star_MPa=0.0), "E_star_MPa"),
    (dict(E_star_MPa=-2e5), "E_star_MPa"),
    (dict(dx_mm=float("inf")), "dx_mm"),
    (dict(dy_mm=0.0), "dy_mm"),
    (dict(mask=np.ones((31, 32), dtype=bool)), "mask"),
    (dict(mask=np.zeros((32, 32), dtype=bool)), "mask"),
    (dict(load_N=1e7), "gap_mm"),            # the contact would need more than the grid
    (dict(tol=0.0), "tol"),
    (dict(dtype=np.int64), "dtype"),
])
def test_bad_input_names_the_field(small_gap, change, field):
    h, dx, dy = small_gap
    args = dict(gap_mm=h, dx_mm=dx, dy_mm=dy, load_N=2500.0, E_star_MPa=E_STAR)
    args.update(change)
    with pytest.raises(ValueError, match=field) as info:
        P.solve_contact(**args)
    assert "\n" not in str(info.value)


def test_non_finite_gap_on_material_is_refused_off_material_ignored(small_gap):
    h, dx, dy = small_gap
    bad = h.copy()
    bad[3, 4] = np.nan
    with pytest.raises(ValueError, match=r"gap_mm: nan at cell \(3, 4\)"):
        P.solve_contact(bad, dx, dy, 2500.0, E_STAR)
    mask = np.ones(h.shape, dtype=bool)
    mask[3, 4] = False
    sol = P.solve_contact(bad, dx, dy, 2500.0, E_STAR, mask=mask)
    assert sol.pressure_MPa[3, 4] == 0


def test_edge_loads_bad_arguments(small_gap):
    h, dx, dy = small_gap
    sol = P.solve_contact(h, dx, dy, 2500.0, E_STAR)
    with pytest.raises(ValueError, match="axis"):
        sol.edge_loads(axis=2)
    with pytest.raises(ValueError, match="width_mm"):
        sol.edge_loads(width_mm=-0.1)


def test_solution_arrays_are_read_only(small_gap):
    h, dx, dy = small_gap
    sol = P.solve_contact(h, dx, dy, 2500.0, E_STAR)
    with pytest.raises(ValueError):
        sol.pressure_MPa[0, 0] = 1.0
    with pytest.raises(AttributeError):
        sol.approach_mm = 0.0
