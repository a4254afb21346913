"""The contacts of one mesh position solved as one problem (contact.pressure.solve_shared):
one approach, one load, the split following from the solve; checked against Hertz's
approach law, against grids of other cells, and, for a loaded helical pair with its teeth
bending, against the coupled equations themselves evaluated independently (a linear
convolution by scipy.signal of Love's cell coefficients, plus the teeth's bending of the
final pressure)."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq
from scipy.signal import fftconvolve

from toothcontact.analyses import analyse
from toothcontact.analytic.hertz import hertz_point
from toothcontact.case import parse_case
from toothcontact.contact import influence
from toothcontact.contact import pressure as P
from toothcontact.contact.compliance import PairCompliance
from toothcontact.contact.loaded import _member_ends, free_ends
from toothcontact.parallel import workers

E_STAR = 113186.8          # MPa, steel on steel (E 206 GPa, nu 0.3)


def bowl(n, step, A, B, separation):
    """The gap (mm) A x² + B y² + separation on an n × n grid of `step` (mm) about 0."""
    x = (np.arange(n) - (n - 1) / 2) * step
    return A * x[:, None] ** 2 + B * x[None, :] ** 2 + separation


def hertz_split(pairs, load):
    """The load on the first of two bowls (A, B, separation) that close by one approach:
    separation_k + Hertz's approach (Johnson eq 4.39 via hertz_point) equal."""

    def mismatch(w):
        (A1, B1, s1), (A2, B2, s2) = pairs
        return (s1 + hertz_point(A1, B1, w, 1 / E_STAR).approach
                - s2 - hertz_point(A2, B2, load - w, 1 / E_STAR).approach)

    return brentq(mismatch, 1e-9 * load, (1 - 1e-9) * load)


def test_two_ellipses_share_the_load_as_hertz_by_one_approach():
    """Two bowls of different curvature, the second 2 µm farther apart, started at an even
    split: the solve moves the load to the split Hertz's law gives (within 1 %), both
    carry their Hertz peaks (within 1.5 %) and report one approach, and the loads sum to
    the load."""
    load, step, n = 3000.0, 0.04, 96
    pairs = [(0.010, 0.030, 0.0), (0.020, 0.025, 0.002)]
    grids = [P.Grid(bowl(n, step, A, B, s), step, step) for A, B, s in pairs]
    first, second = P.solve_shared(grids, [0.5 * load, 0.5 * load], E_STAR, tol=1e-8)
    w = hertz_split(pairs, load)
    assert first.load_N + second.load_N == pytest.approx(load, rel=1e-9)
    assert first.load_N == pytest.approx(w, rel=0.01)
    assert first.approach_mm == second.approach_mm
    for solution, (A, B, s), share in ((first, pairs[0], w), (second, pairs[1], load - w)):
        hertz = hertz_point(A, B, share, 1 / E_STAR)
        assert solution.peak_pressure_MPa == pytest.approx(hertz.p0, rel=0.015)
        assert solution.approach_mm - s == pytest.approx(hertz.approach, rel=0.02)


def test_a_pair_beyond_the_approach_carries_nothing_and_grids_of_other_cells_agree():
    """A bowl 50 µm away (far beyond the other's 10 µm approach), even when started with
    half the load, ends with none (None); and one bowl solved on two grids of different
    cells (0.02 and 0.03 mm) beside an identical one gives the even split (within 0.5 %):
    the iteration runs in loads, not pressures, so cell sizes do not weigh the split."""
    load, A, B = 3000.0, 0.015, 0.02
    near = P.Grid(bowl(96, 0.02, A, B, 0.0), 0.02, 0.02)
    far = P.Grid(bowl(96, 0.02, A, B, 0.05), 0.02, 0.02)
    carried, nothing = P.solve_shared([near, far], [0.5 * load, 0.5 * load], E_STAR)
    assert nothing is None and carried.load_N == pytest.approx(load, rel=1e-9)
    coarse = P.Grid(bowl(64, 0.03, A, B, 0.0), 0.03, 0.03)
    fine, rough = P.solve_shared([near, coarse], [0.2 * load, 0.8 * load], E_STAR)
    assert fine.load_N == pytest.approx(0.5 * load, rel=0.005)
    assert rough.load_N == pytest.approx(0.5 * load, rel=0.005)


def test_a_grid_whose_contact_reaches_its_edge_is_named():
    """The contact of the second grid runs off its border: GridEdgeError names grid 1."""
    small = P.Grid(bowl(12, 0.02, 0.015, 0.02, 0.0), 0.02, 0.02)
    big = P.Grid(bowl(96, 0.02, 0.015, 0.02, 0.0), 0.02, 0.02)
    with pytest.raises(P.GridEdgeError, match="grid 1: the contact reaches") as found:
        P.solve_shared([big, small], [1000.0, 1000.0], E_STAR)
    assert found.value.reached == {1: (True, True)}


