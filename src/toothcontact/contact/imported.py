"""Contact of imported bodies: a user's STL or STEP of a parallel-axis pair, analysed on the
triangulations (mesh.TriangleSurface) the way contact.cycle analyses exact flanks.

At each pinion angle the vertices of the pinion's driving flanks near the gear are measured
against the gear's surface (signed distance, negative inside); the gear's lag is solved until the least of
them is zero, the lag window found first by a scan over one gear pitch (the driving flanks
close as the gear falls behind, so contact sits at the window's lagging end). Around each
tooth's closest vertex the distances are fitted with a cubic in the pinion's tangent plane
(x along the face, y across it); the quadratic part gives A, B and their direction, its
vertex the contact point. Hertz, the rigid ellipse and the margins to both bodies' edges
follow as for exact flanks: the face ends are the planes at each body's axial extremes, the
tip the circle of its farthest vertex from the axis, the form circle the user's form
diameter (checked only when given). A margin is measured in the tangent plane and turned
into a length along the flank with the flank's radial slope at the contact. The triangulation
limits the accuracy: distances carry the facets' chordal error, so the patch must rise 20
chordal errors above the contact, and across the profile it then spans only a few rows of
facets: B converges with the tessellation (within 12 % at 2 µm, 4 % at 1 µm on the bundled
pair; A within 1 %), bounded in a test against the exact analysis of the same pair. Units: mm, N, MPa, rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..analytic.hertz import hertz_point
from ..assembly import ParallelMesh
from ..mesh import TriangleSurface
from .cycle import FIT_GAP, CycleSettings

#: band (mm) of the gear's reach beyond its outer radius in which pinion vertices are probed
PROBE_BAND = 0.5
#: least cosine between a probed vertex's normal and its direction of motion: the driving
#: flanks, not the tip lands, roots or back flanks (a pair without backlash touches both)
LEADING = 0.3
#: distances (mm) up to which they are found exactly (farther ones only bound from above):
#: the lag solve and the fit patches look no farther
EXACT_WITHIN = 0.25
#: least number of vertices in a tooth's fit patch
FIT_VERTICES = 40


def imported_cycle(mesh: ParallelMesh, pinion: TriangleSurface, gear: TriangleSurface,
                   normal_load: float, C_E: float, settings: CycleSettings = CycleSettings(),
                   form_radii: tuple[float | None, float | None] = (None, None)) -> list[dict]:
    """One row per mesh position and pinion tooth in contact, with the keys of
    contact.cycle's rows that a mesh can support (no analytic A and B) and `method` =
    "mesh". `mesh` places the bodies as their files give them: each body's axis is its z
    axis; the gear's angle at phi1 = 0 is `mesh.gear_start`. `form_radii` (mm, pinion and
    gear): where the active flanks start; a form edge is checked only when given. The
    transmission error is given about its mean over the cycle (the files' phase is
    arbitrary)."""
    normals = pinion.mesh.vertex_normals
    # the driving flanks lead as the pinion turns (+z): their normals face the motion
    motion = np.stack([-pinion.vertices[:, 1], pinion.vertices[:, 0], np.zeros(len(normals))], -1)
    motion /= np.maximum(np.linalg.norm(motion, axis=-1, keepdims=True), 1e-12)
    leading = np.einsum("ij,ij->i", normals, motion) > LEADING
    gear_reach = float(np.max(np.hypot(gear.vertices[:, 0], gear.vertices[:, 1]))) + PROBE_BAND
    edges = {name: _Edges((float(body.vertices[:, 2].min()), float(body.vertices[:, 2].max())),
                          float(np.max(np.hypot(body.vertices[:, 0], body.vertices[:, 1]))), form)
             for name, body, form in (("pinion", pinion, form_radii[0]), ("gear", gear, form_radii[1]))}
    pitch = mesh.driver_pitch
    # the patch must rise well above the facets' chordal error to show its curvature
    chordal = {"pinion": chordal_error(pinion), "gear": chordal_error(gear)}
    band = max(FIT_GAP, 20.0 * max(chordal.values()))
    rows, placed, lag = [], [], None
    for phi in np.linspace(-0.5 * pitch, 0.5 * pitch, settings.positions):
        frame = mesh.pinion_frame(phi)
        world = frame.to_world(pinion.vertices)
        probe = np.flatnonzero(leading & (np.hypot(*(world[:, :2] - mesh.center[:2]).T)
                                          <= gear_reach))
        if probe.size == 0:
            raise ValueError(f"no pinion vertex reaches the gear at roll {math.degrees(phi):.3f} deg")

        def distances(delta, which=None):
            points = world[probe] if which is None else world[probe[which]]
            local = mesh.gear_frame(phi, 0, delta).to_local(points)
            return gear.signed_distance(local, exact_within=EXACT_WITHIN)[0]

        lag = _solve_lag(distances, probe.size, gear_reach, mesh, lag)
        d = distances(lag)
        # the lag on the fitted minima, and the pairs within the approach of it
        tooth = np.rint(np.arctan2(*(frame.to_local(world[probe])[:, 1::-1].T)) / pitch).astype(int)
        fits = {}
        for t in np.unique(tooth[d <= settings.approach + 0.05]):
            mine = tooth == t
            fit = _fit(world[probe[mine]], normals[probe[mine]] @ frame.R.T, d[mine], band)
            if fit is not None:
                fits[int(t)] = fit
        if not fits or min(f["s"] for f in fits.values()) > settings.approach:
            raise ValueError(f"the mesh's gap at the contact (roll {math.degrees(phi):.3f} deg) "
                             "is not a bowl: the tessellation is too coarse for the contact "
                             "(export the STL with a finer tolerance)")
        floor = min(f["s"] for f in fits.values())
        closest = np.argmin(d)[None]
        slope = (distances(lag + 1e-6, closest)[0] - distances(lag, closest)[0]) / 1e-6
        lag -= floor / slope
        in_contact = {t: f for t, f in fits.items() if f["s"] - floor <= settings.approach}
        share = normal_load / len(in_contact)
        for t, f in sorted(in_contact.items()):
            row, where = _row(mesh, frame, phi, t, lag, f, f["s"] - floor, share, C_E, settings,
                              edges)
            rows.append(row)
            placed.append(where)
    _add_profile_margins(rows, placed, {"pinion": pinion, "gear": gear}, edges, chordal)
    # the files' phase is arbitrary: the transmission error is the lag about its mean
    lags = {r["roll_deg"]: r["transmission_error_urad"] for r in rows}
    mean = float(np.mean(list(lags.values())))
    for r in rows:
        r["transmission_error_urad"] -= mean
    return rows


def _solve_lag(distances, count: int, reach: float, mesh: ParallelMesh,
               previous: float | None, tolerance: float = 1e-7) -> float:
    """The lag (rad) at which the least of the probes' distances closes to zero on the
    driving side. `distances(delta, which)` measures probes `which` (of `count`) at lag
    delta; `reach` (mm) is the gear's outer radius. The closure is bracketed from the
    previous position's lag, or first by a scan of two gear pitches (every eighth probe),
    then found by regula falsi on the probes that can matter: those within twice the
    bracket's travel of the least, a set that shrinks with the bracket."""
    every = np.arange(count)

    def least(delta, which=every):
        return float(np.min(distances(delta, which)))

    if previous is None:
        pitch = 2.0 * math.pi / mesh.gear_teeth
        grid = np.linspace(-pitch, pitch, 49)
        sparse = every[::8]
        clear = np.array([least(d, sparse) for d in grid]) > 0
        if not clear.any():
            raise ValueError("the bodies overlap at every gear angle over two pitches: check "
                             "the centre distance and the bodies' axes (each file's z axis)")
        ends = np.flatnonzero(clear[:-1] & ~clear[1:])   # clear, then overlapping: the lagging end
        if ends.size == 0:
            raise ValueError("the gear never closes on the pinion over two pitches: no contact "
                             "(check the centre distance and the bodies' placement)")
        end = ends[np.argmin(np.abs(grid[ends]))]
        lo, hi, step = grid[end] - 0.5 * (grid[1] - grid[0]), grid[end + 1], grid[1] - grid[0]
    else:
        step = 1e-4
        lo, hi = previous - step, previous + step
    d_lo = distances(lo, every)
    while np.min(d_lo) <= 0:
        step *= 4
        lo -= step
        d_lo = distances(lo, every)

    def within_reach(d, width):
        """The probes that can be least anywhere in a bracket `width` (rad) wide: a gear
        point moves at most reach·width across it."""
        return d < np.min(d) + 2.0 * reach * width + 1e-3

    near = every[within_reach(d_lo, hi - lo)]
    while least(hi, near) > 0:
        hi += 4 * (hi - lo)
        near = every[within_reach(d_lo, hi - lo)]
    f_lo, f_hi = least(lo, near), least(hi, near)
    mid = lo
    for _ in range(100):   # regula falsi (Illinois), bracketing the closure
        mid = hi - f_hi * (hi - lo) / (f_hi - f_lo)
        d_mid = distances(mid, near)
        f_mid = float(np.min(d_mid))
        if abs(f_mid) < tolerance or hi - lo < 1e-13:
            break
        if f_mid > 0:
            lo, f_lo = mid, f_mid
            f_hi *= 0.5
        else:
            hi, f_hi = mid, f_mid
            f_lo *= 0.5
        near = near[within_reach(d_mid, hi - lo)]
    return mid


