"""What every flank offers: points, normals, derivatives and curvature at any (u, v).

A flank is a parametric surface r(u, v) over a rectangular parameter domain, written once as
plain numpy code in `point`; evaluating it on jets (see `jet`) gives the exact first and
second derivatives. Differential geometry (normals, fundamental forms, principal curvatures)
is computed here once for all flanks. Units: mm, rad; curvature in 1/mm, positive where the
flank is convex (bulges out of the material), the convention of `analytic.hertz`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .jet import Jet


def cross(a, b):
    """a × b of vectors given by their components a[0], a[1], a[2] (triples of arrays, or
    arrays with the components on the first axis), as a triple."""
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    """a · b of vectors given by their components (see cross)."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


#: samples per parameter of the grid Flank.parameters_near starts from
GUESS_SAMPLES = 33

class Flank:
    """Base class of the exact flanks.

    Subclasses set `domain` = ((u0, u1), (v0, v1)), `edges` (names of the four sides of the
    domain, keys "u0", "u1", "v0", "v1") and `orientation` (+1 or -1, so that
    orientation·(r_u × r_v) points out of the material), and implement `point(u, v)`
    returning (x, y, z) with numpy functions only, so that it runs on jets as well.
    """

    domain: tuple[tuple[float, float], tuple[float, float]]
    edges: dict[str, str]
    orientation: float = 1.0
    #: whether its contact lines with a conjugate mate run straight across it (an involute
    #: helicoid's: a loaded contact's field can be laid along them; a worm set's curve)
    straight_contact_lines: bool = False

    def point(self, u, v):  # pragma: no cover - interface
        raise NotImplementedError

    def evaluate(self, u, v, order: int = 2) -> FlankSample:
        """Points and exact derivatives at arrays of (u, v) (broadcast together); with
        order 1 only the first derivatives (r_uu, r_uv, r_vv are None)."""
        U, V = Jet.variables(u, v, order)
        x, y, z = self.point(U, V)
        comps = [x if isinstance(x, Jet) else Jet(np.broadcast_to(x, U.f.shape)) for x in (x, y, z)]

        def stack(field):
            if order == 1 and field in ("uu", "uv", "vv"):
                return None
            return np.stack([np.broadcast_to(getattr(c, field), U.f.shape) for c in comps], axis=-1)

        return FlankSample(stack("f"), stack("u"), stack("v"), stack("uu"), stack("uv"),
                           stack("vv"), self.orientation)

    def tangents(self, u, v):
        """Point, r_u and r_v at arrays of (u, v) as triples of components (a constant one
        may stay 0-d): the hot path of every ray solve, with no stacking."""
        U, V = Jet.variables(u, v, order=1)
        parts = [c if isinstance(c, Jet) else Jet(c) for c in self.point(U, V)]
        return (tuple(c.f for c in parts), tuple(c.u for c in parts),
                tuple(c.v for c in parts))

    def parameters_near(self, points):
        """Starting parameters (u, v) for points near the flank (own frame): those of the
        nearest point of a GUESS_SAMPLES × GUESS_SAMPLES grid over the domain. Flanks with a
        closed-form guess override this."""
        from scipy.spatial import cKDTree

        if getattr(self, "_guess_tree", None) is None:
            u, v = self.grid(GUESS_SAMPLES, GUESS_SAMPLES)
            self._guess_tree = (cKDTree(np.stack(self.point(u, v), axis=-1).reshape(-1, 3)),
                                u.ravel(), v.ravel())
        tree, u, v = self._guess_tree
        _, index = tree.query(np.asarray(points).reshape(-1, 3), workers=-1)
        shape = np.shape(points)[:-1]
        return u[index].reshape(shape), v[index].reshape(shape)

    def breaks(self) -> FlankBreaks:
        """Where the flank's edges are broken and its modifications bend it (none here)."""
        return FlankBreaks()

    def profile_parameters(self, count: int) -> np.ndarray:
        """`count` values of u evenly over the domain: where a section (a solid's, a
        picture's) samples the profile."""
        (u0, u1), _ = self.domain
        return np.linspace(u0, u1, count)

    def grid(self, nu: int, nv: int):
        """A regular (nu × nv) grid over the domain: arrays u, v of shape (nu, nv)."""
        (u0, u1), (v0, v1) = self.domain
        return np.meshgrid(np.linspace(u0, u1, nu), np.linspace(v0, v1, nv), indexing="ij")