def test_every_grid_whose_contact_reaches_its_edge_is_named_at_once():
    """Two of three grids too small for their contacts: both are named in one error (a
    caller widens them together, not in one solve each)."""
    small = P.Grid(bowl(12, 0.02, 0.015, 0.02, 0.0), 0.02, 0.02)
    big = P.Grid(bowl(96, 0.02, 0.015, 0.02, 0.0), 0.02, 0.02)
    with pytest.raises(P.GridEdgeError, match="grid 0, 2: the contact reaches") as found:
        P.solve_shared([small, big, small], [1000.0, 1000.0, 1000.0], E_STAR)
    assert found.value.reached == {0: (True, True), 2: (True, True)}


@pytest.mark.parametrize("long_axis", [0, 1])
def test_the_edges_a_contact_reaches_are_named_by_axis(long_axis):
    """A contact line along one axis of its grid, wider than the grid across it, reaches
    only the edges across the other axis: GridEdgeError.reached says which (the loaded
    contact then widens its field along that axis alone)."""
    x = (np.arange(400) - 199.5) * 0.02
    y = (np.arange(12) - 5.5) * 0.02
    gap = 0.01 * x[:, None] ** 2 + 0.02 * y[None, :] ** 2
    if long_axis == 1:
        gap = gap.T
    with pytest.raises(P.GridEdgeError) as found:
        P.solve_shared([P.Grid(gap, 0.02, 0.02)], [1000.0], E_STAR)
    assert found.value.reached == {0: (False, True) if long_axis == 0 else (True, False)}


HELICAL = {"kind": "spur", "teeth": [23, 57], "module": "2.5 mm", "pressure_angle": "20 deg",
           "helix_angle": "20 deg", "hand": "right", "face_width": "25 mm",
           "pinion": {"profile_shift": 0.2, "crown": {"height": "12 um", "center": "3 mm"},
                      "tip_relief": {"amount": "10 um", "start_diameter": "65 mm"}},
           "gear": {"profile_shift": -0.2,
                    "tip_relief": {"amount": "10 um", "start_diameter": "153.6 mm"}},
           "load": {"tangential_load": "6000 N"},
           "analysis": {"positions": 3, "interference": False,
                        "positions_check": False, "pressure_grid": 64}}


@pytest.fixture(scope="module")
def helical():
    """The bundled helical pair's design analysed in this process, with the teeth's
    operator of each loaded contact's field (field -> StructureOperator), as the solve
    used them."""
    built, teeth = {}, []
    original = PairCompliance.operator

    def keep(self, cycle, field):
        operator = original(self, cycle, field)
        built[id(field)] = (field, operator)        # the field kept: its id stays its own
        teeth[:] = [self]
        return operator

    with pytest.MonkeyPatch.context() as patch, workers(1):
        patch.setattr(PairCompliance, "operator", keep)
        result = analyse(parse_case(HELICAL))
    operators = {id(c.field): built[id(c.field)][1] for c in result.loaded if c is not None}
    return result, operators, teeth[0]


def cell_kernel(ox, oy, dx, dy, reference, E_star):
    """The displacement (mm per MPa, E* = 1) at the offsets (ox, oy) (mm, any, not only
    whole cells) of 1 MPa on one dx × dy cell: Johnson eq (3.25)'s double difference of F
    at the cell's corners, less each body's Boussinesq displacement at its reference depth
    (influence.InfluenceOperator's terms, here at any offset)."""
    total = 0.0
    for sx, sy, sign in ((1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1)):
        s, t = ox + sx * dx / 2, oy + sy * dy / 2
        total = total + sign * influence._antiderivative(s, t) / math.pi
        for depth, E, nu in reference:
            G = E / (2.0 * (1.0 + nu))
            total = total - sign * E_star / (4.0 * math.pi * G) * influence._depth_antiderivative(
                s, t, depth, nu)
    return total


def mirrored_oblique(p, end, dx, dy, reference, E_star):
    """The mirror term of an oblique free end (influence.ObliqueFreeEnd) summed directly
    (mm per E*): each tapered cell's pressure as a uniform cell centred on its exact image
    about the end's line (not spread onto the cells around it, as the solver does), its
    displacement read at every tapered cell by `cell_kernel`."""
    I, J = np.meshgrid(np.arange(p.shape[0]), np.arange(p.shape[1]), indexing="ij")
    d = end.a * I + end.b * J + end.c
    band = (d > 0.0) & (d < end.reach_mm)
    u = np.zeros(p.shape)
    if not band.any():
        return u
    i, j, d = I[band], J[band], d[band]
    taper = influence.end_taper(d / end.reach_mm)
    x, y = i * dx, j * dy
    image_x, image_y = x - 2.0 * d * end.a / dx, y - 2.0 * d * end.b / dy
    K = cell_kernel(x[:, None] - image_x[None, :], y[:, None] - image_y[None, :], dx, dy,
                    reference, E_star)
    u[band] = end.weight * taper * (K @ (taper * p[band])) / E_star
    return u


