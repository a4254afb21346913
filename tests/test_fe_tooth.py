"""The 3D finite-element tooth (tests/fe_tooth.py) against closed forms and a direct solve, and
the tooth compliance model (contact.compliance) against it on the 20-tooth pinion of
cases/spur_crowned_20_60.toml (issue 27 item 5c). Coarse meshes: under a minute in all; the
finer comparison, its mesh convergence and the proposed correction are
benchmarks/fe_tooth_face.py (benchmarks/fe_tooth_face.json).

Status of the model against the FE (benchmark, pinion at r = 30 mm): the beam's slice
compliance was 20-25 % above FE, a point load in mid-face deflected the model's tooth
2.0-2.6x as far and FE's deflection spread over a decay length about twice Vlasov's
coupling length; the model is corrected to it (compliance.SLICE_FACTOR,
COUPLING_PER_ROOT_CHORD), and the tests below check the corrected model to 10 %: c, the
mid-face point load, the coupling length, how c grows with the load's height, and (since
the coupling fades at the free ends over Reissner's layer, structure.end_layer) the
face end: FE's end-over-mid ratio 2.3-2.4 against the line's 2.19 (1.87 before)."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("skfem")

import fe_tooth as ft  # noqa: E402  (tests/ is on sys.path)

E, NU = ft.E_STEEL, ft.NU_STEEL
E_PLANE, G = E / (1 - NU ** 2), E / (2 * (1 + NU))


def test_a_plane_strain_strip_deflects_as_timoshenkos_cantilever():
    """A strip 20 × 2 mm held at one end, a shear line load on the other (plane strain,
    quadratic triangles of 0.5 mm): tip deflection PL³/(3E'I) + PL/(κGt), κ = 5/6, within
    1 % (the fully held end is a little stiffer than the beam's: 0.45 % here)."""
    S = ft.rectangle_section(20.0, 2.0, 0.5)
    r = ft.plane_strain(S)
    exact = 20.0 ** 3 / (3 * E_PLANE * 2.0 ** 3 / 12) + 20.0 / (5 / 6 * G * 2.0)
    assert r["centre"][0] == pytest.approx(exact, rel=0.01)


def test_a_square_beam_deflects_as_timoshenkos_cantilever_in_3d():
    """The strip extruded to a 2 × 2 mm beam (quadratic tetrahedra, the symmetric half about
    mid-width, free sides), 1 N on its end face: tip deflection PL³/(3EI) + PL/(κGA) within
    1.5 % (0.8 % here) at mid-width and at the free side alike."""
    S = ft.rectangle_section(20.0, 2.0, 0.5)
    T = ft.Tooth3D(S, ft.graded(0.0, 1.0, [], 0.5))
    u = T.factors["sym"].solve(0.5 * T.patch_load(0, 0.0, 1.0))
    w = T.normal_at(u, S.site.centre)
    exact = 20.0 ** 3 / (3 * E * 2.0 ** 4 / 12) + 20.0 / (5 / 6 * G * 4.0)
    assert w[0] == pytest.approx(exact, rel=0.015)
    assert w[-1] == pytest.approx(exact, rel=0.015)


def mirrored(half, plane: int):
    """The whole-width mesh: the half mesh (z >= 0, its first `plane` vertices on z = 0) and
    its mirror image, the same tetrahedra mirrored (the extrusion's prism split is not
    mirror-symmetric, so extruding the whole width would be another mesh)."""
    from skfem import MeshTet

    n = half.p.shape[1]
    image = half.p[:, plane:] * np.array([[1.0], [1.0], [-1.0]])
    index = np.where(half.t < plane, half.t, half.t - plane + n)
    return MeshTet(np.hstack([half.p, image]), np.hstack([half.t, index[[0, 2, 1, 3]]]))


def test_the_two_halves_add_up_to_the_whole_face_and_the_factor_to_a_direct_solve():
    """A short block (section 6 × 3 mm, 6 mm wide) loaded on a patch at one end of its
    width: the symmetric and antisymmetric half models (multifrontal Cholesky) together
    against the whole width solved directly by scikit-fem/SciPy (SuperLU), to 1e-7 of the
    largest deflection, on both halves of the width."""
    from skfem import (Basis, ElementTetP2, ElementVector, FacetBasis, Functional, LinearForm,
                       asm, condense, solve)
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    S = ft.rectangle_section(6.0, 3.0, 0.75)
    z = ft.graded(0.0, 3.0, [(2.0, 3.0, 0.5)], 1.0)
    T = ft.Tooth3D(S, z)
    unit = T.patch_load(0, 2.0, 3.0)
    u = T.factors["sym"].solve(0.5 * unit)
    a = T.factors["anti"].solve(0.5 * unit)
    half = T.normal_at(np.column_stack([u, a]), S.site.centre)
    mine = np.concatenate([(half[:, 0] - half[:, 1])[::-1][:-1], half[:, 0] + half[:, 1]])

    zz = np.concatenate([-z[::-1][:-1], z])
    mesh = mirrored(ft.extrude(S.p, S.t, z), S.p.shape[1])
    e = ElementVector(ElementTetP2())
    basis = Basis(mesh, e, intorder=2)
    K = asm(linear_elasticity(*lame_parameters(E, NU)), basis)
    held = basis.get_dofs(mesh.facets_satisfying(lambda x: x[0] < 1e-9)).all()
    patch = mesh.facets_satisfying(lambda x: (x[0] > 6.0 - 1e-9) & (x[2] > 2.0 - 1e-9))
    fb = FacetBasis(mesh, e, facets=patch)
    area = asm(Functional(lambda w: 1.0 + 0.0 * w.x[0]), fb)
    f = asm(LinearForm(lambda v, w: -v[1] / area), fb)
    full = solve(*condense(K, f, D=held))
    pts = np.vstack([np.full(len(zz), 6.0 - 1e-7), np.zeros(len(zz)),
                     np.clip(zz, -3.0 + 1e-7, 3.0 - 1e-7)])
    direct = -(basis.probes(pts) @ full).reshape(3, -1)[1]
    assert np.max(np.abs(mine - direct)) < 1e-7 * np.max(np.abs(direct))
    assert mine[-1] > 2.0 * mine[0] > 0                 # the loaded end moves most


def test_a_twisted_whole_face_factor_is_a_direct_solve():
    """The helical tooth's tooling: a block (section 6 × 3 mm) over the whole width
    z = -3..3 mm, each plane turned by 0.05 rad/mm (Tooth3D's twist: no mid-face symmetry,
    one factor), factorised on 2 BLAS threads for the fronts over 300 rows (Factor's
    threaded path, uncalibrated),
    against scikit-fem/SciPy's direct solve of the same mesh, to 1e-8."""
    from skfem import condense, solve

    S = ft.rectangle_section(6.0, 3.0, 0.75)
    z = np.linspace(-3.0, 3.0, 11)
    T = ft.Tooth3D(S, z, twist=0.05, factorise=False)
    assert list(T._free) == ["full"]
    factor = ft.Factor(T.K, T._free["full"], T.basis.doflocs, threads=2, big=300,
                       calibrate=False)
    assert factor.threads_used == 2
    unit = T.patch_load(0, 1.0, 3.0)
    mine = factor.solve(np.column_stack([unit] * 9))[:, 4]
    held = np.setdiff1d(np.arange(T.dofs), T._free["full"])
    direct = solve(*condense(T.K, unit, D=held))
    assert np.max(np.abs(mine - direct)) < 1e-8 * np.max(np.abs(direct))
    # the sections turn: a point of plane z sits at angle 0.05·z
    k = S.p.shape[1] * 10 + int(np.argmax(S.p[0]))
    assert math.atan2(T.mesh.p[1, k], T.mesh.p[0, k]) == pytest.approx(
        0.15 + math.atan2(S.p[1, k % S.p.shape[1]], S.p[0, k % S.p.shape[1]]), abs=1e-12)


def test_the_half_space_compressions_agree_with_each_other():
    """Weber's flattening to a depth: the plane-strain strip (2D closed form) against a long
    rectangle (Love's rectangle and Boussinesq at depth, 3D) times its length, within 1.5 %;
    the mirrored patch beside a free end adds less than the patch itself."""
    strip = ft.halfspace_strip(0.3, 2.3, E, NU)
    assert ft.halfspace_patch(0.3, 200.0, 2.3, E, NU) * 200.0 == pytest.approx(strip, rel=0.015)
    own = ft.halfspace_patch(0.3, 1.0, 2.3, E, NU)
    mirror = ft.halfspace_patch(0.3, 1.0, 2.3, E, NU, offset=1.0)
    assert 0 < mirror < own


@pytest.fixture(scope="module")
def pinion():
    return ft.case_gears()[0]


@pytest.fixture(scope="module")
def study(pinion):
    """The pinion at r = 30 mm on a coarse mesh (about 60,000 dofs per half)."""
    return ft.face_study(pinion, radii=(30.0,), h_patch=0.3, h_tooth=1.5, h_far=6.0,
                         growth=0.45, hz_fine=0.5, hz_coarse=4.0, fit_from=(3.0,),
                         log=lambda *_: None)["sites"][0]


def test_the_slice_compliance_grows_with_the_load_height_as_in_plane_strain_fe(pinion):
    """What the model gets right: c(31.5 mm)/c(28.5 mm) on the pinion's flank, the model
    (1.99) against the whole gear in plane strain (2.05), within 10 %; and FE/c is nearly
    the same at all three heights (the beam's 0.79-0.83, within 0.05 of each other), so one
    factor corrects it."""
    from toothcontact.contact.compliance import ToothCompliance

    radii = (28.5, 30.0, 31.5)
    S = ft.section_mesh(pinion, radii, 0.1, 0.5, 3.0, growth=0.3)
    fe = np.array(ft.plane_strain(S)["centre"])
    model = ToothCompliance(pinion, E, NU).at(np.array(radii))[0]
    assert (model[2] / model[0]) / (fe[2] / fe[0]) == pytest.approx(1.0, abs=0.10)
    assert np.ptp(fe / model) < 0.05


def test_the_corrected_slice_compliance_is_the_fe_tooths_within_10_percent(study):
    """(1) Uniform line load: FE (3D, mid-face, at the centre line) against the model's c,
    which is the beam's times SLICE_FACTOR (0.815, fitted on the medium mesh of the
    benchmark): within 10 % (measured 0.969 on this coarse mesh, which is stiffer); the
    plane-strain section within 4 % of the 3D mid-face. Before the correction FE/c was
    0.78-0.83."""
    fe, model = study["fe"], study["model"]
    assert fe["c_3d_centre"] / model["c"] == pytest.approx(1.0, abs=0.10)
    assert fe["c_2d_centre"] == pytest.approx(fe["c_3d_centre"], rel=0.04)


def test_a_mid_face_point_load_spreads_along_the_face_as_in_fe(study):
    """(3), (4): under a mid-face patch the model's deflection is the FE's within 10 %
    (measured +1.5 %; 2.0-2.6x before the correction), its coupling length
    (COUPLING_PER_ROOT_CHORD × S_f = 5.77 mm) the one that matches FE's point-over-uniform
    deflection within 10 % (measured 5.67 mm), and FE's decay length (cosh fit from 3 mm:
    4.82 mm on this mesh, 5.4-5.9 in the benchmark) within 25 % of it. Vlasov's length,
    2.86 mm, was half of these."""
    fe, model, fit = study["fe"], study["model"], study["fits"]["centre_3"]
    lam = model["coupling_length"]
    assert model["mid"] / fe["mid_centre"] == pytest.approx(1.0, abs=0.10)
    assert fe["lambda_match_centre"] == pytest.approx(lam, rel=0.10)
    assert fit["L"] == pytest.approx(lam, rel=0.25)
    profile = np.array(study["profiles"]["centre"]["mid"])
    mid = len(profile) // 2
    assert np.all(np.diff(profile[mid:]) < 0)           # falls from mid-face to the end


def test_a_patch_at_the_face_end_deflects_the_model_as_fe_within_10_percent(study):
    """(2): a patch touching the face end deflects 2.3-2.4x the mid-face one in FE (centre
    line; benchmark; 2.35 here). The model's line with free ends w' = 0 gave 1.87 (a
    Pasternak line cannot exceed 2), 0.81 of FE's deflection at the end; with its coupling
    fading over Reissner's free-edge layer (structure.end_layer, 1.47 mm here) it gives
    2.19, 0.95 of FE's (measured), within 10 % (the bands: FE in [2.1, 2.7], the model's
    ratio in [2.0, 2.4]). The layer leaves a uniform load's deflection uniform (the next
    test)."""
    fe, model = study["fe"], study["model"]
    assert 2.1 < fe["ratio_centre"] < 2.7
    assert 2.0 < model["ratio"] < 2.4
    assert model["end"] / fe["end_centre"] == pytest.approx(1.0, abs=0.10)


def test_under_a_uniform_load_the_face_ends_deflect_as_mid_face_in_fe_and_model(study):
    """Under a line load uniform along the face, FE's tooth deflects at its face ends 0.97-
    0.99 of mid-face (benchmark, three teeth: the free end is not softer under a spread
    load, only under a concentrated one), the model's Pasternak line exactly as mid-face
    (w' = 0 everywhere, however its coupling fades at the ends): within 5 % (measured 0.988
    here). So the face end's softness under a point load (the test above) is not a softer
    end for the line loads a pattern spreads along the face; an end factor fitted to the
    point load would soften these by a third, the fading coupling leaves them as they are."""
    z = np.array(study["z"])
    line = np.array(study["profiles"]["centre"]["line"])
    mid = line[np.argmin(np.abs(z))]
    assert 0.95 < line[-1] / mid < 1.0 and 0.95 < line[0] / mid < 1.0
