"""toothcontact: geometric tooth-contact analysis of gears under misalignment and deflection."""

__version__ = "0.2.0"
