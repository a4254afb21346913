"""Geometry benchmark against other open gear generators, side by side in one run.

Builds two parts with toothcontact and with the peers from PyPI (plus cq_gears from a
source checkout where it imports), times build and STEP export, and measures each built
solid's flank deviation from toothcontact's exact surface:

  * crowned spur gear: z = 20, m = 3 mm, alpha = 20 deg, b = 30 mm, all teeth, lead crown
    R = 4000 mm, parabolic (py-gearworks' crowning is parabolic: c = h/(1e-3·m·cos alpha));
  * the seed-000 worm wheel: z2 = 40 for a 1-start worm, mn = 1.1 mm, lead angle 4.1 deg
    (mx = mn/cos 4.1 deg), ZA, alpha = 20 deg, DIN 3975 face width b2 = 2·mx·sqrt(q + 1).

Prints a table and writes benchmarks/geometry_peers.json. Peer code is only installed and
called, never copied into the project.

Setup (the peers need Python >= 3.12 for wormgear 0.2; cadquery 2.8 and build123d 0.12 run
on the project's cadquery-ocp 7.9, so everything imports in ONE process):

    PY312=$(pyenv root)/versions/3.12.1/bin/python3.12        # any CPython >= 3.12
    $PY312 -m venv /tmp/peers-venv
    /tmp/peers-venv/bin/pip install -e /work/main wormgear==0.2.0 py-gearworks==0.0.24 \
        cadquery==2.8.0 'cadquery-ocp>=7.9,<8'
    # cq_gears (meadiode/cq_gears) is not on PyPI: put a source checkout's top folder on
    # CQ_GEARS_PATH (default /tmp/cq_gears_src, the folder that holds cq_gears/__init__.py).

Run (about 5 min on 2 cores, most of it wormgear's virtual hobbing at 36 steps, its
'preview' preset; its default 72 steps takes ~750 s here, its 'ultra' 360 steps hours):

    /tmp/peers-venv/bin/python benchmarks/geometry_peers.py
    /tmp/peers-venv/bin/python benchmarks/geometry_peers.py --hobbing-steps 72 --hobbing-limit 900

How deviation is measured: points are sampled on the B-rep faces of the built solid (a UV
grid inside each face, face orientation respected, spacing 0.1 mm spur / 0.05 mm wheel),
restricted to the faces near one tooth; flank points are those whose outward normal is
mostly tangential. The peer's tooth is aligned by a least-squares rotation about the gear
axis (both flanks together, so a tooth-thickness error shows as +/- on the two flanks), then

  * spur: normal distance in the transverse plane d = rb·(psi_point - psi_flank), exact for
    involutes, with the crown drop added (it is a normal offset);
  * worm wheel: closest point on toothcontact's exact enveloped flank (WormWheelFlank,
    Gauss-Newton on (u, v) from a grid guess), d = (P - S(u, v))·n.

d > 0 is excess material. Kept: form..tip radius (spur) / inside the exact flank's domain
and the DIN blank (wheel), at least 0.5 mm from the face ends. Our solids are measured the
same way. Our exact wheel flank itself is checked independently as an envelope (max over
hob positions of the hob thread's normal penetration into the flank: 0 for a true
envelope; a +1 µm offset of the flank must read 1 µm). Where toothcontact.cad has no
build_wheel (older trees), the wheel-solid row says n/a and the exact flanks are the base.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import sys
import tempfile
import time
import traceback
from importlib import metadata
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from timing import timed  # noqa: E402
JSON_OUT = HERE / "geometry_peers.json"
CQ_GEARS_PATH = os.environ.get("CQ_GEARS_PATH", "/tmp/cq_gears_src")

# --- the two parts ---------------------------------------------------------------------------
SPUR_TEETH, SPUR_MODULE, SPUR_ALPHA_DEG, SPUR_FACE = 20, 3.0, 20.0, 30.0
SPUR_CROWN_RADIUS = 4000.0  # mm, parabolic: end drop 15²/8000 = 28.1 µm
WHEEL_TEETH, WORM_STARTS, WORM_MN, WORM_GAMMA_DEG, WORM_ALPHA_DEG = 40, 1, 1.1, 4.1, 20.0
END_MARGIN = 0.5  # mm kept clear of the face ends


def versions() -> dict:
    out = {"python": platform.python_version(), "machine": platform.machine(),
           "cpus": os.cpu_count()}
    for dist in ("toothcontact", "wormgear", "py-gearworks", "build123d", "cadquery",
                 "cadquery-ocp", "numpy", "scipy"):
        try:
            out[dist] = metadata.version(dist)
        except metadata.PackageNotFoundError:
            out[dist] = None
    try:
        import subprocess
        head = subprocess.run(["git", "-C", CQ_GEARS_PATH, "rev-parse", "--short", "HEAD"],
                              capture_output=True, text=True)
        out["cq_gears"] = head.stdout.strip() or "source checkout"
    except Exception:  # noqa: BLE001
        out["cq_gears"] = "source checkout"
    return out


# --- sampling B-rep faces ----------------------------------------------------------------------
def sample_faces(shape, spacing: float, wedge: float, r_lo: float, r_hi: float,
                 max_xy: float):
    """Points and outward unit normals on the faces of `shape` whose bounding box meets the
    wedge |polar angle| < wedge, r_lo < r < r_hi (and spans less than max_xy in x and y).
    A UV grid of cell centres about `spacing` mm apart, kept where the point is IN the face."""
    from OCP.Bnd import Bnd_Box
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.BRepBndLib import BRepBndLib
    from OCP.BRepTools import BRepTools
    from OCP.BRepTopAdaptor import BRepTopAdaptor_FClass2d
    from OCP.gp import gp_Pnt, gp_Pnt2d, gp_Vec
    from OCP.TopAbs import TopAbs_FACE, TopAbs_IN, TopAbs_REVERSED
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    x_lo, y_hi = r_lo * math.cos(wedge) - 1.0, r_hi * math.sin(wedge) + 1.0
    pts, nrm = [], []
    explorer = TopExp_Explorer(shape, TopAbs_FACE)
    while explorer.More():
        face = TopoDS.Face_s(explorer.Current())
        explorer.Next()
        box = Bnd_Box()
        BRepBndLib.Add_s(face, box)
        xmin, ymin, _, xmax, ymax, _ = box.Get()
        if xmax < x_lo or xmin > r_hi + 1.0 or ymin > y_hi or ymax < -y_hi:
            continue
        if xmax - xmin > max_xy or ymax - ymin > max_xy:
            continue
        surf = BRepAdaptor_Surface(face, True)
        u0, u1, v0, v1 = BRepTools.UVBounds_s(face)

        def length(along_u: bool) -> float:
            ts = np.linspace(0.0, 1.0, 9)
            total = 0.0
            for w in (0.25, 0.5, 0.75):
                prev = None
                for t in ts:
                    p = surf.Value(u0 + t * (u1 - u0), v0 + w * (v1 - v0)) if along_u else \
                        surf.Value(u0 + w * (u1 - u0), v0 + t * (v1 - v0))
                    if prev is not None:
                        total += p.Distance(prev)
                    prev = p
            return total / 3.0

        nu = int(np.clip(math.ceil(length(True) / spacing), 3, 600))
        nv = int(np.clip(math.ceil(length(False) / spacing), 3, 600))
        classifier = BRepTopAdaptor_FClass2d(face, 1e-9)
        flip = -1.0 if face.Orientation() == TopAbs_REVERSED else 1.0
        p, du, dv = gp_Pnt(), gp_Vec(), gp_Vec()
        for u in u0 + (np.arange(nu) + 0.5) / nu * (u1 - u0):
            for v in v0 + (np.arange(nv) + 0.5) / nv * (v1 - v0):
                if classifier.Perform(gp_Pnt2d(float(u), float(v))) != TopAbs_IN:
                    continue
                surf.D1(float(u), float(v), p, du, dv)
                n = du.Crossed(dv)
                mag = n.Magnitude()
                if mag < 1e-14:
                    continue
                pts.append((p.X(), p.Y(), p.Z()))
                nrm.append((flip * n.X() / mag, flip * n.Y() / mag, flip * n.Z() / mag))
    return np.array(pts).reshape(-1, 3), np.array(nrm).reshape(-1, 3)


def z_centre(shape) -> float:
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib
    box = Bnd_Box()
    BRepBndLib.Add_s(shape, box)
    _, _, zmin, _, _, zmax = box.Get()
    return 0.5 * (zmin + zmax)


def stats(d: np.ndarray) -> dict:
    d = np.asarray(d, float)
    if d.size == 0:
        return {"points": 0, "max_um": None, "rms_um": None}
    return {"points": int(d.size), "max_um": float(np.abs(d).max() * 1e3),
            "rms_um": float(np.sqrt(np.mean(d * d)) * 1e3),
            "min_signed_um": float(d.min() * 1e3), "max_signed_um": float(d.max() * 1e3)}


# --- the spur gear -------------------------------------------------------------------------------
def spur_reference():
    from toothcontact.surfaces.modify import FlankModifications, LeadCrown
    from toothcontact.surfaces.generation import generate_side
    from toothcontact.surfaces.involute import CylindricalGear

    gear = CylindricalGear(SPUR_TEETH, SPUR_MODULE, math.radians(SPUR_ALPHA_DEG), SPUR_FACE)
    mods = FlankModifications(lead_crown=LeadCrown(radius=SPUR_CROWN_RADIUS, shape="parabolic"))
    form = generate_side(gear).form_radius
    return gear, mods, form


def spur_deviation(shape, gear, mods, form_radius: float) -> dict:
    """Transverse normal deviation of one tooth's two flanks from the exact crowned involute
    (see the module docstring); the tooth nearest +x after a least-squares rotation."""
    rb, tau, psi_b = gear.base_radius, 2 * math.pi / gear.teeth, gear.base_half_angle
    r_tip, half = gear.tip_radius, 0.5 * gear.face_width
    P, N = sample_faces(shape, 0.1, 0.75 * tau, gear.root_radius_value, r_tip,
                        max_xy=2.5 * (r_tip - gear.root_radius_value) + 10.0)
    z = P[:, 2] - z_centre(shape)
    r = np.hypot(P[:, 0], P[:, 1])
    theta = np.arctan2(P[:, 1], P[:, 0])
    n_t = -np.sin(theta) * N[:, 0] + np.cos(theta) * N[:, 1]
    keep = ((r > form_radius + 1e-3) & (r < r_tip - 1e-3) & (np.abs(z) <= half - END_MARGIN)
            & (np.abs(n_t) > 0.5) & (np.abs(N[:, 2]) < 0.5))
    r, theta, z, side = r[keep], theta[keep], z[keep], np.sign(n_t[keep])
    alpha = np.arccos(rb / r)
    inv_r = np.tan(alpha) - alpha
    drop = mods.drop(z, 0 * z, gear.face_width, 0.0, 1.0)
    e = theta + side * inv_r - side * (psi_b - drop / rb)  # = rho + k·tau on the exact flank
    rho = np.angle(np.mean(np.exp(2j * np.pi * e / tau))) * tau / (2 * np.pi)
    k = np.round((e - rho) / tau)
    k0 = np.round(-rho / tau)  # the tooth nearest +x
    on = k == k0
    e, side = e[on] - k0 * tau, side[on]
    rho = float(np.mean(e))  # least squares over both flanks
    d = side * rb * (e - rho)
    out = stats(d)
    out.update(rotation_deg=math.degrees(rho + k0 * tau),
               mean_plus_um=float(np.mean(d[side > 0]) * 1e3) if np.any(side > 0) else None,
               mean_minus_um=float(np.mean(d[side < 0]) * 1e3) if np.any(side < 0) else None)
    return out


# --- the worm wheel -------------------------------------------------------------------------------
def wheel_geometry():
    gamma = math.radians(WORM_GAMMA_DEG)
    mx = WORM_MN / math.cos(gamma)
    r1 = WORM_STARTS * mx / math.tan(gamma) / 2
    b2 = 2 * math.sqrt((r1 + mx) ** 2 - r1 ** 2)
    return gamma, mx, r1, b2


def our_wheel_flanks(form: str = "ZA"):
    """Both flanks of wheel tooth 0 (hob = the worm, DIN 3975 proportions)."""
    from toothcontact.surfaces.wheel import WormWheelFlank
    from toothcontact.surfaces.worm import WormFlank

    gamma, mx, r1, b2 = wheel_geometry()
    flanks = {}
    for side in ("left", "right"):
        hob = WormFlank.from_lead_angle(form, WORM_STARTS, gamma, normal_module=WORM_MN,
                                        pressure_angle=math.radians(WORM_ALPHA_DEG),
                                        length=b2 + 4 * math.pi * mx, side=side)
        flanks[side] = WormWheelFlank(hob, WHEEL_TEETH)
    return flanks


class WheelReference:
    """Closest points on the exact wheel flanks of tooth 0 (both sides)."""

    def __init__(self, flanks: dict, n: int = 81):
        from scipy.spatial import cKDTree

        self.flanks = flanks
        self.sides = list(flanks)
        f0 = flanks[self.sides[0]]
        self.tau = 2 * math.pi / f0.teeth
        self.half = f0.face_width / 2
        nodes, normals, labels, uv = [], [], [], []
        for i, side in enumerate(self.sides):
            u, v = flanks[side].grid(n, n)
            s = flanks[side].evaluate(u.ravel(), v.ravel())
            ok = flanks[side].inside_blank(s.points, tol=0.05)
            for k in (-1, 0, 1):  # neighbour teeth too, for the coarse rotation search
                c, sn = math.cos(k * self.tau), math.sin(k * self.tau)
                R = np.array([[c, -sn, 0], [sn, c, 0], [0, 0, 1.0]])
                nodes.append(s.points[ok] @ R.T)
                normals.append(s.normals[ok] @ R.T)
                labels.append(np.full(ok.sum(), 3 * i + (k + 1)))
                uv.append(np.stack([u.ravel()[ok], v.ravel()[ok]], -1))
        self.nodes, self.normals = np.concatenate(nodes), np.concatenate(normals)
        self.labels, self.uv = np.concatenate(labels), np.concatenate(uv)
        self.tree = cKDTree(self.nodes)

    def project(self, side: str, P: np.ndarray, uv0: np.ndarray, iterations: int = 12):
        """Gauss-Newton foot points: (u, v, signed distance, tangential residual)."""
        f = self.flanks[side]
        u, v = uv0[:, 0].copy(), uv0[:, 1].copy()
        for _ in range(iterations):
            s = f.evaluate(u, v)
            r = P - s.points
            a11 = np.einsum("ij,ij->i", s.r_u, s.r_u)
            a12 = np.einsum("ij,ij->i", s.r_u, s.r_v)
            a22 = np.einsum("ij,ij->i", s.r_v, s.r_v)
            b1 = np.einsum("ij,ij->i", s.r_u, r)
            b2 = np.einsum("ij,ij->i", s.r_v, r)
            det = a11 * a22 - a12 * a12
            du, dv = (a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det
            u = np.clip(u + du, -0.2, 1.2)
            v = np.clip(v + dv, -1.2 * self.half, 1.2 * self.half)
        s = f.evaluate(u, v)
        r = P - s.points
        d = np.einsum("ij,ij->i", r, s.normals)
        tangential = np.linalg.norm(r - d[:, None] * s.normals, axis=1)
        return u, v, d, tangential, s.normals

    def deviation(self, P: np.ndarray, N: np.ndarray) -> dict:
        tau = self.tau
        # coarse rotation: the one that puts the sampled flanks nearest the exact grid
        rng = np.random.default_rng(0)
        sub = rng.choice(len(P), size=min(len(P), 2000), replace=False)
        best = (math.inf, 0.0)
        for rho in np.linspace(-tau / 2, tau / 2, 241):
            d, _ = self.tree.query(rotate(P[sub], rho))
            best = min(best, (float(np.median(d)), float(rho)))
        rho = best[1]
        # map the most-sampled peer tooth onto tooth 0 (the grid also holds teeth -1, +1)
        _, idx = self.tree.query(rotate(P[sub], rho))
        counts = np.bincount(self.labels[idx] % 3, minlength=3)
        rho -= (int(np.argmax(counts)) - 1) * tau
        for _ in range(4):  # refine: least squares over both flanks of tooth 0
            Q, M = rotate(P, rho), rotate(N, rho)
            _, idx = self.tree.query(Q)
            label = self.labels[idx]
            keep = (label % 3 == 1) & (np.einsum("ij,ij->i", M, self.normals[idx]) > 0.7)
            parts = []
            for i, side in enumerate(self.sides):
                sel = keep & (label == 3 * i + 1)
                if not np.any(sel):
                    continue
                u, v, d, tan_res, n = self.project(side, Q[sel], self.uv[idx[sel]])
                inside = self.flanks[side].inside_blank(Q[sel], tol=1e-6)
                ok = ((u >= 0) & (u <= 1) & (np.abs(v) <= self.half - END_MARGIN) & inside
                      & (tan_res < 1e-3))
                g = np.einsum("ij,ij->i", n, np.cross([0.0, 0.0, 1.0], Q[sel]))
                parts.append((side, d[ok], g[ok]))
            d_all = np.concatenate([p[1] for p in parts])
            g_all = np.concatenate([p[2] for p in parts])
            step = -float(np.sum(d_all * g_all) / np.sum(g_all * g_all))
            rho += step
            if abs(step) < 1e-9:
                break
        out = stats(d_all)
        out["rotation_deg"] = math.degrees(rho)
        for side, d, _ in parts:
            out[f"mean_{side}_um"] = float(np.mean(d) * 1e3) if d.size else None
            out[f"max_{side}_um"] = float(np.abs(d).max() * 1e3) if d.size else None
        return out


def rotate(P: np.ndarray, rho: float) -> np.ndarray:
    c, s = math.cos(rho), math.sin(rho)
    return P @ np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]]).T


def wheel_deviation(shape, ref: WheelReference) -> dict:
    f = ref.flanks[ref.sides[0]]
    r_lo = f.root_diameter / 2 - 0.5
    P, N = sample_faces(shape, 0.05, 0.75 * ref.tau, r_lo, f.outside_diameter / 2 + 0.5,
                        max_xy=12.0)
    r = np.hypot(P[:, 0], P[:, 1])
    theta = np.arctan2(P[:, 1], P[:, 0])
    n_t = -np.sin(theta) * N[:, 0] + np.cos(theta) * N[:, 1]
    z = P[:, 2] - z_centre(shape)
    keep = (np.abs(n_t) > 0.5) & (np.abs(z) <= ref.half - END_MARGIN) & (r > r_lo)
    P = np.column_stack([P[keep, 0], P[keep, 1], z[keep]])
    return ref.deviation(P, N[keep])


def envelope_check(flank, n: int = 31, window_turns: float = 1.0, samples: int = 4001,
                   offset: float = 0.0) -> dict:
    """Independent check that `flank` is the envelope of its hob: for wheel points on a grid
    (inside the blank), the largest normal penetration of the hob's thread into the point
    over hob angles phi1* ± window_turns·2π (phi1* the generating angle). A true envelope
    gives 0: the hob touches each flank point once and never cuts through it.
    Uses only the hob's axial profile and the machine kinematics (`wheel_from_hob`).
    `offset` (mm) moves the checked points along the flank normal (a self-test: it must
    read back as |offset|)."""
    hob = flank.hob
    others = {"left": "right", "right": "left"}
    from toothcontact.surfaces.worm import WormFlank

    mate = WormFlank(hob.form, hob.starts, hob.axial_module, hob.pitch_diameter,
                     length=hob.length, hand=hob.hand, pressure_angle=hob.pressure_angle,
                     side=others[hob.side], tip_diameter=hob.tip_diameter,
                     root_diameter=hob.root_diameter, wheel_diameter=hob.wheel_diameter)
    left, right = (hob, mate) if hob.side == "left" else (mate, hob)
    p, px = hob.screw_parameter, hob.axial_pitch
    r_root, r_tip = hob.root_diameter / 2, hob.tip_diameter / 2

    u, v = flank.grid(n, n)
    u, v = u.ravel(), v.ravel()
    sample = flank.evaluate(u, v)
    W = sample.points + offset * sample.normals
    ok = flank.inside_blank(sample.points) & (u > 1e-3) & (u < 1 - 1e-3)
    u, v, W = u[ok], v[ok], W[ok]
    _, _, phi_star = flank.generating_parameters(u, v)

    def penetration(phi, pts):  # phi (m, k) hob angles, pts (m, 3) wheel points -> (m, k) mm
        M = flank.wheel_from_hob(phi)  # hob -> wheel: X_w = R·X_h + t
        R, t = M[..., :3, :3], M[..., :3, 3]
        X = np.einsum("mkji,mkj->mki", R, pts[:, None, :] - t)  # R^T (X_w - t)
        rho = np.hypot(X[..., 0], X[..., 1])
        psi = np.arctan2(X[..., 1], X[..., 0])
        rc = np.clip(rho, r_root, r_tip)
        zl = p * psi + np.asarray(left.axial_profile(rc))
        zr = p * psi + np.asarray(right.axial_profile(rc))
        # axial offset from the nearest thread centre line (turns repeat every px), wrapped
        # into [-px/2, px/2): the wrap lies mid-space, far from both flanks
        w = np.mod(X[..., 2] - 0.5 * (zl + zr) + 0.5 * px, px) - 0.5 * px
        eps = 1e-7
        grad = lambda prof, r: np.sqrt(  # noqa: E731
            1 + ((np.asarray(prof(r + eps)) - np.asarray(prof(r - eps))) / (2 * eps)) ** 2
            + (p / r) ** 2)
        # axial depth inside the thread (> 0 inside), to a normal depth via |grad| of
        # z - p·psi - f(r) at the nearer flank
        depth = 0.5 * (zr - zl) - np.abs(w)
        pen = depth / np.where(w < 0, grad(left.axial_profile, rc), grad(right.axial_profile, rc))
        pen = np.where(rho > r_tip, -np.inf, pen)   # beyond the hob tip: no thread
        pen = np.where(rho < r_root, np.inf, pen)   # inside the hob core: cut
        return pen

    offsets = np.linspace(-1.0, 1.0, samples) * window_turns * 2 * math.pi
    worst = np.full(len(W), -np.inf)
    arg = np.zeros(len(W))
    for chunk in np.array_split(np.arange(len(W)), max(1, len(W) // 40)):
        pen = penetration(phi_star[chunk, None] + offsets[None, :], W[chunk])
        j = np.argmax(pen, axis=1)
        worst[chunk], arg[chunk] = pen[np.arange(len(chunk)), j], offsets[j]
    # refine each maximum by golden-section search around the best sample
    h = offsets[1] - offsets[0]
    lo, hi = arg - h, arg + h
    g = (math.sqrt(5) - 1) / 2
    for _ in range(40):
        a, b = hi - g * (hi - lo), lo + g * (hi - lo)
        fa = penetration((phi_star + a)[:, None], W)[:, 0]
        fb = penetration((phi_star + b)[:, None], W)[:, 0]
        hi = np.where(fa > fb, b, hi)
        lo = np.where(fa > fb, lo, a)
    refined = penetration((phi_star + 0.5 * (lo + hi))[:, None], W)[:, 0]
    worst = np.maximum(worst, refined)
    at_contact = penetration(phi_star[:, None], W)[:, 0]
    return {"points": int(len(W)), "max_um": float(np.abs(worst).max() * 1e3),
            "rms_um": float(np.sqrt(np.mean(worst * worst)) * 1e3),
            "max_penetration_um": float(worst.max() * 1e3),
            "min_penetration_um": float(worst.min() * 1e3),
            "at_generating_angle_max_um": float(np.abs(at_contact).max() * 1e3)}


# --- the runs ------------------------------------------------------------------------------------
class _Skip(Exception):
    pass


class HobbingTimeout(BaseException):
    """Raised from wormgear's progress callback (it swallows Exception) to stop the hobbing."""


