"""Stresses below a loaded contact: the elastic half-space under the solved pressure field,
at depth, and the largest principal shear (σ1 − σ3)/2 and von Mises stress with their
depths: what pitting and case crushing are judged by.

The stress at depth z is the pressure convolved with Boussinesq's stresses under a normal
point load (Johnson, *Contact Mechanics*, 1985, §3.2, turned to Cartesian axes),
integrated over each pressure cell (the cell's midpoint beyond NEAR of the longer cell
side, a Gauss-Legendre rule on the cells nearer: GAUSS points per axis or more, at most
half the depth apart), and summed by FFT over grids zero-padded to
twice their size: a linear, not a periodic, convolution (Liu, Wang & Liu, *Wear* 243
(2000) 101-111, "DC-FFT"), in single precision (twice as fast; 1e-6 of the peak).
Frictionless: the pressure's tractions are normal. The depths are scanned at DEPTHS times
the contact's equivalent half-width (its area over twice its length); each peak is the
vertex of the parabola through three depths close about the scan's estimate.
Sign: compression negative. Units: mm, MPa.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

#: cells (each way) within which a cell's point-load stress is integrated by Gauss-Legendre
NEAR = 4
#: points of that rule along each axis
GAUSS = 6
#: depths scanned, as multiples of the contact's equivalent half-width (area / 2·length):
#: Hertz's largest shear lies at 0.786 b in a line contact, 0.61 of it in a circular one
DEPTHS = (0.12, 0.35, 0.6, 0.85, 1.15, 1.6)
#: each peak is then refined by the parabola through the depths REFINE_STEP times the
#: equivalent half-width either side of the scan's estimate
REFINE_STEP = 0.03


@dataclass(frozen=True)
class SubsurfacePeak:
    """The largest principal shear and von Mises stress below a contact (MPa) and their
    depths (mm)."""

    shear_MPa: float
    shear_depth_mm: float
    von_mises_MPa: float
    von_mises_depth_mm: float


def point_load_stresses(x, y, z, nu: float) -> np.ndarray:
    """Stresses (6, ...): σxx, σyy, σzz, σxy, σxz, σyz (MPa) at (x, y, z) (mm, z > 0 into
    the body) under a unit normal point load (1 N, compressive) at the origin: Boussinesq
    (Johnson §3.2), with (1 - z/ρ)/r² written as 1/(ρ(ρ + z)) and (σ_r - σ_θ)/r²
    in a form that holds on the axis."""
    dtype = np.result_type(x, y, z, 1.0)         # float32 in, float32 out; else float64
    x, y, z = np.broadcast_arrays(*(np.asarray(v, dtype) for v in (x, y, z)))
    rho = np.sqrt(x * x + y * y + z * z)
    c = 1.0 / (2.0 * math.pi)
    over = 1.0 / rho                        # 1/ρ, 1/ρ³ and 1/ρ⁵ by products (no pow)
    over3 = over * over * over
    over5 = over3 * over * over
    closer = 1.0 / (rho + z)
    inner = over * closer
    theta = -c * (1.0 - 2.0 * nu) * (inner - z * over3)
    spread = c * ((1.0 - 2.0 * nu) * (2.0 * rho + z) * over3 * closer * closer
                  - 3.0 * z * over5)
    shear = -3.0 * c * z * z * over5
    return np.stack([theta + spread * x * x, theta + spread * y * y,
                     z * shear, spread * x * y, shear * x, shear * y])


def _influence(shape: tuple[int, int], nx: int, ny: int, dx: float, dy: float, z: float,
               nu: float) -> np.ndarray:
    """The stresses (6, *shape) at depth z under a unit pressure on one dx × dy cell of an
    nx × ny grid, at every offset of it, in FFT (wrap-around) order on a padded grid of
    `shape` (at least 2n - 1 each way: a linear convolution).

    The offsets a linear convolution of n cells reads are -(n - 1)...n - 1 each way; the
    stresses are evaluated on the offsets >= 0 and mirrored (σxy and σxz odd in x, σxy and
    σyz odd in y), the offsets no cell reads left zero."""
    X, Y = np.meshgrid((np.arange(nx) * dx).astype(np.float32),
                       (np.arange(ny) * dy).astype(np.float32), indexing="ij")
    quadrant = point_load_stresses(X, Y, np.float32(z), nu) * np.float32(dx * dy)
    out = np.zeros((6,) + tuple(shape), np.float32)
    out[:, :nx, :ny] = quadrant
    odd_x = np.array([1, 1, 1, -1, -1, 1], np.float32)[:, None, None]
    odd_y = np.array([1, 1, 1, -1, 1, -1], np.float32)[:, None, None]
    if nx > 1:
        out[:, shape[0] - nx + 1:, :ny] = odd_x * quadrant[:, :0:-1]
    if ny > 1:
        out[:, :, shape[1] - ny + 1:] = odd_y * out[:, :, ny - 1:0:-1]
    # the cells within NEAR of the longer cell side each way are integrated by Gauss-Legendre
    # with nodes at most half the depth apart along each axis (a long cell at a shallow
    # depth is no point load: a line contact's shear 2.5 times McEwen's on cells 3 b long);
    # those of the shorter side beyond NEAR of its own cells, at their midline across it
    nodes = [max(GAUSS, math.ceil(2.0 * d / z)) for d in (dx, dy)]
    inner = [np.arange(-k, k + 1) for k in (min(NEAR, nx - 1), min(NEAR, ny - 1))]
    _integrated(out, inner[0], inner[1], dx, dy, z, nu, nodes)
    longest = max(dx, dy)
    for axis, (d, n) in enumerate(((dx, nx), (dy, ny))):
        reach, k = min(math.ceil(NEAR * longest / d - 1e-9), n - 1), inner[axis][-1]
        if reach > k:
            beyond = np.concatenate([np.arange(-reach, -k), np.arange(k + 1, reach + 1)])
            offsets = [beyond, inner[1]] if axis == 0 else [inner[0], beyond]
            _integrated(out, *offsets, dx, dy, z, nu,
                        [1, nodes[1]] if axis == 0 else [nodes[0], 1])
    return out


@functools.lru_cache(maxsize=64)
def _gauss_legendre(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre nodes and weights of n points on [-1, 1] (numpy's, kept: a loaded
    cycle asks for the same few rules thousands of times)."""
    return np.polynomial.legendre.leggauss(n)


