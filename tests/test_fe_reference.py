"""The 3D finite-element reference (tests/fe_reference.py) against closed forms and itself.

Coarse meshes: each test takes seconds (the finer runs are benchmarks/fe_quarter_space.py).
"""

import numpy as np
import pytest

pytest.importorskip("skfem")

import fe_reference as fr  # noqa: E402  (tests/ is on sys.path, as for mutations.py)

E, NU = 210000.0, 0.3


def test_stiffness_matches_scikit_fem():
    """The closed-form brick stiffness equals scikit-fem's linear_elasticity assembly."""
    from skfem import Basis, ElementHex1, ElementVector, asm
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    x = fr.graded_axis(-2.0, 1.0, [(0.0, 0.0, 0.2)], growth=0.5)
    y = fr.graded_axis(0.0, 1.5, [(0.0, 0.3, 0.25)], growth=0.5)
    mesh = fr.block_mesh(x, y, [-1.0, -0.4, 0.0])
    basis = Basis(mesh, ElementVector(ElementHex1()))
    assert np.array_equal(basis.nodal_dofs, 3 * np.arange(mesh.p.shape[1]) + np.arange(3)[:, None])
    K_ref = asm(linear_elasticity(*lame_parameters(E, NU)), basis)
    K = fr.stiffness(mesh, E, NU)
    assert abs(K - K_ref).max() <= 1e-12 * abs(K_ref).max()


def test_love_rectangle_matches_quadrature():
    """Love's closed form for a uniformly loaded rectangle equals (1-nu^2)p/(pi E) int dA/r."""
    from scipy.integrate import dblquad

    rect = (-1.0, 0.5, -0.3, 0.7)
    for px, py in [(0.0, 0.0), (2.0, 1.0), (-1.0, -0.3), (-3.0, -4.0)]:
        num = dblquad(lambda yy, xx: 1.0 / np.hypot(xx - px, yy - py), rect[0], rect[1],
                      rect[2], rect[3], epsabs=1e-11)[0]
        closed = fr.love_rectangle_uz(px, py, rect, 1.0, 1.0, 0.0) * np.pi
        assert closed == pytest.approx(num, rel=1e-9)


@pytest.mark.parametrize("end_free, far_end", [(True, "run_on"), (False, "run_on"), (True, "free")])
def test_punch_line_load_uniform_far_from_the_ends(end_free, far_end):
    """(a) A long strip (24a on a 8a-deep layer): q(x) within 2 % of mid-length's value
    wherever x is at least 6a from both punch ends."""
    a, length = 1.0, 24.0
    res = fr.flat_punch_line_load(a, length, end_free=end_free, far_end=far_end, depth=8.0,
                                  width=8.0, run_on=8.0, h_end=a / 8)
    far = np.abs(res.x + length / 2) <= length / 2 - 6 * a
    assert far.sum() >= 10
    assert np.abs(res.q_norm[far] - 1).max() < 0.02
    # the load is the sum of the line load, and both ends differ from mid-length
    assert res.total == pytest.approx(res.node_force.sum())
    assert (res.q_norm[-1] < 0.9) if end_free else (res.q_norm[-1] > 2.0)


def test_surface_displacement_converges_to_love():
    """(b) Uniform pressure on a square (side 1 mm) 10 mm from the free end of a 20 mm block:
    u_z(centre) - u_z(centre +- 1, 2 mm) against Love's half-space values. The differences
    hardly see the fixed bottom; trilinear bricks are too stiff by ~2 % at element size
    s/4 (refine 1) and ~1 % at s/6 (refine 1.5)."""
    s, p, D = 1.0, 100.0, 10.0
    patch = (-D - s / 2, -D + s / 2, -s / 2, s / 2, p)

    def love(x):
        return -fr.love_rectangle_uz(x, 0.0, patch[:4], p, E, NU)    # u_z, negative down

    errors = []
    for refine in (1.0, 1.5):
        res = fr.surface_displacement([patch], end_free=True, nu=NU, E=E, Lx=20.0, Ly=20.0,
                                      H=20.0, refine=refine, fine_to_end=False)
        ratios = [(res(-D) - res(-D + d)) / (love(-D) - love(-D + d)) for d in (1.0, 2.0, -2.0)]
        errors.append(max(abs(r - 1) for r in ratios))
        assert min(ratios) > 0.95 and max(ratios) < 1.01
    assert errors[0] < 0.03
    assert errors[1] < 0.015
    assert errors[1] < 0.7 * errors[0]