def chordal_error(surface: TriangleSurface) -> float:
    """The facets' typical distance (mm) from the smooth surface they stand for: θ·L/8 of
    adjacent facets at angle θ across an edge of length L (a chord of a circle of curvature
    θ/L sags by that much), the 90th percentile over the smoothly curved edges."""
    mesh = surface.mesh
    angles = mesh.face_adjacency_angles
    edges = mesh.vertices[mesh.face_adjacency_edges]
    length = np.linalg.norm(edges[:, 0] - edges[:, 1], axis=-1)
    # the chord across the edge, not along it: the facets' widths, about their area / length
    width = mesh.area_faces[mesh.face_adjacency].mean(axis=1) * 2.0 / np.maximum(length, 1e-12)
    smooth = (angles > 0) & (angles < math.radians(20))
    if not smooth.any():
        return 0.0
    return float(np.percentile(angles[smooth] * width[smooth] / 8.0, 90))


def _fit(points: np.ndarray, normals: np.ndarray, d: np.ndarray, band: float) -> dict | None:
    """The gap of one tooth from its vertices (world) and their distances: a cubic in the
    tangent plane at the closest vertex over the vertices within `band` (mm) of the least
    distance, widened until the patch holds FIT_VERTICES. None when the fit is no bowl."""
    k = int(np.argmin(d))
    n = normals[k] / np.linalg.norm(normals[k])
    e1 = np.array([0.0, 0.0, 1.0]) - n[2] * n
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(n, e1)
    rel = points - points[k]
    x, y = rel @ e1, rel @ e2
    while np.count_nonzero(d <= d[k] + band) < FIT_VERTICES and band < 0.2:
        band *= 1.5
    use = d <= d[k] + band
    sx, sy = max(np.ptp(x[use]), 1e-6), max(np.ptp(y[use]), 1e-6)
    X, Y = x[use] / sx, y[use] / sy
    powers = [(i, j - i) for j in range(4) for i in range(j + 1)]
    design = np.stack([X**i * Y**j for i, j in powers], axis=-1)
    coef, *_ = np.linalg.lstsq(design, d[use], rcond=None)
    c = dict(zip(powers, coef))
    H = np.array([[2 * c[(2, 0)] / sx**2, c[(1, 1)] / (sx * sy)],
                  [c[(1, 1)] / (sx * sy), 2 * c[(0, 2)] / sy**2]])
    g = np.array([c[(1, 0)] / sx, c[(0, 1)] / sy])
    values, vectors = np.linalg.eigh(0.5 * H)
    if not values[0] > 0:
        return None
    shift = np.linalg.solve(H, -g)
    s = float(c[(0, 0)] + 0.5 * g @ shift)
    return {"point": points[k] + shift[0] * e1 + shift[1] * e2, "s": s, "A": float(values[0]),
            "B": float(values[1]), "angle": float(np.arctan2(vectors[1, 0], vectors[0, 0])),
            "e1": e1, "e2": e2, "vertices": int(use.sum()), "rms": float(np.sqrt(np.mean(
                (design @ coef - d[use]) ** 2)))}


