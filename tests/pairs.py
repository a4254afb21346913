"""A spur pair placed and run through the contact cycle: the tests' common set-up."""

import math

from toothcontact import gearset
from toothcontact.analytic.hertz import compliance
from toothcontact.surfaces.placement import Misalignment
from toothcontact.case import parse_case
from toothcontact.contact.cycle import CycleSettings, parallel_cycle

STEEL = compliance(206000.0, 0.3, 206000.0, 0.3)


def spur_cycle(case: dict, slope: float = 0.0, positions: int = 3):
    """The pair of a spur case table and its contact cycle under `slope` (rad) at 8000 N
    tangential load, steel: (gearset.GearPair, contact.cycle.ContactCycle)."""
    pair = gearset.gear_pair(parse_case(case))
    mesh = pair.placed(Misalignment(slope=slope))
    pinion = gearset.working_flank(pair.pinion, pair.pinion_modifications, 1)
    gear = gearset.working_flank(pair.gear, pair.gear_modifications, mesh.gear_side)
    load = 8000.0 / math.cos(pair.working_pressure_angle)
    return pair, parallel_cycle(mesh, pinion, gear, load, STEEL, CycleSettings(positions=positions))
