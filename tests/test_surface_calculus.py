"""The jet arithmetic and the shared differential geometry, on surfaces with known answers."""

import numpy as np
import pytest

from toothcontact.surfaces.base import Flank
from toothcontact.surfaces.jet import Jet


class Torus(Flank):
    """Torus with tube radius a around a circle of radius c; curvatures 1/a and
    cos(u)/(c + a cos u) (convex positive, outward normal)."""

    def __init__(self, c=10.0, a=3.0):
        self.c, self.a = c, a
        self.domain = ((-3.0, 3.0), (0.0, 6.0))
        self.edges = {"u0": "a", "u1": "b", "v0": "c", "v1": "d"}
        self.orientation = -1.0  # r_u × r_v points into the tube

    def point(self, u, v):
        ring = self.c + self.a * np.cos(u)
        return ring * np.cos(v), ring * np.sin(v), self.a * np.sin(u)


def test_torus_curvatures_and_normals():
    torus = Torus()
    u, v = torus.grid(13, 7)
    s = torus.evaluate(u, v)
    k1, k2, d1, d2 = s.principal_curvatures()
    ring = np.cos(u) / (torus.c + torus.a * np.cos(u))
    expected = np.sort(np.stack([np.full_like(u, 1 / torus.a), ring]), axis=0)
    np.testing.assert_allclose(k1, expected[0], rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(k2, expected[1], rtol=1e-12, atol=1e-14)
    radial = np.stack([np.cos(u) * np.cos(v), np.cos(u) * np.sin(v), np.sin(u)], axis=-1)
    np.testing.assert_allclose(np.abs(np.einsum("...i,...i", s.normals, radial)), 1.0, rtol=1e-12)
    np.testing.assert_allclose(np.einsum("...i,...i", d1, d2), 0.0, atol=1e-9)


@pytest.mark.parametrize("name,fn,exact", [
    ("sin(u v)", lambda u, v: np.sin(u * v),
     lambda u, v: (np.sin(u * v), v * np.cos(u * v), u * np.cos(u * v), -v * v * np.sin(u * v),
                   np.cos(u * v) - u * v * np.sin(u * v), -u * u * np.sin(u * v))),
    ("atan2(v, u)/sqrt(u)", lambda u, v: np.arctan2(v, u) / np.sqrt(u), None),
    ("u**2.5 exp(v) - log(u) tan(v)", lambda u, v: u**2.5 * np.exp(v) - np.log(u) * np.tan(v), None),
])
def test_jet_derivatives(name, fn, exact):
    u0, v0 = np.array([0.7, 1.3]), np.array([0.4, -0.9])
    U, V = Jet.variables(u0, v0)
    j = fn(U, V)
    if exact is not None:
        for got, want in zip((j.f, j.u, j.v, j.uu, j.uv, j.vv), exact(u0, v0)):
            np.testing.assert_allclose(got, want, rtol=1e-13)
    # independent check: central differences of the plain function
    h = 1e-4
    f = lambda a, b: fn(a, b)  # noqa: E731
    np.testing.assert_allclose(j.u, (f(u0 + h, v0) - f(u0 - h, v0)) / (2 * h), rtol=1e-7)
    np.testing.assert_allclose(j.vv, (f(u0, v0 + h) - 2 * f(u0, v0) + f(u0, v0 - h)) / h**2, rtol=1e-5)
    np.testing.assert_allclose(j.uv, (f(u0 + h, v0 + h) - f(u0 + h, v0 - h) - f(u0 - h, v0 + h)
                                      + f(u0 - h, v0 - h)) / (4 * h * h), rtol=1e-5)