def row(tool, part, mode, build=None, step=None, dev=None, note="", **extra):
    return {"tool": tool, "part": part, "mode": mode, "build_s": build, "step_s": step,
            "deviation": dev, "note": note, **extra}


def run_spur(tmp: Path, rows: list) -> None:
    gear, mods, form = spur_reference()
    print(f"spur: form radius {form:.4f} mm, tip {gear.tip_radius:.4f} mm", flush=True)

    # ours
    from toothcontact.cad import build_gear, flank_deviation, write_step
    t_build, body = timed(lambda: build_gear(gear, mods), repeat=3)
    t_step, _ = timed(lambda: write_step(body.solid, tmp / "ours_spur.step"), repeat=3)
    dev = spur_deviation(body.solid, gear, mods, form)
    rows.append(row("toothcontact", "spur", "B-spline loft, exact fit points", t_build, t_step,
                    dev, f"own flank_deviation() {flank_deviation(body) * 1e3:.3f} µm"))

    # py-gearworks: crowning c gives a parabolic end drop of c·1e-3·m·cos(alpha)
    try:
        import build123d as bd
        import py_gearworks as pgw

        h = (0.5 * SPUR_FACE) ** 2 / (2 * SPUR_CROWN_RADIUS)
        c = h / (1e-3 * SPUR_MODULE * math.cos(math.radians(SPUR_ALPHA_DEG)))

        def build():
            g = pgw.SpurGear(number_of_teeth=SPUR_TEETH, module=SPUR_MODULE, height=SPUR_FACE,
                             pressure_angle=math.radians(SPUR_ALPHA_DEG), crowning=c,
                             dedendum_coefficient=1.25)
            return g.build_part()

        t_build, part = timed(build, repeat=3)
        t_step, _ = timed(lambda: bd.export_step(part, str(tmp / "gw_spur.step")), repeat=3)
        dev = spur_deviation(part.wrapped, gear, mods, form)
        rows.append(row("py-gearworks", "spur", f"SpurGear(crowning={c:.3f})", t_build, t_step,
                        dev, "crown LOST: a symmetric crown has equal end sections, so "
                        "GearBuilder.is_prismatic() extrudes the end section (whole flank "
                        "thinned by the end drop)"))
        # the same with is_prismatic() forced False (a runtime patch, not shipped behaviour):
        # what its lofted surfaces achieve when the crown is kept
        from py_gearworks import conv_build123d
        shipped = conv_build123d.GearBuilder.is_prismatic
        conv_build123d.GearBuilder.is_prismatic = lambda self, tol=1e-7: False
        try:
            t_build, part = timed(build, repeat=3)
            t_step, _ = timed(lambda: bd.export_step(part, str(tmp / "gw_spur2.step")), repeat=3)
        finally:
            conv_build123d.GearBuilder.is_prismatic = shipped
        dev = spur_deviation(part.wrapped, gear, mods, form)
        rows.append(row("py-gearworks", "spur", "same, is_prismatic patched to False", t_build,
                        t_step, dev, "runtime patch, not shipped behaviour: loft through 3 "
                        "sections keeps the parabolic crown"))
    except Exception as exc:  # noqa: BLE001
        rows.append(row("py-gearworks", "spur", "SpurGear", note=f"failed: {exc!r}"))
        traceback.print_exc()

    # cq_gears: no crowning
    try:
        sys.path.insert(0, CQ_GEARS_PATH)
        import cq_gears

        def build():
            return cq_gears.SpurGear(module=SPUR_MODULE, teeth_number=SPUR_TEETH,
                                     width=SPUR_FACE, pressure_angle=SPUR_ALPHA_DEG).build()

        t_build, solid = timed(build, repeat=3)
        t_step, _ = timed(lambda: solid.exportStep(str(tmp / "cqg_spur.step")), repeat=3)
        dev_crowned = spur_deviation(solid.wrapped, gear, mods, form)
        from toothcontact.surfaces.modify import FlankModifications
        dev = spur_deviation(solid.wrapped, gear, FlankModifications(), form)
        rows.append(row("cq_gears", "spur", "SpurGear (no crowning option)", t_build, t_step,
                        dev, "deviation from the UNcrowned involute (it cannot crown); "
                        f"from the crowned one: max {dev_crowned['max_um']:.1f} µm",
                        deviation_from_crowned=dev_crowned))
    except Exception as exc:  # noqa: BLE001
        rows.append(row("cq_gears", "spur", "SpurGear", note=f"not installable here: {exc!r}"))
        traceback.print_exc()

    rows.append(row("wormgear", "spur", "-", note="no spur gears (worm pairs only)"))


