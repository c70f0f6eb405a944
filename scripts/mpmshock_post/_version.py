"""The one version number of mpmshock: this package's, and the simulator's (CMake reads this file)."""

__version__ = "0.2.0"
