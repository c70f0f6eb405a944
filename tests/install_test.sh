#!/usr/bin/env bash
# cmake --install gives a working prefix: the program, the Python commands and a CMake package
# that a project outside the tree builds against.
# usage: install_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAILED: $*" >&2; exit 1; }
prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" >"$work/install.log" || fail "cmake --install: $(tail -5 "$work/install.log")"
for f in bin/mpmshock bin/mpmshock-plot bin/mpmshock-converge include/mpmshock/scene.hpp include/mpmshock/version.hpp \
         share/man/man1/mpmshock.1 share/mpmshock/configs/default.scene lib/mpmshock/python/mpmshock_post/reader.py; do
  [ -e "$prefix/$f" ] || fail "$f was not installed"
done
ls "$prefix"/lib*/cmake/mpmshock/mpmshockConfig.cmake >/dev/null 2>&1 || ls "$prefix"/lib/*/cmake/mpmshock/mpmshockConfig.cmake >/dev/null \
  || fail "no mpmshockConfig.cmake"
"$prefix/bin/mpmshock" --version | grep -q "^mpmshock [0-9]" || fail "installed mpmshock --version"
# The installed commands run from anywhere, with the installed package and simulator.
cd "$work"
"$prefix/bin/mpmshock" "$prefix/share/mpmshock/configs/default.scene" --set output_dir=run --set "end_time=5 ns" \
  --set cell_size=20um --quiet >run.out 2>&1 || fail "installed mpmshock: $(cat run.out)"
[ -s run/log.txt ] || fail "the run wrote no log.txt"
env -u PYTHONPATH "$prefix/bin/mpmshock-plot" timeseries run --output plot.png >plot.out 2>&1 || fail "installed mpmshock-plot: $(cat plot.out)"
[ -s plot.png ] || fail "mpmshock-plot wrote no plot.png"
env -u PYTHONPATH PYTHONPATH="$prefix/lib/mpmshock/python" /usr/bin/python3 -c \
  "import mpmshock_post, sys; sys.exit(0 if mpmshock_post.__version__ else 1)" || fail "import mpmshock_post"
# The installed mpmshock-converge resolves scenes through the installed simulator (no $MPMSHOCK, no
# checkout): two levels of a tiny study.
env -u PYTHONPATH -u MPMSHOCK PATH=/usr/bin:/bin "$prefix/bin/mpmshock-converge" "$prefix/share/mpmshock/configs/default.scene" \
  --out study --values 50um,25um --set "end_time=5 ns" >converge.out 2>&1 || fail "installed mpmshock-converge: $(tail -5 converge.out)"
[ -s study/convergence.csv ] || fail "mpmshock-converge wrote no convergence.csv"
# The package is the reader, units, theory, statistics, plots and the convergence tool; the studies
# stay in the checkout (studies/).
if ls "$prefix/lib/mpmshock/python/mpmshock_post" | grep -E "^(paper|accuracy|dimension|scene_input)"; then
  fail "the installed package holds a study module"
fi
# A project outside the tree: find_package(mpmshock) and mpmshock::core.
cmake -S "$src/tests/install_consumer" -B consumer -DCMAKE_PREFIX_PATH="$prefix" >consumer.log 2>&1 \
  || fail "configuring the consumer: $(tail -20 consumer.log)"
cmake --build consumer >>consumer.log 2>&1 || fail "building the consumer: $(tail -20 consumer.log)"
consumer/consumer "$prefix/share/mpmshock/configs/default.scene" >resolved.txt || fail "the consumer failed"
grep -q "^velocity = " resolved.txt || fail "the consumer did not resolve the scene"
echo "all checks passed"
