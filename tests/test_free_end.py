"""Free face ends: the quarter-space correction of the half-space contact (influence.FreeEnd,
Guilbault's mirror pressure with a factor), checked against a direct sum of its own
definition, against 3D finite elements of an elastic block with a free end (tests/
fe_reference.py: a rigid flat strip punch on a block that ends flush with it, and on one
that runs on; a Hertz line contact of a rigid cylinder, and of two elastic bodies where one
ends and the other runs on, a worm set's mixed end), and on the FZG C-type gear
(cases/fzg_c_type.toml: aligned, uncrowned, flush ends)."""

import json
import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from toothcontact.contact import influence
from toothcontact.contact.loaded import _member_ends, _merged
from toothcontact.contact.influence import FreeEnd, free_end_factor
from toothcontact.contact.pressure import Grid, solve_shared

E_STEEL, NU = 210000.0, 0.3
E_BRONZE, NU_BRONZE = 98000.0, 0.35


def direct_mirror(p, end, dx, dy):
    """The mirror term by its definition, summed cell by cell (mm for E* = 1): the tapered
    pressure of each cell j, put at its mirror 2·index - 1 - j, displaces each tapered
    cell i by Love's coefficient of their offset."""
    n0, n1 = p.shape
    width = int(math.ceil(end.reach_mm / dx))
    taper = np.zeros(n0)
    for i in range(n0):
        depth = i - end.index if end.side == "low" else end.index - 1 - i
        if 0 <= depth < width:
            taper[i] = end.taper(width, dx)[depth]
    u = np.zeros_like(p)
    for i in range(n0):
        for k in range(n1):
            if taper[i] == 0.0:
                continue
            total = 0.0
            for j in range(n0):
                if taper[j] == 0.0:
                    continue
                mirror = 2 * end.index - 1 - j
                total += taper[j] * np.sum(influence.rectangle_displacement(
                    (i - mirror) * dx, (k - np.arange(n1)) * dy, 0.5 * dx, 0.5 * dy) * p[j])
            u[i, k] = end.weight * taper[i] * total
    return u


@pytest.mark.parametrize("side", ["low", "high"])
def test_the_mirror_term_is_its_definition_and_symmetric(side):
    """On a 14 × 5 grid with an end crossing it, the operator's mirror term (one
    convolution of the mirrored strip) equals the cell-by-cell sum of its definition to
    1e-12, and the whole operator (half-space plus mirror) is symmetric: v·K u = u·K v."""
    rng = np.random.default_rng(7)
    dx, dy = 0.2, 0.15
    end = FreeEnd(0, 3 if side == "low" else 11, side, 1.4, 1.5)
    op = influence.influence_operator((14, 5), dx, dy)
    p = rng.random((14, 5))
    u = np.zeros_like(p)
    end.add_mirror(u, p, op, (dx, dy), single=False)
    assert np.max(np.abs(u - direct_mirror(p, end, dx, dy))) < 1e-12 * np.max(np.abs(u))

    def K(q):
        out = op(q)
        end.add_mirror(out, q, op, (dx, dy), single=False)
        return out

    a, b = rng.random((14, 5)), rng.random((14, 5))
    assert np.sum(b * K(a)) == pytest.approx(np.sum(a * K(b)), rel=1e-12)


def punch_line_load(a, length, phi, cell):
    """Our line load under a rigid flat strip punch |y| <= a, x in [-length, 0] (mm) on an
    elastic half-space (E* = E/(1 - ν²): the punch rigid), its end at x = 0 free (the
    mirror with factor phi, acting over the whole strip) or running on (phi = 0): the mean
    over the last c·a against mid-length, for c = 0.05, 0.1, 0.25."""
    nx, ny = int(round(length / cell)), int(round(2 * a / cell))
    gap = np.zeros((2 * nx + 2, ny + 2))              # room past x = 0 for the mirror
    mask = np.zeros(gap.shape, bool)
    mask[1:nx + 1, 1:-1] = True
    ends = (FreeEnd(0, nx + 1, "high", phi, length),) if phi else ()
    s = solve_shared([Grid(gap, cell, cell, mask, None, (), ends)], [1000.0],
                     E_STEEL / (1 - NU**2), tol=1e-8, max_iter=2000)[0]
    q = s.pressure_MPa.sum(axis=1)[1:nx + 1] * cell
    x = (np.arange(nx) + 0.5) * cell - length
    mid = q[np.argmin(np.abs(x + 0.5 * length))]
    return {c: float(q[x > -c * a].mean() / mid) for c in (0.05, 0.1, 0.25)}


