"""The studies run inside a checkout of mpmshock (they are the project's own campaigns, not part of
the installed package): this puts the checkout's package (scripts/mpmshock_post) on the path when
no installed one is importable, and names the checkout's build (build/src/mpmshock) as the simulator
when neither $MPMSHOCK nor PATH names one. Every entry script of studies/ imports it first."""

import importlib.util
import os
import shutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]   # the checkout
STUDIES = ROOT / "studies"

if importlib.util.find_spec("mpmshock_post") is None:
    sys.path.insert(1, str(ROOT / "scripts"))
if not os.environ.get("MPMSHOCK") and not shutil.which("mpmshock") and (ROOT / "build/src/mpmshock").is_file():
    os.environ["MPMSHOCK"] = str(ROOT / "build/src/mpmshock")
