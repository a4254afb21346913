"""Flash temperature of a sliding contact: Blok's surface temperature rise under the frictional
heat of the solved pressure field, each surface moving through the heat source.

Each surface point crosses the contact fast (Peclet number v·b/(2κ) well above 1 for gear
teeth: heat flows into the body normal to the surface only), so a surface moving at speed V
sees θ(s) = 1/(B·sqrt(π·V))·∫ q(σ)/sqrt(s - σ) dσ over the flux q met upstream along its
path (Jaeger, Proc. R. Soc. N.S.W. 76 (1942); Carslaw & Jaeger §10.7), B = sqrt(λρc) its
thermal contact coefficient. The paths are straight lines along the surface's mean
direction of motion over the contact (the flux resampled bilinearly on a grid along them,
as fine along a path as the field's finer spacing, the paths as far apart as its coarser
one), at each point's own speed. The heat μ·p·v_s divides between the bodies so that their largest
temperatures are equal (Blok, 1937). Units: W/m², m/s, mm, W·s^0.5/(m²·K), K."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from scipy.ndimage import map_coordinates
from scipy.signal import oaconvolve

#: a steel's thermal contact coefficient sqrt(λρc) (W·s^0.5/(m²·K)): λ = 45 W/(m·K),
#: ρ = 7850 kg/m³, c = 460 J/(kg·K)
STEEL_CONTACT_COEFFICIENT = float(np.sqrt(45.0 * 7850.0 * 460.0))

#: a body's surface velocity (m/s) in the field's plane, (vx, vy) along its axes, at field
#: points (x, y) (mm)
Velocity = Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]


def _upstream_kernel(n: int, step: float) -> np.ndarray:
    """(n,) weights k[i] = ∫ over the cell i cells upstream of a cell's centre of
    (s - σ)^-1/2 dσ (m^0.5) on cells of `step` (m), the surface moving toward +s: a cell's
    rise is Σ_m q[m]·k[j - m], a causal convolution along the path."""
    i = np.arange(n)
    return 2.0 * (np.sqrt((i + 0.5) * step) - np.sqrt(np.clip((i - 0.5) * step, 0.0, None)))


def surface_rise(flux: np.ndarray, x: np.ndarray, y: np.ndarray, velocity: Velocity,
                 B: float) -> float:
    """The largest temperature rise (K) of one body's surface taking all the heat `flux`
    (W/m² on the field's (nx, ny) cells at x, y, mm), the body moving at `velocity`: along
    straight paths in its flux-weighted mean direction, each point at its own speed; inf
    where the surface stands still in the heat."""
    X, Y = np.meshgrid(x, y, indexing="ij")
    hot = flux > 0.0
    vx, vy = velocity(X[hot], Y[hot])
    weight = flux[hot] / flux[hot].max()     # scaled: a tiny flux's squares would underflow
    d = np.array([np.sum(weight * vx), np.sum(weight * vy)])
    if not np.linalg.norm(d) > 0.0:
        return np.inf
    d /= np.linalg.norm(d)
    dx, dy = float(x[1] - x[0]), float(y[1] - y[0])
    # along the path as fine as the field's finer spacing; across paths its coarser one
    step, spacing = min(dx, dy), max(dx, dy)
    s_hot = X[hot] * d[0] + Y[hot] * d[1]
    t_hot = -X[hot] * d[1] + Y[hot] * d[0]
    pad = 2.0 * max(dx, dy)
    s = np.arange(s_hot.min() - pad, s_hot.max() + pad + step, step)
    t = np.arange(t_hot.min() - pad, t_hot.max() + pad + spacing, spacing)
    S, T = np.meshgrid(s, t, indexing="ij")
    xs, ys = S * d[0] - T * d[1], S * d[1] + T * d[0]
    sampled = map_coordinates(flux, [(xs - x[0]) / dx, (ys - y[0]) / dy], order=1,
                              cval=0.0)
    # each path's rise: its flux convolved with the upstream kernel (by FFT: a long line
    # contact's paths run to thousands of cells)
    heated = oaconvolve(sampled.T, _upstream_kernel(len(s), step * 1e-3)[None, :],
                        axes=1)[:, :len(s)]                                  # (nt, ns)
    ux, uy = velocity(xs, ys)
    speed = (ux * d[0] + uy * d[1]).T
    inside = sampled.T > 0.0
    if np.any(inside & (speed <= 0.0)):
        return np.inf
    return float(np.max(np.where(inside, heated, 0.0) / (B * np.sqrt(np.pi * np.where(
        speed > 0.0, speed, 1.0)))))


def flash_temperature(flux: np.ndarray, x: np.ndarray, y: np.ndarray,
                      bodies: tuple[tuple[Velocity, float], tuple[Velocity, float]]) -> float:
    """The flash temperature (K) of a contact: the largest rise of both surfaces with the
    heat divided so that their largest rises are equal (Blok): T1·T2/(T1 + T2) of the rises
    either body would take with all the heat; 0 with no heat. `bodies`: each surface's
    velocity and thermal contact coefficient."""
    if not np.any(flux > 0.0):
        return 0.0
    rises = [surface_rise(flux, x, y, velocity, B) for velocity, B in bodies]
    if np.isinf(rises[0]) or np.isinf(rises[1]):
        return min(rises)
    return rises[0] * rises[1] / (rises[0] + rises[1])