def mirrored(p, end, dx, dy, reference, E_star):
    """The mirror term of a free end (influence.FreeEnd) evaluated directly (mm per E*): the
    tapered pressure placed at its mirror cells (2·index - 1 - i) on a grid extended past
    the end, linearly convolved with Love's cell coefficients (scipy.signal), read back on
    the tapered cells."""
    if isinstance(end, influence.ObliqueFreeEnd):
        return mirrored_oblique(p, end, dx, dy, reference, E_star)
    q = p if end.axis == 0 else p.T
    step = (dx, dy)[end.axis]
    n, m = q.shape
    i = np.arange(n)
    depth = (i - end.index) if end.side == "low" else (end.index - 1 - i)
    width = int(math.ceil(end.reach_mm / step))
    inside = (depth >= 0) & (depth < width)
    taper = np.zeros(n)
    taper[inside] = end.taper(width, step)[depth[inside]]
    shift = n                                     # row r of the image grid is r - shift
    image = np.zeros((3 * n, m))
    image[2 * end.index - 1 - i[inside] + shift] = (taper[:, None] * q)[inside]
    steps = (dx, dy) if end.axis == 0 else (dy, dx)
    kernel = influence.InfluenceOperator.coefficients(3 * n, m, *steps, reference, E_star)
    centred = np.roll(kernel, (3 * n, m), axis=(0, 1))[1:, 1:]
    u = fftconvolve(image, centred, mode="full")[3 * n - 1:6 * n - 1, m - 1:2 * m - 1]
    u = end.weight * taper[:, None] * u[shift:shift + n] / E_star
    return u if end.axis == 0 else u.T


def test_a_loaded_helical_position_satisfies_the_coupled_equations(helical):
    """The bundled helical pair's design (bias crown, tip relief on both members; three
    pairs in contact, one on a relieved tip), its teeth bending: at every position the
    final pressure p and the common approach D satisfy h + K·p + B·p = D on the contact
    and >= D elsewhere on the material (K with the mirror term of every free face end,
    evaluated directly on an extended grid; an end crossing the field obliquely has its
    images off the cells, which the solver spreads onto the cells around them: that
    spreading is held within 2 % of the mirror term's largest against a direct sum of each
    image as its own cell, measured 1.6 % on the pinion's end, 12 nm; the equations are then
    checked with the spread term the solve used), to 1.5e-4 of the position's largest
    displacement (the scale of the solver's tolerance, a relative gap error of 1e-5 over
    the cells: a pair on a relieved tip, a few cells touching, misses by 2.1e-4 of its own,
    0.4 nm; with the bodies' coupling the largest miss is 1.16e-4 of the position's, 2.0 nm
    of 17 µm, 1e-4 before it), with K·p
    recomputed as a linear convolution (scipy.signal.fftconvolve) of Love's cell
    coefficients and B·p the teeth's bending of that same pressure. The code before
    (separate solves per pair, the split from a model of each pair's approach, the bending
    of a coarser first solve held fixed on the full grid) missed by 2.7e-3 here, and gave
    the bundled helical pair's largest pressure as 1928 MPa where the coupled solve gives
    1573 MPa. The teeth of different pairs move with their gear bodies
    (PairCompliance.body_coupling: each contact's root loads from the others', added as the
    solve adds them)."""
    result, operators, teeth = helical
    rows = result.sections["positions"]
    assert sum(c is not None for c in result.loaded) >= 6
    for roll in {r["roll_deg"] for r in rows}:
        contacts = [c for r, c in zip(rows, result.loaded)
                    if c is not None and r["roll_deg"] == roll]
        structures = [operators[id(c.field)] for c in contacts]
        body = teeth.body_coupling(structures, [r["pair"] for r, c in zip(rows, result.loaded)
                                                if c is not None and r["roll_deg"] == roll])
        if body is not None:
            roots = np.array([B.root_resultants(c.solution.pressure_MPa)
                              for B, c in zip(structures, contacts)])
            moves = np.einsum("klmab,lmb->kma", body, roots)
        gaps, scale = [], 0.0
        for k, contact in enumerate(contacts):
            s, f, B = contact.solution, contact.field, operators[id(contact.field)]
            n0, n1 = s.pressure_MPa.shape
            kernel = influence.InfluenceOperator.coefficients(n0, n1, s.dx_mm, s.dy_mm, B.reference,
                                                      s.E_star_MPa)
            centred = np.roll(kernel, (n0, n1), axis=(0, 1))[1:, 1:]  # offsets -n+1 .. n-1
            u = (fftconvolve(s.pressure_MPa, centred, mode="full")[n0 - 1:2 * n0 - 1,
                                                                     n1 - 1:2 * n1 - 1]
                 / s.E_star_MPa + B(s.pressure_MPa))
            if body is not None:
                u += B.root_deflection(moves[k])
            for end in free_ends(f, _member_ends(None), B.reference):
                direct = mirrored(s.pressure_MPa, end, s.dx_mm, s.dy_mm, B.reference,
                                  s.E_star_MPa)
                if isinstance(end, influence.ObliqueFreeEnd):
                    spread = np.zeros(direct.shape)
                    end.add_mirror(spread, s.pressure_MPa,
                                   influence.InfluenceOperator(direct.shape, s.dx_mm, s.dy_mm,
                                                       B.reference, s.E_star_MPa),
                                   (s.dx_mm, s.dy_mm), False)
                    spread /= s.E_star_MPa
                    assert np.max(np.abs(spread - direct)) <= 0.02 * np.max(np.abs(direct))
                    direct = spread
                u += direct
            gaps.append((np.where(f.material, f.gap + u - s.approach_mm, np.nan),
                         s.pressure_MPa > 0, f.material))
            scale = max(scale, float(np.max(np.abs(u[f.material]))))
        for g, touching, material in gaps:
            assert np.max(np.abs(g[touching])) < 1.5e-4 * scale
            assert np.nanmin(g[~touching & material]) > -1.5e-4 * scale
        assert len({c.solution.approach_mm for c in contacts}) == 1
        assert math.fsum(c.solution.load_N for c in contacts) == pytest.approx(
            math.fsum(r["normal_load_N"] for r in rows if r["roll_deg"] == roll), rel=1e-9)