def _integrated(out: np.ndarray, a: np.ndarray, b: np.ndarray, dx: float, dy: float, z: float,
                nu: float, nodes: list[int]) -> None:
    """The stresses at offsets a·dx, b·dy (into `out`, FFT order) under a unit pressure on
    a dx × dy cell, integrated over it by Gauss-Legendre rules of `nodes` points per axis."""
    (ux, wx), (uy, wy) = (_gauss_legendre(n) for n in nodes)
    A, B, U, V = np.meshgrid(a * dx, b * dy, 0.5 * dx * ux, 0.5 * dy * uy, indexing="ij")
    w = np.outer(wx, wy) * (0.25 * dx * dy)
    out[:, (a % out.shape[1])[:, None], (b % out.shape[2])[None, :]] = (
        point_load_stresses(A - U, B - V, z, nu) * w).sum(axis=(3, 4))


def stresses(pressure: np.ndarray, dx: float, dy: float, z: float, nu: float,
             transformed=None) -> np.ndarray:
    """The stresses (6, nx, ny) at depth z (mm) below each cell centre of a pressure grid
    (MPa, cells dx × dy mm): σxx, σyy, σzz, σxy, σxz, σyz. `transformed`: the pressure's
    padded transform (_transformed), where the caller has it."""
    from scipy import fft

    p = np.asarray(pressure, float)
    nx, ny = p.shape
    shape, load = transformed or _transformed(p)
    product = fft.rfft2(_influence(shape, nx, ny, dx, dy, z, nu), workers=1) * load
    # back along the complex axis first, then only the grid's rows along the real one
    rows = fft.ifft(product, axis=1, overwrite_x=True, workers=1)[:, :nx]
    return fft.irfft(rows, n=shape[1], axis=2, workers=1)[..., :ny].astype(float)


def _transformed(p: np.ndarray) -> tuple[tuple[int, int], np.ndarray]:
    """The padded grid's shape (fast FFT lengths of at least 2n - 1) and the pressure's
    transform on it."""
    from scipy import fft

    shape = tuple(fft.next_fast_len(2 * n - 1, real=True) for n in p.shape)
    return shape, fft.rfft2(p.astype(np.float32), s=shape, workers=1)


