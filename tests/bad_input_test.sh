#!/usr/bin/env bash
# The bad-input corpus (tests/data/bad/expected.txt): every malformed scene, given as a full run,
# exits 2 with its message (file, line, key), does not crash, and writes nothing; every file in the
# corpus is listed in the manifest. Good oddities (tests/data/good) run.
# usage: bad_input_test.sh MPMSHOCK_BINARY TESTS_DATA_DIR
set -u
bin=$(realpath "$1")
data=$(realpath "$2")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAILED: $*" >&2; failures=$((failures + 1)); }

cd "$data/bad" || exit 1
listed=0
while IFS=$'\t' read -r file pattern; do
  case "$file" in "#"* | "") continue ;; esac
  listed=$((listed + 1))
  out_dir="$work/out_$listed"
  message=$("$bin" "$file" --quiet --set "output_dir=$out_dir" 2>&1)
  rc=$?
  [ "$rc" -eq 2 ] || fail "$file: exit $rc (expected 2): $message"
  echo "$message" | grep -qE -- "$pattern" || fail "$file: message '$message' does not match /$pattern/"
  [ -e "$out_dir" ] && fail "$file: wrote $out_dir"
done < expected.txt
present=$(ls -d ./*.scene | wc -l)
[ "$present" -eq "$listed" ] || fail "the corpus has $present scenes but the manifest lists $listed"

# Inputs the fuzzer once crashed on (scripts/fuzz.sh keeps them): parsed or refused, never a crash.
if [ -d "$data/fuzz-crashers" ]; then
  for file in "$data"/fuzz-crashers/*; do
    [ -f "$file" ] || continue
    "$bin" "$file" --check >/dev/null 2>&1
    rc=$?
    [ "$rc" -eq 0 ] || [ "$rc" -eq 2 ] || fail "fuzz crasher $(basename "$file"): exit $rc"
  done
fi

cd "$data/good" || exit 1
for file in *.scene; do
  "$bin" "$file" --quiet --set "output_dir=$work/good" --force >/dev/null 2>"$work/err" ||
    fail "good scene $file failed: $(cat "$work/err")"
done

if [ "$failures" -eq 0 ]; then echo "all checks passed ($listed bad scenes)"; else echo "$failures check(s) failed"; exit 1; fi