def run_wheel(tmp: Path, rows: list, hobbing_steps: int, hobbing_limit: float) -> None:
    gamma, mx, r1, b2 = wheel_geometry()
    print(f"wheel: mx {mx:.5f} mm, d1 {2 * r1:.4f} mm, d2 {WHEEL_TEETH * mx:.4f} mm, "
          f"b2 {b2:.4f} mm", flush=True)
    try:
        import toothcontact.surfaces.wheel  # noqa: F401
        have_wheel = True
    except ImportError as exc:
        have_wheel = False
        print(f"toothcontact.surfaces.wheel not importable ({exc}): wheel deviations skipped")

    ref = None
    if have_wheel:
        def ours():
            flanks = our_wheel_flanks("ZA")
            for f in flanks.values():
                u, v = f.grid(201, 201)
                f.evaluate(u, v)
            return flanks

        t_ours, flanks = timed(ours, repeat=3)
        env = envelope_check(flanks["left"])
        env_r = envelope_check(flanks["right"])
        worst = env if env["max_um"] >= env_r["max_um"] else env_r
        probe = envelope_check(flanks["left"], offset=0.001)["max_um"]  # must read 1 µm
        rows.append(row("toothcontact", "worm wheel", "exact envelope flanks, 2×201² grid",
                        t_ours, None, worst,
                        "surfaces only, no solid (STEP n/a); deviation = independent "
                        f"envelope check (hob penetration; a +1 µm offset reads {probe:.4f} µm)",
                        envelope_left=env, envelope_right=env_r, envelope_probe_1um=probe))
        ref = WheelReference(flanks)
        try:
            ref_zn = WheelReference(our_wheel_flanks("ZN"))
        except Exception:  # noqa: BLE001
            ref_zn = None
        try:  # our wheel solid (toothcontact.cad.build_wheel), when the project has it
            from toothcontact.cad import build_wheel, write_step

            def solid():
                fl = our_wheel_flanks("ZA")
                return build_wheel(fl["left"], fl["right"])

            t_solid, body = timed(solid, repeat=2)
            t_step, _ = timed(lambda: write_step(body.solid, tmp / "ours_wheel.step"))
            dev = wheel_deviation(body.solid, ref)
            rows.append(row("toothcontact", "worm wheel", "B-spline solid, all teeth (build_wheel)",
                            t_solid, t_step, dev,
                            f"own flank_deviation() {body.flank_deviation() * 1e3:.3f} µm; "
                            "flanks + loft", baseline=True))
        except ImportError:
            rows.append(row("toothcontact", "worm wheel", "B-spline solid",
                            note="n/a (not built yet: no toothcontact.cad.build_wheel)"))
    else:
        rows.append(row("toothcontact", "worm wheel", "exact envelope flanks",
                        note="n/a (toothcontact.surfaces.wheel not importable)"))
        ref_zn = None

    def deviation(part):
        if ref is None:
            return None, None
        out = []
        for r in (ref, ref_zn):
            try:
                out.append(wheel_deviation(part.wrapped, r) if r is not None else None)
            except Exception as exc:  # noqa: BLE001 - keep the timings of the row
                traceback.print_exc()
                out.append({"error": repr(exc)})
        return tuple(out)

    try:
        import build123d as bd
        from wormgear import WormGear, WormWheel
        from wormgear.advanced import virtual_hobbing

        common = dict(module=mx, num_teeth=WHEEL_TEETH, face_width=b2,
                      worm_num_starts=WORM_STARTS, worm_target_lead_angle=WORM_GAMMA_DEG,
                      pressure_angle=WORM_ALPHA_DEG, profile="ZA")
        seed, t_seed = None, None
        for mode, kw in (("WormWheel helical (fastest)", {}),
                         ("WormWheel throated", {"throated": True})):
            t_build, part = timed(lambda: WormWheel(**common, **kw))
            if seed is None:
                seed, t_seed = part, t_build
            name = "wg_wheel_throated.step" if kw else "wg_wheel_helical.step"
            t_step, _ = timed(lambda: bd.export_step(part, str(tmp / name)))
            dev, dev_zn = deviation(part)
            rows.append(row("wormgear", "worm wheel", mode, t_build, t_step, dev,
                            "twisted trapezoid loft, not an envelope", deviation_vs_ZN=dev_zn))
            print(f"  wormgear {mode}: {t_build:.1f} s", flush=True)

        t_worm, worm = timed(lambda: WormGear(module=mx, num_starts=WORM_STARTS, length=b2 + 10,
                                              target_lead_angle=WORM_GAMMA_DEG,
                                              ratio=WHEEL_TEETH // WORM_STARTS,
                                              pressure_angle=WORM_ALPHA_DEG, profile="ZA"))
        progress = []
        start = time.perf_counter()

        def callback(message, percent):
            progress.append((time.perf_counter() - start, percent))
            if time.perf_counter() - start > hobbing_limit and percent < 100:
                raise HobbingTimeout()

        mode = f"virtual_hobbing(steps={hobbing_steps}) (most accurate run)"
        if hobbing_steps <= 0:
            raise _Skip()
        try:
            start = time.perf_counter()
            part = virtual_hobbing(worm, seed, steps=hobbing_steps, progress_callback=callback)
            t_build = time.perf_counter() - start
            t_step, _ = timed(lambda: bd.export_step(part, str(tmp / "wg_hobbed.step")))
            dev, dev_zn = deviation(part)
            per_step = t_build / hobbing_steps
            rows.append(row("wormgear", "worm wheel", mode, t_build, t_step, dev,
                            f"boolean cuts every {360 / hobbing_steps:g}° of wheel turn; "
                            f"'ultra' 360 steps ≥ {per_step * 360:.0f} s by linear extrapolation",
                            deviation_vs_ZN=dev_zn, prerequisite_s={"seed WormWheel": t_seed,
                                                            "WormGear": t_worm},
                            progress=progress))
        except HobbingTimeout:
            elapsed, reached = progress[-1] if progress else (hobbing_limit, 0.0)
            estimate = elapsed / (reached / 100) if reached > 0 else None
            rows.append(row("wormgear", "worm wheel", mode, None, None, None,
                            f"stopped at the {hobbing_limit:g} s limit, {reached:.0f} % done"
                            + (f" (≈ {estimate:.0f} s in all at that rate)" if estimate else ""),
                            progress=progress, estimated_build_s=estimate))
        print(f"  wormgear hobbing: {rows[-1]['build_s']}", flush=True)
    except _Skip:
        pass
    except Exception as exc:  # noqa: BLE001
        rows.append(row("wormgear", "worm wheel", "-", note=f"failed: {exc!r}"))
        traceback.print_exc()

    # py-gearworks has no worm-wheel type: the usual stand-in is a helical involute gear with
    # the wheel's pitch diameter (mn, beta = gamma) and the ZA mid-plane profile angle
    # (alpha_t = 20 deg); exact only in the mid-plane
    try:
        import build123d as bd
        import py_gearworks as pgw

        alpha_n = math.atan(math.tan(math.radians(WORM_ALPHA_DEG)) * math.cos(gamma))

        def build():
            g = pgw.HelicalGear(number_of_teeth=WHEEL_TEETH, helix_angle=gamma, module=WORM_MN,
                                height=b2, pressure_angle=alpha_n, z_anchor=0.5,
                                dedendum_coefficient=1.2)
            return g.build_part()

        t_build, part = timed(build, repeat=3)
        t_step, _ = timed(lambda: bd.export_step(part, str(tmp / "gw_helical_wheel.step")))
        dev, dev_zn = deviation(part)
        rows.append(row("py-gearworks", "worm wheel", "HelicalGear stand-in (no wheel type)",
                        t_build, t_step, dev, "helical involute, beta = 4.1°, alpha_t = 20°: "
                        "not an envelope (exact in the mid-plane only)", deviation_vs_ZN=dev_zn))
    except Exception as exc:  # noqa: BLE001
        rows.append(row("py-gearworks", "worm wheel", "-", note=f"no worm-wheel type; "
                        f"helical stand-in failed: {exc!r}"))
        traceback.print_exc()
    rows.append(row("cq_gears", "worm wheel", "-",
                    note="no worm-wheel type (Worm and crossed helical gears only)"))