@pytest.fixture(scope="module")
def fe_punch():
    """The 3D finite-element punch (tests/fe_reference.py: a = 1 mm, 10 mm long, on a block
    8 lengths deep and wide, running on past the strip's far end): (free end, running on)."""
    fr = pytest.importorskip("fe_reference")
    return (fr.flat_punch_line_load(1.0, 10.0, end_free=True, nu=NU, E=E_STEEL, h_end=1 / 8),
            fr.flat_punch_line_load(1.0, 10.0, end_free=False, nu=NU, E=E_STEEL))


def test_a_flat_punch_at_a_free_end_loads_it_as_3d_finite_elements_do(fe_punch):
    """A rigid flat strip punch (a = 1 mm, 10 mm long) ending flush with its block's free
    end face, and on a block that runs on past it. The finite elements (converged: 0.522
    at elements of a/8 and a/16 at the end) put 0.52 of mid-length's line load in the last
    0.1a at the free end, against 5.2 where the block runs on. Our half-space with the
    mirror term (φ = 1.42 for ν = 0.3): 0.485, within 10 % (-7 %); running on, 3.16 over
    the last 0.25a against 3.32 (-5 %; the last 0.1a of a running-on punch is the edge
    singularity's, which the finite elements do not resolve at this size). Ours converges
    with the cells (0.483, 0.484, 0.485 at 0.05, 0.025, 0.0125 mm). The mirror's shape is
    the model's limit: 0.345 against 0.49 over the last 0.05a, 0.65 against 0.58 over the
    last 0.25a (benchmarks/fe_quarter_space.json)."""
    free, running = fe_punch
    ours_free = punch_line_load(1.0, 10.0, free_end_factor(NU), 0.025)
    ours_running = punch_line_load(1.0, 10.0, 0.0, 0.025)
    assert ours_free[0.1] == pytest.approx(free.end_average(0.1), rel=0.10)
    assert ours_running[0.25] == pytest.approx(running.end_average(0.25), rel=0.10)
    assert free.end_average(0.1) < 0.6 and running.end_average(0.1) > 4.0
    assert ours_free[0.1] < 0.6 and ours_running[0.1] > 4.0


def cylinder_line_load(radius, load, length, phi, cell, E_star=E_STEEL / (1 - NU**2)):
    """Our line load under a rigid cylinder (axis along x, x in [-length, 0], `radius` mm)
    on an elastic half-space with its end at x = 0 free (phi) or running on (0), the load
    scaled so that mid-length carries `load` N/mm: the mean over the last c·b against
    mid-length, for c = 0.05, 0.1, 0.25, 0.5 (b the Hertz half-width at `load`). E_star
    (MPa): the body's, or a pair's (two elastic bodies on one half-space; phi then the
    FreeEnd's weight, see loaded._member_ends)."""
    b = math.sqrt(4 * load * radius / (math.pi * E_star))
    nx, ny = int(round(length / cell)), int(round(6 * b / cell))
    y = (np.arange(ny) - 0.5 * (ny - 1)) * cell
    gap = np.broadcast_to(y**2 / (2 * radius), (2 * nx + 2, ny)).copy()
    mask = np.zeros(gap.shape, bool)
    mask[1:nx + 1] = True
    ends = (FreeEnd(0, nx + 1, "high", phi, length),) if phi else ()
    total = load * length
    for _ in range(3):                        # the mid-length line load brought to `load`
        s = solve_shared([Grid(gap, cell, cell, mask, None, (), ends)], [total], E_star,
                         tol=1e-8, max_iter=2000)[0]
        q = s.pressure_MPa.sum(axis=1)[1:nx + 1] * cell
        x = (np.arange(nx) + 0.5) * cell - length
        mid = q[np.argmin(np.abs(x + 0.5 * length))]
        total *= load / mid
    return {c: float(q[x > -c * b].mean() / mid) for c in (0.05, 0.1, 0.25, 0.5)}


