#!/usr/bin/env bash
# One command from a fresh Debian machine to a finished run: installs what is missing, builds,
# and runs the small default scene (configs/default.scene) into output/default.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
build/src/mpmshock configs/default.scene --force "$@"