@dataclass(frozen=True)
class _Edges:
    """A body's edges in its own frame: the face ends (z of its axial extremes, mm), the
    tip radius and the form radius (mm, None: not known)."""

    ends: tuple[float, float]
    tip: float
    form: float | None


def _row(mesh, frame, phi, tooth, lag, fit, gap, load, C_E, settings, edges):
    """The result row of one contact (face-end margins only; the tip and form margins are
    added for all rows at once by _add_profile_margins), and its ellipse as placed: the
    contact point, normal, A and B axes (world), semi-axes and both bodies' frames."""
    e = hertz_point(fit["A"], fit["B"], load, C_E)
    local = frame.to_local(fit["point"])
    along = fit["e1"] * math.cos(fit["angle"]) + fit["e2"] * math.sin(fit["angle"])
    normal = np.cross(fit["e1"], fit["e2"])
    across = np.cross(normal, along)
    frames = {"pinion": frame, "gear": mesh.gear_frame(phi, 0, lag)}
    margins = {}
    for name, body_frame in frames.items():
        edge = edges[name]
        axis = body_frame.R[:, 2]
        reach = math.hypot(e.a * float(along @ axis), e.b * float(across @ axis))
        z = float(body_frame.to_local(fit["point"])[2])
        margins[f"{name}_end_A"] = z - edge.ends[0] - reach
        margins[f"{name}_end_B"] = edge.ends[1] - z - reach
    row = {"roll_deg": math.degrees(phi), "pair": tooth, "method": "mesh",
           "contact_radius_pinion_mm": float(math.hypot(local[0], local[1])),
           "face_position_mm": float(local[2]), "separation_mm": gap,
           "A_per_mm": fit["A"], "B_per_mm": fit["B"], "fit_rms_mm": fit["rms"],
           "fit_vertices": fit["vertices"], "transmission_error_urad": lag * 1e6,
           "normal_load_N": load, "contact_model": "ellipse", "a_mm": e.a, "b_mm": e.b,
           "p_max_MPa": e.p0, "approach_mm": e.approach,
           "rigid_a_mm": math.sqrt(settings.approach / fit["A"]),
           "rigid_b_mm": math.sqrt(settings.approach / fit["B"]),
           "edge_margins_mm": margins}
    return row, _Placed(fit["point"], normal, along, across, e.a, e.b, frames)