def ratios(rows: list) -> None:
    """ratio = peer build time / toothcontact build time of the same part (our solid where
    we build one, else our exact flank generation)."""
    ours = {}
    for r in rows:
        if r["tool"] == "toothcontact" and r["build_s"] and (r.get("baseline")
                                                              or r["part"] not in ours):
            ours[r["part"]] = r["build_s"]
    for r in rows:
        base = ours.get(r["part"])
        r["ratio"] = (r["build_s"] / base) if (r["build_s"] and base) else None


def fmt(x, spec):
    if x is None:
        width = int(spec.split(".")[0] or 0)
        return "—".rjust(width)
    return format(x, spec)


def print_table(rows: list) -> None:
    head = (f"{'tool':13} {'part':10} {'mode':48} {'build s':>8} {'STEP s':>7} "
            f"{'max µm':>8} {'rms µm':>8} {'ratio':>6}")
    print("\n" + head + "\n" + "-" * len(head))
    for r in rows:
        dev = r["deviation"] or {}
        step = "n/a" if (r["tool"] == "toothcontact" and r["step_s"] is None) else \
            fmt(r["step_s"], "7.2f")
        print(f"{r['tool']:13} {r['part']:10} {r['mode'][:48]:48} {fmt(r['build_s'], '8.2f')} "
              f"{step:>7} {fmt(dev.get('max_um'), '8.2f')} {fmt(dev.get('rms_um'), '8.2f')} "
              f"{fmt(r['ratio'], '6.1f')}")
        if r["note"]:
            print(f"{'':13} {'':10} └ {r['note']}")
    print("ratio = peer build time / toothcontact build time of the same part (our solid; "
          "our exact flanks where no solid is built)")


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--hobbing-steps", type=int, default=36,
                        help="wormgear virtual_hobbing steps per wheel turn (default 36, its "
                             "'preview' preset; 72 = its default 'balanced' takes ~750 s here; "
                             "0 skips it)")
    parser.add_argument("--hobbing-limit", type=float, default=600.0,
                        help="stop wormgear's hobbing after this many seconds (default 600)")
    parser.add_argument("--keep-step", metavar="DIR",
                        help="keep the exported STEP files in DIR (default: a temp dir)")
    parser.add_argument("--skip-wheel", action="store_true")
    parser.add_argument("--skip-spur", action="store_true")
    args = parser.parse_args(argv)

    import logging
    import warnings
    logging.disable(logging.WARNING)
    warnings.filterwarnings("ignore")

    started = time.perf_counter()
    rows: list = []
    with tempfile.TemporaryDirectory() as tmp:
        out_dir = Path(args.keep_step) if args.keep_step else Path(tmp)
        out_dir.mkdir(parents=True, exist_ok=True)
        if not args.skip_spur:
            run_spur(out_dir, rows)
        if not args.skip_wheel:
            run_wheel(out_dir, rows, args.hobbing_steps, args.hobbing_limit)
    ratios(rows)
    print_table(rows)

    summary = {}
    wheel_rows = [r for r in rows if r["tool"] == "toothcontact" and r["part"] == "worm wheel"
                  and r["build_s"]]
    wheel_ours = next((r for r in wheel_rows if r.get("baseline")), wheel_rows[0] if wheel_rows
                      else None)
    wheel_flanks = wheel_rows[0] if wheel_rows else None
    hobbed = next((r for r in rows if r["mode"].startswith("virtual_hobbing") and r["build_s"]),
                  None)
    if wheel_ours and hobbed:
        summary["wheel_speedup_vs_wormgear_most_accurate"] = hobbed["build_s"] / wheel_ours["build_s"]
        summary["wheel_speedup_target"] = 5.0
    if wheel_ours and wheel_ours["deviation"]:
        summary["wheel_solid_deviation_um"] = wheel_ours["deviation"]["max_um"]
    if wheel_flanks and wheel_flanks["deviation"]:
        summary["wheel_envelope_error_um"] = wheel_flanks["deviation"]["max_um"]
        summary["wheel_envelope_target_um"] = 1.0
    for key, value in summary.items():
        print(f"{key}: {value:.3g}")
    total = time.perf_counter() - started
    print(f"total run time {total:.0f} s")
    JSON_OUT.write_text(json.dumps({"versions": versions(), "rows": rows, "summary": summary,
                                    "run_s": total, "hobbing_steps": args.hobbing_steps},
                                   indent=2, default=float) + "\n")
    print(f"wrote {JSON_OUT}")


if __name__ == "__main__":
    main()