def von_mises(s: np.ndarray) -> np.ndarray:
    xx, yy, zz, xy, xz, yz = s
    return np.sqrt(0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2)
                   + 3.0 * (xy * xy + xz * xz + yz * yz))


def principal_shear(s: np.ndarray) -> np.ndarray:
    """(σ1 - σ3)/2 of stresses (6, ...): sqrt(J2)·cos θ with θ the Lode angle,
    sin 3θ = -(3√3/2) J3 / J2^(3/2), |θ| <= π/6 (the principal stresses from the
    deviator's invariants)."""
    xx, yy, zz, xy, xz, yz = s
    mean = (xx + yy + zz) / 3.0
    a, b, c = xx - mean, yy - mean, zz - mean
    J2 = 0.5 * (a * a + b * b + c * c) + xy * xy + xz * xz + yz * yz
    J3 = a * b * c + 2.0 * xy * yz * xz - a * yz * yz - b * xz * xz - c * xy * xy
    ratio = np.divide(J3, J2 ** 1.5, out=np.zeros_like(J2), where=J2 > 0.0)
    theta = np.arcsin(np.clip(-1.5 * math.sqrt(3.0) * ratio, -1.0, 1.0)) / 3.0
    return np.sqrt(J2) * np.cos(theta)


def _largest(s: np.ndarray) -> tuple[float, float]:
    """The largest principal shear and von Mises stress of stresses (6, nx, ny); the shear
    is computed only where von Mises allows it to be the largest (σ_vm/2 <= τ <= σ_vm/√3)."""
    vm = von_mises(s)
    top = float(vm.max())
    where = vm >= math.sqrt(3.0) * 0.5 * top * (1.0 - 1e-6)
    return float(principal_shear(s[:, where]).max()), top


def peak(pressure: np.ndarray, dx: float, dy: float, nu: float) -> SubsurfacePeak | None:
    """The largest principal shear and von Mises stress below a pressure grid (MPa, cells
    dx × dy mm) of a body of Poisson's ratio nu, and their depths; None without pressure.
    The grid is cut to the cells in contact first; each peak's depth and value are the
    vertex of the parabola through three depths close about the scan's estimate."""
    p = np.asarray(pressure, float)
    on = p > 0.0
    if not on.any():
        return None
    rows, cols = np.flatnonzero(on.any(axis=1)), np.flatnonzero(on.any(axis=0))
    p = p[rows[0]:rows[-1] + 1, cols[0]:cols[-1] + 1]
    length = max(p.shape[0] * dx, p.shape[1] * dy)
    half_width = float(on.sum() * dx * dy / (2.0 * length))
    transformed = _transformed(p)
    found: dict[float, tuple[float, float]] = {}

    def at(z: float) -> tuple[float, float]:
        if z not in found:
            found[z] = _largest(stresses(p, dx, dy, z, nu, transformed))
        return found[z]

    # no shallower than half the shorter cell side (the pressure steps across it)
    for z in np.unique(np.maximum(np.array(DEPTHS) * half_width, 0.5 * min(dx, dy))):
        at(float(z))
    out = []
    for column in (0, 1):
        depths = sorted(found)
        k = max(range(len(depths)), key=lambda i: found[depths[i]][column])
        z = depths[k]
        if 0 < k < len(depths) - 1:
            three = np.array(depths[k - 1:k + 2])
            z = _parabola_peak(three, np.array([found[d][column] for d in three]))
        h = min(REFINE_STEP * half_width, 0.5 * z)
        three = np.array([z - h, z, z + h])
        values = np.array([at(float(d))[column] for d in three])
        vertex = _parabola_peak(three, values)
        out += [float(np.polyval(np.polyfit(three, values, 2), vertex)), vertex]
    return SubsurfacePeak(*out)


def _parabola_peak(z: np.ndarray, f: np.ndarray) -> float:
    """The depth of the peak of the parabola through three points, clipped to their span."""
    a, b, _ = np.linalg.solve(np.vander(z, 3), f)
    if a >= 0.0:
        return float(z[1])
    return float(np.clip(-b / (2.0 * a), z[0], z[2]))
