"""The elastic half-space's influence on a contact grid, and the free end faces that make a
body a quarter-space there: u = K * p for the contact solver (contact.pressure).

Two elastic half-spaces pressed together by a pressure p on a grid in their common tangent
plane displace their surfaces together by u = K * p with K = 1/(π E*) · (integral of 1/r
over one cell) (Johnson eq 3.25), 1/E* = (1-ν1²)/E1 + (1-ν2²)/E2 (Johnson eq 4.22):
- Influence coefficients of uniform pressure on a rectangular cell: Love (1929), as given by
  Johnson, *Contact Mechanics* (1985) eq (3.25), written with asinh terms
  (:func:`rectangle_displacement`).
- u = K * p by DC-FFT: Liu, Wang & Liu, Wear 243 (2000) 101-111: the coefficients laid
  out on 2N points per axis in wrap-around order, p zero-padded to 2N, so that the cyclic
  convolution is the linear, non-periodic one. The kernel's spectrum is computed once per
  grid (:func:`influence_operator`, cached by shape, dx, dy).
- A free end face crossing the grid (:class:`FreeEnd`, :class:`ObliqueFreeEnd`): the
  quarter-space's surface displacement is the half-space's plus φ times that of the
  pressure mirrored about the end (Guilbault 2011; φ from 3D finite elements here).

Grid convention as contact.pressure's: x along axis 0, y along axis 1. Units: mm, N, MPa.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import scipy.fft as sfft

# --------------------------------------------------------------------------------------------
# influence coefficients


def _antiderivative(s: np.ndarray, t: np.ndarray) -> np.ndarray:
    """F(s, t) = s·asinh(t/|s|) + t·asinh(s/|t|) (mm), with ∂²F/∂s∂t = 1/sqrt(s² + t²).

    Johnson eq (3.25)'s s·ln(t + r) + t·ln(s + r) differs from it by terms in s or t alone,
    which cancel in the double difference; the asinh form has no cancellation where
    t + r is small."""
    with np.errstate(divide="ignore", invalid="ignore"):
        a = np.where(s != 0.0, s * np.arcsinh(t / np.abs(s)), 0.0)
        b = np.where(t != 0.0, t * np.arcsinh(s / np.abs(t)), 0.0)
    return a + b


def _depth_antiderivative(s: np.ndarray, t: np.ndarray, depth: float, nu: float) -> np.ndarray:
    """H(s, t) (mm) with ∂²H/∂s∂t = d²/ρ³ + 2(1-ν)/ρ, ρ² = s² + t² + d² (d = depth > 0,
    mm): Boussinesq's displacement at depth d (Johnson eq 3.21b) integrated over a
    rectangle by the double difference of H at its corners, from ∫∫ d²/ρ³ = d·atan(st/(dρ))
    and ∫∫ 1/ρ = s·asinh(t/sqrt(s² + d²)) + t·asinh(s/sqrt(t² + d²)) - d·atan(st/(dρ))."""
    rho = np.sqrt(s * s + t * t + depth * depth)
    return (2.0 * (1.0 - nu) * (s * np.arcsinh(t / np.hypot(s, depth))
                                + t * np.arcsinh(s / np.hypot(t, depth)))
            - (1.0 - 2.0 * nu) * depth * np.arctan(s * t / (depth * rho)))


def rectangle_displacement(x, y, half_x: float, half_y: float, E_star: float = 1.0):
    """Normal surface displacement (mm) at (x, y) (mm) of the two bodies together under a
    uniform pressure of 1 MPa on the rectangle |x'| <= half_x, |y'| <= half_y (mm), composite
    modulus E_star (MPa).

    Love (1929); Johnson, *Contact Mechanics* (1985) eq (3.25), with (1-ν²)/E of one body
    replaced by 1/E* for both: u = [F(x+a, y+b) - F(x+a, y-b) - F(x-a, y+b)
    + F(x-a, y-b)] / (π E*), F(s, t) = s·asinh(t/|s|) + t·asinh(s/|t|)."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    a, b = float(half_x), float(half_y)
    total = (_antiderivative(x + a, y + b) - _antiderivative(x + a, y - b)
             - _antiderivative(x - a, y + b) + _antiderivative(x - a, y - b))
    return total / (math.pi * E_star)