def test_a_hertz_line_contact_at_a_free_end_loads_it_as_3d_finite_elements_do():
    """A rigid cylinder (R = 84 mm, Hertz half-width b = 1 mm, p0 = 1374 MPa, 10b long) on a
    block that ends flush with it, and on one that runs on. The finite elements
    (tests/fe_reference.py, elements b/8 across, block 4 lengths: 0.510; converged with
    finer elements and larger blocks, 0.506, benchmarks/fe_cylinder_end.json) put 0.51 of
    mid-length's line load in the last 0.1b at the free end, against 3.56 over the last
    0.25b running on (the last 0.1b of a running-on end is the edge singularity's, still
    falling 1.6 % per refinement there). Ours, the half-space with the mirror term: 0.464
    (-9 %) and 3.40 (-5 %), within 10 %. Further in the mirror's shape shows: +12 % over the
    last 0.25b and +18 % over 0.5b of the free end, -34 % over 0.05b (the flat punch's
    pattern)."""
    fr = pytest.importorskip("fe_reference")
    size = 40.0
    free = fr.cylinder_end_line_load(end_free=True, depth=size, width=size, run_on=size)
    running = fr.cylinder_end_line_load(end_free=False, depth=size, width=size, run_on=size)
    load = free.q_mid
    ours_free = cylinder_line_load(84.0, load, 10.0, free_end_factor(NU), 0.05)
    ours_running = cylinder_line_load(84.0, load, 10.0, 0.0, 0.05)
    assert ours_free[0.1] == pytest.approx(free.end_average(0.1), rel=0.10)
    assert ours_running[0.25] == pytest.approx(running.end_average(0.25), rel=0.10)
    assert free.peak_mid == pytest.approx(free.p0_hertz, rel=0.02)


def oblique_cylinder_line_load(radius, load, length, phi, cell, angle):
    """cylinder_line_load with the cylinder's axis at `angle` (rad) to the grid's x: the
    same body and end face turned in the plane, its end crossing the cells obliquely
    (influence.ObliqueFreeEnd); the line load binned along the axis."""
    E_star = E_STEEL / (1 - NU**2)
    b = math.sqrt(4 * load * radius / (math.pi * E_star))
    along = np.array([math.cos(angle), math.sin(angle)])
    across = np.array([-along[1], along[0]])
    corners = np.array([s * along + q * across for s in (-length, length) for q in (-3 * b, 3 * b)])
    lo, hi = corners.min(axis=0), corners.max(axis=0)
    shape = np.ceil((hi - lo) / cell).astype(int) + 1
    X, Y = np.meshgrid(lo[0] + np.arange(shape[0]) * cell, lo[1] + np.arange(shape[1]) * cell,
                       indexing="ij")
    s, q = X * along[0] + Y * along[1], X * across[0] + Y * across[1]
    gap = q**2 / (2 * radius)
    mask = (s < 0) & (s > -length) & (np.abs(q) < 3 * b)
    # d = -s (mm) at cell (i, j): the distance from the end into the body
    ends = ((influence.ObliqueFreeEnd(-along[0] * cell, -along[1] * cell, -float(lo @ along), phi,
                              length),) if phi else ())
    total = load * length
    for _ in range(3):                        # the mid-length line load brought to `load`
        solved = solve_shared([Grid(gap, cell, cell, mask, None, (), ends)], [total], E_star,
                              tol=1e-8, max_iter=2000)[0]
        cell_load = solved.pressure_MPa * cell * cell
        mid = cell_load[np.abs(s + 0.5 * length) < 0.5].sum()     # N over 1 mm
        total *= load / mid
    return {c: float(cell_load[s > -c * b].sum() / (c * b) / mid) for c in (0.1, 0.25, 0.5)}


