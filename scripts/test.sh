#!/usr/bin/env bash
# One command from a fresh Debian machine to a tested build: installs what is missing, builds, and
# runs the whole CTest suite (unit, integration, docs). Extra arguments go to ctest (e.g. -L unit).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
cd build
ctest --output-on-failure -j "$(nproc)" "$@"
