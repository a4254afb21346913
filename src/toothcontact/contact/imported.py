"""Contact of imported bodies: a user's STL or STEP of a parallel-axis pair, analysed on their
triangulations (mesh.TriangleSurface) the way contact.cycle analyses exact flanks.

The pinion's driving flanks (facets facing the motion, within the gear's reach) are cut by
transverse planes ("stations", every STATION_STEP along the common face of both bodies), and
the points where the planes cut the facets' edges, put back on the smooth surface the facets
stand for (mesh module: Phong tessellation, exact to second order, so a chordal error of
facets does not ripple the result), are measured against the gear's smooth surface (signed
distance, negative inside). Across the profile, each station's least separation is the
vertex of the parabola through its least point and their neighbours, held within them (a
contact at the tip or form end of the profile stays at that end: no contact is placed
off the flank); along the face, the stations' least separations make the gap of the contact
line. Where the closest points of three neighbours are not squarely on one face of the gear
(the separation has a kink as they pass the gear's tip corner), no parabola is put through
them; the gear's tip corners are probed against the pinion's smooth surface instead. The
gear's lag is solved until the least of all is zero (the lag window is found first by a
scan over two gear pitches: the driving flanks close as the gear falls behind).

Each tooth within the approach of the least is a contact, of one of two kinds:
  * "ellipse": the gap along the face is a bowl whose least lies inside the face and whose
    rigid pattern (within the approach) is shorter than the face: A from the bowl along the
    face, B from the parabolas across the profile, their directions from the drift of the
    contact across the profile, then Hertz (point contact) as for exact flanks;
  * "line": otherwise (uncrowned flanks, or a crown too small for the misalignment): the
    contact is a line along the face, the stations within the approach of the tooth's least,
    cut by the face ends; Hertz line contact (the load over the length in contact, B across
    the profile), no approach.
Edges: the face ends are the planes at each body's axial extremes, the tips the circles of
each body's farthest point from its axis, the form circles the user's form diameters
(checked only when given). A margin is positive clear of the edge; negative when the pattern
is cut by it: minus the extent cut off where a bowl turns beyond the edge, minus the face
width where the gap keeps falling beyond it. Units: mm, N, MPa, rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..analytic.hertz import hertz_line, hertz_point
from ..surfaces.placement import ParallelMesh
from ..surfaces.triangles import TriangleSurface
from .cycle import CycleSettings, mesh_positions

#: band (mm) of the gear's reach beyond its outer radius in which pinion flanks are probed
PROBE_BAND = 0.5
#: least cosine between a probed facet's normal and its direction of motion: the driving
#: flanks, not the tip lands, roots or back flanks (a pair without backlash touches both)
LEADING = 0.3
#: distances (mm) up to which they are found exactly (farther ones only bound from above):
#: the lag solve and the fits look no farther
EXACT_WITHIN = 0.25
#: spacing (mm) of the transverse sections along the face
STATION_STEP = 1.0
#: least number of sections over the common face
STATIONS_MIN = 11
#: the sections at the face ends lie this far (mm) inside them (not in the end faces' plane)
END_INSET = 1e-3
#: a body's tips: its points within this fraction of its largest radius
TIP_BAND = 0.02
#: the gear's tip land: its facets whose corners all lie within this (mm) of its tip circle
TIP_LAND = 0.01
#: a probe faces a facet squarely where its offset from the closest point is within this
#: cosine of the facet's normal (a surface's curvature tilts it by about half a facet's turn)
SQUARE = 0.999
#: the probes within this (mm) of the least are measured again as the lag settles
SETTLE_BAND = 0.05
#: least spacing (mm) along a profile of the points a parabola is put through
DISTINCT = 1e-3
#: half-width (mm) across the profile of the parabola fitted for the curvature B
B_WINDOW = 0.25


def imported_cycle(mesh: ParallelMesh, pinion: TriangleSurface, gear: TriangleSurface,
                   normal_load: float, C_E: float, settings: CycleSettings = CycleSettings(),
                   form_radii: tuple[float | None, float | None] = (None, None)) -> list[dict]:
    """One row per mesh position and pinion tooth in contact, with contact.cycle's keys that
    a mesh can support (no analytic A and B), `method` = "mesh", `contact_model`
    ("ellipse" or "line"), `contact_length_mm`, `edge_contact_at`. `mesh` places the bodies
    as their files give them: each body's axis is its z axis; the gear's angle at phi1 = 0 is
    `mesh.gear_start`. `form_radii` (mm, pinion and gear): where the active flanks start; a
    form edge is checked only when given. The transmission error is given about its mean
    over the cycle (the files' phase is arbitrary). Raises ValueError naming the cause where
    the pair cannot be analysed."""
    edges = {name: _Edges((float(body.vertices[:, 2].min()), float(body.vertices[:, 2].max())),
                          float(np.max(np.hypot(body.vertices[:, 0], body.vertices[:, 1]))), form)
             for name, body, form in (("pinion", pinion, form_radii[0]), ("gear", gear, form_radii[1]))}
    # the driving flanks lead as the pinion turns (+z): their facets face the motion
    centroid = pinion.triangles.mean(axis=1)
    motion = np.stack([-centroid[:, 1], centroid[:, 0], np.zeros(len(centroid))], -1)
    motion /= np.maximum(np.linalg.norm(motion, axis=-1, keepdims=True), 1e-12)
    leading = np.flatnonzero(np.einsum("ij,ij->i", pinion.mesh.face_normals, motion) > LEADING)
    gear_reach = edges["gear"].tip + PROBE_BAND
    pitch = mesh.driver_pitch
    heights, common = _stations(mesh, edges)
    # the gear's tip corners, where its tip lands meet its flanks: their sections are
    # probed against the pinion (a corner is no smooth surface to fit a parabola on)
    tip_land = np.flatnonzero(np.hypot(gear.triangles[..., 0], gear.triangles[..., 1]).min(axis=1)
                              >= edges["gear"].tip - TIP_LAND)
    tips = gear.sections(tip_land, heights - mesh.center[2])
    pinion_reach = edges["pinion"].tip + PROBE_BAND + 4.0 * math.pi * edges["gear"].tip / mesh.gear_teeth
    driving = np.zeros(len(pinion.faces), bool)
    driving[leading] = True
    rows, placed, lag = [], [], None
    for phi in mesh_positions(pitch, settings.positions, settings.at):
        frame = mesh.pinion_frame(phi)
        corners = frame.to_world(pinion.triangles[leading].reshape(-1, 3))[:, :2] - mesh.center[:2]
        near = np.hypot(corners[:, 0], corners[:, 1]).reshape(-1, 3).min(axis=1)
        faces = leading[near <= gear_reach]
        if faces.size == 0:
            raise ValueError(f"no driving flank of the pinion reaches the gear at roll "
                             f"{math.degrees(phi):.3f} deg: check the centre distance and "
                             "that each file's z axis is its gear's axis")
        profile = _Profiles.cut(pinion, faces, heights, pitch)
        world = frame.to_world(profile.points)
        tip_world = mesh.gear_frame(phi, 0, 0.0).to_world(tips[0])
        close = np.flatnonzero(np.hypot(tip_world[:, 0], tip_world[:, 1]) <= pinion_reach)
        probes = _Probes(mesh, phi, world, tips[0][close], tips[2][close], pinion, gear, driving)
        lag = _solve_lag(probes.distances, probes.count, gear_reach, mesh, lag)
        lag, least = _settle(probes, profile, lag, pitch)
        floor = float(np.min(least.gap))
        frames = {"pinion": frame, "gear": mesh.gear_frame(phi, 0, lag)}
        in_contact = np.unique(profile.tooth_of[least.gap <= floor + settings.approach])
        for tooth in in_contact:
            mine = profile.tooth_of == tooth
            contact = _along(least, mine, profile, heights, common, settings.approach)
            row, where = _row(phi, int(tooth), lag, contact, floor, normal_load / len(in_contact),
                              C_E, settings, frames, edges, common)
            rows.append(row)
            placed.append(where)
    _add_profile_margins(rows, placed, {"pinion": pinion, "gear": gear}, edges)
    # the files' phase is arbitrary: the transmission error is the lag about its mean
    lags = {r["roll_deg"]: r["transmission_error_urad"] for r in rows}
    mean = float(np.mean(list(lags.values())))
    for r in rows:
        r["transmission_error_urad"] -= mean
    return rows


def _stations(mesh: ParallelMesh, edges: dict) -> tuple[np.ndarray, tuple]:
    """The heights (pinion z, mm) of the transverse sections over the face both bodies
    share, and that face: (low end, high end, name of the body whose end is the low one,
    name of the one whose end is the high one). The gear's end planes are taken where they
    cross the pinion's axis's parallel through the pitch point."""
    frame = mesh.gear_frame(0.0)
    normal = frame.R[:, 2]
    pitch_point = mesh.center * np.array([mesh.pinion_teeth / (mesh.pinion_teeth + mesh.gear_teeth),
                                          1.0, 0.0])
    gear_ends = []
    for z in edges["gear"].ends:
        origin = frame.to_world(np.array([0.0, 0.0, z]))
        gear_ends.append(float((normal @ (origin - pitch_point)) / normal[2]))
    low_gear, high_gear = min(gear_ends), max(gear_ends)
    (p0, p1) = edges["pinion"].ends
    low = (p0, "pinion") if p0 >= low_gear else (low_gear, "gear")
    high = (p1, "pinion") if p1 <= high_gear else (high_gear, "gear")
    if high[0] - low[0] <= 2.0 * STATION_STEP:
        raise ValueError(f"the bodies' faces do not overlap along the axis (pinion z "
                         f"{p0:.3f}..{p1:.3f} mm, gear {low_gear:.3f}..{high_gear:.3f} mm): "
                         "check misalignment.axial_shift and the files' z origins")
    count = max(STATIONS_MIN, math.ceil((high[0] - low[0]) / STATION_STEP) + 1)
    # a tilted gear's end planes cross the pinion's sections: its end sections stay inside
    # the gear's face over the pinion's whole depth
    inset = END_INSET + math.hypot(normal[0], normal[1]) / abs(normal[2]) * edges["pinion"].tip
    heights = np.linspace(low[0] + inset, high[0] - inset, count)
    return heights, (low[0], high[0], low[1], high[1])


@dataclass(frozen=True)
class _Profiles:
    """The pinion's driving flanks cut by the stations (pinion frame, mm): points on the
    smooth surface with their normals, sorted by profile (a tooth's flank at a station) and,
    within one, by radius; `s` the arc length along the profile, `group` the profile of each
    point (tooth_of[group]: its tooth, station_of[group]: its station)."""

    points: np.ndarray
    normals: np.ndarray
    s: np.ndarray
    group: np.ndarray
    starts: np.ndarray
    tooth_of: np.ndarray
    station_of: np.ndarray

    @classmethod
    def cut(cls, pinion: TriangleSurface, faces: np.ndarray, heights: np.ndarray,
            pitch: float) -> _Profiles:
        points, normals, station = pinion.sections(faces, heights)
        tooth = np.rint(np.arctan2(points[:, 1], points[:, 0]) / pitch).astype(int)
        key = (tooth - tooth.min()) * len(heights) + station
        radius = np.hypot(points[:, 0], points[:, 1])
        order = np.lexsort((radius, key))
        points, normals, key = points[order], normals[order], key[order]
        labels, starts, group = np.unique(key, return_index=True, return_inverse=True)
        step = np.linalg.norm(np.diff(points, axis=0), axis=-1)
        s = np.concatenate([[0.0], np.cumsum(step)])
        s -= s[starts][group]
        return cls(points, normals, s, group, starts, labels // len(heights) + tooth.min(),
                   labels % len(heights))


class _Probes:
    """What is measured at one pinion roll: the pinion's profile points (world) against the
    gear's smooth surface, then the gear's tip corners (gear frame) against the pinion's
    (only where the closest point is on a driving flank: inf elsewhere). `distances(delta,
    which)` (mm) at gear lag delta, of probes `which` (all: None) in that order; `measure`
    also gives the closest points (pinion frame, for the tip corners) and the facets."""

    def __init__(self, mesh, phi, world, tip_points, tip_station, pinion, gear, driving):
        self.mesh, self.phi, self.world = mesh, phi, world
        self.tip_points, self.tip_station = tip_points, tip_station
        self.pinion, self.gear, self.driving = pinion, gear, driving
        self.count = len(world) + len(tip_points)

    def measure(self, delta: float, which=None):
        which = np.arange(self.count) if which is None else np.asarray(which)
        own = which < len(self.world)
        d = np.empty(len(which))
        near = np.full((len(which), 3), np.nan)
        face = np.full(len(which), -1)
        gear_frame = self.mesh.gear_frame(self.phi, 0, delta)
        pinion_frame = self.mesh.pinion_frame(self.phi)
        if own.any():
            local = gear_frame.to_local(self.world[which[own]])
            d[own], near[own], face[own] = self.gear.signed_distance(
                local, exact_within=EXACT_WITHIN, smooth=True)
        if (~own).any():
            local = pinion_frame.to_local(gear_frame.to_world(self.tip_points[which[~own] - len(self.world)]))
            dist, near[~own], face[~own] = self.pinion.signed_distance(
                local, exact_within=EXACT_WITHIN, smooth=True)
            d[~own] = np.where(self.driving[face[~own]], dist, np.inf)
        return d, near, face

    def distances(self, delta: float, which=None) -> np.ndarray:
        return self.measure(delta, which)[0]


@dataclass(frozen=True)
class _Least:
    """Each profile's least separation `gap` (mm): the parabola's vertex through its least
    point and their neighbours, within them; at a profile's end, that end (`corner`); or
    the gear's tip corner where that comes closer. `point`, `normal`: where, on the pinion
    (its frame), `s` the arc along the profile there, `index` the least point, `points_gap`
    the separation of every profile point (mm), `points_part` the face of the gear each
    faces squarely (-1: a crease)."""

    gap: np.ndarray
    s: np.ndarray
    index: np.ndarray
    corner: np.ndarray
    point: np.ndarray
    normal: np.ndarray
    points_gap: np.ndarray
    points_part: np.ndarray


def _least_across(profile: _Profiles, gap: np.ndarray, part: np.ndarray) -> _Least:
    """The least separation of every profile from the separations `gap` of its points
    (whose closest points lie squarely on the gear's faces `part`, -1: on a crease): the
    vertex of the parabola through its least point and the nearest point on either side at least DISTINCT away
    (sections cross edges that nearly meet at the face ends), held between them; the least
    point itself at a profile's end, where the parabola does not open upward, or where the
    three points' closest points are not on one face of the gear (the gap has a kink where
    they pass one of its corners)."""
    count = len(profile.starts)
    order = np.lexsort((gap, profile.group))
    i = order[np.searchsorted(profile.group[order], np.arange(count))]
    ends = np.append(profile.starts[1:], len(gap)) - 1
    # a key that increases along the profiles, each after the one before
    span = float(np.max(profile.s)) + 1.0
    key = profile.group * span + profile.s
    left = np.searchsorted(key, key[i] - DISTINCT, "right") - 1
    right = np.searchsorted(key, key[i] + DISTINCT, "left")
    corner = (left < profile.starts) | (right > ends)
    inner = np.flatnonzero(~corner)
    j, i1, k = left[inner], i[inner], right[inner]
    s0, s1, s2 = profile.s[j], profile.s[i1], profile.s[k]
    g0, g1, g2 = gap[j], gap[i1], gap[k]
    d01, d12 = (g1 - g0) / (s1 - s0), (g2 - g1) / (s2 - s1)
    curve = (d12 - d01) / (s2 - s0)                 # half the second derivative
    opens = (curve > 0) & (part[i1] >= 0) & (part[j] == part[i1]) & (part[k] == part[i1])
    with np.errstate(divide="ignore", invalid="ignore"):
        vertex = np.where(opens, 0.5 * (s0 + s1) - d01 / (2.0 * np.where(opens, curve, 1.0)), s1)
    vertex = np.clip(vertex, s0, s2)
    # Newton's form through the three: g0 + d01 (s - s0) + curve (s - s0)(s - s1)
    value = g0 + d01 * (vertex - s0) + np.where(opens, curve, 0.0) * (vertex - s0) * (vertex - s1)
    least_gap, least_s = gap[i].copy(), profile.s[i].copy()
    least_gap[inner] = np.where(opens, np.minimum(value, g1), g1)
    least_s[inner] = vertex
    # the point there: between the least point and its neighbour on that side
    other = i.copy()
    other[inner] = np.where(vertex < s1, j, k)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.clip(np.nan_to_num((least_s - profile.s[i]) / (profile.s[other] - profile.s[i])), 0, 1)
    point = profile.points[i] + t[:, None] * (profile.points[other] - profile.points[i])
    normal = profile.normals[i] + t[:, None] * (profile.normals[other] - profile.normals[i])
    normal /= np.linalg.norm(normal, axis=-1, keepdims=True)
    return _Least(least_gap, least_s, i, corner, point, normal, gap, part)


def _facing(gear: TriangleSurface, points: np.ndarray, closest: np.ndarray, face: np.ndarray):
    """A label per probe (gear frame, with its closest point on the gear's smooth surface
    and that point's facet) of the face of the gear it faces squarely (its offset from the
    closest point within SQUARE of the facet's normal), -1 where it does not (the closest
    point is on a crease: the separation has a kink there)."""
    offset = points - closest
    length = np.linalg.norm(offset, axis=-1)
    square = np.abs(np.einsum("ij,ij->i", offset, gear.mesh.face_normals[face])) >= SQUARE * length
    return np.where(square | (length < 1e-6), gear.parts[face], -1)


def _settle(probes: _Probes, profile: _Profiles, lag: float, pitch: float,
            tolerance: float = 1e-7):
    """The lag (rad) at which the least separation (profiles between their points, and the
    gear's tip corners) is zero, from a lag at which their least point's is, and the
    profiles' least separations then (a tip corner's where it comes closer: on the
    pinion's tooth it faces, at its station)."""
    n = len(profile.points)
    d, near, face = probes.measure(lag)
    for step in range(6):
        if step:
            # the probes that can matter are measured again; the others move with them
            again = np.flatnonzero(d < np.min(d) + SETTLE_BAND)
            before = d[again]
            d[again], near[again], face[again] = probes.measure(lag, again)
            shift = np.mean((d[again] - before)[np.isfinite(before)])
            others = np.ones(len(d), bool)
            others[again] = False
            d[others] += shift
        local = probes.mesh.gear_frame(probes.phi, 0, lag).to_local(probes.world)
        least = _least_across(profile, d[:n], _facing(probes.gear, local, near[:n], face[:n]))
        tip = np.flatnonzero(np.isfinite(d[n:]))
        if tip.size:
            tooth = np.rint(np.arctan2(near[n + tip, 1], near[n + tip, 0]) / pitch).astype(int)
            key = tooth * 1_000_003 + probes.tip_station[tip]
            labels = profile.tooth_of * 1_000_003 + profile.station_of
            at = np.searchsorted(labels, key)
            found = (at < len(labels)) & (labels[np.minimum(at, len(labels) - 1)] == key)
            for g, q, dist in zip(at[found], near[n + tip[found]], d[n + tip[found]]):
                if dist < least.gap[g]:
                    least.gap[g], least.point[g] = dist, q
                    least.corner[g] = True
        g = int(np.argmin(least.gap))
        if abs(least.gap[g]) < tolerance:
            break
        probe = np.array([int(np.argmin(d))])
        slope = (probes.distances(lag + 1e-6, probe)[0] - d[probe[0]]) / 1e-6
        lag -= least.gap[g] / slope
    return lag, least


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
        grid = np.linspace(-pitch, pitch, 33)
        sparse = every[::8]
        clear = np.array([least(d, sparse) for d in grid]) > 0
        if not clear.any():
            raise ValueError("the bodies overlap at every gear angle over two pitches: check "
                             "the centre distance, the tooth counts and the bodies' axes "
                             "(each file's z axis)")
        ends = np.flatnonzero(clear[:-1] & ~clear[1:])   # clear, then overlapping: the lagging end
        if ends.size == 0:
            raise ValueError("the gear never closes on the pinion over two pitches: no "
                             "contact (check the centre distance, gear_phase and the bodies' "
                             "placement)")
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


def teeth_per_turn(surface: TriangleSurface) -> float:
    """How many teeth a whole turn of the body would hold: 2π over the median angle between
    neighbouring tooth tips (the clusters of its points within TIP_BAND of its largest
    radius about its z axis); a sector gives the same as its whole gear. nan where the body
    shows fewer than two tips."""
    v = surface.vertices
    r = np.hypot(v[:, 0], v[:, 1])
    angle = np.sort(np.arctan2(v[r >= (1.0 - TIP_BAND) * r.max(), 1], v[r >= (1.0 - TIP_BAND) * r.max(), 0]))
    if angle.size < 2:
        return float("nan")
    # start the circle in its widest empty stretch (between two tips, or a sector's gap)
    step = np.diff(np.append(angle, angle[0] + 2.0 * math.pi))
    widest = int(np.argmax(step))
    angle = np.unwrap(np.roll(angle, -(widest + 1)))
    step = np.diff(angle)
    split = np.flatnonzero(step > 0.5 * step.max()) + 1
    if split.size == 0:
        return float("nan")
    centres = np.array([0.5 * (a[0] + a[-1]) for a in np.split(angle, split)])
    return float(2.0 * math.pi / np.median(np.diff(centres)))


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


@dataclass(frozen=True)
class _Edges:
    """A body's edges in its own frame: the face ends (z of its axial extremes, mm), the
    tip radius and the form radius (mm, None: not known)."""

    ends: tuple[float, float]
    tip: float
    form: float | None


@dataclass(frozen=True)
class _Line:
    """One tooth's contact from its stations' least separations (pinion frame, mm): its
    model ("ellipse" or "line"), centre, normal and A axis (ellipse) or direction (line),
    A and B (1/mm), its least separation, the rigid pattern and what the face ends cut off
    (see _along)."""

    model: str
    point: np.ndarray          # the contact's centre (pinion frame)
    normal: np.ndarray
    along: np.ndarray          # unit vector of the A axis (ellipse) or of the line
    A: float
    B: float
    floor: float               # the tooth's least separation (mm)
    pattern: tuple[float, float]   # the rigid pattern's ends along the face (pinion z)
    cut: dict                  # "low"/"high": extent (mm) cut off by that face end, or None
    ends: list                 # points (pinion frame) of the line's ends and its least


def _along(least: _Least, mine: np.ndarray, profile: _Profiles, heights: np.ndarray,
           common: tuple, approach: float) -> _Line:
    """One tooth's contact from its profiles' (`mine`) least separations (see module
    docstring)."""
    groups = np.flatnonzero(mine)
    station = profile.station_of[groups]
    g = np.full(len(heights), np.inf)
    g[station] = least.gap[groups]
    point = np.full((len(heights), 3), np.nan)
    normal = np.full((len(heights), 3), np.nan)
    point[station], normal[station] = least.point[groups], least.normal[groups]
    B = np.full(len(heights), np.nan)
    for k, grp in zip(station, groups):
        B[k] = _curvature_across(profile, least, grp)
    valid = np.isfinite(g)
    z, gv = heights[valid], g[valid]
    k = int(np.argmin(gv))
    floor = float(gv[k])
    width = common[1] - common[0]
    # the gap along the face, a quadratic over the whole face: does a crown turn it?
    fit = np.polyfit(z, gv, 2) if len(z) >= 3 else np.array([0.0, 0.0, floor])
    run = _run(z, gv, k, floor + approach)
    lo_cut = run[0] <= heights[0] + 1e-9 and valid[0]
    hi_cut = run[1] >= heights[-1] - 1e-9 and valid[-1]
    pattern = (common[0] if lo_cut else run[0], common[1] if hi_cut else run[1])
    cut = {"low": _cut_off(fit, common[0], floor + approach, -1.0, width) if lo_cut else None,
           "high": _cut_off(fit, common[1], floor + approach, 1.0, width) if hi_cut else None}
    A_line = float(fit[0])
    # a bowl: its least inside the face, for the stations and for the quadratic through them
    # all (near an end the stations' small differences alone cannot tell)
    interior = 0 < k < len(z) - 1 and A_line > 0 and z[0] < -fit[1] / (2.0 * A_line) < z[-1]
    bowl = interior and 2.0 * math.sqrt(approach / A_line) < width
    zv, pv, nv, Bv = heights[valid], point[valid], normal[valid], B[valid]
    known = np.isfinite(Bv)
    if not known.any():
        raise ValueError("the separation across the pinion's profile does not open upward "
                         f"at any section of tooth {profile.tooth_of[groups[0]]} (fewer than "
                         "four section points on the flank round the contact)")
    ends = [_interpolate(zv, pv, zz) for zz in pattern] + [pv[k]]
    if bowl:
        # the bowl's vertex, from the stations near the least
        use = np.abs(z - z[k]) <= max(2.0 * math.sqrt(approach / A_line), 3.0 * (z[1] - z[0]))
        c2, c1, _ = np.polyfit(z[use], gv[use], 2) if use.sum() >= 3 else fit
        z_least = float(np.clip(-c1 / (2.0 * c2), z[k - 1], z[k + 1])) if c2 > 0 else float(z[k])
        A_line = float(c2) if c2 > 0 else A_line
        centre, n = _interpolate(zv, pv, z_least), _interpolate(zv, nv, z_least)
        n /= np.linalg.norm(n)
        e1 = np.array([0.0, 0.0, 1.0]) - n[2] * n
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(n, e1)
        # the contact's drift across the profile along the face gives the cross term
        x, y = (pv[use] - centre) @ e1, (pv[use] - centre) @ e2
        drift = float(np.polyfit(x, y, 1)[0]) if len(x) >= 2 and np.ptp(x) > 0 else 0.0
        b_across = float(np.interp(z_least, zv[known], Bv[known]))
        c = -b_across * drift
        values, vectors = np.linalg.eigh(np.array([[A_line + c * c / b_across, c], [c, b_across]]))
        along = vectors[0, 0] * e1 + vectors[1, 0] * e2
        return _Line("ellipse", centre, n, along, float(values[0]), float(values[1]), floor,
                     pattern, cut, ends)
    middle = 0.5 * (pattern[0] + pattern[1])
    centre, n = _interpolate(zv, pv, middle), _interpolate(zv, nv, middle)
    n /= np.linalg.norm(n)
    e1 = np.array([0.0, 0.0, 1.0]) - n[2] * n
    e1 /= np.linalg.norm(e1)
    inside = known & (zv >= pattern[0] - 1e-9) & (zv <= pattern[1] + 1e-9)
    b_across = float(np.median(Bv[inside] if inside.any() else Bv[known]))
    return _Line("line", centre, n, e1, A_line, b_across, floor, pattern, cut, ends)


def _run(z: np.ndarray, g: np.ndarray, k: int, level: float) -> tuple[float, float]:
    """The ends (mm) of the stretch round station k where the piecewise-linear gap g(z)
    stays below `level`."""
    lo = k
    while lo > 0 and g[lo - 1] <= level:
        lo -= 1
    hi = k
    while hi < len(z) - 1 and g[hi + 1] <= level:
        hi += 1
    left = z[lo] if lo == 0 else z[lo - 1] + (level - g[lo - 1]) / (g[lo] - g[lo - 1]) * (z[lo] - z[lo - 1])
    right = z[hi] if hi == len(z) - 1 else z[hi] + (level - g[hi]) / (g[hi + 1] - g[hi]) * (z[hi + 1] - z[hi])
    return float(left), float(right)


def _cut_off(fit: np.ndarray, edge: float, level: float, outward: float, width: float) -> float:
    """The extent (mm) beyond the face end at `edge` (outward: +1 the high end, -1 the
    low end) of the pattern below `level` of the gap q(z) = fit (a quadratic along the
    face) continued beyond the edge; the face width where q keeps falling (no crown turns
    it within a face width of the edge)."""
    a, b, c = fit
    if a <= 0:
        return width
    disc = b * b - 4.0 * a * (c - level)
    if disc <= 0:
        return 0.0
    roots = ((-b - math.sqrt(disc)) / (2.0 * a), (-b + math.sqrt(disc)) / (2.0 * a))
    far = roots[1] if outward > 0 else roots[0]
    return float(min(max(outward * (far - edge), 0.0), width))


def _interpolate(heights: np.ndarray, values: np.ndarray, z: float) -> np.ndarray:
    """Values (n, 3) given at heights, linearly at z (held at the ends)."""
    return np.array([np.interp(z, heights, values[:, i]) for i in range(values.shape[1])])


def _curvature_across(profile: _Profiles, least: _Least, group: int) -> float:
    """B (1/mm): half the second derivative across the profile of its points' separations
    near its least, from a parabola (with its slope: one-sided at a corner) over the points
    within B_WINDOW that face the same face of the gear as its least point (no kink where
    they pass a corner of the gear), at least its five nearest; nan where fewer than four
    or where the parabola does not open upward."""
    start = profile.starts[group]
    stop = profile.starts[group + 1] if group + 1 < len(profile.starts) else len(profile.s)
    arc = profile.s[start:stop] - least.s[group]
    g, part = least.points_gap[start:stop], least.points_part[start:stop]
    own = least.points_part[least.index[group]]
    same = part == own
    if own >= 0 and np.count_nonzero(same) >= 4:
        arc, g = arc[same], g[same]
    if len(arc) < 4:
        return float("nan")
    use = np.abs(arc) <= max(B_WINDOW, np.sort(np.abs(arc))[min(4, len(arc) - 1)])
    if len(np.unique(np.round(arc[use] / DISTINCT))) < 3:
        return float("nan")
    B = float(np.polyfit(arc[use], g[use], 2)[0])
    return B if B > 0 else float("nan")


def _row(phi, tooth, lag, line: _Line, floor, load, C_E, settings, frames, edges, common):
    """The result row of one contact (face-end margins only; the tip and form margins are
    added for all rows at once by _add_profile_margins), and its placements for those: the
    contact point(s), normal, axes and semi-axes, and both bodies' frames."""
    R = frames["pinion"].R
    point, normal, along = R @ line.point, R @ line.normal, R @ line.along
    across = np.cross(normal, along)
    length = line.pattern[1] - line.pattern[0]
    model = line.model
    if model == "ellipse":
        e = hertz_point(line.A, line.B, load, C_E)
        a, b, p0, approach = e.a, e.b, e.p0, e.approach
        rigid_a = math.sqrt(settings.approach / line.A)
        if 2.0 * a >= common[1] - common[0]:     # the loaded ellipse would span the face
            model = "line"
    if model == "line":
        contact = hertz_line(load / length, 1.0 / (2.0 * line.B), C_E)
        a, b, p0, approach = 0.5 * length, contact.b, contact.p0, None
        rigid_a = 0.5 * length
    margins = {}
    for name, body_frame in frames.items():
        lo, hi = edges[name].ends
        axis = body_frame.R[:, 2]
        if model == "ellipse":
            reach = math.hypot(a * float(along @ axis), b * float(across @ axis))
            z = float(body_frame.to_local(point)[2])
            margins[f"{name}_end_A"] = z - lo - reach
            margins[f"{name}_end_B"] = hi - z - reach
        else:
            ends = [float(body_frame.to_local(R @ p)[2]) for p in line.ends[:2]]
            margins[f"{name}_end_A"] = min(ends) - lo
            margins[f"{name}_end_B"] = hi - max(ends)
    # a line cut by a face end: minus what the end cut off (the face width where the gap
    # keeps falling beyond it)
    for side, end in (("low", 2), ("high", 3)):
        if line.cut[side] is not None and model == "line":
            margins[f"{common[end]}_end_{'A' if side == 'low' else 'B'}"] = -line.cut[side]
    local = line.point
    row = {"roll_deg": math.degrees(phi), "pair": tooth, "method": "mesh",
           "contact_model": model,
           "contact_radius_pinion_mm": float(math.hypot(local[0], local[1])),
           "face_position_mm": float(local[2]), "separation_mm": line.floor - floor,
           "A_per_mm": line.A, "B_per_mm": line.B,
           "transmission_error_urad": lag * 1e6,
           "normal_load_N": load, "a_mm": a, "b_mm": b,
           "p_max_MPa": p0, "approach_mm": approach, "contact_length_mm": length,
           "rigid_a_mm": rigid_a, "rigid_b_mm": math.sqrt(settings.approach / line.B),
           "edge_margins_mm": margins}
    if model == "ellipse":
        return row, [_Placed(point, normal, along, across, a, b, frames)]
    # a line is held against the tip and form circles at its ends and its least point
    return row, [_Placed(R @ p, normal, along, across, 0.0, b, frames) for p in line.ends]


@dataclass(frozen=True)
class _Placed:
    """A contact (ellipse, or one point of a line) as placed (world, mm) with the frames of
    both bodies there."""

    point: np.ndarray
    normal: np.ndarray
    along: np.ndarray
    across: np.ndarray
    a: float
    b: float
    frames: dict


def _add_profile_margins(rows: list[dict], placed: list[list[_Placed]], bodies: dict,
                         edges: dict) -> None:
    """Each row's margins to both bodies' tip circles (and form circles where known), then
    its least margin (`edge_margin_mm`, any edge) and whether a face end cuts its pattern
    (`edge_contact`, `edge_contact_at`: the face end that cuts most): the length along the
    body's transverse profile from the contact (the least of a line's ends and least point)
    to the circle (walked on the mesh for all rows at once, to within each body's chordal
    error of the circle), less the ellipse's reach along it."""
    flat = [c for group in placed for c in group]
    owner = np.repeat(np.arange(len(placed)), [len(group) for group in placed])
    for name, surface in bodies.items():
        edge = edges[name]
        local = np.array([c.frames[name].to_local(c.point) for c in flat])
        normal = np.array([c.frames[name].R.T @ c.normal for c in flat])
        # the profile's tangent: in the transverse plane and the tangent plane, in world
        tangent = np.cross(normal, [0.0, 0.0, 1.0])
        tangent /= np.linalg.norm(tangent, axis=-1, keepdims=True)
        reach = np.array([math.hypot(c.a * float(c.frames[name].R @ t @ c.along),
                                     c.b * float(c.frames[name].R @ t @ c.across))
                          for c, t in zip(flat, tangent)])
        for key, radius, upward in ((f"{name}_tip", edge.tip, True),
                                    (f"{name}_form", edge.form, False)):
            if radius is None:
                continue
            arcs = _profile_arcs(surface, local, radius, upward, chordal_error(surface))
            margin = np.full(len(rows), np.inf)
            np.minimum.at(margin, owner, np.minimum(arcs, PROFILE_REACH) - reach)
            for row, m in zip(rows, margin):
                row["edge_margins_mm"][key] = float(m)
    for row in rows:
        margins = row["edge_margins_mm"]
        row["edge_margin_mm"] = min(margins.values())
        end = min((k for k in margins if "_end_" in k), key=margins.get)
        row["edge_contact"] = bool(margins[end] < 0.0)
        row["edge_contact_at"] = end if margins[end] < 0.0 else None


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