@dataclass(frozen=True)
class FlankBreaks:
    """Where a flank's edges are broken, in its own parameters: `rounding` (u where its tip
    edge's rounding or chamfer starts, and +1 or -1 toward the tip) or None; `chamfer` (v,
    mm from mid-face either way, where its face ends' chamfers' rounded edges start) or
    None; `profile_kinks` (u) and `lead_kinks` (v) where its modifications and broken edges
    bend it (relief starts, roundings' and chamfers' ends)."""

    rounding: tuple[float, float] | None = None
    chamfer: float | None = None
    profile_kinks: tuple[float, ...] = ()
    lead_kinks: tuple[float, ...] = ()


@dataclass(frozen=True)
class FlankSample:
    """A flank evaluated at arrays of parameters; vectors have a trailing axis of 3."""

    points: np.ndarray
    r_u: np.ndarray
    r_v: np.ndarray
    r_uu: np.ndarray
    r_uv: np.ndarray
    r_vv: np.ndarray
    orientation: float = 1.0

    @property
    def normals(self) -> np.ndarray:
        """Unit normals out of the material."""
        n = self.orientation * np.stack(cross(np.moveaxis(self.r_u, -1, 0),
                                              np.moveaxis(self.r_v, -1, 0)), axis=-1)
        return n / np.linalg.norm(n, axis=-1, keepdims=True)

    def fundamental_forms(self):
        """(E, F, G) and (L, M, N), with L = -r_uu·n etc. (convex positive)."""
        n = self.normals
        dot = lambda a, b: np.einsum("...i,...i->...", a, b)  # noqa: E731
        first = (dot(self.r_u, self.r_u), dot(self.r_u, self.r_v), dot(self.r_v, self.r_v))
        second = (-dot(self.r_uu, n), -dot(self.r_uv, n), -dot(self.r_vv, n))
        return first, second

    def principal_curvatures(self):
        """(k1, k2, d1, d2): principal curvatures k1 <= k2 (1/mm) and unit directions (3D)."""
        (E, F, G), (L, M, N) = self.fundamental_forms()
        det = E * G - F * F
        mean = (E * N - 2 * F * M + G * L) / (2 * det)
        gauss = (L * N - M * M) / det
        root = np.sqrt(np.maximum(mean * mean - gauss, 0.0))
        k1, k2 = mean - root, mean + root

        def direction(k):
            # (L - kE) du + (M - kF) dv = 0, or the second row when the first vanishes
            a, b = L - k * E, M - k * F
            c, d = M - k * F, N - k * G
            use_first = np.abs(a) + np.abs(b) >= np.abs(c) + np.abs(d)
            du = np.where(use_first, -b, -d)
            dv = np.where(use_first, a, c)
            degenerate = (np.abs(du) + np.abs(dv)) == 0  # umbilic: any direction
            du = np.where(degenerate, 1.0, du)
            vec = du[..., None] * self.r_u + dv[..., None] * self.r_v
            return vec / np.linalg.norm(vec, axis=-1, keepdims=True)

        return k1, k2, direction(k1), direction(k2)

    def normal_curvature(self, du, dv) -> np.ndarray:
        """Curvature (1/mm, convex positive) of the flank along the tangent du·r_u + dv·r_v."""
        (E, F, G), (L, M, N) = self.fundamental_forms()
        return (L * du * du + 2 * M * du * dv + N * dv * dv) / (E * du * du + 2 * F * du * dv + G * dv * dv)
