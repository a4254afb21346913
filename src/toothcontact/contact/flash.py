"""Flash temperature of a sliding contact: Blok's surface temperature rise under the frictional
heat of the solved pressure field, each surface moving through the heat source.

Each surface point crosses the contact fast (Peclet number v·b/(2κ) well above 1 for gear
teeth: heat flows into the body normal to the surface only), so a surface moving at speed V
across the source sees θ(y) = 1/(B·sqrt(π·V))·∫ q(η)/sqrt(y - η) dη over the flux q met
upstream (Jaeger, Proc. R. Soc. N.S.W. 76 (1942); Carslaw & Jaeger §10.7), B = sqrt(λρc) its
thermal contact coefficient. The heat μ·p·v_s divides between the bodies so that their
largest temperatures are equal (Blok, 1937). The flux is integrated across the contact
(along the field's second axis) with each body's speed across it: for a contact line that
the motion crosses obliquely this is the same time under the source. Units: W/m², m/s, mm,
W·s^0.5/(m²·K), K."""

from __future__ import annotations

import numpy as np

#: a steel's thermal contact coefficient sqrt(λρc) (W·s^0.5/(m²·K)): λ = 45 W/(m·K),
#: ρ = 7850 kg/m³, c = 460 J/(kg·K)
STEEL_CONTACT_COEFFICIENT = float(np.sqrt(45.0 * 7850.0 * 460.0))


def _upstream_weights(ny: int, dy: float) -> np.ndarray:
    """(ny, ny) weights W[j, m] = ∫ over cell m upstream of cell j's centre of
    (y_j - η)^-1/2 dη (m^0.5) on cells of size dy (m), the surface moving toward +y."""
    j = np.arange(ny)[:, None]
    m = np.arange(ny)[None, :]
    far = np.clip((j - m + 0.5) * dy, 0.0, None)
    near = np.clip((j - m - 0.5) * dy, 0.0, None)
    return 2.0 * (np.sqrt(far) - np.sqrt(near))


def surface_rise(flux: np.ndarray, dy_mm: float, speed: np.ndarray, B: float) -> np.ndarray:
    """The temperature rise (K) of one body's surface on the field (nx, ny) under the heat
    flux `flux` (W/m², per cell) it takes, the body crossing the field along its second axis
    at `speed` (m/s per cell, signed: > 0 toward +y)."""
    W = _upstream_weights(flux.shape[1], dy_mm * 1e-3)
    forward = flux @ W.T
    backward = (flux[:, ::-1] @ W.T)[:, ::-1]
    V = np.abs(speed)
    with np.errstate(divide="ignore", invalid="ignore"):
        rise = np.where(speed >= 0.0, forward, backward) / (B * np.sqrt(np.pi * V))
    return np.where(V > 0.0, rise, np.inf)


def flash_temperature(flux: np.ndarray, dy_mm: float, speeds: tuple[np.ndarray, np.ndarray],
                      coefficients: tuple[float, float]) -> float:
    """The flash temperature (K) of a contact: the largest rise of both surfaces with the
    heat divided so that their largest rises are equal (Blok): T1·T2/(T1 + T2) of the rises
    either body would take with all the heat; 0 with no heat."""
    if not np.any(flux > 0.0):
        return 0.0
    rises = [float(np.max(surface_rise(flux, dy_mm, V, B)))
             for V, B in zip(speeds, coefficients)]
    if np.isinf(rises[0]) or np.isinf(rises[1]):
        return min(rises)
    return rises[0] * rises[1] / (rises[0] + rises[1])