class InfluenceOperator:
    """u = K * p on an n0 × n1 grid of dx × dy cells (mm), for E* = 1 MPa (divide u by E*).

    DC-FFT (Liu, Wang & Liu 2000): K[k, l], the displacement at cell (k, l) under 1 MPa on
    cell (0, 0), -n < k < n, is laid out on L >= 2n points per axis in wrap-around order
    (the kernel of a grid of L/2 cells, L even and fast for the FFT); p is zero-padded to L,
    and the cyclic convolution of the two then equals the linear one on the grid. K is even
    in both axes, so its spectrum is real; it is stored as such, in float64 and (on first
    use) float32. The transforms are pruned: the real one runs first, along the longer
    axis, on the grid's own lines only; the complex one along the shorter axis; the lines
    of the result thrown away are not transformed back.

    reference: for bodies of finite size, ((depth, E, nu), ...) per body: the displacement
    is then the compression between the surface and the point at that depth (mm) below the
    load in each body (E in MPa), not the surface's sinking relative to infinity: K less
    E_star times the bodies' Boussinesq displacement at their depths (Johnson eq 3.21b,
    u_z = F/(4πG)·[d²/ρ³ + 2(1-ν)/ρ], ρ² = r² + d², integrated over each loaded cell as
    the surface term is: :func:`_depth_antiderivative`; taken at the cell's centre instead,
    a cell large against the depth, 7.7 × 33.5 mm at 4 mm, made the kernel negative
    definite). A line contact's approach relative to infinity grows without bound
    with the contact's length; measured to a depth it does not (Weber's contact flattening
    of a tooth measures it to the tooth's centre line).
    """

    def __init__(self, shape: tuple[int, int], dx: float, dy: float,
                 reference: tuple = (), E_star: float = 1.0, quadrant: np.ndarray | None = None):
        n0, n1 = (int(s) for s in shape)
        self.shape, self.dx, self.dy = (n0, n1), float(dx), float(dy)
        self.reference, self.E_star = reference, E_star
        # the real transform runs along the longer axis (on the grid's short rows only),
        # the complex one along the shorter: 20-40 % faster on a long contact's grid; on one
        # thread (scipy's default): these transforms are too small for threads to pay (the
        # bundled spur case 3.85 s single-threaded, 4.64 s on both cores)
        self._real_axis = 0 if n0 >= n1 else 1
        #: the DC-FFT circulant's size (2n per axis, made fast)
        self.padded = self._lengths(2)
        #: the preconditioner's circulant size (n per axis, made fast)
        self.wrapped = self._lengths(1)
        need = tuple(n // 2 + 1 for n in self.padded)
        if quadrant is None or quadrant.shape[0] < need[0] or quadrant.shape[1] < need[1]:
            quadrant = self.quadrant(need[0] - 1, need[1] - 1, dx, dy, reference, E_star)
        #: the coefficients of offsets k, l >= 0 (at least the padded circulant's half; a
        #: part of the grid takes its own from them)
        self._quadrant = quadrant
        self._spectrum = {np.float64: self._kernel_spectrum(self.padded)}
        self._inverse: dict = {}
        self._parts: dict = {}

    def part(self, shape: tuple[int, int]) -> InfluenceOperator:
        """The operator of a part of this grid, `shape` cells (its coefficients taken from
        this operator's; kept for the next call with the same shape)."""
        shape = (int(shape[0]), int(shape[1]))
        if shape not in self._parts:
            if len(self._parts) >= 32:
                self._parts.clear()
            self._parts[shape] = InfluenceOperator(shape, self.dx, self.dy, self.reference,
                                                   self.E_star, self._quadrant)
        return self._parts[shape]

    def _lengths(self, factor: int) -> tuple[int, int]:
        """A circulant's size: factor·n per axis, or the next even length the FFT factors
        fast (a length with a large prime factor, 2·964 = 8·241, transforms 4-5 times
        slower)."""
        return tuple(_even_fast_length(factor * n, axis == self._real_axis)
                     for axis, n in enumerate(self.shape))

    def _kernel_spectrum(self, lengths: tuple[int, int]) -> np.ndarray:
        """The spectrum of the kernel laid out on the `lengths` circulant as for a grid of
        half its size, in the transforms' layout (the real transform's axis halved): the
        kernel is even, so its spectrum is real and is the type-I DCT of its quadrant (the
        DFT of an even sequence of 2N points, for frequencies 0..N), mirrored along the
        complex transform's axis."""
        spectrum = sfft.dctn(self._quadrant[:lengths[0] // 2 + 1, :lengths[1] // 2 + 1],
                             type=1)
        other = 1 - self._real_axis
        mirror = np.flip(spectrum, axis=other).take(range(1, spectrum.shape[other] - 1),
                                                    axis=other)
        return np.concatenate([spectrum, mirror], axis=other)

    @staticmethod
    def quadrant(n0: int, n1: int, dx: float, dy: float, reference: tuple = (),
                 E_star: float = 1.0) -> np.ndarray:
        """Influence coefficients (mm per MPa, E* = 1 MPa) of the offsets k·dx, l·dy,
        0 <= k <= n0, 0 <= l <= n1 ((n0 + 1) × (n1 + 1)).

        F is evaluated once on the cell corners (k - 1/2)·dx, (l - 1/2)·dy; the double
        difference of neighbours is Johnson eq (3.25) for each cell. `reference`: see the
        class."""
        xs = (np.arange(n0 + 2) - 0.5) * dx
        ys = (np.arange(n1 + 2) - 0.5) * dy
        F = _antiderivative(xs[:, None], ys[None, :])
        quadrant = np.diff(np.diff(F, axis=0), axis=1) / math.pi    # (n0 + 1, n1 + 1)
        for depth, E, nu in reference:
            H = _depth_antiderivative(xs[:, None], ys[None, :], depth, nu)
            G = E / (2.0 * (1.0 + nu))
            quadrant = quadrant - E_star / (4.0 * math.pi * G) * np.diff(np.diff(H, axis=0),
                                                                       axis=1)
        return quadrant

    @staticmethod
    def coefficients(n0: int, n1: int, dx: float, dy: float, reference: tuple = (),
                     E_star: float = 1.0) -> np.ndarray:
        """Influence coefficients (mm per MPa, E* = 1 MPa) on the 2n0 × 2n1 wrap-around grid:
        index k <= n0 is the offset k·dx, index k > n0 the offset (k - 2n0)·dx (the
        quadrant mirrored: K is even in both axes)."""
        quadrant = InfluenceOperator.quadrant(n0, n1, dx, dy, reference, E_star)
        half = np.concatenate([quadrant, quadrant[-2:0:-1]], axis=0)
        return np.concatenate([half, half[:, -2:0:-1]], axis=1)

    def _spectra(self, single: bool, inverse: bool):
        """(dtype, spectrum) in float32 or float64: the DC-FFT circulant's, or with inverse
        the preconditioner's (1/spectrum of the `wrapped` circulant: positive for this
        kernel, the guard only keeps it finite); each computed on first use."""
        key = np.float32 if single else np.float64
        store = self._inverse if inverse else self._spectrum
        if inverse and np.float64 not in store:
            spectrum = self._kernel_spectrum(self.wrapped)
            store[np.float64] = 1.0 / np.maximum(spectrum, 1e-12 * spectrum.max())
        if key not in store:
            store[key] = store[np.float64].astype(np.float32)
        return key, store[key]

    def _convolve(self, p, spectrum, dtype, lengths) -> np.ndarray:
        n0, n1 = self.shape
        real, other = self._real_axis, 1 - self._real_axis
        P = sfft.rfft(np.asarray(p, dtype=dtype), n=lengths[real], axis=real)
        P = sfft.fft(P, n=lengths[other], axis=other, overwrite_x=True)
        P *= spectrum
        U = sfft.ifft(P, axis=other, overwrite_x=True)
        U = U[:n0] if other == 0 else U[:, :n1]
        return sfft.irfft(U, n=lengths[real], axis=real)[:n0, :n1]

    def __call__(self, p: np.ndarray, single: bool = False) -> np.ndarray:
        """Displacement (mm, for E* = 1 MPa) under the pressure p (MPa) on the grid; single:
        the transforms in float32 (relative error about 1e-7)."""
        dtype, spectrum = self._spectra(single, inverse=False)
        return self._convolve(p, spectrum, dtype, self.padded)

    def approximate_inverse(self, u: np.ndarray, single: bool = False) -> np.ndarray:
        """Pressure (MPa, E* = 1 MPa) whose periodic displacement on the grid is u: the
        inverse of the kernel's circulant of the grid's own size (`wrapped`). An
        approximate inverse of K, used as the preconditioner (a circulant preconditioner of
        the Toeplitz matrix, Strang 1986; with FFTs, Zhao, Vollebregt & Oosterlee 2014)."""
        dtype, inverse = self._spectra(single, inverse=True)
        return self._convolve(u, inverse, dtype, self.wrapped)


def _even_fast_length(n: int, real: bool) -> int:
    """The least even length >= n that the FFT factors into small primes."""
    length = sfft.next_fast_len(n, real=real)
    while length % 2:
        length = sfft.next_fast_len(length + 1, real=real)
    return length


@functools.lru_cache(maxsize=16)
def influence_operator(shape: tuple[int, int], dx: float, dy: float, reference: tuple = (),
                       E_star: float = 1.0) -> InfluenceOperator:
    """The grid's :class:`InfluenceOperator`, built once per (shape, dx, dy, reference,
    E_star) and kept (the last 16; ``influence_operator.cache_clear()`` forgets them)."""
    return InfluenceOperator(shape, dx, dy, reference, E_star)


# --------------------------------------------------------------------------------------------
# free end faces


#: the mirror-pressure factor φ of a free end face (Guilbault 2011) by Poisson's ratio: the
#: quarter-space's surface displacement is the half-space's plus φ times the half-space
#: displacement of the pressure mirrored about the end face. φ = 1 is a plain mirror (the
#: end face a frictionless symmetry plane: no shear on it, but the normal stress a rigid
#: smooth wall would hold); freeing that stress makes the end more compliant still, φ > 1.
#: Derived here, not taken from the literature: the least-squares fit of the mirror term
#: (with a constant, which a contact's rigid approach takes up) to 3D finite-element
#: surface displacements of an elastic block with a free end under a square patch 0.5 to 4
#: patch widths from the end, against the same block running on (tests/fe_reference.py,
#: benchmarks/fe_quarter_space.py: residual 3-5 % of the free end's excess; measured from
#: infinity instead the fit gives 1.60, 1.74, 1.90, 2.11, with residual 5-7 %)
FREE_END_FACTORS = ((0.25, 1.29), (0.30, 1.42), (0.35, 1.57), (0.40, 1.75))


def free_end_factor(nu: float) -> float:
    """φ (FREE_END_FACTORS) for Poisson's ratio nu, linear between the table's ratios and
    held at its ends."""
    ratios, factors = zip(*FREE_END_FACTORS)
    return float(np.interp(nu, ratios, factors))


def end_taper(depth: np.ndarray) -> np.ndarray:
    """A free end's mirror weight at `depth` from the end in reaches: 1 to half the reach,
    a cosine down to 0 at the reach."""
    d = np.asarray(depth, float)
    return np.where(d <= 0.5, 1.0, np.where(d < 1.0, 0.5 + 0.5 * np.cos(2.0 * math.pi * (d - 0.5)),
                                             0.0))


@dataclass(frozen=True)
class FreeEnd:
    """A free end face of one of the two bodies, crossing a grid along `axis` (0: its x):
    there the body is a quarter-space, not a half-space that runs on.

    Its displacement gains φ times the half-space displacement, at the same point, of the
    pressure mirrored about the end face: Hetényi's overlapping half-spaces (J. Appl. Mech.
    37 (1970) 70-76: a mirror image cancels the shear the half-space leaves on the end
    plane) condensed into one mirror term with a factor, as Guilbault's fast quarter-space
    correction does (J. Tribology 133 (2011) 031402). The mirror term is a Hankel operator
    along `axis` (it depends on x_i + x_j): symmetric, computed by one convolution of the
    mirrored strip.

    index: along `axis`, the first cell of the body's material (side "low": the end lies
        before it) or one past its last (side "high");
    weight: φ times the body's share of the composite compliance (φ for two bodies ending
        flush, each its own share);
    reach_mm: the mirror acts between cells within reach_mm of the end, both tapered to zero
        over its outer half (with a reference depth the kernel fades within a few depths;
        on half-spaces the reach should span the contact)."""

    axis: int
    index: int
    side: str
    weight: float
    reach_mm: float

    def shifted(self, rows: slice, cols: slice) -> FreeEnd:
        """The same end on a part of the grid starting at (rows.start, cols.start)."""
        start = (rows, cols)[self.axis].start or 0
        return FreeEnd(self.axis, self.index - start, self.side, self.weight, self.reach_mm)

    def taper(self, count: int, step: float) -> np.ndarray:
        """Weights of the `count` cells inward from the end (step mm each): see end_taper."""
        return end_taper((np.arange(count) + 0.5) * step / self.reach_mm)

    def add_mirror(self, u: np.ndarray, p: np.ndarray, op: InfluenceOperator,
                   spacing: tuple[float, float], single: bool) -> None:
        """Adds the mirror term of the pressure p (MPa, the grid's shape) to the displacement
        u (mm for E* = 1 MPa, the grid's shape; in place), `op` the grid's half-space."""
        step = spacing[self.axis]
        width = max(int(math.ceil(self.reach_mm / step)), 1)
        if self.axis == 1:
            u, p = u.T, p.T
        n = p.shape[0]
        # cells [lo, hi) within the reach, inward from the end; their depths from it
        if self.side == "low":
            lo, hi = max(self.index, 0), min(self.index + width, n)
            depth = np.arange(lo, hi) - self.index
        else:
            lo, hi = max(self.index - width, 0), min(self.index, n)
            depth = self.index - 1 - np.arange(lo, hi)
        if hi <= lo:
            return
        taper = self.taper(width, step)[depth][:, None]
        strip = p[lo:hi] * taper
        if not strip.any():
            return
        # the strip and its mirror on one line of cells: the mirror of cell i is
        # 2·index - 1 - i; `reach` cells from the end to the strip's far side, each way
        reach = int(depth.max()) + 1
        line = np.zeros((2 * reach, p.shape[1]))
        if self.side == "low":
            line[reach - 1 - depth] = strip            # mirrors, before the end
            take = reach + depth
        else:
            line[reach + depth] = strip                # mirrors, past the end
            take = reach - 1 - depth
        part = op.part(line.shape if self.axis == 0 else line.T.shape)
        image = part(line, single) if self.axis == 0 else part(line.T, single).T
        u[lo:hi] += self.weight * taper * image[take]


@dataclass(frozen=True)
class ObliqueFreeEnd:
    """A free end face of one of the bodies crossing a grid obliquely (a helical flank's
    face end on a field laid along its helix): the line d = 0, d = a·i + b·j + c (mm) the
    distance from the end into the body's material at cell (i, j) (a/dx, b/dy the unit
    normal into the material).

    The same mirror term as FreeEnd's, φ times the half-space displacement of the pressure
    mirrored about the end: the image of cell j at R x_j = x_j - 2·d_j·n lies off the cell
    centres, so its tapered pressure is spread onto the four cells around the image by
    bilinear weights (which keep its load and its centre), the half-space displacement of
    those images taken by one convolution on the box holding them and the band, and read
    at the band's cells. The exact operator is symmetric (|R x_i - x_j|² = |x_i - x_j|² +
    4·d_i·d_j); the spreading approximates it to second order in the cell size.

    weight, reach_mm: as FreeEnd's (the mirror acts on and from the cells with
    0 < d < reach_mm, tapered by end_taper)."""

    a: float
    b: float
    c: float
    weight: float
    reach_mm: float

    def shifted(self, rows: slice, cols: slice) -> ObliqueFreeEnd:
        """The same end on a part of the grid starting at (rows.start, cols.start)."""
        i0, j0 = rows.start or 0, cols.start or 0
        return ObliqueFreeEnd(self.a, self.b, self.c + self.a * i0 + self.b * j0,
                              self.weight, self.reach_mm)

    def add_mirror(self, u: np.ndarray, p: np.ndarray, op: InfluenceOperator,
                   spacing: tuple[float, float], single: bool) -> None:
        """Adds the mirror term of the pressure p (MPa, the grid's shape) to the displacement
        u (mm for E* = 1 MPa, the grid's shape; in place), `op` the grid's half-space."""
        dx, dy = spacing
        n0, n1 = p.shape
        I, J = np.meshgrid(np.arange(n0), np.arange(n1), indexing="ij")
        d = self.a * I + self.b * J + self.c
        band = (d > 0.0) & (d < self.reach_mm)
        if not band.any():
            return
        i, j, d = I[band], J[band], d[band]
        taper = end_taper(d / self.reach_mm)
        load = p[band] * taper
        if not load.any():
            return
        # the images (in cell units), and the box that holds them and the band
        si, sj = i - 2.0 * d * self.a / dx ** 2, j - 2.0 * d * self.b / dy ** 2
        fi, fj = np.floor(si).astype(int), np.floor(sj).astype(int)
        wi, wj = si - fi, sj - fj
        lo = (min(fi.min(), i.min()), min(fj.min(), j.min()))
        hi = (max(fi.max() + 2, i.max() + 1), max(fj.max() + 2, j.max() + 1))
        canvas = np.zeros((hi[0] - lo[0], hi[1] - lo[1]))
        for di, dj, w in ((0, 0, (1 - wi) * (1 - wj)), (1, 0, wi * (1 - wj)),
                          (0, 1, (1 - wi) * wj), (1, 1, wi * wj)):
            np.add.at(canvas, (fi + di - lo[0], fj + dj - lo[1]), load * w)
        image = op.part(canvas.shape)(canvas, single)
        u[band] += self.weight * taper * image[i - lo[0], j - lo[1]]
