#!/usr/bin/env bash
# Installs the Debian packages mpmshock needs, if any are missing (apt-get; uses sudo when not root).
set -euo pipefail
packages=(build-essential cmake git libeigen3-dev libhdf5-dev hdf5-tools libopenmpi-dev openmpi-bin nlohmann-json3-dev
          python3 python3-numpy
          python3-h5py python3-matplotlib python3-pytest python3-pandas python3-xarray)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "installing: ${missing[*]}" >&2
sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
