"""toothcontact: geometric tooth-contact analysis of gears under misalignment and deflection."""

from .memory import keep_freed_memory

__version__ = "0.1.0"

keep_freed_memory()