def test_an_oblique_free_end_loads_its_end_as_a_square_one():
    """The Hertz line contact of the test above (b = 1 mm, 10b long, cells of b/20) turned
    by 30 deg to the grid, so that its free end crosses the cells obliquely (a helical
    flank's face end on a field laid along the helix): the mirror's images then fall off
    the cell centres and are spread onto them. The line load at the end against mid-length
    agrees with the square end's: within 2 % over the last 0.25b and 0.5b and within 5 %
    over the last 0.1b (two cells, a staircase along the end; measured -0.6 %, -0.6 % and
    -0.9 %; with cells of b/40 -0.5 %, -0.5 %, -0.65 %); on the half-space (running on) the
    same within 2 % over 0.25b. The operator stays symmetric to the spreading's order:
    |v·K u - u·K v| below 1e-3 of v·K u (measured 8e-6)."""
    phi = free_end_factor(NU)
    load = math.pi * E_STEEL / (1 - NU**2) / (4 * 84.0)      # b = 1 mm
    square = cylinder_line_load(84.0, load, 10.0, phi, 0.05)
    turned = oblique_cylinder_line_load(84.0, load, 10.0, phi, 0.05, math.radians(30.0))
    for c in (0.25, 0.5):
        assert turned[c] == pytest.approx(square[c], rel=0.02)
    assert turned[0.1] == pytest.approx(square[0.1], rel=0.05)
    running = oblique_cylinder_line_load(84.0, load, 10.0, 0.0, 0.05, math.radians(30.0))
    assert running[0.25] == pytest.approx(cylinder_line_load(84.0, load, 10.0, 0.0, 0.05)[0.25],
                                          rel=0.02)

    rng = np.random.default_rng(3)
    dx, dy = 0.1, 0.08
    end = influence.ObliqueFreeEnd(0.6 * dx, 0.8 * dy, -1.2, phi, 1.5)
    op = influence.influence_operator((30, 24), dx, dy)

    def K(p):
        out = op(p)
        end.add_mirror(out, p, op, (dx, dy), single=False)
        return out

    u, v = rng.random((30, 24)), rng.random((30, 24))
    assert abs(np.sum(v * K(u)) - np.sum(u * K(v))) < 1e-3 * np.sum(v * K(u))


#: benchmarks/fe_mixed_end.json, fe_best_estimate_mean_last: the 3D finite elements' mean
#: line load over the last c·b of body A's end against mid-length (refine 2 at blocks 2L,
#: plus the change from blocks 2L to 8L at refine 1)
FE_MIXED = {0.05: 0.9608, 0.1: 0.9065, 0.25: 0.8702, 0.5: 0.8647}
FE_FLUSH = {0.05: 0.4074, 0.1: 0.4477, 0.25: 0.5185, 0.5: 0.5877}


def worm_pair():
    """A bronze wheel (A: E 98 GPa, ν 0.35) and a steel worm (B): each member's end weight
    as loaded._member_ends gives it (φ(ν) times its share of the composite compliance), and
    the pair's E* (MPa)."""
    members = {"A": SimpleNamespace(E=E_BRONZE, nu=NU_BRONZE),
               "B": SimpleNamespace(E=E_STEEL, nu=NU)}
    E_star = 1.0 / sum((1 - m.nu**2) / m.E for m in members.values())
    return _member_ends(SimpleNamespace(members=members)), E_star