@dataclass(frozen=True)
class _Placed:
    """A contact ellipse as placed (world, mm) with the frames of both bodies there."""

    point: np.ndarray
    normal: np.ndarray
    along: np.ndarray
    across: np.ndarray
    a: float
    b: float
    frames: dict


def _add_profile_margins(rows: list[dict], placed: list[_Placed], bodies: dict, edges: dict,
                         chordal: dict) -> None:
    """Each row's margins to both bodies' tip circles (and form circles where known), then
    its worst margin and edge flag: the length along the body's transverse profile from the
    contact to the circle (walked on the mesh for all rows at once, to within each body's
    chordal error `chordal` (mm) of the circle), less the ellipse's reach along it."""
    for name, surface in bodies.items():
        edge = edges[name]
        local = np.array([c.frames[name].to_local(c.point) for c in placed])
        normal = np.array([c.frames[name].R.T @ c.normal for c in placed])
        # the profile's tangent: in the transverse plane and the tangent plane, in world
        tangent = np.cross(normal, [0.0, 0.0, 1.0])
        tangent /= np.linalg.norm(tangent, axis=-1, keepdims=True)
        reach = np.array([math.hypot(c.a * float(c.frames[name].R @ t @ c.along),
                                     c.b * float(c.frames[name].R @ t @ c.across))
                          for c, t in zip(placed, tangent)])
        for key, radius, upward in ((f"{name}_tip", edge.tip, True),
                                    (f"{name}_form", edge.form, False)):
            if radius is None:
                continue
            arcs = _profile_arcs(surface, local, radius, upward, chordal[name])
            for row, arc, r in zip(rows, arcs, reach):
                row["edge_margins_mm"][key] = float(arc - r)
    for row in rows:
        worst = min(row["edge_margins_mm"].values())
        row["edge_margin_mm"], row["edge_contact"] = worst, bool(worst < 0.0)


