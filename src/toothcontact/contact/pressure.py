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
- u = K * p and the free end faces: contact.influence (Love's coefficients, DC-FFT, the
  quarter-space's mirror term).
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

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ..analytic.hertz import hertz_point
from .influence import influence_operator

__all__ = [
    "ContactSolution",
    "EdgeLoad",
    "Grid",
    "GridEdgeError",
    "hertz_start",
    "interference_start",
    "solve_contact",
    "solve_shared",
]


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


@dataclass(frozen=True)
class Grid:
    """One gap field of a shared solve (see :func:`solve_shared`): the gap (mm; x along axis
    0 in steps dx_mm, y along axis 1 in steps dy_mm), the material mask (None: everywhere),
    a further linear displacement `structure` p (MPa) -> u (mm) of its bodies (the teeth's
    bending: a contact.structure.StructureOperator, called on the grid and on a part of it
    by its `window(rows, cols)`), the depths its compression is measured to
    (`reference`, see influence.InfluenceOperator), and the free end faces of its bodies that cross
    it (`free_ends`, influence.FreeEnd: there a body is a quarter-space)."""

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

    def __init__(self, grids: list[_Checked], E_star: float, single: bool, ops=None,
                 body: np.ndarray | None = None):
        self.grids, self.E_star = grids, E_star
        #: the gear bodies' coupling of the grids' teeth (compliance.PairCompliance.
        #: body_coupling: C[k, l] per member), or None
        self.body = body
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
        roots = None if self.body is None else np.zeros((len(self.grids),) + self.body.shape[2:4])
        for k, ((s, q), op, structure, grid) in enumerate(zip(
                self._blocks(values, where), self.ops, self.structures, self.grids)):
            if q is not None:
                u = op(q, single)
                for end in grid.free_ends:
                    end.add_mirror(u, q, op, (grid.dx, grid.dy), single)
                u = u.ravel() * self.compliance
                out[s] = u if structure is None else u + structure(q).ravel()
                if roots is not None:
                    roots[k] = structure.root_resultants(q)
        if roots is not None and roots.any():
            self._add_body(out, roots)
        return out

    def _add_body(self, out: np.ndarray, roots: np.ndarray) -> None:
        """Add to `out` (mm, flat) each grid's teeth moving with their gear bodies under the
        other grids' root loads (`roots`, (grids, members, 3): StructureOperator.
        root_resultants of each grid's pressure)."""
        moves = np.einsum("klmab,lmb->kma", self.body, roots)
        for k, (s, structure) in enumerate(zip(self.slices, self.structures)):
            if moves[k].any():
                out[s] += structure.root_deflection(moves[k]).ravel()

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
        grids, ops, inside, kept = [], [], [], []
        for k, (g, op, s, shape, window) in enumerate(zip(self.grids, self.ops, self.slices,
                                                          self.shapes, windows)):
            if window is None:
                continue
            kept.append(k)
            rows, cols = window
            grids.append(_Checked(g.h[rows, cols], g.dx, g.dy, g.m[rows, cols],
                                  None if g.structure is None else g.structure.window(rows, cols),
                                  g.reference,
                                  tuple(end.shifted(rows, cols) for end in g.free_ends)))
            ops.append(op.part(grids[-1].h.shape))
            inside.append(np.arange(s.start, s.stop).reshape(shape)[rows, cols].ravel())
        body = None if self.body is None else self.body[np.ix_(kept, kept)]
        return _System(grids, self.E_star, self.single, ops, body), np.concatenate(inside)


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
                 dtype=np.float64, body: np.ndarray | None = None
                 ) -> list[ContactSolution | None]:
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
    body: the gear bodies' coupling of the grids' teeth, C[k, l] (members, 3, 3) turning
        the root loads of grid l's structure into the root moves of grid k's
        (compliance.PairCompliance.body_coupling), or None: the grids' teeth then deflect
        apart.

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
    system = _System(checked, E_star, single, body=body)
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
        contact.structure.StructureOperator); the approach then includes it.
    reference: ((depth mm, E MPa, nu) per body, see influence.InfluenceOperator): the depth in each
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
