"""Normal contact of two elastic bodies on a grid: the pressure under a gap field.

Two elastic half-spaces are pressed together by a normal load W; the initial separation (gap)
h between them is known on a uniform rectangular grid in the common tangent plane. The
pressure p and the rigid-body approach delta satisfy (Polonsky & Keer 1999)

    h - delta + u = 0  where p > 0,    h - delta + u >= 0  where p = 0,
    p >= 0,    sum(p)·dx·dy = W,

u being the elastic displacement of both surfaces together, u = K * p with
K = 1/(π E*) · (integral of 1/r over one cell) (Johnson eq 3.25) and
1/E* = (1-ν1²)/E1 + (1-ν2²)/E2 (Johnson eq 4.22). For a Hertz gap delta is Hertz's approach
(analytic.hertz.hertz_point).

Grid convention: ``gap[i, j]`` is the gap at x = x0 + i·dx, y = y0 + j·dy: **x along axis 0,
y along axis 1** (``np.meshgrid(x, y, indexing="ij")``); each value stands for the dx × dy
cell around its point. ``mask[i, j]`` False marks a cell without material (beyond a face end,
off the flank): no pressure there, and its gap is not used.

Method:
- Influence coefficients of uniform pressure on a rectangular cell: Love (1929), as given by
  Johnson, *Contact Mechanics* (1985) eq (3.25), written with asinh terms
  (:func:`rectangle_displacement`).
- u = K * p by DC-FFT: Liu, Wang & Liu, Wear 243 (2000) 101-111: the coefficients laid
  out on 2N points per axis in wrap-around order, p zero-padded to 2N, so that the cyclic
  convolution is the linear, non-periodic one. The kernel's spectrum is computed
  once per grid (:func:`influence_operator`, cached by shape, dx, dy).
- Solver: the constrained conjugate gradient method of Polonsky & Keer, Wear 231 (1999)
  206-219, with the load constraint, preconditioned on the contact set by the inverse of
  the kernel's periodic circulant of the grid's own size (an FFT approximate inverse of
  the Toeplitz influence matrix, as in Zhao, Vollebregt & Oosterlee, Numer. Linear
  Algebra Appl. 21 (2014) 256-274; its use inside the constrained iteration is ours),
  started from the Hertz ellipse fitted to the gap (:func:`hertz_start`), or from the
  rigid interference where that ellipse lies mostly off the material
  (:func:`interference_start`). It iterates on a window of the grid about the cells in
  contact and penetrating, and checks the whole grid after each pass (a window too small
  is widened).

Units: mm, N, MPa.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import scipy.fft as sfft

from ..analytic.hertz import hertz_point

__all__ = [
    "ContactSolution",
    "EdgeLoad",
    "Grid",
    "GridEdgeError",
    "InfluenceOperator",
    "hertz_start",
    "interference_start",
    "influence_operator",
    "rectangle_displacement",
    "solve_contact",
    "solve_shared",
]


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
# results


@dataclass(frozen=True)
class EdgeLoad:
    """Load at one edge of the material (a face end), in the strip of cells of each grid line
    along `axis` from the edge inward over `width_mm` (a partial cell by its covered part).

    edge_pressure_MPa: the pressure averaged across the strip, on the grid line along the
        edge where that average is largest (MPa; converges as the grid is refined);
    raw_peak_MPa: the largest pressure in the cells next to the edge (MPa; grows as the grid
        is refined: the pressure at a sharp end is singular);
    load_N, load_fraction: the load within the strip (N), and its share of the total;
    line_index: index along the other axis of the line with edge_pressure_MPa;
    side: "low" (edge at the lowest index along `axis`) or "high".
    """

    axis: int
    side: str
    width_mm: float
    edge_pressure_MPa: float
    raw_peak_MPa: float
    load_N: float
    load_fraction: float
    line_index: int


@dataclass(frozen=True)
class ContactSolution:
    """A solved contact on the grid (x along axis 0, y along axis 1). Arrays are read-only.

    pressure_MPa: pressure per cell (0 outside the contact and the mask);
    displacement_mm: elastic displacement u of the two surfaces together;
    separation_mm: loaded gap h - approach + u on material cells (0 in contact to the
        solver's tolerance, >= 0 elsewhere; 0 where there is no material);
    area_mm2: number of cells with p > 0 times dx·dy; mean_pressure_MPa = load / area;
    approach_mm: rigid-body approach delta (Hertz's approach for a Hertz gap);
    iterations: conjugate gradient steps;
    relative_error: max(rms of separation in contact, largest penetration outside it)
        / largest displacement, computed afresh in float64 at the end.
    """

    pressure_MPa: np.ndarray
    displacement_mm: np.ndarray
    separation_mm: np.ndarray
    mask: np.ndarray
    dx_mm: float
    dy_mm: float
    load_N: float
    E_star_MPa: float
    area_mm2: float
    peak_pressure_MPa: float
    mean_pressure_MPa: float
    approach_mm: float
    iterations: int
    relative_error: float

    def edge_loads(self, axis: int = 0, width_mm: float = 0.1) -> tuple[EdgeLoad, EdgeLoad]:
        """Load at the two edges of the mask along `axis` (0: x), in strips `width_mm` (mm)
        wide inside the material: (low, high). For face ends, x runs along the face.

        In each grid line along `axis` the low edge is the start of its first material cell
        and the high edge the end of its last; lines without material are skipped, and the
        strip holds only material cells. The strip is `width_mm` deep across the edge: where
        the edge runs obliquely to the grid (a helical flank's tip, a tilted face end) the
        line's strip is longer by sqrt(1 + slope²), the slope of the edge against the
        line's normal fitted over seven neighbouring lines; an edge within 18 deg of the
        lines (slope above 3) is left to the other axis. The edge pressure is the mean over
        the strip and `width_mm` along the edge (the lines within width/2 of the line it is
        reported at): a square patch, so that a staircase edge's cell-to-cell spikes do not
        decide it."""
        if axis not in (0, 1):
            raise ValueError(f"axis: {axis!r} must be 0 (x) or 1 (y)")
        width = _positive("width_mm", width_mm, "mm")
        p, mask = self.pressure_MPa, self.mask
        step = self.dx_mm if axis == 0 else self.dy_mm
        if axis == 1:
            p, mask = p.T, mask.T
        across = self.dy_mm if axis == 0 else self.dx_mm
        lines = np.arange(p.shape[1])
        edges = []
        for side in ("low", "high"):
            ps, ms = (p, mask) if side == "low" else (p[::-1], mask[::-1])
            has = ms.any(axis=0)
            first = np.argmax(ms, axis=0)                                # per line
            slope = _edge_slope(first, has) * step / across
            stretch = np.where(np.abs(slope) <= 3.0, np.sqrt(1.0 + slope**2), 0.0)
            offset = np.arange(ms.shape[0])[:, None] - first[None, :]   # cells from the edge
            covered = (np.clip(width * stretch / step - offset, 0.0, 1.0) * (offset >= 0)
                       * ms * has)
            strip_width = covered.sum(axis=0) * step                     # mm, per line
            line_load = (covered * ps).sum(axis=0) * step                # MPa·mm per line
            # and as deep along the edge: the mean over lines within width/2 of each other
            window = np.ones(2 * min(int(0.5 * width / across), (len(line_load) - 1) // 2) + 1)
            patch_load = np.convolve(line_load, window, mode="same")
            patch_width = np.convolve(strip_width, window, mode="same")
            averaged = np.divide(patch_load, patch_width, out=np.zeros_like(line_load),
                                 where=(patch_width > 0) & (strip_width > 0))
            line = int(np.argmax(averaged))
            load = float(line_load.sum()) * (self.dy_mm if axis == 0 else self.dx_mm)
            edge_cells = ps[first, lines][has]
            edges.append(EdgeLoad(
                axis=axis, side=side, width_mm=width,
                edge_pressure_MPa=float(averaged[line]),
                raw_peak_MPa=float(edge_cells.max()) if edge_cells.size else 0.0,
                load_N=load, load_fraction=load / self.load_N, line_index=line))
        return edges[0], edges[1]


def _edge_slope(first: np.ndarray, has: np.ndarray, reach: int = 3) -> np.ndarray:
    """d(first)/d(line) (cells per line) of an edge's position per line, by a least-squares
    line over the 2·reach + 1 neighbouring lines that have material (0 where fewer than
    three do): the window sums of the normal equations by one convolution each."""
    i = np.arange(len(first), dtype=float)
    weight = has.astype(float)
    y = np.where(has, first, 0.0).astype(float)
    window = np.ones(2 * reach + 1)

    def total(values):
        return np.convolve(values, window)[reach:reach + len(values)]

    n, sx, sxx, sy, sxy = (total(v) for v in (weight, weight * i, weight * i * i, y, y * i))
    det = n * sxx - sx * sx
    with np.errstate(invalid="ignore", divide="ignore"):
        slope = (n * sxy - sx * sy) / det
    return np.where(has & (n >= 3) & (det > 0), slope, 0.0)


# --------------------------------------------------------------------------------------------
# input checks


def _positive(name: str, value, unit: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name}: {value!r} must be a number > 0 {unit}") from None
    if not (math.isfinite(v) and v > 0):
        raise ValueError(f"{name}: {value!r} must be a finite number > 0 {unit}")
    return v


def _check_grid(gap, dx, dy, mask):
    """(gap with 0 off the material, dx, dy, mask) of one grid, checked."""
    dx, dy = _positive("dx_mm", dx, "mm"), _positive("dy_mm", dy, "mm")
    try:
        h = np.array(gap, dtype=float)
    except (TypeError, ValueError):
        raise ValueError("gap_mm: must be a 2-D array of numbers (mm)") from None
    if h.ndim != 2 or min(h.shape) < 3:
        raise ValueError(f"gap_mm: shape {h.shape} must be a 2-D grid of at least 3 × 3 cells")
    if mask is None:
        m = np.ones(h.shape, dtype=bool)
    else:
        m = np.asarray(mask)
        if m.shape != h.shape:
            raise ValueError(f"mask: shape {m.shape} must equal the gap's shape {h.shape}")
        if m.dtype != bool:
            if not np.all((m == 0) | (m == 1)):
                raise ValueError("mask: values must be True (material) or False (none)")
            m = m.astype(bool)
    if not m.any():
        raise ValueError("mask: no cell has material (all False); at least one must be True")
    bad = m & ~np.isfinite(h)
    if bad.any():
        i, j = np.argwhere(bad)[0]
        raise ValueError(f"gap_mm: {h[i, j]} at cell ({i}, {j}) must be finite where mask is "
                         "True")
    return np.where(m, h, 0.0), dx, dy, m.copy()


# --------------------------------------------------------------------------------------------
# warm start


def hertz_start(h, dx: float, dy: float, mask, load: float, E_star: float):
    """Initial pressure (MPa) on the grid: the Hertz ellipse of the quadratic fitted to the gap.

    The gap on material cells near its minimum is fitted by least squares with
    c0 + c1 x + c2 y + c3 x² + c4 xy + c5 y²; the eigenvalues of the quadratic part are A <= B
    and analytic.hertz.hertz_point gives a, b and p0 for the load (Johnson eqs 4.36-4.39);
    the fit is repeated over the rigid interference at Hertz's approach. The start is
    p0·sqrt(1 - ξ²/a² - η²/b²) about the fitted minimum in the ellipse's axes, on material
    cells. None when the fit is no bowl (or its cells lie on a line), or when the material
    cells under the ellipse carry less than half of its load: the fitted bowl then lies
    mostly beyond the material or the grid (a contact cut by an edge, a gap with no bowl
    near its minimum), and so does not resemble the contact (see :func:`interference_start`)."""
    i0, j0 = np.unravel_index(np.argmin(np.where(mask, h, np.inf)), h.shape)
    x = ((np.arange(h.shape[0]) - i0) * dx)[:, None]
    y = ((np.arange(h.shape[1]) - j0) * dy)[None, :]
    rel = h - h[i0, j0]
    level = float(np.quantile(rel[mask], min(1.0, max(0.02, 12.0 / mask.sum()))))
    contact = None
    for _ in range(2):
        select = mask & (rel <= level)
        if select.sum() < 6:
            return None
        xs, ys = np.broadcast_to(x, h.shape)[select], np.broadcast_to(y, h.shape)[select]
        M = np.stack([np.ones_like(xs), xs, ys, xs * xs, xs * ys, ys * ys], axis=1)
        scale = np.abs(M).max(axis=0)
        scale[scale == 0] = 1.0
        M /= scale                          # normal equations, einsum: no BLAS threads
        try:
            c = np.linalg.solve(np.einsum("ki,kj->ij", M, M), np.einsum("ki,k->i", M, rel[select]))
        except np.linalg.LinAlgError:        # the cells lie on a line: no bowl to fit
            return None
        c /= scale
        H = np.array([[c[3], 0.5 * c[4]], [0.5 * c[4], c[5]]])
        evals, evecs = np.linalg.eigh(H)
        if not (evals[0] > 0 and evals[1] / evals[0] < 1e8):
            return None
        centre = np.linalg.solve(2.0 * H, -c[1:3])
        contact = hertz_point(evals[0], evals[1], load, 1.0 / E_star)
        level = max(level, contact.approach)   # the rigid interference holds the ellipse
    ex, ey = evecs[:, 0]                      # direction of A: the long semi-axis a
    xi = (x - centre[0]) * ex + (y - centre[1]) * ey
    eta = (y - centre[1]) * ex - (x - centre[0]) * ey
    inside = 1.0 - (xi / contact.a) ** 2 - (eta / contact.b) ** 2
    p = contact.p0 * np.sqrt(np.clip(inside, 0.0, None)) * mask
    return p if p.sum() * dx * dy >= 0.5 * load else None


def interference_start(h, dx: float, dy: float, mask, load: float, E_star: float):
    """Initial pressure (MPa) on the grid from the rigid interference, for any gap (a cut
    ellipse, a line contact, several patches): p = sqrt(L - (h - h_min)) on the material
    cells with h - h_min < L (the caller scales it to the load).

    The level L follows from the Hertz sphere (Johnson 1985, eqs 4.22-4.23: a² = R·delta,
    W = 4 E* a³ / (3R)): the contact's edge lies where the gap is delta/2, so with L = delta/2
    and the contact area A(L) = pi·a², W = (8/3)·E*·L·sqrt(A(L)/pi), and p0·sqrt(1 - r²/a²)
    is p0·sqrt(1 - (h - h_min)/L). Here A(L) is the area of the material cells with
    h - h_min <= L, and L solves W = (8/3)·E*·L·sqrt(A(L)/pi) (increasing in L; linear
    between the sorted gap values). None when even the whole material falls short of the
    load by this estimate (a gap flat on all of it, as under a flat punch)."""
    levels = np.sort(h[mask])
    lowest = levels[0]
    levels -= lowest
    carried = (8.0 / 3.0) * E_star * levels * np.sqrt(
        np.arange(1, levels.size + 1) * (dx * dy / math.pi))
    k = int(np.searchsorted(carried, load))           # carried[k - 1] < load <= carried[k]
    if k == levels.size:
        return None
    level = levels[k - 1] + (levels[k] - levels[k - 1]) * (
        (load - carried[k - 1]) / (carried[k] - carried[k - 1]))
    return np.sqrt(np.clip(level - (h - lowest), 0.0, None)) * mask


# --------------------------------------------------------------------------------------------
# solver


class GridEdgeError(ValueError):
    """The contact reaches the edge of one grid or more on material: the gap does not close
    within them under the load. `reached`: per such grid (its index in a shared solve),
    whether it reaches the edges across x (the grid's first or last row) and those across y
    (its first or last column)."""

    def __init__(self, message: str, reached: dict[int, tuple[bool, bool]]):
        super().__init__(message)
        self.reached = reached


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


@dataclass(frozen=True)
class Grid:
    """One gap field of a shared solve (see :func:`solve_shared`): the gap (mm; x along axis
    0 in steps dx_mm, y along axis 1 in steps dy_mm), the material mask (None: everywhere),
    a further linear displacement `structure` p (MPa) -> u (mm) of its bodies (the teeth's
    bending: a contact.compliance.StructureOperator, called on the grid and on a part of it
    by its `window(rows, cols)`), the depths its compression is measured to
    (`reference`, see InfluenceOperator), and the free end faces of its bodies that cross
    it (`free_ends`, :class:`FreeEnd`: there a body is a quarter-space)."""

    gap_mm: np.ndarray
    dx_mm: float
    dy_mm: float
    mask: np.ndarray | None = None
    structure: object = None
    reference: tuple = ()
    free_ends: tuple = ()


class _Checked(NamedTuple):
    """One grid of a shared solve as checked: gap h (0 off the material), cell sides, mask."""

    h: np.ndarray
    dx: float
    dy: float
    m: np.ndarray
    structure: object
    reference: tuple
    free_ends: tuple = ()


class _System:
    """The grids of a shared solve as one flattened vector (the grids' cells one after the
    other): the influence is block diagonal, each grid's own half-space (DC-FFT) plus its
    `structure`; the preconditioner each grid's periodic circulant's inverse. Loads are
    p·cell, cell the area of a grid's cells (mm²)."""

    def __init__(self, grids: list[_Checked], E_star: float, single: bool, ops=None):
        self.grids, self.E_star = grids, E_star
        self.compliance, self.single = 1.0 / E_star, single
        self.h = np.concatenate([g.h.ravel() for g in grids])
        self.m = np.concatenate([g.m.ravel() for g in grids])
        self.shapes = [g.h.shape for g in grids]
        bounds = np.cumsum([0] + [g.h.size for g in grids])
        self.slices = [slice(int(a), int(b)) for a, b in zip(bounds[:-1], bounds[1:])]
        #: each grid's half-space (`ops`: given for windows, taken from their grids')
        self.ops = ops if ops is not None else [
            influence_operator(tuple(int(k) for k in g.h.shape), g.dx, g.dy, g.reference,
                               E_star if g.reference else 1.0) for g in grids]
        self.structures = [g.structure for g in grids]
        areas = [g.dx * g.dy for g in grids]
        #: the cells' areas: one number for one grid (or equal cells), else per cell
        self.cells = (areas[0] if len(set(areas)) == 1 else
                      np.concatenate([np.full(g.h.size, a) for g, a in zip(grids, areas)]))
        self._buffer = np.zeros(self.h.size)

    def cell(self, where: np.ndarray):
        """The areas (mm²) of the cells `where` (one number where all cells are alike)."""
        return self.cells if np.isscalar(self.cells) else self.cells[where]

    def load(self, p: np.ndarray, where: np.ndarray) -> float:
        """The load (N) of the pressures p (MPa) on the cells `where`."""
        if np.isscalar(self.cells):
            return self.cells * float(p[where].sum())
        return _dot(self.cells[where], p[where])

    def _blocks(self, values: np.ndarray, where: np.ndarray | None):
        """Each grid's values on the grid (from the flat `values` on `where`, or from the
        whole flat vector with where None), or None for a grid without any."""
        if where is None:
            flat = values
        else:
            flat = self._buffer
            flat.fill(0.0)
            flat[where] = values
        for s, shape in zip(self.slices, self.shapes):
            block = flat[s]
            yield s, (block.reshape(shape) if block.any() else None)

    def displacement(self, values: np.ndarray, where: np.ndarray | None = None,
                     single: bool | None = None) -> np.ndarray:
        """The displacement (mm, flat) under the pressures `values` (MPa) on the cells
        `where` (all cells if None); single: the transforms in float32 (default the
        system's)."""
        single = self.single if single is None else single
        out = np.zeros(self.h.size)
        for (s, q), op, structure, grid in zip(self._blocks(values, where), self.ops,
                                               self.structures, self.grids):
            if q is not None:
                u = op(q, single)
                for end in grid.free_ends:
                    end.add_mirror(u, q, op, (grid.dx, grid.dy), single)
                u = u.ravel() * self.compliance
                out[s] = u if structure is None else u + structure(q).ravel()
        return out

    def precondition(self, values: np.ndarray, where: np.ndarray) -> np.ndarray:
        """The preconditioned residual on `where`, as loads: each grid's approximate inverse
        of the residual `values` (mm), times its cells' area."""
        out = np.zeros(self.h.size)
        for (s, e), op in zip(self._blocks(values, where), self.ops):
            if e is not None:
                out[s] = op.approximate_inverse(e, self.single).ravel()
        return out[where] * self.cell(where)

    def error(self, p: np.ndarray, u: np.ndarray) -> tuple[float, float, np.ndarray]:
        """(relative gap error, approach, busy) of the state p, u (see :func:`_state`); busy:
        the cells in contact or penetrating (flat bool)."""
        contact = np.flatnonzero(p > 0.0)
        approach, _, join, error = _state(self.h + u, contact, self.m)
        busy = np.zeros(self.h.size, bool)
        busy[contact] = busy[join] = True
        return error / float(u[self.m].max()), approach, busy

    def windowed(self, windows: list) -> tuple[_System, np.ndarray]:
        """The system on the windows ((rows, cols) slices per grid, None to leave a grid
        out), and the flat indices of its cells in this system's vector."""
        grids, ops, inside = [], [], []
        for g, op, s, shape, window in zip(self.grids, self.ops, self.slices, self.shapes,
                                           windows):
            if window is None:
                continue
            rows, cols = window
            grids.append(_Checked(g.h[rows, cols], g.dx, g.dy, g.m[rows, cols],
                                  None if g.structure is None else g.structure.window(rows, cols),
                                  g.reference,
                                  tuple(end.shifted(rows, cols) for end in g.free_ends)))
            ops.append(op.part(grids[-1].h.shape))
            inside.append(np.arange(s.start, s.stop).reshape(shape)[rows, cols].ravel())
        return _System(grids, self.E_star, self.single, ops), np.concatenate(inside)


#: a shared solve iterates on a window of each grid: the box about its cells in contact and
#: penetrating, enlarged by WINDOW_CELLS cells each way; the whole grids are checked after
#: every pass and a window widened where they need it (a line contact's field is several
#: contact widths wide: the transforms shrink with it). Two cells: the bundled spur case's
#: full-grid solves took 20 % less time than with 3 cells plus a tenth of the box's sides,
#: in as many passes (one per solve)
WINDOW_CELLS = 2


def _window(busy: np.ndarray, old: tuple[slice, slice] | None) -> tuple[slice, slice] | None:
    """The window (rows, cols) of a grid about its `busy` cells (2-D bool), holding the
    previous window `old` (None: none); None where neither has a cell. It holds all the
    grid's pressure (the busy cells hold the contact): the pass starts from p and u as
    they are."""
    if not busy.any():
        return old
    bounds = []
    for axis, n in enumerate(busy.shape):
        cells = np.flatnonzero(busy.any(axis=1 - axis))
        low = max(int(cells[0]) - WINDOW_CELLS, 0)
        high = min(int(cells[-1]) + 1 + WINDOW_CELLS, n)
        if old is not None:
            low, high = min(low, old[axis].start), max(high, old[axis].stop)
        bounds.append(slice(low, high))
    return tuple(bounds)


def _dot(a: np.ndarray, b: np.ndarray) -> float:
    """a·b by numpy's pairwise sum, not BLAS: BLAS dot spins its threads, slow on a shared
    machine."""
    return float(np.multiply(a, b).sum())


def _state(g, contact, material):
    """The flattened state's (approach, residual on contact, penetrating cells, gap error
    (mm)), from the loaded gap g = h + u, the indices `contact` of the cells with p > 0 and
    the material mask.

    The approach is the mean of g over the contact (the rigid-body approach that the load
    fixes); the residual is g - approach there; a material cell outside the contact
    penetrates where g < approach. The gap error is max(rms of the residual, largest
    penetration); over the largest displacement of the material it is the relative gap error
    of ContactSolution."""
    approach = float(g[contact].mean())
    residual = g[contact] - approach
    outside = material.copy()
    outside[contact] = False
    join = np.flatnonzero(outside & (g < approach))
    penetration = approach - float(g[join].min()) if join.size else 0.0
    return approach, residual, join, max(math.sqrt(_dot(residual, residual) / contact.size),
                                         penetration)


#: the share of the contact set that may join in one step and keep the conjugate direction
#: (the joined cells start with none): a set that grows by a few cells at its rim each
#: step would otherwise restart the iteration as steepest descent every step
JOIN_RESTART = 0.01


def _ccg(system: _System, p, u, load, tol, max_iter):
    """Preconditioned constrained conjugate gradients (Polonsky & Keer 1999) from p, u (flat,
    MPa and mm) on the system's grids together.

    Works on S, the cells in contact (p > 0), and J, the material cells outside S that
    penetrate (loaded gap below the approach; see :func:`_state`), over all grids: the
    grids share one approach (their gaps are measured from one datum) and one load. The
    iteration runs in loads f = p·cell (so that grids of different cells are one symmetric
    system). Per step, on the working set S ∪ J: residual e = g - approach (zero mean on S,
    negative on J), preconditioned residual z = P·M·e with M each grid's approximate inverse
    (times its cell area) and P the removal of the mean on S ∪ J (a direction that keeps
    the load), direction t = z + (G/G_old)·t (G = e·z), or t = z when cells join (Polonsky
    & Keer's δ = 0), r = K t, exact line search tau = e·t / r·t, f -= tau·t, negative
    loads cut to 0 (those cells leave S and t; t, re-centred, keeps the load), and p scaled
    to carry the load (Polonsky & Keer's sequence). u follows p: u -= tau·r, plus the
    displacement of the cut pressures when there are any.

    The penetrating cells join inside the preconditioned step itself (f = -tau·t there):
    Polonsky & Keer's p = -tau·gap is a pressure only for the unpreconditioned step (with
    the preconditioner tau is a pure number, and -tau·gap a length), and their step is 0/0
    when S holds one cell (e = 0 on S), where ours is a steepest-descent step over S ∪ J.
    A grid's `structure` operator adds its displacement to the half-space's in every
    product; the preconditioner stays the half-space's.
    Returns p and the steps taken (max_iter unless the error fell below tol). Raises
    RuntimeError when the step breaks down (t·K·t not a number > 0: no descent left while the
    error is above tol)."""
    hf, mf = system.h, system.m
    pf, uf = p.copy(), u.copy()
    idx = np.flatnonzero(pf > 0.0)
    t = np.zeros(idx.size)
    G_old, conjugate = 1.0, False
    for step in range(max_iter + 1):
        g = hf + uf
        approach, e, join, error = _state(g, idx, mf)
        error /= float(uf[mf].max())
        if error < tol:
            return pf, step
        if step == max_iter:
            break
        work = idx
        if join.size:
            work = np.concatenate([idx, join])
            e = np.concatenate([e, g[join] - approach])
            if join.size > JOIN_RESTART * idx.size:
                conjugate = False
            else:
                t = np.concatenate([t, np.zeros(join.size)])
        z = system.precondition(e, work)
        z -= z.mean()
        G = _dot(e, z)
        t = z + (G / G_old) * t if conjugate else z
        G_old = G
        cells = system.cell(work)
        r = system.displacement(t / cells, work)
        denom = _dot(r[work], t)
        if not (math.isfinite(denom) and denom > 0):
            raise RuntimeError(
                f"solve_contact: the conjugate-gradient step broke down (t·K·t = {denom:.3g}) "
                f"at iteration {step} with relative gap error {error:.3g} on "
                f"{idx.size} contact cells")
        tau = _dot(e, t) / denom
        pw = pf[work] - tau * (t / cells)
        uf -= tau * r
        cut = pw < 0.0
        pf[work] = np.where(cut, 0.0, pw)
        if cut.any():
            uf += system.displacement(-pw[cut], work[cut])
            work, t = work[~cut], t[~cut]
            t -= t.mean()
        idx = work
        conjugate = True
        factor = load / system.load(pf, idx)
        pf[idx] *= factor
        uf *= factor
    return pf, step


def solve_shared(grids: list[Grid], loads_N, E_star_MPa: float, *, tol: float = 1e-8,
                 max_iter: int = 500, warm_start: bool = True, starts=None,
                 dtype=np.float64) -> list[ContactSolution | None]:
    """Pressure on several gap fields that close by one rigid approach and together carry
    one load: the contacts of one mesh position, each on its own grid (their gaps measured
    from one datum: a pair's gap holds its separation). One constrained conjugate-gradient
    solve over all grids (:func:`_ccg`): the split of the load follows, as the contact
    set does.

    grids: the gap fields (see :class:`Grid`).
    loads_N: the load each grid is started with (N, >= 0); their sum is the total load
        the grids carry. A grid started with 0 has no pressure at first (it takes load once
        the approach reaches it).
    starts: per grid, a pressure (MPa) to start from (scaled to the grid's start load), or
        None for the warm start (see :func:`solve_contact`).
    tol, max_iter, warm_start, dtype: as for :func:`solve_contact`.

    Returns one ContactSolution per grid (each with its own load, and the common approach,
    iterations and relative gap error), None for a grid that carries no load. Raises
    GridEdgeError (a ValueError) naming the grids whose contacts reach their edges, ValueError
    for bad input, RuntimeError if tol is not met in max_iter steps."""
    if not grids:
        raise ValueError("grids: at least one gap field is needed")
    loads = [float(w) for w in np.atleast_1d(np.asarray(loads_N, dtype=float))]
    if len(loads) != len(grids) or not all(math.isfinite(w) and w >= 0 for w in loads):
        raise ValueError(f"loads_N: {loads_N!r} must be one finite load >= 0 N per grid "
                         f"({len(grids)})")
    W = _positive("loads_N (their sum)", sum(loads), "N")
    E_star = _positive("E_star_MPa", E_star_MPa, "MPa")
    checked = [_Checked(*_check_grid(g.gap_mm, g.dx_mm, g.dy_mm, g.mask), g.structure,
                        tuple(g.reference), tuple(g.free_ends)) for g in grids]
    tol = _positive("tol", tol, "(relative gap error)")
    if not (isinstance(max_iter, (int, np.integer)) and max_iter >= 1):
        raise ValueError(f"max_iter: {max_iter!r} must be an integer >= 1")
    if np.dtype(dtype) not in (np.dtype(np.float64), np.dtype(np.float32)):
        raise ValueError(f"dtype: {dtype!r} must be numpy.float64 or numpy.float32")
    single = np.dtype(dtype) == np.dtype(np.float32)
    system = _System(checked, E_star, single)
    starts = [None] * len(grids) if starts is None else list(starts)
    p = np.concatenate([_start(g.h, g.dx, g.dy, g.m, w, E_star, start, warm_start).ravel()
                        for g, w, start in zip(checked, loads, starts)])     # carries W
    iterations, windows = 0, [None] * len(grids)
    while True:
        u = system.displacement(p, single=False)             # float64, afresh, everywhere
        error, approach, busy = system.error(p, u)
        if error < tol:
            break
        if iterations >= max_iter:
            raise RuntimeError(f"solve_contact: relative gap error {error:.3g} after "
                               f"{iterations} iterations, above tol = {tol:g}")
        windows = [_window(busy[s].reshape(shape), old)
                   for s, shape, old in zip(system.slices, system.shapes, windows)]
        part, inside = system.windowed(windows)
        solved, steps = _ccg(part, p[inside], u[inside], W, tol, max_iter - iterations)
        p = np.zeros(p.size)
        p[inside] = solved
        iterations += steps
    reached = {}
    for k, ((h, *_), s) in enumerate(zip(checked, system.slices)):
        S = p[s].reshape(h.shape) > 0.0
        edges = (bool(S[[0, -1], :].any()), bool(S[:, [0, -1]].any()))
        if any(edges):
            reached[k] = edges
    if reached:
        # every grid whose contact reaches its edge is named: a caller widens them all
        # before solving again (one by one, a spline's 18 fields took 18 solves)
        which = f"grid {', '.join(map(str, reached))}: " if len(grids) > 1 else ""
        raise GridEdgeError(
            f"gap_mm: {which}the contact reaches the grid's edge under load_N = {W:g}: the "
            "gap must close inside the grid (enlarge the grid, or set mask False where there "
            "is no material)", reached)
    out = []
    for (h, dx, dy, m, *_), s in zip(checked, system.slices):
        pk, uk = p[s].reshape(h.shape), u[s].reshape(h.shape)
        S = pk > 0.0
        if not S.any():
            out.append(None)
            continue
        load, area = float(pk.sum()) * dx * dy, float(S.sum()) * dx * dy
        separation = np.where(m, h + uk - approach, 0.0)
        for array in (pk, uk, separation, m):
            array.setflags(write=False)
        out.append(ContactSolution(
            pressure_MPa=pk, displacement_mm=uk, separation_mm=separation, mask=m,
            dx_mm=dx, dy_mm=dy, load_N=load, E_star_MPa=E_star, area_mm2=area,
            peak_pressure_MPa=float(pk.max()), mean_pressure_MPa=load / area,
            approach_mm=approach, iterations=iterations, relative_error=error))
    return out


def _start(h, dx, dy, m, load, E_star, start, warm_start) -> np.ndarray:
    """A grid's starting pressure (MPa) for `load` (N): `start` where it carries anything
    on the material, else the Hertz ellipse fitted to the gap, else the rigid
    interference (warm_start), else uniform on the material; zero for no load."""
    if load == 0.0:
        return np.zeros(h.shape)
    p = None
    if start is not None:
        p = np.where(m, np.clip(np.asarray(start, float), 0.0, None), 0.0)
        if p.shape != h.shape or not p.sum() > 0:
            p = None
    if p is None and warm_start:
        p = hertz_start(h, dx, dy, m, load, E_star)
        if p is None:
            p = interference_start(h, dx, dy, m, load, E_star)
    if p is None:
        p = m.astype(float)
    return p * (load / (dx * dy * p.sum()))


def solve_contact(gap_mm, dx_mm: float, dy_mm: float, load_N: float, E_star_MPa: float,
                  mask=None, *, tol: float = 1e-8, max_iter: int = 500,
                  warm_start: bool = True, start=None, dtype=np.float64,
                  structure=None, reference: tuple = ()) -> ContactSolution:
    """Pressure between two elastic bodies with initial gap `gap_mm` (mm; x along axis 0 in
    steps dx_mm, y along axis 1 in steps dy_mm) under the normal load `load_N` (N), composite
    modulus `E_star_MPa` (1/E* = (1-ν1²)/E1 + (1-ν2²)/E2, MPa).

    mask: bool array of the gap's shape, False = no material (no pressure, gap not used;
        the gap may be NaN there). Default: material everywhere.
    tol: converged when the relative gap error (see ContactSolution) is below it.
    warm_start: start from the Hertz ellipse fitted to the gap (:func:`hertz_start`), or
        where that ellipse lies mostly off the material, from the rigid interference
        (:func:`interference_start`); False: from uniform pressure on the material.
    start: a pressure (MPa, the gap's shape) to start from instead, e.g. the solution of
        the same gap under another load (scaled to this load; ignored where it carries
        nothing on the material).
    dtype: np.float64, or np.float32 for the transforms inside the iteration (faster); the
        start and the final check are float64 either way, and the iteration is continued
        from a fresh float64 displacement until the check meets tol.
    structure: a further linear displacement of the bodies under the pressure, p (MPa, the
        gap's shape) -> u (mm), symmetric and positive semi-definite (the teeth's bending,
        contact.compliance.StructureOperator); the approach then includes it.
    reference: ((depth mm, E MPa, nu) per body, see InfluenceOperator): the depth in each
        body the contact's compression is measured to (where a tooth's bending starts);
        () for half-spaces (relative to infinity).

    Raises ValueError for a load, E*, dx or dy that is not a finite number > 0, a mask of
    another shape or without material, a gap that is not finite on material, or a contact
    that reaches the grid's edge on material (GridEdgeError: the gap does not close within
    the grid under this load); RuntimeError if tol is not met in max_iter steps, or at once
    if a step breaks down (both with the error reached)."""
    W = _positive("load_N", load_N, "N")
    grid = Grid(gap_mm, dx_mm, dy_mm, mask, structure, tuple(reference))
    return solve_shared([grid], [W], E_star_MPa, tol=tol, max_iter=max_iter,
                        warm_start=warm_start, starts=[start], dtype=dtype)[0]
