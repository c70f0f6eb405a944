#!/usr/bin/env bash
# The README documents every scene key the program knows, and every regions.csv column.
# usage: docs_test.sh MPMSHOCK_BINARY README
set -u
bin=$1
readme=$2
failures=0
for key in $("$bin" --keys | sed -n 's/^| `\([a-zA-Z_.A-Z]*\)`.*/\1/p'); do
  grep -q "\`$key\`" "$readme" || { echo "FAILED: README does not document key '$key'" >&2; failures=$((failures + 1)); }
done
for column in time region count density_mean density_std pressure_mean pressure_std temperature_mean \
  temperature_std velocity_x_mean velocity_x_std velocity_y_mean velocity_y_std rot2_mean div2_mean \
  strain_rate2_mean; do
  grep -q "\`$column\`" "$readme" || { echo "FAILED: README does not document column '$column'" >&2; failures=$((failures + 1)); }
done
if [ "$failures" -eq 0 ]; then echo "all checks passed"; else exit 1; fi