def test_a_window_too_small_for_the_contact_is_widened_to_the_same_answer(monkeypatch):
    """The solve iterates on a window about each grid's contact and penetrating cells and
    checks the whole grid after each pass. Started on the 7 × 7 cells at the centre and its
    first window forced to them (the contact is some 60 cells across), the first pass
    leaves the cells outside penetrating; the whole-grid check finds them, the window is
    widened and the answer is that of the unforced solve (pressures within 1e-5 of the
    peak, measured 1.7e-6; the same approach to 1e-8), in more passes than one."""
    load, step, n = 2000.0, 0.02, 128
    gap = bowl(n, step, 0.010, 0.016, 0.0)
    free = P.solve_contact(gap, step, step, load, E_STAR, tol=1e-8)
    windows, passes = P._window, []
    centre = slice(n // 2 - 3, n // 2 + 4)
    start = np.zeros(gap.shape)
    start[centre, centre] = 1.0

    def first_tiny(busy, old):
        passes.append(old)
        return (centre, centre) if old is None else windows(busy, old)

    monkeypatch.setattr(P, "_window", first_tiny)
    widened = P.solve_contact(gap, step, step, load, E_STAR, tol=1e-8, start=start)
    assert len(passes) >= 2
    assert np.max(np.abs(widened.pressure_MPa - free.pressure_MPa)) < 1e-5 * free.peak_pressure_MPa
    assert widened.approach_mm == pytest.approx(free.approach_mm, rel=1e-8)


def test_the_operators_of_a_window_are_the_grids_operators_there(helical):
    """A window's half-space and teeth bending (InfluenceOperator.part,
    StructureOperator.window) give on the window what the whole grid's operators give for
    the same pressure (zero outside it), to rounding."""
    result, operators, _ = helical
    contact = next(c for c in result.loaded if c is not None)
    s, B = contact.solution, operators[id(contact.field)]
    shape = s.pressure_MPa.shape
    rows, cols = slice(5, shape[0] - 9), slice(3, shape[1] - 4)
    rng = np.random.default_rng(7)
    p = np.zeros(shape)
    p[rows, cols] = rng.random(p[rows, cols].shape) * contact.field.material[rows, cols]
    whole = influence.influence_operator(shape, s.dx_mm, s.dy_mm, B.reference, s.E_star_MPa)
    part = whole.part(p[rows, cols].shape)
    expected = whole(p)[rows, cols]
    assert np.max(np.abs(part(p[rows, cols]) - expected)) < 1e-12 * np.max(np.abs(expected))
    bent = B(p)[rows, cols]
    assert np.max(np.abs(B.window(rows, cols)(p[rows, cols]) - bent)) < 1e-12 * np.max(np.abs(bent))
