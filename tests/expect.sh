# Shared by the command-line test scripts (source it): fail counts a failed check; expect runs
# mpmshock ($bin) and checks its exit code and output. A run that hangs fails after 120 s.
failures=0

fail() { echo "FAILED: $*" >&2; failures=$((failures + 1)); }

# expect CODE PATTERN -- ARGS...: run mpmshock, check the exit code and that stdout+stderr match.
expect() {
  local code=$1 pattern=$2
  shift 3
  local out rc
  out=$(timeout 120 "$bin" "$@" 2>&1)
  rc=$?
  [ "$rc" -eq "$code" ] || fail "mpmshock $*: exit $rc, expected $code; output: $out"
  echo "$out" | grep -qE -- "$pattern" || fail "mpmshock $*: output lacks /$pattern/: $out"
}