def test_punch_end_ratio_mesh_convergence():
    """(c) End-to-mid line-load ratios (mean q over the last 0.1a and 0.25a) of the free end
    change by < 1 % from refine 1 to 1.5; the running-on end (a q ~ 1/sqrt(distance)
    singularity, integrable) by < 3 % over the last 0.25a."""
    a, length, B = 1.0, 10.0, 10.0
    kw = dict(depth=B, width=B, run_on=B, h_end=a / 8)
    free = [fr.flat_punch_line_load(a, length, end_free=True, refine=r, **kw) for r in (1, 1.5)]
    for c in (0.1, 0.25):
        r1, r2 = (f.end_average(c) for f in free)
        assert 0.5 < r2 < 0.8
        assert abs(r2 / r1 - 1) < 0.01
    run = [fr.flat_punch_line_load(a, length, end_free=False, refine=r, **kw) for r in (1, 1.5)]
    r1, r2 = (f.end_average(0.25) for f in run)
    assert r2 > 2.5
    assert abs(r2 / r1 - 1) < 0.03


def test_mirror_exact_for_a_frictionless_wall():
    """The fit's bookkeeping: with the end face on a frictionless wall (u_x = 0) the run-on
    block's displacement plus its mirror image is exact, phi = 1 (the free end's phi > 1)."""
    s, D = 1.0, 1.0
    case = [[(-D - s / 2, -D + s / 2, -s / 2, s / 2, 100.0)]]
    kw = dict(nu=NU, E=E, Lx=10.0, Ly=10.0, H=10.0, h=0.5)
    wall = fr.surface_displacements(case, end_free=True, wall=True, **kw)[0]
    free = fr.surface_displacements(case, end_free=True, **kw)[0]
    runon = fr.surface_displacements(case, end_free=False, **kw)[0]
    x = wall.x[wall.x >= -(D + s) - 1e-9]
    m = runon(-x)
    for res, lo, hi in ((wall, 1 - 1e-8, 1 + 1e-8), (free, 1.2, 2.5)):
        d = res(x) - runon(x)
        phi = (m @ d) / (m @ m)
        assert lo < phi < hi


def test_cylinder_line_contact_at_a_free_end():
    """(d) A rigid cylinder (R = 84 mm, 10b long, b = 1 mm: w = 2158 N/mm, p0 = 1374 MPa)
    on a block 10 mm deep and wide, coarse (elements b/6 across, b/12 at the end face):
    the contact set solved exactly on the condensed top (no tension, no penetration), the
    mid-length peak pressure within 5 % of Hertz, the end of the cylinder loaded more where
    the block runs on past it (> 1.5 of mid-length over the last 0.5b) and less where the
    block ends flush with it (< 1). Finer and larger: benchmarks/fe_cylinder_end.py."""
    kw = dict(depth=10.0, width=10.0, run_on=10.0, refine=0.75)
    free = fr.cylinder_end_line_load(end_free=True, **kw)
    running = fr.cylinder_end_line_load(end_free=False, **kw)
    for res in (free, running):
        assert res.q_mid == pytest.approx(2157.69, rel=1e-4)
        assert res.peak_mid == pytest.approx(res.p0_hertz, rel=0.05)
        assert res.half_width_mid == pytest.approx(res.b_hertz, abs=0.25)
        assert res.reach < res.y[-1]
        assert res.total == pytest.approx(res.node_force.sum())
    for c in (0.05, 0.1, 0.25, 0.5):
        assert free.end_average(c) < 1.0
        assert running.end_average(c) > 1.5
    assert free.p_end[0] < free.peak_mid < running.p_end[0]


def test_two_body_line_contact_reduces_to_one_body_on_a_rigid_one():
    """(e) mixed_end_line_load (two elastic blocks, each's contact face condensed, the
    contact on the summed compliance) with body B all but rigid (E_b = 1e9 MPa) is
    cylinder_end_line_load's block A under a rigid cylinder: the same mesh on A, the end
    ratios within 1e-3 (B's compliance is 1e-4 of A's). With B elastic and running on past
    A's end, A's end carries more than where B ends flush with it, less than where both run
    on (a coarse, small mesh: 4b long, blocks 4b, elements b/6 across)."""
    kw = dict(length=4.0, depth=4.0, width=4.0, run_on=4.0, refine=0.75)
    one = fr.cylinder_end_line_load(E=98000.0, nu=0.35, **kw)
    two = fr.mixed_end_line_load(E_a=98000.0, nu_a=0.35, E_b=1e9, nu_b=0.3, **kw)
    assert two.dofs["A"] == one.n_dofs and two.dofs["B"] > two.dofs["A"]
    for c in (0.05, 0.1, 0.25, 0.5):
        assert two.end_average(c) == pytest.approx(one.end_average(c), rel=1e-3)
    mixed = fr.mixed_end_line_load(**kw)
    flush = fr.mixed_end_line_load(b_runs_on=False, **kw)
    assert flush.dofs["A"] == flush.dofs["B"] == mixed.dofs["A"]
    for res in (mixed, flush):
        assert res.peak_mid == pytest.approx(res.p0_hertz, rel=0.05)
        assert res.reach < res.y[-1]
    for c in (0.05, 0.1, 0.25, 0.5):
        assert flush.end_average(c) < mixed.end_average(c) < 1.5