def test_a_mixed_end_loads_it_as_3d_finite_elements_do():
    """A worm set's mixed end: the wheel (A, bronze, E = 98 GPa, ν = 0.35) ends at x = 0
    with a free end face while the worm (B, steel) runs on past it. A Hertz line contact
    between them (R = 84 mm, b = 1 mm on the pair's E* = 75.3 GPa: w = 703.7 N/mm, 10b
    long). Ours: the half-space with the pair's E* and ONE mirror at x = 0, weighted as
    loaded._member_ends weights A alone (φ(0.35)·s_A = 1.57 × 0.674 = 1.058; B runs on, no
    mirror), cells of b/20 (b/40 within 0.6 %).

    The finite elements (tests/fe_reference.py mixed_end_line_load: both blocks elastic,
    their contact faces condensed on matching nodes, the contact on C_A + C_B; stored from
    benchmarks/fe_mixed_end.json): A's end carries 0.907 of mid-length's line load over the
    last 0.1b, 0.870 over the last 0.25b. Converged: with elements b/8, b/12, b/16 across
    (blocks 2L) 0.948, 0.942, 0.940 over 0.1b and 0.901, 0.899, 0.898 over 0.25b; with
    blocks 2L, 4L, 8L (elements b/8) 0.948, 0.921, 0.915 and 0.901, 0.878, 0.873 (the best
    estimate: the finest mesh plus the 2L-to-8L change; 4L to 8L moves it < 0.8 %).

    Tolerances: ours within 10 % over the last 0.1b (measured +5.9 %). Over the last 0.25b
    ours MISSES the 10 % target: +13.0 % (+15.1 % over 0.5b), pinned here between +8 % and
    +18 % so that a change of the model shows. Not the split of the weight between the
    members: the weight that would match the FE rises from 1.05 over the last 0.05b to 1.09,
    1.16, 1.24 over 0.1b, 0.25b, 0.5b (benchmarks/fe_mixed_end.json, ours_weight_scan), so
    no weight fits; it is the mirror's shape, too soft at the very end and too stiff further
    in, as for one body on a rigid cylinder (+12 % over 0.25b for steel,
    test_a_hertz_line_contact_at_a_free_end_loads_it_as_3d_finite_elements_do).

    Both ending flush (both mirrors merged as loaded._merged does, weight 1.521): the FE
    0.448 over 0.1b, 0.519 over 0.25b (converged as above: 0.473, 0.478, 0.476 and 0.548,
    0.550, 0.547 with the elements; 0.473, 0.450, 0.446 and 0.548, 0.524, 0.519 with the
    blocks); ours within 10 % over 0.25b (+8.7 %), but 19 % low over 0.1b (pinned between
    -26 % and -12 %): the mirror's over-softening of the last cells grows with its weight.

    The FE solver's two-body coupling is checked against its one-body form in
    tests/test_fe_reference.py (a rigid B gives the rigid cylinder's ratios to 1e-3)."""
    weights, E_star = worm_pair()
    load = math.pi * E_star / (4 * 84.0)                     # b = 1 mm
    mixed = cylinder_line_load(84.0, load, 10.0, weights["A"], 0.05, E_star)
    (flush_end,) = _merged([FreeEnd(0, 0, "high", weights[m], 10.0) for m in ("A", "B")])
    flush = cylinder_line_load(84.0, load, 10.0, flush_end.weight, 0.05, E_star)
    assert weights["A"] == pytest.approx(1.058, abs=1e-3)
    assert flush_end.weight == pytest.approx(1.521, abs=1e-3)

    stored = json.loads((Path(__file__).resolve().parents[1] / "benchmarks"
                         / "fe_mixed_end.json").read_text())["fe_best_estimate_mean_last"]
    for c in (0.05, 0.1, 0.25, 0.5):
        assert stored["mixed"][f"{c}b"] == pytest.approx(FE_MIXED[c], abs=1e-4)
        assert stored["flush"][f"{c}b"] == pytest.approx(FE_FLUSH[c], abs=1e-4)

    assert mixed[0.1] == pytest.approx(FE_MIXED[0.1], rel=0.10)
    assert 0.08 < mixed[0.25] / FE_MIXED[0.25] - 1 < 0.18       # the known miss
    assert flush[0.25] == pytest.approx(FE_FLUSH[0.25], rel=0.10)
    assert -0.26 < flush[0.1] / FE_FLUSH[0.1] - 1 < -0.12       # the known miss
    assert flush[0.1] < mixed[0.1] < 1.0

    fr = pytest.importorskip("fe_reference")
    live = fr.mixed_end_line_load(depth=20.0, width=20.0, run_on=20.0, refine=0.75)
    assert live.q_mid == pytest.approx(load, rel=1e-6)
    for c in (0.1, 0.25):
        assert 0.0 < live.end_average(c) / FE_MIXED[c] - 1 < 0.08
    assert mixed[0.1] == pytest.approx(live.end_average(0.1), rel=0.10)

    def error(ours, fe, c):
        return ours[c] / fe[c] - 1.0

    assert abs(error(mixed, FE_MIXED, 0.1)) < 0.10
    assert 0.08 < error(mixed, FE_MIXED, 0.25) < 0.18
    assert abs(error(flush, FE_FLUSH, 0.25)) < 0.10
    assert -0.26 < error(flush, FE_FLUSH, 0.1) < -0.12