#: step (mm) of the walk along a transverse profile on a mesh
PROFILE_STEP = 0.05
#: longest walk (mm): no flank runs farther from a contact to its tip or form circle
PROFILE_REACH = 30.0
#: a walk whose direction has less than this radial component has reached a land about the
#: axis (the tip land's facets are chords inside the tip circle)
LAND = 0.1


def _profile_arcs(surface: TriangleSurface, points: np.ndarray, radius: float,
                  upward: bool, slack: float) -> np.ndarray:
    """Length (mm) along each point's transverse profile on the surface (points in its own
    frame, on it) to the circle of `radius` about its axis, going outward (`upward`) or
    inward: steps of PROFILE_STEP along the surface's tangent in the transverse plane, each
    put back onto the surface at its closest point and into the starting plane, the last
    one cut where it comes within `slack` (mm, the facets' chordal error) of the circle, or
    ended where it runs onto a land about the axis (a tip land's facets are chords inside
    the tip circle); inf where the walk does not get there."""
    p = np.array(points, float)
    out = np.full(len(p), np.inf)
    arc = np.zeros(len(p))
    r = np.hypot(p[:, 0], p[:, 1])
    out[(r >= radius - slack) if upward else (r <= radius + slack)] = 0.0
    active = np.flatnonzero(~np.isfinite(out))
    z = p[:, 2].copy()
    for _ in range(int(PROFILE_REACH / PROFILE_STEP)):
        if active.size == 0:
            break
        q, n = surface.closest(p[active])
        t = np.cross(n, [0.0, 0.0, 1.0])
        t /= np.maximum(np.linalg.norm(t, axis=-1), 1e-12)[:, None]
        radial = q[:, :2] / np.linalg.norm(q[:, :2], axis=-1, keepdims=True)
        outward = np.einsum("ij,ij->i", t[:, :2], radial)
        t *= (np.where(outward >= 0.0, 1.0, -1.0) * (1.0 if upward else -1.0))[:, None]
        # on a land about the axis (a tip or root circle's facets) the profile runs round it
        landed = np.abs(outward) < LAND
        out[active[landed]] = arc[active[landed]]
        keep = ~landed
        active, q, t = active[keep], q[keep], t[keep]
        if active.size == 0:
            break
        step, _ = surface.closest(q + PROFILE_STEP * t)
        step[:, 2] = z[active]
        r0, r1 = np.hypot(q[:, 0], q[:, 1]), np.hypot(step[:, 0], step[:, 1])
        length = np.linalg.norm(step - q, axis=-1)
        target = radius - slack if upward else radius + slack
        crossed = (r1 >= target) if upward else (r1 <= target)
        with np.errstate(all="ignore"):
            fraction = np.clip((target - r0) / (r1 - r0), 0.0, 1.0)
        out[active[crossed]] = (arc[active] + fraction * length)[crossed]
        arc[active] += length
        p[active] = step
        active = active[~crossed & (length > 0.1 * PROFILE_STEP)]
    return out
