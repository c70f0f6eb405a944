"""Post-processing of mpmshock run directories: a reader (SI units throughout) and the paper's plots.

Install it where pip is available (`pip install -e scripts`, which also installs the
`mpmshock-plot` command), or, with Debian's /usr/bin/python3 and no pip, start Python in scripts/
or put scripts/ on PYTHONPATH. From a notebook:

    from mpmshock_post import reader
    run = reader.Run("output/paper_base")

The plotting modules (timeseries, field, hist, compare, probes) return matplotlib Figures in the
paper's units (g/cm3, GPa, K, m/s, ns, um); the command line `scripts/mpmshock-plot` drives them.
"""

from .errors import PostError
from .reader import Run, Snapshot

__all__ = ["PostError", "Run", "Snapshot"]
