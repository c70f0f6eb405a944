"""Post-processing of mpmshock run directories: a reader (SI units throughout) and the paper's plots.

The package is used installed, never by editing sys.path:

- `cmake --install build --prefix P` puts it in P/lib/mpmshock/python:
  `export PYTHONPATH=P/lib/mpmshock/python`;
- `pip install scripts` (from the repository root) where pip is available;
- in a checkout, with Debian's /usr/bin/python3 and no pip: `PYTHONPATH=scripts`.

From a notebook:

    import mpmshock_post
    from mpmshock_post import reader
    mpmshock_post.__version__                 # '0.2.0', the simulator's version too
    run = reader.Run("output/paper_base")
    run.regions()["B800"]["pressure_mean"]    # Pa, one value per sample
    run.regions().to_pandas()                 # with pandas installed (optional)

The plotting modules (timeseries, field, hist, compare, probes) return matplotlib Figures in the
paper's units (g/cm3, GPa, K, m/s, ns, um); the command line `mpmshock-plot` drives them.
"""

from ._version import __version__
from .errors import PostError
from .reader import Run, Snapshot

__all__ = ["PostError", "Run", "Snapshot", "__version__"]
