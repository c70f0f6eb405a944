"""Post-processing of mpmshock run directories: a reader (SI units throughout) and the paper's plots.

From a notebook:

    import sys
    sys.path.insert(0, "/path/to/mpmshock/scripts")
    from mpmshock_post import reader
    run = reader.Run("output/paper_base")

The plotting modules (timeseries, field, hist, compare) return matplotlib Figures in the paper's
units (g/cm3, GPa, K, m/s, ns, um); the command line `scripts/mpmshock-plot` drives them.
"""

from .errors import PostError
from .reader import Run, Snapshot

__all__ = ["PostError", "Run", "Snapshot"]
