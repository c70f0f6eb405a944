#!/usr/bin/env bash
# The quick paper campaign (docs/reproducing-the-paper.md): every case in both temperature models,
# then every figure and a comparison row for every claim, none of them "not run". About 5-6 minutes
# and 3 GB here, so it is registered only with -DMPMSHOCK_PAPER_TEST=ON (ctest -L paper).
# Usage: paper_quick_test.sh MPMSHOCK OUT_DIR
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
export MPMSHOCK="$1" OMP_WAIT_POLICY=PASSIVE
out="$2"
"$root/studies/paper/reproduce-paper" --quick --out "$out"
for n in 01 02 03 04 05 06 07 08 09 10 11 12 13; do
  [ -s "$out/fig$n.png" ] || { echo "FAILED: $out/fig$n.png was not made"; exit 1; }
done
rows=$(($(wc -l < "$out/comparison.csv") - 1))
[ "$rows" -ge 80 ] || { echo "FAILED: comparison.csv has $rows rows, expected a row for each of the paper's claims (80+)"; exit 1; }
if grep -q 'not run' "$out/comparison.csv"; then
  echo "FAILED: comparison.csv has rows whose run is missing:"; grep 'not run' "$out/comparison.csv"; exit 1
fi
echo "paper quick campaign: 13 figures, $rows comparison rows in $out"
