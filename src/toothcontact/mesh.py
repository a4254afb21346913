"""Triangle meshes of positioned bodies, and interference between them (python-fcl).

The separation search sees only the two active flanks; a tooth tip digging into the mate's
root, or a neighbouring tooth touching its back flank, is found here instead: the bodies are
tessellated from their B-spline solids, placed by their frames, and collided as BVH models.
Units: mm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Interference:
    """Where two placed meshes overlap: contact points (mm, world) and how many there are."""

    points: np.ndarray

    @property
    def found(self) -> bool:
        return len(self.points) > 0


def placed_model(vertices: np.ndarray, faces: np.ndarray, R: np.ndarray, origin: np.ndarray):
    """An fcl collision object of a triangle mesh placed by world = R·local + origin."""
    import fcl

    model = fcl.BVHModel()
    model.beginModel(len(vertices), len(faces))
    model.addSubModel(np.asarray(vertices, float), np.asarray(faces, np.int32))
    model.endModel()
    return fcl.CollisionObject(model, fcl.Transform(np.asarray(R, float), np.asarray(origin, float)))


def interference(a, b, max_points: int = 50) -> Interference:
    """Overlap of two placed collision objects (see `placed_model`)."""
    import fcl

    request = fcl.CollisionRequest(num_max_contacts=max_points, enable_contact=True)
    result = fcl.CollisionResult()
    fcl.collide(a, b, request, result)
    points = np.array([c.pos for c in result.contacts], float).reshape(-1, 3)
    return Interference(points)


def clearance(a, b) -> float:
    """Least distance (mm) between two placed collision objects that do not overlap."""
    import fcl

    result = fcl.DistanceResult()
    return float(fcl.distance(a, b, fcl.DistanceRequest(enable_nearest_points=True), result))
