"""CAD views of the exact flanks: B-spline solids (OCP, the kernel of CadQuery) -> STEP,
tessellation -> STL. Everything here imports OCP, so it is loaded only by the commands that
write or check solids."""

from .files import is_valid, read_step, tessellate, volume, write_mesh, write_step
from .gear import RING_RIM_MODULES, GearBody, build_gear
from .loft import flank_deviation
from .parts import SOLID_KINDS, build_parts
from .wheel import WheelBody, build_wheel
from .worm import WormBody, build_worm, worm_flank_deviation

__all__ = ["GearBody", "RING_RIM_MODULES", "SOLID_KINDS", "build_parts", "WheelBody", "WormBody",
           "build_gear", "build_wheel", "build_worm", "flank_deviation", "is_valid", "read_step",
           "tessellate", "volume", "worm_flank_deviation", "write_mesh", "write_step"]
